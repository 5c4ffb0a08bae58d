"""Radiosity and importance: the furnace's analytic answer, the solvers against each other and
against bounds derived from their tolerance, the duality <R, B> = <I, E>, the receiver against
the rendered picture, light leaks, non-convergence, bad input, Southwell's ambient term and the
three pictures.

Notation: M = I - diag(rho) F per channel, B solves M B = E (E = pi Le), I solves M^T I = R.
The iterative solvers stop at the relative residual max|b - M x| / max|b| <= tol.
"""

from __future__ import annotations

import math
import sys
import warnings

import numpy as np
import pytest

import dualight
from dualight import _core, scenes
from dualight.radiosity import (
    ConvergenceWarning,
    DirectSolver,
    PatchMesh,
    SouthwellSolver,
    form_factors,
    receiver,
    solve,
)

ITERATIVE = ("jacobi", "gauss_seidel", "southwell")
RESOLUTION = (32, 24)  # width, height: not square, so a transposed picture is caught


# Shared Cornell box system --------------------------------------------------------------------
@pytest.fixture(scope="module")
def cornell() -> tuple[dualight.Scene, PatchMesh, tuple]:
    """The Cornell box at max_edge 80 mm (1326 patches) and its form factors, computed once."""
    scene = scenes.cornell_box(resolution=RESOLUTION)
    patches = PatchMesh(scene, max_edge=80.0)
    ff = form_factors(patches, quadrature=3, shadow_rays=4, seed=0)
    return scene, patches, ff


@pytest.fixture(scope="module")
def cornell_direct(cornell) -> dualight.radiosity.Solution:
    scene, patches, ff = cornell
    return solve(scene, "direct", patches=patches, precomputed=ff)


def _csr(F: _core.FormFactors) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rows = np.repeat(np.arange(F.n), np.diff(np.asarray(F.indptr)).astype(np.int64))
    return rows, np.asarray(F.indices).astype(np.int64), np.asarray(F.values, dtype=np.float64)


def _residuals(sol: dualight.radiosity.Solution) -> tuple[np.ndarray, np.ndarray]:
    """E - M B and R - M^T I, computed here (numpy) from the CSR arrays, per channel."""
    rows, cols, vals = _csr(sol.form_factors)
    n, rho = sol.form_factors.n, sol.rho
    FB = np.stack(  # noqa: N806
        [np.bincount(rows, vals * sol.B[cols, c], minlength=n) for c in range(3)], axis=1
    )
    FtI = np.stack(  # noqa: N806 - (F^T (rho I))_j = sum_i F_ij rho_i I_i
        [np.bincount(cols, vals * rho[rows, c] * sol.I[rows, c], minlength=n) for c in range(3)],
        axis=1,
    )
    return sol.E - (sol.B - rho * FB), sol.R - (sol.I - FtI)


@pytest.fixture(scope="module")
def bounds(cornell) -> dict[str, float]:
    """How far a relative residual r can put a solution from the exact one.

    Primal: M^{-1} = sum_k (diag(rho) F)^k >= 0 and ||diag(rho) F||_inf = max_i rho_i s_i
    (s_i the row sums) < 1, so max|B - B*| <= r max|E| / (1 - max_i rho_i s_i).
    Dual: F is not exactly reciprocal (quadrature, stochastic visibility), so ||M^-T||_inf is
    taken as it is: M^-T >= 0, hence ||M^-T||_inf = max(M^-T 1), solved directly (and checked to
    be at least 1, the identity's share). max|I - I*| <= r max|R| ||M^-T||_inf.
    """
    _, patches, (F, _) = cornell
    system = _core.RadiositySystem(F, patches.reflectance, patches.areas)
    ones = np.ones((len(patches), 3))
    primal = DirectSolver(system, ones)
    primal.step()
    dual = DirectSolver(system, ones, dual=True, factors=primal.factors)
    dual.step()
    rho_s = float((patches.reflectance * np.asarray(F.row_sums())[:, None]).max())
    return {
        "rho_s": rho_s,
        "primal_a_priori": 1.0 / (1.0 - rho_s),
        "primal": float(primal.solution.max()),
        "dual": float(dual.solution.max()),
    }


