"""Surface materials: what :meth:`dualight.Scene.add_mesh` accepts as ``material=``.

* :class:`Diffuse` -- a two-sided Lambertian reflector (the default).
* :class:`Mirror` -- a two-sided ideal specular reflector.
* :class:`Dielectric` -- a smooth interface between air (IOR 1) and a material such as glass.
* :class:`Conductor` and :class:`RoughConductor` -- metals with Fresnel reflectance (complex
  IOR, or one of Mitsuba 3's named metals), smooth or with Beckmann/GGX microfacets.
* :class:`ThinDielectric` and :class:`RoughDielectric` -- a window pane and frosted glass.
* :class:`Plastic` and :class:`RoughPlastic` -- a diffuse base under a smooth or rough coat.
* :class:`TwoSided` -- one of the reflectors above, reflecting on both sides.

The last seven take Mitsuba 3's plugin names and parameters (``conductor``, ``roughconductor``,
``thindielectric``, ``roughdielectric``, ``plastic``, ``roughplastic``, ``twosided``), with
``ior`` the relative IOR ``int_ior / ext_ior``, so a Mitsuba scene file maps one to one; like
Mitsuba's, the reflectors among them are one-sided (black behind their normals) unless wrapped
in :class:`TwoSided`.

Each is a frozen dataclass derived from :class:`Material`, validated when it is made, and each
matches one Mitsuba 3 BSDF so that :func:`dualight.mitsuba.scene_dict` can export it exactly.
Each describes itself: the core BSDF it compiles to (``_core_bsdf``) and, from the core's own
flags, what it is (:attr:`Material.flags`: diffuse, glossy, specular, reflection,
transmission). ``Mirror`` and ``Dielectric`` scatter into single directions (Dirac deltas,
``"specular"``): the path tracer follows them by sampling, and radiosity, which assumes diffuse
reflectors, refuses scenes that contain them.

Directions and sides follow the mesh: a triangle's normal is the right-hand-rule normal
``(v1 - v0) x (v2 - v0)``; for a dielectric it points to the exterior (IOR 1), so a closed glass
object needs outward-facing triangles.
"""

from __future__ import annotations

import copy
import functools
import json
import math
from dataclasses import dataclass
from importlib import resources
from numbers import Real
from typing import Any, ClassVar, Literal

import numpy as np

from dualight.textures import Texture, check_texture_range

__all__ = [
    "Conductor",
    "Dielectric",
    "Diffuse",
    "Material",
    "Mirror",
    "Plastic",
    "RoughConductor",
    "RoughDielectric",
    "RoughPlastic",
    "ThinDielectric",
    "TwoSided",
]

RGB = tuple[float, float, float]


def _reflectance(value: Any, owner: str) -> Any:
    """``value`` as 3 floats, each finite and in ``[0, 1]``, or a ValueError naming ``owner``;
    a :class:`~dualight.textures.Texture` whose values lie in ``[0, 1]`` as it is."""
    if isinstance(value, Texture):
        check_texture_range(value, owner, "reflectance", 0.0, 1.0)
        return value
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{owner} reflectance must be 3 numbers, got {value!r}") from exc
    if arr.shape != (3,):
        raise ValueError(f"{owner} reflectance must be 3 numbers, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{owner} reflectance must be finite, got {arr.tolist()}")
    if np.any(arr < 0.0) or np.any(arr > 1.0):
        raise ValueError(
            f"{owner} reflectance must be in [0, 1] per channel (energy conservation), "
            f"got {arr.tolist()}"
        )
    return (float(arr[0]), float(arr[1]), float(arr[2]))


@functools.lru_cache(maxsize=256)
def _core_of(material: Material) -> Any:
    """The core BSDF of a material (cached: rough plastic tabulates its coat when made)."""
    return material._core_bsdf()


def _rgb(value: Any, owner: str, name: str, upper: float, texture: bool = False) -> Any:
    """``value`` (a number or 3 numbers) as 3 finite floats in ``[0, upper]``; where
    ``texture``, a texture whose values lie there as it is."""
    if texture and isinstance(value, Texture):
        check_texture_range(value, owner, name, 0.0, upper)
        return value
    try:
        arr = np.broadcast_to(np.asarray(value, dtype=np.float64), (3,))
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{owner} {name} must be a number or 3 numbers, got {value!r}") from exc
    if not np.all(np.isfinite(arr)) or np.any(arr < 0.0) or np.any(arr > upper):
        raise ValueError(f"{owner} {name} must be finite and in [0, {upper:g}], got {arr.tolist()}")
    return (float(arr[0]), float(arr[1]), float(arr[2]))


