"""The Mitsuba 3 XML file being read: :class:`_Context` (its path, the files it includes,
its ``<default>`` values, errors that name the file and element) and :class:`_TopLevel` (its
top-level elements, read in the order their references need)."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any


class _Context:
    """The file being read and its ``<default>`` values (with load-time overrides)."""

    def __init__(self, path: Path, params: Mapping[str, Any]) -> None:
        self.path = path
        self.folder = path.parent
        self.params = {str(k): str(v) for k, v in params.items()}
        self.defaults: dict[str, str] = {}
        self.top: _TopLevel | None = None  # the scene's elements that <ref id> names
        self.origins: dict[int, Path] = {}  # id() of an element read from an included file

    def source(self, element: ET.Element | None) -> Path:
        """The file ``element`` was read from (an included one, or the scene's)."""
        return self.path if element is None else self.origins.get(id(element), self.path)

    def error(self, element: ET.Element | None, message: str) -> ValueError:
        tag = "" if element is None else f"<{element.tag}{_attrs(element)}>: "
        return ValueError(f"{str(self.source(element))!r}: {tag}{message}")

    def located(self, exc: Exception) -> bool:
        """Whether an error message already names one of the scene's files (and an element)."""
        files = {self.path, *self.origins.values()}
        return any(str(exc).startswith(repr(str(f))) for f in files)

    def attr(self, element: ET.Element, name: str, default: str | None = None) -> str:
        value = element.get(name, default)
        if value is None:
            raise self.error(element, f"missing attribute {name!r}")
        return self.substitute(element, value)

    def substitute(self, element: ET.Element, value: str) -> str:
        def replace(match: re.Match[str]) -> str:
            key = match.group(1)
            if key in self.params:
                return self.params[key]
            if key in self.defaults:
                return self.defaults[key]
            raise self.error(element, f"${key} has no <default name={key!r}> nor a given value")

        return re.sub(r"\$([A-Za-z_][A-Za-z0-9_]*)", replace, value)

    def ref(self, element: ET.Element, tag: str) -> Any:
        """What a ``<ref id>`` to a top-level ``tag`` element stands for (see _TopLevel)."""
        if self.top is None:
            raise self.error(element, "a reference outside a scene's elements")
        return self.top.ref(element, tag)


def _attrs(element: ET.Element) -> str:
    keep = {k: v for k, v in element.attrib.items() if k in ("type", "name", "id")}
    return "".join(f' {k}="{v}"' for k, v in keep.items())


def _paths(parent: ET.Element, where: str) -> list[tuple[ET.Element, str]]:
    """The children of ``parent`` (at path ``where``) with their paths (``scene/shape[3]``)."""
    seen: dict[str, int] = {}
    out = []
    for child in parent:
        seen[child.tag] = seen.get(child.tag, 0) + 1
        out.append((child, f"{where}/{child.tag}[{seen[child.tag]}]"))
    return out


# How messages name elements whose tag is not a word.
_NAMES = {"bsdf": "BSDF", "emitter": "emitter", "sensor": "sensor", "film": "film"}
# The top-level elements a <ref id> can name.
_REFERENCED = ("bsdf", "texture", "shapegroup")
_Read = Callable[[ET.Element, str], Any]


class _TopLevel:
    """A scene's top-level elements, each read once by ``read(element, path)``: in file order
    (:meth:`visit`), or earlier when a ``<ref id>`` names one defined later (:meth:`ref`), as
    Mitsuba 3 instantiates objects in the order their references need. Each is read with the
    ``<default>`` values in effect where it stands. A reference names the latest element of its
    id read so far, else the first one in the file; one back to an element being read is a
    cycle."""

    def __init__(self, ctx: _Context, root: ET.Element, read: _Read) -> None:
        self.ctx, self.read = ctx, read
        self.paths: dict[int, str] = {}
        self.defaults: dict[int, dict[str, str]] = {}  # in effect at each element
        self.keys: dict[int, str] = {}  # the id of each element a reference can name
        self.first: dict[str, ET.Element] = {}  # the first such element of each id
        self.done: dict[int, Any] = {}  # what ``read`` returned, by element
        self.named: dict[str, tuple[ET.Element, Any]] = {}  # the latest read of each id
        self.reading: list[ET.Element] = []
        defaults: dict[str, str] = {}
        for element, path in _paths(root, "scene"):
            self.paths[id(element)] = path
            self.defaults[id(element)] = dict(defaults)
            ctx.defaults, saved = defaults, ctx.defaults
            try:
                if element.tag == "default":
                    defaults[ctx.attr(element, "name")] = element.get("value", "")
                elif element.tag in _REFERENCED and element.get("id") is not None:
                    self.index(element)
            finally:
                ctx.defaults = saved

    def index(self, element: ET.Element) -> None:
        """Note the id of an element a reference can name (with the defaults in effect)."""
        try:
            key = self.ctx.substitute(element, element.get("id", ""))
        except ValueError:
            return  # an id with an unknown $name: refused where the element is read
        self.keys[id(element)] = key
        self.first.setdefault(key, element)

    def visit(self, element: ET.Element) -> Any:
        """What ``read`` returns for a top-level element, reading it if it has not been."""
        if id(element) not in self.done:
            self.ctx.defaults, saved = self.defaults[id(element)], self.ctx.defaults
            self.reading.append(element)
            try:
                self.done[id(element)] = self.read(element, self.paths[id(element)])
            finally:
                self.ctx.defaults = saved
                self.reading.pop()
        if id(element) in self.keys:
            self.named[self.keys[id(element)]] = (element, self.done[id(element)])
        return self.done[id(element)]

    def find(self, ref: ET.Element) -> tuple[ET.Element, Any] | None:
        """The element a ``<ref id>`` names and what ``read`` returned for it (None: no
        element has that id); raises on a reference cycle."""
        key = self.ctx.attr(ref, "id")
        if key in self.named:
            return self.named[key]
        if key not in self.first:
            return None
        element = self.first[key]
        starts = [i for i, e in enumerate(self.reading) if e is element]
        if starts:
            chain = [self.keys.get(id(e), e.tag) for e in self.reading[starts[0] :]]
            cycle = " -> ".join(repr(k) for k in (*chain, key))
            raise self.ctx.error(ref, f"reference cycle: {cycle}")
        return element, self.visit(element)

    def ref(self, ref: ET.Element, tag: str) -> Any:
        """What ``read`` returned for the ``tag`` element a ``<ref id>`` names; raises if
        there is none."""
        found = self.find(ref)
        noun = _NAMES.get(tag, tag)
        key = self.ctx.attr(ref, "id")
        if found is None:
            raise self.ctx.error(ref, f"no {noun} with id {key!r} is defined in the scene")
        if found[0].tag != tag:
            raise self.ctx.error(ref, f"no {noun} with id {key!r}: it names a <{found[0].tag}>")
        return found[1]