# 8. Furnace -----------------------------------------------------------------------------------
@pytest.mark.parametrize("rho", [0.5, 0.9, 0.99, 0.999])
def test_furnace_direct_matches_analytic_radiosity(rho: float) -> None:
    # Closed cube, every wall emits Le = 1 and reflects rho: B = pi Le / (1 - rho) everywhere.
    # Measured worst relative errors (max_edge 0.25, 432 patches): 6.5e-9, 1.7e-8, 4.1e-8,
    # 2.6e-7 for rho = 0.5, 0.9, 0.99, 0.999 (closure is exact to float rounding).
    scene = scenes.furnace(rho, 1.0, resolution=(16, 16))
    sol = solve(scene, "direct", max_edge=0.25)
    exact = math.pi / (1.0 - rho)
    worst = float(np.abs(sol.B / exact - 1.0).max())
    assert worst < 1e-3, worst
    assert sol.stats["converged"] and sol.duality_gap < 1e-10
    # Negative control: 1 % less reflectance (same geometry, same form factors).
    wrong = scenes.furnace(0.99 * rho, 1.0, resolution=(16, 16))
    off = solve(
        wrong,
        "direct",
        patches=PatchMesh(wrong, max_edge=0.25),
        precomputed=(sol.form_factors, sol.stats["form_factors"]),
    )
    assert float(np.abs(off.B / exact - 1.0).min()) > 5e-3


# 9. Solvers against direct --------------------------------------------------------------------
def test_direct_solution_has_a_tiny_residual(cornell_direct) -> None:
    # Checked with an independent (numpy) product by M and M^T, not the library's residual.
    sol = cornell_direct
    rB, rI = _residuals(sol)  # noqa: N806
    assert np.abs(rB).max() <= 1e-12 * np.abs(sol.E).max()
    assert np.abs(rI).max() <= 1e-12 * np.abs(sol.R).max()
    assert sol.stats["radiosity_residual"] < 1e-12 and sol.stats["importance_residual"] < 1e-12


def test_error_bounds_are_consistent(bounds) -> None:
    # max(M^-1 1) may not exceed the a-priori 1 / (1 - max rho_i s_i); both are >= 1.
    assert 1.0 <= bounds["primal"] <= bounds["primal_a_priori"] * (1 + 1e-9)
    assert bounds["dual"] >= 1.0


@pytest.mark.parametrize("method", ITERATIVE)
def test_iterative_solvers_agree_with_direct(cornell, cornell_direct, bounds, method) -> None:
    # Measured at tol 1e-6, max error / (tol max|b|): B 2.27 (jacobi), 0.94 (gauss_seidel),
    # 0.88 (southwell) against the a-priori bound 8.8; I 2.71, 0.81, 1.95 against
    # max(M^-T 1) = 4.1.
    scene, patches, ff = cornell
    tol = 1e-6
    sol = solve(scene, method, tol=tol, patches=patches, precomputed=ff)
    ref = cornell_direct
    assert sol.stats["converged"], sol.stats
    err_B = np.abs(sol.B - ref.B).max()  # noqa: N806
    err_I = np.abs(sol.I - ref.I).max()  # noqa: N806
    assert err_B <= tol * np.abs(ref.E).max() * bounds["primal_a_priori"], err_B
    assert err_I <= tol * np.abs(ref.R).max() * bounds["dual"], err_I
    # The solvers' own residuals agree with an independent computation.
    rB, rI = _residuals(sol)  # noqa: N806
    assert np.abs(rB).max() / np.abs(sol.E).max() == pytest.approx(
        sol.stats["radiosity_residual"], rel=1e-6
    )
    assert np.abs(rI).max() / np.abs(sol.R).max() == pytest.approx(
        sol.stats["importance_residual"], rel=1e-6
    )
    assert sol.stats["radiosity_residual"] <= tol and sol.stats["importance_residual"] <= tol


