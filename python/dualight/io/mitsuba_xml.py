"""A subset of Mitsuba 3's XML scene format: :func:`load_mitsuba_xml` and
:func:`read_mitsuba_settings` (parsed with the standard library's ``xml.etree``; meshes read with
trimesh). See :func:`load_mitsuba_xml` for what is supported."""

from __future__ import annotations

import math
import re
import warnings
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from dualight.emitters import (
    ConstantEnvironment,
    DirectionalLight,
    Emitter,
    EnvironmentMap,
    PointLight,
    SpotLight,
)
from dualight.io._common import (
    RGB,
    PathLike,
    _angle_weighted_normals,
    _existing_file,
    _loaded_normals,
    _loaded_uv,
    _mesh_arrays,
    _trimesh_geometries,
)
from dualight.materials import (
    Conductor,
    Dielectric,
    Diffuse,
    Material,
    Mirror,
    Plastic,
    RoughConductor,
    RoughDielectric,
    RoughPlastic,
    ThinDielectric,
    TwoSided,
)
from dualight.scene import Camera, Scene
from dualight.textures import Bitmap, Checkerboard, Texture

__all__ = ["load_mitsuba_xml", "read_mitsuba_settings"]

# --------------------------------------------------------------------------------------------
# Mitsuba 3 XML: values

_SUPPORTED = {
    "shape": ("obj", "ply", "rectangle", "cube", "sphere"),
    "bsdf": (
        "diffuse",
        "twosided",
        "conductor",
        "roughconductor",
        "dielectric",
        "thindielectric",
        "roughdielectric",
        "plastic",
        "roughplastic",
    ),
    "texture": ("bitmap", "checkerboard"),
    "emitter": ("area (inside a shape)", "point", "spot", "directional", "constant", "envmap"),
    "sensor": ("perspective",),
    "film": ("hdrfilm",),
}

# Mitsuba 3's named indices of refraction (src/render/ior.h).
_IOR = {
    "vacuum": 1.0,
    "helium": 1.000036,
    "hydrogen": 1.000132,
    "air": 1.000277,
    "carbon dioxide": 1.00045,
    "water": 1.3330,
    "acetone": 1.36,
    "ethanol": 1.361,
    "carbon tetrachloride": 1.461,
    "glycerol": 1.4729,
    "benzene": 1.501,
    "silicone oil": 1.52045,
    "bromine": 1.661,
    "water ice": 1.31,
    "fused quartz": 1.458,
    "pyrex": 1.470,
    "acrylic glass": 1.49,
    "polypropylene": 1.49,
    "bk7": 1.5046,
    "sodium chloride": 1.544,
    "amber": 1.55,
    "pet": 1.5750,
    "diamond": 2.419,
}


class _Context:
    """The file being read and its ``<default>`` values (with load-time overrides)."""

    def __init__(self, path: Path, params: Mapping[str, Any]) -> None:
        self.path = path
        self.folder = path.parent
        self.params = {str(k): str(v) for k, v in params.items()}
        self.defaults: dict[str, str] = {}
        self.textures: dict[str, Texture] = {}  # top-level <texture id=...>

    def error(self, element: ET.Element | None, message: str) -> ValueError:
        tag = "" if element is None else f"<{element.tag}{_attrs(element)}>: "
        return ValueError(f"{str(self.path)!r}: {tag}{message}")

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


def _attrs(element: ET.Element) -> str:
    keep = {k: v for k, v in element.attrib.items() if k in ("type", "name", "id")}
    return "".join(f' {k}="{v}"' for k, v in keep.items())


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
            tags = " or ".join(f"<{t}>" for t in allowed[name])
            raise ctx.error(
                child,
                f"{what} property {name!r} must be given as {tags} (got <{child.tag}>; "
                "spectra are not supported, textures only where they are listed)",
            )
        if name in out:
            raise ctx.error(child, f"property {name!r} is given twice")
        out[name] = child
    return out


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


# --------------------------------------------------------------------------------------------
# Mitsuba 3 XML: BSDFs, shapes, sensor