def _real(value: Any, owner: str, name: str, low: float, high: float) -> float:
    """A real number in ``[low, high]`` (TypeError for non-numbers, ValueError outside)."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"{owner} {name} must be a real number, got {type(value).__name__}")
    x = float(value)
    if not (math.isfinite(x) and low <= x <= high):
        raise ValueError(f"{owner} {name} must be finite and in [{low:g}, {high:g}], got {value!r}")
    return x


def _relative_ior(value: Any, owner: str) -> float:
    ior = _real(value, owner, "ior", 1e-3, 1e3)
    if ior == 1.0:
        raise ValueError(
            f"{owner} ior must differ from 1 (an index-matched interface scatters nothing)"
        )
    return ior


MicrofacetDistribution = Literal["beckmann", "ggx"]


def _distribution(value: Any, owner: str) -> str:
    if value not in ("beckmann", "ggx"):
        raise ValueError(f"{owner} distribution must be 'beckmann' or 'ggx', got {value!r}")
    return str(value)


@functools.cache
def named_metals() -> dict[str, tuple[RGB, RGB]]:
    """Mitsuba 3's named conductors as ``{name: (eta, k)}`` in RGB, the values its ``*_rgb``
    variants use (``data/metals.json``, made by ``scripts/make_metal_table.py``)."""
    text = resources.files("dualight").joinpath("data/metals.json").read_text()
    table = json.loads(text)["metals"]
    return {name: (tuple(v["eta"]), tuple(v["k"])) for name, v in table.items()}  # type: ignore[misc]


# Mitsuba's default IOR names as relative IORs: polypropylene and BK7 glass against air.
_AIR = 1.000277
_POLYPROPYLENE = 1.49 / _AIR
_BK7 = 1.5046 / _AIR


class Material:
    """Base class of every material :meth:`dualight.Scene.add_mesh` accepts.

    A subclass names its core BSDF (``_kind``, a :class:`dualight._core.BsdfKind` name) and
    gives the core's parameters (``_core_parameters``; a BSDF with other parameters overrides
    ``_core_bsdf``) and the RGB it stands for in ``Mesh.reflectance``
    (:attr:`rgb_reflectance`); everything else, what the material *is*, comes from the core
    BSDF's flags, so no caller lists material types.
    """

    __slots__ = ()
    _kind: ClassVar[str]
    # Fields that may hold a texture, and the core BSDF parameter each drives.
    _texturable: ClassVar[dict[str, str]] = {}

    def _textures(self) -> list[tuple[str, Any]]:
        """``(core parameter, core texture)`` for each field that holds a texture."""
        return [
            (parameter, getattr(self, name)._core_texture())
            for name, parameter in self._texturable.items()
            if isinstance(getattr(self, name), Texture)
        ]

    @property
    def textured(self) -> bool:
        """Whether some parameter is a texture."""
        return any(isinstance(getattr(self, name), Texture) for name in self._texturable)

    def _core_parameters(self) -> tuple[RGB, float]:
        """``(reflectance, ior)`` as the core's ``Scene(kind=..., ior=...)`` arrays take them."""
        raise NotImplementedError

    def _core_bsdf(self) -> Any:
        """The core BSDF (a ``dualight._core.Bsdf``) the compiled scene uses for this material."""
        from dualight import _core

        reflectance, ior = self._core_parameters()
        return _core.Bsdf(getattr(_core.BsdfKind, self._kind), reflectance=reflectance, ior=ior)

    @property
    def rgb_reflectance(self) -> RGB:
        """The RGB reflectance the material stands for in ``Mesh.reflectance``."""
        return self._core_parameters()[0]

    @property
    def flags(self) -> frozenset[str]:
        """What the material is, from its core BSDF: a subset of ``"diffuse"``, ``"glossy"``,
        ``"specular"`` (Dirac lobes), ``"reflection"`` and ``"transmission"``."""
        return frozenset(_core_of(self).flags)

    @property
    def is_diffuse_reflector(self) -> bool:
        """Only diffuse reflection: what radiosity can solve (the core's own test of its flags)."""
        return bool(_core_of(self).is_diffuse_reflector)

    def _mitsuba_bsdf(self) -> dict[str, Any]:
        """The Mitsuba 3 BSDF dict (``mitsuba.load_dict`` form) this material stands for."""
        raise NotImplementedError

    @property
    def has_specular(self) -> bool:
        """Some Dirac (ideal specular) lobe."""
        return "specular" in self.flags