def test_agreement_bound_is_tight_enough_to_see_a_one_percent_reflectance_error(
    cornell, cornell_direct, bounds
) -> None:
    # Negative control for the solver agreement: the same system with every reflectance 1 %
    # lower is more than 10 times as far from the reference as the bound at tol = 1e-6 allows
    # (measured: 0.058 against 5.1e-4).
    _, patches, ff = cornell
    darker = scenes.cornell_box(resolution=RESOLUTION, reflectance_scale=0.99)
    off = solve(
        darker,
        "direct",
        patches=PatchMesh(darker, max_edge=80.0),
        precomputed=ff,
        importance=False,
    )
    ref = cornell_direct
    assert np.abs(off.B - ref.B).max() > 10 * 1e-6 * np.abs(ref.E).max() * bounds["primal_a_priori"]


# 10. Duality ----------------------------------------------------------------------------------
def test_duality_with_direct(cornell_direct) -> None:
    sol = cornell_direct
    np.testing.assert_allclose(sol.measurement_primal, sol.measurement_dual, rtol=1e-10)
    assert sol.duality_gap < 1e-10
    assert np.all(sol.measurement_primal > 0)


@pytest.mark.parametrize("method", ITERATIVE)
def test_duality_gap_of_iterative_solvers(cornell, method) -> None:
    # For any B and I: <R, B> - <I, E> = <R - M^T I, B> - <I, E - M B> (since <M^T I, B> =
    # <I, M B>), so |gap| <= tol (max|R| sum|B| + max|E| sum|I|) per channel (146-370 tol
    # relative to the measurement here). Measured relative gaps at tol 1e-6: 21 tol (jacobi),
    # 6.9 tol (gauss_seidel), 14 tol (southwell): the rule of thumb 2 tol / (1 - max rho)
    # = 17.5 tol is not a bound (jacobi exceeds it).
    scene, patches, ff = cornell
    tol = 1e-6
    sol = solve(scene, method, tol=tol, patches=patches, precomputed=ff)
    gap = sol.measurement_primal - sol.measurement_dual
    rB, rI = _residuals(sol)  # noqa: N806
    identity = np.sum(rI * sol.B, axis=0) - np.sum(sol.I * rB, axis=0)
    np.testing.assert_allclose(gap, identity, rtol=1e-6, atol=1e-12 * sol.measurement_primal.max())
    bound = tol * (
        np.abs(sol.R).max() * np.abs(sol.B).sum(axis=0) + np.abs(sol.E).max() * np.abs(sol.I).sum(0)
    )
    assert np.all(np.abs(gap) <= bound), (gap, bound)
    assert sol.duality_gap < 1e-3  # and small in absolute terms


def test_measurement_is_the_mean_of_the_flat_picture(cornell, cornell_direct) -> None:
    # receiver() and render() must sample the camera alike (samples_per_axis, seed): then
    # <R, B> is exactly the mean pixel of the flat radiosity picture (up to float32 pixels).
    sol = cornell_direct
    measured = sol.measurement_primal
    same = np.asarray(sol.render(smooth=False, samples_per_axis=4, seed=0), dtype=np.float64)
    np.testing.assert_allclose(same.reshape(-1, 3).mean(axis=0), measured, rtol=1e-6)
    defaults = np.asarray(sol.render(smooth=False), dtype=np.float64)
    np.testing.assert_allclose(
        defaults.reshape(-1, 3).mean(axis=0),
        measured,
        rtol=1e-6,
        err_msg="render()'s default sampling differs from the receiver's",
    )
    # Negative control: other camera samples give another mean (measured: by 5e-4 to 6e-4).
    other = np.asarray(sol.render(smooth=False, samples_per_axis=4, seed=1), dtype=np.float64)
    assert np.all(np.abs(other.reshape(-1, 3).mean(axis=0) / measured - 1) > 1e-4)


# 11. Window receiver --------------------------------------------------------------------------
WINDOW = (8, 4, 20, 14)  # x0, y0, x1, y1, half-open


