"""Plots shared by the benchmarks and the notebooks: error against run time.

    fig, ax = plt.subplots()
    plotting.relmse_against_time(ax, {"path": [(0.5, 2e-2), (1.0, 1e-2)]}, title="Cornell box")
    plotting.save_relmse_against_time({"cornell": curves, "door": more}, "out/bench.png")

A curve is a sequence of ``(seconds, relMSE)`` points; on log-log axes an unbiased estimator's
curve falls with slope -1 (error proportional to 1 / time). matplotlib is needed (the ``bench``
and ``test`` extras install it).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

Curve = Sequence[tuple[float, float]]


def curves_by(runs: Iterable[Mapping[str, Any]], key: str) -> dict[str, list[tuple[float, float]]]:
    """The ``(seconds, relmse)`` of each run (a dict with those keys, as the benchmarks write
    them) grouped into curves by ``run[key]``, in the order first seen."""
    curves: dict[str, list[tuple[float, float]]] = {}
    for run in runs:
        curves.setdefault(str(run[key]), []).append((run["seconds"], run["relmse"]))
    return curves


def relmse_against_time(
    ax: Any,
    curves: Mapping[str, Curve],
    *,
    title: str = "",
    xlabel: str = "render time (s)",
    ylabel: str = "relMSE",
    colours: Mapping[str, str] | None = None,
    styles: Mapping[str, str] | None = None,
    legend_size: float = 8,
) -> None:
    """Draw each curve (label -> ``(seconds, relMSE)`` points) on the matplotlib axes ``ax``,
    log-log, points in time order; ``colours`` and ``styles`` (default ``"o-"``) by label."""
    for label, points in curves.items():
        if not points:
            continue
        seconds, errors = zip(*sorted(points), strict=True)
        style = (styles or {}).get(label, "o-")
        ax.loglog(seconds, errors, style, color=(colours or {}).get(label), label=label)
    ax.set_title(title)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=legend_size)


def save_relmse_against_time(
    panels: Mapping[str, Mapping[str, Curve]],
    path: str | Path,
    *,
    panel_size: tuple[float, float] = (5.0, 4.2),
    dpi: int = 110,
    **options: Any,
) -> None:
    """One panel per entry of ``panels`` (title -> curves), side by side, written to ``path``;
    ``options`` go to :func:`relmse_against_time`. Nothing is written without panels."""
    from matplotlib.figure import Figure

    if not panels:
        return
    width, height = panel_size
    fig = Figure(figsize=(width * len(panels), height))
    axes = fig.subplots(1, len(panels), squeeze=False)[0]
    for ax, (title, curves) in zip(axes, panels.items(), strict=True):
        relmse_against_time(ax, curves, title=title, **options)
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
