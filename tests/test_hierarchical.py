"""Hierarchical radiosity with BF and importance-driven refinement (HSA91, SAS92)."""

from __future__ import annotations

import numpy as np
import pytest

import dualight
from dualight import scenes
from dualight.bench import REFERENCE_DIR as REFERENCES
from dualight.radiosity import HierarchicalSolver, PatchMesh, solve


def _view_error(solution, reference: np.ndarray) -> float:
    return float(np.max(np.abs(solution.measurement_primal / reference - 1.0)))


@pytest.fixture(scope="module")
def cornell_reference() -> np.ndarray:
    """Mean pixel value of the unbounded-depth Mitsuba reference (the view measurement)."""
    image = dualight.Image.load(REFERENCES / "cornell_64_full_mean.exr")
    return np.asarray(image).mean(axis=(0, 1))


def test_cornell_agrees_with_the_path_traced_reference(cornell_reference) -> None:
    # The view error (importance oracle, red, the largest) with a 16 x 16 receiver per pixel:
    # 1.28 % / 0.92 % / 0.70 % at eps 1e-4 / 3e-5 / 1e-5, and 0.80-0.90 % at 3e-5 over seeds
    # 1 to 5 (measured 2026-12-04). With the default 4 x 4 receiver the refinement follows where
    # the few samples land, and the error at 1e-5 spread from -2.5 % to +1.2 % over seeds 0 to 7
    # (issue 18). The test holds eps 3e-5 to 1.5 % and asks the error to fall from 1e-4; eps 1e-5
    # (17 s of the test's 25) is left out to keep `make test` short.
    scene = scenes.cornell_box(resolution=(64, 64))
    errors = []
    for eps in (1e-4, 3e-5):
        sol = solve(scene, "hierarchical", oracle="importance", epsilon=eps, samples_per_axis=16)
        errors.append(_view_error(sol, cornell_reference))
    assert errors[1] < 0.015, errors
    assert errors[1] < errors[0]
    # Negative control: 10% less reflectance misses by far more than the tolerance (12.7 %).
    wrong = solve(
        scenes.cornell_box(resolution=(64, 64), reflectance_scale=0.9),
        "hierarchical",
        oracle="importance",
        epsilon=3e-5,
        samples_per_axis=16,
    )
    assert _view_error(wrong, cornell_reference) > 0.05


@pytest.mark.parametrize("oracle", ["bf", "importance"])
def test_duality_holds_on_the_hierarchy(oracle: str) -> None:
    sol = solve(
        scenes.cornell_box(resolution=(32, 32)), "hierarchical", oracle=oracle, epsilon=1e-3
    )
    assert sol.duality_gap < 1e-5, sol.duality_gap  # sweeps stop at a 1e-6 change
    assert sol.stats["links"] > 0 and sol.stats["elements"] >= sol.stats["leaves"] > 0
    # <R, B> is the mean of the flat picture of the leaves, so the receiver maps to leaves right.
    flat = np.asarray(sol.render(mode="radiosity", smooth=False)).mean(axis=(0, 1))
    np.testing.assert_allclose(flat, sol.measurement_primal, rtol=1e-4)


def test_every_leaf_sees_every_source_once() -> None:
    # In a closed cube nothing is occluded, so every other wall must be linked exactly once to
    # every leaf, at some level of its ancestry.
    solver = HierarchicalSolver(scenes.furnace(0.5, 1.0), oracle="bf", epsilon=0.05)
    for _ in range(5):
        solver.step()
        assert solver._core.link_coverage_error() < 1e-9


def _furnace_leaf_errors(oracle: str, epsilon: float, albedo: float = 0.5):
    """Per-leaf relative error of B in the furnace (exact: pi / (1 - 0.5)), leaf areas, and each
    leaf's share of the receiver (R integrated over the leaf)."""
    solver = HierarchicalSolver(
        scenes.furnace(albedo, 1.0), oracle=oracle, epsilon=epsilon, shadow_rays=0
    )
    solver.solve(30)
    sol = solver.solution()
    return sol.B[:, 0] / (np.pi / (1 - 0.5)) - 1, sol.areas, sol.R[:, 0]


