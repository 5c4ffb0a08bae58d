"""Emitters without a surface: point and spot lights (Mitsuba 3's ``point`` and ``spot``).

Area lights are meshes with ``emission`` (:meth:`dualight.Scene.add_mesh`); these are added
with :meth:`dualight.Scene.add_emitter`. Their positions are Dirac deltas: no path can hit
them, so the path tracer reaches them only by next-event estimation, the light tracer only
from their light subpaths, and BDPT only by the strategies that connect to them.

Examples
--------
>>> scene.add_emitter(dualight.PointLight(position=(0, 1.9, 0), intensity=(5, 5, 5)))
>>> scene.add_emitter(dualight.SpotLight((0, 1.9, 0), direction=(0, -1, 0), intensity=(20,) * 3,
...                                      cutoff_angle=30))
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

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


def _intensity(value: Any) -> Vec3:
    rgb = _vec3((value,) * 3 if isinstance(value, int | float) else value, "intensity")
    if min(rgb) < 0:
        raise ValueError(f"intensity must be >= 0, got {rgb}")
    return rgb


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
            "intensity": {"type": "rgb", "value": list(self.intensity)},
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
        d = _vec3(self.direction, "direction")
        if not any(d):
            raise ValueError("direction must be non-zero")
        object.__setattr__(self, "direction", d)
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
            "intensity": {"type": "rgb", "value": list(self.intensity)},
            "cutoff_angle": self.cutoff_angle,
            "beam_width": self.beam_width,
        }


Emitter = PointLight | SpotLight
