"""Hierarchical radiosity leaf by leaf: where its gather errs and what that costs in energy.

For issue 18, item 9. The view measurement can be right while single leaves are wrong, and a
global check (absorbed / emitted power) can pass because leaf errors of both signs cancel. This
study measures the leaves directly. For each scene and epsilon it solves with
:class:`dualight.radiosity.hierarchical.HierarchicalSolver` (``solve(40)``), then computes the
exact flat form factors on the solution's own leaves (:func:`dualight.radiosity.solve.form_factors`,
7-point quadrature, ``--shadow-rays`` visibility rays) and per leaf i

    gather error = (B_i - E_i) / rho_i  -  sum_j F_ij B_j     (the same B on both sides)

that is, the error of the hierarchy's transport alone, not propagated through the bounces. It
reports, in luminance:

- ``energy``: absorbed / emitted, ``sum A (1 - rho) (B - E) / rho / sum A E`` (1 in a closed
  scene up to what hits the light's back in ``cube``);
- ``net_gather_error``: ``sum A * error / sum A * exact gather``, what the transport loses or
  gains in all (a net loss of x per bounce costs about x / (1 - rho) of the energy);
- the same per band of distance from a leaf's centroid to the nearest edge of the box (the
  scenes are boxes), and the worst leaf;
- in ``furnace``, where the exact radiosity is known, also the worst leaf's ``|B / B_exact - 1|``.

Scenes: ``furnace`` (``scenes.furnace(0.5, 1.0)``: uniform radiosity), ``cube``
(``scenes.cube()``: a small light 1 cm under the ceiling, which also occludes), and
``cube_flush`` (the same box with the light flush in the ceiling, the middle of a 3 x 3 grid of
ceiling quads: no occluder). The flat form factors cost O(leaves^2): keep epsilon coarse enough
for about 10^4 leaves (about 2 min each on 2 cores).

    python benchmarks/hierarchical_elements.py                 # the default grid (about 10 min)
    python benchmarks/hierarchical_elements.py --scenes cube_flush --epsilons 3e-3

Writes ``benchmarks/results/hierarchical_elements.json``.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path
from typing import Any

import numpy as np

import dualight
from dualight import scenes
from dualight.radiosity.hierarchical import HierarchicalSolver
from dualight.radiosity.solve import form_factors

LUMINANCE = np.array([0.2126, 0.7152, 0.0722])
EDGE_BANDS = [(0.0, 0.01), (0.01, 0.02), (0.02, 0.05), (0.05, 0.1), (0.1, 0.2), (0.2, 0.5)]
DEFAULT_EPSILONS = {"furnace": [0.1, 0.05], "cube": [1e-2, 3e-3], "cube_flush": [1e-2, 3e-3]}


def _quad(scene: dualight.Scene, corners: np.ndarray, centre: np.ndarray, **material: Any) -> None:
    """Adds a quad (4 corners in order) facing `centre`."""
    normal = np.cross(corners[1] - corners[0], corners[2] - corners[0])
    if np.dot(normal, centre - corners[0]) < 0:
        corners = corners[::-1]
    scene.add_mesh(corners, np.array([[0, 1, 2], [0, 2, 3]]), **material)


def cube_flush(reflectance: float = 0.7, light_radiance: float = 10.0) -> dualight.Scene:
    """``scenes.cube()``'s box and materials with its light flush in the ceiling (no occluder)."""
    camera = dualight.Camera(
        origin=(0.1, 0.1, 0.1),
        target=(1.0, 1.0, 1.0),
        up=(0.0, 1.0, 0.0),
        fov=100.0,
        resolution=(64, 64),
    )
    scene = dualight.Scene(camera=camera)
    centre = np.full(3, 0.5)
    rho = (reflectance,) * 3

    def box_face(
        axis: int, at: float, lo: tuple[float, float], hi: tuple[float, float]
    ) -> np.ndarray:
        u, v = [a for a in range(3) if a != axis]
        corners = np.zeros((4, 3))
        for k, (a, b) in enumerate(
            [(lo[0], lo[1]), (hi[0], lo[1]), (hi[0], hi[1]), (lo[0], hi[1])]
        ):
            corners[k, axis], corners[k, u], corners[k, v] = at, a, b
        return corners

    for axis, at in [(1, 0.0), (0, 0.0), (0, 1.0), (2, 0.0), (2, 1.0)]:
        _quad(scene, box_face(axis, at, (0.0, 0.0), (1.0, 1.0)), centre, reflectance=rho)
    third = 1.0 / 3.0
    for i in range(3):
        for j in range(3):
            face = box_face(1, 1.0, (i * third, j * third), ((i + 1) * third, (j + 1) * third))
            light = {"emission": (light_radiance,) * 3} if (i, j) == (1, 1) else {}
            _quad(scene, face, centre, reflectance=rho, **light)
    return scene


