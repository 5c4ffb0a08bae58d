"""Primary-sample-space MLT over BDPT (Kelemen et al. 2002), with and without Kelemen's MIS of
large steps, its multiplexed form (MMLT, Hachisuka et al. 2014) with a mutation budget or a
time limit, and path-space MLT (Veach 1997), against the Mitsuba references of the Cornell box,
its caustic variant (glass and mirror spheres) and the door ajar. MLT pixels are correlated (a
chain splats into many pixels) and its brightness is set by estimates of b, so it is tested on
block means with variances from independent runs."""

from __future__ import annotations

import functools
import math
from statistics import NormalDist

import numpy as np
import pytest

import dualight
from dualight import metrics, scenes
from dualight.bench import REFERENCE_DIR as REFERENCES

RUNS, MPP, BLOCK = 12, 24, 8
# Cases whose runs are too skewed for a t-test of 12: MMLT's block in the caustic box's
# lower right corner (row 6, column 7) at 24 mutations per pixel has skew 1.6 over 96 seeds
# (mean x0.993 +- 0.017 of the reference, median x0.946, a tail to x1.61; at 96 mutations per
# pixel still skew 1.8), so 12 runs mostly lie below the mean and their t-statistic's tail at
# the Sidak-corrected level is far heavier than Student's: seeds 100 to 111 gave t = -10.8
# (issue 18, once the random streams were independent). The skew of a mean of n runs falls
# as 1 / sqrt(n): 36 runs.
RUNS_OF = {
    ("caustics", "mmlt"): 36,
    # Veach's plates with their direct light in the chains (CHAINS_TAKE_DIRECT_LIGHT): 12 runs
    # left the passing side at max |t| 5.0 to 5.6 and the control (light x0.9) at 7.1 to 7.4
    # against t* 6.4, both too close; 36 runs of 24 mutations per pixel cost about 10 s.
    **{("veach_mis", v): 36 for v in ("pssmlt", "mmlt", "mlt")},
}
ALPHA = 0.01
# A fixed-seed case gives the same numbers at every run: once it passes, its false alarm is
# paid. A time-limited one does a different amount of work at every run, so each run is a
# fresh draw at the test's level: over a hundred runs of the suite at 1 % one would fail for
# nothing (CI once saw max |t| 6.77 against 6.38 on the quiet machine's null distribution,
# whose max |t| had median 3.7 and a maximum of 5.5 over 19 sets of 12 runs). These cases are
# tested at 0.1 %; their negative control still fails by far (light x0.95: max |t| 48).
REDRAWN_ALPHA = 0.001
TIME_LIMITED = {"mmlt_time"}


def redrawn_alpha(variant: str) -> float:
    """The family-wise level of a variant's tests: REDRAWN_ALPHA when its work depends on
    the machine (a time limit), else ALPHA."""
    return REDRAWN_ALPHA if variant in TIME_LIMITED else ALPHA


SCENES = {
    "cornell": scenes.cornell_box,
    "caustics": functools.partial(scenes.cornell_box, variant="caustics"),
    "door": scenes.door_ajar,
    "glossy": functools.partial(scenes.cornell_box, variant="glossy"),
    "coated": functools.partial(scenes.cornell_box, variant="coated"),
    "smooth": functools.partial(scenes.cornell_box, variant="smooth"),
    "textured": functools.partial(scenes.cornell_box, variant="textured"),
    "point": functools.partial(scenes.cornell_box, variant="point"),
    "spot": functools.partial(scenes.cornell_box, variant="spot"),
    "sun": functools.partial(scenes.cornell_box, variant="sun"),
    "sky": functools.partial(scenes.cornell_box, variant="sky"),
    "envmap": functools.partial(scenes.cornell_box, variant="envmap"),
    "lamp": functools.partial(scenes.cornell_box, variant="lamp"),
    "veach_mis": scenes.veach_mis,
    "veach_bidir": scenes.veach_bidir,
    "door_glossy": functools.partial(scenes.door_ajar, variant="glossy"),
}


def _reference(scene: str = "cornell") -> tuple[np.ndarray, np.ndarray]:
    mean = dualight.Image.load(REFERENCES / f"{scene}_64_mean.exr")
    var = dualight.Image.load(REFERENCES / f"{scene}_64_var.exr")
    return np.asarray(mean), np.asarray(var)