def test_window_receiver(cornell, cornell_direct) -> None:
    scene, patches, ff = cornell
    sol = solve(scene, "direct", window=WINDOW, patches=patches, precomputed=ff)
    x0, y0, x1, y1 = WINDOW
    prim, _ = _core.trace_camera_hits(
        patches._compile(), scene.camera._compile(), samples_per_axis=4, seed=0
    )
    in_window = np.zeros(len(patches), dtype=bool)
    hits = prim[y0:y1, x0:x1].reshape(-1)
    in_window[hits[hits >= 0]] = True
    R = sol.R[:, 0]  # noqa: N806
    assert np.all(R[~in_window] == 0.0)
    assert np.all(R[in_window] > 0.0)  # every patch hit in the window faces the camera here
    full = cornell_direct.R[:, 0]
    assert 0 < np.count_nonzero(R) < np.count_nonzero(full)
    assert np.all(full[R > 0] > 0)
    # The window's measurement is the mean of that window of the flat picture.
    picture = np.asarray(sol.render(smooth=False, samples_per_axis=4, seed=0), dtype=np.float64)
    window_mean = picture[y0:y1, x0:x1].reshape(-1, 3).mean(axis=0)
    np.testing.assert_allclose(window_mean, sol.measurement_primal, rtol=1e-6)
    # Negative control: the whole picture's mean fails that check in every channel (the
    # window is not the whole picture in disguise).
    whole_mean = picture.reshape(-1, 3).mean(axis=0)
    assert np.all(np.abs(whole_mean / sol.measurement_primal - 1) > 1e-6)
    assert sol.duality_gap < 1e-10
    # Receivers are additive over a partition of the image into windows.
    w, h = scene.camera.resolution
    halves = [receiver(patches, scene.camera, window=win) for win in ((0, 0, 16, h), (16, 0, w, h))]
    np.testing.assert_allclose(0.5 * (halves[0] + halves[1]), full, rtol=1e-12, atol=1e-15)


# 12. Light leaks ------------------------------------------------------------------------------
def _two_rooms() -> tuple[dualight.Scene, np.ndarray]:
    """Rooms A (0 <= x <= 1) and B (1 <= x <= 2), unit height and depth, each closed by six
    inward-facing quads, so the dividing wall x = 1 is two coincident quads, one per side,
    and floors, ceilings and front/back walls are split exactly at x = 1. A light hangs under
    room A's ceiling. Returns the scene and which meshes belong to room B."""
    camera = dualight.Camera(
        origin=(0.2, 0.5, 0.5), target=(1.0, 0.4, 0.6), fov=80, resolution=(16, 16)
    )
    scene = dualight.Scene(camera=camera)
    in_b = []
    faces = {
        "floor": [0, 4, 5, 1],
        "ceiling": [3, 2, 6, 7],
        "front": [0, 1, 2, 3],
        "back": [4, 7, 6, 5],
        "left": [0, 3, 7, 4],
        "right": [1, 5, 6, 2],
    }
    for room, (x0, x1) in (("A", (0.0, 1.0)), ("B", (1.0, 2.0))):
        corners = np.array(
            [[x0, 0, 0], [x1, 0, 0], [x1, 1, 0], [x0, 1, 0], [x0, 0, 1], [x1, 0, 1]]
            + [[x1, 1, 1], [x0, 1, 1]],
            dtype=np.float64,
        )
        centre = np.array([(x0 + x1) / 2, 0.5, 0.5])
        for name, f in faces.items():
            quad = corners[f]
            normal = np.cross(quad[1] - quad[0], quad[2] - quad[0])
            assert np.dot(normal, centre - quad.mean(axis=0)) > 0  # inward
            scene.add_mesh(quad, [[0, 1, 2, 3]], reflectance=(0.8, 0.8, 0.8), name=f"{room}_{name}")
            in_b.append(room == "B")
    light = np.array([[0.3, 0.99, 0.3], [0.7, 0.99, 0.3], [0.7, 0.99, 0.7], [0.3, 0.99, 0.7]])
    assert np.cross(light[1] - light[0], light[2] - light[0])[1] < 0  # faces down
    scene.add_mesh(light, [[0, 1, 2, 3]], reflectance=(0.5, 0.5, 0.5), emission=(5, 5, 5))
    in_b.append(False)
    return scene, np.array(in_b)


@pytest.fixture(scope="module")
def two_rooms() -> tuple[dualight.Scene, np.ndarray, PatchMesh]:
    scene, in_b = _two_rooms()
    return scene, in_b, PatchMesh(scene, max_edge=0.25)


