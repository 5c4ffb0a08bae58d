"""Hierarchical radiosity with BF and importance-driven refinement (HSA91, SAS92)."""

from __future__ import annotations

import numpy as np
import pytest

import dualight
from dualight import scenes
from dualight.bench import REFERENCE_DIR as REFERENCES
from dualight.radiosity import HierarchicalSolver, solve


def _view_error(solution, reference: np.ndarray) -> float:
    return float(np.max(np.abs(solution.measurement_primal / reference - 1.0)))


@pytest.fixture(scope="module")
def cornell_reference() -> np.ndarray:
    """Mean pixel value of the unbounded-depth Mitsuba reference (the view measurement)."""
    image = dualight.Image.load(REFERENCES / "cornell_64_full_mean.exr")
    return np.asarray(image).mean(axis=(0, 1))


def test_cornell_agrees_with_the_path_traced_reference(cornell_reference) -> None:
    # The view error (importance oracle, red, the largest) with a 16 x 16 receiver per pixel:
    # 2.2 % / 1.6 % / 1.17 % at eps 1e-4 / 3e-5 / 1e-5 (seeds 0 to 3 within 0.1 %). With the
    # default 4 x 4 receiver the refinement follows where the few samples land, and the error
    # at 1e-5 spread from -2.5 % to +1.2 % over seeds 0 to 7 (issue 18: the bound of 1.5 % at
    # 3e-5 once held for seed 0 only). The test holds eps 1e-5 to 1.5 % and asks the error to
    # fall as eps does.
    scene = scenes.cornell_box(resolution=(64, 64))
    errors = []
    for eps in (3e-5, 1e-5):
        sol = solve(scene, "hierarchical", oracle="importance", epsilon=eps, samples_per_axis=16)
        errors.append(_view_error(sol, cornell_reference))
    assert errors[1] < 0.015, errors
    assert errors[1] < errors[0]
    # Negative control: 10% less reflectance misses by far more than the tolerance.
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


def test_furnace_energy_is_conserved() -> None:
    solver = HierarchicalSolver(scenes.furnace(0.5, 1.0), oracle="bf", epsilon=0.01, shadow_rays=0)
    solver.solve(20)
    sol = solver.solution()
    exact = np.pi / (1 - 0.5)
    assert abs(np.average(sol.B[:, 0], weights=sol.areas) / exact - 1) < 5e-3


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
