"""The light tracer and BDPT against the stored Mitsuba 3 references (tests/references):
per-pixel and per-block Welch tests with both images' variances, and Delta E 2000, each with a
negative control that must fail the same comparison. (The path tracer's own rows are in
test_path_vs_mitsuba.py.)

The light tracer cannot render light that reaches the camera by a specular bounce (a mirror or
glass seen directly): those pixels are masked out of its comparisons (see
``renderable_by_light_tracing``), and nowhere else.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

import dualight
from dualight import metrics, scenes

REFERENCES = Path(__file__).parent / "references"


@dataclass(frozen=True)
class Case:
    reference: str
    build: Callable[..., dualight.Scene]  # keyword arguments: the negative control's change
    wrong: dict
    spp: dict[str, int]  # per method: enough for the negative control to fail


CASES = {
    "cornell": Case(
        "cornell_64",
        lambda **kw: scenes.cornell_box(resolution=(64, 64), **kw),
        {"light_scale": 0.97},
        {"light": 1024, "bdpt": 512},
    ),
}


def _reference(name: str) -> tuple[np.ndarray, np.ndarray, dict]:
    mean = dualight.Image.load(REFERENCES / f"{name}_mean.exr")
    var = dualight.Image.load(REFERENCES / f"{name}_var.exr")
    return np.asarray(mean), np.asarray(var), mean.stats


def renderable_by_light_tracing(scene: dualight.Scene, subsamples: int = 4) -> np.ndarray:
    """Pixels whose every camera ray (on a subsamples^2 grid) first hits a non-specular
    surface, or nothing: the only pixels a light tracer can render completely."""
    cam = scene.camera
    assert cam is not None
    ray_cam = cam._compile()
    offsets = (np.arange(subsamples) + 0.5) / subsamples
    origins, directions, pixel = [], [], []
    for y in range(cam.height):
        for x in range(cam.width):
            for oy in offsets:
                for ox in offsets:
                    o, d = ray_cam.generate_ray(x + ox, y + oy)
                    origins.append(o)
                    directions.append(d)
                    pixel.append(y * cam.width + x)
    _, prim = scene._compile().intersect(np.array(origins), np.array(directions))
    _, _, mesh_of = scene.triangle_arrays()
    specular = np.array([not isinstance(m.material, dualight.Diffuse) for m in scene.meshes])
    hits_specular = np.zeros(len(prim), dtype=bool)
    hit = prim >= 0
    hits_specular[hit] = specular[mesh_of[prim[hit]]]
    bad = np.zeros(cam.width * cam.height, dtype=bool)
    np.logical_or.at(bad, np.array(pixel), hits_specular)
    return ~bad.reshape(cam.height, cam.width)


def _compare(case: Case, method: str, seed: int, **wrong) -> metrics.Comparison:
    ref, ref_var, info = _reference(case.reference)
    scene = case.build(**wrong)
    image = dualight.render(
        scene,
        method,
        spp=case.spp[method],
        max_depth=info["max_depth"],
        rr_depth=info["rr_depth"],
        seed=seed,
        progress=False,
    )
    mask = renderable_by_light_tracing(scene) if method == "light" else None
    return metrics.compare(image, image.variance, ref, ref_var, mask=mask)


@pytest.mark.parametrize("method", ["light", "bdpt"])
@pytest.mark.parametrize("name", sorted(CASES))
def test_matches_mitsuba_and_the_negative_control_fails(name: str, method: str) -> None:
    case = CASES[name]
    result = _compare(case, method, seed=21)
    print(f"\n{name} {method} vs Mitsuba: {result}")
    assert result.pixel.pass_fraction >= 0.9975, result
    assert result.blocks.pass_fraction >= 0.9975, result
    assert result.delta_e["mean"] < 1.0, result
    assert result.passed
    wrong = _compare(case, method, seed=21, **case.wrong)
    print(f"{name} {method} {case.wrong} vs Mitsuba: {wrong}")
    assert not wrong.passed
    assert wrong.blocks.pass_fraction < 0.9975
