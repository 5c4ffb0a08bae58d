"""The classic scenes of Veach's thesis (Veach 1997, "Robust Monte Carlo Methods for Light
Transport Simulation"), built for :mod:`dualight.scenes`: the multiple-importance-sampling
plates (fig. 9.2), the bidirectional room lit indirectly (ch. 10) and the glossy objects of
the door scene (ch. 11). The geometry is ours, to the figures' descriptions; the settings are
in each function's docstring."""

from __future__ import annotations

import math

import numpy as np

from dualight._shapes import _axis_rect, _box, _open_cylinder, _orient, _quads_mesh, icosphere
from dualight.materials import (
    Dielectric,
    RoughConductor,
    RoughDielectric,
    RoughPlastic,
    TwoSided,
)
from dualight.scene import Camera, Scene

# veach_mis ------------------------------------------------------------------------------------
#: The plates' GGX roughness, from the farthest (top of the image) to the nearest.
VEACH_MIS_ALPHAS = (0.005, 0.02, 0.05, 0.1)
#: The spherical lights' radii, left to right; each one's radiance is
#: ``VEACH_MIS_POWER / radius**2`` so that all four emit the same power.
VEACH_MIS_RADII = (0.03, 0.1, 0.3, 0.9)
VEACH_MIS_POWER = 0.8
_MIS_LIGHT_X = (-3.75, -1.25, 1.25, 3.75)
_MIS_LIGHT_Y, _MIS_LIGHT_Z = 3.5, -2.0
_MIS_CAMERA = (0.0, 3.5, 15.0)
#: Each plate's centre (y, z) and its length across (the plates are 8 wide along x).
_MIS_PLATES = ((-1.1, 0.0), (-1.6, 1.2), (-2.1, 2.4), (-2.6, 3.6))
_MIS_PLATE_LENGTH = 1.2
_MIS_FLOOR_Y = -3.2


def _plate(centre: np.ndarray, light: np.ndarray, eye: np.ndarray) -> np.ndarray:
    """A plate 8 wide along x at ``centre``, tilted about x so that it mirrors ``light`` (the
    lights' row) towards ``eye``: its normal is the half vector (in the y-z plane)."""
    to_eye = (eye - centre) / np.linalg.norm(eye - centre)
    to_light = (light - centre) / np.linalg.norm(light - centre)
    n = to_eye + to_light
    n[0] = 0.0
    n /= np.linalg.norm(n)
    across = np.cross(n, [1.0, 0.0, 0.0])  # in the y-z plane, along the plate's length
    h = 0.5 * _MIS_PLATE_LENGTH * across
    x = np.array([4.0, 0.0, 0.0])
    quad = np.array([centre - x - h, centre + x - h, centre + x + h, centre - x + h])
    return _orient(quad, centre + n, inward=True)


