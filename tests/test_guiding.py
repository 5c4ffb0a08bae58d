"""Path guiding (issue 22): the SD-tree guides' samples against their densities, guided renders
deterministic for a seed whatever the thread count, their stats, Ctrl-C during training, and bad
input. Guided renders against the Mitsuba references (with negative controls) are rows of
test_pathspace_vs_mitsuba.py (``*_guided``)."""

from __future__ import annotations

import dataclasses
import math
import types

import numpy as np
import pytest

import dualight
from chi2 import chi2_sf, pearson, sidak
from ctrl_c import interrupted
from dualight import scenes

ALPHA = 0.01
LEAVES_TESTED = 3


@pytest.fixture(scope="module")
def cornell() -> dualight.Scene:
    return scenes.cornell_box(resolution=(32, 32))


@pytest.fixture(scope="module")
def door() -> dualight.Scene:
    return scenes.door_ajar(resolution=(32, 32))


def _chi2(cells: np.ndarray, d: np.ndarray) -> tuple[float, int, float]:
    """Pearson's statistic of unit directions d (N, 3) over a leaf's quadtree cells (rows u0,
    v0, size, density on the square; each expects N times its density times its area)."""
    assert np.isfinite(d).all()
    u = (d[:, 2] + 1) / 2
    v = (np.arctan2(d[:, 1], d[:, 0]) % (2 * np.pi)) / (2 * np.pi)
    # The cell of each direction: cells tile the square, so one holds it (up to rounding).
    inside = (
        (u[:, None] >= cells[None, :, 0])
        & (u[:, None] < cells[None, :, 0] + cells[None, :, 2])
        & (v[:, None] >= cells[None, :, 1])
        & (v[:, None] < cells[None, :, 1] + cells[None, :, 2])
    )
    observed = np.bincount(inside.argmax(1)[inside.any(1)], minlength=len(cells)).astype(float)
    statistic, k = pearson(observed, len(d) * cells[:, 3] * cells[:, 2] ** 2)
    dof = max(k - 1, 1)
    return statistic, dof, chi2_sf(statistic, dof) if math.isfinite(statistic) else 0.0


@pytest.mark.parametrize("transport", ["radiance", "importance"])
def test_guide_samples_follow_its_density(cornell: dualight.Scene, transport: str) -> None:
    guide = dualight.train_guide(cornell, transport, spp=64, seed=1)
    leaves = guide.leaves()
    assert guide.stats["iterations"] == 4  # 1 + 2 + 4 + 8 spp: a quarter of 64
    busiest = np.argsort(-leaves["directional_nodes"])[:LEAVES_TESTED]
    rng = np.random.default_rng(7)
    level = sidak(ALPHA, 2 * LEAVES_TESTED)
    for leaf in busiest:
        point = (leaves["lo"][leaf] + leaves["hi"][leaf]) / 2
        cells = guide.directional(*point)
        # The density integrates to one over the square, and pdf() agrees with the cells.
        assert np.sum(cells[:, 3] * cells[:, 2] ** 2) == pytest.approx(1.0, abs=1e-4)
        centre = cells[:, :2] + cells[:, 2:3] / 2
        cos_theta, phi = 2 * centre[:, 0] - 1, 2 * np.pi * centre[:, 1]
        sin_theta = np.sqrt(1 - cos_theta**2)
        dirs = np.stack([sin_theta * np.cos(phi), sin_theta * np.sin(phi), cos_theta], 1)
        pdf = guide.pdf(
            np.repeat(point[None], len(cells), 0).astype(np.float32), dirs.astype(np.float32)
        )
        np.testing.assert_allclose(pdf * 4 * np.pi, cells[:, 3], rtol=1e-4)
        n = 100_000
        d = guide.sample(
            np.repeat(point[None].astype(np.float32), n, 0), rng.random((n, 2), dtype=np.float32)
        )
        statistic, dof, p = _chi2(cells, d)
        assert p > level, f"leaf {leaf}: chi2 {statistic:.1f} on {dof} dof, p {p:.2e}"