# Variants under test: (method, options of render). "pssmlt" and "mmlt" use Kelemen's MIS of
# large steps (the default); "pssmlt_plain" the estimator without it; "mmlt_time" a time limit
# instead of a mutation budget (see _time_limit); "mlt" path-space MLT (Veach), "mlt_flat" with
# its flattened importance (chains aim at luminance over sqrt of the pixel brightness).
VARIANTS: dict[str, tuple[str, dict]] = {
    "pssmlt": ("pssmlt", {}),
    "pssmlt_plain": ("pssmlt", {"mlt": {"large_step_mis": False}}),
    "mmlt": ("mmlt", {}),
    "mmlt_time": ("mmlt", {}),
    "mlt": ("mlt", {}),
    "mlt_flat": ("mlt", {"mlt": {"importance": "flattened"}}),
}


# The negative control's light: 5 % dimmer, 10 % on the door, whose renders at this budget are
# noisier (light x0.95 passes there: max |t| 5.5 against 6.4).
CONTROL_LIGHT = {"cornell": 0.95, "caustics": 0.95, "door": 0.9}
# The glossy materials' scenes (issue 19) take a material's change as the block test's negative
# control: every roughness x1.2 (rough gold, frosted glass, rough-plastic floor); on the coated
# scene every albedo x0.95 (the plastic floor's base and the walls). Its IOR (the floor's coat
# and the bubble, the control of tests/test_pathspace_vs_mitsuba.py) moves the image by less
# than 12 MMLT runs of 24 mutations per pixel resolve: 1.5 -> 1.7 max |t| 3.6, -> 2.0 5.9,
# against t* 6.4. The textured box's control moves its textures along u by 1/32 (half a
# texel of the back wall). The smooth-shaded spheres' scene takes the albedo control too:
# rendering the spheres flat moves its 8x8 blocks by less than 12 runs of 24 mutations per
# pixel resolve (max |t| 5.0 against t* 6.4; on 4x4 blocks 5.2 against 7.4; the path tracer's
# and light tracer's tests in test_pathspace_vs_mitsuba.py resolve it).
CONTROL_MATERIAL = {
    "glossy": (("roughness_scale", 1.2),),
    "coated": (("reflectance_scale", 0.95),),
    "smooth": (("reflectance_scale", 0.95),),
    "textured": (("texture_shift", 1 / 32),),
    "point": (("light_scale", 0.95),),
    "spot": (("spot_cutoff", 45.0),),
    "sun": (("light_scale", 0.95),),
    "sky": (("light_scale", 0.95),),
    "envmap": (("env_rotation", 30.0),),
    "lamp": (("texture_shift", 0.5),),
    "veach_mis": (("light_scale", 0.9),),
    "veach_bidir": (("light_scale", 0.95),),
    "door_glossy": (("light_scale", 0.9),),
}

# A known defect (issue 18, found with the independent random streams): under a time limit
# MMLT's b_ci95 is too narrow. s^2/sigma^2 of b over 12 seeds was 2.01, 1.76, 2.05 in three
# sets and 3.09 in one (outside [0.13, 3.03]), against 0.83 and 0.89 with a mutation budget.
# The chi-square check fails at random then (about one run in ten); the other brightness
# checks still hold for this variant, and a failure of b's check alone is reported as xfail.
B_INTERVAL_TOO_NARROW = {
    "mmlt_time": "MMLT's b_ci95 under a time limit is about 1.4x too narrow (s^2/sigma^2 ~1.9)"
}

# Variants whose image luminance is not b's estimate: the flattened importance divides f* by a
# pixel factor, so the image sums b / factor over the chains' states.
NOT_B_NORMALISED = {"mlt_flat"}