def veach_mis(
    resolution: tuple[int, int] = (128, 128),
    *,
    roughness_scale: float = 1.0,
    light_scale: float = 1.0,
) -> Scene:
    """Veach's multiple-importance-sampling plates (thesis fig. 9.2; Veach and Guibas 1995).

    Four rough metal plates, each tilted to mirror a row of four spherical lights towards the
    camera. The lights shrink from left to right while their radiance grows as ``1 / r**2``, so
    each emits the same power: the glossy highlight of a small light on a smooth plate is found
    well only by sampling the BSDF, that of a large light on a rough plate only by sampling the
    light, and MIS (``render(..., strategies="mis")``, the default) finds both.

    Layout (y up; the camera looks along -z)
        Camera at ``(0, 3.5, 15)`` looking at ``(0, -0.2, 1.5)``, ``fov`` 36 degrees along x.
        Lights: spheres (:func:`icosphere`, 3 subdivisions) of radii
        ``VEACH_MIS_RADII = (0.03, 0.1, 0.3, 0.9)`` at ``x = -3.75, -1.25, 1.25, 3.75``,
        ``y = 3.5``, ``z = -2``, radiance ``light_scale * 0.8 / r**2`` (white: 889, 80, 8.9,
        0.99), black otherwise. Plates: 8 x 1.2 rectangles centred at ``x = 0`` and
        ``(y, z) = (-1.1, 0), (-1.6, 1.2), (-2.1, 2.4), (-2.6, 3.6)``, each tilted about x to
        the half vector between the camera and the lights' row (``(0, 3.5, -2)``).
    Materials
        Plates: Mitsuba's ``roughconductor`` (GGX, aluminium ``material="Al"``, one-sided) of
        roughness ``alpha = roughness_scale * (0.005, 0.02, 0.05, 0.1)`` from the farthest
        plate (top of the image) to the nearest. A floor at ``y = -3.2`` (``[-12, 12] x
        [-8, 10]`` in x, z): diffuse 0.4.

    Meshes (names): ``plate0`` (farthest) to ``plate3``, ``light0`` (smallest) to ``light3``,
    ``floor``.

    Parameters
    ----------
    resolution : (int, int), optional
        Image ``(width, height)``.
    roughness_scale : float, optional
        Multiplies every plate's roughness (a negative control), in ``(0, 10]``.
    light_scale : float, optional
        Multiplies every light's radiance, ``> 0``.

    Returns
    -------
    Scene

    Raises
    ------
    ValueError
        If a scale is out of its range.
    """
    roughness_scale = _scale(roughness_scale, "veach_mis", "roughness_scale", 10.0)
    light_scale = _scale(light_scale, "veach_mis", "light_scale", 1e6)
    eye = np.array(_MIS_CAMERA)
    camera = Camera(
        origin=_MIS_CAMERA, target=(0.0, -0.2, 1.5), fov=36.0, resolution=tuple(resolution)
    )
    scene = Scene(camera=camera)
    row = np.array([0.0, _MIS_LIGHT_Y, _MIS_LIGHT_Z])
    for i, ((y, z), alpha) in enumerate(zip(_MIS_PLATES, VEACH_MIS_ALPHAS, strict=True)):
        v, f = _quads_mesh([_plate(np.array([0.0, y, z]), row, eye)])
        metal = RoughConductor(material="Al", alpha=alpha * roughness_scale, distribution="ggx")
        scene.add_mesh(v, f, material=metal, name=f"plate{i}")
    for j, (x, r) in enumerate(zip(_MIS_LIGHT_X, VEACH_MIS_RADII, strict=True)):
        v, f = icosphere((x, _MIS_LIGHT_Y, _MIS_LIGHT_Z), r, 3)
        le = light_scale * VEACH_MIS_POWER / r**2
        scene.add_mesh(v, f, reflectance=(0.0, 0.0, 0.0), emission=(le, le, le), name=f"light{j}")
    floor = _axis_rect(1, _MIS_FLOOR_Y, (-12.0, 0.0, -8.0), (12.0, 0.0, 10.0))
    v, f = _quads_mesh([_orient(floor, np.array([0.0, 0.0, 0.0]), inward=True)])
    scene.add_mesh(v, f, reflectance=(0.4, 0.4, 0.4), name="floor")
    return scene


def _scale(value: float, owner: str, name: str, upper: float) -> float:
    """``value`` as a float in ``(0, upper]``, or a ValueError naming it."""
    x = float(value)
    if not (math.isfinite(x) and 0.0 < x <= upper):
        raise ValueError(f"{owner}: {name} must be in (0, {upper:g}], got {value!r}")
    return x


def _ior(value: float, owner: str) -> float:
    """``value`` as a relative IOR in ``(1, 4]``, or a ValueError naming it."""
    x = float(value)
    if not (math.isfinite(x) and 1.0 < x <= 4.0):
        raise ValueError(f"{owner}: ior must be in (1, 4], got {value!r}")
    return x


