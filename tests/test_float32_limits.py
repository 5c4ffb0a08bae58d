"""What the float32 core can hold (issue 18, item 6): emission within [1e-12, 1e12] renders
exactly as the unscaled scene scaled, by every method, image and variance; beyond, add_mesh
refuses it naming the reason (it rendered black above 3.4e38, light tracing and BDPT gave 0
from 1.8e34, the variance was Inf from about 1e19 and 15 % off in denormals at 1.7e-18)."""

from __future__ import annotations

import numpy as np
import pytest

import dualight
from dualight import scenes

METHODS = ["path", "light", "bdpt", "pssmlt", "mmlt", "mlt"]
# The Cornell light's brightest and dimmest channels are 18.4 and 6.8: 2**35 and 2**-36 keep
# them inside [1e-12, 1e12], by powers of two, so scaled renders are equal bit for bit.
SCALES = [2.0**35, 2.0**-36]


def _render(method: str, light_scale: float) -> dualight.Image:
    scene = scenes.cornell_box(resolution=(16, 16), light_scale=light_scale)
    budget = {"spp": 8} if method in ("path", "light", "bdpt") else {"mutations_per_pixel": 8}
    depth = {"max_depth": 6} if method == "mmlt" else {}
    return dualight.render(scene, method, seed=7, progress=False, **budget, **depth)


def _scaled_equal(image: dualight.Image, base: dualight.Image, scale: float) -> bool:
    same = np.array_equal(np.asarray(image, np.float64) / scale, np.asarray(base, np.float64))
    if base.variance is not None:
        var = np.asarray(image.variance, np.float64) / scale**2
        same = same and np.array_equal(var, np.asarray(base.variance, np.float64))
    return same


@pytest.mark.parametrize("method", METHODS)
def test_emission_at_the_limits_renders_the_scaled_image_exactly(method: str) -> None:
    base = _render(method, 1.0)
    for scale in SCALES:
        assert _scaled_equal(_render(method, scale), base, scale), scale
    # Control: a light 1 % dimmer at the same scale is not the scaled image.
    assert not _scaled_equal(_render(method, SCALES[0] * 0.99), base, SCALES[0])


@pytest.mark.parametrize("scale", [2.0**36, 2.0**-45])
def test_emission_beyond_the_limits_is_refused_naming_the_reason(scale: float) -> None:
    with pytest.raises(ValueError, match=r"light: emission must be 0 or within \[1e-12, 1e12\]"):
        scenes.cornell_box(resolution=(16, 16), light_scale=scale)


def test_a_scene_too_small_for_float32_is_refused_when_rendered() -> None:
    scene = scenes.cornell_box(resolution=(16, 16))
    tiny = dualight.Scene(scene.camera)
    for mesh in scene.meshes:  # 5.6e-9 across (the path tracer wrong there, all three at 5.6e-10)
        tiny.add_mesh(
            mesh.vertices * 1e-11, mesh.triangles, material=mesh.material, emission=mesh.emission
        )
    with pytest.raises(ValueError, match=r"scene is 5\.59e-09 across: .* smaller than 1e-07"):
        dualight.render(tiny, spp=1, progress=False)


def test_coordinates_and_iors_at_the_limits_are_accepted() -> None:
    quad = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float64)
    dualight.Scene().add_mesh(quad * 1e12, [[0, 1, 2, 3]])
    dualight.Camera(origin=(0, 0, 1e12), target=(0, 0, -1e12))
    assert dualight.Dielectric(ior=1e18).ior == 1e18
    assert dualight.Dielectric(ior=1e-18).ior == 1e-18