# (scene, variant) pairs under test: every variant on the Cornell box; the three methods with
# their defaults, and MLT with its flattened importance, on the caustic box and the door.
# Marked long (make test-long), left out of make test for its time as issues 19 and 20 added
# scenes: the caustic box's and the door's flattened-importance runs, the Cornell box's
# PSSMLT without Kelemen's MIS (the flattened importance keeps its Cornell box run in make
# test; test_stats_and_options checks the plain estimator's weights against Kelemen's), the
# caustic box's MMLT (50 s: 36 runs for its skew; the caustic box keeps PSSMLT and MLT, MMLT
# the Cornell, glossy and coated boxes), the Cornell box's MMLT under a time limit (37 s: its
# 12 renders of twice the budgeted runs' time; the same code with a mutation budget stays,
# and test_stats_and_options checks that a time limit ends a render) and the door's MMLT
# (17 s; the door keeps PSSMLT and MLT), and the caustic box's PSSMLT (29 s, issue 23: the
# caustic box keeps MLT; PSSMLT keeps the Cornell box and the door).
CASES = [("cornell", v) for v in VARIANTS] + [
    (s, v) for s in ("caustics", "door") for v in ("pssmlt", "mmlt", "mlt", "mlt_flat")
]
LONG_CASES = {
    ("caustics", "mlt_flat"),
    ("cornell", "pssmlt_plain"),
    ("door", "mlt_flat"),
    ("caustics", "mmlt"),
    ("cornell", "mmlt_time"),
    ("door", "mmlt"),
    ("caustics", "pssmlt"),
}
# Glossy, coated, smooth-shaded and textured materials, and point, spot and textured area
# lights and emitters at infinity (issue 20), in the three Metropolis methods (path-space MLT
# refuses the coated box's smooth plastic floor: its Dirac coat over a diffuse base); block
# tests only. make test keeps one or two methods per scene and `long` marks the rest
# (make test-long), which run the same code as those kept: PSSMLT and MMLT share BDPT's
# subpaths and connections.
MATERIAL_CASES = [
    ("glossy", "mmlt"),
    ("coated", "mmlt"),
    ("textured", "mlt"),
    ("glossy", "mlt"),
    ("glossy", "pssmlt"),
    ("coated", "pssmlt"),
    ("smooth", "pssmlt"),
    ("smooth", "mmlt"),
    ("smooth", "mlt"),
    ("textured", "pssmlt"),
    ("textured", "mmlt"),
    ("point", "mmlt"),
    ("spot", "mmlt"),
    ("point", "pssmlt"),
    ("spot", "pssmlt"),
    ("point", "mlt"),
    ("spot", "mlt"),
    ("envmap", "mmlt"),
    ("sun", "mmlt"),
    ("sky", "mmlt"),
    ("sun", "pssmlt"),
    ("sky", "pssmlt"),
    ("envmap", "pssmlt"),
    ("envmap", "mlt"),
    ("sun", "mlt"),
    ("sky", "mlt"),
    ("lamp", "mlt"),
    ("lamp", "pssmlt"),
    ("lamp", "mmlt"),
    # Issue 21's classic scenes (Veach's plates, his bidirectional room, the glossy door),
    # every Metropolis method, long: make test compares their path tracer and BDPT with
    # Mitsuba (test_pathspace_vs_mitsuba.py), whose subpaths and connections these run.
    *[
        (s, v)
        for s in ("veach_mis", "veach_bidir", "door_glossy")
        for v in ("pssmlt", "mmlt", "mlt")
    ],
    ("door_glossy", "mlt_flat"),
]
# Emitters at infinity (issue 20): the open-top box under a sun, a sky and an environment map,
# all long for make test's time (its path, light and BDPT comparisons with Mitsuba and
# test_mlt_mutations' chains under the map stay in make test), as is the point-lit box's MMLT
# (15 s; make test ran 14:41 and 15:04 with it; its BDPT and light tracer stay), and the
# textured area light's three (18 to 26 s each; test_pathspace_vs_mitsuba.py checks its path
# and light tracers and BDPT, whose subpaths and connections PSSMLT and MMLT run, and
# test_mlt_mutations.py path-space MLT's bidirectional chains under it), and the glossy box's
# path-space MLT (21 s; test_mlt_mutations.py runs its bidirectional and lens-perturbation
# chains on the glossy box against BDPT, and make test keeps MLT on the textured box, whose
# aluminium block is glossy).
# The coated box's MMLT (28 s) is long too, for make test's time (issue 23): MMLT keeps the
# Cornell and glossy boxes, the coated box its path, light and BDPT comparisons.
LONG_MATERIAL_CASES = set(MATERIAL_CASES[3:]) | {("coated", "mmlt")}