# veach_bidir ----------------------------------------------------------------------------------
VEACH_BIDIR_ROOM = (4.0, 2.6, 4.0)
VEACH_BIDIR_LIGHT_RADIANCE = (900.0, 800.0, 620.0)
_BIDIR_MATERIALS = {
    "walls": (0.75, 0.72, 0.66),
    "floor": (0.50, 0.42, 0.34),
    "ceiling": (0.80, 0.80, 0.80),
    "table": (0.55, 0.36, 0.20),
}
_BIDIR_TABLE_TOP = ((1.1, 0.70, 2.2), (2.9, 0.75, 3.3))
_BIDIR_TABLE_FOOT = ((1.9, 0.0, 2.65), (2.1, 0.70, 2.85))
_BIDIR_EGG = ((1.75, 0.97, 2.7), (0.16, 0.22, 0.16))
_BIDIR_LAMP = (3.25, 3.35)  # the lamp's axis (x, z)
_BIDIR_SHADE = (1.5, 0.35, (0.16, 0.30))  # bottom height, height, radii (bottom, top)
_BIDIR_BULB = (1.58, 0.06)  # height, half size


def veach_bidir(
    resolution: tuple[int, int] = (128, 128),
    *,
    light_scale: float = 1.0,
    ior: float = 1.5,
) -> Scene:
    """Veach's bidirectional scene (thesis ch. 10; Veach and Guibas 1995): a room lit only
    indirectly, by a lamp whose light first hits the ceiling or its glossy shade, with a glass
    egg on a table.

    No surface the camera sees is lit directly, and the egg's caustic on the table is lit by the
    ceiling's reflection: a path tracer connects to the hidden bulb only from the ceiling and
    the shade, while BDPT's light subpaths start there.

    Layout (metres; y up; the camera looks along +z)
        Room: the box ``[0, 4] x [0, 2.6] x [0, 4]`` of one-sided quads facing in. Camera at
        ``(1.2, 1.25, 0.25)`` looking at ``(2.1, 0.95, 3.5)``, ``fov`` 62 degrees along x.
        Table: a top ``[1.1, 2.9] x [0.70, 0.75] x [2.2, 3.3]`` on a foot ``[1.9, 2.1] x
        [0, 0.7] x [2.65, 2.85]``. Egg: an :func:`icosphere` (3 subdivisions) scaled to
        semi-axes ``(0.16, 0.22, 0.16)``, centred at ``(1.75, 0.97, 2.7)`` (resting on the
        table). Lamp on the axis ``x = 3.25, z = 3.35``: a stand ``0.04`` square from the floor
        to the shade, a shade (an open frustum of 16 quads, radius 0.16 at ``y = 1.5`` widening
        to 0.30 at ``y = 1.85``) and a bulb, a ``0.12 x 0.12`` square at ``y = 1.58`` facing up
        (+y), radiance ``light_scale * (900, 800, 620)``. The camera is below the bulb, so it
        sees its unlit back.
    Materials
        Walls (0.75, 0.72, 0.66), floor (0.50, 0.42, 0.34), ceiling 0.8, table and foot
        (0.55, 0.36, 0.20), stand 0.3, bulb 0: two-sided diffuse. Shade: two-sided
        ``roughconductor`` (gold, ``material="Au"``, GGX ``alpha = 0.2``). Egg: ``dielectric``
        of relative IOR ``ior``.

    Meshes (names): ``floor``, ``ceiling``, ``walls``, ``table``, ``egg``, ``stand``,
    ``shade``, ``bulb``.

    Parameters
    ----------
    resolution : (int, int), optional
        Image ``(width, height)``.
    light_scale : float, optional
        Multiplies the bulb's radiance, ``> 0``.
    ior : float, optional
        The egg's relative index of refraction, in ``(1, 4]``.

    Returns
    -------
    Scene
    """
    light_scale = _scale(light_scale, "veach_bidir", "light_scale", 1e6)
    ior = _ior(ior, "veach_bidir")
    camera = Camera(
        origin=(1.2, 1.25, 0.25), target=(2.1, 0.95, 3.5), fov=62.0, resolution=tuple(resolution)
    )
    scene = Scene(camera=camera)
    _bidir_room(scene)
    (v0, f0), (v1, f1) = _box(*_BIDIR_TABLE_TOP), _box(*_BIDIR_TABLE_FOOT)
    v, f = np.concatenate([v0, v1]), np.concatenate([f0, f1 + len(v0)])
    scene.add_mesh(v, f, reflectance=_BIDIR_MATERIALS["table"], name="table")
    centre, axes = _BIDIR_EGG
    v, f = icosphere((0.0, 0.0, 0.0), 1.0, 3)
    scene.add_mesh(np.asarray(centre) + v * np.asarray(axes), f, material=Dielectric(ior=ior),
                   name="egg")  # fmt: skip
    _bidir_lamp(scene, light_scale)
    return scene


