"""Numerical-stability stress suite (issue 7, item 3).

Every test is marked ``stress`` (``pytest -m stress`` runs the suite alone); the longer ones
are also ``slow``: the radiosity solvers at rho = 0.9 and 0.999 (0.99 and 0.9999 are in the fast
subset). ``make test`` runs everything; ``make test-fast`` (``-m "not slow and not mitsuba"``)
the fast subset. Measured on 2 shared cores: fast subset 40 s, slow part 7 s.

Cases: radiosity with reflectance up to 0.9999 (every solver converges or says it did not, the
furnace value and the bookkeeping of bounces hold); the Cornell box scaled by 1e-5 and 1e5; a very
bright small light (1e8); sliver and near-zero-area (but valid) triangles; coplanar overlapping
surfaces; the camera inside closed geometry and on a wall; nearly grazing rays. Methods: path,
light, bdpt, mlt (32 x 32, few samples) and the radiosity solvers. Every image and solution is
checked for NaN and Inf, and energy conservation where it must hold.

How images are compared (``_agree``): the renders are independent Monte Carlo estimates (a
scaled scene takes other float roundings, so even the same seed gives other paths), so equality
means equality within noise:

* per 4 x 4 block, Welch's two-sample test on the block means with the renders' own per-pixel
  variances (``dualight.metrics.welch_test``, Sidak-corrected alpha 0.01 over the blocks); at
  least 98 % of blocks must pass (at 64 blocks, one unlucky block is allowed);
* the image means agree within 5 standard errors (pixels taken as independent; light tracing
  correlates few of them).

Each comparison has a negative control: the same comparison against the same scene with a 10 %
dimmer light must fail it (``_differ``), so a test that passes is a test that could fail. MLT
has no per-pixel variance; there the image means must agree within 5 % (chains of 16 x 32 x 32
x 8 mutations normalised by a 4,000-sample bootstrap: measured ratios 0.977 to 1.023 over
the cases here), and a 20 %
dimmer light must fall outside.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import dualight
from dualight import metrics, scenes
from dualight.radiosity import ConvergenceWarning, PatchMesh, form_factors, solve

pytestmark = pytest.mark.stress

RES = (32, 32)
SPP = {"path": 64, "light": 64, "bdpt": 32}
MLT = {"chains": 16, "bootstrap": 4000, "direct_spp": 8}
METHODS = ["path", "light", "bdpt", "mlt"]


# helpers --------------------------------------------------------------------------------------
def _render(scene: dualight.Scene, method: str, *, seed: int = 1, **kw) -> dualight.Image:
    kw.setdefault("max_depth", 6)
    if method == "mlt":
        kw.setdefault("mutations_per_pixel", 8)
        kw.setdefault("mlt", MLT)
    else:
        kw.setdefault("spp", SPP[method])
    image = dualight.render(scene, method, seed=seed, progress=False, **kw)
    _assert_finite(image)
    return image


def _assert_finite(image: dualight.Image) -> None:
    pixels = np.asarray(image)
    assert np.isfinite(pixels).all(), f"{np.sum(~np.isfinite(pixels))} non-finite pixels"
    assert (pixels >= 0).all(), "negative radiance"
    if image.variance is not None:
        assert np.isfinite(image.variance).all(), "non-finite variance"


def _mean_z(a: dualight.Image, b: dualight.Image) -> float:
    n = np.asarray(a).size
    sigma = math.sqrt(float(np.sum(a.variance, dtype=np.float64) + np.sum(b.variance))) / n
    return abs(float(np.mean(a, dtype=np.float64)) - float(np.mean(b, dtype=np.float64))) / sigma


def _agree(a: dualight.Image, b: dualight.Image) -> tuple[bool, str]:
    """Equal within noise (see the module docstring); returns (verdict, numbers)."""
    if a.variance is None:  # MLT
        ratio = float(np.mean(a, dtype=np.float64)) / float(np.mean(b, dtype=np.float64))
        return abs(ratio - 1) < 0.05, f"mean ratio {ratio:.4f}"
    welch = metrics.welch_test(a, a.variance, b, b.variance, block=4)
    z = _mean_z(a, b)
    return (
        welch.pass_fraction >= 0.98 and z < 5,
        f"blocks {welch.pass_fraction:.3f}, mean z {z:.2f}",
    )


def _check_equal_with_control(
    method: str, build, reference: dualight.Image, dim_reference: dualight.Image
) -> str:
    image = _render(build(), method)
    ok, numbers = _agree(image, reference)
    assert ok, f"{method}: differs from the unchanged scene: {numbers}"
    bad, control = _agree(image, dim_reference)
    assert not bad, f"{method}: the control (dimmer light) went unnoticed: {control}"
    return numbers


def _copy(scene: dualight.Scene, scale: float = 1.0, camera: dualight.Camera | None = None):
    """The scene scaled by ``scale`` about the origin (camera too): radiance is unchanged."""
    c = camera or scene.camera
    out = dualight.Scene(
        dualight.Camera(
            tuple(np.multiply(c.origin, scale)),
            tuple(np.multiply(c.target, scale)),
            c.up,
            c.fov,
            c.resolution,
        )
    )
    for m in scene.meshes:
        out.add_mesh(
            m.vertices * scale, m.triangles, emission=m.emission, material=m.material, name=m.name
        )
    return out


@pytest.fixture(scope="module")
def references() -> dict[tuple[str, float], dualight.Image]:
    """Each method on the plain Cornell box (32 x 32) and with a 10 % dimmer light (20 % for
    MLT), the controls. Seed 2 (the tests render with seed 1: independent noise)."""
    out = {}
    for method in METHODS:
        for light in (1.0, 0.8 if method == "mlt" else 0.9):
            scene = scenes.cornell_box(resolution=RES, light_scale=light)
            out[method, light] = _render(scene, method, seed=2)
    return out


def _refs(references, method: str) -> tuple[dualight.Image, dualight.Image]:
    return references[method, 1.0], references[method, 0.8 if method == "mlt" else 0.9]


# 1. Radiosity with rho up to 0.9999 -----------------------------------------------------------
@pytest.fixture(scope="module")
def furnace_system():
    """Form factors of the furnace cube at max_edge 0.25 (432 patches), shared by every rho
    (only the reflectance changes)."""
    scene = scenes.furnace(0.5, 1.0, (8, 8))
    patches = PatchMesh(scene, max_edge=0.25)
    return patches, form_factors(patches)


SOLVER_CASES = [
    pytest.param(rho, method, marks=[] if rho in (0.99, 0.9999) else pytest.mark.slow)
    for rho in (0.9, 0.99, 0.999, 0.9999)
    for method in ("direct", "jacobi", "gauss_seidel", "southwell")
]


@pytest.mark.parametrize(("rho", "method"), SOLVER_CASES)
def test_furnace_solvers_converge_or_say_so(furnace_system, rho: float, method: str) -> None:
    """Closed cube, every wall emitting Le = 1 and reflecting rho: B = pi / (1 - rho) everywhere.

    A solver either converges (relative residual <= tol = 1e-6) and then matches the furnace:
    the relative error is at most the residual (``|B - B*| <= |M^-1| r |E| = r B*``) plus the
    form factors' closure error (row sums of F are 1 to ~1e-10) amplified by 1 / (1 - rho): the
    bound is ``tol + 1e-7 + 1e-9 / (1 - rho)``. Measured: the direct solver's errors 1.7e-8,
    4.1e-8, 2.6e-7, 2.5e-6 for rho = 0.9 ... 0.9999 (closure: 4-60 times below the bound); the
    converged iterative solvers' up to 9.3e-7 (Jacobi, rho = 0.9: at most the residual, as the
    bound says, so a wrong solver fails). Or it stops at max_iter = 1000, warns
    (``ConvergenceWarning``) and says so in ``stats``; then B is finite, positive and below B*
    (gathering and shooting from zero only add light, K >= 0). The same holds for importance.
    Measured: at 0.99 Jacobi stops (residual 4.3e-5), at 0.999 and 0.9999 all iterative solvers
    stop; direct always converges.
    """
    patches, ff = furnace_system
    scene = scenes.furnace(rho, 1.0, (8, 8))
    exact = math.pi / (1.0 - rho)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ConvergenceWarning)
        sol = solve(
            scene, method, patches=PatchMesh(scene, max_edge=0.25), precomputed=ff, max_iter=1000
        )
    warned = any(issubclass(w.category, ConvergenceWarning) for w in caught)
    for name, x in (("B", sol.B), ("I", sol.I)):
        assert np.isfinite(x).all(), f"non-finite {name}"
        assert (x > 0).all(), f"{name} not positive"
    for side in ("radiosity", "importance"):
        assert math.isfinite(sol.stats[f"{side}_residual"])
    error = sol.B / exact - 1.0
    if sol.stats["converged"]:
        assert not warned
        bound = 1e-6 + 1e-7 + 1e-9 / (1.0 - rho)
        assert float(np.abs(error).max()) < bound, (float(np.abs(error).max()), bound)
        assert sol.duality_gap < 1e-4
    else:
        assert warned, "did not converge, and said nothing"
        assert method != "direct"
        assert float(error.max()) < 1e-6, "an iterative solver overshot the furnace value"
    # Control: the furnace value of a 1 % lower rho is far from every converged solution.
    if sol.stats["converged"]:
        wrong = math.pi / (1.0 - 0.99 * rho)
        assert float(np.abs(sol.B / wrong - 1.0).min()) > 1e-3


@pytest.mark.parametrize("rho", [0.99, 0.9999])
def test_jacobi_accounts_for_every_bounce(furnace_system, rho: float) -> None:
    """Energy bookkeeping when not converged: k Jacobi sweeps from zero hold exactly the light of
    paths of fewer than k bounces, ``B_k = pi (1 - rho^k) / (1 - rho)``, whatever the
    residual (to 1e-6 relative: closure 1e-10 summed over k <= 1000 bounces, then float
    rounding). Control: one bounce more or less is off by ``rho^k (1 - rho)`` relative to B*,
    4e-7 (rho = 0.99, k = 1000) and 9e-5 (0.9999): the 0.9999 control must fail the bound.
    """
    patches, ff = furnace_system
    scene = scenes.furnace(rho, 1.0, (8, 8))
    k = 1000
    with pytest.warns(ConvergenceWarning, match="jacobi did not converge"):
        sol = solve(
            scene,
            "jacobi",
            patches=PatchMesh(scene, max_edge=0.25),
            precomputed=ff,
            max_iter=k,
            importance=False,
        )
    assert sol.stats["radiosity_iterations"] == k
    relative = sol.B * (1.0 - rho) / math.pi
    assert float(np.abs(relative - (1.0 - rho**k)).max()) < 1e-6
    if rho > 0.999:
        assert float(np.abs(relative - (1.0 - rho ** (k + 1))).min()) > 1e-6


@pytest.mark.parametrize("rho", [0.99, 0.9999])
def test_hierarchical_furnace_says_it_did_not_converge(rho: float) -> None:
    """Hierarchical radiosity (BF oracle, epsilon 0.05, links capped at 200,000): finite,
    positive, never above the furnace value (2 % slack: links approximate F), and a
    ``ConvergenceWarning`` when it stops unconverged. Measured: the link cap stops refinement
    after 7 steps at B / B* = 0.876-0.884 (rho = 0.99) and 0.0208 (rho = 0.9999: its sweeps
    cannot propagate 10^4 bounces); with the default cap (2e7 links) the 0.9999 case takes
    50 s and 670 MB and still ends at 0.027-0.033."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ConvergenceWarning)
        sol = solve(
            scenes.furnace(rho, 1.0, (8, 8)),
            "hierarchical",
            oracle="bf",
            epsilon=0.05,
            shadow_rays=0,
            max_links=200_000,
        )
    exact = math.pi / (1.0 - rho)
    assert np.isfinite(sol.B).all() and (sol.B > 0).all()
    assert float(sol.B.max()) < 1.02 * exact
    warned = any(issubclass(w.category, ConvergenceWarning) for w in caught)
    assert sol.stats["converged"] or warned
    assert not (sol.stats["converged"] and warned)