@dataclass(frozen=True)
class Diffuse(Material):
    """A two-sided Lambertian reflector: ``f = reflectance / pi`` on both sides.

    Matches Mitsuba 3's ``twosided`` BSDF around ``diffuse`` with an RGB ``reflectance``.

    Parameters
    ----------
    reflectance : tuple of 3 float, optional
        Albedo per RGB channel, each finite and in ``[0, 1]``.

    Raises
    ------
    ValueError
        If ``reflectance`` is not 3 finite numbers in ``[0, 1]``.
    """

    reflectance: Any = (0.5, 0.5, 0.5)
    _kind: ClassVar[str] = "lambertian"
    _texturable: ClassVar[dict[str, str]] = {"reflectance": "reflectance"}

    def __post_init__(self) -> None:
        object.__setattr__(self, "reflectance", _reflectance(self.reflectance, "Diffuse"))

    def _core_parameters(self) -> tuple[RGB, float]:
        return _constant(self.reflectance), 1.0

    def _mitsuba_bsdf(self) -> dict[str, Any]:
        return {
            "type": "twosided",
            "bsdf": {"type": "diffuse", "reflectance": _mi_rgb(self.reflectance)},
        }


@dataclass(frozen=True)
class Mirror(Material):
    """A two-sided ideal specular reflector: light leaves in the mirrored direction only,
    scaled by ``reflectance`` (no Fresnel term).

    Matches Mitsuba 3's ``twosided`` BSDF around ``conductor`` with ``material="none"`` (a
    perfect reflector) and an RGB ``specular_reflectance``.

    Parameters
    ----------
    reflectance : tuple of 3 float, optional
        Fraction of light reflected per RGB channel, each finite and in ``[0, 1]``.

    Raises
    ------
    ValueError
        If ``reflectance`` is not 3 finite numbers in ``[0, 1]``.
    """

    reflectance: Any = (1.0, 1.0, 1.0)
    _kind: ClassVar[str] = "mirror"
    _texturable: ClassVar[dict[str, str]] = {"reflectance": "specular_reflectance"}

    def __post_init__(self) -> None:
        object.__setattr__(self, "reflectance", _reflectance(self.reflectance, "Mirror"))

    def _core_parameters(self) -> tuple[RGB, float]:
        return _constant(self.reflectance), 1.0

    def _mitsuba_bsdf(self) -> dict[str, Any]:
        conductor = {
            "type": "conductor",
            "material": "none",
            "specular_reflectance": _mi_rgb(self.reflectance),
        }
        return {"type": "twosided", "bsdf": conductor}


@dataclass(frozen=True)
class Dielectric(Material):
    """A smooth interface between the exterior (IOR 1, on the side of the triangle normals)
    and a clear interior of index ``ior``: Fresnel-weighted ideal reflection and refraction,
    with total internal reflection from inside. It absorbs nothing.

    Matches Mitsuba 3's ``dielectric`` BSDF (one BSDF for both sides, not ``twosided``) with
    ``int_ior=ior`` and ``ext_ior=1.0``.

    Parameters
    ----------
    ior : float, optional
        Index of refraction of the interior, finite and ``> 0`` (glass about 1.5, water 1.33).

    Raises
    ------
    TypeError
        If ``ior`` is not a real number.
    ValueError
        If ``ior`` is not finite or not ``> 0``.
    """

    ior: float = 1.5
    _kind: ClassVar[str] = "dielectric"

    def __post_init__(self) -> None:
        ior = self.ior
        if isinstance(ior, bool) or not isinstance(ior, Real):
            raise TypeError(f"Dielectric ior must be a real number, got {type(ior).__name__}")
        ior = float(ior)
        if not (math.isfinite(ior) and ior > 0.0):
            raise ValueError(f"Dielectric ior must be finite and > 0, got {self.ior!r}")
        if not 1e-18 <= ior <= 1e18:  # Fresnel squares it in float32
            raise ValueError(
                f"Dielectric ior must be within [1e-18, 1e18], got {self.ior!r}: the core's "
                "Fresnel terms square it in float32, which overflows or underflows beyond"
            )
        object.__setattr__(self, "ior", ior)

    def _core_parameters(self) -> tuple[RGB, float]:
        # It absorbs nothing: Fresnel splits light between reflection and refraction.
        return (1.0, 1.0, 1.0), self.ior

    def _mitsuba_bsdf(self) -> dict[str, Any]:
        return {"type": "dielectric", "int_ior": float(self.ior), "ext_ior": 1.0}


