"""Path guiding's guides, to look at: :func:`train_guide` trains the guide that
``render(..., guiding=True)`` trains before its image, and returns it (a ``dualight._core.Guide``:
``pdf``, ``sample``, ``leaves``, ``directional``, ``stats``). :func:`plot_directional` draws one
point's distribution of directions.

Two guides, one per transport direction (the duality applied to path sampling): a radiance guide
learnt from camera paths (where light comes from, for ``"path"``) and an importance guide learnt
from light paths (where a particle will be seen by the camera, for ``"light"``). Each is an
SD-tree (Müller, Gross and Novák 2017): a binary tree over the scene's box with a quadtree of
directions in each leaf, built in iterations of 1, 2, 4, ... samples per pixel.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Literal

import numpy as np

from dualight import _core
from dualight.methods import ESTIMATORS
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