# 1b. The furnace by the path-space methods at rho = 0.999 ---------------------------------------
FURNACE_BUDGET = {"path": {"spp": 16}, "light": {"spp": 64}, "bdpt": {"spp": 8}, "mlt": {}}


def _furnace_means(
    method: str, rho: float, emission: float, max_depth: int, seeds: int = 4
) -> list[float]:
    scene = scenes.furnace(rho, emission, (16, 16))
    return [
        float(
            np.mean(
                _render(scene, method, seed=seed, max_depth=max_depth, **FURNACE_BUDGET[method]),
                dtype=np.float64,
            )
        )
        for seed in range(seeds)
    ]


@pytest.mark.parametrize("method", METHODS)
def test_high_albedo_furnace_conserves_energy(method: str) -> None:
    """Furnace at rho = 0.999 with paths of at most 64 segments: the radiance everywhere is
    ``sum_{i<64} rho^i = (1 - rho^64) / (1 - rho) = 62.03`` (Le = 1). Long paths through RR
    at survival ~0.999, throughputs near 1 for 63 bounces: nothing may be lost or gained. The
    mean over 4 seeds must be within 2.5 % (measured spread of one seed's image mean: light
    tracing at 64 spp 1.5 %, others below; per-pixel variances understate it for light
    tracing and BDPT, whose splats correlate pixels, so the seeds' spread is used). Control: Le
    = 0.95 must be outside."""
    expected = (1 - 0.999**64) / (1 - 0.999)
    mean = float(np.mean(_furnace_means(method, 0.999, 1.0, 64)))
    assert abs(mean / expected - 1) < 0.025, (mean, expected)
    dim = float(np.mean(_furnace_means(method, 0.999, 0.95, 64)))
    assert abs(dim / expected - 1) > 0.025, (dim, expected)


