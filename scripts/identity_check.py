"""Bit-identity check for refactors: renders every method and solves every radiosity system
on the reference scenes with fixed seeds, and saves (``--save``) or compares (``--compare``)
the raw arrays.

A refactor is judged by identical output: run ``--save before.npz`` on the old commit and
``--compare before.npz`` on the new one. Every array must be equal bit for bit
(``np.array_equal`` with NaNs equal), and so must the integer counters of the stats.

    .venv/bin/python scripts/identity_check.py --save build/identity_before.npz
    .venv/bin/python scripts/identity_check.py --compare build/identity_before.npz
"""

from __future__ import annotations

import argparse
import sys
import time
from typing import Any

import numpy as np

import dualight
from dualight import radiosity, scenes

RES = (40, 40)
SPP = 16
MUTATIONS = 16
MLT_SMALL = {"bootstrap": 4000, "chains": 32, "direct_spp": 4}


def _scenes() -> dict[str, dualight.Scene]:
    return {
        "cornell": scenes.cornell_box(RES),
        "caustics": scenes.cornell_box(RES, variant="caustics"),
        "door": scenes.door_ajar(RES),
        "rooms4": scenes.rooms(4, resolution=RES),
    }


def _configurations() -> list[tuple[str, dict[str, Any]]]:
    depth = dict(max_depth=6)
    return [
        ("path", dict(method="path", spp=SPP, **depth)),
        ("path_unbounded", dict(method="path", spp=SPP)),
        ("path_sobol", dict(method="path", spp=SPP, sampler="sobol", **depth)),
        ("light", dict(method="light", spp=SPP, **depth)),
        ("bdpt", dict(method="bdpt", spp=SPP, **depth)),
        ("bdpt_balance", dict(method="bdpt", spp=SPP, heuristic="balance", **depth)),
        ("bdpt_strategies", dict(method="bdpt", spp=SPP, strategy_images=True, **depth)),
        ("pssmlt", dict(method="pssmlt", spp=MUTATIONS, mlt=dict(MLT_SMALL), **depth)),
        (
            "pssmlt_nomis",
            dict(
                method="pssmlt", spp=MUTATIONS, mlt=dict(MLT_SMALL, large_step_mis=False), **depth
            ),
        ),
        ("mmlt", dict(method="mmlt", spp=MUTATIONS, mlt=dict(MLT_SMALL), **depth)),
        ("mlt_luminance", dict(method="mlt", spp=MUTATIONS, mlt=dict(MLT_SMALL), **depth)),
        (
            "mlt_flattened",
            dict(method="mlt", spp=MUTATIONS, mlt=dict(MLT_SMALL, importance="flattened"), **depth),
        ),
    ]


RADIOSITY = ("direct", "jacobi", "gauss_seidel", "southwell", "hierarchical")
_COUNTERS = ("samples", "rays", "mutations", "accepted", "invalid_samples", "links")


def collect(selected: set[str] | None = None) -> dict[str, np.ndarray]:
    out: dict[str, np.ndarray] = {}
    for scene_name, scene in _scenes().items():
        for name, kw in _configurations():
            key = f"{scene_name}/{name}"
            if selected and not any(s in key for s in selected):
                continue
            start = time.perf_counter()
            image = dualight.render(scene, seed=7, threads=2, progress=False, **kw)
            out[key + "/mean"] = np.asarray(image)
            if image.variance is not None:
                out[key + "/variance"] = np.asarray(image.variance)
            for (s, t), layer in sorted((getattr(image, "strategies", None) or {}).items()):
                out[f"{key}/strategy_{s}_{t}"] = np.asarray(layer)
            for counter in _COUNTERS:
                if counter in image.stats:
                    out[f"{key}/{counter}"] = np.asarray(image.stats[counter])
            for float_stat in ("b", "b_per_depth"):
                if float_stat in image.stats:
                    out[f"{key}/{float_stat}"] = np.asarray(
                        image.stats[float_stat], dtype=np.float64
                    )
            print(f"{key}: {time.perf_counter() - start:.2f} s", flush=True)
        if scene.has_specular:
            continue
        for method in RADIOSITY:
            key = f"{scene_name}/radiosity_{method}"
            if selected and not any(s in key for s in selected):
                continue
            kw: dict[str, Any] = dict(seed=3, threads=2)
            if method == "hierarchical":
                kw.update(max_iter=4)
            else:
                kw.update(max_edge=0.25 * _extent(scene), max_iter=200)
            sol = radiosity.solve(scene, method, **kw)
            out[key + "/B"] = np.asarray(sol.B)
            if sol.I is not None:
                out[key + "/I"] = np.asarray(sol.I)
            print(f"{key}: done", flush=True)
    return out


def _extent(scene: dualight.Scene) -> float:
    lo, hi = scene.bounds()
    return float(np.max(np.asarray(hi) - np.asarray(lo)))


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    group = parser.add_mutually_exclusive_group(required=True)
    group.add_argument("--save", metavar="NPZ")
    group.add_argument("--compare", metavar="NPZ")
    parser.add_argument("--only", nargs="*", help="substrings of configuration keys to run")
    args = parser.parse_args()
    got = collect(set(args.only) if args.only else None)
    if args.save:
        np.savez_compressed(args.save, **got)
        print(f"saved {len(got)} arrays to {args.save}")
        return 0
    ref = np.load(args.compare)
    differing = []
    for key, value in got.items():
        if key not in ref.files:
            differing.append(f"{key}: missing from the reference")
        elif ref[key].shape != value.shape or not np.array_equal(ref[key], value, equal_nan=True):
            differing.append(f"{key}: differs")
    for line in differing:
        print(line)
    print(f"{len(got) - len(differing)} identical, {len(differing)} differing")
    return 1 if differing else 0


if __name__ == "__main__":
    sys.exit(main())