SCENES = {
    "furnace": lambda: scenes.furnace(0.5, 1.0),
    "cube": scenes.cube,
    "cube_flush": cube_flush,
}


def edge_distance(centroids: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Distance from each centroid (on a face of the box [lo, hi]) to the nearest edge of the box:
    the second smallest of its distances to the six planes (the smallest is its own face's, 0)."""
    d = np.concatenate([centroids - lo, hi - centroids], axis=1)
    return np.sort(d, axis=1)[:, 1]


def study(name: str, epsilon: float, shadow_rays: int) -> dict[str, Any]:
    scene = SCENES[name]()
    t0 = time.perf_counter()
    solver = HierarchicalSolver(scene, oracle="bf", epsilon=epsilon)
    solver.solve(max_iter=40)
    sol = solver.solution()
    seconds = time.perf_counter() - t0
    F, _ = form_factors(sol.patches, quadrature=7, shadow_rays=shadow_rays)
    B, E = sol.B @ LUMINANCE, sol.E @ LUMINANCE
    rho, A = sol.rho @ LUMINANCE, sol.areas
    starts = F.indptr.astype(np.int64)
    rows = np.repeat(np.arange(F.n), np.diff(starts))
    exact = np.bincount(rows, weights=F.values.astype(np.float64) * B[F.indices], minlength=F.n)
    error = (B - E) / rho - exact
    absorbed = np.sum(A * (1 - rho) * (B - E) / rho)
    vertices = sol.patches.vertices
    centroids = vertices[sol.patches.triangles].mean(axis=1)
    dist = edge_distance(centroids, vertices.min(axis=0), vertices.max(axis=0))
    bands = []
    for lo, hi in EDGE_BANDS:
        m = (dist >= lo) & (dist < hi)
        if m.any():
            bands.append(
                {
                    "edge_distance": [lo, hi],
                    "leaves": int(m.sum()),
                    "area": float(A[m].sum()),
                    "gather_error": float(np.sum(A[m] * error[m]) / np.sum(A[m] * exact[m])),
                }
            )
    row: dict[str, Any] = {
        "scene": name,
        "oracle": "bf",
        "epsilon": epsilon,
        "leaves": len(B),
        "links": int(sol.stats["links"]),
        "solve_seconds": seconds,
        "energy": float(absorbed / np.sum(A * E)),
        "net_gather_error": float(np.sum(A * error) / np.sum(A * exact)),
        "worst_leaf_gather_error": float(np.max(np.abs(error) / np.maximum(exact, 1e-12))),
        "bands": bands,
    }
    if name == "furnace":
        row["worst_leaf_radiosity_error"] = float(
            np.max(np.abs(B / (np.pi * 2.0 * np.sum(LUMINANCE)) - 1))
        )
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", nargs="*", default=list(SCENES), choices=list(SCENES))
    parser.add_argument("--epsilons", nargs="*", type=float, help="the same for every scene")
    parser.add_argument(
        "--shadow-rays", type=int, default=4, help="per quadrature point of the flat form factors"
    )
    parser.add_argument(
        "--out", type=Path, default=Path(__file__).parent / "results" / "hierarchical_elements.json"
    )
    args = parser.parse_args()
    rows = []
    for name in args.scenes:
        for epsilon in args.epsilons or DEFAULT_EPSILONS[name]:
            row = study(name, epsilon, args.shadow_rays)
            bands = " ".join(f"{b['gather_error']:+.3f}" for b in row["bands"])
            print(
                f"{name:10s} eps {epsilon:g}: {row['leaves']} leaves, energy {row['energy']:.4f}, "
                f"net gather {row['net_gather_error']:+.4f}, by edge distance {bands}",
                flush=True,
            )
            rows.append(row)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps({"dualight": dualight.__version__, "rows": rows}, indent=1))


if __name__ == "__main__":
    main()
