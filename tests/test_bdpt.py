"""Path-space duality without Mitsuba: the light tracer, BDPT and the path tracer estimate the
same image; BDPT's strategy images sum to its image; the power and balance heuristics agree;
cached path densities match their recomputation (verify); and the estimators' plumbing
(determinism, max_depth, Ctrl-C, bad options)."""

from __future__ import annotations

import time

import numpy as np
import pytest

import dualight
from dualight import _testing, metrics, scenes

ADJOINT = ("light", "bdpt")


def _welch(a: dualight.Image, b: dualight.Image, block: int) -> metrics.WelchResult:
    return metrics.welch_test(a, a.variance, b, b.variance, block=block)


@pytest.fixture(scope="module")
def cornell_path() -> dualight.Image:
    scene = scenes.cornell_box(resolution=(32, 32))
    return dualight.render(scene, "path", spp=1024, max_depth=6, seed=11, progress=False)


@pytest.mark.parametrize("method", ADJOINT)
def test_adjoint_estimators_agree_with_the_path_tracer(method: str, cornell_path) -> None:
    scene = scenes.cornell_box(resolution=(32, 32))
    spp = 1024 if method == "light" else 256
    image = dualight.render(scene, method, spp=spp, max_depth=6, seed=12, progress=False)
    pixels, blocks = _welch(image, cornell_path, 1), _welch(image, cornell_path, 4)
    assert pixels.pass_fraction >= 0.995, pixels
    assert blocks.pass_fraction >= 0.99, blocks
    # The image means agree within 5 standard errors (the light's edge pixels dominate them).
    n = image.variance.size
    sigma = float(np.sqrt(np.sum(image.variance) + np.sum(cornell_path.variance))) / n
    assert abs(float(np.mean(image)) - float(np.mean(cornell_path))) < 5 * sigma
    # Negative control: 5% less light fails the same block test.
    dim = scenes.cornell_box(resolution=(32, 32), light_scale=0.95)
    wrong = dualight.render(dim, method, spp=spp, max_depth=6, seed=12, progress=False)
    assert _welch(wrong, cornell_path, 4).pass_fraction < 0.9, "a 5% dimmer light went unnoticed"


@pytest.mark.parametrize("method", ADJOINT)
@pytest.mark.parametrize(("rho", "max_depth"), [(0.5, -1), (0.7, 4)])
def test_furnace_matches_analytic_radiance(method: str, rho: float, max_depth: int) -> None:
    scene = scenes.furnace(rho, 1.0, resolution=(16, 16))
    image = dualight.render(scene, method, spp=512, max_depth=max_depth, seed=3, progress=False)
    if max_depth < 0:
        expected = scenes.furnace_radiance(rho, 1.0)
    else:
        expected = sum(rho**i for i in range(max_depth))
    mean = float(np.mean(image))
    # The image mean's standard error, from the estimator's own variances (pixels independent
    # enough for this: a particle splats into at most max_depth pixels).
    sigma = float(np.sqrt(np.sum(image.variance)) / image.variance.size)
    assert abs(mean - expected) < 5 * sigma + 1e-6 * expected, (mean, expected, sigma)
    wrong = dualight.render(
        scenes.furnace(rho * 0.97, 1.0, resolution=(16, 16)),
        method,
        spp=512,
        max_depth=max_depth,
        seed=3,
        progress=False,
    )
    assert abs(float(np.mean(wrong)) - expected) > 5 * sigma


def test_strategy_images_sum_to_the_image() -> None:
    scene = scenes.cornell_box(resolution=(24, 24))
    image = dualight.render(
        scene, "bdpt", spp=16, max_depth=5, seed=1, strategy_images=True, progress=False
    )
    strategies = image.strategies
    expected_keys = {(d + 1 - t, t) for d in range(1, 6) for t in range(1, d + 2)}
    assert set(strategies) == expected_keys
    total = np.sum(list(strategies.values()), axis=0)
    np.testing.assert_allclose(total, np.asarray(image), rtol=1e-5, atol=1e-6)
    # Light tracing strategies (t = 1) reach this view, and every depth contributes.
    assert np.sum(strategies[(2, 1)]) > 0
    assert all(np.sum(strategies[(0, d + 1)]) >= 0 for d in range(1, 6))
    # Negative control of the check itself: dropping one strategy breaks the sum.
    partial = total - strategies[(1, 2)]
    assert not np.allclose(partial, np.asarray(image), rtol=1e-5, atol=1e-6)


def test_strategy_images_need_bdpt_and_a_bounded_depth() -> None:
    scene = scenes.cornell_box(resolution=(8, 8))
    with pytest.raises(ValueError, match="bounded max_depth"):
        dualight.render(scene, "bdpt", spp=1, strategy_images=True, progress=False)
    with pytest.raises(ValueError, match="bdpt"):
        dualight.render(scene, "path", spp=1, max_depth=3, strategy_images=True, progress=False)
    with pytest.raises(ValueError, match="heuristic"):
        dualight.render(scene, "bdpt", spp=1, heuristic="cubic", progress=False)