@pytest.mark.parametrize("method", ["path", "light"])
def test_high_albedo_furnace_unbounded(method: str) -> None:
    """rho = 0.97 with unbounded paths (Russian roulette from vertex 5, survival
    ``min(max beta, 0.95)``): radiance Le / (1 - rho) = 33.3 everywhere. The image means of 16
    seeds must hold 1 / (1 - rho) within Student's t interval of their own spread (level
    0.1 %): one seed's mean spreads by 5.7 % for path tracing (heavy-tailed: seeds 0 to 15 from
    x0.96 to x1.18) and 2 % for light tracing, so the old check of 4 seeds within a fixed 5 %
    failed one time in ten (issue 18). Control: rho = 0.96 (radiance 25) fails the same test.

    Why not rho = 0.999 here: the survival cap 0.95 (Mitsuba's) makes the roulette weights grow
    as (rho / 0.95)^k, so for rho > sqrt(0.95) = 0.975 the estimator's variance is infinite
    and a finite run is far below the mean with high probability (measured at rho = 0.999,
    4 x 16 spp: path 465, light 182 against 1000). Unbiased, but useless there: bound
    ``max_depth`` (as the test above) for such furnaces."""
    t_star = metrics.student_t_critical(15, 1e-3)

    def t(rho: float) -> float:
        ratios = np.array(_furnace_means(method, rho, 1.0, -1, seeds=16)) * 0.03
        return abs(ratios.mean() - 1) / (ratios.std(ddof=1) / 4.0)

    assert t(0.97) < t_star, (t(0.97), t_star)
    assert t(0.96) > t_star


