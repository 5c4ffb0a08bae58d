"""Values in a Mitsuba 3 XML file: numbers, colours, spectra, named properties and
``<transform>`` elements, and the messages for what the loader does not read."""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from collections.abc import Mapping

import numpy as np

from dualight.io._common import RGB
from dualight.io._mitsuba_context import _NAMES, _Context

# What the loader reads, by element and plugin type (each one's properties are in the tables
# below; _PROPERTY_TABLES checks they agree). Everything else is refused, or substituted by
# _Survey with strict=False.
_SUPPORTED = {
    "shape": ("obj", "ply", "rectangle", "cube", "sphere", "disk", "instance"),
    "bsdf": (
        "twosided",
        "diffuse",
        "conductor",
        "roughconductor",
        "dielectric",
        "thindielectric",
        "roughdielectric",
        "plastic",
        "roughplastic",
    ),
    "texture": ("bitmap", "checkerboard"),
    "emitter": ("area", "point", "spot", "directional", "constant", "envmap"),
    "sensor": ("perspective",),
    "film": ("hdrfilm",),
    "rfilter": ("box",),  # others are approximated by it, with a warning
}


def _unsupported_type(tag: str, kind: str) -> str:
    """The message for a plugin type the loader does not read."""
    if tag == "emitter":
        top = [k for k in _SUPPORTED["emitter"] if k != "area"]
        return (
            f"emitter type {kind!r} is not supported at the top level (supported: "
            f"{', '.join(top)}; area emitters go inside a <shape>)"
        )
    supported = ", ".join(_SUPPORTED[tag])
    return f"{_NAMES.get(tag, tag)} type {kind!r} is not supported (supported: {supported})"


def _nested_message(child: ET.Element, element: ET.Element) -> str:
    return (
        f"<{child.tag}> inside <{element.tag} type={element.get('type')!r}> is not supported "
        "(nested plugins are not)"
    )


