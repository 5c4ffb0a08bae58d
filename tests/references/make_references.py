"""Render the Mitsuba 3 reference images that the tests compare against.

Usage (from the repository root, with Mitsuba installed); they are written into the package,
``python/dualight/data/references`` (shipped as package data, so ``python -m dualight bench``
and the notebooks find them in a pip install), unless ``--out`` says otherwise::

    .venv/bin/python tests/references/make_references.py            # every reference
    .venv/bin/python tests/references/make_references.py cornell_64  # just one

Each reference ``NAME`` is stored as two float32 EXR files written by ``dualight.Image``:
``NAME_mean.exr`` (mean radiance) and ``NAME_var.exr`` (per-pixel variance *of that mean*), both
carrying the render settings as metadata (``scene``, ``spp``, ``seed``, ``variant``,
``max_depth``, ``rr_depth``, ``mitsuba``, ``seconds``, ``quantity``).

The references (see README.md beside them for how long they took):

* ``cornell_64``: ``cornell_box(resolution=(64, 64))``, ``max_depth=8`` (bounded, so every
  renderer stops at the same path length), ``rr_depth=5`` (Mitsuba's default: Russian roulette
  keeps the mean, which is all the Welch test compares; the variances are each renderer's own).
* ``furnace_64``: ``furnace(0.5, 1.0, (64, 64))``, ``max_depth=16``, ``rr_depth=5``. With paths
  of at most ``k`` segments its radiance is ``sum_{i<k} rho^i Le = Le (1 - rho^k) / (1 - rho)``
  everywhere, here ``2 (1 - 2^-16)``.
* ``cornell_64_full``: the same Cornell box with ``max_depth=-1`` (unbounded: every bounce,
  ended only by Russian roulette from ``rr_depth=5``, which keeps the mean). This is the full
  global illumination that radiosity computes (it counts every bounce), so
  ``tests/test_radiosity_vs_mitsuba.py`` compares against it.
* ``door_64``: ``door_ajar(resolution=(64, 64))`` (Veach's door, 10 degrees open),
  ``max_depth=8``, ``rr_depth=5``. Light reaches the camera's room only through the gap, so a
  path tracer needs many samples: each pixel's relative standard deviation of one sample is
  about 16 (median), hence the 524288 spp.
* ``caustics_64``: ``cornell_box(resolution=(64, 64), variant="caustics")`` (the Cornell box
  with a mirror and a glass sphere, ``ior=1.5``), ``max_depth=8``, ``rr_depth=5``.
* ``glossy_64``: ``cornell_box(resolution=(64, 64), variant="glossy")`` (rough gold and
  frosted-glass spheres on a rough-plastic floor: Mitsuba's ``roughconductor``,
  ``roughdielectric`` and ``roughplastic``), ``max_depth=8``, ``rr_depth=5``.
* ``coated_64``: ``cornell_box(resolution=(64, 64), variant="coated")`` (a smooth copper
  sphere, a thin-glass bubble, a smooth-plastic floor: ``conductor``, ``thindielectric``,
  ``plastic``), ``max_depth=8``, ``rr_depth=5``.
* ``smooth_64``: ``cornell_box(resolution=(64, 64), variant="smooth")`` (coarse white and
  glass spheres shaded by their vertex normals), ``max_depth=8``, ``rr_depth=5``.
* ``textured_64``: ``cornell_box(resolution=(64, 64), variant="textured")`` (a bitmap back
  wall, a checkerboard floor, an aluminium block of checkerboard roughness), ``max_depth=8``,
  ``rr_depth=5``.
* ``lamp_64``: the classic box whose ceiling light's radiance is a bitmap texture.
* ``sun_64``, ``sky_64``, ``envmap_64``: the open-top box lit by a directional light, a
  constant environment and an environment map (``cornell_box(variant=...)``).
* ``veach_mis_64``, ``veach_bidir_64``, ``door_glossy_64``: Veach's scenes
  (``veach_mis()``, ``veach_bidir()``, ``door_ajar(variant="glossy")`` at 64 x 64),
  ``max_depth=8``, ``rr_depth=5``.
* ``point_64``, ``spot_64``: ``cornell_box(resolution=(64, 64), variant="point")`` and
  ``variant="spot"`` (the classic box lit by a point light or a spot light below the ceiling),
  ``max_depth=8``, ``rr_depth=5``.
* ``rooms10_64``: ``rooms(10, resolution=(64, 64))`` (ten diffuse rooms joined by doors, the
  importance-driven radiosity scene; path guiding's seeded variant is measured on it),
  ``max_depth=8``, ``rr_depth=5``; ``rooms10_dark_64`` the same building seen from room 1 left
  dark (``camera_room=1, camera_room_lit=False``): lit only through its doors.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parents[2] / "python" / "dualight" / "data" / "references"


@dataclass(frozen=True)
class Reference:
    """How one reference is rendered."""

    name: str
    scene: str  # a Python expression in dualight.scenes, recorded in the metadata
    build: Callable[[], object]
    spp: int
    max_depth: int
    rr_depth: int = 5
    seed: int = 0


def _references() -> dict[str, Reference]:
    from dualight import scenes

    refs = [
        Reference(
            "cornell_64",
            "cornell_box(resolution=(64, 64))",
            lambda: scenes.cornell_box(resolution=(64, 64)),
            spp=262144,
            max_depth=8,
        ),
        Reference(
            "furnace_64",
            "furnace(0.5, 1.0, (64, 64))",
            lambda: scenes.furnace(0.5, 1.0, (64, 64)),
            spp=16384,
            max_depth=16,
        ),
        Reference(
            "cornell_64_full",
            "cornell_box(resolution=(64, 64))",
            lambda: scenes.cornell_box(resolution=(64, 64)),
            spp=262144,
            max_depth=-1,
        ),
        Reference(
            "door_64",
            "door_ajar(resolution=(64, 64))",
            lambda: scenes.door_ajar(resolution=(64, 64)),
            spp=524288,
            max_depth=8,
        ),
        Reference(
            "caustics_64",
            'cornell_box(resolution=(64, 64), variant="caustics")',
            lambda: scenes.cornell_box(resolution=(64, 64), variant="caustics"),
            spp=262144,
            max_depth=8,
        ),
        Reference(
            "glossy_64",
            'cornell_box(resolution=(64, 64), variant="glossy")',
            lambda: scenes.cornell_box(resolution=(64, 64), variant="glossy"),
            spp=131072,
            max_depth=8,
        ),
        Reference(
            "coated_64",
            'cornell_box(resolution=(64, 64), variant="coated")',
            lambda: scenes.cornell_box(resolution=(64, 64), variant="coated"),
            spp=131072,
            max_depth=8,
        ),
        Reference(
            "textured_64",
            'cornell_box(resolution=(64, 64), variant="textured")',
            lambda: scenes.cornell_box(resolution=(64, 64), variant="textured"),
            spp=131072,
            max_depth=8,
        ),
        Reference(
            "smooth_64",
            'cornell_box(resolution=(64, 64), variant="smooth")',
            lambda: scenes.cornell_box(resolution=(64, 64), variant="smooth"),
            spp=131072,
            max_depth=8,
        ),
        Reference(
            "point_64",
            'cornell_box(resolution=(64, 64), variant="point")',
            lambda: scenes.cornell_box(resolution=(64, 64), variant="point"),
            spp=131072,
            max_depth=8,
        ),
        Reference(
            "spot_64",
            'cornell_box(resolution=(64, 64), variant="spot")',
            lambda: scenes.cornell_box(resolution=(64, 64), variant="spot"),
            spp=131072,
            max_depth=8,
        ),
        Reference(
            "sun_64",
            'cornell_box(resolution=(64, 64), variant="sun")',
            lambda: scenes.cornell_box(resolution=(64, 64), variant="sun"),
            spp=131072,
            max_depth=8,
        ),
        Reference(
            "sky_64",
            'cornell_box(resolution=(64, 64), variant="sky")',
            lambda: scenes.cornell_box(resolution=(64, 64), variant="sky"),
            spp=131072,
            max_depth=8,
        ),
        Reference(
            "envmap_64",
            'cornell_box(resolution=(64, 64), variant="envmap")',
            lambda: scenes.cornell_box(resolution=(64, 64), variant="envmap"),
            spp=131072,
            max_depth=8,
        ),
        Reference(
            "lamp_64",
            'cornell_box(resolution=(64, 64), variant="lamp")',
            lambda: scenes.cornell_box(resolution=(64, 64), variant="lamp"),
            spp=131072,
            max_depth=8,
        ),
        Reference(
            "veach_mis_64",
            "veach_mis(resolution=(64, 64))",
            lambda: scenes.veach_mis(resolution=(64, 64)),
            spp=131072,
            max_depth=8,
        ),
        Reference(
            "veach_bidir_64",
            "veach_bidir(resolution=(64, 64))",
            lambda: scenes.veach_bidir(resolution=(64, 64)),
            spp=131072,
            max_depth=8,
        ),
        Reference(
            "door_glossy_64",
            'door_ajar(resolution=(64, 64), variant="glossy")',
            lambda: scenes.door_ajar(resolution=(64, 64), variant="glossy"),
            spp=262144,
            max_depth=8,
        ),
        Reference(
            "rooms10_64",
            "rooms(10, resolution=(64, 64))",
            lambda: scenes.rooms(10, resolution=(64, 64)),
            spp=262144,
            max_depth=8,
        ),
        Reference(
            "rooms10_dark_64",
            "rooms(10, resolution=(64, 64), camera_room=1, camera_room_lit=False)",
            lambda: scenes.rooms(10, resolution=(64, 64), camera_room=1, camera_room_lit=False),
            spp=262144,
            max_depth=8,
        ),
    ]
    return {r.name: r for r in refs}


def load(name: str, directory: Path = HERE) -> tuple[np.ndarray, np.ndarray, dict[str, object]]:
    """The stored mean, variance of the mean and metadata of reference ``name``."""
    import dualight

    mean = dualight.Image.load(directory / f"{name}_mean.exr")
    var = dualight.Image.load(directory / f"{name}_var.exr")
    return np.asarray(mean), np.asarray(var), dict(mean.stats)


def noise(mean: np.ndarray, var: np.ndarray, block: int = 8) -> dict[str, list[float]]:
    """Relative noise of a reference: per RGB channel, the median over pixels of
    ``sqrt(var) / mean`` (standard deviation of a pixel mean over the mean) and the same for the
    means of ``block x block`` pixel blocks (whose variance is the sum of the pixels' over
    ``block**4``). Pixels or blocks with a zero mean are left out."""
    h, w, _ = mean.shape
    hb, wb = h // block, w // block
    m = mean[: hb * block, : wb * block].reshape(hb, block, wb, block, 3).mean(axis=(1, 3))
    v = var[: hb * block, : wb * block].reshape(hb, block, wb, block, 3).sum(axis=(1, 3))
    v = v / block**4

    def median_rel(mu: np.ndarray, s2: np.ndarray) -> list[float]:
        out = []
        for c in range(3):
            ok = mu[..., c] > 0.0
            out.append(float(np.median(np.sqrt(s2[..., c][ok]) / mu[..., c][ok])))
        return out

    return {"pixel": median_rel(mean, var), "block": median_rel(m, v)}


def make(ref: Reference, directory: Path = HERE, variant: str | None = None) -> float:
    """Render and store ``ref``; return the render time in seconds."""
    import mitsuba as mi

    import dualight
    from dualight import mitsuba as dm

    chosen = dm.variant(variant) if variant else dm.variant()
    scene = ref.build()
    start = time.perf_counter()
    mean, var = dm.reference(
        scene, ref.spp, ref.seed, max_depth=ref.max_depth, rr_depth=ref.rr_depth, variant=chosen
    )
    seconds = time.perf_counter() - start
    stats: dict[str, object] = {
        "scene": ref.scene,
        "spp": ref.spp,
        "seed": ref.seed,
        "variant": chosen,
        "max_depth": ref.max_depth,
        "rr_depth": ref.rr_depth,
        "integrator": "path (dualight.mitsuba.reference)",
        "mitsuba": mi.__version__,
        "seconds": round(seconds, 1),
    }
    dualight.Image(mean, stats={**stats, "quantity": "mean"}).save(
        directory / f"{ref.name}_mean.exr"
    )
    dualight.Image(var, stats={**stats, "quantity": "variance of the mean"}).save(
        directory / f"{ref.name}_var.exr"
    )
    return seconds


def main(argv: list[str] | None = None) -> int:
    refs = _references()
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "names", nargs="*", help=f"references to render (default: all of {list(refs)})"
    )
    parser.add_argument("--variant", help="Mitsuba variant (default: dualight.mitsuba.variant())")
    parser.add_argument("--out", type=Path, default=HERE, help="output directory")
    args = parser.parse_args(argv)
    unknown = [n for n in args.names if n not in refs]
    if unknown:
        parser.error(f"unknown reference(s) {unknown}; choose from {list(refs)}")
    for name in args.names or list(refs):
        ref = refs[name]
        print(
            f"{name}: {ref.scene}, spp={ref.spp}, max_depth={ref.max_depth}, "
            f"rr_depth={ref.rr_depth}, seed={ref.seed} ...",
            flush=True,
        )
        seconds = make(ref, args.out, args.variant)
        mean, var, stats = load(name, args.out)
        rel = np.sqrt(var.mean(axis=(0, 1))) / np.maximum(mean.mean(axis=(0, 1)), 1e-12)
        med = noise(mean, var)
        print(
            f"  {seconds:.1f} s with {stats['variant']}; mean RGB "
            f"{np.round(mean.mean(axis=(0, 1)), 5).tolist()}, "
            f"rms relative std of a pixel mean {np.round(rel, 5).tolist()}, "
            f"median relative std of a pixel mean {np.round(med['pixel'], 5).tolist()}, "
            f"of an 8x8 block mean {np.round(med['block'], 5).tolist()}",
            flush=True,
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
