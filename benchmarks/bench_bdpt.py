"""Equal-time error of the path tracer, the light tracer and BDPT (and Mitsuba 3's `path`)
on the Cornell box, its caustic variant and Veach's door scene.

Each estimator renders every scene for a series of time budgets (dualight: ``time_limit``;
Mitsuba: a series of spp, timed). Error is relMSE (pbrt-v4's definition) against the stored
Mitsuba references of the tests (``dualight/data/references/<scene>_64``, 64x64,
``max_depth`` 8). Those references are noisy themselves: the expected relMSE against a noisy
reference is the true relMSE plus the reference's own term ``mean(var_ref / (ref + eps)^2)``,
which is estimated from the reference's variance image and subtracted (``relmse`` is corrected,
``relmse_raw`` is not). Monte Carlo error falls as 1/time, so ``1 / (relMSE * seconds)`` is an
estimator's efficiency;
the ratio of two efficiencies is the ratio of their times to equal error. Ratios use the longest
budget. The light tracer cannot render pixels that see a mirror or glass directly, so its error
is also reported on the pixels it can render (``relmse_lt_pixels``, for every estimator).

Writes ``benchmarks/results/bench_bdpt.json`` and ``bench_bdpt.png`` (relMSE against seconds,
one panel per scene).

    python benchmarks/bench_bdpt.py            # budgets 0.5..8 s per render
    python benchmarks/bench_bdpt.py --quick    # budgets 0.25..1 s, for a smoke run
"""

from __future__ import annotations

import argparse
import ast
import inspect
import json
import os
import platform
import sys
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

import dualight
from dualight import metrics, scenes
from dualight import mitsuba as dmi
from dualight.bench import REFERENCE_DIR
from dualight.plotting import curves_by, save_relmse_against_time

HERE = Path(__file__).resolve().parent
RESULTS = HERE / "results"
REFERENCES = REFERENCE_DIR  # shipped with the package
sys.path[:0] = [str(HERE)]
from bench_path import time_mitsuba  # noqa: E402

SCENES: dict[str, tuple[str, Callable[[], dualight.Scene]]] = {
    "cornell": ("cornell_64", lambda: scenes.cornell_box(resolution=(64, 64))),
    "caustics": (
        "caustics_64",
        lambda: scenes.cornell_box(resolution=(64, 64), variant="caustics"),
    ),
    "door": ("door_64", lambda: scenes.door_ajar(resolution=(64, 64))),
}
METHODS = ("path", "light", "bdpt")
# (faster?, than) pairs whose equal-time efficiency ratio is reported.
RATIOS = [
    ("dualight_bdpt", "dualight_path"),
    ("dualight_bdpt", "dualight_light"),
    ("dualight_bdpt", "mitsuba_path"),
    ("dualight_path", "mitsuba_path"),
    ("dualight_light", "dualight_path"),
]
EPS = 1e-2  # relMSE's offset, as metrics.relmse


def load_reference(name: str) -> tuple[np.ndarray, np.ndarray, dict[str, Any]]:
    mean = dualight.Image.load(REFERENCES / f"{name}_mean.exr")
    var = dualight.Image.load(REFERENCES / f"{name}_var.exr")
    return np.asarray(mean), np.asarray(var), mean.stats


@dataclass
class Prepared:
    """A scene of SCENES with its stored reference (mean, variance, metadata) and the pixels
    the light tracer can render; its BVH is built."""

    name: str
    reference: str
    scene: dualight.Scene
    mean: np.ndarray
    variance: np.ndarray
    info: dict[str, Any]
    mask: np.ndarray


def _prepared(name: str, ref_name: str, build: Callable[[], dualight.Scene]) -> Prepared:
    scene = build()
    ref, ref_var, info = load_reference(ref_name)
    mask = metrics.renderable_by_light_tracing(scene)
    # One sample per pixel builds the BVH before any timed render.
    dualight.render(scene, "path", spp=1, max_depth=int(info["max_depth"]), progress=False)
    return Prepared(name, ref_name, scene, ref, ref_var, info, mask)