# Scenes whose light is nearly all direct (2 segments), which the Metropolis methods render
# apart by BDPT by default (direct_spp): their chains would carry almost nothing and their
# block tests would test that BDPT pass again (on Veach's plates PSSMLT, MMLT and MLT gave the
# same t-statistics to the digit), so their chains take the direct light too (direct_spp=0).
CHAINS_TAKE_DIRECT_LIGHT = {"veach_mis"}


def _params(cases: list[tuple[str, str]], long: set[tuple[str, str]]) -> list:
    return [
        pytest.param(*c, id=f"{c[0]}-{c[1]}", marks=[pytest.mark.long] if c in long else [])
        for c in cases
    ]


@functools.cache
def _runs(
    variant: str,
    light_scale: float = 1.0,
    scene_name: str = "cornell",
    change: tuple[tuple[str, float], ...] = (),
) -> list[dualight.Image]:
    method, kw = VARIANTS[variant]
    if scene_name in CHAINS_TAKE_DIRECT_LIGHT:
        kw = {**kw, "mlt": {**kw.get("mlt", {}), "direct_spp": 0}}
    budget = (
        {"spp": None, "time_limit": _time_limit()}
        if variant == "mmlt_time"
        else {"mutations_per_pixel": MPP}
    )
    scene = SCENES[scene_name](resolution=(64, 64), light_scale=light_scale, **dict(change))
    return [
        dualight.render(scene, method, max_depth=8, seed=100 + i, progress=False, **budget, **kw)
        for i in range(RUNS_OF.get((scene_name, variant), RUNS))
    ]


def _time_limit() -> float:
    """Twice what the MMLT renders of MPP mutations per pixel took on this machine just now:
    most of that is the bootstrap and the direct light (the same here), so the chains get
    about half the time, many times MPP mutations per pixel on a quiet machine and fewer under
    load, when the renders' spread (which the block test measures) grows."""
    return 2.0 * float(np.mean([r.stats["seconds"] for r in _runs("mmlt")]))


def _block_test(
    runs: list[dualight.Image], scene: str = "cornell", alpha: float = ALPHA
) -> tuple[float, float, float]:
    """t-test of the runs' block means against the reference's, the runs' variance measured
    from their spread (so correlation between pixels and the error of b count), with
    Student's t for len(runs) - 1 degrees of freedom (the reference's own variance is 50x
    smaller) and a Sidak-corrected level over blocks and channels. The variance has
    metrics.welch_test's floor (1e-12): blocks that every run and the reference render
    exactly alike (a constant sky seen directly, nothing seen at all) have none, and 0 / 0
    failed them as NaN.
    Returns (fraction of blocks passing, largest |t|, critical value)."""
    ref, ref_var = _reference(scene)
    blocks = np.array([metrics.block_mean(np.asarray(r), BLOCK) for r in runs])
    mean = blocks.mean(axis=0)
    var_of_mean = blocks.var(axis=0, ddof=1) / len(runs)
    ref_blocks = metrics.block_mean(ref, BLOCK)
    ref_block_var = metrics.block_mean(ref_var, BLOCK) / BLOCK**2
    t = np.abs(mean - ref_blocks) / np.sqrt(var_of_mean + ref_block_var + 1e-12)
    alpha_per_test = -math.expm1(math.log1p(-alpha) / t.size)
    critical = metrics.student_t_critical(len(runs) - 1, alpha_per_test)
    passed = np.all(t < critical, axis=2)
    return float(passed.mean()), float(t.max()), critical


@pytest.fixture(
    params=[
        pytest.param(c, id=f"{c[0]}-{c[1]}", marks=[pytest.mark.long] if c in LONG_CASES else [])
        for c in CASES
    ]
)
def case(request) -> tuple[str, str]:
    return request.param


