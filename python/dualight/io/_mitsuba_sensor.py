"""The Mitsuba 3 sensor (its film and sampler) as a dualight camera, and the integrator's
settings."""

from __future__ import annotations

import math
import warnings
import xml.etree.ElementTree as ET
from typing import Any

import numpy as np

from dualight.io._mitsuba_context import _Context
from dualight.io._mitsuba_values import (
    _PROPERTY_TAGS,
    _boolean,
    _integer,
    _number,
    _properties,
    _string,
    _transform,
    _unsupported_type,
)
from dualight.scene import Camera


def _fov_along_x(fov: float, axis: str, width: int, height: int) -> float:
    """Convert Mitsuba's ``fov`` along ``fov_axis`` to dualight's full angle along x."""
    aspect = width / height
    if axis == "smaller":
        axis = "x" if width <= height else "y"
    elif axis == "larger":
        axis = "x" if width >= height else "y"
    half = math.tan(math.radians(fov) / 2.0)
    if axis == "y":
        half *= aspect
    elif axis == "diagonal":
        half *= width / math.hypot(width, height)
    return math.degrees(2.0 * math.atan(half))


_SENSOR_PROPERTIES: dict[str, tuple[str, ...]] = {
    "fov": ("float",),
    "fov_axis": ("string",),
    "to_world": ("transform",),
    "near_clip": ("float",),
    "far_clip": ("float",),
}
_FILM_PROPERTIES: dict[str, tuple[str, ...]] = {
    "width": ("integer",),
    "height": ("integer",),
    "pixel_format": ("string",),
    "component_format": ("string",),
    "file_format": ("string",),
    "sample_border": ("boolean",),
}
_SAMPLER_PROPERTIES: dict[str, tuple[str, ...]] = {
    "sample_count": ("integer",),
    "seed": ("integer",),
}


def _sensor(ctx: _Context, element: ET.Element, settings: dict[str, Any]) -> Camera:
    kind = ctx.attr(element, "type")
    if kind != "perspective":
        raise ctx.error(element, _unsupported_type("sensor", kind))
    props = _properties(ctx, element, _SENSOR_PROPERTIES, "perspective sensor")
    width, height = 768, 576  # Mitsuba's default film
    rfilter = "gaussian"  # and its default pixel filter
    for child in element:
        if child.tag == "film":
            film = ctx.attr(child, "type")
            if film != "hdrfilm":
                raise ctx.error(child, _unsupported_type("film", film))
            fprops = _properties(ctx, child, _FILM_PROPERTIES, "hdrfilm")
            width = _integer(ctx, fprops.get("width"), width)
            height = _integer(ctx, fprops.get("height"), height)
            if width < 1 or height < 1:
                raise ctx.error(child, f"film size must be positive, got {width} x {height}")
            rfilters = [c for c in child if c.tag == "rfilter"]
            if rfilters:
                rfilter = ctx.attr(rfilters[0], "type")
            for c in child:
                if c.tag not in (*_PROPERTY_TAGS, "rfilter"):
                    raise ctx.error(c, f"<{c.tag}> inside a film is not supported")
        elif child.tag == "sampler":
            sprops = _properties(ctx, child, _SAMPLER_PROPERTIES, "sampler")
            if "sample_count" in sprops:
                settings["spp"] = _integer(ctx, sprops["sample_count"], 4)
            # For render's keywords only (read_mitsuba_settings(raw=True) leaves them out).
            settings["_sampler"] = ctx.attr(child, "type")
            if "seed" in sprops:
                settings["_seed"] = _integer(ctx, sprops["seed"], 0)
        elif child.tag not in (*_PROPERTY_TAGS, "transform"):
            raise ctx.error(child, f"<{child.tag}> inside a sensor is not supported")
    if rfilter != "box":
        warnings.warn(
            f"{str(ctx.path)!r}: the film's {rfilter!r} pixel filter is replaced by a box "
            'filter (dualight\'s only one; add <rfilter type="box"/> to the hdrfilm for an '
            "exact match)",
            UserWarning,
            stacklevel=4,
        )
    fov = _number(ctx, props.get("fov"), math.nan)
    if "fov" not in props:
        raise ctx.error(
            element, 'the sensor needs <float name="fov"> (focal_length is not supported)'
        )
    if not 0.0 < fov < 180.0:
        raise ctx.error(props["fov"], f"fov must be in (0, 180) degrees, got {fov}")
    axis = _string(ctx, props.get("fov_axis"), "x")
    if axis not in ("x", "y", "diagonal", "smaller", "larger"):
        raise ctx.error(props["fov_axis"], f"unknown fov_axis {axis!r}")
    m = _transform(ctx, props["to_world"]) if "to_world" in props else np.eye(4)
    origin = m[:3, 3]
    left, up, forward = (m[:3, k] / np.linalg.norm(m[:3, k]) for k in range(3))
    if not np.allclose(np.cross(up, forward), left, atol=1e-4):
        raise ctx.error(
            props.get("to_world"),
            "the sensor's to_world must be a rotation and translation (e.g. a lookat); "
            "mirrored or sheared cameras are not supported",
        )
    try:
        return Camera(
            origin=tuple(origin),
            target=tuple(origin + forward),
            up=tuple(up),
            fov=_fov_along_x(fov, axis, width, height),
            resolution=(width, height),
        )
    except ValueError as exc:
        raise ctx.error(element, str(exc)) from None


def _integrator(ctx: _Context, element: ET.Element, settings: dict[str, Any]) -> None:
    settings["integrator"] = ctx.attr(element, "type")
    for child in element:
        if child.tag in ("integer", "boolean", "float", "string"):
            name = ctx.attr(child, "name")
            if child.tag == "integer":
                settings[name] = _integer(ctx, child, 0)
            elif child.tag == "boolean":
                settings[name] = _boolean(ctx, child, False)
            elif child.tag == "float":
                settings[name] = _number(ctx, child, 0.0)
            else:
                settings[name] = ctx.attr(child, "value")
        elif child.tag == "integrator":  # e.g. an aov or moment wrapper: read the nested one
            _integrator(ctx, child, settings)
