"""Built-in scenes.

* :func:`cornell_box`: the Cornell box from the Cornell Program of Computer Graphics'
  measured data (geometry and camera in millimetres), with the RGB reflectances and light
  radiance that Mitsuba 3's ``cornell_box()`` uses for the measured spectra.
* :func:`furnace`: a closed cube with uniform reflectance and emission; every surface has the
  analytic radiance ``Le / (1 - rho)`` (:func:`furnace_radiance`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from dualight.scene import Camera, Scene

# Cornell box data, www.graphics.cornell.edu/online/box/data.html (quads, millimetres).
_CORNELL_QUADS: dict[str, list[list[tuple[float, float, float]]]] = {
    "floor": [[(552.8, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 559.2), (549.6, 0.0, 559.2)]],
    "ceiling": [
        [(556.0, 548.8, 0.0), (556.0, 548.8, 559.2), (0.0, 548.8, 559.2), (0.0, 548.8, 0.0)]
    ],
    "back_wall": [
        [(549.6, 0.0, 559.2), (0.0, 0.0, 559.2), (0.0, 548.8, 559.2), (556.0, 548.8, 559.2)]
    ],
    "green_wall": [[(0.0, 0.0, 559.2), (0.0, 0.0, 0.0), (0.0, 548.8, 0.0), (0.0, 548.8, 559.2)]],
    "red_wall": [
        [(552.8, 0.0, 0.0), (549.6, 0.0, 559.2), (556.0, 548.8, 559.2), (556.0, 548.8, 0.0)]
    ],
    "short_block": [
        [(130.0, 165.0, 65.0), (82.0, 165.0, 225.0), (240.0, 165.0, 272.0), (290.0, 165.0, 114.0)],
        [(290.0, 0.0, 114.0), (290.0, 165.0, 114.0), (240.0, 165.0, 272.0), (240.0, 0.0, 272.0)],
        [(130.0, 0.0, 65.0), (130.0, 165.0, 65.0), (290.0, 165.0, 114.0), (290.0, 0.0, 114.0)],
        [(82.0, 0.0, 225.0), (82.0, 165.0, 225.0), (130.0, 165.0, 65.0), (130.0, 0.0, 65.0)],
        [(240.0, 0.0, 272.0), (240.0, 165.0, 272.0), (82.0, 165.0, 225.0), (82.0, 0.0, 225.0)],
    ],
    "tall_block": [
        [
            (423.0, 330.0, 247.0),
            (265.0, 330.0, 296.0),
            (314.0, 330.0, 456.0),
            (472.0, 330.0, 406.0),
        ],
        [(423.0, 0.0, 247.0), (423.0, 330.0, 247.0), (472.0, 330.0, 406.0), (472.0, 0.0, 406.0)],
        [(472.0, 0.0, 406.0), (472.0, 330.0, 406.0), (314.0, 330.0, 456.0), (314.0, 0.0, 456.0)],
        [(314.0, 0.0, 456.0), (314.0, 330.0, 456.0), (265.0, 330.0, 296.0), (265.0, 0.0, 296.0)],
        [(265.0, 0.0, 296.0), (265.0, 330.0, 296.0), (423.0, 330.0, 247.0), (423.0, 0.0, 247.0)],
    ],
}
# The measured light lies in the ceiling's plane; it is lowered by 0.1 mm so the two never
# compete for the same hit (Mitsuba's and pbrt's versions of the scene do the same).
_CORNELL_LIGHT = [
    (343.0, 548.7, 227.0),
    (343.0, 548.7, 332.0),
    (213.0, 548.7, 332.0),
    (213.0, 548.7, 227.0),
]
_CORNELL_ROOM_CENTRE = np.array([278.0, 274.4, 279.6])

# Mitsuba 3's RGB values for the measured Cornell spectra.
CORNELL_WHITE = (0.885809, 0.698859, 0.666422)
CORNELL_RED = (0.570068, 0.0430135, 0.0443706)
CORNELL_GREEN = (0.105421, 0.37798, 0.076425)
CORNELL_LIGHT_RADIANCE = (18.387, 13.9873, 6.75357)
CORNELL_LIGHT_REFLECTANCE = (0.78, 0.78, 0.78)


def _orient(quad: np.ndarray, towards: np.ndarray, inward: bool) -> np.ndarray:
    """Reverse a quad's vertex order if its normal does not face (or face away from) a point."""
    n = np.cross(quad[1] - quad[0], quad[2] - quad[0])
    facing = float(np.dot(n, towards - quad.mean(axis=0))) > 0.0
    return quad if facing == inward else quad[::-1]


