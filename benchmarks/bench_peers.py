"""dualight's path tracer against Mitsuba 3's ``path`` (scalar_rgb and llvm_ad_rgb) side by side
(issue 23): the Cornell box, the caustic box and the door (64x64, ``max_depth`` and ``rr_depth``
as their stored Mitsuba references), one thread and all threads, at equal time.

Both renderers get the same scene (``Scene.to_mitsuba``), a box filter and independent samplers,
so the comparison measures the implementations. Each comparison runs with Embree's robust mode
(dualight's default) and without it (Mitsuba 3's default), in both renderers alike
(``Scene.robust_intersections``, Mitsuba's ``embree_use_robust_intersections``). Mitsuba has
no time limit: each of its renders takes the spp a calibration render predicts fills the budget
(after a warm-up render, so LLVM kernels are compiled); dualight renders with ``time_limit``.
Runs are interleaved per seed.
Efficiency is ``1 / (relMSE x seconds)`` (relMSE with the pbrt-v4 offset, reference noise
removed, bench_bdpt.errors); a ratio above 1 means dualight reaches the same error sooner. Also
samples per second, and relMSE x spp (error per sample, independent of speed).

The Cornell box's light variants (point, spot, sun, sky, envmap, lamp: emitters other than the
area light; the lanes sample the environment map's and the textured lamp's lights lane by lane)
run when named in ``--scenes``, and write their own JSON.

Writes ``benchmarks/results/bench_peers.json``; ``--quick`` writes ``bench_peers_quick.json``.

    python benchmarks/bench_peers.py                 # 8 s budgets, 2 seeds: about 11 minutes
    python benchmarks/bench_peers.py --quick         # 1 s budgets, 1 seed, the Cornell box
    python benchmarks/bench_peers.py --lanes off     # dualight one path at a time (its own JSON)
    python benchmarks/bench_peers.py --scenes point,spot,sun,sky,envmap,lamp --seeds 1 \
        --threads 1 --intersections robust --budget 4   # bench_peers_lights.json, 3 minutes
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

import dualight
from dualight import mitsuba as dmi
from dualight import scenes

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_mlt  # noqa: E402
from bench_bdpt import RESULTS, errors, load_reference  # noqa: E402

PEERS = ("scalar_rgb", "llvm_ad_rgb")
NAMES = ("cornell", "caustics", "door")
LIGHTS = ("point", "spot", "sun", "sky", "envmap", "lamp")  # Cornell variants, 64x64


def prepare(name: str) -> tuple[dualight.Scene, np.ndarray, np.ndarray, dict[str, Any]]:
    """Scene ``name`` (of NAMES or LIGHTS) with its stored reference and metadata, its BVH built."""
    if name in NAMES:
        _, scene, ref, ref_var, info = bench_mlt.prepare(name)
        return scene, ref, ref_var, info
    ref, ref_var, info = load_reference(f"{name}_64")
    scene = scenes.cornell_box(resolution=(64, 64), variant=name)
    dualight.render(scene, "path", spp=1, max_depth=int(info["max_depth"]), progress=False)
    return scene, ref, ref_var, info


def render_dualight(
    scene: dualight.Scene,
    budget: float,
    info: dict[str, Any],
    threads: int,
    seed: int,
    lanes: dualight.methods.Lanes = "auto",
) -> tuple[np.ndarray, float, int, str]:
    """dualight's path tracer for ``budget`` seconds: image, seconds, spp, and which of its
    builds ran (``stats["lanes"]``)."""
    start = time.perf_counter()
    image = dualight.render(
        scene,
        "path",
        spp=None,
        time_limit=budget,
        max_depth=int(info["max_depth"]),
        rr_depth=int(info["rr_depth"]),
        seed=seed,
        sampler="independent",
        threads=threads,
        progress=False,
        lanes=lanes,
    )
    return (
        np.asarray(image),
        time.perf_counter() - start,
        int(image.stats["spp"]),
        image.stats["lanes"],
    )


def mitsuba_scene(scene: dualight.Scene, variant: str, info: dict[str, Any]) -> Any:
    """The scene loaded in Mitsuba ``variant`` with an independent sampler."""
    import mitsuba as mi

    dmi.variant(variant)
    desc = scene.to_mitsuba(spp=1, max_depth=int(info["max_depth"]), rr_depth=int(info["rr_depth"]))
    desc["sensor"]["sampler"]["type"] = "independent"
    return mi.load_dict(desc)


def render_mitsuba(mscene: Any, variant: str, spp: int, seed: int) -> tuple[np.ndarray, float]:
    """Mitsuba's render of ``spp`` samples per pixel: image, seconds."""
    import mitsuba as mi

    dmi.variant(variant)
    start = time.perf_counter()
    image = np.asarray(mi.render(mscene, spp=spp, seed=seed), dtype=np.float32)
    return image, time.perf_counter() - start


