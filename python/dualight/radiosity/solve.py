"""`solve`: the radiosity and importance of a diffuse scene by one of the patch solvers or by
hierarchical radiosity, and the form factors the patch solvers share."""

from __future__ import annotations

import numbers
import time
import warnings
from collections.abc import Callable
from typing import Any

import numpy as np

from dualight import _core
from dualight.methods import RadiosityMethod
from dualight.radiosity.hierarchical import HierarchicalSolver, Oracle
from dualight.radiosity.patches import PatchMesh
from dualight.radiosity.solution import Solution, receiver
from dualight.radiosity.solvers import SOLVERS, DirectSolver, Step
from dualight.scene import Camera, Scene, _freezes_scene

# The core's defaults of the options these functions pass on.
_FORM_FACTORS = _core.FormFactorOptions()
_HIERARCHICAL = _core.HierarchicalOptions()


class ConvergenceWarning(RuntimeWarning):
    """An iterative solver stopped at max_iter with its residual above tol."""


def form_factors(
    patches: PatchMesh,
    *,
    quadrature: int = _FORM_FACTORS.quadrature,
    shadow_rays: int = _FORM_FACTORS.shadow_rays,
    seed: int = _FORM_FACTORS.seed,
    threads: int = _FORM_FACTORS.threads,
    progress: Callable[[int, int], None] | None = None,
    skip: bool = _FORM_FACTORS.skip_unneeded,
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
        quadrature=quadrature,
        shadow_rays=shadow_rays,
        seed=seed,
        threads=threads,
        skip_unneeded=skip,
    )
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
        k: raw[k] for k in ("pairs_tested", "pairs_facing", "rays", "seconds", "rays_per_second")
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


def _progress_of(
    progress: bool | Callable[[int, int], None], label: str
) -> tuple[Callable[[int, int], None] | None, Any]:
    """The core's callback for ``progress`` (a tqdm bar named ``label`` for True, which the
    caller closes) and the bar (None unless True)."""
    if progress is True:
        from dualight._progress import TqdmProgress

        bar = TqdmProgress(label)
        return bar, bar
    return (progress if callable(progress) else None), None


def _keep_partial(error: BaseException, partial: Solution) -> None:
    try:
        error.partial_result = partial  # type: ignore[attr-defined]
    except (AttributeError, TypeError):  # an exception type without attributes: raised as it is
        pass


def _check_solve_arguments(scene: Any, camera: Any, tol: Any, max_iter: Any, seed: Any) -> None:
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


@_freezes_scene
def solve(
    scene: Scene,
    method: RadiosityMethod = "direct",
    *,
    max_edge: float | None = None,
    max_area: float | None = None,
    tol: float = 1e-6,
    max_iter: int = 1000,
    importance: bool = True,
    camera: Camera | None = None,
    window: tuple[int, int, int, int] | None = None,
    quadrature: int = _FORM_FACTORS.quadrature,
    shadow_rays: int = _FORM_FACTORS.shadow_rays,
    seed: int = 0,
    threads: int | None = None,
    progress: bool | Callable[[int, int], None] = False,
    patches: PatchMesh | None = None,
    precomputed: tuple[_core.FormFactors, dict[str, Any]] | None = None,
    oracle: Oracle = _HIERARCHICAL.oracle.name,  # type: ignore[assignment]
    epsilon: float = _HIERARCHICAL.epsilon,
    min_area: float | None = None,
    max_links: int = _HIERARCHICAL.max_links,
    view_only: bool = False,
    skip: bool = True,
    samples_per_axis: int = 4,
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
    samples_per_axis:
        Stratified camera samples per pixel and axis (1 to 64) that define the receiver ``R``
        and so the measurement. The default 4 x 4 leaves the hierarchical measurement of the
        64 x 64 Cornell box a seed-dependent error of about 1 % (the importance oracle
        refines where the samples land); 16 x 16 takes it under 0.1 %.
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
        callback, bar = _progress_of(progress, "hierarchical linking")
        try:
            solver = HierarchicalSolver(
                scene,
                camera=camera,
                window=window,
                oracle=oracle,
                epsilon=epsilon,
                min_area=min_area,
                shadow_rays=shadow_rays,
                tolerance=tol,
                seed=seed,
                threads=threads or 0,
                max_links=max_links,
                skip=skip,
                samples_per_axis=samples_per_axis,
                progress=callback,
            )
        finally:
            if bar is not None:
                bar.close()
        callback, bar = _progress_of(progress, "hierarchical refinement")
        try:
            solver.solve(max_iter=min(max_iter, 100), progress=callback)
        except BaseException as error:
            # Ctrl-C or another exception during a step: the hierarchy of the steps before it
            # is a solution (coarser), kept on the exception as for renders.
            if solver.history:
                _keep_partial(error, solver.solution())
            raise
        finally:
            if bar is not None:
                bar.close()
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
    if method == "direct" and len(patches) > _core.MAX_DIRECT_PATCHES:
        # Before the form factors: they took minutes before the solver refused (issue 18).
        raise ValueError(
            f"the direct solver holds a dense n x n matrix: {len(patches)} patches is more "
            f"than {_core.MAX_DIRECT_PATCHES}; use an iterative method (gauss_seidel, jacobi, "
            "southwell) or a larger max_edge"
        )
    n_threads = threads or 0
    start = time.perf_counter()
    R = receiver(patches, cam, window=window, seed=seed, samples_per_axis=samples_per_axis)
    if precomputed is not None and precomputed[1].get("view_only"):
        raise ValueError(
            "precomputed form factors were computed for one view only (view_only=True): "
            "they lack the rows other views need"
        )
    callback, bar = _progress_of(progress, "form factors")
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
    # Point, spot and directional lights and environments enter as their first shot: the
    # reflected part of the irradiance they give each patch directly (Cohen and Wallace 1993,
    # sec. 2.3).
    E = patches.emission
    if scene.emitters:
        callback, bar = _progress_of(progress, "direct light")
        try:
            E = E + patches.reflectance * patches.direct_irradiance(
                threads=n_threads, progress=callback
            )
        finally:
            if bar is not None:
                bar.close()
    R3 = np.repeat(R[:, None], 3, axis=1)

    stats: dict[str, Any] = {"patches": len(patches), "form_factors": ff_stats, "method": method}
    history: dict[str, list[Step]] = {}
    solve_start = time.perf_counter()

    def run(rhs: np.ndarray, dual: bool, factors: Any = None) -> tuple[np.ndarray, Any]:
        cls = SOLVERS[method]
        if cls is DirectSolver:
            callback, bar = (None, None)
            if factors is None:
                callback, bar = _progress_of(progress, "LU factorisation")
            try:
                solver = DirectSolver(
                    system, rhs, dual=dual, factors=factors, threads=n_threads, progress=callback
                )
            finally:
                if bar is not None:
                    bar.close()
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