def test_a_wrong_density_fails_the_same_chi_square(cornell: dualight.Scene) -> None:
    """Negative control: samples drawn uniformly on the sphere do not follow the guide's density."""
    guide = dualight.train_guide(cornell, spp=64, seed=1)
    leaves = guide.leaves()
    leaf = int(np.argmax(leaves["directional_nodes"]))
    point = (leaves["lo"][leaf] + leaves["hi"][leaf]) / 2
    cells = guide.directional(*point)
    rng = np.random.default_rng(3)
    d = rng.normal(size=(100_000, 3))
    _, _, p = _chi2(cells, d / np.linalg.norm(d, axis=1, keepdims=True))
    assert p < sidak(ALPHA, 2 * LEAVES_TESTED)


def _without_seconds(g: dict) -> dict:
    """A guiding stats dict without its timings (guided BDPT's: both guides')."""
    return {
        k: _without_seconds(v) if isinstance(v, dict) else v
        for k, v in g.items()
        if k not in ("training_seconds", "rendering_seconds")
    }


@pytest.mark.parametrize("method", ["path", "light", "bdpt"])
def test_guided_renders_do_not_depend_on_the_thread_count(
    door: dualight.Scene, method: str
) -> None:
    spp = 16 if method == "bdpt" else 32
    images = [
        dualight.render(door, method, spp=spp, seed=5, threads=t, guiding=True, progress=False)
        for t in (1, 2)
    ]
    assert np.array_equal(np.asarray(images[0]), np.asarray(images[1]))
    assert np.array_equal(images[0].variance, images[1].variance)
    g0, g1 = (_without_seconds(im.stats["guiding"]) for im in images)
    assert g0 == g1


@pytest.mark.parametrize("method", ["path", "light"])
def test_guided_stats_say_what_training_took(cornell: dualight.Scene, method: str) -> None:
    image = dualight.render(
        cornell, method, spp=64, seed=2, guiding={"training": 0.5}, progress=False
    )
    stats = image.stats
    g = stats["guiding"]
    assert g["iterations"] == 5 and g["training_spp"] == 31  # 1 + 2 + 4 + 8 + 16 <= 32
    # training comes on top of the image's samples; the image keeps the last two iterations'
    assert g["kept_spp"] == 8 + 16 and stats["spp"] == 64 + 8 + 16
    assert g["spatial_leaves"] >= 1 and g["directional_nodes"] >= 1 and g["records"] > 0
    assert 0.5 <= g["bsdf_fraction_min"] <= g["bsdf_fraction"] <= g["bsdf_fraction_max"] <= 1.0
    assert stats["seconds"] == pytest.approx(g["training_seconds"] + g["rendering_seconds"])
    unguided = dualight.render(cornell, method, spp=64, seed=2, progress=False)
    assert "guiding" not in unguided.stats


@pytest.mark.parametrize("method", ["path", "light", "bdpt"])
def test_the_image_keeps_the_last_training_iterations_samples(
    cornell: dualight.Scene, method: str
) -> None:
    """keep_iterations=k adds the samples of the last k training iterations to the image's own
    (the same own samples whatever k: same seed): its variance drops by about the share of
    samples added; k=0 keeps none, and the image is then the render's own samples."""
    options = {"training": 0.5, "adjoint_roulette": False}
    images = {
        k: dualight.render(
            cornell,
            method,
            spp=64,
            seed=3,
            guiding={**options, "keep_iterations": k},
            progress=False,
        )
        for k in (0, 1, 3)
    }
    kept = {k: im.stats["guiding"]["kept_spp"] for k, im in images.items()}
    assert kept == {0: 0, 1: 16, 3: 4 + 8 + 16}
    assert all(im.stats["spp"] == 64 + kept[k] for k, im in images.items())
    variance = {k: float(im.variance.mean()) for k, im in images.items()}
    # Cornell: guided and unguided samples are alike, so variance ~ 1 / samples
    for k in (1, 3):
        ratio = variance[k] / variance[0]
        assert 0.8 * 64 / (64 + kept[k]) < ratio < 1.1 * 64 / (64 + kept[k])
    assert not np.array_equal(np.asarray(images[0]), np.asarray(images[1]))


