"""The demo's report as one HTML page and its Markdown twin: sections of text, tables and
figures (PNG files beside the page, referenced by relative paths so the folder can be moved)."""

from __future__ import annotations

import html
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path


@dataclass(frozen=True)
class Figure:
    """A PNG beside the page and its caption; ``pixelated`` enlarges a small image without
    smoothing (``width`` CSS pixels wide)."""

    file: str
    caption: str
    width: int = 256
    pixelated: bool = False


@dataclass
class Section:
    """One part of the demo: a title, a paragraph of explanation, bullet lines of results, an
    optional table (header row first) and figures."""

    title: str
    intro: str
    lines: list[str] = field(default_factory=list)
    table: list[Sequence[str]] = field(default_factory=list)
    figures: list[Figure] = field(default_factory=list)


_STYLE = """
body { font-family: system-ui, sans-serif; max-width: 72rem; margin: 2rem auto; padding: 0 1rem;
       color: #222; line-height: 1.45; }
h1 { font-size: 1.6rem; } h2 { font-size: 1.25rem; margin-top: 2.2rem; }
figure { display: inline-block; margin: 0 1rem 1rem 0; vertical-align: top; }
figcaption { font-size: 0.85rem; color: #555; max-width: 18rem; }
img.pixelated { image-rendering: pixelated; }
table { border-collapse: collapse; margin: 0.6rem 0 1rem 0; font-size: 0.92rem; }
td, th { border: 1px solid #ccc; padding: 0.25rem 0.6rem; text-align: right; }
th { background: #f3f3f3; } td:first-child, th:first-child { text-align: left; }
code { background: #f3f3f3; padding: 0 0.2rem; }
"""


def _inline(text: str) -> str:
    """Escape, then render `code` spans (the only markup the sections use)."""
    parts = html.escape(text).split("`")
    return "".join(f"<code>{p}</code>" if i % 2 else p for i, p in enumerate(parts))


def _html_table(rows: list[Sequence[str]]) -> str:
    head = "".join(f"<th>{_inline(c)}</th>" for c in rows[0])
    body = "".join(
        "<tr>" + "".join(f"<td>{_inline(c)}</td>" for c in row) + "</tr>" for row in rows[1:]
    )
    return f"<table><tr>{head}</tr>{body}</table>"


def _html_figure(fig: Figure) -> str:
    cls = ' class="pixelated"' if fig.pixelated else ""
    return (
        f'<figure><img src="{html.escape(fig.file)}" width="{fig.width}"{cls} '
        f'alt="{html.escape(fig.caption)}"><figcaption>{_inline(fig.caption)}</figcaption>'
        "</figure>"
    )


def write_html(path: Path, title: str, summary: str, sections: list[Section]) -> None:
    """Write the page: a title, a summary paragraph, then every section."""
    out = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        f"<title>{html.escape(title)}</title><style>{_STYLE}</style></head><body>",
        f"<h1>{html.escape(title)}</h1><p>{_inline(summary)}</p>",
    ]
    for s in sections:
        out.append(f"<h2>{_inline(s.title)}</h2><p>{_inline(s.intro)}</p>")
        if s.lines:
            out.append("<ul>" + "".join(f"<li>{_inline(line)}</li>" for line in s.lines) + "</ul>")
        if s.table:
            out.append(_html_table(s.table))
        out.append("<div>" + "".join(_html_figure(f) for f in s.figures) + "</div>")
    out.append("</body></html>")
    path.write_text("\n".join(out) + "\n")


def markdown(title: str, summary: str, sections: list[Section]) -> str:
    """The same report as Markdown (``report.md``)."""
    out = [f"# {title}", "", summary]
    for s in sections:
        out += ["", f"## {s.title}", "", s.intro, ""]
        out += [f"- {line}" for line in s.lines]
        if s.table:
            out += ["", "| " + " | ".join(s.table[0]) + " |"]
            out += ["| " + " | ".join("---" for _ in s.table[0]) + " |"]
            out += ["| " + " | ".join(row) + " |" for row in s.table[1:]]
        if s.figures:
            out += ["", "images: " + ", ".join(f.file for f in s.figures)]
    return "\n".join(out) + "\n"
