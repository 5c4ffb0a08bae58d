"""Mitsuba 3 BSDFs and textures: ``<bsdf>`` and ``<texture>`` elements as dualight
materials and textures."""

from __future__ import annotations

import warnings
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from typing import Any

from dualight.io._mitsuba_context import _Context
from dualight.io._mitsuba_values import (
    _COLOUR,
    _RGB_OR_FLOAT,
    _TEXTURE_TAGS,
    _boolean,
    _float,
    _no_children,
    _number,
    _properties,
    _rgb_value,
    _string,
    _transform,
    _unsupported_type,
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
from dualight.textures import Bitmap, Checkerboard, Texture

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


def _bsdf(ctx: _Context, element: ET.Element) -> Material:
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
            both = TwoSided(_bsdf_or_ref(ctx, inner[0]))
        except ValueError as exc:
            if ctx.located(exc):
                raise
            raise ctx.error(element, str(exc)) from None
        if type(both) is Conductor and both.eta == (0.0,) * 3 and both.k == (1.0,) * 3:
            return Mirror(both.specular_reflectance)  # the same BSDF (Fresnel is 1), by its name
        return both
    if kind not in _BSDF_PROPERTIES:
        raise ctx.error(element, _unsupported_type("bsdf", kind))
    props = _properties(ctx, element, _BSDF_PROPERTIES[kind], kind)
    _no_children(ctx, element)
    try:
        return _BSDF_BUILDERS[kind](ctx, props)
    except (ValueError, TypeError) as exc:
        if ctx.located(exc):
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
        return ctx.ref(element, "texture")
    kind = ctx.attr(element, "type")
    if kind not in _TEXTURE_PROPERTIES:
        raise ctx.error(element, _unsupported_type("texture", kind))
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
        if isinstance(exc, ValueError) and ctx.located(exc):
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


def _bsdf_or_ref(ctx: _Context, element: ET.Element) -> Material:
    return ctx.ref(element, "bsdf") if element.tag == "ref" else _bsdf(ctx, element)
