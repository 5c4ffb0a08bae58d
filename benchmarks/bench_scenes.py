"""Every method on Veach's classic scenes at equal time (issue 21): ``veach_mis``,
``veach_bidir`` and the glossy door (``door_ajar(variant="glossy")``), against their Mitsuba 3
references (``veach_mis_64``, ``veach_bidir_64``, ``door_glossy_64``; 64x64, ``max_depth`` 8).

* The curves: path, light, bdpt, pssmlt, mmlt, mlt (Veach's luminance target) and mlt_flat (the
  flattened importance) on each scene, each at every budget (``time_limit``) and ``--seeds``
  seeds: relMSE (reference noise removed) and Delta E 2000 (mean over pixels) against the
  measured seconds; on ``veach_mis`` also the path tracer by BSDF sampling alone and by light
  sampling alone (``render(strategies=...)``), Veach's figure 9.2 at equal time.
* Veach's figure on the glossy door: BDPT at ``--figure-spp`` (40) spp against MLT given the same
  wall time, with the reference (``bench_scenes_door_glossy.png``).
* The equal-time table: relMSE of each method over BDPT's (and over MIS's on ``veach_mis``) at
  every budget, mean over seeds with its spread.

Writes ``benchmarks/results/bench_scenes.json`` and ``bench_scenes.png`` (relMSE against
seconds, one panel per scene); ``--quick`` writes ``*_quick`` files (git ignores them).

    python benchmarks/bench_scenes.py --budgets 1,4,8   # 2 seeds: about 10 minutes
    python benchmarks/bench_scenes.py --quick     # budgets 0.25,0.5 s, 1 seed: a smoke run
    python benchmarks/bench_scenes.py --scenes door_glossy --methods bdpt,mlt,mlt_flat \
        --budgets 16,32 --no-figure --tag door_long  # longer budgets: bench_scenes_door_long.*
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path
from typing import Any

from dualight import scenes

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_mlt  # noqa: E402
from bench_bdpt import RESULTS, SCENES  # noqa: E402

CLASSIC = {
    "veach_mis": ("veach_mis_64", lambda: scenes.veach_mis(resolution=(64, 64))),
    "veach_bidir": ("veach_bidir_64", lambda: scenes.veach_bidir(resolution=(64, 64))),
    "door_glossy": (
        "door_glossy_64",
        lambda: scenes.door_ajar(resolution=(64, 64), variant="glossy"),
    ),
}
METHODS = ("path", "light", "bdpt", "pssmlt", "mmlt", "mlt", "mlt_flat")
STRATEGIES = ("path_bsdf", "path_light")  # on veach_mis, beside "path" (MIS)
RATIOS = [
    ("mlt", "bdpt"),
    ("mlt_flat", "bdpt"),
    ("pssmlt", "bdpt"),
    ("mmlt", "bdpt"),
    ("bdpt", "path"),
    ("light", "path"),
    ("path", "path_bsdf"),
    ("path", "path_light"),
]


def relmse_over(curves: list[dict[str, Any]], base: str) -> dict[str, dict[str, float]]:
    """relMSE of every method over ``base``'s at each budget (> 1: worse than ``base``)."""
    out: dict[str, dict[str, float]] = {}
    by = {(c["method"], c["budget"]): c for c in curves}
    for (method, budget), c in by.items():
        b = by.get((base, budget))
        if b is not None and method != base:
            out.setdefault(method, {})[f"{budget:g} s"] = c["relmse"] / b["relmse"]
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--budgets", type=str, default="1,4,8")
    parser.add_argument("--scenes", type=str, default=",".join(CLASSIC))
    parser.add_argument("--methods", type=str, default=",".join(METHODS))
    parser.add_argument("--figure-spp", type=int, default=40, help="BDPT's spp in the figure")
    parser.add_argument("--seeds", type=int, default=2, help="renders per method and budget")
    parser.add_argument("--quick", action="store_true", help="budgets 0.25,0.5; *_quick files")
    parser.add_argument("--tag", type=str, default="", help="write bench_scenes_TAG.* instead")
    parser.add_argument("--no-figure", action="store_true", help="skip the door figure")
    args = parser.parse_args()
    if args.quick:
        args.budgets, args.seeds = "0.25,0.5", 1
    budgets = [float(b) for b in args.budgets.split(",")]
    methods = [m for m in args.methods.split(",") if m]
    names = [n for n in args.scenes.split(",") if n]
    unknown = set(methods) - set(METHODS) | set(names) - set(CLASSIC)
    if unknown:
        parser.error(f"unknown scene or method: {', '.join(sorted(unknown))}")
    SCENES.update(CLASSIC)  # bench_mlt reads its scenes and references from this table
    suffix = "_quick" if args.quick else (f"_{args.tag}" if args.tag else "")
    start = time.perf_counter()
    skipped: dict[str, str] = {}
    summary: dict[str, Any] = {
        "environment": bench_mlt.environment(),
        "budgets_seconds": budgets,
        "seeds": args.seeds,
        "methods": methods,
        "skipped_methods": skipped,
        "scenes": {},
    }
    if "door_glossy" in names and not args.no_figure:
        summary["figure"] = bench_mlt.figure(
            args.figure_spp, skipped, suffix, args.seeds, "door_glossy", "bench_scenes"
        )
    for name in names:
        todo = methods + (list(STRATEGIES) if name == "veach_mis" else [])
        entry = bench_mlt.scene_study(name, todo, budgets, args.seeds, skipped, RATIOS)
        entry["relmse_over_bdpt"] = relmse_over(entry["curves"], "bdpt")
        if name == "veach_mis":
            entry["relmse_over_mis"] = relmse_over(
                [c for c in entry["curves"] if c["method"].startswith("path")], "path"
            )
        summary["scenes"][name] = entry
        print(f"  relMSE over BDPT's: {json.dumps(entry['relmse_over_bdpt'], indent=None)}")
        if "relmse_over_mis" in entry:
            print(f"  relMSE over MIS's: {json.dumps(entry['relmse_over_mis'])}")
    bench_mlt.print_ratios(summary, max(budgets), RATIOS)
    for method, why in skipped.items():
        print(f"skipped {method!r}: {why}")
    summary["environment"]["load_average_at_end"] = list(os.getloadavg())
    summary["environment"]["wall_seconds"] = time.perf_counter() - start
    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / f"bench_scenes{suffix}.json").write_text(json.dumps(summary, indent=2) + "\n")
    bench_mlt.plot(summary, RESULTS / f"bench_scenes{suffix}.png", (*METHODS, *STRATEGIES))
    print(f"wrote {RESULTS / f'bench_scenes{suffix}.json'} and bench_scenes{suffix}.png")


if __name__ == "__main__":
    main()
