"""Unsupported elements of a Mitsuba 3 XML scene: :class:`_Survey` lists them together
(``strict=True``) or replaces each by the nearest supported element (``strict=False``)."""

from __future__ import annotations

import copy
import math
import warnings
import xml.etree.ElementTree as ET
from collections.abc import Callable, Mapping
from typing import NamedTuple

import numpy as np

from dualight.io._mitsuba_context import _attrs, _Context, _paths, _TopLevel
from dualight.io._mitsuba_emitters import _AREA_PROPERTIES, _EMITTER_PROPERTIES
from dualight.io._mitsuba_materials import _BSDF_PROPERTIES, _TEXTURE_PROPERTIES
from dualight.io._mitsuba_sensor import _FILM_PROPERTIES, _SAMPLER_PROPERTIES, _SENSOR_PROPERTIES
from dualight.io._mitsuba_shapes import _SHAPE_PROPERTIES
from dualight.io._mitsuba_values import (
    _PROPERTY_TAGS,
    _RGB_OR_FLOAT,
    _SUPPORTED,
    _TEXTURE_TAGS,
    _float,
    _nested_message,
    _rgb_value,
    _spectrum_mean,
    _tag_message,
    _unsupported_type,
)

# The one property of the scene itself that is read: Embree's robust mode (Mitsuba 3's name).
ROBUST_INTERSECTIONS = "embree_use_robust_intersections"
_TOP_LEVEL = (
    "default",
    "integrator",
    "sensor",
    "bsdf",
    "texture",
    "shape",
    "shapegroup",
    "emitter",
    "include",
)
# The properties each supported plugin type takes, by element (the builders' tables).
_PROPERTY_TABLES: dict[str, dict[str, dict[str, tuple[str, ...]]]] = {
    "bsdf": {"twosided": {}, **_BSDF_PROPERTIES},
    "shape": _SHAPE_PROPERTIES,
    "texture": _TEXTURE_PROPERTIES,
    "emitter": {"area": _AREA_PROPERTIES, **_EMITTER_PROPERTIES},
    "sensor": {"perspective": _SENSOR_PROPERTIES},
    "film": {"hdrfilm": _FILM_PROPERTIES},
}
_LABELS = {
    "shape": "shape {!r}",
    "texture": "texture {!r}",
    "emitter": "{} emitter",
    "sensor": "{} sensor",
}
# BSDFs that wrap another (a normal or bump map, an opacity mask, a blend of two): the nested
# one stands in for them.
_WRAPPERS = ("bumpmap", "normalmap", "mask", "blendbsdf")
_Visit = Callable[[ET.Element, str], ET.Element | None]


class _Issue(NamedTuple):
    """An unsupported element: where it is, why, and what ``strict=False`` does instead."""

    where: str
    reason: str
    instead: str


