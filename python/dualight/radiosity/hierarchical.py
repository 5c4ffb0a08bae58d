"""Hierarchical radiosity with importance-driven refinement.

[Hanrahan, Salzman and Aupperle 1991] link elements of per-triangle subdivision trees at the
coarsest level that keeps each transfer accurate; [Smits, Arvo and Salesin 1992] solve radiosity
and importance together and refine a link only where its energy transfer matters for the view,
so the unseen parts of a large model stay coarse.

    solver = HierarchicalSolver(scene, oracle="importance", epsilon=1e-3)
    while not solver.step().converged: ...
    solution = solver.solution()          # the same Solution type as the flat solvers

Oracles, for a link carrying energy from element j to element i (form factor F_ij, and
F_max = max(F_ij, F_ji): a small source next to a large receiver has a small F_ij but makes the
receiver's irradiance vary strongly, so both directions are tested, as in HSA91):

* ``"bf"``: refine when ``F_max * B_j`` (a bound on the radiosity error the link leaves at the
  receiver) exceeds ``epsilon`` times the brightest emitted radiosity.
* ``"importance"``: refine when ``F_max * rho_i * W_i * B_j * max(A_i, A_j)`` (that error
  weighted by the receiver's importance W, plus the importance error it leaves at the source
  weighted by the source's radiosity) exceeds ``epsilon`` times the measurement.

Per-link bounds do not bound an element's total: at a leaf in a corner the errors of many links
add up with one sign (with the link test alone, single leaves of the furnace were off by up to
66 % at ``"bf"``, epsilon 0.1). So each step also evaluates what every element gathers at its 7
quadrature points, and where that strays from the element's average by more than the oracle's
threshold (for ``"bf"``, ``epsilon`` times the brightest emitted radiosity, in luminance; for
``"importance"``, ``epsilon`` times the measurement once weighted by the element's importance
and area), the links that stray most are pushed down to the element's children until the rest
stray by at most half of it; each point counts only what the oracle's rays from it see of the
source. In the furnace the worst leaf is then within about 2 ``epsilon`` of the exact radiosity
with ``"bf"``.

A link whose source has children carries their radiosity, each weighted by its share of the
link's form factor as the receiver sees it (exact point form factors from the receiver's 7
points; for a partly hidden link, only from the points whose ray to the child arrives), and
importance flows back to those children, so the two systems stay adjoint. A source's average
over-weights what the receiver sees little of: a bias of one sign in every gather that adds up
over an enclosure (without this the cube lost 4 % of its energy at ``"bf"``, epsilon 1e-3).

A partly visible link is judged by its unoccluded form factor, so shadow boundaries refine. Each
link keeps two independent visibility estimates: one carries light, the other decides
refinement (with one, refinement would keep unlucky underestimates: a dark bias).

Each element emits its own radiosity: pi times its mean emitted radiance (a radiance texture's
mean over the element, textures being Mitsuba's ``area`` emitters with a textured
``radiance``), plus the first shot of point, spot and directional lights and of the
environment: its albedo times their mean irradiance over it, with visibility (as the uniform
solvers' :meth:`PatchMesh.direct_irradiance`, 4 x 4 points per element, 8 x 8 environment
direction pairs per point), taken again for every element refinement creates, so shadows and
textures refine like any other variation.

BF's threshold is relative to the brightest emitter, so dim interreflections stay coarse until
epsilon is small; importance's is relative to the view's measurement. Measured in
benchmarks/bench_hierarchical.py.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from dualight import _core
from dualight.radiosity.patches import (
    PatchMesh,
    require_diffuse,
    sub_triangle_uv,
    triangle_albedo,
)
from dualight.radiosity.solution import Solution, camera_samples
from dualight.scene import Camera, Scene

Oracle = Literal["bf", "importance"]

# The core's defaults of HierarchicalOptions, which checks every value.
_DEFAULT = _core.HierarchicalOptions()


@dataclass(frozen=True)
class HierarchicalStep:
    """What one refine-and-solve iteration reports."""

    iteration: int
    elements: int
    leaves: int
    links: int
    links_refined: int
    rays: int
    memory_bytes: int
    residual: float
    seconds: float
    converged: bool
    link_limit: bool
    rays_skipped: int = 0  # visibility rays a convex enclosure made unneeded


def receiver_samples(
    scene: Scene,
    camera: Camera,
    *,
    window: tuple[int, int, int, int] | None = None,
    samples_per_axis: int = 4,
    seed: int = 0,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """Camera samples landing on the front of a scene triangle: (triangle, b1, b2, weight).

    Each sample carries ``1 / (samples in the window * pi)`` of the measurement, the mean
    pixel value of the (windowed) image, as :func:`dualight.radiosity.receiver` defines it.
    """
    positions, triangles, _ = scene.triangle_arrays()
    prim, bary, front = camera_samples(
        scene._compile(),
        positions[triangles],
        camera,
        window=window,
        samples_per_axis=samples_per_axis,
        seed=seed,
    )
    return (
        prim[front].astype(np.uint32),
        bary[front][:, 0].astype(np.float32),
        bary[front][:, 1].astype(np.float32),
        1.0 / (prim.size * np.pi),
    )


class HierarchicalSolver:
    """Stepped hierarchical radiosity and importance of a diffuse scene.

    Parameters
    ----------
    scene, camera, window:
        The scene (its triangles are the roots of the element trees) and the view whose mean
        pixel value is the measurement (importance comes from it).
    oracle:
        ``"importance"`` (Smits et al.) or ``"bf"`` (Hanrahan et al.).
    epsilon:
        Refinement threshold, relative (see the module docstring).
    min_area:
        Elements are not split below this area (default: 1e-4 of the largest input triangle).
    shadow_rays:
        Visibility rays per receiver quadrature point (7 points per link), for each of the two
        independent estimates a link keeps (one for transport, one for the oracle).
    max_links:
        Refinement stops before this many links (steps report ``link_limit``; the solution is
        then not converged).
    skip:
        Skip visibility rays where the scene makes them pointless (a convex enclosure, see
        :attr:`dualight.Scene.features`); steps report ``rays_skipped``. ``False`` traces
        them all.
    samples_per_axis:
        Stratified camera samples per pixel and axis (1 to 64) that give the view's
        importance and measurement (see :func:`dualight.radiosity.solve`).
    progress:
        ``progress(done, total)``, called about every 100 ms while the input triangles are
        linked (O(triangles^2)); Ctrl-C stops that linking (KeyboardInterrupt, no solver).
    """

    def __init__(
        self,
        scene: Scene,
        *,
        camera: Camera | None = None,
        window: tuple[int, int, int, int] | None = None,
        oracle: Oracle = _DEFAULT.oracle.name,  # type: ignore[assignment]
        epsilon: float = _DEFAULT.epsilon,
        min_area: float | None = None,
        shadow_rays: int = _DEFAULT.shadow_rays,
        sweeps: int = _DEFAULT.sweeps,
        tolerance: float = _DEFAULT.tolerance,
        seed: int = _DEFAULT.seed,
        threads: int = _DEFAULT.threads,
        max_links: int = _DEFAULT.max_links,
        skip: bool = _DEFAULT.skip_unneeded,
        samples_per_axis: int = 4,
        progress: Callable[[int, int], None] | None = None,
    ) -> None:
        if min_area is not None and not min_area > 0:
            raise ValueError(f"min_area must be > 0, got {min_area!r}")
        options = _core.HierarchicalOptions(
            oracle=oracle,
            epsilon=epsilon,
            min_area=min_area or 0.0,
            shadow_rays=shadow_rays,
            sweeps=sweeps,
            tolerance=tolerance,
            seed=seed,
            threads=threads,
            max_links=max_links,
            skip_unneeded=skip,
        )
        if not isinstance(scene, Scene):
            raise TypeError(f"scene must be a dualight.Scene, got {type(scene).__name__}")
        self.oracle, self.epsilon = oracle, epsilon
        with scene._in_use():
            self._build(scene, camera, window, seed, samples_per_axis, options, progress)

    def _build(
        self,
        scene: Scene,
        camera: Camera | None,
        window: tuple[int, int, int, int] | None,
        seed: int,
        samples_per_axis: int,
        options: _core.HierarchicalOptions,
        progress: Callable[[int, int], None] | None,
    ) -> None:
        require_diffuse(scene)
        if not scene.has_emitters:
            raise ValueError("scene has no emitter: give some mesh a positive emission")
        cam = camera or scene.camera
        if cam is None:
            raise ValueError("the receiver needs a camera: pass camera= or give the scene one")
        self.scene, self.camera = scene, cam
        self._mesh_count = len(scene.meshes)
        start = time.perf_counter()
        prim, b1, b2, weight = receiver_samples(
            scene, cam, window=window, seed=seed, samples_per_axis=samples_per_axis
        )
        # A textured input triangle's albedo is its texture's mean over the triangle; its
        # elements keep it (Solution.render draws the texture over the leaves).
        self._albedo = triangle_albedo(scene)
        self._core = _core.HierarchicalSolver(
            scene._compile(), prim, b1, b2, weight, options, progress, albedo=self._albedo
        )
        self.setup_seconds = time.perf_counter() - start
        self.history: list[HierarchicalStep] = []

    def step(self, progress: Callable[[int, int], None] | None = None) -> HierarchicalStep:
        """Refine every link the oracle flags, then solve radiosity and importance;
        ``progress(done, total)`` is called about every 100 ms (an exception it raises stops
        the step and reaches the caller)."""
        s = self._core.step(progress)
        result = HierarchicalStep(**{k: s[k] for k in HierarchicalStep.__dataclass_fields__})
        self.history.append(result)
        return result

    def solve(
        self, max_iter: int = 30, progress: Callable[[int, int], None] | None = None
    ) -> list[HierarchicalStep]:
        """Step until nothing is refined (or ``max_iter`` steps); returns all steps.
        ``progress`` is each step's (see :meth:`step`)."""
        while len(self.history) < max_iter:
            step = self.step(progress)
            if step.converged or step.link_limit:
                break
        return self.history

    @property
    def converged(self) -> bool:
        """Whether the last step refined nothing."""
        return bool(self.history) and self.history[-1].converged

    def measurements(self) -> tuple[np.ndarray, np.ndarray]:
        """``(<R, B>, <I, E>)`` per channel on the current hierarchy."""
        primal, dual = self._core.measurements()
        return np.array(primal), np.array(dual)

    def links(self) -> dict[str, np.ndarray]:
        """Every link: receiver and source input triangles and element centroids, and F."""
        return self._core.links()

    def solution(self) -> Solution:
        """The current leaves as a :class:`dualight.radiosity.Solution`."""
        with self.scene._in_use():
            if len(self.scene.meshes) != self._mesh_count:
                raise RuntimeError(
                    "HierarchicalSolver.solution: meshes were added to the scene after this "
                    "solver was built; build a new solver for the new scene"
                )
            return self._solution()

    def _solution(self) -> Solution:
        leaves = self._core.leaves()
        _, _, mesh_of_triangle = self.scene.triangle_arrays()
        n = len(leaves["area"])
        vertices = leaves["vertices"].reshape(-1, 3).astype(np.float64)
        textured = {}
        if self._albedo is not None:
            textured = {
                "uv_corners": sub_triangle_uv(
                    self.scene, leaves["root"], vertices.reshape(n, 3, 3)
                ),
                "reflectance": self._albedo[leaves["root"]],
            }
        patches = PatchMesh.from_triangles(
            self.scene,
            vertices,
            np.arange(3 * n).reshape(n, 3),
            mesh_of_triangle[leaves["root"]],
            **textured,
        )
        area = leaves["area"]
        last = self.history[-1] if self.history else None
        stats: dict[str, Any] = {
            "method": "hierarchical",
            "oracle": self.oracle,
            "epsilon": self.epsilon,
            "steps": len(self.history),
            "converged": self.converged,
            "elements": last.elements if last else 0,
            "leaves": n,
            "links": last.links if last else 0,
            "rays": int(self._core.total_rays),
            "skipped": {"visibility_rays": int(self._core.total_rays_skipped)},
            "memory_bytes": last.memory_bytes if last else 0,
            "seconds": self.setup_seconds + sum(h.seconds for h in self.history),
        }
        return Solution(
            patches=patches,
            B=leaves["B"],
            I=leaves["W"] * area[:, None],
            E=leaves["E"],
            R=np.repeat((leaves["R"] * area)[:, None], 3, axis=1),
            form_factors=None,
            camera=self.camera,
            method="hierarchical",
            stats=stats,
            history={"hierarchical": list(self.history)},
            link_density=leaves["link_density"],
        )
