"""Mitsuba 3 emitters: stand-alone ``<emitter>`` elements as dualight emitters, and the
properties of the area emitters shapes hold."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Mapping

import numpy as np

from dualight.emitters import (
    ConstantEnvironment,
    DirectionalLight,
    Emitter,
    EnvironmentMap,
    PointLight,
    SpotLight,
)
from dualight.io._mitsuba_context import _Context
from dualight.io._mitsuba_materials import _rgb_or
from dualight.io._mitsuba_values import (
    _COLOUR,
    _no_children,
    _number,
    _properties,
    _rgb_value,
    _transform,
    _unsupported_type,
    _vector,
)

_EMITTER_PROPERTIES: dict[str, dict[str, tuple[str, ...]]] = {
    "point": {
        "intensity": ("rgb", "float"),
        "position": ("point", "vector"),
        "to_world": ("transform",),
    },
    "spot": {
        "intensity": ("rgb", "float"),
        "cutoff_angle": ("float",),
        "beam_width": ("float",),
        "to_world": ("transform",),
    },
    "directional": {
        "irradiance": ("rgb", "float"),
        "direction": ("vector",),
        "to_world": ("transform",),
    },
    "constant": {"radiance": ("rgb", "float")},
    "envmap": {"filename": ("string",), "scale": ("float",), "to_world": ("transform",)},
}
_AREA_PROPERTIES: dict[str, tuple[str, ...]] = {"radiance": _COLOUR}


def _emitter(ctx: _Context, element: ET.Element) -> Emitter:
    """A stand-alone emitter (Mitsuba 3's parameters and defaults: intensity, irradiance and
    radiance 1, a spot's cutoff 20 degrees and beam width 3/4 of it, shining along its
    ``to_world``'s +z, as does a directional light without ``direction``; an envmap's scale 1)."""
    kind = ctx.attr(element, "type")
    if kind not in _EMITTER_PROPERTIES:
        raise ctx.error(element, _unsupported_type("emitter", kind))
    props = _properties(ctx, element, _EMITTER_PROPERTIES[kind], f"{kind} emitter")
    _no_children(ctx, element)
    if kind in ("directional", "constant", "envmap"):
        return _infinite_emitter(ctx, element, kind, props)
    intensity = _rgb_value(ctx, props["intensity"]) if "intensity" in props else (1.0, 1.0, 1.0)
    m = _transform(ctx, props["to_world"]) if "to_world" in props else np.eye(4)
    if "position" in props and "to_world" in props:
        raise ctx.error(element, "a point emitter takes position or to_world, not both")
    origin = _vector(ctx, props["position"]) if "position" in props else m[:3, 3]
    cutoff = _number(ctx, props.get("cutoff_angle"), 20.0)
    beam = _number(ctx, props.get("beam_width"), 0.75 * cutoff)
    try:
        if kind == "point":
            return PointLight(tuple(origin), intensity)
        return SpotLight(tuple(origin), tuple(m[:3, 2]), intensity, cutoff, beam)
    except ValueError as e:
        raise ctx.error(element, f"{kind} emitter: {e}") from None


def _infinite_emitter(
    ctx: _Context, element: ET.Element, kind: str, props: Mapping[str, ET.Element]
) -> DirectionalLight | ConstantEnvironment | EnvironmentMap:
    """A ``directional``, ``constant`` or ``envmap`` emitter from its properties."""
    m = _transform(ctx, props["to_world"]) if "to_world" in props else np.eye(4)
    try:
        if kind == "directional":
            if "direction" in props and "to_world" in props:
                raise ctx.error(
                    element, "a directional emitter takes direction or to_world, not both"
                )
            direction = _vector(ctx, props["direction"]) if "direction" in props else m[:3, 2]
            irradiance = _rgb_or(ctx, props, "irradiance", 1.0)
            return DirectionalLight(tuple(direction), irradiance)
        if kind == "constant":
            return ConstantEnvironment(_rgb_or(ctx, props, "radiance", 1.0))
        if "filename" not in props:
            raise ctx.error(element, 'an envmap needs <string name="filename">')
        return EnvironmentMap(
            ctx.folder / ctx.attr(props["filename"], "value"),
            scale=_number(ctx, props.get("scale"), 1.0),
            to_world=m,
        )
    except (ValueError, FileNotFoundError) as exc:
        if isinstance(exc, ValueError) and ctx.located(exc):
            raise
        raise ctx.error(element, f"{kind} emitter: {exc}") from None
