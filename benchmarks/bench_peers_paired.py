"""dualight's path tracer against Mitsuba 3's ``llvm_ad_rgb`` ``path``, its efficiency ratio in
two factors each measured with an interval (issue 23): error per sample and samples per second.

``bench_peers.py`` takes the efficiency ratio from a few equal-time renders per scene. On the
caustic box one render's relMSE swings by tens of percent (its caustics are found by BSDF
sampling alone), and this machine's speed drifts by up to a third within an hour, so one run's
ratio there may land on either side of 1 by chance. Here:

- **Error per sample**: relMSE x spp (bench_bdpt.errors, reference noise removed), averaged over
  ``--seeds`` renders of ``--spp`` samples per pixel by each renderer; the ratio's 95 % interval
  by bootstrap over the seeds. It does not depend on threads or speed: measured once per scene
  and Embree mode, with the most threads.
- **Samples per second**: ``--reps`` pairs of renders of the same spp, one by each renderer, in
  one process, in alternating order, so that the machine's drift falls on both; the geometric
  mean of the pairs' time ratios with a 95 % interval (two standard errors of the log ratio).
- **Efficiency** (1 / (relMSE x seconds)) is their quotient; its interval combines both on the
  log scale (two standard errors each: the pairs' and the bootstrap's spread).

Both renderers get the same scene (``Scene.to_mitsuba``), box filter, independent sampler and
path length, as in ``bench_peers.py``. Writes ``benchmarks/results/bench_peers_paired.json``.

    python benchmarks/bench_peers_paired.py                          # 13 to 16 minutes
    python benchmarks/bench_peers_paired.py --intersections robust   # about 7 minutes
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

import dualight

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from bench_bdpt import RESULTS, errors  # noqa: E402
from bench_peers import NAMES, environment, mitsuba_scene, prepare, render_mitsuba, set_threads  # noqa: E402

PEER = "llvm_ad_rgb"


def options(info: dict[str, Any]) -> dict[str, Any]:
    """render's keywords that match the reference's (and so Mitsuba's) settings."""
    return {
        "max_depth": int(info["max_depth"]),
        "rr_depth": int(info["rr_depth"]),
        "sampler": "independent",
    }


def log_interval(mean_log: float, se_log: float) -> dict[str, float]:
    """A ratio exp(mean_log) with its 95 % interval, exp(mean_log -+ 2 se_log)."""
    return {
        "ratio": math.exp(mean_log),
        "low": math.exp(mean_log - 2 * se_log),
        "high": math.exp(mean_log + 2 * se_log),
        "se_log": se_log,
    }


@dataclass
class Setup:
    """A scene in one Embree mode, its reference, and Mitsuba's load of it."""

    scene: dualight.Scene
    ref: np.ndarray
    ref_var: np.ndarray
    info: dict[str, Any]
    mscene: Any


def setup(name: str, robust: bool) -> Setup:
    """Scene ``name`` (bench_peers.prepare), Embree's robust mode on or off in both renderers."""
    scene, ref, ref_var, info = prepare(name)
    scene.robust_intersections = robust
    return Setup(scene, ref, ref_var, info, mitsuba_scene(scene, PEER, info))


def error_per_sample(p: Setup, seeds: int, spp: int, threads: int) -> dict[str, Any]:
    """relMSE x spp of both renderers over ``seeds`` renders each, and dualight's ratio to
    Mitsuba's with a bootstrap interval (resampling each renderer's seeds)."""
    scene, ref, ref_var, info, mscene = p.scene, p.ref, p.ref_var, p.info, p.mscene
    full = np.ones(ref.shape[:2], dtype=bool)
    set_threads(threads)
    ours, theirs = [], []
    for seed in range(1, seeds + 1):
        image = dualight.render(
            scene, "path", spp=spp, seed=seed, threads=threads, progress=False, **options(info)
        )
        ours.append(errors(np.asarray(image), ref, ref_var, full)["relmse"] * spp)
        peer_image, _ = render_mitsuba(mscene, PEER, spp, seed)
        theirs.append(errors(peer_image, ref, ref_var, full)["relmse"] * spp)
    a, b = np.array(ours), np.array(theirs)
    rng = np.random.default_rng(0)
    boots = [
        math.log(a[rng.integers(0, seeds, seeds)].mean() / b[rng.integers(0, seeds, seeds)].mean())
        for _ in range(4000)
    ]
    low, high = np.percentile(boots, [2.5, 97.5])
    return {
        "dualight": float(a.mean()),
        PEER: float(b.mean()),
        "ratio": float(a.mean() / b.mean()),
        "low": math.exp(low),
        "high": math.exp(high),
        "se_log": float(np.std(boots)),
    }


def samples_per_second(p: Setup, reps: int, spp: int, threads: int) -> dict[str, Any]:
    """dualight's samples per second over Mitsuba's, from ``reps`` interleaved pairs of renders."""
    scene, info, mscene = p.scene, p.info, p.mscene
    set_threads(threads)
    render_mitsuba(mscene, PEER, 4, seed=999)  # JIT compile
    dualight.render(
        scene, "path", spp=4, seed=999, threads=threads, progress=False, **options(info)
    )
    logs = []
    for r in range(reps):
        seconds = {}
        for who in ("dualight", PEER) if r % 2 == 0 else (PEER, "dualight"):
            if who == PEER:
                seconds[who] = render_mitsuba(mscene, PEER, spp, r + 1)[1]
                continue
            start = time.perf_counter()
            dualight.render(
                scene, "path", spp=spp, seed=r + 1, threads=threads, progress=False, **options(info)
            )
            seconds[who] = time.perf_counter() - start
        logs.append(math.log(seconds[PEER] / seconds["dualight"]))
    return {
        **log_interval(float(np.mean(logs)), float(np.std(logs, ddof=1) / math.sqrt(reps))),
        "pairs": logs,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scenes", type=str, default=",".join(NAMES))
    parser.add_argument("--threads", type=str, default=f"1,{os.cpu_count() or 1}")
    parser.add_argument("--intersections", type=str, default="robust,fast")
    parser.add_argument("--seeds", type=int, default=40, help="renders per renderer for the error")
    parser.add_argument("--error-spp", type=int, default=256)
    parser.add_argument("--reps", type=int, default=16, help="pairs of timed renders")
    parser.add_argument("--spp", type=int, default=512, help="spp per timed render and thread")
    args = parser.parse_args()
    names = [n for n in args.scenes.split(",") if n]
    if any(n not in NAMES for n in names):
        raise SystemExit(f"--scenes takes {', '.join(NAMES)}")
    modes = [m for m in args.intersections.split(",") if m]
    if not modes or any(m not in ("robust", "fast") for m in modes):
        raise SystemExit(f"--intersections takes robust and/or fast, got {args.intersections!r}")
    thread_counts = sorted({int(t) for t in args.threads.split(",")})
    started, load = time.perf_counter(), os.getloadavg()
    results: dict[str, Any] = {}
    for name, mode in [(n, m) for n in names for m in modes]:
        p = setup(name, mode == "robust")
        error = error_per_sample(p, args.seeds, args.error_spp, thread_counts[-1])
        entry: dict[str, Any] = {"error_per_sample": error}
        for threads in thread_counts:
            speed = samples_per_second(p, args.reps, args.spp * threads, threads)
            efficiency = log_interval(
                math.log(speed["ratio"] / error["ratio"]),
                math.hypot(speed["se_log"], error["se_log"]),
            )
            entry[f"threads_{threads}"] = {"samples_per_second": speed, "efficiency": efficiency}
            print(
                f"{name:>9} {mode:>6} {threads} thread(s) dualight / {PEER}: efficiency "
                f"x{efficiency['ratio']:.3f} ({efficiency['low']:.3f}-{efficiency['high']:.3f}) = "
                f"samples/s x{speed['ratio']:.3f} ({speed['low']:.3f}-{speed['high']:.3f}) / "
                f"error per sample x{error['ratio']:.3f} ({error['low']:.3f}-{error['high']:.3f})",
                flush=True,
            )
        results.setdefault(mode, {})[name] = entry
    summary = {
        "environment": environment(started, load),
        "peer": PEER,
        "settings": vars(args),
        "results": results,
    }
    RESULTS.mkdir(parents=True, exist_ok=True)
    out = RESULTS / "bench_peers_paired.json"
    out.write_text(json.dumps(summary, indent=2) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