@pytest.mark.parametrize(("scene", "variant"), _params(MATERIAL_CASES, LONG_MATERIAL_CASES))
def test_glossy_materials_block_means_match_mitsuba(scene: str, variant: str) -> None:
    runs = _runs(variant, scene_name=scene)
    passed, t_max, critical = _block_test(runs, scene, redrawn_alpha(variant))
    print(
        f"\n{scene} {variant} {len(runs)} runs, {BLOCK}x{BLOCK} blocks: {100 * passed:.2f}% "
        f"pass, max |t| {t_max:.2f} vs t* {critical:.2f}"
    )
    assert passed >= 0.9975
    change = CONTROL_MATERIAL[scene]
    other = tuple((k, v) for k, v in change if k != "light_scale")
    light_scale = dict(change).get("light_scale", 1.0)
    wrong, t_wrong, _ = _block_test(
        _runs(variant, light_scale, scene, other), scene, redrawn_alpha(variant)
    )
    print(f"{dict(change)}: {100 * wrong:.2f}% pass, max |t| {t_wrong:.2f}")
    assert wrong < 0.9975


def test_block_means_match_mitsuba_and_a_dimmer_light_fails(case: tuple[str, str]) -> None:
    scene, variant = case
    runs = _runs(variant, scene_name=scene)
    passed, t_max, critical = _block_test(runs, scene, redrawn_alpha(variant))
    mpp = np.mean([r.stats["mutations"] for r in runs]) / 64**2
    print(
        f"\n{scene} {variant} {len(runs)} runs x {mpp:.0f} mutations/pixel, "
        f"{BLOCK}x{BLOCK} blocks: {100 * passed:.2f}% pass, "
        f"max |t| {t_max:.2f} vs t* {critical:.2f}"
    )
    assert passed >= 0.9975
    dim = CONTROL_LIGHT[scene]
    wrong, t_wrong, _ = _block_test(_runs(variant, dim, scene), scene, redrawn_alpha(variant))
    print(f"light x{dim}: {100 * wrong:.2f}% pass, max |t| {t_wrong:.2f}")
    assert wrong < 0.9975


def _chi2_quantile(dof: int, p: float) -> float:
    """Wilson and Hilferty's approximation of the chi-square quantile (relative error under
    1 % at 11 degrees of freedom in the tails used here)."""
    z = NormalDist().inv_cdf(p)
    k = 2.0 / (9.0 * dof)
    return dof * (1.0 - k + z * math.sqrt(k)) ** 3


def _brightness_checks(runs: list[dualight.Image], scene: str, variant: str) -> dict[str, bool]:
    """What the runs' brightness must satisfy, each at level ALPHA (or redrawn_alpha):
    * b's interval is honest: the spread of b over the seeds against the b_ci95 each run
      reports, s^2 / sigma^2 ~ chi^2(n - 1) / (n - 1);
    * the image's brightness is unbiased: the seeds' mean within the Student-t interval of
      their own spread, and that interval narrow enough to see the negative control's
      dimming (half its width under half the dimming, so a light dimmer by that much falls
      outside). A fixed bound (0.5 %, before issue 18) demanded more than the seeds' spread
      allows where one seed's mean spreads by several per cent (the door with MLT's
      flattened importance: se 1.1 % over 12 seeds).
    An image's brightness is not b alone: the direct light (rendered apart by BDPT) and, with
    Kelemen's MIS, the Metropolis layer's share of each splat carry errors b's interval leaves
    out, so the image is judged by the seeds' spread, b by its own interval."""
    ref, _ = _reference(scene)
    alpha = redrawn_alpha(variant)
    ratios = np.array([float(np.mean(r)) / float(ref.mean()) for r in runs])
    b = np.array([r.stats["b"] for r in runs])
    b_sigma = np.array([r.stats["b_ci95"] / 1.96 for r in runs])
    n = len(runs)
    spread = b.var(ddof=1) / np.mean(b_sigma**2)
    low, high = (_chi2_quantile(n - 1, q) / (n - 1) for q in (alpha / 2, 1 - alpha / 2))
    se = ratios.std(ddof=1) / math.sqrt(n)
    t_star = metrics.student_t_critical(n - 1, alpha)
    print(
        f"\n{scene} {variant} image mean / reference over {n} seeds: {np.round(ratios, 4)} "
        f"(mean {ratios.mean():.4f}, se {se:.4f}); b's spread / its interval: s^2/sigma^2 "
        f"{spread:.2f} in [{low:.2f}, {high:.2f}]"
    )
    checks = {
        "mean within its interval": abs(ratios.mean() - 1.0) < t_star * se,
        "interval sees the control": t_star * se < 0.5 * (1.0 - CONTROL_LIGHT[scene]),
    }
    if variant not in NOT_B_NORMALISED:
        checks["b's interval honest"] = bool(low < spread < high)
    return checks