def _bidir_room(scene: Scene) -> None:
    """The room's floor, ceiling and walls, facing in."""
    lo, hi = np.zeros(3), np.asarray(VEACH_BIDIR_ROOM)
    centre = 0.5 * (lo + hi)
    parts = {
        "floor": [_axis_rect(1, 0.0, lo, hi)],
        "ceiling": [_axis_rect(1, hi[1], lo, hi)],
        "walls": [_axis_rect(a, x, lo, hi) for a in (0, 2) for x in (lo[a], hi[a])],
    }
    for name, quads in parts.items():
        v, f = _quads_mesh([_orient(q, centre, inward=True) for q in quads])
        scene.add_mesh(v, f, reflectance=_BIDIR_MATERIALS[name], name=name)


def _bidir_lamp(scene: Scene, light_scale: float) -> None:
    """The lamp: stand, glossy shade and the bulb facing up."""
    x, z = _BIDIR_LAMP
    bottom, height, radii = _BIDIR_SHADE
    v, f = _box((x - 0.02, 0.0, z - 0.02), (x + 0.02, bottom, z + 0.02))
    scene.add_mesh(v, f, reflectance=(0.3, 0.3, 0.3), name="stand")
    v, f = _open_cylinder((x, bottom, z), radii, height, 16)
    shade = TwoSided(RoughConductor(material="Au", alpha=0.2, distribution="ggx"))
    scene.add_mesh(v, f, material=shade, name="shade")
    y, s = _BIDIR_BULB
    bulb = _axis_rect(1, y, (x - s, 0.0, z - s), (x + s, 0.0, z + s))
    v, f = _quads_mesh([_orient(bulb, np.array([x, y + 1.0, z]), inward=True)])
    le = tuple(light_scale * c for c in VEACH_BIDIR_LIGHT_RADIANCE)
    scene.add_mesh(v, f, reflectance=(0.0, 0.0, 0.0), emission=le, name="bulb")


# door_ajar(variant="glossy") ------------------------------------------------------------------
#: The glossy door's objects on the dark room's floor: a rough copper sphere, a frosted glass
#: sphere and a rough-plastic block (centres, radii or corners in metres).
DOOR_GLOSSY_ALPHA = 0.1


def door_glossy_objects(scene: Scene, roughness_scale: float, ior: float) -> None:
    """Add the glossy door's objects (see :func:`dualight.scenes.door_ajar`) to ``scene``."""
    a = DOOR_GLOSSY_ALPHA * roughness_scale
    v, f = icosphere((1.15, 0.35, 3.2), 0.35, 4)
    metal = RoughConductor(material="Cu", alpha=a, distribution="ggx")
    scene.add_mesh(v, f, material=metal, name="copper_sphere")
    v, f = icosphere((2.55, 0.3, 3.05), 0.3, 4)
    glass = RoughDielectric(alpha=a, ior=ior, distribution="ggx")
    scene.add_mesh(v, f, material=glass, name="frosted_sphere")
    v, f = _box((2.95, 0.0, 2.2), (3.55, 0.45, 2.8))
    plastic = RoughPlastic(
        diffuse_reflectance=(0.2, 0.25, 0.5), alpha=a, distribution="ggx", ior=1.5
    )
    scene.add_mesh(v, f, material=plastic, name="plastic_block")
