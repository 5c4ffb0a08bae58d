"""Surface materials: what :meth:`dualight.Scene.add_mesh` accepts as ``material=``.

* :class:`Diffuse` -- a two-sided Lambertian reflector (the default).
* :class:`Mirror` -- a two-sided ideal specular reflector.
* :class:`Dielectric` -- a smooth interface between air (IOR 1) and a material such as glass.

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

import functools
import math
from dataclasses import dataclass
from numbers import Real
from typing import Any, ClassVar

import numpy as np

__all__ = ["Dielectric", "Diffuse", "Material", "Mirror"]

RGB = tuple[float, float, float]


def _reflectance(value: Any, owner: str) -> RGB:
    """``value`` as 3 floats, each finite and in ``[0, 1]``, or a ValueError naming ``owner``."""
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


@functools.cache
def _core_bsdf_of_kind(kind: str) -> Any:
    """A core BSDF of a kind, for what depends on the kind alone (its flags)."""
    from dualight import _core

    return _core.Bsdf(getattr(_core.BsdfKind, kind))


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
        return frozenset(_core_bsdf_of_kind(self._kind).flags)

    @property
    def is_diffuse_reflector(self) -> bool:
        """Only diffuse reflection: what radiosity can solve (the core's own test of its flags)."""
        return bool(_core_bsdf_of_kind(self._kind).is_diffuse_reflector)

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

    reflectance: RGB = (0.5, 0.5, 0.5)
    _kind: ClassVar[str] = "lambertian"

    def __post_init__(self) -> None:
        object.__setattr__(self, "reflectance", _reflectance(self.reflectance, "Diffuse"))

    def _core_parameters(self) -> tuple[RGB, float]:
        return self.reflectance, 1.0


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

    reflectance: RGB = (1.0, 1.0, 1.0)
    _kind: ClassVar[str] = "mirror"

    def __post_init__(self) -> None:
        object.__setattr__(self, "reflectance", _reflectance(self.reflectance, "Mirror"))

    def _core_parameters(self) -> tuple[RGB, float]:
        return self.reflectance, 1.0


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