def test_furnace_leaves_converge_with_bf() -> None:
    # Issue 18: with the per-link test alone single leaves were off by 66 / 54 / 33 % at eps
    # 0.1 / 0.05 / 0.02 (leaves in corners inherit coarse links). With the element check the worst
    # leaf is 20.8 / 9.7 / 3.9 %: within 2.5 eps, as BF's threshold (eps times the brightest
    # emitted radiosity, here half of B) puts at most eps / 2 per level.
    worst = []
    for eps in (0.1, 0.05, 0.02):
        error, area, _ = _furnace_leaf_errors("bf", eps)
        worst.append(float(np.abs(error).max()))
        assert worst[-1] < 2.5 * eps, (eps, worst)
    assert worst[0] > worst[1] > worst[2], worst
    # Energy: the area-weighted mean within 0.5 % (measured 0.02 % at eps 0.02).
    assert abs(np.average(error, weights=area)) < 5e-3
    # Negative control: albedo 0.45 against the exact value for 0.5 fails the same bound.
    error, _, _ = _furnace_leaf_errors("bf", 0.02, albedo=0.45)
    assert np.abs(error).max() > 2.5 * 0.02


def test_furnace_seen_leaves_converge_with_importance() -> None:
    # The importance oracle bounds errors weighted by importance and area, so single leaves that
    # matter little can stay coarse; what the camera sees, the view-weighted mean per-leaf error
    # (the mean error of the flat picture), must fall with eps. Issue 18: 4.0 / 2.5 / 1.35 % at
    # eps 1e-3 / 1e-4 / 1e-5 with the per-link test alone (and growing from eps 1e-2 to 1e-3);
    # 0.59 / 0.25 / 0.09 % with the element check.
    seen = []
    for eps in (1e-3, 1e-4, 1e-5):
        error, _, receiver = _furnace_leaf_errors("importance", eps)
        seen.append(float(np.average(np.abs(error), weights=receiver)))
    assert seen[0] < 0.01 and seen[2] < 0.002, seen
    assert seen[0] > seen[1] > seen[2], seen
    error, _, receiver = _furnace_leaf_errors("importance", 1e-4, albedo=0.45)
    assert np.average(np.abs(error), weights=receiver) > 0.01


def _importance_weighted_difference(hierarchical, flat) -> float:
    """Per-leaf |B / B_flat - 1| (luminance), averaged with the weights of each leaf's share of
    the measurement in the flat solution (importance times radiosity)."""
    lum = np.array([0.2126, 0.7152, 0.0722])
    b, b_flat = hierarchical.B @ lum, flat.B @ lum
    weight = (flat.I @ lum) * b_flat
    lit = b_flat > 0
    return float(np.average(np.abs(b[lit] / b_flat[lit] - 1), weights=weight[lit]))


def test_cornell_leaves_agree_with_the_flat_solution_on_the_same_elements() -> None:
    # The flat (direct) solution on the hierarchy's own leaves has no link approximation, so the
    # difference per leaf is the hierarchy's error alone. Measured with the element check and
    # source views: 2.6 / 2.0 / 1.35 % at eps 3e-3 / 1e-3 / 3e-4; with the per-link test alone:
    # 3.8 / 3.3 / 3.0 %.
    scene = scenes.cornell_box(resolution=(32, 32))
    differences = []
    for eps in (3e-3, 1e-3, 3e-4):
        sol = solve(scene, "hierarchical", oracle="importance", epsilon=eps)
        flat = solve(
            scene, "direct", patches=sol.patches, importance=True, quadrature=7, shadow_rays=4
        )
        differences.append(_importance_weighted_difference(sol, flat))
    assert differences[0] > differences[1] > differences[2], differences
    assert differences[2] < 0.025, differences
    # Negative control: the flat solution of a box with 10 % less reflectance, same elements.
    darker = scenes.cornell_box(resolution=(32, 32), reflectance_scale=0.9)
    wrong = solve(
        darker,
        "direct",
        patches=PatchMesh.from_triangles(
            darker, sol.patches.vertices, sol.patches.triangles, sol.patches.mesh_index
        ),
        importance=True,
        quadrature=7,
        shadow_rays=4,
    )
    assert _importance_weighted_difference(sol, wrong) > 0.025


