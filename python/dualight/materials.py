"""Surface materials: what :meth:`dualight.Scene.add_mesh` accepts as ``material=``.

* :class:`Diffuse` -- a two-sided Lambertian reflector (the default).
* :class:`Mirror` -- a two-sided ideal specular reflector.
* :class:`Dielectric` -- a smooth interface between air (IOR 1) and a material such as glass.

Each is a frozen dataclass, validated when it is made, and each matches one Mitsuba 3 BSDF so
that :func:`dualight.mitsuba.scene_dict` can export it exactly. ``Mirror`` and ``Dielectric``
scatter into single directions (Dirac deltas): the path tracer follows them by sampling, and
radiosity, which assumes diffuse surfaces, refuses scenes that contain them.

Directions and sides follow the mesh: a triangle's normal is the right-hand-rule normal
``(v1 - v0) x (v2 - v0)``; for a dielectric it points to the exterior (IOR 1), so a closed glass
object needs outward-facing triangles.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from numbers import Real
from typing import Any, TypeAlias

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


@dataclass(frozen=True)
class Diffuse:
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

    def __post_init__(self) -> None:
        object.__setattr__(self, "reflectance", _reflectance(self.reflectance, "Diffuse"))


@dataclass(frozen=True)
class Mirror:
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

    def __post_init__(self) -> None:
        object.__setattr__(self, "reflectance", _reflectance(self.reflectance, "Mirror"))


@dataclass(frozen=True)
class Dielectric:
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

    def __post_init__(self) -> None:
        ior = self.ior
        if isinstance(ior, bool) or not isinstance(ior, Real):
            raise TypeError(f"Dielectric ior must be a real number, got {type(ior).__name__}")
        ior = float(ior)
        if not (math.isfinite(ior) and ior > 0.0):
            raise ValueError(f"Dielectric ior must be finite and > 0, got {self.ior!r}")
        object.__setattr__(self, "ior", ior)


#: Any material :meth:`dualight.Scene.add_mesh` accepts.
Material: TypeAlias = Diffuse | Mirror | Dielectric


def _reflectance_of(material: Material) -> RGB:
    """The RGB reflectance a material stands for in ``Mesh.reflectance``.

    The albedo of a :class:`Diffuse`, the reflectance of a :class:`Mirror`, and ``(1, 1, 1)``
    for a :class:`Dielectric` (it absorbs nothing; Fresnel splits light between reflection and
    refraction).
    """
    if isinstance(material, Diffuse | Mirror):
        return material.reflectance
    if isinstance(material, Dielectric):
        return (1.0, 1.0, 1.0)
    raise TypeError(f"not a dualight material: {type(material).__name__}")