def calibrate_mitsuba(mscene: Any, variant: str, budget: float) -> int:
    """The spp that fills ``budget`` seconds, from a warm-up and a timed render of 16 spp
    (doubled until it takes a tenth of the budget)."""
    render_mitsuba(mscene, variant, 4, seed=999)  # JIT compile
    spp = 16
    while True:
        _, seconds = render_mitsuba(mscene, variant, spp, seed=998)
        if seconds >= 0.1 * budget or spp >= 1 << 16:
            return max(1, int(round(spp * budget / seconds)))
        spp *= 2


def cpu() -> dict[str, Any]:
    """The CPU as /proc/cpuinfo names it (Linux; empty elsewhere), with the vector extensions
    both renderers' Embree and dualight's lanes choose from, so that runs on different machines
    can be told apart: their ratios differ."""
    try:
        lines = Path("/proc/cpuinfo").read_text().splitlines()
    except OSError:
        return {}
    fields: dict[str, str] = {}
    for line in lines:
        key, sep, value = line.partition(":")
        if not sep:
            break  # the first processor's fields end at a blank line
        fields.setdefault(key.strip(), value.strip())
    flags = fields.get("flags", "").split()
    wanted = ("avx2", "avx512f", "avx512_fp16", "amx_tile")
    return {
        "model_name": fields.get("model name", ""),
        "family_model_stepping": [fields.get(k, "") for k in ("cpu family", "model", "stepping")],
        "mhz": fields.get("cpu MHz", ""),
        "extensions": [f for f in wanted if f in flags],
    }


def environment(started: float, load: tuple[float, float, float]) -> dict[str, Any]:
    """The machine and the run a JSON summary records: ``started`` on ``time.perf_counter``,
    ``load`` the load averages at the start."""
    import mitsuba as mi

    return {
        "cpu_count": os.cpu_count(),
        "cpu": cpu(),
        "platform": platform.platform(),
        "python": platform.python_version(),
        "mitsuba": mi.__version__,
        "load_average_at_start": load,
        "load_average_at_end": os.getloadavg(),
        "wall_seconds": time.perf_counter() - started,
    }


def set_threads(threads: int) -> None:
    """Mitsuba's (Dr.Jit's) thread pool; dualight takes ``threads`` per render."""
    import drjit as dr

    dr.set_thread_count(threads)


def row(seconds: float, spp: int, error: dict[str, float]) -> dict[str, Any]:
    return {"seconds": seconds, "spp": spp, **error}