_RGB_OR_FLOAT = ("rgb", "float")
_COLOUR = ("rgb", "float", *_TEXTURE_TAGS)  # a colour Mitsuba lets a texture give
_ROUGHNESS = {
    "distribution": ("string",),
    "alpha": ("float", *_TEXTURE_TAGS),
    "alpha_u": ("float", *_TEXTURE_TAGS),
    "alpha_v": ("float", *_TEXTURE_TAGS),
    "sample_visible": ("boolean",),
}
_METAL = {"material": ("string",), "eta": _RGB_OR_FLOAT, "k": _RGB_OR_FLOAT}
_IORS = {"int_ior": ("float", "string"), "ext_ior": ("float", "string")}
_BSDF_PROPERTIES: dict[str, dict[str, tuple[str, ...]]] = {
    "diffuse": {"reflectance": _COLOUR},
    "conductor": _METAL | {"specular_reflectance": _COLOUR},
    "roughconductor": _METAL | _ROUGHNESS | {"specular_reflectance": _COLOUR},
    "dielectric": _IORS
    | {"specular_reflectance": _RGB_OR_FLOAT, "specular_transmittance": _RGB_OR_FLOAT},
    "thindielectric": _IORS,
    "roughdielectric": _IORS | _ROUGHNESS,
    "plastic": _IORS
    | {
        "diffuse_reflectance": _COLOUR,
        "specular_reflectance": _COLOUR,
        "nonlinear": ("boolean",),
    },
}
# Rough plastic's roughness is a number in Mitsuba (its coat's tables depend on it).
_BSDF_PROPERTIES["roughplastic"] = _BSDF_PROPERTIES["plastic"] | _ROUGHNESS | {"alpha": ("float",)}


def _bsdf(ctx: _Context, element: ET.Element, bsdfs: Mapping[str, Material]) -> Material:
    kind = ctx.attr(element, "type")
    if kind == "twosided":
        inner = [c for c in element if c.tag in ("bsdf", "ref")]
        _properties(ctx, element, {}, "twosided")
        if len(inner) != 1:
            raise ctx.error(
                element,
                "twosided must hold exactly one BSDF (two different sides are not supported)",
            )
        try:
            both = TwoSided(_bsdf_or_ref(ctx, inner[0], bsdfs))
        except ValueError as exc:
            raise ctx.error(element, str(exc)) from None
        if type(both) is Conductor and both.eta == (0.0,) * 3 and both.k == (1.0,) * 3:
            return Mirror(both.specular_reflectance)  # the same BSDF (Fresnel is 1), by its name
        return both
    if kind not in _BSDF_PROPERTIES:
        supported = ", ".join(["twosided", *_BSDF_PROPERTIES])
        raise ctx.error(element, f"BSDF type {kind!r} is not supported (supported: {supported})")
    props = _properties(ctx, element, _BSDF_PROPERTIES[kind], kind)
    _no_children(ctx, element)
    try:
        return _BSDF_BUILDERS[kind](ctx, props)
    except (ValueError, TypeError) as exc:
        if str(exc).startswith(repr(str(ctx.path))):
            raise  # already names the file and the element (a texture's)
        raise ctx.error(element, str(exc)) from None


def _rgb_or(ctx: _Context, props: Mapping[str, ET.Element], key: str, default: Any) -> Any:
    """A colour property (a texture where one is given), or ``default``."""
    if key not in props:
        return default
    element = props[key]
    return _texture(ctx, element) if element.tag in _TEXTURE_TAGS else _rgb_value(ctx, element)


def _number_or_none(ctx: _Context, props: Mapping[str, ET.Element], key: str) -> Any:
    if key not in props:
        return None
    element = props[key]
    return _texture(ctx, element) if element.tag in _TEXTURE_TAGS else _number(ctx, element, 0.0)


_TEXTURE_PROPERTIES: dict[str, dict[str, tuple[str, ...]]] = {
    "bitmap": {
        "filename": ("string",),
        "raw": ("boolean",),
        "filter_type": ("string",),
        "wrap_mode": ("string",),
        "to_uv": ("transform",),
    },
    "checkerboard": {"color0": _RGB_OR_FLOAT, "color1": _RGB_OR_FLOAT, "to_uv": ("transform",)},
}


