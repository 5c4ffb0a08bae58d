"""Path guiding's guides, to look at: :func:`train_guide` trains the guide that
``render(..., guiding=True)`` trains before its image, and returns it (a ``dualight._core.Guide``:
``pdf``, ``sample``, ``leaves``, ``directional``, ``stats``). :func:`plot_directional` draws one
point's distribution of directions.

Two guides, one per transport direction (the duality applied to path sampling): a radiance guide
learnt from camera paths (where light comes from, for ``"path"``) and an importance guide learnt
from light paths (where a particle will be seen by the camera, for ``"light"``). Each is an
SD-tree (Müller, Gross and Novák 2017): a binary tree over the scene's box with a quadtree of
directions in each leaf, built in iterations of 1, 2, 4, ... samples per pixel.
Guided BDPT (``render(..., "bdpt", guiding=True)``) trains and uses both.

:func:`solution_records` turns a radiosity and importance solution into records from which
``render(..., guide_from=solution)`` builds the guides its first training iteration samples.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Literal

import numpy as np

from dualight import _core
from dualight.methods import ESTIMATORS
from dualight.radiosity.solution import Solution
from dualight.render import _budget, _guiding_fields, _plain
from dualight.scene import Camera, Scene

Transport = Literal["radiance", "importance"]
"""``train_guide(transport=...)``: which guide: ``"radiance"`` from camera paths (the path
tracer's) or ``"importance"`` from light paths (the light tracer's)."""


def train_guide(
    scene: Scene,
    transport: Transport = "radiance",
    *,
    spp: int = 64,
    max_depth: int = -1,
    seed: int = 0,
    threads: int | None = None,
    camera: Camera | None = None,
    guiding: Mapping[str, Any] | None = None,
) -> Any:
    """Train the guide ``render(scene, "path" | "light", spp=spp, guiding=...)`` would (its
    share ``guiding["training"]`` of ``spp``, default a quarter, in iterations of doubling
    samples per pixel) and return it: a ``dualight._core.Guide``.

    ``guide.pdf(points, directions)`` gives solid-angle densities, ``guide.sample(points, u)``
    directions, ``guide.leaves()`` the spatial subdivision (boxes, with each leaf's node count
    and learnt BSDF fraction), ``guide.directional(x, y, z)`` the quadtree at a point, and
    ``guide.stats`` the training's iterations, seconds and tree sizes. Ctrl-C stops the
    training and raises ``KeyboardInterrupt`` with the guide so far as ``partial_result``."""
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a dualight.Scene, got {type(scene).__name__}")
    if transport not in ("radiance", "importance"):
        raise ValueError(f"transport must be 'radiance' or 'importance', got {transport!r}")
    if camera is not None and not isinstance(camera, Camera):
        raise TypeError(f"camera must be a dualight.Camera, got {type(camera).__name__}")
    method = "path" if transport == "radiance" else "light"
    estimator = ESTIMATORS[method]
    spp_checked, threads = _budget(estimator, spp, None, threads, None)
    fields = {
        "spp": spp_checked,
        "max_depth": _plain(max_depth),
        "seed": _plain(seed),
        "threads": threads or 0,
    }
    fields.update(_guiding_fields(dict(guiding or {}), estimator, method))
    options = estimator.options(**fields)
    scene.validate_for_rendering(camera)
    cam = camera or scene.camera
    assert cam is not None
    train = _core.train_radiance_guide if transport == "radiance" else _core.train_importance_guide
    result = train(scene._compile(), cam._compile(), options)
    if result["keyboard_interrupt"]:
        interrupt = KeyboardInterrupt()
        interrupt.partial_result = result["guide"]  # type: ignore[attr-defined]
        raise interrupt
    return result["guide"]


def plot_directional(guide: Any, point: tuple[float, float, float], ax: Any = None) -> Any:
    """Draw the guide's distribution of directions at ``point`` on the square of its cylindrical
    map (``u = (cos theta + 1) / 2`` across, ``v = phi / 2 pi`` up; world z is theta's axis),
    each quadtree cell shaded by its density (log scale). Returns the matplotlib axes."""
    import matplotlib.pyplot as plt
    from matplotlib.collections import PatchCollection
    from matplotlib.colors import LogNorm
    from matplotlib.patches import Rectangle

    cells = guide.directional(*(float(c) for c in point))
    if ax is None:
        _, ax = plt.subplots(figsize=(4, 4))
    density = np.maximum(cells[:, 3], 1e-3) if len(cells) else np.ones(1)
    patches = [Rectangle((u0, v0), s, s) for u0, v0, s, _ in cells]
    collection = PatchCollection(
        patches, cmap="magma", norm=LogNorm(1e-3, max(density.max(), 1e-2))
    )
    collection.set_array(density)
    ax.add_collection(collection)
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.set_aspect("equal")
    ax.set_xlabel("(cos theta + 1) / 2")
    ax.set_ylabel("phi / 2 pi")
    ax.figure.colorbar(collection, ax=ax, label="density on the square")
    return ax


def solution_records(
    solution: Solution,
    transport: Transport,
    *,
    records: int = 1 << 18,
    seed: int = 0,
) -> np.ndarray:
    """Guide records (rows ``x, y, z, wx, wy, wz, value``) from a radiosity solution, as
    ``render(..., guide_from=solution)`` seeds its guides with (Peter and Pietrek 1998's idea:
    start light paths towards what the camera sees).

    About ``records`` rows in all: at random points of each patch ``i``, directions towards a
    random point of a patch ``j`` drawn with probability ``F_ij / sum_j F_ij`` (so occluded
    patches are never chosen); ``value`` is the quantity arriving along the direction over the
    direction's solid-angle density. ``"radiance"``: ``B_j / pi`` (the radiance patch ``j``
    sends, emission included). ``"importance"``: ``rho_j I_j / A_j`` (the measurement a unit of
    power arriving at ``j`` makes, from the importance solution ``M^T I = R``). Colours are
    averaged over channels. Needs the solution's form factors (not a hierarchical solution's
    links) and, for importance, ``solve(..., importance=True)``."""
    if transport not in ("radiance", "importance"):
        raise ValueError(f"transport must be 'radiance' or 'importance', got {transport!r}")
    F = getattr(solution, "form_factors", None)
    if F is None:
        raise ValueError(
            "guide_from needs a radiosity solution with form factors (method 'direct', "
            "'jacobi', 'gauss_seidel' or 'southwell'; a hierarchical one has links instead)"
        )
    if transport == "importance" and solution.I is None:
        raise ValueError("guide_from needs the importance solution: solve(..., importance=True)")
    if (
        isinstance(records, bool)
        or not isinstance(records, int | np.integer)
        or not 1 <= records <= _core.MAX_GUIDE_RECORDS
    ):
        raise ValueError(f"records must be an int in [1, 2^24], got {records!r}")
    pm = solution.patches
    indptr = np.asarray(F.indptr, dtype=np.int64)
    indices = np.asarray(F.indices, dtype=np.int64)
    values = np.asarray(F.values, dtype=np.float64)
    # Row i's form factors are values[indptr[i]:indptr[i + 1]]: its sum and the sampling below
    # read the same running sum (rows may be empty, the last ones too).
    cum = np.concatenate([[0.0], np.cumsum(values)])
    row_sum = cum[indptr[1:]] - cum[indptr[:-1]]
    if transport == "radiance":
        q = np.asarray(solution.B, dtype=np.float64).mean(axis=1) / np.pi
    else:
        rho_I = np.asarray(solution.rho, dtype=np.float64) * np.asarray(solution.I)  # noqa: N806
        q = rho_I.mean(axis=1) / pm.areas
    senders = np.flatnonzero(row_sum > 0.0)
    if len(senders) == 0:
        raise ValueError("the solution's form factors are all zero: no patch sees another")
    per_patch = max(1, records // len(senders))
    rng = np.random.default_rng(seed)
    i = np.repeat(senders, per_patch)
    target = cum[indptr[i]] + rng.random(len(i)) * row_sum[i]
    pos = np.clip(np.searchsorted(cum, target, side="right") - 1, indptr[i], indptr[i + 1] - 1)
    j = indices[pos]

    def points(patch: np.ndarray) -> np.ndarray:
        v = pm.vertices[pm.triangles[patch]]
        a, b = rng.random(len(patch)), rng.random(len(patch))
        s = np.sqrt(a)[:, None]
        b = b[:, None]
        return (1 - s) * v[:, 0] + s * (1 - b) * v[:, 1] + s * b * v[:, 2]

    p_i, p_j = points(i), points(j)
    d = p_j - p_i
    r2 = np.einsum("ij,ij->i", d, d)
    with np.errstate(divide="ignore", invalid="ignore"):
        w = d / np.sqrt(r2)[:, None]
        cos_j = np.abs(np.einsum("ij,ij->i", pm.normals[j], w))
        pdf_w = values[pos] / row_sum[i] * r2 / (cos_j * pm.areas[j])
        value = q[j] / pdf_w
    keep = (r2 > 0) & (cos_j > 1e-4) & np.isfinite(value) & (value >= 0)
    out = np.concatenate([p_i, w, value[:, None]], axis=1)[keep]
    return out.astype(np.float32)
