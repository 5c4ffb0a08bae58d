"""Shading normals and the adjoint BSDF of importance transport [Veach 1997, sec. 5.3].

With shading normals the BSDF as a function on the geometric surface is not symmetric, so the
light tracer and BDPT's light subpaths need the adjoint correction to agree with the path
tracer. On a sphere the shading and geometric normals differ by a few degrees only, which
moves the image by less than a test of a few seconds resolves (tests/test_pathspace_vs_mitsuba.py
compares the smooth-sphere scene with Mitsuba); here a floor whose shading normals all lean
30 degrees makes the correction a large factor: without it (tried, by returning 1 from
``walk_weight_correction`` and using the camera-side direction in importance mode) the light
tracer misses the path tracer by far: 82 % of pixels and 28 % of 4x4 blocks passed (max |z|
32), BDPT 86 % and 58 % (max |z| 30), where the leaning control below still fails.
"""

from __future__ import annotations

import numpy as np
import pytest

import dualight
from dualight import metrics

LEAN = np.radians(30.0)


def _tilted_floor(lean: float = LEAN) -> dualight.Scene:
    """A white floor lit by a small square light above it; the floor's shading normals lean
    ``lean`` towards +x, the light and the camera see it from both sides of the lean."""
    camera = dualight.Camera(
        origin=(0.0, 1.2, -1.6), target=(0.0, 0.0, 0.0), fov=55.0, resolution=(32, 32)
    )
    scene = dualight.Scene(camera=camera)
    floor = np.array([[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]], dtype=np.float64)
    normals = np.tile([np.sin(lean), np.cos(lean), 0.0], (4, 1))
    scene.add_mesh(
        floor, [[0, 3, 2, 1]], reflectance=(0.8, 0.8, 0.8), normals=normals, name="floor"
    )
    light = np.array([[0.3, 1, -0.2], [0.7, 1, -0.2], [0.7, 1, 0.2], [0.3, 1, 0.2]])
    scene.add_mesh(light, [[0, 1, 2, 3]], reflectance=(0, 0, 0), emission=(8, 8, 8), name="light")
    return scene


def _render(scene: dualight.Scene, method: str, seed: int) -> dualight.Image:
    return dualight.render(scene, method, spp=256, max_depth=3, seed=seed, progress=False)


@pytest.mark.parametrize("method", ["light", "bdpt"])
def test_adjoint_estimators_match_the_path_tracer_on_leaning_shading_normals(method: str) -> None:
    scene = _tilted_floor()
    path = _render(scene, "path", seed=1)
    other = _render(scene, method, seed=2)
    args = (np.asarray(other), other.variance, np.asarray(path), path.variance)
    pixels, blocks = metrics.welch_test(*args), metrics.welch_test(*args, block=4)
    print(
        f"\n{method} vs path: pixels {pixels.pass_fraction:.4f} (max |z| {pixels.max_z:.3g}), "
        f"4x4 blocks {blocks.pass_fraction:.4f} (max |z| {blocks.max_z:.3g})"
    )
    assert pixels.pass_fraction >= 0.9975 and blocks.pass_fraction == 1.0
    # The control: the same floor shaded by normals leaning 25 degrees fails the same test.
    wrong = _render(_tilted_floor(np.radians(25.0)), method, seed=2)
    args = (np.asarray(wrong), wrong.variance, np.asarray(path), path.variance)
    pixels, blocks = metrics.welch_test(*args), metrics.welch_test(*args, block=4)
    print(
        f"lean 25 degrees: pixels {pixels.pass_fraction:.4f} (max |z| {pixels.max_z:.3g}), "
        f"4x4 blocks {blocks.pass_fraction:.4f}"
    )
    assert pixels.pass_fraction < 0.9975 or blocks.pass_fraction < 1.0