def test_power_and_balance_heuristics_agree_in_expectation() -> None:
    scene = scenes.cornell_box(resolution=(32, 32))
    power = dualight.render(scene, "bdpt", spp=256, max_depth=5, seed=5, progress=False)
    balance = dualight.render(
        scene, "bdpt", spp=256, max_depth=5, seed=6, heuristic="balance", progress=False
    )
    assert _welch(power, balance, 1).pass_fraction >= 0.995
    assert _welch(power, balance, 4).pass_fraction >= 0.99
    wrong = dualight.render(
        scenes.cornell_box(resolution=(32, 32), reflectance_scale=0.95),
        "bdpt",
        spp=256,
        max_depth=5,
        seed=6,
        heuristic="balance",
        progress=False,
    )
    assert _welch(power, wrong, 4).pass_fraction < 0.9


def test_verify_recomputes_cached_path_quantities() -> None:
    for scene in (
        scenes.cornell_box(resolution=(32, 32)),
        scenes.furnace(0.8, 1.0, (16, 16)),
        scenes.cornell_box(resolution=(32, 32), variant="smooth"),  # shading normals' weights
    ):
        check = _testing.verify_random_subpaths(
            scene._compile(), scene.camera._compile(), 4000, max_depth=8, seed=2
        )
        assert check["vertices"] > 8000
        assert check["off"] == 0, check
        assert max(check["pdf_fwd"], check["pdf_rev"], check["beta"]) < 1e-4, check


@pytest.mark.parametrize("method", ADJOINT)
def test_same_seed_same_image_with_one_or_two_threads(method: str) -> None:
    scene = scenes.cornell_box(resolution=(24, 24))
    one = dualight.render(scene, method, spp=8, seed=7, threads=1, progress=False)
    two = dualight.render(scene, method, spp=8, seed=7, threads=2, progress=False)
    np.testing.assert_array_equal(np.asarray(one), np.asarray(two))
    np.testing.assert_array_equal(one.variance, two.variance)
    other = dualight.render(scene, method, spp=8, seed=8, threads=2, progress=False)
    assert not np.array_equal(np.asarray(one), np.asarray(other))


@pytest.mark.parametrize("method", ADJOINT)
def test_max_depth_one_is_the_directly_seen_emitter(method: str, tiny_scene) -> None:
    image = dualight.render(tiny_scene, method, spp=256, max_depth=1, seed=1, progress=False)
    arr = np.asarray(image)
    assert np.all(arr[0, 0] == 0.0)  # the square does not fill the view
    centre = arr[6:10, 6:10].reshape(-1, 3).mean(axis=0)
    # BDPT sees emitters by (s, t) = (0, 2) exactly; the light tracer by splatting particles.
    np.testing.assert_allclose(centre, [1.0, 2.0, 3.0], rtol=0.05 if method == "light" else 1e-6)
    black = dualight.render(tiny_scene, method, spp=4, max_depth=0, progress=False)
    assert np.all(np.asarray(black) == 0.0)


@pytest.mark.parametrize("method", ADJOINT)
def test_stats_count_light_paths(method: str) -> None:
    scene = scenes.cornell_box(resolution=(16, 16))
    image = dualight.render(scene, method, spp=4, seed=1, progress=False)
    s = image.stats
    assert s["method"] == method and s["light_paths"] == 16 * 16 * 4
    assert s["rays"] > 0 and s["invalid_samples"] == 0 and not s["interrupted"]
    assert not s["specular_surfaces"]


@pytest.mark.parametrize("method", ["path", *ADJOINT])
def test_stats_count_connections_skipped_at_specular_vertices(method: str) -> None:
    """A mirror in view: connections that end on it cannot carry light and are not traced."""
    plain = scenes.cornell_box(resolution=(16, 16))
    with_mirror = scenes.cornell_box(resolution=(16, 16))
    corners = np.array([[500.0, 10, 400], [350, 10, 540], [350, 400, 540], [500, 400, 400]])
    with_mirror.add_mesh(corners, [[0, 1, 2, 3]], material=dualight.Mirror(), name="mirror")
    a = dualight.render(plain, method, spp=16, max_depth=6, seed=1, progress=False).stats
    b = dualight.render(with_mirror, method, spp=16, max_depth=6, seed=1, progress=False).stats
    assert b["specular_surfaces"] and not a["specular_surfaces"]
    assert b["skipped_connections"] > 1.2 * a["skipped_connections"], (a, b)


