"""BDPT's equal-time efficiency against the depth where Russian roulette starts (``rr_depth``).

Every vertex of a camera subpath connects to every vertex of its light subpath, so BDPT's
connections multiply with the two subpaths' lengths, and a roulette that starts earlier can save
more time than it adds noise. This renders ``bench_bdpt``'s scenes (the Cornell box, its caustic
variant and Veach's door; 64x64, ``max_depth`` 8) with BDPT for a fixed time at each
``rr_depth``, the depths interleaved seed by seed, and reports efficiency 1 / (relMSE x seconds)
against the tests' Mitsuba references (their own noise removed, as in ``bench_bdpt``).

Writes ``benchmarks/results/bench_bdpt_rr.json`` (or ``--out``).

    python benchmarks/bench_bdpt_rr.py        # 8 s, seeds 1-4, rr_depth 5, 3, 2
    python benchmarks/bench_bdpt_rr.py --budget 1 --seeds 1 --out /tmp/rr.json  # a smoke run
    # every stored 64x64 reference (max_depth 8), 4 s, seeds 1-3, rr_depth 5 and 2:
    python benchmarks/bench_bdpt_rr.py --scenes references --budget 4 --seeds 1,2,3 \
        --rr-depths 5,2 --out benchmarks/results/bench_bdpt_rr_references.json
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
RESULTS = HERE / "results"
sys.path[:0] = [str(HERE)]
from bench_bdpt import Prepared, bdpt_efficiency, prepared_references, prepared_scenes  # noqa: E402


def efficiency(
    p: Prepared, budget: float, rr_depth: int, seed: int, threads: int | None
) -> dict[str, Any]:
    """One BDPT render of ``budget`` seconds: its spp, seconds, relMSE and efficiency."""
    return bdpt_efficiency(p, budget, seed, threads, rr_depth=rr_depth)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--budget", type=float, default=8.0, help="seconds per render")
    parser.add_argument("--seeds", type=str, default="1,2,3,4")
    parser.add_argument("--rr-depths", type=str, default="5,3,2")
    parser.add_argument("--threads", type=int, default=None, help="default: every core")
    parser.add_argument(
        "--scenes",
        choices=("bench_bdpt", "references"),
        default="bench_bdpt",
        help="bench_bdpt's three scenes, or every stored 64x64 reference",
    )
    parser.add_argument("--out", type=Path, default=RESULTS / "bench_bdpt_rr.json")
    args = parser.parse_args()
    seeds = [int(s) for s in args.seeds.split(",")]
    depths = [int(d) for d in args.rr_depths.split(",")]
    summary: dict[str, Any] = {
        "machine": {"cpu_count": os.cpu_count(), "platform": platform.platform()},
        "budget_seconds": args.budget,
        "threads": args.threads,
        "seeds": seeds,
        "rr_depths": depths,
        "scenes": {},
    }
    chosen = prepared_references() if args.scenes == "references" else prepared_scenes()
    for p in chosen:
        runs = [efficiency(p, args.budget, d, seed, args.threads) for seed in seeds for d in depths]
        means = {
            d: float(np.mean([r["efficiency"] for r in runs if r["rr_depth"] == d])) for d in depths
        }
        summary["scenes"][p.name] = {"runs": runs, "mean_efficiency": means}
        for d in depths:
            print(
                f"{p.name:>9} rr_depth {d}: efficiency {means[d]:8.2f} "
                f"({means[d] / means[depths[0]]:.2f}x rr_depth {depths[0]})",
                flush=True,
            )
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(summary, indent=2) + "\n")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