def test_no_light_leaks_into_the_dark_room(two_rooms) -> None:
    scene, in_b, patches = two_rooms
    sol = solve(scene, "direct", patches=patches, shadow_rays=4, importance=False)
    room_b = in_b[patches.mesh_index]
    assert sol.B[~room_b].min() > 0  # room A is lit everywhere
    leaked = sol.B[room_b]
    lit = np.unique(patches.mesh_index[room_b][np.any(leaked > 0, axis=1)])
    assert np.all(leaked == 0.0), (
        f"{np.count_nonzero(np.any(leaked > 0, axis=1))} of {room_b.sum()} patches of room B "
        f"receive light (max B {leaked.max():.3g}, room A's mean {sol.B[~room_b].mean():.3g}); "
        f"meshes {[scene.meshes[m].name for m in lit]}"
    )


def test_without_shadow_rays_light_goes_through_the_wall(two_rooms) -> None:
    # Negative control: visibility is what keeps room B dark.
    scene, in_b, patches = two_rooms
    sol = solve(scene, "direct", patches=patches, shadow_rays=0, importance=False)
    room_b = in_b[patches.mesh_index]
    assert sol.B[room_b].max() > 0.1 * sol.B[~room_b].mean()


# 13. Non-convergence --------------------------------------------------------------------------
def test_non_convergence_is_reported() -> None:
    # rho = 1 in a closed box: M is singular, Jacobi cannot reach tol in 5 sweeps.
    scene = scenes.furnace(1.0, 1.0, resolution=(8, 8))
    with pytest.warns(ConvergenceWarning, match="jacobi did not converge"):
        sol = solve(scene, "jacobi", max_edge=0.5, max_iter=5)
    assert sol.stats["converged"] is False
    assert sol.stats["radiosity_converged"] is False
    assert sol.stats["radiosity_iterations"] == 5
    assert sol.stats["radiosity_residual"] > 1e-6
    # Control: with rho = 0.5 the same call converges, silently.
    with warnings.catch_warnings():
        warnings.simplefilter("error", ConvergenceWarning)
        ok = solve(scenes.furnace(0.5, 1.0, resolution=(8, 8)), "jacobi", max_edge=0.5)
    assert ok.stats["converged"] is True


# 14. Bad input --------------------------------------------------------------------------------
def _lit_square(camera: dualight.Camera | None) -> dualight.Scene:
    scene = dualight.Scene(camera=camera)
    scene.add_mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]], emission=(1, 1, 1))
    return scene


def test_unknown_method() -> None:
    with pytest.raises(ValueError, match="unknown method 'cholesky'.*direct"):
        solve(scenes.furnace(0.5, 1.0), "cholesky", max_edge=0.5)


def test_no_emitter() -> None:
    with pytest.raises(ValueError, match="no emitter"):
        solve(scenes.cornell_box(light_scale=0.0), "direct", max_edge=200.0)


def test_no_camera() -> None:
    with pytest.raises(ValueError, match="needs a camera"):
        solve(_lit_square(None), "direct", max_edge=0.5)
    camera = dualight.Camera(origin=(0.5, 0.5, 2), target=(0.5, 0.5, 0), resolution=(8, 8))
    assert solve(_lit_square(None), "direct", max_edge=0.5, camera=camera).camera == camera


@pytest.mark.parametrize("max_edge", [0.0, -1.0, float("nan"), float("inf")])
def test_non_positive_max_edge(max_edge: float) -> None:
    with pytest.raises(ValueError, match="max_edge must be a positive number"):
        solve(scenes.furnace(0.5, 1.0), "direct", max_edge=max_edge)


@pytest.mark.parametrize(
    "window", [(0, 0, 33, 24), (0, 0, 32, 25), (-1, 0, 8, 8), (5, 5, 5, 10), (10, 0, 4, 8)]
)
def test_window_outside_the_image(cornell, window) -> None:
    scene, patches, ff = cornell
    with pytest.raises(ValueError, match=r"window .* is not inside the \(32, 24\) image"):
        solve(scene, "direct", window=window, patches=patches, precomputed=ff)