def _float(ctx: _Context, element: ET.Element, text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise ctx.error(element, f"{text!r} is not a number") from None
    if not math.isfinite(value):
        raise ctx.error(element, f"value {text!r} is not finite")
    return value


def _floats(ctx: _Context, element: ET.Element, text: str) -> list[float]:
    return [_float(ctx, element, t) for t in re.split(r"[,\s]+", text.strip()) if t]


def _vector(ctx: _Context, element: ET.Element, default: float = 0.0) -> np.ndarray:
    """A ``point``/``vector``/``translate``-style element: ``value="x y z"`` or x, y, z
    attributes (missing ones default to ``default``)."""
    if "value" in element.attrib:
        numbers = _floats(ctx, element, ctx.attr(element, "value"))
        if len(numbers) == 1:
            numbers *= 3
        if len(numbers) != 3:
            raise ctx.error(element, f"value must hold 1 or 3 numbers, got {len(numbers)}")
        return np.array(numbers)
    return np.array(
        [_float(ctx, element, ctx.attr(element, k, str(default))) for k in ("x", "y", "z")]
    )


def _rgb_value(ctx: _Context, element: ET.Element) -> RGB:
    tag = element.tag
    if tag in ("texture", "ref"):
        raise ctx.error(element, "a texture is not supported here (only a colour)")
    if tag == "rgb":
        numbers = _floats(ctx, element, ctx.attr(element, "value"))
        if len(numbers) == 1:
            numbers *= 3
        if len(numbers) != 3:
            raise ctx.error(element, f"an rgb value needs 1 or 3 numbers, got {len(numbers)}")
    elif tag == "float":
        numbers = [_float(ctx, element, ctx.attr(element, "value"))] * 3
    else:
        raise ctx.error(
            element,
            f"colours must be <rgb> or <float> (got <{tag}>; spectra and textures are not "
            "supported)",
        )
    if any(c < 0.0 for c in numbers):
        raise ctx.error(element, f"a colour must be >= 0, got {numbers}")
    return (numbers[0], numbers[1], numbers[2])


_PROPERTY_TAGS = ("float", "integer", "boolean", "string", "rgb", "point", "vector", "spectrum")
# Named children that give a BSDF parameter as a texture, inline or by reference.
_TEXTURE_TAGS = ("texture", "ref")
_RGB_OR_FLOAT = ("rgb", "float")
_COLOUR = ("rgb", "float", *_TEXTURE_TAGS)  # a colour Mitsuba lets a texture give


def _properties(
    ctx: _Context, element: ET.Element, allowed: Mapping[str, tuple[str, ...]], what: str
) -> dict[str, ET.Element]:
    """The property children of ``element`` by name, refusing names not in ``allowed`` (name
    -> accepted tags) and duplicates."""
    out: dict[str, ET.Element] = {}
    for child in element:
        named_texture = child.tag in _TEXTURE_TAGS and child.get("name", "bsdf") != "bsdf"
        if child.tag not in _PROPERTY_TAGS and child.tag != "transform" and not named_texture:
            continue
        name = child.get("name")
        if name is None:
            raise ctx.error(child, "a property needs a name")
        if name not in allowed:
            known = ", ".join(sorted(allowed)) or "none"
            raise ctx.error(
                child, f"property {name!r} of {what} is not supported (supported: {known})"
            )
        if child.tag not in allowed[name]:
            raise ctx.error(child, _tag_message(what, name, allowed[name], child.tag))
        if name in out:
            raise ctx.error(child, f"property {name!r} is given twice")
        out[name] = child
    return out


def _tag_message(what: str, name: str, allowed: tuple[str, ...], tag: str) -> str:
    tags = " or ".join(f"<{t}>" for t in allowed)
    return (
        f"{what} property {name!r} must be given as {tags} (got <{tag}>; spectra are not "
        "supported, textures only where they are listed)"
    )


def _spectrum_mean(ctx: _Context, element: ET.Element) -> float | None:
    """The mean of a ``<spectrum value>``: one number, or ``wavelength:value`` pairs (None for
    a spectrum from a file)."""
    if "value" not in element.attrib:
        return None
    words = ctx.attr(element, "value").replace(",", " ").split()
    values = [_float(ctx, element, w.split(":")[-1]) for w in words]
    return sum(values) / len(values) if values else None


def _number(ctx: _Context, element: ET.Element | None, default: float) -> float:
    if element is None:
        return default
    return _float(ctx, element, ctx.attr(element, "value"))


def _integer(ctx: _Context, element: ET.Element | None, default: int) -> int:
    if element is None:
        return default
    text = ctx.attr(element, "value")
    try:
        return int(text)
    except ValueError:
        raise ctx.error(element, f"{text!r} is not an integer") from None


def _boolean(ctx: _Context, element: ET.Element | None, default: bool) -> bool:
    if element is None:
        return default
    text = ctx.attr(element, "value").strip().lower()
    if text not in ("true", "false"):
        raise ctx.error(element, f"a boolean must be true or false, got {text!r}")
    return text == "true"


def _string(ctx: _Context, element: ET.Element | None, default: str) -> str:
    return default if element is None else ctx.attr(element, "value")


def _no_children(ctx: _Context, element: ET.Element) -> None:
    """Refuses children other than properties (and the named textures _properties took)."""
    for child in element:
        named_texture = child.tag in _TEXTURE_TAGS and child.get("name", "bsdf") != "bsdf"
        if child.tag not in _PROPERTY_TAGS and child.tag != "transform" and not named_texture:
            raise ctx.error(child, _nested_message(child, element))


# --------------------------------------------------------------------------------------------
# Mitsuba 3 XML: transforms


def _rotation(axis: np.ndarray, degrees: float) -> np.ndarray:
    a = axis / np.linalg.norm(axis)
    t = math.radians(degrees)
    c, s = math.cos(t), math.sin(t)
    x, y, z = a
    m = np.eye(4)
    m[:3, :3] = [
        [c + x * x * (1 - c), x * y * (1 - c) - z * s, x * z * (1 - c) + y * s],
        [y * x * (1 - c) + z * s, c + y * y * (1 - c), y * z * (1 - c) - x * s],
        [z * x * (1 - c) - y * s, z * y * (1 - c) + x * s, c + z * z * (1 - c)],
    ]
    return m


def _look_at(origin: np.ndarray, target: np.ndarray, up: np.ndarray) -> np.ndarray:
    """Mitsuba's ``look_at``: columns left, up, forward, origin."""
    forward = target - origin
    if np.linalg.norm(forward) == 0.0:
        raise ValueError("lookat target equals its origin")
    forward = forward / np.linalg.norm(forward)
    left = np.cross(up, forward)
    if np.linalg.norm(left) < 1e-9:
        raise ValueError("lookat up is zero or parallel to the view direction")
    left = left / np.linalg.norm(left)
    new_up = np.cross(forward, left)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = left, new_up, forward, origin
    return m


def _transform(ctx: _Context, element: ET.Element) -> np.ndarray:
    """A ``<transform>``: its operations applied in order (each one left-multiplies)."""
    m = np.eye(4)
    for op in element:
        if op.tag == "translate":
            step = np.eye(4)
            step[:3, 3] = _vector(ctx, op, 0.0)
        elif op.tag == "scale":
            step = np.diag([*_vector(ctx, op, 1.0), 1.0])
        elif op.tag == "rotate":
            if "value" in op.attrib:
                axis = _vector(ctx, op)
            else:
                axis = np.array([_float(ctx, op, ctx.attr(op, k, "0")) for k in ("x", "y", "z")])
            if np.linalg.norm(axis) == 0.0:
                raise ctx.error(op, "rotation axis is zero")
            step = _rotation(axis, _float(ctx, op, ctx.attr(op, "angle")))
        elif op.tag == "matrix":
            numbers = _floats(ctx, op, ctx.attr(op, "value"))
            if len(numbers) == 9:
                step = np.eye(4)
                step[:3, :3] = np.reshape(numbers, (3, 3))
            elif len(numbers) == 16:
                step = np.reshape(numbers, (4, 4))
            else:
                raise ctx.error(op, f"a matrix needs 9 or 16 numbers, got {len(numbers)}")
            if not np.allclose(step[3], [0, 0, 0, 1]):
                raise ctx.error(op, "projective matrices are not supported")
        elif op.tag == "lookat":
            try:
                step = _look_at(
                    np.array(_floats(ctx, op, ctx.attr(op, "origin"))),
                    np.array(_floats(ctx, op, ctx.attr(op, "target"))),
                    np.array(_floats(ctx, op, ctx.attr(op, "up", "0 1 0"))),
                )
            except ValueError as exc:
                raise ctx.error(op, str(exc)) from None
        else:
            raise ctx.error(
                op,
                "transform operation not supported (supported: translate, scale, rotate, "
                "matrix, lookat)",
            )
        m = step @ m
    if abs(np.linalg.det(m[:3, :3])) < 1e-30:
        raise ctx.error(element, "the transform is singular")
    return m


def _apply(m: np.ndarray, v: np.ndarray) -> np.ndarray:
    return v @ m[:3, :3].T + m[:3, 3]