def test_guided_bdpt_stats_hold_both_guides(cornell: dualight.Scene) -> None:
    """Guided BDPT trains a radiance guide (camera subpaths) and an importance guide (light
    subpaths) together, from its own samples: one training, whose iterations both guides count
    and whose last two iterations' samples the image keeps; stats hold both guides."""
    image = dualight.render(
        cornell, "bdpt", spp=64, seed=2, guiding={"training": 0.5}, progress=False
    )
    stats = image.stats
    g = stats["guiding"]
    assert g["kept_spp"] == 8 + 16 and stats["spp"] == 64 + 8 + 16
    for guide in (g["radiance"], g["importance"]):
        assert guide["iterations"] == 5 and guide["training_spp"] == 31  # 1 + ... + 16 <= 32
        assert guide["spatial_leaves"] >= 1 and guide["records"] > 0
        assert 0.5 <= guide["bsdf_fraction_min"] <= guide["bsdf_fraction_max"] <= 1.0
        assert guide["training_seconds"] == g["training_seconds"]
    assert stats["seconds"] == pytest.approx(g["training_seconds"] + g["rendering_seconds"])


@pytest.mark.parametrize("method", ["path", "light", "bdpt"])
def test_a_time_limited_render_tries_whether_the_guide_pays(method: str) -> None:
    """Under a time limit, before the training's last iteration (or after the training), a guided
    and an unguided pass of half the last iteration's spp each are kept in the image and the
    image is rendered by the more efficient (unless the passes disagree beyond their variances:
    then guided). The stats add up: spp and
    seconds count training, trial and the image's own samples. trial=False, or spp alone, runs
    no trial."""
    cornell = scenes.cornell_box(resolution=(16, 16))  # passes of at least 32 spp in the time
    image = dualight.render(
        cornell, method, spp=None, time_limit=1.0, seed=5, progress=False, guiding=True
    )
    stats, g = image.stats, image.stats["guiding"]
    iterations = (g["radiance"] if method == "bdpt" else g)["iterations"]
    last = 1 << (iterations - 1)
    stopped = (g["radiance"] if method == "bdpt" else g)["stopped_by_trial"]
    # passes of half the last iteration's spp (at least 32): after the training, or before its
    # last iteration (the one before it then had half that spp: if it stopped the training, it
    # is the last)
    assert g["trial"] and g["trial_seconds"] > 0.0
    passes = (max(last, 32),) if stopped else (max(last // 2, 32), max(last, 32))
    assert g["trial_spp"] in tuple(2 * p for p in passes)
    assert g["efficiency_ratio"] > 0.0 and g["trial_disagreement"] > 0.0
    trusted = g["trial_disagreement"] <= 1.15
    # before the last iteration the guided pass must also pay for it (ratio_to_pay above 1)
    assert g["trial_ratio_to_pay"] >= 1.0
    pays = g["efficiency_ratio"] >= g["trial_ratio_to_pay"]
    assert g["rendered_guided"] == (pays or not trusted)
    # an unguided win before the last iteration stops the training there
    assert not (stopped and g["rendered_guided"])
    assert stats["spp"] > g["kept_spp"] + g["trial_spp"]
    assert stats["seconds"] == pytest.approx(
        g["training_seconds"] + g["rendering_seconds"] + g["trial_seconds"]
    )
    assert stats["seconds"] < 1.25
    if method == "bdpt":
        assert g["importance"]["trial_spp"] == g["trial_spp"]
    off = dualight.render(
        cornell, method, time_limit=0.3, seed=5, progress=False, guiding={"trial": False}
    )
    by_spp = dualight.render(cornell, method, spp=64, seed=5, progress=False, guiding=True)
    for other in (off, by_spp):
        assert not other.stats["guiding"]["trial"] and other.stats["guiding"]["trial_spp"] == 0
        assert other.stats["guiding"]["rendered_guided"]


def test_a_fixed_bsdf_fraction_of_one_renders_the_unguided_image(cornell: dualight.Scene) -> None:
    """With the BSDF always chosen the guide draws no random number and changes no density:
    the unguided image (BDPT: its MIS weights too; and classic BDPT's, light_pool=1, which
    guided BDPT runs)."""
    fixed = {
        "learn_bsdf_fraction": False,
        "bsdf_fraction": 1.0,
        "adjoint_roulette": False,
        "keep_iterations": 0,
    }
    for method in ("path", "light", "bdpt"):
        guided = dualight.render(cornell, method, spp=16, seed=4, guiding=fixed, progress=False)
        classic = {"light_pool": 1} if method == "bdpt" else {}
        plain = dualight.render(cornell, method, spp=16, seed=4, progress=False, **classic)
        assert np.array_equal(np.asarray(guided), np.asarray(plain))


def test_adjoint_roulette_says_what_it_did(door: dualight.Scene) -> None:
    """On the door, paths in the dark room split and paths with little left to carry stop;
    without the roulette neither happens (and the light tracer never plays it)."""
    g = dualight.render(door, "path", spp=16, seed=3, guiding=True, progress=False).stats["guiding"]
    assert g["adjoint_roulette"] and g["split_paths"] > 0 and g["roulette_stops"] > 0
    off = {"adjoint_roulette": False}
    g = dualight.render(door, "path", spp=16, seed=3, guiding=off, progress=False).stats["guiding"]
    assert not g["adjoint_roulette"] and g["split_paths"] == 0 and g["roulette_stops"] == 0
    g = dualight.render(door, "light", spp=16, seed=3, guiding=True, progress=False).stats[
        "guiding"
    ]
    assert not g["adjoint_roulette"] and g["split_paths"] == 0


def _doorway_share(guide: object, point: tuple[float, float, float], n: int = 20000) -> float:
    """The share of the guide's directions at a dark-room point of the door scene that cross the
    doorway (x in [1.55, 2.45], y < 2 on the wall's plane z = 4)."""
    rng = np.random.default_rng(0)
    points = np.tile(np.array(point, dtype=float), (n, 1))
    d = guide.sample(points, rng.random((n, 2)))  # type: ignore[attr-defined]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (4.0 - points[:, 2]) / d[:, 2]
    hit = points + t[:, None] * d
    return float(((t > 0) & (hit[:, 0] > 1.55) & (hit[:, 0] < 2.45) & (hit[:, 1] < 2)).mean())


def test_training_plays_adjoint_roulette_and_still_learns_the_doorway(door: dualight.Scene) -> None:
    """Training iterations after the first play adjoint-driven roulette and splitting (their
    samples are kept in the image), recording each split branch's radiance on its own branch:
    the guide changes, and from the dark room's floor it still sends more than 4 times the share
    of directions a uniform direction would (about 0.02) through the doorway to the lit room
    (0.15 to 0.38 measured)."""
    guides = {
        rr: dualight.train_guide(
            door, "radiance", spp=1024, seed=1, guiding={"adjoint_roulette": rr}
        )
        for rr in (True, False)
    }
    points = np.random.default_rng(1).random((200, 3)) * (4.0, 2.5, 4.0)
    up = np.tile([0.0, 1.0, 0.0], (200, 1))
    assert not np.array_equal(guides[True].pdf(points, up), guides[False].pdf(points, up))
    for guide in guides.values():
        for point in ((2.5, 0.0, 2.0), (3.0, 0.0, 1.0)):
            assert _doorway_share(guide, point) > 0.08


@pytest.mark.usefixtures("ctrl_c_raises")
@pytest.mark.parametrize("transport", ["radiance", "importance"])
def test_ctrl_c_stops_training_within_half_a_second(door: dualight.Scene, transport: str) -> None:
    caught, latency = interrupted(
        lambda: dualight.train_guide(door, transport, spp=1 << 16, guiding={"training": 0.9}), 0.3
    )
    assert latency < 0.5
    assert hasattr(caught, "partial_result")


@pytest.mark.usefixtures("ctrl_c_raises")
@pytest.mark.parametrize("method", ["path", "light", "bdpt"])
def test_ctrl_c_during_training_keeps_the_last_iteration_image(
    door: dualight.Scene, method: str
) -> None:
    """Interrupted while training, a guided render stops within 0.5 s and returns the last
    finished training iteration's image (unbiased on its own), not an empty one."""
    caught, latency = interrupted(
        lambda: dualight.render(
            door, method, spp=1 << 16, guiding={"training": 0.9}, progress=False
        ),
        0.5,
    )
    assert latency < 0.5
    image = caught.partial_result  # type: ignore[attr-defined]
    g = image.stats["guiding"]
    # Guided BDPT is interrupted while training its radiance guide (the first): the path
    # tracer's last iteration.
    guide = g["radiance"] if method == "bdpt" else g
    assert image.stats["interrupted"] and guide["iterations"] >= 1
    assert image.stats["spp"] == 1 << (guide["iterations"] - 1)  # the last finished iteration's
    assert float(np.asarray(image).mean()) > 0.0
    assert image.stats["seconds"] == pytest.approx(g["training_seconds"])


def test_a_progress_callback_error_reaches_the_caller(door: dualight.Scene) -> None:
    class Stop(Exception):
        pass

    def progress(done: int, total: int) -> None:
        raise Stop

    with pytest.raises(Stop):
        dualight.render(door, "path", spp=1 << 14, guiding=True, progress=progress)


def test_bad_guiding_input_is_named(cornell: dualight.Scene) -> None:
    with pytest.raises(ValueError, match="guiding applies to method 'path', 'light', 'bdpt' only"):
        dualight.render(cornell, "pssmlt", spp=4, guiding=True, progress=False)
    with pytest.raises(TypeError, match="unknown guiding option 'trainig'"):
        dualight.render(cornell, "path", spp=4, guiding={"trainig": 0.5}, progress=False)
    with pytest.raises(TypeError, match="guiding must be True, False or a dict"):
        dualight.render(cornell, "path", spp=4, guiding="yes", progress=False)  # type: ignore[arg-type]
    for key, value in (
        ("training", 1.0),
        ("training", 0.0),
        ("bsdf_fraction", 1.5),
        ("rho", 0.0),
        ("spatial_threshold", 0),
        ("max_records", 1 << 30),
        ("keep_iterations", 65),
        ("keep_iterations", -1),
        ("training", float("nan")),
    ):
        with pytest.raises(ValueError, match=f"guide_{key}"):
            dualight.render(cornell, "light", spp=4, guiding={key: value}, progress=False)
    with pytest.raises(ValueError, match="transport must be"):
        dualight.train_guide(cornell, "radiosity")  # type: ignore[arg-type]
    from concurrent.futures import ThreadPoolExecutor

    with (
        ThreadPoolExecutor(1) as pool,
        pytest.raises(ValueError, match="guiding is not supported with executor"),
    ):
        dualight.render(cornell, "path", spp=16, guiding=True, executor=pool, progress=False)


@pytest.fixture(scope="module")
def cornell_solution(cornell: dualight.Scene) -> dualight.radiosity.Solution:
    return dualight.radiosity.solve(cornell, "gauss_seidel", max_edge=110.0)


def test_radiance_records_of_a_solution_point_at_the_light(
    cornell: dualight.Scene, cornell_solution: dualight.radiosity.Solution
) -> None:
    """Seeded from radiosity, the radiance guide at floor points favours the ceiling light: its
    density towards the light's centre (median over 16 points) is far above the cosine lobe's
    (at most 1 / pi). Control: records of a solution whose every patch has the same radiosity
    (no light to point at) do not favour it."""
    lo, hi = (np.asarray(b) for b in cornell.bounds())
    rng = np.random.default_rng(1)
    n = 16
    floor = np.stack(
        [rng.uniform(100, 450, n), np.full(n, lo[1] + 1e-3), rng.uniform(100, 450, n)], axis=1
    )
    light = np.array([(lo[0] + hi[0]) / 2, hi[1] - 1.0, (lo[2] + hi[2]) / 2])
    to_light = (light - floor) / np.linalg.norm(light - floor, axis=1)[:, None]

    def median_density(solution: dualight.radiosity.Solution) -> float:
        records = dualight.guiding.solution_records(solution, "radiance")
        guide = dualight._core.guide_from_records(cornell._compile(), records)
        return float(np.median(guide.pdf(floor.astype(np.float32), to_light.astype(np.float32))))

    assert median_density(cornell_solution) > 1.0
    flat = dataclasses.replace(cornell_solution, B=np.ones_like(cornell_solution.B))
    assert median_density(flat) < 1.0 / np.pi


def test_solution_records_skip_patches_that_see_nothing(
    cornell_solution: dualight.radiosity.Solution,
) -> None:
    """Patches whose form-factor rows are empty (the last ones too, as for black patches whose
    rows were not computed) send no records; the others still do."""
    F = cornell_solution.form_factors
    indptr = np.asarray(F.indptr).copy()
    last = len(indptr) - 3  # the last two rows emptied
    cut = indptr[last]
    indptr[last:] = cut
    emptied = types.SimpleNamespace(
        indptr=indptr, indices=np.asarray(F.indices)[:cut], values=np.asarray(F.values)[:cut]
    )
    solution = dataclasses.replace(cornell_solution, form_factors=emptied)
    records = dualight.guiding.solution_records(solution, "radiance", records=4096)
    assert len(records) > 3000
    patches = cornell_solution.patches
    p = records[:, :3].astype(np.float64)

    def on_patch(k: int) -> np.ndarray:
        a, b, c = patches.vertices[patches.triangles[k]]
        n = np.cross(b - a, c - a)
        in_plane = np.abs((p - a) @ n) <= 1e-3 * np.linalg.norm(n)
        edges = [np.cross(v1 - v0, p - v0) @ n >= -1e-6 for v0, v1 in ((a, b), (b, c), (c, a))]
        return in_plane & edges[0] & edges[1] & edges[2]

    assert on_patch(0).any()  # control: a patch whose row was kept sends records
    assert not any(on_patch(k).any() for k in (last, last + 1))


@pytest.mark.parametrize("method", ["path", "light", "bdpt"])
def test_guide_from_a_solution_seeds_the_first_iteration(
    cornell: dualight.Scene, cornell_solution: dualight.radiosity.Solution, method: str
) -> None:
    """guide_from: the first training iteration samples the seeded guide(s), so the training's
    paths and records differ from an unseeded one's, and the stats say so."""
    options = {"training": 0.5}
    seeded = dualight.render(
        cornell,
        method,
        spp=8,
        seed=3,
        guiding=options,
        guide_from=cornell_solution,
        progress=False,
    )
    plain = dualight.render(cornell, method, spp=8, seed=3, guiding=options, progress=False)
    g, g0 = seeded.stats["guiding"], plain.stats["guiding"]
    assert g["seeding_seconds"] > 0.0
    guides = (g["radiance"], g["importance"]) if method == "bdpt" else (g,)
    unseeded = (g0["radiance"], g0["importance"]) if method == "bdpt" else (g0,)
    for guide, other in zip(guides, unseeded, strict=True):
        assert guide["seeded"] and not other["seeded"]
        assert guide["iterations"] == other["iterations"] >= 1
        # The seeded iterations' paths were sampled differently: so were their records.
        assert (guide["records"], guide["directional_nodes"]) != (
            other["records"],
            other["directional_nodes"],
        )


def test_bad_guide_from_input_is_named(
    cornell: dualight.Scene, cornell_solution: dualight.radiosity.Solution
) -> None:
    with pytest.raises(ValueError, match="guide_from seeds path guiding"):
        dualight.render(cornell, "path", spp=4, guide_from=cornell_solution, progress=False)
    with pytest.raises(TypeError, match="guide_from must be a dualight.radiosity.Solution"):
        dualight.render(cornell, "path", spp=4, guiding=True, guide_from="x", progress=False)
    other = dualight.radiosity.solve(scenes.rooms(2, resolution=(8, 8)), max_edge=2.0)
    with pytest.raises(ValueError, match="solution is of another scene"):
        dualight.render(cornell, "path", spp=4, guiding=True, guide_from=other)
    hierarchical = dualight.radiosity.solve(cornell, "hierarchical", max_edge=280.0)
    with pytest.raises(ValueError, match="form factors"):
        dualight.render(cornell, "path", spp=4, guiding=True, guide_from=hierarchical)
    primal = dualight.radiosity.solve(cornell, "gauss_seidel", max_edge=280.0, importance=False)
    with pytest.raises(ValueError, match="importance=True"):
        dualight.render(cornell, "light", spp=4, guiding=True, guide_from=primal)
    compiled = cornell._compile()
    good = dualight.guiding.solution_records(cornell_solution, "radiance", records=64)
    for rows, message in (
        (good[:, :6], r"shape \(N, 7\)"),
        (good[:0], "number 1 to"),
        (np.where(np.arange(7) == 6, np.nan, good), "finite"),
        (np.where(np.arange(7) == 6, -1.0, good), "values >= 0"),
        (np.where(np.arange(7) >= 3, 0.0, good), "non-zero directions"),
    ):
        with pytest.raises(ValueError, match=message):
            dualight._core.guide_from_records(compiled, rows.astype(np.float32))
    with pytest.raises(ValueError, match="bsdf_fraction"):
        dualight._core.guide_from_records(compiled, good, bsdf_fraction=1.5)
    for bad in (0, True, 1.5, 2**24 + 1):
        with pytest.raises(ValueError, match="records must be an int"):
            dualight.guiding.solution_records(cornell_solution, "radiance", records=bad)