def _mi_rgb(value: Any) -> dict[str, Any]:
    if isinstance(value, Texture):
        return value._mitsuba_dict()
    return {"type": "rgb", "value": [float(c) for c in value]}


def _core() -> Any:
    from dualight import _core as core

    return core


class _Reflector(Material):
    """Reflects on its front only unless ``two_sided`` (set by :class:`TwoSided`)."""

    __slots__ = ()
    two_sided: bool

    def _one_sided_bsdf(self) -> dict[str, Any]:
        raise NotImplementedError

    def _mitsuba_bsdf(self) -> dict[str, Any]:
        inner = self._one_sided_bsdf()
        return {"type": "twosided", "bsdf": inner} if self.two_sided else inner


def _metal(material: str | None, eta: Any, k: Any, owner: str) -> tuple[RGB, RGB]:
    """(eta, k) from a named metal or given values; ``"none"`` is the perfect mirror."""
    if material is not None and (eta is not None or k is not None):
        raise ValueError(f"{owner}: give material or eta and k, not both (as Mitsuba)")
    if material is None and eta is None and k is None:
        material = "none"
    if material == "none":
        return (0.0, 0.0, 0.0), (1.0, 1.0, 1.0)
    if material is not None:
        metals = named_metals()
        if material not in metals:
            raise ValueError(
                f"{owner}: unknown metal {material!r} (known: none, {', '.join(sorted(metals))})"
            )
        return metals[material]
    return _rgb(0.0 if eta is None else eta, owner, "eta", 1e3), _rgb(
        1.0 if k is None else k, owner, "k", 1e3
    )


@dataclass(frozen=True)
class Conductor(_Reflector):
    """A smooth metal, Mitsuba 3's ``conductor``: mirror reflection weighted by the Fresnel
    reflectance of the complex IOR ``eta + i k`` (per RGB channel) and ``specular_reflectance``.

    Parameters
    ----------
    material : str, optional
        One of Mitsuba's named metals (``"Au"``, ``"Ag"``, ``"Cu"``, ``"Al"``, ... see
        :func:`named_metals`) or ``"none"``, a perfect mirror (the default when neither
        ``material`` nor ``eta``/``k`` is given).
    eta, k : float or 3 floats, optional
        The complex IOR relative to the exterior, each in ``[0, 1000]``.
    specular_reflectance : float or 3 floats, optional
        A scale on the reflectance, in ``[0, 1]``.
    two_sided : bool, optional
        Reflect on both sides (Mitsuba's ``twosided`` around it); by default the back is black.
    """

    material: str | None = None
    eta: Any = None
    k: Any = None
    specular_reflectance: Any = 1.0
    two_sided: bool = False
    _kind: ClassVar[str] = "conductor"
    _texturable: ClassVar[dict[str, str]] = {"specular_reflectance": "specular_reflectance"}

    def __post_init__(self) -> None:
        eta, k = _metal(self.material, self.eta, self.k, "Conductor")
        if self.material is None and self.eta is None and self.k is None:
            object.__setattr__(self, "material", "none")
        object.__setattr__(self, "eta", eta)
        object.__setattr__(self, "k", k)
        spec = _rgb(self.specular_reflectance, "Conductor", "specular_reflectance", 1.0, True)
        object.__setattr__(self, "specular_reflectance", spec)
        object.__setattr__(self, "two_sided", bool(self.two_sided))

    def _core_bsdf(self) -> Any:
        return _core().Bsdf.conductor(
            eta=self.eta,
            k=self.k,
            specular_reflectance=_constant(self.specular_reflectance),
            two_sided=self.two_sided,
        )

    def _core_parameters(self) -> tuple[RGB, float]:
        return _constant(self.specular_reflectance), 1.0

    def _one_sided_bsdf(self) -> dict[str, Any]:
        spec = {"specular_reflectance": _mi_rgb(self.specular_reflectance)}
        if self.material is not None:  # a named metal: Mitsuba looks up the same data
            return {"type": "conductor", "material": self.material, **spec}
        return {"type": "conductor", "eta": _mi_rgb(self.eta), "k": _mi_rgb(self.k), **spec}


