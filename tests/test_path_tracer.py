"""Path tracer against analytic answers, and its determinism, time limit, progress and Ctrl-C."""

from __future__ import annotations

import time

import numpy as np
import pytest

import dualight
from ctrl_c import interrupted
from dualight import metrics, scenes


def _truncated_furnace(rho: float, Le: float, max_depth: int) -> float:
    """Radiance of the furnace counting paths of at most max_depth segments."""
    if max_depth < 0:
        return scenes.furnace_radiance(rho, Le)
    return Le * sum(rho**i for i in range(max_depth))


def _against_constant(image: dualight.Image, value: float, block: int) -> metrics.WelchResult:
    ref = np.full(image.shape, value, dtype=np.float32)
    return metrics.welch_test(image, image.variance, ref, np.zeros_like(ref), block=block)


@pytest.mark.parametrize(("rho", "max_depth"), [(0.5, -1), (0.8, -1), (0.5, 2), (0.9, 4)])
def test_furnace_matches_analytic_radiance(rho: float, max_depth: int) -> None:
    # 1024 spp: per-pixel values are right-skewed (Russian roulette), and at a few hundred spp
    # the pixels that missed the rare large samples underestimate their own variance, which
    # the normal approximation behind the Welch test does not allow for.
    scene = scenes.furnace(rho, 1.0, resolution=(32, 32))
    image = dualight.render(scene, spp=1024, max_depth=max_depth, seed=1, progress=False)
    expected = _truncated_furnace(rho, 1.0, max_depth)
    pixel = _against_constant(image, expected, block=1)
    blocks = _against_constant(image, expected, block=8)
    assert pixel.pass_fraction >= 0.9975, pixel
    assert blocks.pass_fraction >= 0.9975, blocks
    assert abs(np.mean(image) / expected - 1.0) < 2e-3
    # Negative control: 3% less reflectance must fail the same block test.
    wrong = dualight.render(
        scenes.furnace(rho * 0.97, 1.0, resolution=(32, 32)),
        spp=1024,
        max_depth=max_depth,
        seed=1,
        progress=False,
    )
    assert _against_constant(wrong, expected, block=8).pass_fraction < 0.9975


def test_max_depth_one_shows_emission_only_exactly() -> None:
    image = dualight.render(
        scenes.furnace(0.5, 1.0, resolution=(8, 8)), spp=4, max_depth=1, progress=False
    )
    assert np.all(np.asarray(image) == 1.0)
    black = dualight.render(
        scenes.furnace(0.5, 1.0, resolution=(8, 8)), spp=4, max_depth=0, progress=False
    )
    assert np.all(np.asarray(black) == 0.0)


def test_directly_seen_emitter_has_its_radiance(tiny_scene) -> None:
    image = dualight.render(tiny_scene, spp=4, max_depth=1, progress=False)
    centre = np.asarray(image)[8, 8]
    np.testing.assert_array_equal(centre, [1.0, 2.0, 3.0])
    corner = np.asarray(image)[0, 0]  # the square does not fill the view
    np.testing.assert_array_equal(corner, [0.0, 0.0, 0.0])


def test_same_seed_same_image_with_one_or_two_threads() -> None:
    scene = scenes.cornell_box(resolution=(48, 40))
    one = dualight.render(scene, spp=8, seed=7, threads=1, progress=False)
    two = dualight.render(scene, spp=8, seed=7, threads=2, progress=False)
    assert np.array_equal(np.asarray(one), np.asarray(two))
    assert np.array_equal(one.variance, two.variance)
    other = dualight.render(scene, spp=8, seed=8, threads=2, progress=False)
    assert not np.array_equal(np.asarray(one), np.asarray(other))


def test_stats_describe_the_render() -> None:
    image = dualight.render(scenes.cornell_box(resolution=(32, 32)), spp=4, progress=False)
    s = image.stats
    assert s["method"] == "path" and s["spp"] == 4 and s["samples"] == 32 * 32 * 4
    assert s["rays"] >= s["samples"] and s["seconds"] > 0 and s["samples_per_second"] > 0
    assert s["invalid_samples"] == 0 and not s["interrupted"]


def test_time_limit_stops_on_a_whole_pass() -> None:
    scene = scenes.cornell_box(resolution=(64, 64))
    start = time.perf_counter()
    image = dualight.render(scene, spp=None, time_limit=0.5, progress=False)
    elapsed = time.perf_counter() - start
    assert 0.5 <= elapsed < 1.5
    assert image.stats["time_limited"] and image.stats["spp"] >= 1
    assert image.stats["samples"] == image.stats["spp"] * 64 * 64


def test_progress_callback_reports_and_its_errors_propagate() -> None:
    scene = scenes.cornell_box(resolution=(64, 64))
    calls: list[tuple[int, int]] = []
    dualight.render(scene, spp=64, progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1] == (64 * 64 * 64, 64 * 64 * 64)

    def broken(done: int, total: int) -> None:
        raise RuntimeError("callback failed")

    with pytest.raises(RuntimeError, match="callback failed"):
        dualight.render(scene, spp=100000, progress=broken)


def test_progress_bar_follows_a_new_total() -> None:
    """The MLT methods report the direct light's samples, then the chains' mutations: the bar
    starts over with the new total instead of ending at the wrong one."""
    from dualight.render import _TqdmProgress

    bar = _TqdmProgress("test")
    bar(10, 100)
    bar(100, 100)
    bar(5, 40)
    assert bar._bar.total == 40 and bar._bar.n == 5
    bar(40, 40)
    assert bar._bar.n == bar._bar.total == 40
    bar.close()


@pytest.mark.parametrize("method", dualight.METHODS)
@pytest.mark.usefixtures("ctrl_c_raises")
def test_ctrl_c_stops_within_half_a_second_and_keeps_the_partial_image(method: str) -> None:
    scene = scenes.cornell_box(resolution=(64, 64))
    depth = {"max_depth": 8} if method == "mmlt" else {}  # MMLT: chains per path length
    caught, latency = interrupted(
        lambda: dualight.render(
            scene, method, spp=1_000_000, time_limit=20.0, progress=False, **depth
        ),
        0.4,
    )
    assert latency < 0.5, f"took {latency:.3f} s to stop"
    partial = caught.partial_result  # type: ignore[attr-defined]
    assert isinstance(partial, dualight.Image) and partial.stats["interrupted"]
    # MLT may be stopped before its first mutation; its separately rendered direct light stays.
    assert partial.stats["samples"] > 0 or np.any(np.asarray(partial) > 0)
    assert np.all(np.isfinite(np.asarray(partial)))