def prepared_scenes() -> Iterator[Prepared]:
    """Each scene of SCENES whose reference is stored (the others are skipped, saying so)."""
    for name, (ref_name, build) in SCENES.items():
        if not (REFERENCES / f"{ref_name}_mean.exr").exists():
            print(f"skipping {name}: no reference {ref_name} (tests/references/make_references.py)")
            continue
        yield _prepared(name, ref_name, build)


def scene_of_reference(expression: str) -> dualight.Scene:
    """The scene a stored reference's metadata names (``"cornell_box(resolution=(64, 64))"``):
    a call of a function of :mod:`dualight.scenes` with literal arguments, nothing else."""
    call = ast.parse(expression, mode="eval").body
    if not (isinstance(call, ast.Call) and isinstance(call.func, ast.Name)):
        raise ValueError(f"not a call of a dualight.scenes function: {expression!r}")
    build = getattr(scenes, call.func.id, None)
    ours = inspect.isfunction(build) and build.__module__.startswith("dualight.")
    if not ours or call.func.id.startswith("_"):
        raise ValueError(f"dualight.scenes has no function {call.func.id!r}")
    args = [ast.literal_eval(a) for a in call.args]
    kwargs = {k.arg: ast.literal_eval(k.value) for k in call.keywords if k.arg is not None}
    return build(*args, **kwargs)


def prepared_references() -> Iterator[Prepared]:
    """Every stored 64x64 reference of bounded max_depth, its scene built from its metadata."""
    for path in sorted(REFERENCES.glob("*_64_mean.exr")):
        ref_name = path.name.removesuffix("_mean.exr")
        info = load_reference(ref_name)[2]
        if int(info["max_depth"]) < 1:
            continue
        expression = str(info["scene"])
        name = ref_name.removesuffix("_64")
        yield _prepared(name, ref_name, lambda e=expression: scene_of_reference(e))


def errors(image: np.ndarray, ref: np.ndarray, ref_var: np.ndarray, mask: np.ndarray) -> dict:
    raw = metrics.relmse(image, ref, EPS)
    floor = float(np.mean(ref_var / (ref + EPS) ** 2))
    masked = metrics.relmse(image[mask][None], ref[mask][None], EPS)
    masked_floor = float(np.mean(ref_var[mask] / (ref[mask] + EPS) ** 2))
    return {
        "relmse_raw": raw,
        "reference_floor": floor,
        "relmse": max(raw - floor, 1e-12),
        "relmse_lt_pixels": max(masked - masked_floor, 1e-12),
    }


def bdpt_efficiency(
    p: Prepared, budget: float, seed: int, threads: int | None, **options: Any
) -> dict[str, Any]:
    """One BDPT render of ``p``'s scene for ``budget`` seconds with ``options`` (render's
    keywords): the options, its spp, seconds, relMSE and efficiency 1 / (relMSE x seconds)."""
    start = time.perf_counter()
    image = dualight.render(
        p.scene,
        "bdpt",
        spp=None,
        time_limit=budget,
        max_depth=int(p.info["max_depth"]),
        seed=seed,
        threads=threads,
        progress=False,
        **options,
    )
    seconds = time.perf_counter() - start
    relmse = errors(np.asarray(image), p.mean, p.variance, p.mask)["relmse"]
    return {
        **options,
        "seed": seed,
        "threads": image.stats["threads"],
        "spp": image.stats["spp"],
        "seconds": seconds,
        "relmse": relmse,
        "efficiency": 1.0 / (relmse * seconds),
    }


def efficiency_ratios(top: dict[str, dict[str, Any]], pairs: list[tuple[str, str]]) -> dict:
    """Equal-time ratios of efficiency 1 / (relMSE * seconds), "a / b" for each pair present."""
    return {
        f"{a} / {b}": top[a]["efficiency"] / top[b]["efficiency"]
        for a, b in pairs
        if a in top and b in top
    }