def test_bdpt_starts_roulette_at_vertex_two_by_default() -> None:
    """rr_depth=None is each method's own default: BDPT's 2 (its connections multiply with its
    subpaths' lengths), Mitsuba's 5 for the others. The default reaches the core: the image is
    rr_depth=2's to the bit and not rr_depth=5's."""
    scene = scenes.cornell_box(resolution=(16, 16))
    render = lambda method, **kw: dualight.render(  # noqa: E731
        scene, method, spp=8, max_depth=8, seed=3, progress=False, **kw
    )
    default = render("bdpt")
    assert default.stats["rr_depth"] == 2
    np.testing.assert_array_equal(np.asarray(default), np.asarray(render("bdpt", rr_depth=2)))
    five = render("bdpt", rr_depth=5)
    assert five.stats["rr_depth"] == 5
    assert not np.array_equal(np.asarray(default), np.asarray(five))
    for method in ("path", "light"):
        assert render(method).stats["rr_depth"] == 5
    mlt = {"bootstrap": 1000, "chains": 4}
    pssmlt = dualight.render(scene, "pssmlt", mutations_per_pixel=1, progress=False, mlt=mlt)
    assert pssmlt.stats["rr_depth"] == 5


def test_light_pool_keeps_the_expectation() -> None:
    """BDPT's light pool (each connection takes a light subpath of its pixel's group) estimates
    the classic BDPT's image, at the default 16 and at 5, whose groups do not divide the
    18-pixel rows (the tiles' rows hold 16 and 2 pixels): per pixel (Welch, each pixel's own
    variance) and on the image mean over 8 seeds each (the seeds' scatter: the pixels of a
    group, like light tracing's splats, correlate, so summed pixel variances would understate
    the mean's). A 5% dimmer light fails the same mean test, and a 20% dimmer one the same
    per-pixel test (at 256 spp a 5% one passes it; seeds 200-202 gave pass fractions of 0.39-0.43
    at 20% and 0.89-0.96 at 10%). stats["light_pool"] says which ran."""
    scene = scenes.cornell_box(resolution=(18, 12))
    dim = scenes.cornell_box(resolution=(18, 12), light_scale=0.95)

    def renders(pool: int | None, first_seed: int, on=scene) -> list[dualight.Image]:
        return [
            dualight.render(
                on, "bdpt", spp=256, max_depth=6, seed=seed, light_pool=pool, progress=False
            )
            for seed in range(first_seed, first_seed + 8)
        ]

    def mean_z(a: list[dualight.Image], b: list[dualight.Image]) -> float:
        ma, mb = (np.array([float(np.mean(i)) for i in x]) for x in (a, b))
        return abs(ma.mean() - mb.mean()) / float(np.sqrt(ma.var(ddof=1) / 8 + mb.var(ddof=1) / 8))

    classic = renders(1, 100)
    assert classic[0].stats["light_pool"] == 1
    for pool, first_seed in ((None, 200), (5, 300)):
        pooled = renders(pool, first_seed)
        assert pooled[0].stats["light_pool"] == (16 if pool is None else pool)
        assert _welch(pooled[0], classic[0], 1).pass_fraction >= 0.99
        assert mean_z(pooled, classic) < 5.0
    assert mean_z(renders(None, 200, on=dim), classic) > 5.0, "a 5% dimmer light went unnoticed"
    dimmer = scenes.cornell_box(resolution=(18, 12), light_scale=0.8)
    wrong = dualight.render(dimmer, "bdpt", spp=256, max_depth=6, seed=200, progress=False)
    assert _welch(wrong, classic[0], 1).pass_fraction < 0.99, "a 20% dimmer light went unnoticed"


def test_light_pool_reaches_the_core_but_not_guided_bdpt() -> None:
    """16 (the default) and 1 render different images; guided BDPT joins each sample's own
    subpaths whatever light_pool says (the same bits, stats["light_pool"] 1)."""
    scene = scenes.cornell_box(resolution=(16, 16))
    render = lambda **kw: dualight.render(  # noqa: E731
        scene, "bdpt", spp=4, max_depth=4, seed=9, progress=False, **kw
    )
    assert not np.array_equal(np.asarray(render()), np.asarray(render(light_pool=1)))
    guided, guided_one = render(guiding=True), render(guiding=True, light_pool=1)
    np.testing.assert_array_equal(np.asarray(guided), np.asarray(guided_one))
    assert guided.stats["light_pool"] == guided_one.stats["light_pool"] == 1


@pytest.mark.parametrize("method", ADJOINT)
def test_time_limit(method: str) -> None:
    # (Ctrl-C for every method: test_path_tracer.py.)
    scene = scenes.cornell_box(resolution=(32, 32))
    start = time.perf_counter()
    limited = dualight.render(scene, method, spp=None, time_limit=0.5, progress=False)
    assert time.perf_counter() - start < 2.0
    assert limited.stats["time_limited"] and limited.stats["light_paths"] > 0


def test_unknown_method_is_named() -> None:
    with pytest.raises(ValueError, match="bdpt"):
        dualight.render(scenes.cornell_box(resolution=(8, 8)), "mlt-ish", spp=1, progress=False)