def _texture(ctx: _Context, element: ET.Element) -> Texture:
    """A ``<texture>`` (bitmap or checkerboard), or a ``<ref>`` to a top-level one."""
    if element.tag == "ref":
        key = ctx.attr(element, "id")
        if key not in ctx.textures:
            raise ctx.error(element, f"no texture with id {key!r} is defined before this reference")
        return ctx.textures[key]
    kind = ctx.attr(element, "type")
    if kind not in _TEXTURE_PROPERTIES:
        raise ctx.error(
            element, f"texture type {kind!r} is not supported (supported: bitmap, checkerboard)"
        )
    props = _properties(ctx, element, _TEXTURE_PROPERTIES[kind], f"texture {kind!r}")
    _no_children(ctx, element)
    to_uv = _transform(ctx, props["to_uv"]) if "to_uv" in props else None
    try:
        if kind == "checkerboard":
            return Checkerboard(
                _rgb_or(ctx, props, "color0", 0.4), _rgb_or(ctx, props, "color1", 0.2), to_uv
            )
        if "filename" not in props:
            raise ctx.error(element, 'a bitmap needs <string name="filename">')
        return Bitmap(
            ctx.folder / ctx.attr(props["filename"], "value"),
            raw=_boolean(ctx, props.get("raw"), False),
            filter_type=_string(ctx, props.get("filter_type"), "bilinear"),  # type: ignore[arg-type]
            wrap_mode=_string(ctx, props.get("wrap_mode"), "repeat"),  # type: ignore[arg-type]
            to_uv=to_uv,
        )
    except (ValueError, FileNotFoundError) as exc:
        if isinstance(exc, ValueError) and str(exc).startswith(repr(str(ctx.path))):
            raise
        raise ctx.error(element, str(exc)) from None


def _roughness_keywords(ctx: _Context, props: Mapping[str, ET.Element]) -> dict[str, Any]:
    if not _boolean(ctx, props.get("sample_visible"), True):
        warnings.warn(
            f"{str(ctx.path)!r}: sample_visible=false is ignored (dualight always samples "
            "visible normals; the BSDF is the same, only the noise differs)",
            UserWarning,
            stacklevel=5,
        )
    keywords = {k: _number_or_none(ctx, props, k) for k in ("alpha", "alpha_u", "alpha_v")}
    keywords["distribution"] = _string(ctx, props.get("distribution"), "beckmann").lower()
    return keywords


def _metal_keywords(ctx: _Context, props: Mapping[str, ET.Element]) -> dict[str, Any]:
    metal = _string(ctx, props.get("material"), "none") if "material" in props else None
    return {
        "material": metal,
        "eta": _rgb_value(ctx, props["eta"]) if "eta" in props else None,
        "k": _rgb_value(ctx, props["k"]) if "k" in props else None,
        "specular_reflectance": _rgb_or(ctx, props, "specular_reflectance", 1.0),
    }


def _relative(ctx: _Context, props: Mapping[str, ET.Element], interior: str) -> float:
    return _ior(ctx, props.get("int_ior"), interior) / _ior(ctx, props.get("ext_ior"), "air")


def _plastic_keywords(ctx: _Context, props: Mapping[str, ET.Element]) -> dict[str, Any]:
    return {
        "diffuse_reflectance": _rgb_or(ctx, props, "diffuse_reflectance", 0.5),
        "specular_reflectance": _rgb_or(ctx, props, "specular_reflectance", 1.0),
        "ior": _relative(ctx, props, "polypropylene"),
        "nonlinear": _boolean(ctx, props.get("nonlinear"), False),
    }


def _dielectric(ctx: _Context, props: Mapping[str, ET.Element]) -> Material:
    for key in ("specular_reflectance", "specular_transmittance"):
        if key in props and _rgb_value(ctx, props[key]) != (1.0, 1.0, 1.0):
            raise ctx.error(props[key], f"dielectric {key} other than 1 is not supported")
    return Dielectric(ior=_relative(ctx, props, "bk7"))


def _rough_plastic(ctx: _Context, props: Mapping[str, ET.Element]) -> Material:
    rough = _roughness_keywords(ctx, props)
    if rough["alpha_u"] is not None or rough["alpha_v"] is not None:
        raise ValueError("roughplastic takes an isotropic alpha only (as Mitsuba)")
    alpha = 0.1 if rough["alpha"] is None else rough["alpha"]
    return RoughPlastic(
        alpha=alpha, distribution=rough["distribution"], **_plastic_keywords(ctx, props)
    )


_BSDF_BUILDERS: dict[str, Any] = {
    "diffuse": lambda ctx, p: Diffuse(_rgb_or(ctx, p, "reflectance", (0.5, 0.5, 0.5))),
    "conductor": lambda ctx, p: Conductor(**_metal_keywords(ctx, p)),
    "roughconductor": lambda ctx, p: RoughConductor(
        **_roughness_keywords(ctx, p), **_metal_keywords(ctx, p)
    ),
    "dielectric": _dielectric,
    "thindielectric": lambda ctx, p: ThinDielectric(ior=_relative(ctx, p, "bk7")),
    "roughdielectric": lambda ctx, p: RoughDielectric(
        **_roughness_keywords(ctx, p), ior=_relative(ctx, p, "bk7")
    ),
    "plastic": lambda ctx, p: Plastic(**_plastic_keywords(ctx, p)),
    "roughplastic": _rough_plastic,
}


