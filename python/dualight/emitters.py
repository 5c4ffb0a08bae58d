"""Emitters without a surface: point and spot lights (Mitsuba 3's ``point`` and ``spot``),
directional lights (``directional``) and environments at infinity (``constant``, ``envmap``).

Area lights are meshes with ``emission`` (:meth:`dualight.Scene.add_mesh`); these are added
with :meth:`dualight.Scene.add_emitter`. Point and spot positions and the directional light's
direction are Dirac deltas: no path can hit them, so the path tracer reaches them only by
next-event estimation, the light tracer only from their light subpaths, and BDPT only by the
strategies that connect to them. Rays that leave the scene see the environments.

Emitters at infinity render with every estimator: light subpaths start at a direction at
infinity and enter the scene from a disk of the scene's bounding-sphere radius facing it;
BDPT's camera subpaths end at the environment's vertex at infinity, which path-space MLT's
mutations reach from the light side. Radiosity's
uniform solvers take them all as a first shot (the irradiance each patch receives directly).
A scene takes one environment, as in Mitsuba 3.

Examples
--------
>>> scene.add_emitter(dualight.PointLight(position=(0, 1.9, 0), intensity=(5, 5, 5)))
>>> scene.add_emitter(dualight.SpotLight((0, 1.9, 0), direction=(0, -1, 0), intensity=(20,) * 3,
...                                      cutoff_angle=30))
>>> scene.add_emitter(dualight.DirectionalLight(direction=(0, -1, -1), irradiance=3))
>>> scene.add_emitter(dualight.EnvironmentMap("sky.exr", scale=0.5))
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from dualight import _core

Vec3 = tuple[float, float, float]


def _vec3(value: Any, name: str) -> Vec3:
    try:
        out = tuple(float(x) for x in value)
    except TypeError:
        raise TypeError(f"{name} must be 3 numbers, got {value!r}") from None
    if len(out) != 3:
        raise ValueError(f"{name} must be 3 numbers, got {len(out)}")
    if not all(math.isfinite(x) and abs(x) <= 1e30 for x in out):
        raise ValueError(f"{name} must be finite (|x| <= 1e30), got {out}")
    return out  # type: ignore[return-value]


def _intensity(value: Any, name: str = "intensity") -> Vec3:
    rgb = _vec3((value,) * 3 if isinstance(value, int | float) else value, name)
    if min(rgb) < 0:
        raise ValueError(f"{name} must be >= 0, got {rgb}")
    return rgb


def _direction(value: Any) -> Vec3:
    d = _vec3(value, "direction")
    if not any(d):
        raise ValueError("direction must be non-zero")
    return d


def _rgb_spectrum(rgb: Vec3) -> dict[str, Any]:
    return {"type": "rgb", "value": list(rgb)}


@dataclass(frozen=True)
class PointLight:
    """Isotropic point light (Mitsuba 3's ``point``): ``intensity`` in W/sr per RGB channel
    (a number stands for grey), at ``position``. Irradiance at distance r: intensity / r^2."""

    position: Vec3
    intensity: Vec3 = (1.0, 1.0, 1.0)

    def __post_init__(self) -> None:
        object.__setattr__(self, "position", _vec3(self.position, "position"))
        object.__setattr__(self, "intensity", _intensity(self.intensity))

    def _core_emitter(self) -> _core.Emitter:
        return _core.Emitter.point(self.position, self.intensity)

    def _mitsuba(self) -> dict[str, Any]:
        return {
            "type": "point",
            "position": list(self.position),
            "intensity": _rgb_spectrum(self.intensity),
        }


@dataclass(frozen=True)
class SpotLight:
    """Spot light (Mitsuba 3's ``spot``) at ``position`` shining along ``direction``:
    ``intensity`` (W/sr) on its axis, constant out to ``beam_width`` degrees from the axis,
    falling linearly in angle to zero at ``cutoff_angle`` (default 20; ``beam_width`` defaults
    to three quarters of it, as Mitsuba)."""

    position: Vec3
    direction: Vec3 = (0.0, 0.0, 1.0)
    intensity: Vec3 = (1.0, 1.0, 1.0)
    cutoff_angle: float = 20.0
    beam_width: float | None = field(default=None)

    def __post_init__(self) -> None:
        object.__setattr__(self, "position", _vec3(self.position, "position"))
        object.__setattr__(self, "direction", _direction(self.direction))
        object.__setattr__(self, "intensity", _intensity(self.intensity))
        cutoff = float(self.cutoff_angle)
        if not 0 < cutoff <= 180:
            raise ValueError(f"cutoff_angle must lie in (0, 180] degrees, got {self.cutoff_angle}")
        beam = 0.75 * cutoff if self.beam_width is None else float(self.beam_width)
        if not 0 <= beam <= cutoff:
            raise ValueError(
                f"beam_width must lie in [0, cutoff_angle = {cutoff}] degrees, got {beam}"
            )
        object.__setattr__(self, "cutoff_angle", cutoff)
        object.__setattr__(self, "beam_width", beam)

    def _core_emitter(self) -> _core.Emitter:
        return _core.Emitter.spot(
            self.position, self.direction, self.intensity, self.cutoff_angle, self.beam_width
        )

    def _look_at(self) -> tuple[Vec3, Vec3, Vec3]:
        """(origin, target, up) of a ``lookat`` that puts +z along the direction."""
        p, d = self.position, self.direction
        up = (0.0, 1.0, 0.0) if abs(d[1]) < 0.9 * math.sqrt(sum(x * x for x in d)) else (1.0, 0, 0)
        return p, (p[0] + d[0], p[1] + d[1], p[2] + d[2]), up  # type: ignore[return-value]

    def _mitsuba(self) -> dict[str, Any]:
        import mitsuba as mi

        origin, target, up = self._look_at()
        return {
            "type": "spot",
            "to_world": mi.ScalarTransform4f().look_at(
                origin=list(origin), target=list(target), up=list(up)
            ),
            "intensity": _rgb_spectrum(self.intensity),
            "cutoff_angle": self.cutoff_angle,
            "beam_width": self.beam_width,
        }


@dataclass(frozen=True)
class DirectionalLight:
    """Directional light (Mitsuba 3's ``directional``), the sun's idealisation: ``irradiance``
    (W/m^2 per RGB channel, on a plane facing it; a number stands for grey) arriving along
    ``direction`` (the direction the light travels in) from infinitely far away."""

    direction: Vec3 = (0.0, 0.0, 1.0)
    irradiance: Vec3 = (1.0, 1.0, 1.0)

    def __post_init__(self) -> None:
        object.__setattr__(self, "direction", _direction(self.direction))
        object.__setattr__(self, "irradiance", _intensity(self.irradiance, "irradiance"))

    def _core_emitter(self) -> _core.Emitter:
        return _core.Emitter.directional(self.direction, self.irradiance)

    def _mitsuba(self) -> dict[str, Any]:
        return {
            "type": "directional",
            "direction": list(self.direction),
            "irradiance": _rgb_spectrum(self.irradiance),
        }


@dataclass(frozen=True)
class ConstantEnvironment:
    """Constant environment (Mitsuba 3's ``constant``): ``radiance`` per RGB channel arriving
    from every direction at infinity (a number stands for grey)."""

    radiance: Vec3 = (1.0, 1.0, 1.0)

    def __post_init__(self) -> None:
        object.__setattr__(self, "radiance", _intensity(self.radiance, "radiance"))

    def _core_emitter(self) -> _core.Emitter:
        return _core.Emitter.constant(self.radiance)

    def _mitsuba(self) -> dict[str, Any]:
        return {"type": "constant", "radiance": _rgb_spectrum(self.radiance)}


def _rotation(value: Any) -> np.ndarray:
    """A 3x3 rotation from None (identity), a 3x3 matrix or a 4x4 transform without translation
    use (its upper-left 3x3 must be a rotation)."""
    if value is None:
        return np.eye(3)
    m = np.asarray(getattr(value, "matrix", value), dtype=np.float64)
    if m.shape == (4, 4):
        m = m[:3, :3]
    if m.shape != (3, 3) or not np.all(np.isfinite(m)):
        raise ValueError(f"to_world must be a finite 3x3 or 4x4 matrix, got shape {m.shape}")
    if not np.allclose(m @ m.T, np.eye(3), atol=1e-5) or np.linalg.det(m) <= 0:
        raise ValueError("to_world must be a rotation (orthonormal, determinant 1): an environment "
                         "map's directions cannot be scaled, sheared or mirrored")
    return m


@dataclass(frozen=True, eq=False)
class EnvironmentMap:
    """Image-based environment (Mitsuba 3's ``envmap``): radiance at infinity from a
    latitude-longitude image in Mitsuba's conventions (in the map's frame y is up: the top row
    is +y, the bottom row -y; u = atan2(x, -z) / 2 pi, so the left edge faces -z, a quarter
    across +x, the centre column +z), times ``scale``, turned by ``to_world`` (a rotation: 3x3,
    or 4x4 whose upper-left 3x3 is one).

    Give ``filename`` (an image OpenImageIO reads; EXR or HDR for real light probes; 8-bit files
    are sRGB-decoded) or ``data`` (``(height, width[, 1 or 3])`` linear floats). Next-event
    estimation samples it in proportion to its luminance.

    Raises
    ------
    FileNotFoundError
        If ``filename`` does not exist.
    ValueError
        If the image cannot be read, is negative, non-finite or black, or ``to_world`` is not a
        rotation.
    """

    filename: str | os.PathLike[str] | None = None
    data: Any = field(default=None, repr=False)
    scale: float = 1.0
    to_world: Any = field(default=None, repr=False)
    texels: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        from dualight.textures import Bitmap

        if (self.filename is None) == (self.data is None):
            raise ValueError("EnvironmentMap: give either filename or data")
        scale = float(self.scale)
        if not (math.isfinite(scale) and 0 <= scale <= 1e30):
            raise ValueError(f"EnvironmentMap scale must be finite and >= 0, got {self.scale}")
        object.__setattr__(self, "scale", scale)
        object.__setattr__(self, "to_world", _rotation(self.to_world))
        bitmap = Bitmap(filename=self.filename, data=self.data)
        texels = np.asarray(bitmap.texels, dtype=np.float32)
        if texels.shape[2] == 1:
            texels = np.repeat(texels, 3, axis=2)
        if texels.min() < 0:
            raise ValueError("EnvironmentMap: radiance must be >= 0")
        if not texels.any():
            raise ValueError("EnvironmentMap: the image is black (no positive pixel)")
        if bitmap.filename is not None:
            object.__setattr__(self, "filename", bitmap.filename)
        texels.flags.writeable = False
        object.__setattr__(self, "texels", texels)

    def _core_emitter(self) -> _core.Emitter:
        return _core.Emitter.envmap(self.texels, self.scale, self.to_world.ravel().tolist())

    def _mitsuba(self) -> dict[str, Any]:
        import mitsuba as mi

        m = np.eye(4)
        m[:3, :3] = self.to_world
        return {
            "type": "envmap",
            "bitmap": mi.Bitmap(np.array(self.texels, dtype=np.float32, order="C")),
            "scale": self.scale,
            "to_world": mi.ScalarTransform4f(m.tolist()),
        }


Emitter = PointLight | SpotLight | DirectionalLight | ConstantEnvironment | EnvironmentMap
EMITTER_TYPES = (PointLight, SpotLight, DirectionalLight, ConstantEnvironment, EnvironmentMap)
#: What rays leaving the scene see; a scene takes one, as in Mitsuba 3.
ENVIRONMENTS = (ConstantEnvironment, EnvironmentMap)