@pytest.mark.parametrize(
    ("kwargs", "message"), [({"tol": 0.0}, "tol"), ({"max_iter": 0}, "max_iter")]
)
def test_bad_stopping_rule(cornell, kwargs, message) -> None:
    scene, patches, ff = cornell
    with pytest.raises(ValueError, match=message):
        solve(scene, "jacobi", patches=patches, precomputed=ff, **kwargs)


# 15. Southwell --------------------------------------------------------------------------------
def test_southwell_unshot_power_decreases_and_ambient_helps(cornell, cornell_direct) -> None:
    _, patches, (F, _) = cornell
    system = _core.RadiositySystem(F, patches.reflectance, patches.areas)
    E, A, rho = patches.emission, patches.areas, patches.reflectance  # noqa: N806
    shooter = SouthwellSolver(system, E, shots_per_step=10)
    power = [float(np.sum(A[:, None] * np.abs(shooter.unshot)))]
    for step in range(1, 41):
        shooter.step()
        assert shooter.shots == 10 * step
        assert np.all(shooter.ambient >= 0), shooter.ambient
        power.append(float(np.sum(A[:, None] * np.abs(shooter.unshot))))
    assert np.all(np.diff(power) < 0), power
    assert power[-1] < 0.5 * power[0]
    # Dual side: unshot importance sum |r_i| decreases too.
    R = cornell_direct.R  # noqa: N806
    dual = SouthwellSolver(system, R, dual=True, shots_per_step=10)
    unshot = [float(np.abs(dual.unshot).sum())]
    for _ in range(20):
        dual.step()
        assert np.all(dual.ambient >= 0)
        unshot.append(float(np.abs(dual.unshot).sum()))
    assert np.all(np.diff(unshot) < 0), unshot

    # Early on, x + rho * ambient is closer to the converged radiosity than x alone. Measured
    # (area-weighted RMS error): 3.18 -> 3.12 after 5 shots, 0.44 -> 0.27 after 20.
    def error(x: np.ndarray) -> float:
        return float(np.sqrt(np.sum(A[:, None] * (x - cornell_direct.B) ** 2) / (3 * A.sum())))

    for shots in (5, 20):
        early = SouthwellSolver(system, E, shots_per_step=shots)
        early.step()
        plain = error(early.solution)
        with_ambient = error(early.solution + rho * early.ambient)
        assert with_ambient < plain, (shots, plain, with_ambient)
    # Converged: nothing left unshot, so no ambient.
    done = SouthwellSolver(system, E)
    done.solve(tol=1e-9, max_iter=200)
    assert done.residual <= 1e-9
    assert np.all(done.ambient <= 1e-9 * E.max() / (1 - rho.max()))
    np.testing.assert_allclose(done.solution, cornell_direct.B, rtol=0, atol=1e-7 * E.max())


# 16. Pictures ---------------------------------------------------------------------------------
def test_pictures_have_the_camera_size(cornell_direct) -> None:
    sol = cornell_direct
    for mode in ("radiosity", "importance", "superposition"):
        for smooth in (True, False):
            image = sol.render(mode=mode, smooth=smooth)
            assert isinstance(image, dualight.Image)
            pixels = np.asarray(image)
            assert pixels.shape == (24, 32, 3), (mode, pixels.shape)
            assert np.all(np.isfinite(pixels)) and pixels.min() >= 0 and pixels.max() > 0
            if mode != "radiosity":
                assert pixels.max() <= 1.0
            assert image.stats["mode"] == mode and image.stats["method"] == "direct"
    small = sol.render(camera=sol.camera.with_resolution(10, 6))
    assert np.asarray(small).shape == (6, 10, 3)
    with pytest.raises(ValueError, match="mode must be"):
        sol.render(mode="radiance")  # type: ignore[arg-type]


def test_furnace_radiosity_picture_is_the_analytic_radiance() -> None:
    rho = 0.5
    sol = solve(scenes.furnace(rho, 1.0, resolution=(20, 12)), "direct", max_edge=0.5)
    expected = scenes.furnace_radiance(rho, 1.0)  # Le / (1 - rho): the picture is B / pi
    for smooth in (True, False):
        pixels = np.asarray(sol.render(smooth=smooth), dtype=np.float64)
        assert pixels.shape == (12, 20, 3)
        assert np.abs(pixels / expected - 1).max() < 1e-3, smooth
        # Negative control: 1 % less reflectance is resolved.
        assert np.abs(pixels / scenes.furnace_radiance(0.99 * rho, 1.0) - 1).min() > 5e-3


