"""`solve` and its `Solution`: radiosity and importance of one patch mesh, their measurement
from both sides, and the three pictures (radiosity, importance, superposition)."""

from __future__ import annotations

import numbers
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

from dualight import _core
from dualight.image import Image
from dualight.radiosity.patches import PatchMesh
from dualight.radiosity.solvers import SOLVERS, DirectSolver, Step
from dualight.scene import Camera, Scene

Mode = Literal["radiosity", "importance", "superposition", "elements", "links"]


class ConvergenceWarning(RuntimeWarning):
    """An iterative solver stopped at max_iter with its residual above tol."""


def camera_samples(
    compiled: _core.Scene,
    corners: np.ndarray,
    camera: Camera,
    *,
    window: tuple[int, int, int, int] | None = None,
    samples_per_axis: int = 4,
    seed: int = 0,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Stratified camera samples over the image (or a pixel ``window``): the triangle each hits
    (``-1``: none), its barycentrics, and whether it sees the triangle's front.

    ``corners`` are the ``(T, 3, 3)`` corners of the compiled scene's triangles. Arrays are
    ``(H, W, S)``, ``(H, W, S, 2)`` and ``(H, W, S)``. Patches are one-sided, so a sample that
    sees a back contributes nothing.
    """
    prim, bary = _core.trace_camera_hits(
        compiled, camera._compile(), samples_per_axis=samples_per_axis, seed=seed
    )
    if window is not None:
        x0, y0, x1, y1 = window
        if not (0 <= x0 < x1 <= camera.width and 0 <= y0 < y1 <= camera.height):
            raise ValueError(f"window {window} is not inside the {camera.resolution} image")
        prim, bary = prim[y0:y1, x0:x1], bary[y0:y1, x0:x1]
    c = corners[np.maximum(prim, 0)]
    normal = np.cross(c[..., 1, :] - c[..., 0, :], c[..., 2, :] - c[..., 0, :])
    point = (
        c[..., 0, :]
        + bary[..., :1] * (c[..., 1, :] - c[..., 0, :])
        + bary[..., 1:] * (c[..., 2, :] - c[..., 0, :])
    )
    front = (prim >= 0) & (
        np.einsum("...j,...j->...", normal, np.asarray(camera.origin) - point) > 0
    )
    return prim, bary, front


def receiver(
    patches: PatchMesh,
    camera: Camera,
    *,
    window: tuple[int, int, int, int] | None = None,
    samples_per_axis: int = 4,
    seed: int = 0,
) -> np.ndarray:
    """The receiver ``R``: how much each patch counts in the camera's measurement.

    The measurement is the mean pixel value of the image (or of the pixel ``window``
    ``(x0, y0, x1, y1)``, half-open), each pixel a box-filtered average of radiance. A diffuse
    patch seen from its front leaves radiance ``B / pi``, so ``R_i`` is the share of the
    window's stratified camera samples that land on the front of patch ``i``, divided by pi,
    and ``<R, B>`` is that mean pixel value. ``R_i > 0`` exactly for patches the camera sees.
    """
    prim, _, front = camera_samples(
        patches._compile(),
        patches.vertices[patches.triangles],
        camera,
        window=window,
        samples_per_axis=samples_per_axis,
        seed=seed,
    )
    counts = np.bincount(prim[front], minlength=len(patches)).astype(np.float64)
    return counts / (prim.size * np.pi)


@dataclass
class Solution:
    """Radiosity ``B`` and importance ``I`` of a patch mesh, with what produced them.

    ``B`` solves ``M B = E`` and ``I`` solves ``M^T I = R`` (``M = I - diag(rho) F``), per RGB
    channel. Both answer the same measurement, the mean pixel value of the camera's view:
    ``measurement_primal = <R, B>`` and ``measurement_dual = <I, E>`` (per channel).
    """

    patches: PatchMesh
    B: np.ndarray
    I: np.ndarray | None  # noqa: E741 - the literature's name
    E: np.ndarray
    R: np.ndarray
    form_factors: _core.FormFactors | None  # None for hierarchical solutions (links instead)
    camera: Camera
    method: str
    stats: dict[str, Any] = field(default_factory=dict)
    history: dict[str, list[Any]] = field(default_factory=dict)
    link_density: np.ndarray | None = None  # hierarchical: links per unit area at each patch
    # view_only solves: the patches whose B was solved (non-zero importance); None = all.
    solved: np.ndarray | None = None

    @property
    def areas(self) -> np.ndarray:
        """Patch areas, one per patch."""
        return self.patches.areas

    @property
    def rho(self) -> np.ndarray:
        """Patch reflectances, RGB per patch."""
        return self.patches.reflectance

    @property
    def measurement_primal(self) -> np.ndarray:
        """``<R, B>`` per channel: the camera's mean pixel value from the radiosity solution."""
        return np.sum(self.R * self.B, axis=0)

    @property
    def measurement_dual(self) -> np.ndarray:
        """``<I, E>`` per channel: the same measurement from the importance solution."""
        if self.I is None:
            raise ValueError("importance was not solved: call solve(..., importance=True)")
        return np.sum(self.I * self.E, axis=0)

    @property
    def duality_gap(self) -> float:
        """Largest relative difference between the two measurements over the channels."""
        p, d = self.measurement_primal, self.measurement_dual
        return float(np.max(np.abs(p - d) / np.maximum(np.abs(p), 1e-300)))

    # pictures -------------------------------------------------------------------------
    def vertex_values(self, values: np.ndarray) -> np.ndarray:
        """Per-vertex values: the area-weighted mean of the patches around each vertex.

        Vertices are merged across input triangles when they coincide and their patches share
        a mesh and a plane, so radiosity is smooth across a quad's diagonal but not around
        the corner between a wall and the floor.
        """
        p = self.patches
        key_pos = np.round(p.vertices / max(np.ptp(p.vertices), 1e-30) * 2**20).astype(np.int64)
        tri_normals = np.round(p.normals * 1024).astype(np.int64)
        corners = p.triangles.reshape(-1)
        owner = np.repeat(np.arange(len(p)), 3)
        keys = np.concatenate(
            [key_pos[corners], tri_normals[owner], p.mesh_index[owner, None]], axis=1
        )
        _, group = np.unique(keys, axis=0, return_inverse=True)
        group = group.reshape(-1)
        w = p.areas[owner]
        sums = np.zeros((group.max() + 1, values.shape[1]))
        np.add.at(sums, group, w[:, None] * values[owner])
        weights = np.bincount(group, weights=w)
        per_corner = sums[group] / weights[group, None]
        return per_corner.reshape(len(p), 3, values.shape[1])

    @staticmethod
    def _normalised(values: np.ndarray, visible: np.ndarray) -> np.ndarray:
        """Values / their 99th percentile over the visible pixels, clipped to [0, 1]."""
        seen = values[visible.any(axis=-1)] if visible.ndim == values.ndim + 1 else values
        scale = float(np.percentile(seen, 99)) if seen.size else 0.0
        return np.clip(values / scale, 0.0, 1.0) if scale > 0 else np.zeros_like(values)

    def render(
        self,
        camera: Camera | None = None,
        mode: Mode = "radiosity",
        *,
        smooth: bool = True,
        samples_per_axis: int = 4,
        seed: int = 0,
    ) -> Image:
        """Draw the solution from ``camera`` (default: the solution's camera).

        With the defaults (the receiver's samples and seed), the mean of the flat
        (``smooth=False``) radiosity picture is exactly ``measurement_primal``.

        ``"radiosity"``: radiance ``B / pi`` (linear RGB, comparable with a path-traced image),
        flat per patch or (``smooth``) interpolated from vertex values. ``"importance"``: the
        importance in false colour (mean over channels, normalised, a black-red-yellow-white
        ramp). ``"superposition"``: the radiosity picture in grey with the important parts
        tinted yellow, in proportion to importance: where the work matters for the view.
        ``"elements"``: every patch (leaf element) in its own colour, so the mesh shows.
        ``"links"``: hierarchical solutions only, links per unit area in false colour (log
        scale): where the work went.
        """
        cam = camera or self.camera
        prim, bary, visible = camera_samples(
            self.patches._compile(),
            self.patches.vertices[self.patches.triangles],
            cam,
            samples_per_axis=samples_per_axis,
            seed=seed,
        )
        idx = np.maximum(prim, 0)
        if self.solved is not None and not np.all(self.solved[idx[visible]]):
            raise ValueError(
                "this camera sees patches whose radiosity was not solved: the solution was "
                "computed for one view only (view_only=True)"
            )

        def sample(values: np.ndarray) -> np.ndarray:
            if smooth:
                corners = self.vertex_values(values)[idx]  # H, W, S, 3, C
                b1, b2 = bary[..., 0:1], bary[..., 1:2]
                v = (
                    (1 - b1 - b2) * corners[..., 0, :]
                    + b1 * corners[..., 1, :]
                    + b2 * corners[..., 2, :]
                )
            else:
                v = values[idx]
            return np.where(visible[..., None], v, 0.0).mean(axis=2)

        if mode == "radiosity":
            return Image(sample(self.B / np.pi), stats={"mode": mode, "method": self.method})
        if mode == "elements":
            colours = np.random.default_rng(12345).uniform(0.15, 1.0, size=(len(self.patches), 3))
            flat = np.where(visible[..., None], colours[idx], 0.0)
            return Image(flat.mean(axis=2), stats={"mode": mode, "method": self.method})
        if mode == "links":
            if self.link_density is None:
                raise ValueError("mode 'links' needs a hierarchical solution")
            density = np.log10(np.maximum(self.link_density, 1e-30))[:, None]
            lo = float(np.percentile(density, 1))
            values = np.where(visible[..., None], (density - lo)[idx], 0.0).mean(axis=2)
            t = self._normalised(values[..., 0], visible)
            ramp = np.stack(
                [np.clip(3 * t, 0, 1), np.clip(3 * t - 1, 0, 1), np.clip(3 * t - 2, 0, 1)], -1
            )
            return Image(ramp, stats={"mode": mode, "method": self.method})
        if self.I is None:
            raise ValueError("importance was not solved: call solve(..., importance=True)")
        # Importance per unit area (the adjoint of radiosity): independent of the meshing.
        density = (self.I.mean(axis=1) / self.patches.areas)[:, None]
        if mode == "importance":
            t = self._normalised(sample(density)[..., 0], visible)
            ramp = np.stack(
                [np.clip(3 * t, 0, 1), np.clip(3 * t - 1, 0, 1), np.clip(3 * t - 2, 0, 1)], -1
            )
            return Image(ramp, stats={"mode": mode, "method": self.method})
        if mode == "superposition":
            radiance = sample(self.B / np.pi)
            lum = radiance @ np.array([0.2126, 0.7152, 0.0722])
            grey = self._normalised(lum, visible)[..., None]
            # Reflected light times how much it matters for the view [Smits et al. 1992]
            # (emission is left out: it would only mark the lights).
            luminance_B = ((self.B - self.E) @ np.array([0.2126, 0.7152, 0.0722]))[:, None]
            t = self._normalised(sample(luminance_B * density)[..., 0], visible)[..., None]
            yellow = np.array([1.0, 0.85, 0.0])
            out = (1 - t) * grey * 0.7 + t * yellow * (0.4 + 0.6 * grey)
            return Image(out, stats={"mode": mode, "method": self.method})
        raise ValueError(f"mode must be 'radiosity', 'importance' or 'superposition', got {mode!r}")


def form_factors(
    patches: PatchMesh,
    *,
    quadrature: int = 3,
    shadow_rays: int = 4,
    seed: int = 0,
    threads: int = 0,
    progress: Callable[[int, int], None] | None = None,
    skip: bool = True,
    receivers: np.ndarray | None = None,
) -> tuple[_core.FormFactors, dict[str, Any]]:
    """Form factors of patch pairs (sparse) and stats (pairs, rays, seconds, rays/s,
    reciprocity and closure errors).

    With ``skip`` (the default), work that cannot matter is left out and counted in
    ``stats["skipped"]``: visibility rays in a convex enclosure (facing patches always see
    each other there), rows of patches that reflect nothing (their radiosity is their
    emission), and, given ``receivers`` (``R_i > 0`` per patch: the view that is wanted),
    rows of patches of zero importance for that view. Skipped rows are empty; the
    reciprocity and closure checks then cover the rows that were computed.
    """
    options = _core.FormFactorOptions(
        quadrature=quadrature, shadow_rays=shadow_rays, seed=seed, threads=threads
    )
    options.skip_unneeded = skip
    scatters = receivers_arg = None
    if skip:
        scatters = (np.max(patches.reflectance, axis=1) > 0).astype(np.uint8)
        if receivers is not None:
            receivers_arg = (np.asarray(receivers).reshape(len(patches), -1) > 0).any(axis=1)
            receivers_arg = receivers_arg.astype(np.uint8)
    elif receivers is not None:
        raise ValueError("receivers (view-only rows) needs skip=True")
    F, raw = _core.compute_form_factors(
        patches._compile(), options, progress, scatters=scatters, receivers=receivers_arg
    )
    raw = dict(raw)
    stats: dict[str, Any] = {
        k: raw[k]
        for k in ("pairs_tested", "pairs_facing", "rays", "seconds", "rays_per_second")
    }
    stats.update(quadrature=quadrature, shadow_rays=shadow_rays, nonzeros=int(F.nonzeros))
    stats["important_patches"] = int(raw["important_patches"])
    stats["view_only"] = receivers is not None
    stats["skipped"] = {
        "enabled": skip,
        "visibility_rays": int(raw["rays_skipped"]),
        "rows": int(raw["rows_skipped"]),
    }
    if raw["rows_skipped"] == 0:
        stats.update(form_factor_checks(F, patches.areas))
    return F, stats


def form_factor_checks(F: _core.FormFactors, areas: np.ndarray) -> dict[str, float]:
    """Reciprocity ``A_i F_ij = A_j F_ji`` and closure ``sum_j F_ij`` summaries (computed in
    C++ by merging F with its stored transpose: no extra memory)."""
    return dict(F.checks(np.ascontiguousarray(areas, dtype=np.float64)))


def _check_solve_arguments(
    scene: Any, camera: Any, tol: Any, max_iter: Any, seed: Any
) -> None:
    """Reject bad arguments before any form factor is computed, naming the argument (every
    method, including ``"direct"``, which takes a single step and would ignore ``max_iter``)."""
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a dualight.Scene, got {type(scene).__name__}")
    if camera is not None and not isinstance(camera, Camera):
        raise TypeError(f"camera must be a dualight.Camera, got {type(camera).__name__}")
    if not scene.meshes:
        raise ValueError("scene is empty: add a mesh with Scene.add_mesh")
    if isinstance(tol, bool) or not isinstance(tol, numbers.Real) or not 0 < tol < float("inf"):
        raise ValueError(f"tol must be a finite number > 0, got {tol!r}")
    if isinstance(max_iter, bool) or not isinstance(max_iter, numbers.Integral) or max_iter < 1:
        raise ValueError(f"max_iter must be an integer >= 1, got {max_iter!r}")
    if isinstance(seed, bool) or not isinstance(seed, numbers.Integral) or not 0 <= seed < 2**64:
        raise ValueError(f"seed must be an integer in [0, 2**64), got {seed!r}")


def solve(
    scene: Scene,
    method: str = "direct",
    *,
    max_edge: float | None = None,
    max_area: float | None = None,
    tol: float = 1e-6,
    max_iter: int = 1000,
    importance: bool = True,
    camera: Camera | None = None,
    window: tuple[int, int, int, int] | None = None,
    quadrature: int = 3,
    shadow_rays: int = 4,
    seed: int = 0,
    threads: int | None = None,
    progress: bool | Callable[[int, int], None] = False,
    patches: PatchMesh | None = None,
    precomputed: tuple[_core.FormFactors, dict[str, Any]] | None = None,
    oracle: str = "importance",
    epsilon: float = 1e-3,
    min_area: float | None = None,
    max_links: int = 20_000_000,
    view_only: bool = False,
    skip: bool = True,
) -> Solution:
    """Solve the radiosity system of a diffuse scene and, with ``importance``, its dual.

    Parameters
    ----------
    method:
        ``"direct"`` (dense LU), ``"jacobi"``, ``"gauss_seidel"`` (gathering),
        ``"southwell"`` (shooting, progressive refinement) or ``"hierarchical"`` (links
        between element trees, see :mod:`dualight.radiosity.hierarchical`).
    max_edge, max_area:
        Patch size (see :class:`PatchMesh`); by default 1/10 of the scene's largest extent.
    tol, max_iter:
        Iterative methods stop when the relative residual ``max |b - M x| / max |b|`` is at
        most ``tol``; if ``max_iter`` steps do not get there a :class:`ConvergenceWarning` is
        issued and ``solution.stats["converged"]`` is False.
    importance:
        Also solve ``M^T I = R`` with the same method (the dual: gathering importance is
        shooting energy and vice versa).
    camera, window:
        The view that defines the receiver ``R`` (default ``scene.camera``), optionally a
        pixel window ``(x0, y0, x1, y1)``.
    quadrature, shadow_rays, seed:
        Form-factor accuracy (see :func:`form_factors`).
    patches, precomputed:
        Reuse a patch mesh and its form factors (for comparing methods on one system).
    oracle, epsilon, min_area, max_links:
        Hierarchical only: refinement oracle (``"importance"`` or ``"bf"``), its relative
        threshold, the smallest element area and a cap on links; ``max_iter`` bounds the
        refine-and-solve iterations and ``tol`` the change per sweep.
    view_only:
        Only the camera's view is wanted: form factors are computed only for patches of
        non-zero importance (those the camera sees and, recursively, those seen from an
        important patch that reflects), in waves. ``B`` is then exact on those patches and
        left at ``E`` elsewhere (``solution.solved`` marks which), and ``I`` is exact
        everywhere; the measurement is unchanged. Drawing the solution from a camera that
        sees an unsolved patch raises ``ValueError``.
    skip:
        Leave out work that cannot matter (see :func:`form_factors`); ``stats["skipped"]``
        says what. ``False`` computes everything (for measuring what skipping saves).
    """
    _check_solve_arguments(scene, camera, tol, max_iter, seed)
    for name, flag in (("view_only", view_only), ("skip", skip)):
        if not isinstance(flag, bool):
            raise TypeError(f"{name} must be True or False, got {flag!r}")
    if view_only and not skip:
        raise ValueError("view_only=True skips rows: it needs skip=True")
    if view_only and method == "hierarchical":
        raise ValueError(
            "view_only applies to the patch solvers; hierarchical radiosity already refines "
            "by importance"
        )
    if method == "hierarchical":
        from dualight.radiosity.hierarchical import HierarchicalSolver

        solver = HierarchicalSolver(
            scene,
            camera=camera,
            window=window,
            oracle=oracle,  # type: ignore[arg-type]
            epsilon=epsilon,
            min_area=min_area,
            shadow_rays=shadow_rays,
            tolerance=tol,
            seed=seed,
            threads=threads or 0,
            max_links=max_links,
            skip=skip,
        )
        solver.solve(max_iter=min(max_iter, 100))
        if not solver.converged:
            warnings.warn(
                f"hierarchical refinement still refining after {len(solver.history)} steps",
                ConvergenceWarning,
                stacklevel=2,
            )
        return solver.solution()
    if method not in SOLVERS:
        valid = ", ".join([*SOLVERS, "hierarchical"])
        raise ValueError(f"unknown method {method!r}; choose one of {valid}")
    cam = camera or scene.camera
    if cam is None:
        raise ValueError("the receiver needs a camera: pass camera= or give the scene one")
    if not scene.has_emitters:
        raise ValueError("scene has no emitter: give some mesh a positive emission")
    if patches is None:
        if max_edge is None and max_area is None:
            lo, hi = scene.bounds()
            max_edge = float(np.max(hi - lo)) / 10.0  # ~3,000 patches in a Cornell box
        patches = PatchMesh(scene, max_edge=max_edge, max_area=max_area)
    n_threads = threads or 0
    start = time.perf_counter()
    callback = None
    bar = None
    if progress is True:
        from dualight.render import _TqdmProgress

        bar = _TqdmProgress("form factors")
        callback = bar
    elif callable(progress):
        callback = progress
    R = receiver(patches, cam, window=window, seed=seed)
    if precomputed is not None and precomputed[1].get("view_only"):
        raise ValueError(
            "precomputed form factors were computed for one view only (view_only=True): "
            "they lack the rows other views need"
        )
    try:
        F, ff_stats = precomputed or form_factors(
            patches,
            quadrature=quadrature,
            shadow_rays=shadow_rays,
            seed=seed,
            threads=n_threads,
            progress=callback,
            skip=skip,
            receivers=R if view_only else None,
        )
    finally:
        if bar is not None:
            bar.close()
    system = _core.RadiositySystem(F, patches.reflectance, patches.areas)
    E = patches.emission
    R3 = np.repeat(R[:, None], 3, axis=1)

    stats: dict[str, Any] = {"patches": len(patches), "form_factors": ff_stats, "method": method}
    history: dict[str, list[Step]] = {}
    solve_start = time.perf_counter()

    def run(rhs: np.ndarray, dual: bool, factors: Any = None) -> tuple[np.ndarray, Any]:
        cls = SOLVERS[method]
        if cls is DirectSolver:
            solver = DirectSolver(system, rhs, dual=dual, factors=factors, threads=n_threads)
        elif method == "jacobi":
            solver = cls(system, rhs, dual=dual, threads=n_threads)  # type: ignore[call-arg]
        else:
            solver = cls(system, rhs, dual=dual)  # type: ignore[call-arg]
        steps = solver.solve(tol=tol, max_iter=1 if cls is DirectSolver else max_iter)
        side = "importance" if dual else "radiosity"
        history[side] = steps
        if not solver.converged(tol):
            warnings.warn(
                f"{method} did not converge for {side}: residual {solver.residual:.3g} > tol "
                f"{tol:g} after {len(steps)} steps",
                ConvergenceWarning,
                stacklevel=3,
            )
        stats[f"{side}_residual"] = solver.residual
        stats[f"{side}_iterations"] = len(steps)
        stats[f"{side}_converged"] = solver.converged(tol)
        return np.array(solver.solution), getattr(solver, "factors", None)

    B, factors = run(E, dual=False)
    I_dual = run(R3, dual=True, factors=factors)[0] if importance else None  # noqa: N806
    stats["converged"] = stats["radiosity_converged"] and (
        not importance or stats["importance_converged"]
    )
    stats["solve_seconds"] = time.perf_counter() - solve_start
    stats["seconds"] = time.perf_counter() - start
    stats["skipped"] = dict(ff_stats.get("skipped", {}))
    solved = None
    if view_only:
        # Important patches: those seen (R > 0) and every column of the rows computed.
        seen_from_rows = np.bincount(np.asarray(F.indices), minlength=len(patches)) > 0
        solved = (R > 0) | seen_from_rows
    return Solution(
        patches=patches,
        B=B,
        I=I_dual,
        E=E,
        R=R3,
        form_factors=F,
        camera=cam,
        method=method,
        stats=stats,
        history=history,
        solved=solved,
    )
