"""The path tracer against stored Mitsuba 3 references (dualight/data/references, made by
make_references.py): per-pixel and per-block Welch tests with both images' variances, and
Delta E 2000, each with negative controls that must fail the same comparison."""

from __future__ import annotations

import numpy as np
import pytest

import dualight
from dualight import metrics, scenes
from dualight.bench import REFERENCE_DIR as REFERENCES

SPP = 2048


def _reference(name: str) -> tuple[np.ndarray, np.ndarray, dict]:
    mean = dualight.Image.load(REFERENCES / f"{name}_mean.exr")
    var = dualight.Image.load(REFERENCES / f"{name}_var.exr")
    return np.asarray(mean), np.asarray(var), mean.stats


def _compare(scene: dualight.Scene, name: str, seed: int) -> metrics.Comparison:
    ref, ref_var, info = _reference(name)
    image = dualight.render(
        scene,
        spp=SPP,
        max_depth=info["max_depth"],
        rr_depth=info["rr_depth"],
        seed=seed,
        progress=False,
    )
    return metrics.compare(image, image.variance, ref, ref_var)


@pytest.fixture(scope="module")
def cornell_result() -> metrics.Comparison:
    return _compare(scenes.cornell_box(resolution=(64, 64)), "cornell_64", seed=11)


def test_cornell_matches_mitsuba(cornell_result: metrics.Comparison) -> None:
    print(f"\ncornell vs Mitsuba: {cornell_result}")
    assert cornell_result.pixel.pass_fraction >= 0.9975
    assert cornell_result.blocks.pass_fraction >= 0.9975
    assert cornell_result.delta_e["mean"] < 1.0
    assert cornell_result.passed


@pytest.mark.parametrize(
    "wrong", [{"light_scale": 0.98}, {"reflectance_scale": 0.97}], ids=["light0.98", "rho0.97"]
)
def test_cornell_negative_controls_fail(wrong: dict) -> None:
    result = _compare(scenes.cornell_box(resolution=(64, 64), **wrong), "cornell_64", seed=11)
    print(f"\ncornell {wrong} vs Mitsuba: {result}")
    assert not result.passed
    assert result.blocks.pass_fraction < 0.9975


def test_furnace_matches_mitsuba_and_analytic() -> None:
    result = _compare(scenes.furnace(0.5, 1.0, resolution=(64, 64)), "furnace_64", seed=12)
    print(f"\nfurnace vs Mitsuba: {result}")
    assert result.passed
    ref, _, info = _reference("furnace_64")
    truncated = sum(0.5**i for i in range(info["max_depth"]))  # paths of <= max_depth segments
    assert abs(ref.mean() / truncated - 1.0) < 2e-3


def test_furnace_negative_control_fails() -> None:
    result = _compare(scenes.furnace(0.5 * 0.97, 1.0, resolution=(64, 64)), "furnace_64", seed=12)
    print(f"\nfurnace rho x0.97 vs Mitsuba: {result}")
    assert not result.passed