def test_without_importance_the_dual_is_unavailable() -> None:
    sol = solve(
        scenes.furnace(0.5, 1.0, resolution=(8, 8)), "direct", max_edge=0.5, importance=False
    )
    assert sol.I is None
    with pytest.raises(ValueError, match="importance was not solved"):
        sol.measurement_dual  # noqa: B018
    for mode in ("importance", "superposition"):
        with pytest.raises(ValueError, match="importance was not solved"):
            sol.render(mode=mode)
    assert np.asarray(sol.render()).shape == (8, 8, 3)


@pytest.mark.parametrize("method", ["direct", "jacobi", "hierarchical"])
def test_absurd_thread_counts_use_every_core_and_change_nothing(method: str) -> None:
    """threads=100000 segfaulted (jacobi and hierarchical; direct from 10**7: Eigen's OpenMP
    team) (issue 18): the core gives each request at most one worker per core, and the
    solution does not depend on the thread count."""
    scene = scenes.furnace(0.5, 1.0, (8, 8))
    kw = {"max_edge": 0.5} if method != "hierarchical" else {}
    one = solve(scene, method, threads=1, **kw)
    for threads in (100_000, 10**7):
        many = solve(scene, method, threads=threads, **kw)
        np.testing.assert_array_equal(many.B, one.B)


def test_the_direct_solver_refuses_too_many_patches_before_the_form_factors(monkeypatch) -> None:
    """The dense solver's patch limit is checked before any form factor is computed (issue
    18: it took the form factors' minutes first); the control, within the limit, computes
    them."""
    solve_module = sys.modules["dualight.radiosity.solve"]  # the package's `solve` is the function

    def no_form_factors(*args, **kwargs):
        raise AssertionError("form factors computed before the patch count was checked")

    monkeypatch.setattr(solve_module, "form_factors", no_form_factors)
    scene = scenes.cornell_box(resolution=(16, 16))
    with pytest.raises(ValueError, match="more than 12000"):
        solve(scene, "direct", max_edge=20.0)
    with pytest.raises(AssertionError, match="form factors computed"):
        solve(scene, "direct", max_edge=200.0)


def test_patches_that_memory_cannot_hold_are_refused_before_they_are_built(monkeypatch) -> None:
    """Issue 18: max_edge=0.5 on the Cornell box (31.8 million patches) passed the 50-million
    check and took 5.4 GB before a MemoryError. The patch count is now known first and
    refused, naming the memory it needs, when the system has less available; nothing sizeable
    is allocated before. The control: the same subdivision with room for it goes ahead (here
    a coarser one, to keep the test small)."""
    import tracemalloc

    patches_module = sys.modules["dualight.radiosity.patches"]
    monkeypatch.setattr(patches_module, "_available_bytes", lambda: 2**30)  # 1 GiB free
    scene = scenes.cornell_box(resolution=(16, 16))
    tracemalloc.start()
    try:
        with pytest.raises(MemoryError, match=r"3\.184e\+07 patches, which need about 10\.7 GiB"):
            PatchMesh(scene, max_edge=0.5)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 2**20, f"{peak} bytes allocated before the refusal"
    assert len(PatchMesh(scene, max_edge=20.0)) == 20620  # fits in 1 GiB


def test_the_memory_estimate_bounds_what_building_patches_takes() -> None:
    """PATCH_BYTES, the estimate behind the refusal above, is at least numpy's peak per patch
    while a PatchMesh is built (tracemalloc), at two sizes."""
    import tracemalloc

    from dualight.radiosity.patches import PATCH_BYTES

    scene = scenes.cornell_box(resolution=(16, 16))
    for max_edge in (20.0, 8.0):
        tracemalloc.start()
        try:
            patches = PatchMesh(scene, max_edge=max_edge)
            peak = tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()
        assert peak / len(patches) <= PATCH_BYTES, (max_edge, peak / len(patches))
        del patches