def _alpha(value: Any, owner: str, name: str, texture: bool = False) -> Any:
    if texture and isinstance(value, Texture):
        check_texture_range(value, owner, name, 0.0, 1e3)
        return value
    return _real(value, owner, name, 0.0, 1e3)


def _constant(value: Any) -> Any:
    """A colour for the core BSDF's constant: a texture's mean stands for it (the BSDF's flags
    and radiosity's albedo); at each surface point the texture's value replaces it."""
    return value.mean if isinstance(value, Texture) else value


def _constant_alpha(value: Any) -> Any:
    if isinstance(value, Texture):
        r, g, b = value.mean
        return 0.2126 * r + 0.7152 * g + 0.0722 * b
    return value


def _mi_value(value: Any) -> Any:
    """A roughness for Mitsuba: a number or a texture's dict."""
    return value._mitsuba_dict() if isinstance(value, Texture) else float(value)


@dataclass(frozen=True)
class RoughConductor(_Reflector):
    """A rough metal, Mitsuba 3's ``roughconductor``: microfacet reflection (Beckmann or GGX
    normals sampled by visible normals) with the conductor's Fresnel term.

    Parameters
    ----------
    alpha : float, optional
        Roughness (RMS slope for Beckmann, width for GGX) of an isotropic surface; default 0.1.
    alpha_u, alpha_v : float, optional
        Anisotropic roughness along the surface's first and second tangents, given together
        instead of ``alpha``.
    distribution : {"beckmann", "ggx"}, optional
    material, eta, k, specular_reflectance, two_sided :
        As for :class:`Conductor`.
    """

    alpha: float | None = None
    alpha_u: float | None = None
    alpha_v: float | None = None
    distribution: MicrofacetDistribution = "beckmann"
    material: str | None = None
    eta: Any = None
    k: Any = None
    specular_reflectance: Any = 1.0
    two_sided: bool = False
    _kind: ClassVar[str] = "rough_conductor"
    _texturable: ClassVar[dict[str, str]] = {
        "specular_reflectance": "specular_reflectance",
        "alpha_u": "alpha_u",
        "alpha_v": "alpha_v",
    }

    def __post_init__(self) -> None:
        _roughness(self, "RoughConductor")
        Conductor.__post_init__(self)  # type: ignore[arg-type]
        object.__setattr__(self, "distribution", _distribution(self.distribution, "RoughConductor"))

    def _core_bsdf(self) -> Any:
        return _core().Bsdf.rough_conductor(
            distribution=self.distribution,
            alpha_u=_constant_alpha(self.alpha_u),
            alpha_v=_constant_alpha(self.alpha_v),
            eta=self.eta,
            k=self.k,
            specular_reflectance=_constant(self.specular_reflectance),
            two_sided=self.two_sided,
        )

    def _core_parameters(self) -> tuple[RGB, float]:
        return _constant(self.specular_reflectance), 1.0

    def _one_sided_bsdf(self) -> dict[str, Any]:
        metal = Conductor._one_sided_bsdf(self)  # type: ignore[arg-type]
        return {**metal, "type": "roughconductor", **_mi_roughness(self)}


def _roughness(m: Any, owner: str) -> None:
    """Fills alpha/alpha_u/alpha_v from what was given (Mitsuba's rules: alpha, or both of
    alpha_u and alpha_v; default 0.1)."""
    if m.alpha is not None and (m.alpha_u is not None or m.alpha_v is not None):
        raise ValueError(f"{owner}: give either alpha or alpha_u and alpha_v, not both")
    if (m.alpha_u is None) != (m.alpha_v is None):
        raise ValueError(f"{owner}: give both alpha_u and alpha_v")
    if m.alpha_u is None:
        a = _alpha(0.1 if m.alpha is None else m.alpha, owner, "alpha", True)
        au = av = a
    else:
        au = _alpha(m.alpha_u, owner, "alpha_u", True)
        av = _alpha(m.alpha_v, owner, "alpha_v", True)
        a = au if au is av or (not isinstance(au, Texture) and au == av) else None
    object.__setattr__(m, "alpha", a)
    object.__setattr__(m, "alpha_u", au)
    object.__setattr__(m, "alpha_v", av)