def test_brightness_agrees_with_the_reference_and_b_interval_is_honest(
    case: tuple[str, str],
) -> None:
    scene, variant = case
    checks = _brightness_checks(_runs(variant, scene_name=scene), scene, variant)
    failed = {k for k, ok in checks.items() if not ok}
    if variant in B_INTERVAL_TOO_NARROW and failed == {"b's interval honest"}:
        pytest.xfail(B_INTERVAL_TOO_NARROW[variant])
    assert all(checks.values()), checks
    # The negative control: the block test's dimmer light fails the brightness.
    dim = _brightness_checks(_runs(variant, CONTROL_LIGHT[scene], scene), scene, variant)
    assert not dim["mean within its interval"], dim


def test_stats_and_options() -> None:
    image = _runs("pssmlt")[0]
    s = image.stats
    assert image.variance is None
    assert s["method"] == "pssmlt" and s["mutations"] == 64 * 64 * MPP and s["large_step_mis"]
    assert 0.0 < s["large_step_acceptance_rate"] < s["small_step_acceptance_rate"] < 1.0
    assert s["b"] > 0 and 0 < s["b_ci95"] < 0.1 * s["b"]
    assert s["b_samples"] > 100000 and s["invalid_samples"] == 0
    assert s["b_per_depth"] == [] and s["b_per_depth_ci95"] == []
    # MMLT: b_d of the chains' lengths (3..8; 1 and 2 are the direct light), refined by large
    # steps, summing to b; the mutations allocated by the bootstrap's b_d (largest
    # remainders: each length's share rounded on its own was up to 3 off) add up to the budget.
    m = _runs("mmlt")[0].stats
    b_d, ci_d = np.array(m["b_per_depth"]), np.array(m["b_per_depth_ci95"])
    assert len(b_d) == len(ci_d) == 9 and np.all(b_d[:3] == 0) and np.all(ci_d[:3] == 0)
    assert np.all(b_d[3:] > 0) and np.all((0 < ci_d[3:]) & (ci_d[3:] < 0.1 * b_d[3:]))
    assert np.all(np.diff(b_d[3:]) < 0)  # every bounce loses light
    assert math.isclose(b_d.sum(), m["b"], rel_tol=1e-12)
    assert math.isclose(np.sqrt(np.sum(ci_d**2)), m["b_ci95"], rel_tol=1e-9)
    assert m["b_samples"] == 6 * 100000 + m["large_steps"]
    assert m["mutations"] == 64 * 64 * MPP
    per_depth = m["mutations_per_depth"]
    assert sum(per_depth) == m["mutations"] and per_depth[:3] == [0, 0, 0]
    assert np.all(np.diff(per_depth[3:]) < 0) and per_depth[-1] > 0
    assert not m["time_limited"]
    scene = scenes.cornell_box(resolution=(16, 16))
    timed = dualight.render(scene, "mmlt", spp=None, time_limit=0.5, max_depth=5, progress=False)
    assert timed.stats["time_limited"] and timed.stats["mutations"] > 0
    one = dualight.render(scene, "pssmlt", mutations_per_pixel=4, seed=3, threads=1, progress=False)
    two = dualight.render(scene, "pssmlt", mutations_per_pixel=4, seed=3, threads=2, progress=False)
    np.testing.assert_array_equal(np.asarray(one), np.asarray(two))
    with pytest.raises(ValueError, match="pssmlt"):
        dualight.render(scene, "bdpt", mutations_per_pixel=4, progress=False)
    with pytest.raises(ValueError, match="bounded max_depth"):
        dualight.render(scene, "mmlt", mutations_per_pixel=4, progress=False)
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
    # Without large steps Kelemen's MIS weights are the plain estimator's.
    for method in ("pssmlt", "mmlt"):
        mis, plain = (
            dualight.render(
                scene,
                method,
                mutations_per_pixel=4,
                max_depth=5,
                progress=False,
                mlt={"large_step_probability": 0.0, "bootstrap": 4000, "large_step_mis": on},
            )
            for on in (True, False)
        )
        np.testing.assert_allclose(np.asarray(mis), np.asarray(plain), rtol=1e-5, atol=1e-7)
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