class _Survey:
    """Walk a scene in order, noting each unsupported element and replacing it in the tree by
    the nearest supported one (or removing it), so that the builders see only supported
    elements. With ``strict`` the notes become one error and the rewritten tree is not read.

    Plugin types are checked against ``_SUPPORTED`` and property names against the builders'
    tables; values are left to the builders, which refuse what the core cannot hold."""

    def __init__(self, ctx: _Context, strict: bool, build: bool) -> None:
        self.ctx, self.strict, self.build = ctx, strict, build
        self.issues: list[_Issue] = []
        self.approximations: list[str] = []
        self.objects: _TopLevel | None = None  # the scene's top-level elements, surveyed
        self.textures: dict[str, str] = {}  # replaced top-level textures: id -> rgb value

    def note(self, element: ET.Element, where: str, reason: str, instead: str) -> None:
        source = self.ctx.source(element)
        origin = "" if source == self.ctx.path else f" (in {str(source)!r})"
        self.issues.append(
            _Issue(f"{where} <{element.tag}{_attrs(element)}>{origin}", reason, instead)
        )

    def rewrite(self, parent: ET.Element, where: str, visit: _Visit) -> None:
        """Replace each child of ``parent`` by ``visit(child, its path)`` (None removes it)."""
        outs = [visit(child, path) for child, path in _paths(parent, where)]
        parent[:] = [out for out in outs if out is not None]

    def kind(self, element: ET.Element) -> str:
        return self.ctx.attr(element, "type")

    def scene(self, root: ET.Element) -> None:
        """Survey the top-level elements in order, or earlier where a reference needs one."""
        self.objects = _TopLevel(self.ctx, root, self.top)
        outs = [self.objects.visit(child) for child in list(root)]
        root[:] = [out for out in outs if out is not None]

    def find(self, ref: ET.Element) -> tuple[ET.Element, ET.Element | None] | None:
        """The surveyed top-level element a ``<ref id>`` names (None if none has its id)."""
        return None if self.objects is None else self.objects.find(ref)

    def top(self, element: ET.Element, where: str) -> ET.Element | None:
        tag = element.tag
        if tag == "sensor":
            return self.sensor(element, where)
        elif not self.build or tag == "integrator":
            return element  # integrators are read by read_mitsuba_settings, which says so
        elif tag == "boolean" and element.get("name") == ROBUST_INTERSECTIONS:
            return element  # the scene's own property: Scene(robust_intersections=...)
        elif tag not in _TOP_LEVEL:
            supported = ", ".join(t for t in _TOP_LEVEL if t != "include")
            reason = f"element not supported (supported at the top level: {supported})"
            self.note(element, where, reason, "skipped")
            return None
        elif tag == "bsdf":
            return self.bsdf(element, where)
        elif tag == "texture":
            return self.texture(element, where)
        elif tag == "shape":
            return self.shape(element, where, False)
        elif tag == "shapegroup":
            self.rewrite(element, where, self.grouped)
        elif tag == "emitter":
            return self.emitter(element, where)
        return element

    def plugin(
        self,
        element: ET.Element,
        where: str,
        table: Mapping[str, tuple[str, ...]],
        what: str,
        nested: Mapping[str, _Visit],
    ) -> None:
        """Check a supported plugin's children: properties by ``table``, nested plugins by
        ``nested`` (tag -> visit); unknown ones are noted and removed."""

        def visit(child: ET.Element, path: str) -> ET.Element | None:
            named = child.get("name") is not None and child.get("name") != "bsdf"
            if child.tag in nested and not (child.tag == "ref" and named):
                return nested[child.tag](child, path)
            if child.tag in (*_PROPERTY_TAGS, "transform", *_TEXTURE_TAGS) and named:
                return self.property(child, path, table, what)
            if child.tag in (*_PROPERTY_TAGS, "transform"):
                return child  # without a name: the builder says so
            self.note(child, path, _nested_message(child, element), "ignored")
            return None

        self.rewrite(element, where, visit)

    def property(
        self, child: ET.Element, where: str, table: Mapping[str, tuple[str, ...]], what: str
    ) -> ET.Element | None:
        name = child.get("name", "")
        if name not in table:
            known = ", ".join(sorted(table)) or "none"
            reason = f"property {name!r} of {what} is not supported (supported: {known})"
            self.note(child, where, reason, "ignored")
            return None
        if child.tag == "spectrum" and "spectrum" not in table[name]:
            return self.spectrum(child, where, table[name], what)
        if child.tag == "texture":
            return self.texture(child, where)
        if child.tag == "ref":
            self.find(child)  # survey a texture defined later, which may be replaced
            key = self.ctx.attr(child, "id")
            if key in self.textures:
                return ET.Element("rgb", name=name, value=self.textures[key])
        return child

    def spectrum(
        self, child: ET.Element, where: str, allowed: tuple[str, ...], what: str
    ) -> ET.Element | None:
        """A ``<spectrum>`` property, noted; with its mean as a float or grey rgb instead."""
        name = child.get("name", "")
        reason = _tag_message(what, name, allowed, "spectrum")
        mean = _spectrum_mean(self.ctx, child)
        tag = next((t for t in ("float", "rgb") if t in allowed), None)
        if mean is None or tag is None:
            self.note(child, where, reason, "ignored")
            return None
        self.note(child, where, reason, f'replaced by its mean, <{tag} value="{mean:.6g}">')
        return ET.Element(tag, name=name, value=f"{mean:.9g}")

    def supported(
        self, element: ET.Element, where: str, tag: str, nested: Mapping[str, _Visit]
    ) -> None:
        """Check the children of a supported ``tag`` plugin, by its type's property table."""
        kind = self.kind(element)
        what = _LABELS.get(tag, "{}").format(kind)
        self.plugin(element, where, _PROPERTY_TABLES[tag][kind], what, nested)

    def bsdf(self, element: ET.Element, where: str) -> ET.Element | None:
        if element.tag == "ref":
            return element
        kind = self.kind(element)
        if kind in _SUPPORTED["bsdf"]:
            nested = {"bsdf": self.bsdf, "ref": self.bsdf} if kind == "twosided" else {}
            self.supported(element, where, "bsdf", nested)
            return element
        instead, out = self.bsdf_substitute(element, kind)
        self.note(element, where, _unsupported_type("bsdf", kind), instead)
        for key in ("id", "name"):
            out.attrib.pop(key, None)
            if element.get(key) is not None:
                out.set(key, element.get(key, ""))
        return self.bsdf(out, where)

    def bsdf_substitute(self, element: ET.Element, kind: str) -> tuple[str, ET.Element]:
        """The nearest supported BSDF to an unsupported one, and a note of what it is."""
        if kind == "principled":
            return _principled(self.ctx, element)
        if kind in _WRAPPERS:
            for child in element:
                if child.tag == "bsdf":
                    return f"replaced by its nested <bsdf type={child.get('type')!r}>", child
                found = self.find(child) if child.tag == "ref" else None
                if found is not None and found[0].tag == "bsdf" and found[1] is not None:
                    key = self.ctx.attr(child, "id")
                    return f"replaced by the BSDF {key!r} it holds", copy.deepcopy(found[1])
        out = ET.Element("bsdf", type="diffuse")
        for child in element:
            if child.get("name") in ("reflectance", "base_color", "diffuse_reflectance"):
                out.append(_renamed(child, "reflectance"))
                return f"replaced by a diffuse BSDF of its {child.get('name')}", out
        return "replaced by a diffuse BSDF of reflectance 0.5", out

    def texture(self, element: ET.Element, where: str) -> ET.Element | None:
        kind = self.kind(element)
        if kind in _SUPPORTED["texture"]:
            self.supported(element, where, "texture", {})
            return element
        value = _mean_colour(self.ctx, element)
        self.note(
            element, where, _unsupported_type("texture", kind), f"replaced by the colour {value}"
        )
        if element.get("name") is None:  # top-level: its references become the colour
            self.textures[self.ctx.attr(element, "id")] = value
            return None
        return ET.Element("rgb", name=element.get("name", ""), value=value)

    def shape(self, element: ET.Element, where: str, grouped: bool) -> ET.Element | None:
        kind = self.kind(element)
        if kind not in _SUPPORTED["shape"] or (grouped and kind == "instance"):
            reason = _unsupported_type("shape", kind)
            if grouped and kind == "instance":
                reason = "an instance inside a shapegroup is not supported"
            self.note(element, where, reason, "skipped")
            return None
        nested = {"bsdf": self.bsdf, "ref": self.bsdf, "emitter": self.area}
        self.supported(element, where, "shape", nested)
        return element

    def grouped(self, element: ET.Element, where: str) -> ET.Element | None:
        if element.tag == "shape":
            return self.shape(element, where, True)
        self.note(element, where, "a shapegroup holds shapes only", "ignored")
        return None

    def area(self, element: ET.Element, where: str) -> ET.Element | None:
        if self.kind(element) != "area":
            self.note(element, where, "only area emitters can be attached to a shape", "ignored")
            return None
        self.supported(element, where, "emitter", {})
        return element

    def emitter(self, element: ET.Element, where: str) -> ET.Element | None:
        kind = self.kind(element)
        if kind not in _SUPPORTED["emitter"] or kind == "area":
            self.note(element, where, _unsupported_type("emitter", kind), "skipped")
            return None
        self.supported(element, where, "emitter", {})
        return element

    def sensor(self, element: ET.Element, where: str) -> ET.Element | None:
        kind = self.kind(element)
        if kind == "thinlens":
            instead = (
                "read as a pinhole perspective sensor (aperture_radius, focus_distance dropped)"
            )
            self.note(element, where, _unsupported_type("sensor", kind), instead)
            element.set("type", "perspective")
            for child in list(element):
                if child.get("name") in ("aperture_radius", "focus_distance"):
                    element.remove(child)
        elif kind not in _SUPPORTED["sensor"]:
            self.note(element, where, _unsupported_type("sensor", kind), "skipped (no camera)")
            return None
        nested = {"film": self.film, "sampler": self.sampler}
        self.supported(element, where, "sensor", nested)
        if not self.strict:
            self.pixel_filter(element, where)
        return element

    def film(self, element: ET.Element, where: str) -> ET.Element | None:
        kind = self.kind(element)
        if kind not in _SUPPORTED["film"]:
            instead = "replaced by an hdrfilm of its width and height"
            self.note(element, where, _unsupported_type("film", kind), instead)
            element.set("type", "hdrfilm")
        self.supported(element, where, "film", {"rfilter": lambda e, w: e})
        return element

    def sampler(self, element: ET.Element, where: str) -> ET.Element | None:
        self.plugin(element, where, _SAMPLER_PROPERTIES, "sampler", {})
        return element

    def pixel_filter(self, sensor: ET.Element, where: str) -> None:
        """With ``strict=False``, note a film's pixel filter other than box (the builder warns
        apart otherwise) and make it the box filter that stands in for it."""
        films = [c for c in sensor if c.tag == "film"]
        film = films[0] if films else ET.SubElement(sensor, "film", type="hdrfilm")
        rfilters = [c for c in film if c.tag == "rfilter"]
        kind = self.kind(rfilters[0]) if rfilters else "gaussian"  # Mitsuba's default
        if kind not in _SUPPORTED["rfilter"]:
            self.approximations.append(
                f"{where}: the film's {kind!r} pixel filter is replaced by a box filter "
                "(dualight's only one)"
            )
            for rfilter in rfilters:
                film.remove(rfilter)
            ET.SubElement(film, "rfilter", type="box")

    def report(self) -> None:
        """Raise the issues as one error (strict) or warn of them and the approximations once."""
        if self.strict and self.issues:
            lines = [f"\n  {i.where}: {i.reason}" for i in self.issues]
            raise ValueError(
                f"{str(self.ctx.path)!r}: {len(self.issues)} unsupported element(s) "
                "(load_mitsuba_xml(..., strict=False) substitutes or skips them):" + "".join(lines)
            )
        lines = [f"\n  {i.where}: {i.reason}; {i.instead}" for i in self.issues]
        lines += [f"\n  {a}" for a in self.approximations]
        if lines:
            warnings.warn(
                f"{str(self.ctx.path)!r}: {len(self.issues)} unsupported element(s) substituted, "
                "skipped or ignored, and approximations (strict=False):" + "".join(lines),
                UserWarning,
                stacklevel=4,
            )


