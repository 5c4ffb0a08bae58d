"""Veach's classic scenes (dualight.scenes.veach_mis, veach_bidir, door_ajar(variant="glossy"))
and the sampling-strategy switch of the path tracer and BDPT (render(strategies=...)). Their
comparisons with the Mitsuba references are in test_pathspace_vs_mitsuba.py (path tracer,
BDPT) and test_pssmlt.py (the Metropolis methods)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import dualight
from dualight import metrics, scenes
from dualight._veach_scenes import VEACH_MIS_RADII
from dualight.bench import REFERENCE_DIR as REFERENCES


def _mesh(scene: dualight.Scene, name: str):
    (mesh,) = [m for m in scene.meshes if m.name == name]
    return mesh


def test_veach_mis_lights_emit_the_same_power_and_plates_grow_rougher() -> None:
    scene = scenes.veach_mis((32, 32))
    powers = []
    for j, r in enumerate(VEACH_MIS_RADII):
        light = _mesh(scene, f"light{j}")
        le = light.emission[0]
        assert le == pytest.approx(0.8 / r**2, rel=1e-6)
        powers.append(math.pi * le * light.areas.sum())
    # The icosphere's area deficit is the same at every radius.
    assert max(powers) / min(powers) == pytest.approx(1.0, abs=1e-6)
    alphas = [_mesh(scene, f"plate{i}").material.alpha for i in range(4)]
    assert alphas == sorted(alphas) and alphas[0] == 0.005
    rougher = scenes.veach_mis((32, 32), roughness_scale=2.0)
    assert _mesh(rougher, "plate3").material.alpha == pytest.approx(0.2)


def test_veach_mis_plates_mirror_the_lights_to_the_camera() -> None:
    """Each plate's normal is the half vector between the camera and the lights' row: the
    mirror direction of a camera ray at the plate's centre meets the row's centre."""
    scene = scenes.veach_mis((32, 32))
    eye = np.asarray(scene.camera.origin)
    for i in range(4):
        plate = _mesh(scene, f"plate{i}")
        v = np.asarray(plate.vertices)
        c = v.mean(axis=0)
        n = np.cross(v[1] - v[0], v[2] - v[0])
        n /= np.linalg.norm(n)
        d = (c - eye) / np.linalg.norm(c - eye)
        r = d - 2.0 * np.dot(d, n) * n
        to_row = np.array([0.0, 3.5, -2.0]) - c
        assert np.dot(r, to_row / np.linalg.norm(to_row)) == pytest.approx(1.0, abs=1e-9)


def test_veach_bidir_bulb_is_hidden_and_the_room_lit_indirectly() -> None:
    scene = scenes.veach_bidir((32, 32))
    bulb = _mesh(scene, "bulb")
    v = np.asarray(bulb.vertices)
    n = np.cross(v[1] - v[0], v[2] - v[0])
    assert n[1] > 0  # it faces up
    assert scene.camera.origin[1] < v[:, 1].min()  # the camera is below it: sees its back
    assert scene.emitters_facing(scene.camera.origin) == 0
    # No emitter is seen directly (paths of one segment).
    image = dualight.render(scene, "path", spp=16, max_depth=1, progress=False)
    assert float(np.asarray(image).max()) == 0.0


def test_door_glossy_adds_its_objects_and_keeps_the_classic_door() -> None:
    classic = scenes.door_ajar((32, 32))
    glossy = scenes.door_ajar((32, 32), variant="glossy")
    names = {m.name for m in glossy.meshes} - {m.name for m in classic.meshes}
    assert names == {"copper_sphere", "frosted_sphere", "plastic_block"}
    for m in classic.meshes:
        g = _mesh(glossy, m.name)
        assert np.array_equal(np.asarray(m.vertices), np.asarray(g.vertices))
    rough = scenes.door_ajar((32, 32), variant="glossy", roughness_scale=1.5)
    assert _mesh(rough, "copper_sphere").material.alpha == pytest.approx(0.15)


@pytest.mark.parametrize(
    ("build", "kwargs", "match"),
    [
        (scenes.veach_mis, {"roughness_scale": 0.0}, "roughness_scale"),
        (scenes.veach_mis, {"light_scale": float("nan")}, "light_scale"),
        (scenes.veach_bidir, {"ior": 1.0}, "ior"),
        (scenes.veach_bidir, {"light_scale": -1.0}, "light_scale"),
        (scenes.door_ajar, {"variant": "shiny"}, "variant"),
        (scenes.door_ajar, {"variant": "glossy", "roughness_scale": 11.0}, "roughness_scale"),
        (scenes.door_ajar, {"variant": "glossy", "ior": 0.5}, "ior"),
    ],
)
def test_bad_arguments(build, kwargs: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        build((16, 16), **kwargs)


# The sampling-strategy switch --------------------------------------------------------------
def test_strategies_checked_and_only_for_path_and_bdpt() -> None:
    scene = scenes.cornell_box((8, 8))
    with pytest.raises(ValueError, match="strategies"):
        dualight.render(scene, "path", spp=1, strategies="nee", progress=False)  # type: ignore[arg-type]
    for method in ("light", "mlt", "pssmlt"):
        with pytest.raises(ValueError, match="strategies applies to method 'path', 'bdpt' only"):
            dualight.render(scene, method, spp=1, strategies="bsdf", progress=False)
    image = dualight.render(scene, "bdpt", spp=1, strategies="light", progress=False)
    assert image.stats["strategies"] == "light"
    image = dualight.render(scene, "path", spp=1, strategies="bsdf", progress=False)
    assert "light_samples" in image.stats["skipped"]


@pytest.mark.parametrize("method", ["path", "bdpt"])
def test_one_strategy_alone_where_only_light_sampling_can_find_the_light(method: str) -> None:
    """Under a sun (a delta direction) no path hits the light. BSDF sampling alone must hand
    those paths to light sampling with weight 1: the path tracer's three images are the same
    bits. BDPT's s = 0 cannot sample them either, so "bsdf" and "light" both keep s = 1 (the
    same bits), while MIS also weighs in s >= 2 and t = 1 (another image, the same mean)."""
    scene = scenes.cornell_box((16, 16), variant="sun")
    images = {
        s: np.asarray(dualight.render(scene, method, spp=8, strategies=s, progress=False))
        for s in ("mis", "bsdf", "light")
    }
    assert images["mis"].max() > 0
    assert np.array_equal(images["bsdf"], images["light"])
    assert np.array_equal(images["mis"], images["bsdf"]) == (method == "path")


def test_mis_beats_each_strategy_alone_on_veach_mis() -> None:
    """Veach's figure 9.2 in numbers: at the same samples per pixel MIS has the lowest relMSE
    against Mitsuba (the equal-time study is benchmarks/bench_scenes.py)."""
    ref = np.asarray(dualight.Image.load(REFERENCES / "veach_mis_64_mean.exr"))
    scene = scenes.veach_mis((64, 64))
    err = {}
    for s in ("mis", "bsdf", "light"):
        image = dualight.render(
            scene, "path", spp=64, max_depth=8, seed=5, strategies=s, progress=False
        )
        err[s] = metrics.relmse(np.asarray(image), ref)
    print(f"\nveach_mis path, 64 spp, relMSE: {err}")
    assert err["mis"] < err["bsdf"] and err["mis"] < err["light"]