# 2. Scaled scenes ------------------------------------------------------------------------------
@pytest.mark.parametrize("scale", [1e-7, 1e-5, 1e5, 1e7])
@pytest.mark.parametrize("method", METHODS)
def test_scaled_cornell_box_renders_the_same_image(references, method: str, scale: float) -> None:
    """The Cornell box (about 556 units across) scaled by 1e-7 (5.6e-5 across) to 1e7 (5.6e9):
    radiance does not depend on scale, so the image must equal the unscaled one within noise (see
    the module docstring). Self-intersection (a ray offset not relative to the scene's size)
    would darken it (shadow acne) or leak light; a 10 % dimmer light must fail the same test.

    1e-7 and 1e7 were strict xfails (issue 18): at 1e-7 every point moved off its surface by a
    fixed 1/65536, a quarter of the scene (path mean x1.08); at 1e7 the walls' normals were 0
    (their cross products' squared lengths overflowed float32) and direct light failed (x0.57)."""
    base = scenes.cornell_box(resolution=RES)
    _check_equal_with_control(method, lambda: _copy(base, scale), *_refs(references, method))


@pytest.mark.parametrize("scale", [1e-9, 1e9])
@pytest.mark.parametrize("method", ["path", "light", "bdpt"])
def test_the_ends_of_the_scale_range_render_the_same_image(
    references, method: str, scale: float
) -> None:
    """The smallest and largest scenes dualight accepts (Scene.add_mesh refuses coordinates
    beyond 1e12, render a scene less than 1e-7 across): the Cornell box 5.6e-7 and 5.6e11 across
    renders right too. One step further it was measured wrong: at 1e-11 by the path tracer, at 1e10
    by light tracing and BDPT."""
    base = scenes.cornell_box(resolution=RES)
    _check_equal_with_control(method, lambda: _copy(base, scale), *_refs(references, method))