def run_scene(
    name: str, budget: float, seeds: int, threads: int, robust: bool, lanes: dualight.methods.Lanes
) -> dict[str, Any]:
    """Every renderer on scene ``name`` with ``threads`` threads, ``seeds`` times, with
    Embree's robust mode on or off."""
    scene, ref, ref_var, info = prepare(name)
    scene.robust_intersections = robust
    full = np.ones(ref.shape[:2], dtype=bool)
    pixels = ref.shape[0] * ref.shape[1]
    set_threads(threads)
    mscenes = {v: mitsuba_scene(scene, v, info) for v in PEERS}
    spps = {v: calibrate_mitsuba(mscenes[v], v, budget) for v in PEERS}
    runs: dict[str, list[dict[str, Any]]] = {"dualight": [], **{v: [] for v in PEERS}}
    for k in range(seeds):
        seed = 60 + k
        image, seconds, spp, ran = render_dualight(scene, budget, info, threads, seed, lanes)
        runs["dualight"].append(
            {**row(seconds, spp, errors(image, ref, ref_var, full)), "lanes": ran}
        )
        for v in PEERS:
            image, seconds = render_mitsuba(mscenes[v], v, spps[v], seed)
            runs[v].append(row(seconds, spps[v], errors(image, ref, ref_var, full)))
    summary: dict[str, Any] = {}
    for who, rows in runs.items():
        relmse = float(np.mean([r["relmse"] for r in rows]))
        seconds = float(np.mean([r["seconds"] for r in rows]))
        spp = float(np.mean([r["spp"] for r in rows]))
        summary[who] = {
            "runs": rows,
            "relmse": relmse,
            "seconds": seconds,
            "spp": spp,
            "efficiency": 1.0 / (relmse * seconds),
            "samples_per_second": pixels * spp / seconds,
            "relmse_x_spp": relmse * spp,
        }
    summary["ratios"] = {
        v: {
            "efficiency": summary["dualight"]["efficiency"] / summary[v]["efficiency"],
            "samples_per_second": summary["dualight"]["samples_per_second"]
            / summary[v]["samples_per_second"],
            "error_per_sample": summary["dualight"]["relmse_x_spp"] / summary[v]["relmse_x_spp"],
        }
        for v in PEERS
    }
    return summary


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--budget", type=float, default=8.0, help="seconds per render")
    parser.add_argument("--seeds", type=int, default=2)
    parser.add_argument("--scenes", type=str, default=",".join(NAMES))
    parser.add_argument("--threads", type=str, default=f"1,{os.cpu_count() or 1}")
    parser.add_argument(
        "--intersections", type=str, default="robust,fast", help="Embree modes: robust, fast"
    )
    parser.add_argument("--quick", action="store_true", help="1 s, 1 seed, the Cornell box")
    parser.add_argument(
        "--lanes", type=str, default="auto", help="dualight's render(lanes=...): auto, off, ..."
    )
    args = parser.parse_args()
    if args.quick:
        args.budget, args.seeds, args.scenes = 1.0, 1, "cornell"
    names = [n for n in args.scenes.split(",") if n]
    unknown = [n for n in names if n not in NAMES + LIGHTS]
    if unknown:
        raise SystemExit(f"unknown scenes {unknown}; choose from {', '.join(NAMES + LIGHTS)}")
    thread_counts = sorted({int(t) for t in args.threads.split(",")})
    modes = [m for m in args.intersections.split(",") if m]
    if not modes or any(m not in ("robust", "fast") for m in modes):
        raise SystemExit(f"--intersections takes robust and/or fast, got {args.intersections!r}")
    started = time.perf_counter()
    load = os.getloadavg()
    results: dict[str, dict[str, Any]] = {}
    for threads in thread_counts:
        for name, mode in [(n, m) for n in names for m in modes]:
            r = run_scene(name, args.budget, args.seeds, threads, mode == "robust", args.lanes)
            results.setdefault(f"threads_{threads}", {}).setdefault(mode, {})[name] = r
            for v, ratio in r["ratios"].items():
                print(
                    f"{threads} thread(s) {name:>9} {mode:>6} dualight / {v:<11}: efficiency "
                    f"x{ratio['efficiency']:.2f}, samples/s x{ratio['samples_per_second']:.2f}, "
                    f"error per sample x{ratio['error_per_sample']:.2f}",
                    flush=True,
                )
            rates = ", ".join(
                f"{w} {r[w]['samples_per_second'] / 1e6:.2f} M" for w in ("dualight", *PEERS)
            )
            print(f"{'':>29}samples/s: {rates}", flush=True)
    summary = {
        "environment": environment(started, load),
        "budget_seconds": args.budget,
        "seeds": args.seeds,
        "lanes": args.lanes,
        "results": results,
    }
    RESULTS.mkdir(parents=True, exist_ok=True)
    stem = "bench_peers_quick" if args.quick else "bench_peers"
    if any(n in LIGHTS for n in names):
        stem += "_lights"
    out = RESULTS / (f"{stem}.json" if args.lanes == "auto" else f"{stem}_lanes_{args.lanes}.json")
    out.write_text(json.dumps(summary, indent=2) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