def _ior(ctx: _Context, element: ET.Element | None, default: str) -> float:
    if element is None:
        return _IOR[default]
    text = ctx.attr(element, "value")
    if element.tag == "string" or text.strip().lower() in _IOR:
        key = text.strip().lower()
        if key not in _IOR:
            raise ctx.error(element, f"unknown IOR name {text!r} (known: {', '.join(_IOR)})")
        return _IOR[key]
    value = _float(ctx, element, text)
    if value <= 0.0:
        raise ctx.error(element, f"an IOR must be > 0, got {value}")
    return value


def _no_children(ctx: _Context, element: ET.Element) -> None:
    """Refuses children other than properties (and the named textures _properties took)."""
    for child in element:
        named_texture = child.tag in _TEXTURE_TAGS and child.get("name", "bsdf") != "bsdf"
        if child.tag not in _PROPERTY_TAGS and child.tag != "transform" and not named_texture:
            raise ctx.error(
                child,
                f"<{child.tag}> inside <{element.tag} type={element.get('type')!r}> is "
                "not supported (nested plugins are not)",
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


def _emitter(ctx: _Context, element: ET.Element) -> Emitter:
    """A stand-alone emitter (Mitsuba 3's parameters and defaults: intensity, irradiance and
    radiance 1, a spot's cutoff 20 degrees and beam width 3/4 of it, shining along its
    ``to_world``'s +z, as does a directional light without ``direction``; an envmap's scale 1)."""
    kind = ctx.attr(element, "type")
    if kind not in _EMITTER_PROPERTIES:
        raise ctx.error(
            element,
            f"emitter type {kind!r} is not supported at the top level (supported: "
            f"{', '.join(_EMITTER_PROPERTIES)}; area emitters go inside a <shape>)",
        )
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
        if isinstance(exc, ValueError) and str(exc).startswith(repr(str(ctx.path))):
            raise
        raise ctx.error(element, f"{kind} emitter: {exc}") from None


def _bsdf_or_ref(ctx: _Context, element: ET.Element, bsdfs: Mapping[str, Material]) -> Material:
    if element.tag == "ref":
        ref = ctx.attr(element, "id")
        if ref not in bsdfs:
            raise ctx.error(element, f"no BSDF with id {ref!r} is defined before this reference")
        return bsdfs[ref]
    return _bsdf(ctx, element, bsdfs)


def _rectangle() -> tuple[np.ndarray, np.ndarray]:
    v = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=np.float64)
    return v, np.array([[0, 1, 2], [0, 2, 3]])