def run_dualight(scene: dualight.Scene, method: str, budget: float, max_depth: int, seed: int):
    start = time.perf_counter()
    image = dualight.render(
        scene, method, spp=None, time_limit=budget, max_depth=max_depth, seed=seed, progress=False
    )
    return np.asarray(image), time.perf_counter() - start, image.stats


def run_mitsuba(scene: dualight.Scene, spp: int, max_depth: int, seed: int):
    return time_mitsuba(scene, dmi.variant(), "independent", spp, max_depth, 5, seed)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--budgets", type=str, default="0.5,1,2,4,8")
    parser.add_argument("--mitsuba-spp", type=str, default="16,64,256,1024,4096")
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    if args.quick:
        args.budgets, args.mitsuba_spp = "0.25,0.5,1", "16,64,256"
    budgets = [float(b) for b in args.budgets.split(",")]
    mitsuba_spps = [int(s) for s in args.mitsuba_spp.split(",")]
    suffix = "_quick" if args.quick else ""

    summary: dict[str, Any] = {
        "machine": {"cpu_count": os.cpu_count(), "platform": platform.platform()},
        "budgets_seconds": budgets,
        "scenes": {},
    }
    for prepared in prepared_scenes():
        name, ref_name, scene = prepared.name, prepared.reference, prepared.scene
        ref, ref_var, info, mask = prepared.mean, prepared.variance, prepared.info, prepared.mask
        max_depth = int(info["max_depth"])
        runs: list[dict[str, Any]] = []
        for method in METHODS:
            for i, budget in enumerate(budgets):
                img, secs, stats = run_dualight(scene, method, budget, max_depth, seed=100 + i)
                runs.append(
                    {
                        "renderer": f"dualight_{method}",
                        "budget": budget,
                        "seconds": secs,
                        "spp": stats["spp"],
                        **errors(img, ref, ref_var, mask),
                    }
                )
        try:
            for spp in mitsuba_spps:
                img, secs = run_mitsuba(scene, spp, max_depth, seed=spp)
                runs.append(
                    {
                        "renderer": "mitsuba_path",
                        "variant": dmi.variant(),
                        "spp": spp,
                        "seconds": secs,
                        **errors(img, ref, ref_var, mask),
                    }
                )
        except (ImportError, RuntimeError) as err:
            print(f"skipping Mitsuba: {err}")
        for r in runs:
            r["efficiency"] = 1.0 / (r["relmse"] * r["seconds"])
            print(
                f"{name:>9} {r['renderer']:>15} {r['seconds']:7.2f} s {r['spp']:7d} spp "
                f"relMSE {r['relmse']:.3e} (raw {r['relmse_raw']:.3e}, "
                f"floor {r['reference_floor']:.1e}) LT pixels {r['relmse_lt_pixels']:.3e}"
            )

        top: dict[str, dict[str, Any]] = {}
        for r in runs:  # each renderer's longest run
            if r["seconds"] > top.get(r["renderer"], {"seconds": -1.0})["seconds"]:
                top[r["renderer"]] = r
        ratios = efficiency_ratios(top, RATIOS)
        summary["scenes"][name] = {
            "reference": ref_name,
            "reference_spp": info.get("spp"),
            "max_depth": max_depth,
            "lt_renderable_fraction": float(mask.mean()),
            "runs": runs,
            "equal_time_efficiency_ratios": ratios,
        }
        print(f"{name}: efficiency ratios (time to equal relMSE, > 1: the first is faster)")
        for k, v in ratios.items():
            print(f"   {k:>34}: x{v:.2f}")

    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / f"bench_bdpt{suffix}.json").write_text(json.dumps(summary, indent=2) + "\n")

    panels = {
        f"{name} 64x64, max_depth {entry['max_depth']}": curves_by(entry["runs"], "renderer")
        for name, entry in summary["scenes"].items()
    }
    save_relmse_against_time(
        panels, RESULTS / f"bench_bdpt{suffix}.png", ylabel="relMSE (reference noise removed)"
    )
    print(f"wrote {RESULTS / f'bench_bdpt{suffix}.json'} and bench_bdpt{suffix}.png")


if __name__ == "__main__":
    main()