def _mi_roughness(m: Any) -> dict[str, Any]:
    if m.alpha is not None:
        return {"distribution": m.distribution, "alpha": _mi_value(m.alpha)}
    return {
        "distribution": m.distribution,
        "alpha_u": _mi_value(m.alpha_u),
        "alpha_v": _mi_value(m.alpha_v),
    }


@dataclass(frozen=True)
class ThinDielectric(Material):
    """A thin pane of glass, Mitsuba 3's ``thindielectric``: light is reflected (all internal
    bounces summed) or passes straight through, on either side.

    Parameters
    ----------
    ior : float, optional
        Relative IOR ``int_ior / ext_ior`` (default BK7 against air, as Mitsuba).
    """

    ior: float = _BK7
    _kind: ClassVar[str] = "thin_dielectric"

    def __post_init__(self) -> None:
        object.__setattr__(self, "ior", _relative_ior(self.ior, "ThinDielectric"))

    def _core_bsdf(self) -> Any:
        return _core().Bsdf.thin_dielectric(ior=self.ior)

    def _core_parameters(self) -> tuple[RGB, float]:
        return (1.0, 1.0, 1.0), self.ior

    def _mitsuba_bsdf(self) -> dict[str, Any]:
        return {"type": "thindielectric", "int_ior": float(self.ior), "ext_ior": 1.0}


@dataclass(frozen=True)
class RoughDielectric(Material):
    """Frosted glass, Mitsuba 3's ``roughdielectric``: microfacet reflection and refraction
    [Walter et al. 2007], correct in both transport modes. The exterior is on the normals' side.

    Parameters
    ----------
    alpha, alpha_u, alpha_v, distribution :
        As for :class:`RoughConductor`.
    ior : float, optional
        Relative IOR ``int_ior / ext_ior`` (default BK7 against air).
    """

    alpha: float | None = None
    alpha_u: float | None = None
    alpha_v: float | None = None
    distribution: MicrofacetDistribution = "beckmann"
    ior: float = _BK7
    _kind: ClassVar[str] = "rough_dielectric"
    _texturable: ClassVar[dict[str, str]] = {"alpha_u": "alpha_u", "alpha_v": "alpha_v"}

    def __post_init__(self) -> None:
        _roughness(self, "RoughDielectric")
        object.__setattr__(
            self, "distribution", _distribution(self.distribution, "RoughDielectric")
        )
        object.__setattr__(self, "ior", _relative_ior(self.ior, "RoughDielectric"))

    def _core_bsdf(self) -> Any:
        return _core().Bsdf.rough_dielectric(
            distribution=self.distribution,
            alpha_u=_constant_alpha(self.alpha_u),
            alpha_v=_constant_alpha(self.alpha_v),
            ior=self.ior,
        )

    def _core_parameters(self) -> tuple[RGB, float]:
        return (1.0, 1.0, 1.0), self.ior

    def _mitsuba_bsdf(self) -> dict[str, Any]:
        return {
            "type": "roughdielectric",
            **_mi_roughness(self),
            "int_ior": float(self.ior),
            "ext_ior": 1.0,
        }