def _renamed(element: ET.Element, name: str) -> ET.Element:
    out = copy.deepcopy(element)
    out.set("name", name)
    return out


def _mean_colour(ctx: _Context, element: ET.Element) -> str:
    """The mean of a texture's colour properties as an rgb value, or 0.5 without any."""
    colours = [_rgb_value(ctx, c) for c in element if c.tag in _RGB_OR_FLOAT]
    if not colours:
        return "0.5"
    return " ".join(f"{c:.6g}" for c in np.mean(colours, axis=0))


def _principled(ctx: _Context, element: ET.Element) -> tuple[str, ET.Element]:
    """The nearest supported BSDF to Mitsuba's ``principled``: a ``roughconductor`` tinted by
    ``base_color`` if ``metallic`` is 1, else a ``roughplastic`` over it; GGX of
    ``alpha = max(roughness**2, 1e-3)`` as Mitsuba's principled maps its roughness, the
    plastic's IOR ``eta`` or the one Mitsuba derives from ``specular``,
    ``2 / (1 - sqrt(0.08 specular)) - 1``. Its other lobes (sheen, clearcoat, transmission,
    anisotropy, tints) are dropped; a textured roughness or metallic takes their defaults."""
    props = {c.get("name"): c for c in element if c.get("name") is not None}

    def number(name: str, default: float) -> float:
        child = props.get(name)
        if child is None or child.tag != "float":
            return default
        return _float(ctx, child, ctx.attr(child, "value"))

    alpha = max(number("roughness", 0.5) ** 2, 1e-3)
    metal = number("metallic", 0.0) >= 1.0
    out = ET.Element("bsdf", type="roughconductor" if metal else "roughplastic")
    ET.SubElement(out, "string", name="distribution", value="ggx")
    ET.SubElement(out, "float", name="alpha", value=f"{alpha:.9g}")
    colour = "specular_reflectance" if metal else "diffuse_reflectance"
    if "base_color" in props:
        out.append(_renamed(props["base_color"], colour))
    else:
        ET.SubElement(out, "float", name=colour, value="0.5")  # Mitsuba's default base_color
    if metal:
        ET.SubElement(out, "string", name="material", value="none")
        return f"replaced by a roughconductor (alpha {alpha:.4g}, base_color as {colour})", out
    specular = min(max(number("specular", 0.5), 1e-4), 12.4)  # 1 < eta < inf
    eta = number("eta", 2.0 / (1.0 - math.sqrt(0.08 * specular)) - 1.0)
    ET.SubElement(out, "float", name="int_ior", value=f"{eta:.9g}")
    ET.SubElement(out, "float", name="ext_ior", value="1")
    return (
        f"replaced by a roughplastic (alpha {alpha:.4g}, IOR {eta:.4g}, base_color as {colour}; "
        "other lobes dropped)",
        out,
    )