# 3. A very bright small light ------------------------------------------------------------------
def _small_light_box(radiance_scale: float, light_scale: float = 1.0) -> dualight.Scene:
    """The Cornell box with its light shrunk 100 x per side (area 1e-4 of it) about its centre,
    radiance times ``radiance_scale``."""
    box = scenes.cornell_box(resolution=RES)
    out = dualight.Scene(box.camera)
    for m in box.meshes:
        v = m.vertices
        if m.name == "light":
            centre = v.mean(axis=0)
            v = centre + (v - centre) / 100.0
        out.add_mesh(
            v,
            m.triangles,
            emission=tuple(radiance_scale * light_scale * e for e in m.emission),
            material=m.material,
            name=m.name,
        )
    return out


@pytest.mark.parametrize("method", ["path", "light", "bdpt"])
def test_very_bright_small_light_is_linear(method: str) -> None:
    """A light of 1e-4 the Cornell light's area and 1e8 times its radiance (about 2e9 W m^-2
    sr^-1). Light transport is linear in the emission, so image / 1e8 must equal the image of
    the same small light at radiance 1 within noise (the 1e8 one's variance scaled by 1e-16);
    nothing may overflow float32 (variance ~ 1e8^2 ...). Control: 10 % dimmer unit light."""
    bright = _render(_small_light_box(1e8), method, seed=1)
    unit = _render(_small_light_box(1.0), method, seed=2)
    dim = _render(_small_light_box(1.0, 0.9), method, seed=2)
    scaled = dualight.Image(np.asarray(bright) / 1e8, variance=bright.variance / 1e16)
    ok, numbers = _agree(scaled, unit)
    assert ok, numbers
    assert not _agree(scaled, dim)[0], "control (10 % dimmer) went unnoticed"


def test_very_bright_small_light_mlt() -> None:
    """MLT with the 1e8 light: finite, and image / 1e8 within 5 % of the unit light's mean."""
    bright = _render(_small_light_box(1e8), "mlt", seed=1)
    unit = _render(_small_light_box(1.0), "mlt", seed=2)
    dim = _render(_small_light_box(1.0, 0.8), "mlt", seed=2)
    scaled = dualight.Image(np.asarray(bright) / 1e8)
    ok, numbers = _agree(scaled, unit)
    assert ok, numbers
    assert not _agree(scaled, dim)[0]