@dataclass(frozen=True)
class Plastic(_Reflector):
    """Smooth plastic, Mitsuba 3's ``plastic``: a diffuse base under a smooth dielectric coat
    with its internal scattering.

    Parameters
    ----------
    diffuse_reflectance : float or 3 floats, optional
        The base's albedo in ``[0, 1]`` (default 0.5).
    specular_reflectance : float or 3 floats, optional
        A scale on the coat's reflection, in ``[0, 1]``.
    ior : float, optional
        Relative IOR of the coat (default polypropylene against air, as Mitsuba).
    nonlinear : bool, optional
        Mitsuba's ``nonlinear``: account for the base's colour at each internal bounce.
    two_sided : bool, optional
        Reflect on both sides; by default the back is black.
    """

    diffuse_reflectance: Any = 0.5
    specular_reflectance: Any = 1.0
    ior: float = _POLYPROPYLENE
    nonlinear: bool = False
    two_sided: bool = False
    _kind: ClassVar[str] = "plastic"
    _texturable: ClassVar[dict[str, str]] = {
        "diffuse_reflectance": "diffuse_reflectance",
        "specular_reflectance": "specular_reflectance",
    }

    def __post_init__(self) -> None:
        owner = type(self).__name__
        for name in ("diffuse_reflectance", "specular_reflectance"):
            object.__setattr__(self, name, _rgb(getattr(self, name), owner, name, 1.0, True))
        object.__setattr__(self, "ior", _relative_ior(self.ior, owner))
        object.__setattr__(self, "nonlinear", bool(self.nonlinear))
        object.__setattr__(self, "two_sided", bool(self.two_sided))

    def _core_bsdf(self) -> Any:
        return _core().Bsdf.plastic(
            diffuse_reflectance=_constant(self.diffuse_reflectance),
            specular_reflectance=_constant(self.specular_reflectance),
            ior=self.ior,
            nonlinear=self.nonlinear,
            two_sided=self.two_sided,
        )

    def _core_parameters(self) -> tuple[RGB, float]:
        return _constant(self.diffuse_reflectance), self.ior

    def _one_sided_bsdf(self) -> dict[str, Any]:
        return {
            "type": "plastic",
            "diffuse_reflectance": _mi_rgb(self.diffuse_reflectance),
            "specular_reflectance": _mi_rgb(self.specular_reflectance),
            "int_ior": float(self.ior),
            "ext_ior": 1.0,
            "nonlinear": self.nonlinear,
        }


@dataclass(frozen=True)
class RoughPlastic(Plastic):
    """Rough plastic, Mitsuba 3's ``roughplastic``: a diffuse base under a rough (isotropic
    Beckmann or GGX) coat, with the coat's transmittance and internal reflectance tabulated as
    Mitsuba does.

    Parameters
    ----------
    alpha : float, optional
        The coat's roughness (default 0.1).
    distribution : {"beckmann", "ggx"}, optional
    diffuse_reflectance, specular_reflectance, ior, nonlinear, two_sided :
        As for :class:`Plastic`.
    """

    alpha: float = 0.1
    distribution: MicrofacetDistribution = "beckmann"
    _kind: ClassVar[str] = "rough_plastic"

    def __post_init__(self) -> None:
        super().__post_init__()
        object.__setattr__(self, "alpha", _alpha(self.alpha, "RoughPlastic", "alpha"))
        object.__setattr__(self, "distribution", _distribution(self.distribution, "RoughPlastic"))

    def _core_bsdf(self) -> Any:
        return _core().Bsdf.rough_plastic(
            distribution=self.distribution,
            alpha=self.alpha,
            diffuse_reflectance=_constant(self.diffuse_reflectance),
            specular_reflectance=_constant(self.specular_reflectance),
            ior=self.ior,
            nonlinear=self.nonlinear,
            two_sided=self.two_sided,
        )

    def _one_sided_bsdf(self) -> dict[str, Any]:
        smooth = super()._one_sided_bsdf()
        return smooth | {
            "type": "roughplastic",
            "distribution": self.distribution,
            "alpha": float(self.alpha),
        }


def TwoSided(material: Material) -> Material:  # noqa: N802 - named as Mitsuba's plugin
    """``material`` reflecting on both sides, as Mitsuba 3's ``twosided`` around it.

    The reflectors (:class:`Conductor`, :class:`RoughConductor`, :class:`Plastic`,
    :class:`RoughPlastic`) come back with ``two_sided=True``; :class:`Diffuse` and
    :class:`Mirror` are two-sided already and come back unchanged.

    Raises
    ------
    ValueError
        For a material that transmits (a dielectric), as Mitsuba.
    """
    if "transmission" in material.flags:
        raise ValueError(
            f"twosided around a transmitting material ({type(material).__name__}) is not supported"
        )
    if isinstance(material, _Reflector):
        both = copy.copy(material)
        object.__setattr__(both, "two_sided", True)
        return both
    if isinstance(material, (Diffuse, Mirror)):
        return material
    raise TypeError(f"TwoSided takes a dualight material, got {type(material).__name__}")