def _quads_mesh(quads: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    vertices = np.concatenate(quads)
    faces = np.arange(len(vertices)).reshape(-1, 4)
    return vertices, faces


def cornell_camera(resolution: tuple[int, int] = (128, 128)) -> Camera:
    """The measured Cornell camera: 35 mm focal length on a 25 mm film, looking along +z."""
    fov = math.degrees(2.0 * math.atan(0.5 * 0.025 / 0.035))
    return Camera(
        origin=(278.0, 273.0, -800.0),
        target=(278.0, 273.0, -799.0),
        up=(0.0, 1.0, 0.0),
        fov=fov,
        resolution=resolution,
    )


def cornell_box(
    resolution: tuple[int, int] = (128, 128),
    *,
    light_scale: float = 1.0,
    reflectance_scale: float = 1.0,
) -> Scene:
    """The Cornell box (measured geometry and camera; Mitsuba 3's RGB materials).

    ``light_scale`` and ``reflectance_scale`` multiply the light's radiance and every wall's
    and block's reflectance; tests use them as negative controls.
    """
    scene = Scene(camera=cornell_camera(resolution))
    materials = {
        "floor": CORNELL_WHITE,
        "ceiling": CORNELL_WHITE,
        "back_wall": CORNELL_WHITE,
        "green_wall": CORNELL_GREEN,
        "red_wall": CORNELL_RED,
        "short_block": CORNELL_WHITE,
        "tall_block": CORNELL_WHITE,
    }
    for name, rho in materials.items():
        quads = [np.array(q, dtype=np.float64) for q in _CORNELL_QUADS[name]]
        if name.endswith("block"):
            centre = np.mean(np.concatenate(quads), axis=0)
            quads = [_orient(q, centre, inward=False) for q in quads]
        else:
            quads = [_orient(q, _CORNELL_ROOM_CENTRE, inward=True) for q in quads]
        v, f = _quads_mesh(quads)
        scene.add_mesh(v, f, reflectance=tuple(reflectance_scale * c for c in rho), name=name)
    light = _orient(np.array(_CORNELL_LIGHT), _CORNELL_ROOM_CENTRE, inward=True)
    v, f = _quads_mesh([light])
    scene.add_mesh(
        v,
        f,
        reflectance=CORNELL_LIGHT_REFLECTANCE,
        emission=tuple(light_scale * c for c in CORNELL_LIGHT_RADIANCE),
        name="light",
    )
    return scene


def furnace_radiance(reflectance: float, emission: float) -> float:
    """Radiance everywhere inside :func:`furnace`: ``Le / (1 - rho)``."""
    if not 0.0 <= reflectance < 1.0:
        raise ValueError(f"furnace reflectance must be in [0, 1), got {reflectance}")
    return emission / (1.0 - reflectance)


def furnace(
    reflectance: float | Sequence[float] = 0.5,
    emission: float | Sequence[float] = 1.0,
    resolution: tuple[int, int] = (64, 64),
    *,
    size: float = 1.0,
) -> Scene:
    """A closed cube of side ``size`` whose inside walls all reflect and emit alike.

    Inside, radiance is the same everywhere and in every direction: ``Le / (1 - rho)`` per
    channel. The camera sits inside, looking at a corner so three walls are in view.
    """
    rho = np.broadcast_to(np.asarray(reflectance, dtype=np.float64), (3,))
    Le = np.broadcast_to(np.asarray(emission, dtype=np.float64), (3,))
    s = float(size)
    corners = s * np.array(
        [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]],
        dtype=np.float64,
    )
    faces = [[0, 1, 2, 3], [4, 7, 6, 5], [0, 4, 5, 1], [3, 2, 6, 7], [0, 3, 7, 4], [1, 5, 6, 2]]
    centre = np.full(3, 0.5 * s)
    quads = [_orient(corners[f], centre, inward=True) for f in faces]
    v, f = _quads_mesh(quads)
    camera = Camera(
        origin=(0.2 * s, 0.3 * s, 0.25 * s),
        target=(0.8 * s, 0.7 * s, 0.9 * s),
        up=(0.0, 1.0, 0.0),
        fov=70.0,
        resolution=resolution,
    )
    scene = Scene(camera=camera)
    scene.add_mesh(v, f, reflectance=tuple(rho), emission=tuple(Le), name="furnace")
    return scene
