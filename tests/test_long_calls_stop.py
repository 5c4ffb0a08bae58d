"""Ctrl-C stops every long radiosity call within 0.5 s (issue 18, item 3): the dense LU of the
direct solver (2.5-6.4 s uninterruptible), form factors with many shadow rays (checked once per
patch pair: 44 s at shadow_rays=10**6), the hierarchical solver's initial linking (O(n^2):
6 s at 20k triangles), its roots' first shot and its refinement. Each test sends SIGINT 0.3 s
into the call and measures how long the call takes to raise KeyboardInterrupt."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

import dualight
from ctrl_c import interrupted
from dualight import _core, scenes
from dualight.radiosity import HierarchicalSolver, PatchMesh, form_factors

LATENCY = 0.5


pytestmark = pytest.mark.usefixtures("ctrl_c_raises")


def _latency_of_ctrl_c(call: Callable[[], object], after: float = 0.3) -> float:
    """Seconds from SIGINT (sent ``after`` s into ``call``) to its KeyboardInterrupt."""
    return interrupted(call, after)[1]


def _dense_system(n: int) -> _core.RadiositySystem:
    """A diagonally dominant n-patch system: each patch sees the next 8 (F = 0.1 each)."""
    cols = (np.arange(n)[:, None] + np.arange(1, 9)[None, :]) % n
    indptr = np.arange(0, 8 * n + 1, 8, dtype=np.uint64)
    F = _core.FormFactors.from_csr(n, indptr, cols.ravel().astype(np.uint32), np.full(8 * n, 0.1))
    return _core.RadiositySystem(F, np.full((n, 3), 0.8), np.ones(n))


def test_the_dense_lu_factorisation_stops_on_ctrl_c() -> None:
    system = _dense_system(5000)  # three dense LUs of 5000 x 5000: seconds
    latency = _latency_of_ctrl_c(lambda: _core.DirectSolver(system, 0))
    assert latency < LATENCY, f"took {latency:.3f} s to stop"


def test_the_dense_lu_reports_its_panels_and_solves_both_sides() -> None:
    n = 700
    system = _dense_system(n)
    calls: list[tuple[int, int]] = []
    direct = _core.DirectSolver(system, 0, lambda done, total: calls.append((done, total)))
    assert calls and calls[-1] == (3 * 6, 3 * 6)  # 700 columns: six panels of 128, per channel
    rng = np.random.default_rng(5)
    b = rng.uniform(0.0, 1.0, (n, 3))
    for dual in (False, True):
        x = direct.solve(b, dual=dual)
        assert system.residual(x, b, dual=dual) < 1e-12


def test_form_factors_with_many_shadow_rays_stop_on_ctrl_c() -> None:
    scene = scenes.cornell_box(resolution=(16, 16))
    patches = PatchMesh(scene, max_edge=200.0)
    latency = _latency_of_ctrl_c(
        lambda: form_factors(patches, shadow_rays=10**6, skip=False, threads=1)
    )
    assert latency < LATENCY, f"took {latency:.3f} s to stop"


def _many_triangles(per_side: int) -> dualight.Scene:
    """The Cornell box with a floor of 2 * per_side**2 triangles (the hierarchy's roots)."""
    scene = scenes.cornell_box(resolution=(16, 16))
    lo, hi = scene.bounds()
    x = np.linspace(lo[0] + 0.01, hi[0] - 0.01, per_side + 1)
    z = np.linspace(lo[2] + 0.01, hi[2] - 0.01, per_side + 1)
    xx, zz = np.meshgrid(x, z, indexing="ij")
    v = np.stack([xx.ravel(), np.full(xx.size, lo[1] + 0.01), zz.ravel()], axis=1)
    k = np.arange(per_side)
    i, j = np.meshgrid(k, k, indexing="ij")
    a = (i * (per_side + 1) + j).ravel()
    quads = np.stack([a, a + 1, a + per_side + 2, a + per_side + 1], axis=1)
    scene.add_mesh(v, quads, reflectance=(0.5, 0.5, 0.5), name="fine floor")
    return scene


def test_hierarchical_linking_stops_on_ctrl_c() -> None:
    scene = _many_triangles(100)  # 20,000 more roots: seconds of O(n^2) linking
    latency = _latency_of_ctrl_c(lambda: HierarchicalSolver(scene, threads=1))
    assert latency < LATENCY, f"took {latency:.3f} s to stop"


def test_hierarchical_first_shot_stops_on_ctrl_c_and_counts_in_the_progress() -> None:
    """Under a sky, the roots' first shot (an environment's irradiance over each of 20,000
    roots) comes before the linking: it stops on Ctrl-C, and the set-up's progress counts it
    (its total is twice the roots: the first shot, then the linking's rows)."""
    scene = _many_triangles(100)
    scene.add_emitter(dualight.ConstantEnvironment(0.5))
    latency = _latency_of_ctrl_c(lambda: HierarchicalSolver(scene, threads=1))
    assert latency < LATENCY, f"took {latency:.3f} s to stop"
    small = scenes.cornell_box((16, 16), variant="sky")
    calls: list[tuple[int, int]] = []
    HierarchicalSolver(small, progress=lambda done, total: calls.append((done, total)))
    assert calls[-1] == (2 * small.triangle_count, 2 * small.triangle_count)


def test_hierarchical_refinement_stops_on_ctrl_c_keeping_the_solution() -> None:
    scene = scenes.cornell_box(resolution=(16, 16))
    result: list[object] = []

    def solve() -> None:
        try:
            dualight.radiosity.solve(
                scene, "hierarchical", epsilon=1e-7, shadow_rays=64, threads=1, max_links=10**8
            )
        except KeyboardInterrupt as error:
            result.append(getattr(error, "partial_result", None))
            raise

    latency = _latency_of_ctrl_c(solve, after=1.0)
    assert latency < LATENCY, f"took {latency:.3f} s to stop"
    (partial,) = result
    assert isinstance(partial, dualight.radiosity.Solution)
    assert np.all(np.isfinite(partial.B)) and partial.B.max() > 0