# 4. Sliver and near-degenerate triangles ------------------------------------------------------
def _slivers(vertices: np.ndarray, triangles: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Each triangle split into ``n`` slivers fanning from its first vertex (same area)."""
    vs, fs = [], []
    for tri in triangles:
        a, b, c = vertices[tri]
        t = np.linspace(0.0, 1.0, n + 1)[:, None]
        edge = b + t * (c - b)
        base = sum(len(x) for x in vs)
        vs.append(np.vstack([a[None], edge]))
        fs.append(np.stack([np.full(n, base), base + 1 + np.arange(n), base + 2 + np.arange(n)], 1))
    return np.vstack(vs), np.vstack(fs)


def _sliver_box(light_scale: float = 1.0) -> dualight.Scene:
    """The Cornell box with its floor, back wall and light as 2 x 2000 slivers each (aspect
    ratio ~2000, angles ~3e-4 rad), plus near-zero-area triangles (height 1e-4 on 300-unit
    edges: area 1.5e-2, 1e-7 of a wall, and an emitting one of the light's radiance) floating in
    the box. Slivers keep the area, so the image must be unchanged; the tiny triangles carry
    ~1e-7 of the light's power and must not break light sampling (pdf ~ 1 / area)."""
    box = scenes.cornell_box(resolution=RES, light_scale=light_scale)
    out = dualight.Scene(box.camera)
    for m in box.meshes:
        v, f = m.vertices, m.triangles
        if m.name in ("floor", "back_wall", "light"):
            v, f = _slivers(v, f, 2000)
        out.add_mesh(v, f, emission=m.emission, material=m.material, name=m.name)
    thin = np.array([[100.0, 400.0, 300.0], [400.0, 400.0, 300.0], [250.0, 400.0001, 300.0]])
    out.add_mesh(thin, [[0, 1, 2]], reflectance=(0.5, 0.5, 0.5), name="thin")
    out.add_mesh(
        thin + [0, -50, 50],
        [[0, 2, 1]],
        emission=box.meshes[-1].emission,
        reflectance=(0, 0, 0),
        name="thin_light",
    )
    assert 0 < out.meshes[-1].areas[0] < 0.1
    return out


@pytest.mark.parametrize("method", METHODS)
def test_slivers_and_near_degenerate_triangles(references, method: str) -> None:
    """See ``_sliver_box``: equal to the plain Cornell box within noise; the control (10 %
    dimmer light) must fail. The tiny emitter adds ~1e-7 of the power: invisible in the test."""
    _check_equal_with_control(method, _sliver_box, *_refs(references, method))


# 5. Coplanar overlapping surfaces --------------------------------------------------------------
def _doubled_box() -> dualight.Scene:
    """Every non-emitting surface of the Cornell box twice (coincident, same material), the
    second copy with its faces wound the other way: z-fighting between identical surfaces must
    change nothing."""
    box = scenes.cornell_box(resolution=RES)
    out = _copy(box)
    for m in box.meshes:
        if not m.is_emitter:
            out.add_mesh(m.vertices, m.triangles[:, ::-1], material=m.material, name=m.name + "2")
    return out


@pytest.mark.parametrize("method", METHODS)
def test_coplanar_duplicated_surfaces(references, method: str) -> None:
    """Coincident duplicates of every wall and block: equal to the plain box within noise."""
    _check_equal_with_control(method, _doubled_box, *_refs(references, method))


@pytest.mark.parametrize("method", METHODS)
def test_coplanar_overlapping_different_materials_stay_finite(method: str) -> None:
    """A black floor overlapping (coplanar with) the floor, half its size: which one a ray hits
    is decided by rounding, so no exact image is expected; it must be finite and non-negative
    (checked by ``_render``)."""
    box = scenes.cornell_box(resolution=RES)
    scene = _copy(box)
    floor = box.meshes[0]
    scene.add_mesh(
        floor.vertices * [0.5, 1, 0.5] + [100, 0, 100],
        floor.triangles,
        reflectance=(0, 0, 0),
        name="black_floor",
    )
    _render(scene, method)


# 6. Camera inside geometry ---------------------------------------------------------------------
def _camera_in_a_cell(emission: tuple[float, float, float]) -> dualight.Scene:
    """The Cornell box with the camera inside a closed 20-unit cube (reflectance 0.5, inside
    emitting ``emission``) 300 units in front of the usual eye."""
    box = scenes.cornell_box(resolution=RES)
    cell = scenes.furnace(0.5, 1.0).meshes[0]
    centre = np.array(box.camera.origin) + [0, 0, 300]
    camera = dualight.Camera(tuple(centre), tuple(centre + [0, 0, 1]), (0, 1, 0), 40.0, RES)
    scene = _copy(box, camera=camera)
    scene.add_mesh(
        (cell.vertices - 0.5) * 20 + centre,
        cell.triangles,
        reflectance=(0.5, 0.5, 0.5),
        emission=emission,
        name="cell",
    )
    return scene


@pytest.mark.parametrize("method", METHODS)
def test_camera_inside_a_closed_box_sees_almost_nothing(method: str) -> None:
    """The camera inside a closed, non-emitting cube within the lit Cornell box: no light can
    reach it. Every pixel must be below 1e-8 of the image of the same cell emitting Le = 1
    inside (the control, which must be bright: mean > 0.1); MLT must not divide by its zero
    normalisation. Exactly zero is asked by the next test (BDPT leaks ~1e-10 there)."""
    black = _render(_camera_in_a_cell((0, 0, 0)), method)
    lit = _render(_camera_in_a_cell((1, 1, 1)), method)
    assert float(np.mean(lit)) > 0.1
    assert float(np.max(black)) < 1e-8 * float(np.mean(lit)), float(np.max(black))


@pytest.mark.parametrize("method", ["path", "light", "bdpt", "mlt"])
def test_camera_inside_a_closed_box_sees_exactly_black(method: str) -> None:
    """As above, but exactly 0: what a closed zero-thickness wall must give.

    BDPT was a strict xfail, leaking 1e-10 (issue 18) in two ways: a camera path leaving the
    edge where two walls meet started in the other wall's plane and Embree reported that wall
    at t = 0 (now re-traced past it: Scene::intersect), and its next connection ran along the
    wall with a cosine whose sign rounding decided (now no contribution: along_surface in
    connect.h; without it 1.9e-11 still leaked)."""
    black = _render(_camera_in_a_cell((0, 0, 0)), method)
    assert float(np.max(black)) == 0.0, float(np.max(black))


def _camera_at(z: float, light_scale: float = 1.0) -> dualight.Scene:
    box = scenes.cornell_box(resolution=RES, light_scale=light_scale)
    camera = dualight.Camera((278.0, 273.0, z), (278.0, 273.0, 0.0), (0, 1, 0), 60.0, RES)
    return _copy(box, camera=camera)


@pytest.mark.parametrize("method", METHODS)
def test_camera_on_a_wall(references, method: str) -> None:
    """The eye exactly in the plane of the back wall (z = 559.2), looking into the box: camera
    rays start on a surface. The image must be finite and equal (within noise, see the module
    docstring) to the one from 1e-3 units in front of the wall (rendered by the same method,
    seed 2); the control with a 20 % dimmer light must fail (this view sees little light, mean
    0.07: 10 % is at 4.6 standard errors on the mean for light tracing, too close to call).

    A strict xfail for path, BDPT and MLT before (issue 18): camera rays hit the wall at t = 0
    (the path tracer saw its back: mean 0 against 0.0697) while light tracing's connections
    stopped 1e-5 short of the eye. Now every estimator ignores surfaces within
    Scene::eye_clearance of the pinhole, rays from it and connections to it alike."""
    ref = _render(_camera_at(559.2 - 1e-3), method, seed=2)
    dim = _render(_camera_at(559.2 - 1e-3, 0.8), method, seed=2)
    _check_equal_with_control(method, lambda: _camera_at(559.2), ref, dim)


# 7. Nearly grazing rays ------------------------------------------------------------------------
def _grazing_plane(emission: float = 1.0) -> dualight.Scene:
    """A 40 x 2000 emitting strip (Le = ``emission``, facing up) seen from 1 unit above its near
    end, looking 1 degree down with a 4 degree field of view: the lower rows see the strip at
    grazing angles (cos 1e-3 to 0.05), the upper rows miss it. The strip is not much larger
    than what the camera sees, so light tracing's particles land in view."""
    angle = math.radians(1.0)
    camera = dualight.Camera(
        (0.0, 1.0, -1000.0),
        (0.0, 1.0 - math.sin(angle), -1000.0 + math.cos(angle)),
        (0, 1, 0),
        4.0,
        RES,
    )
    scene = dualight.Scene(camera)
    v = np.array([[-20, 0, -990], [20, 0, -990], [20, 0, 1000], [-20, 0, 1000]], float)
    scene.add_mesh(v, [[0, 3, 2, 1]], reflectance=(0, 0, 0), emission=(emission,) * 3)
    return scene


@pytest.mark.parametrize("method", ["path", "light", "bdpt"])
def test_grazing_view_of_an_emitter(method: str) -> None:
    """Emitter seen directly at grazing angles (``max_depth=1``): the path tracer's pixels are
    coverage fractions of Le = 1, so in [0, 1]; light tracing (particles splatted through
    cosines ~1e-6) and BDPT must give the same image within noise. Control: Le = 0.9."""
    reference = _render(_grazing_plane(), "path", seed=5, max_depth=1, spp=64)
    assert float(np.max(reference)) <= 1.0 + 1e-6
    assert float(np.mean(reference)) > 0.2
    kw = {"max_depth": 1, "spp": 64 if method != "light" else 256}
    image = _render(_grazing_plane(), method, seed=1, **kw)
    ok, numbers = _agree(image, reference)
    assert ok, numbers
    dim = _render(_grazing_plane(0.9), method, seed=1, **kw)
    assert not _agree(dim, reference)[0]


def _grazing_light_box(light_scale: float = 1.0) -> dualight.Scene:
    """A diffuse floor lit by a light 1 unit above it, its normal tilted 89.9 degrees away from
    the floor's: light arrives at grazing angles and leaves the light at grazing angles."""
    camera = dualight.Camera((0, 300, -600), (0, 0, 0), (0, 1, 0), 50.0, RES)
    scene = dualight.Scene(camera)
    floor = np.array([[-500, 0, -500], [500, 0, -500], [500, 0, 500], [-500, 0, 500]], float)
    scene.add_mesh(floor, [[0, 3, 2, 1]], reflectance=(0.7, 0.7, 0.7), name="floor")
    tilt = math.radians(89.9)
    half = 50.0
    # A square light at height 1 + ..., normal (0, cos tilt, sin tilt) pointing mostly along +z.
    n = np.array([0.0, math.cos(tilt), -math.sin(tilt)])
    u = np.array([1.0, 0.0, 0.0])
    w = np.cross(n, u)
    centre = np.array([0.0, 1.0 + half * abs(w[1]), 400.0])
    quad = np.array(
        [centre + half * (su * u + sw * w) for su, sw in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    )
    faces = np.array([[0, 1, 2, 3]])
    if np.dot(np.cross(quad[1] - quad[0], quad[2] - quad[0]), n) < 0:
        faces = faces[:, ::-1]
    scene.add_mesh(
        quad, faces, reflectance=(0, 0, 0), emission=(1e3 * light_scale,) * 3, name="light"
    )
    return scene


@pytest.mark.parametrize("method", ["light", "bdpt", "mlt"])
def test_grazing_illumination(method: str) -> None:
    """Light leaving an emitter and reaching a floor at cosines ~1e-3: every method agrees with
    the path tracer within noise; controls: a dimmer light.

    MLT's image carries no variance, and here it is the direct light alone (b = 0: only the
    floor reflects, so no path of three segments or more), rendered apart by BDPT at 8 spp: one
    seed's image mean spreads by 6 % (seeds 1 to 8: x0.92 to x1.09), so one seed within 5 %
    failed at random once the random streams were independent (issue 18). MLT is judged by 16
    seeds' mean within Student's t interval of their spread and the reference's error."""
    reference = _render(_grazing_light_box(), "path", seed=5, spp=256)
    assert float(np.mean(reference)) > 0
    if method == "mlt":
        assert _mlt_seeds_agree(_grazing_light_box(), reference)
        assert not _mlt_seeds_agree(_grazing_light_box(0.9), reference)
        return
    image = _render(_grazing_light_box(), method, seed=1)
    ok, numbers = _agree(image, reference)
    assert ok, numbers
    dim = _render(_grazing_light_box(0.9), method, seed=1)
    assert not _agree(dim, reference)[0]


def _mlt_seeds_agree(scene: dualight.Scene, reference: dualight.Image, seeds: int = 16) -> bool:
    """The image means of MLT with seeds 1 to ``seeds`` against the reference's: their mean
    within Student's t interval (level 0.1 %) of the seeds' spread and the reference's own
    standard error."""
    ratios = np.array(
        [
            float(np.mean(_render(scene, "mlt", seed=s), dtype=np.float64))
            for s in range(1, seeds + 1)
        ]
    )
    ref_mean = float(np.mean(reference, dtype=np.float64))
    ref_se = math.sqrt(float(np.sum(np.mean(reference.variance, axis=2), dtype=np.float64)))
    ref_se /= reference.shape[0] * reference.shape[1]
    ratios /= ref_mean
    se = math.sqrt(ratios.var(ddof=1) / seeds + (ref_se / ref_mean) ** 2)
    return abs(ratios.mean() - 1) < metrics.student_t_critical(seeds - 1, 1e-3) * se
