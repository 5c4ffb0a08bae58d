"""Primary-sample-space MLT over BDPT (Kelemen et al. 2002), its multiplexed form (MMLT,
Hachisuka et al. 2014) and path-space MLT (Veach 1997), against the Mitsuba Cornell reference.
MLT pixels are correlated (a chain splats into many pixels) and its brightness is set by
estimates of b, so it is tested on block means with variances from independent runs."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import dualight
from dualight import metrics, scenes

REFERENCES = Path(__file__).parent / "references"
RUNS, MPP, BLOCK = 12, 24, 8
ALPHA = 0.01


def _t_critical(dof: int, alpha_per_test: float) -> float:
    """Two-sided Student-t critical value (numerical integration of the density; no SciPy)."""
    t = np.linspace(0.0, 400.0, 2_000_001)
    log_c = math.lgamma((dof + 1) / 2) - math.lgamma(dof / 2) - 0.5 * math.log(dof * math.pi)
    pdf = np.exp(log_c - (dof + 1) / 2 * np.log1p(t * t / dof))
    tail = 2.0 * (
        np.trapezoid(pdf, t)
        - np.concatenate([[0.0], np.cumsum((pdf[1:] + pdf[:-1]) / 2 * np.diff(t))])
    )
    return float(t[np.argmax(tail < alpha_per_test)])


def _reference() -> tuple[np.ndarray, np.ndarray]:
    mean = dualight.Image.load(REFERENCES / "cornell_64_mean.exr")
    var = dualight.Image.load(REFERENCES / "cornell_64_var.exr")
    return np.asarray(mean), np.asarray(var)


METHODS = ("pssmlt", "mmlt", "mlt")


def _runs(method: str, **scene_kw) -> list[dualight.Image]:
    scene = scenes.cornell_box(resolution=(64, 64), **scene_kw)
    return [
        dualight.render(
            scene, method, mutations_per_pixel=MPP, max_depth=8, seed=100 + i, progress=False
        )
        for i in range(RUNS)
    ]


def _block_test(runs: list[dualight.Image]) -> tuple[float, float, float]:
    """t-test of the runs' block means against the reference's, the runs' variance measured
    from their spread (so correlation between pixels and the error of b count), with
    Student's t for len(runs) - 1 degrees of freedom (the reference's own variance is 50x
    smaller) and a Sidak-corrected level over blocks and channels.
    Returns (fraction of blocks passing, largest |t|, critical value)."""
    ref, ref_var = _reference()
    blocks = np.array([metrics.block_mean(np.asarray(r), BLOCK) for r in runs])
    mean = blocks.mean(axis=0)
    var_of_mean = blocks.var(axis=0, ddof=1) / len(runs)
    ref_blocks = metrics.block_mean(ref, BLOCK)
    ref_block_var = metrics.block_mean(ref_var, BLOCK) / BLOCK**2
    t = np.abs(mean - ref_blocks) / np.sqrt(var_of_mean + ref_block_var)
    alpha_per_test = -math.expm1(math.log1p(-ALPHA) / t.size)
    critical = _t_critical(len(runs) - 1, alpha_per_test)
    passed = np.all(t < critical, axis=2)
    return float(passed.mean()), float(t.max()), critical


@pytest.fixture(scope="module", params=METHODS)
def method_runs(request) -> tuple[str, list[dualight.Image]]:
    return request.param, _runs(request.param)


@pytest.fixture(scope="module")
def cornell_runs() -> list[dualight.Image]:
    return _runs("pssmlt")


def test_block_means_match_mitsuba_and_a_dimmer_light_fails(method_runs) -> None:
    method, runs = method_runs
    passed, t_max, critical = _block_test(runs)
    print(
        f"\n{method} {RUNS} runs x {MPP} mutations/pixel, {BLOCK}x{BLOCK} blocks: "
        f"{100 * passed:.2f}% pass, max |t| {t_max:.2f} vs t* {critical:.2f}"
    )
    assert passed >= 0.9975
    wrong, t_wrong, _ = _block_test(_runs(method, light_scale=0.95))
    print(f"light x0.95: {100 * wrong:.2f}% pass, max |t| {t_wrong:.2f}")
    assert wrong < 0.9975


def test_brightness_agrees_with_the_reference_within_b_interval(method_runs) -> None:
    method, runs = method_runs
    ref, _ = _reference()
    ratios = np.array([float(np.mean(r)) / float(ref.mean()) for r in runs])
    rel_sigma = np.array([r.stats["b_ci95"] / 1.96 / r.stats["b"] for r in runs])
    print(
        f"\n{method} image mean / reference over {RUNS} seeds: {np.round(ratios, 4)} "
        f"(mean {ratios.mean():.4f}), b rel. sd {rel_sigma.mean():.4f}"
    )
    # Each image's brightness is b's estimate: within 4 of its standard errors.
    assert np.all(np.abs(ratios - 1.0) < 4.0 * rel_sigma)
    # The seeds' mean brightness, within 4 standard errors of the mean, and within 0.5 %.
    assert abs(ratios.mean() - 1.0) < 4.0 * rel_sigma.mean() / np.sqrt(RUNS)
    assert abs(ratios.mean() - 1.0) < 0.005


def test_stats_and_options(cornell_runs) -> None:
    s = cornell_runs[0].stats
    assert cornell_runs[0].variance is None
    assert s["method"] == "pssmlt" and s["mutations"] == 64 * 64 * MPP
    assert 0.0 < s["large_step_acceptance_rate"] < s["small_step_acceptance_rate"] < 1.0
    assert s["b"] > 0 and 0 < s["b_ci95"] < 0.1 * s["b"]
    assert s["b_samples"] > 100000 and s["invalid_samples"] == 0
    scene = scenes.cornell_box(resolution=(16, 16))
    one = dualight.render(scene, "pssmlt", mutations_per_pixel=4, seed=3, threads=1, progress=False)
    two = dualight.render(scene, "pssmlt", mutations_per_pixel=4, seed=3, threads=2, progress=False)
    np.testing.assert_array_equal(np.asarray(one), np.asarray(two))
    with pytest.raises(ValueError, match="pssmlt"):
        dualight.render(scene, "bdpt", mutations_per_pixel=4, progress=False)
    with pytest.raises(ValueError, match="bounded max_depth"):
        dualight.render(scene, "mmlt", mutations_per_pixel=4, progress=False)
    with pytest.raises(ValueError, match="time_limit"):
        dualight.render(scene, "mmlt", spp=None, time_limit=1.0, max_depth=5, progress=False)
    mm1 = dualight.render(
        scene, "mmlt", mutations_per_pixel=4, max_depth=5, threads=1, progress=False
    )
    mm2 = dualight.render(
        scene, "mmlt", mutations_per_pixel=4, max_depth=5, threads=2, progress=False
    )
    np.testing.assert_array_equal(np.asarray(mm1), np.asarray(mm2))
    with pytest.raises(TypeError):
        dualight.render(scene, "pssmlt", mutations_per_pixel=1, mlt={"sigmaa": 0.1}, progress=False)
    with pytest.raises(ValueError, match="sigma"):
        dualight.render(scene, "pssmlt", mutations_per_pixel=1, mlt={"sigma": 2.0}, progress=False)
    # Without separate direct light, the chains carry it too and agree on the brightness.
    ref, _ = _reference()
    whole = dualight.render(
        scenes.cornell_box(resolution=(64, 64)),
        "pssmlt",
        mutations_per_pixel=16,
        max_depth=8,
        mlt={"direct_spp": 0, "bootstrap": 400000},
        progress=False,
    )
    sigma = whole.stats["b_ci95"] / 1.96 / whole.stats["b"]
    assert abs(float(np.mean(whole)) / float(ref.mean()) - 1.0) < 4.0 * sigma