@pytest.mark.parametrize("oracle", ["bf", "importance"])
def test_refinement_is_monotone_in_epsilon(oracle: str) -> None:
    scene = scenes.cornell_box(resolution=(32, 32))
    links = [
        solve(scene, "hierarchical", oracle=oracle, epsilon=eps).stats["links"]
        for eps in (1e-1, 1e-2, 1e-3)
    ]
    assert links[0] <= links[1] <= links[2], links
    assert links[2] > links[0]


def test_importance_spends_fewer_links_where_the_camera_does_not_look() -> None:
    # rooms(4): the camera sees one room. At equal or better view error the importance oracle
    # must need far fewer links than BF (the benchmark measures the full curves).
    scene = scenes.rooms(4)
    reference = np.asarray(dualight.render(scene, spp=512, seed=1, progress=False)).mean(
        axis=(0, 1)
    )
    bf = solve(scene, "hierarchical", oracle="bf", epsilon=3e-3)
    imp = solve(scene, "hierarchical", oracle="importance", epsilon=1e-3)
    assert _view_error(imp, reference) <= _view_error(bf, reference) + 2e-3
    assert imp.stats["links"] * 3 < bf.stats["links"], (imp.stats["links"], bf.stats["links"])


def test_solver_steps_report_progress() -> None:
    solver = HierarchicalSolver(scenes.cornell_box(resolution=(32, 32)), epsilon=1e-3)
    steps = solver.solve(max_iter=30)
    assert steps[-1].converged and steps[-1].links_refined == 0
    assert all(s.elements >= s.leaves > 0 and s.memory_bytes > 0 for s in steps)
    assert steps[-1].links >= steps[0].links
    assert solver.measurements()[0].shape == (3,)


def test_pictures_of_a_hierarchical_solution() -> None:
    sol = solve(scenes.cornell_box(resolution=(24, 16)), "hierarchical", epsilon=1e-2)
    for mode in ("radiosity", "importance", "superposition", "elements", "links"):
        image = sol.render(mode=mode)
        assert image.shape == (16, 24, 3) and np.all(np.isfinite(np.asarray(image)))
    flat = solve(scenes.furnace(0.5, 1.0, resolution=(8, 8)), "direct", max_edge=0.5)
    with pytest.raises(ValueError, match="hierarchical"):
        flat.render(mode="links")


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"oracle": "nope"}, "oracle"),
        ({"epsilon": 0.0}, "epsilon"),
        ({"min_area": -1.0}, "min_area"),
        ({"shadow_rays": -1}, "shadow_rays"),
    ],
)
def test_bad_options_raise(kwargs, message) -> None:
    with pytest.raises(ValueError, match=message):
        HierarchicalSolver(scenes.cornell_box(resolution=(8, 8)), **kwargs)


def test_link_limit_stops_refinement_without_crashing() -> None:
    solver = HierarchicalSolver(scenes.furnace(0.5, 1.0), oracle="bf", epsilon=1e-4, max_links=5000)
    steps = solver.solve(max_iter=30)
    assert steps[-1].link_limit and not solver.converged
    assert steps[-1].links <= 5000
    with pytest.warns(dualight.radiosity.ConvergenceWarning):
        solve(scenes.furnace(0.5, 1.0), "hierarchical", oracle="bf", epsilon=1e-4, max_links=5000)


def test_on_the_cube_importance_needs_no_more_links_than_bf() -> None:
    # Everything in the cube is visible, so importance has little to skip; it must not cost more
    # than 1.1x BF's links for no worse a view error (benchmark: it needs far fewer, since BF's
    # threshold follows the bright light and leaves dim interreflections coarse).
    scene = scenes.cube()
    reference = np.asarray(dualight.render(scene, spp=512, seed=2, progress=False)).mean(
        axis=(0, 1)
    )
    bf = solve(scene, "hierarchical", oracle="bf", epsilon=1e-2)
    imp = solve(scene, "hierarchical", oracle="importance", epsilon=1e-2)
    assert _view_error(imp, reference) <= _view_error(bf, reference)
    assert imp.stats["links"] <= 1.1 * bf.stats["links"], (imp.stats["links"], bf.stats["links"])