def _cube() -> tuple[np.ndarray, np.ndarray]:
    """[-1, 1]^3 with outward-facing triangles (four vertices per face, as Mitsuba's)."""
    verts, faces = [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            u, w = (axis + 1) % 3, (axis + 2) % 3
            quad = []
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = np.zeros(3)
                p[axis], p[u], p[w] = sign, a, b
                quad.append(p)
            base = len(verts)
            quad_f = [[base, base + 1, base + 2], [base, base + 2, base + 3]]
            if sign < 0:  # (u, w) order gives normal +axis: flip for the -axis face
                quad_f = [f[::-1] for f in quad_f]
            verts.extend(quad)
            faces.extend(quad_f)
    return np.array(verts), np.array(faces)


def _file_mesh(
    ctx: _Context, element: ET.Element, kind: str, filename: str, face_normals: bool
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None, np.ndarray | None]:
    """Vertices, faces, shading normals (None: flat) and texture coordinates (None: none) of an
    OBJ/PLY shape. As in Mitsuba, without ``face_normals`` the file's vertex normals are used,
    or smooth ones are computed."""
    path = ctx.folder / filename
    if not path.is_file():
        raise FileNotFoundError(
            f"no such {kind.upper()} file: {str(path)!r} (named by <shape type={kind!r}> in "
            f"{str(ctx.path)!r})"
        )
    geoms = [g for _, g in _trimesh_geometries(path, kind)]
    parts = [_mesh_arrays(g, str(path)) for g in geoms]
    offsets = np.cumsum([0] + [len(v) for v, _ in parts[:-1]])
    v = np.concatenate([p[0] for p in parts])
    f = np.concatenate([p[1] + off for p, off in zip(parts, offsets, strict=True)])
    uvs = [_loaded_uv(g, kind) for g in geoms]
    uv = np.concatenate(uvs) if all(u is not None for u in uvs) else None  # type: ignore[arg-type]
    if face_normals:
        return v, f, None, uv
    loaded = [_loaded_normals(g) for g in geoms]
    if all(n is not None for n in loaded):
        return v, f, np.concatenate(loaded), uv  # type: ignore[arg-type]
    return v, f, _angle_weighted_normals(v, f), uv


_SHAPE_PROPERTIES: dict[str, dict[str, tuple[str, ...]]] = {
    "obj": {
        "filename": ("string",),
        "face_normals": ("boolean",),
        "flip_normals": ("boolean",),
        "to_world": ("transform",),
    },
    "rectangle": {"flip_normals": ("boolean",), "to_world": ("transform",)},
    "cube": {"flip_normals": ("boolean",), "to_world": ("transform",)},
    "sphere": {
        "center": ("point",),
        "radius": ("float",),
        "flip_normals": ("boolean",),
        "to_world": ("transform",),
    },
}
_SHAPE_PROPERTIES["ply"] = _SHAPE_PROPERTIES["obj"]


def _shape(
    ctx: _Context,
    element: ET.Element,
    bsdfs: Mapping[str, Material],
    scene: Scene,
    index: int,
    sphere_subdivisions: int,
) -> None:
    from dualight.scenes import icosphere

    kind = ctx.attr(element, "type")
    if kind not in _SHAPE_PROPERTIES:
        raise ctx.error(
            element,
            f"shape type {kind!r} is not supported (supported: {', '.join(_SUPPORTED['shape'])})",
        )
    props = _properties(ctx, element, _SHAPE_PROPERTIES[kind], f"shape {kind!r}")
    material: Material | None = None
    emission: RGB | Texture = (0.0, 0.0, 0.0)
    for child in element:
        if child.tag in _PROPERTY_TAGS or child.tag == "transform":
            continue
        if child.tag in ("bsdf", "ref"):
            if child.tag == "ref" and child.get("name", "bsdf") != "bsdf":
                raise ctx.error(child, "only a BSDF can be referenced from a shape")
            if material is not None:
                raise ctx.error(child, "a shape can have only one BSDF")
            material = _bsdf_or_ref(ctx, child, bsdfs)
        elif child.tag == "emitter":
            if ctx.attr(child, "type") != "area":
                raise ctx.error(child, "only area emitters can be attached to a shape")
            if sum(c.tag == "emitter" for c in element) > 1:
                raise ctx.error(child, "a shape can have only one emitter")
            eprops = _properties(ctx, child, {"radiance": _COLOUR}, "area emitter")
            _no_children(ctx, child)
            if "radiance" not in eprops:
                raise ctx.error(child, 'an area emitter needs a radiance (<rgb name="radiance">)')
            emission = _rgb_or(ctx, eprops, "radiance", None)
        else:
            raise ctx.error(child, f"<{child.tag}> inside a shape is not supported")

    to_world = _transform(ctx, props["to_world"]) if "to_world" in props else np.eye(4)
    normals: np.ndarray | None = None
    uv: np.ndarray | None = None
    textured_lamp = isinstance(emission, Texture)
    if ((material is not None and material.textured) or textured_lamp) and kind in (
        "cube",
        "sphere",
    ):
        what = "an emitted radiance texture" if textured_lamp else "a textured BSDF"
        raise ctx.error(
            element,
            f"{what} on a {kind} shape is not supported (dualight does not lay out Mitsuba's "
            "texture coordinates on it); use a mesh with texture coordinates",
        )
    if kind in ("obj", "ply"):
        if "filename" not in props:
            raise ctx.error(element, f'a {kind} shape needs <string name="filename">')
        filename = ctx.attr(props["filename"], "value")
        face_normals = _boolean(ctx, props.get("face_normals"), False)
        v, f, normals, uv = _file_mesh(ctx, element, kind, filename, face_normals)
        label = Path(filename).stem
    elif kind == "rectangle":
        (v, f), label = _rectangle(), "rectangle"
        uv = (v[:, :2] + 1.0) / 2.0  # Mitsuba's: (0, 0) at the corner (-1, -1)
    elif kind == "cube":
        (v, f), label = _cube(), "cube"
    else:
        centre = _vector(ctx, props["center"]) if "center" in props else np.zeros(3)
        radius = _number(ctx, props.get("radius"), 1.0)
        if radius <= 0.0:
            raise ctx.error(props["radius"], f"sphere radius must be > 0, got {radius}")
        v, f = icosphere(centre, radius, sphere_subdivisions)
        normals = v - centre  # the sphere's own normals: smooth, as Mitsuba's analytic sphere
        label = "sphere"
    v = _apply(to_world, v)
    if normals is not None:  # normals transform by the inverse transpose
        normals = normals @ np.linalg.inv(to_world[:3, :3])
    if kind in ("rectangle", "cube") and np.linalg.det(to_world[:3, :3]) < 0.0:
        # Mitsuba transforms these shapes' normals as normals, so a mirroring transform keeps
        # their front side; meshes and spheres take the transformed triangles' orientation.
        f = f[:, ::-1]
    if _boolean(ctx, props.get("flip_normals"), False):
        f = f[:, ::-1]
        normals = None if normals is None else -normals
    name = element.get("id") or f"{label}{index}"
    if material is None:  # Mitsuba's default BSDF: diffuse 0.5, black on emitters
        emits = textured_lamp or any(e > 0.0 for e in emission)  # type: ignore[union-attr]
        material = Diffuse((0.0,) * 3 if emits else (0.5,) * 3)
    try:
        scene.add_mesh(
            v,
            f,
            emission=emission,
            material=material,
            name=name,
            degenerate="drop",
            normals=normals,
            uv=uv,
        )
    except ValueError as exc:
        raise ctx.error(element, str(exc)) from None


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


def _sensor(ctx: _Context, element: ET.Element, settings: dict[str, Any]) -> Camera:
    kind = ctx.attr(element, "type")
    if kind != "perspective":
        raise ctx.error(element, f"sensor type {kind!r} is not supported (supported: perspective)")
    props = _properties(
        ctx,
        element,
        {
            "fov": ("float",),
            "fov_axis": ("string",),
            "to_world": ("transform",),
            "near_clip": ("float",),
            "far_clip": ("float",),
        },
        "perspective sensor",
    )
    width, height = 768, 576  # Mitsuba's default film
    rfilter = "gaussian"  # and its default pixel filter
    for child in element:
        if child.tag == "film":
            film = ctx.attr(child, "type")
            if film != "hdrfilm":
                raise ctx.error(child, f"film type {film!r} is not supported (supported: hdrfilm)")
            fprops = _properties(
                ctx,
                child,
                {
                    "width": ("integer",),
                    "height": ("integer",),
                    "pixel_format": ("string",),
                    "component_format": ("string",),
                    "file_format": ("string",),
                    "sample_border": ("boolean",),
                },
                "hdrfilm",
            )
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
            sprops = _properties(
                ctx, child, {"sample_count": ("integer",), "seed": ("integer",)}, "sampler"
            )
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


# Deeper nesting than any scene needs (scene > shape > bsdf > twosided's bsdf > texture > ...
# is 6) is refused before the elements are read recursively.
_MAX_DEPTH = 64


def _check_depth(ctx: _Context, root: ET.Element) -> None:
    """Refuse elements nested deeper than ``_MAX_DEPTH``, naming the deepest one's path."""
    stack = [(root, 1)]
    while stack:
        element, depth = stack.pop()
        if depth > _MAX_DEPTH:
            raise ctx.error(
                element,
                f"elements are nested more than {_MAX_DEPTH} deep; no Mitsuba scene needs that",
            )
        stack.extend((child, depth + 1) for child in element)


def _parse(
    path: PathLike, params: Mapping[str, Any] | None, build: bool, sphere_subdivisions: int
) -> tuple[Scene, dict[str, Any]]:
    xml_path = _existing_file(path, "Mitsuba XML")
    ctx = _Context(xml_path, params or {})
    try:
        root = ET.parse(xml_path).getroot()
    except ET.ParseError as exc:
        raise ValueError(f"{str(xml_path)!r} is not well-formed XML: {exc}") from None
    if root.tag != "scene":
        raise ctx.error(root, "the root element must be <scene>")
    _check_depth(ctx, root)
    version = root.get("version", "3.0.0")
    if version.split(".")[0] not in ("2", "3"):
        raise ctx.error(root, f"scene version {version!r}: only Mitsuba 2 and 3 files are read")
    scene = Scene()
    settings: dict[str, Any] = {}
    bsdfs: dict[str, Material] = {}
    shapes = 0
    for element in root:
        tag = element.tag
        if tag == "default":
            ctx.defaults[ctx.attr(element, "name")] = element.get("value", "")
        elif tag == "integrator":
            _integrator(ctx, element, settings)
        elif tag == "sensor":
            camera = _sensor(ctx, element, settings)
            if build:
                if scene.camera is not None:
                    raise ctx.error(element, "only one sensor is supported")
                scene.camera = camera
        elif not build:
            continue
        elif tag == "bsdf":
            material = _bsdf(ctx, element, bsdfs)
            key = element.get("id")
            if key is None:
                raise ctx.error(element, "a top-level BSDF needs an id to be referenced")
            bsdfs[ctx.substitute(element, key)] = material
        elif tag == "texture":
            key = element.get("id")
            if key is None:
                raise ctx.error(element, "a top-level texture needs an id to be referenced")
            ctx.textures[ctx.substitute(element, key)] = _texture(ctx, element)
        elif tag == "shape":
            _shape(ctx, element, bsdfs, scene, shapes, sphere_subdivisions)
            shapes += 1
        elif tag == "emitter":
            scene.add_emitter(_emitter(ctx, element))
        else:
            raise ctx.error(
                element,
                "element not supported (supported at the top level: default, integrator, "
                "sensor, bsdf, texture, shape)",
            )
    return scene, settings


def load_mitsuba_xml(
    path: PathLike,
    *,
    params: Mapping[str, Any] | None = None,
    sphere_subdivisions: int = 4,
) -> Scene:
    """Load a scene in Mitsuba 3's XML format (a subset of it) with its camera.

    Supported:

    * ``<default name value>`` and ``$name`` substitution in attribute values (``params``
      overrides defaults, like ``mitsuba.load_file(path, **params)``);
    * shapes ``obj``, ``ply`` (``filename`` relative to the XML file, ``face_normals``),
      ``rectangle`` (``[-1, 1]^2`` at ``z = 0``, normal ``+z``), ``cube`` (``[-1, 1]^3``),
      ``sphere`` (``center``, ``radius``; tessellated as an icosphere of
      ``sphere_subdivisions``), each with ``flip_normals`` and a ``to_world`` ``<transform>``
      of ``translate``, ``scale``, ``rotate``, ``matrix`` and ``lookat`` operations;
    * BSDFs, inline or top-level with an ``id`` and referenced by ``<ref id>``: ``diffuse``
      (RGB ``reflectance``), ``twosided`` around any reflector, ``conductor`` (Mitsuba's
      named metals or ``eta``/``k``; ``material="none"``, a perfect mirror, by default),
      ``roughconductor``, ``dielectric``, ``thindielectric``, ``roughdielectric``,
      ``plastic`` and ``roughplastic`` with Mitsuba 3's parameters (``int_ior``/``ext_ior``
      as numbers or Mitsuba's IOR names, defaults as in Mitsuba); see
      :mod:`dualight.materials`;
    * ``<emitter type="area">`` inside a shape with an RGB ``radiance`` or a ``bitmap`` or
      ``checkerboard`` texture of it (one-sided, on the normals' side); stand-alone
      ``point`` (``position`` or ``to_world``) and ``spot`` (``to_world``, its +z the beam's
      axis; ``cutoff_angle``, ``beam_width``) emitters with an RGB or float ``intensity``
      (:mod:`dualight.emitters`);
    * ``<sensor type="perspective">`` with ``fov``, ``fov_axis`` (x, y, diagonal, smaller,
      larger; converted to dualight's fov along x), ``to_world`` (rotation and translation);
      its ``<film type="hdrfilm">`` ``width`` and ``height``; its sampler's ``sample_count``
      and the ``<integrator>`` settings are read by :func:`read_mitsuba_settings`.

    Approximations, each with a ``UserWarning``: ``sample_visible=false`` on a rough BSDF is
    ignored (dualight samples visible normals: the same BSDF, other noise); a pixel filter
    other than ``box`` (Mitsuba's default is a Gaussian) is replaced by dualight's box filter.
    As in Mitsuba, ``obj``/``ply`` meshes without ``face_normals`` are shaded smoothly, by the
    file's vertex normals or by normals computed as Mitsuba does (each face's normal weighted
    by its angle at the vertex); a ``sphere`` is an icosphere shaded by the sphere's own
    normals. Without a warning: dualight's ``diffuse`` is two-sided, so a one-sided
    Mitsuba ``diffuse`` differs only where light reaches the back of a surface (conductors and
    plastics are one-sided unless in ``twosided``, as in Mitsuba); a shape without a BSDF gets
    Mitsuba's default: diffuse 0.5, or black if it emits.

    Everything else (other plugin types, textures, spectra, other emitters, includes,
    unknown properties) raises a ``ValueError`` that names the element and the file.

    Parameters
    ----------
    path : str or pathlib.Path
        The XML file.
    params : mapping, optional
        Values for ``$name`` references, overriding ``<default>`` elements.
    sphere_subdivisions : int, optional
        Icosphere subdivisions of ``sphere`` shapes (``20 * 4**n`` triangles).

    Returns
    -------
    dualight.Scene
        The scene, with a camera if the file has a sensor.

    Raises
    ------
    FileNotFoundError
        If the XML file or a mesh file it names does not exist.
    ValueError
        On malformed XML, unsupported elements, bad or non-finite numbers.

    Examples
    --------
    >>> scene = dualight.load_mitsuba_xml("cbox.xml", params={"radiance": 10})
    >>> depth = dualight.read_mitsuba_settings("cbox.xml", keys=("max_depth", "rr_depth"))
    >>> image = dualight.render(scene, spp=256, **depth)
    """
    scene, _ = _parse(path, params, True, sphere_subdivisions)
    return scene


# Mitsuba integrators and samplers and the dualight method or sampler that computes the same
# image (bdpt, pssmlt and mlt are Mitsuba 0.6's names).
_INTEGRATORS = {
    "path": "path",
    "ptracer": "light",
    "bdpt": "bdpt",
    "pssmlt": "pssmlt",
    "mlt": "mlt",
}
_SAMPLERS = ("independent", "sobol")
# Integrator properties dualight does as Mitsuba does with these values: left out silently.
_SAME_AS_MITSUBA = {"hide_emitters": False}


def _render_keywords(path: PathLike, settings: Mapping[str, Any]) -> dict[str, Any]:
    """The keywords of :func:`dualight.render` that the file's settings amount to; what has
    no keyword is left out, with a ``UserWarning`` unless dualight does it anyway."""
    out: dict[str, Any] = {}
    dropped = []
    for key, value in settings.items():
        if key == "integrator":
            if value in _INTEGRATORS:
                out["method"] = _INTEGRATORS[value]
            else:
                dropped.append(f"integrator {value!r}")
        elif key in ("spp", "max_depth", "rr_depth"):
            out[key] = value
        elif key == "_seed":
            out["seed"] = value
        elif key == "_sampler":
            if value in _SAMPLERS:
                out["sampler"] = value
            else:
                dropped.append(f"sampler {value!r}")
        elif key not in _SAME_AS_MITSUBA or _SAME_AS_MITSUBA[key] != value:
            dropped.append(f"{key}={value!r}")
    if dropped:
        warnings.warn(
            f"{str(path)!r}: no dualight.render keyword for {', '.join(dropped)}; left out "
            "(read_mitsuba_settings(..., raw=True) returns the file's settings as given)",
            UserWarning,
            stacklevel=3,
        )
    return out


def read_mitsuba_settings(
    path: PathLike,
    *,
    params: Mapping[str, Any] | None = None,
    keys: tuple[str, ...] | None = None,
    raw: bool = False,
) -> dict[str, Any]:
    """The render settings a Mitsuba 3 XML file asks for, as keywords of
    :func:`dualight.render`, so that ``render(scene, **read_mitsuba_settings(path))`` renders
    what ``mitsuba.render(mitsuba.load_file(path))`` would.

    Parameters
    ----------
    path : str or pathlib.Path
        The XML file.
    params : mapping, optional
        As in :func:`load_mitsuba_xml`.
    keys : tuple of str, optional
        Return only these keys (those the file gives).
    raw : bool, optional
        Return the file's settings as given (the integrator's type and properties, the
        sampler's ``sample_count`` as ``spp``), not render's keywords.

    Returns
    -------
    dict
        Of those the file gives: ``method`` (from the integrator's type: ``path`` is
        ``"path"``, ``ptracer`` is ``"light"``; Mitsuba 0.6's ``bdpt``, ``pssmlt`` and
        ``mlt`` keep their names), ``spp`` (the sampler's ``sample_count``), ``max_depth``
        and ``rr_depth`` (the integrator's), ``seed`` (the sampler's) and ``sampler``
        (``independent`` or ``sobol``). Settings without a render keyword (another
        integrator or sampler, ``hide_emitters=True``, ...) are left out with a
        ``UserWarning``; those dualight does anyway (``hide_emitters=False``) silently.
        With ``raw=True``: ``integrator`` (its type), the integrator's properties as given
        and ``spp``.
    """
    _, settings = _parse(path, params, False, 0)
    if raw:
        settings = {k: v for k, v in settings.items() if not k.startswith("_")}
    else:
        settings = _render_keywords(path, settings)
    if keys is not None:
        settings = {k: v for k, v in settings.items() if k in keys}
    return settings
