"""Render time of every method on the Cornell box and the door (128x128, both cores), median
of repeated runs: the before/after check of a refactor that must not change speed.

Writes ``benchmarks/results/bench_render_speed_<label>.json``; with ``--against LABEL`` it
also prints the ratio of each median to that earlier run's.

    python benchmarks/bench_render_speed.py --label before
    python benchmarks/bench_render_speed.py --label after --against before
"""

from __future__ import annotations

import argparse
import json
import platform
import statistics
import time
from pathlib import Path
from typing import Any

import dualight
from dualight import scenes

RESULTS = Path(__file__).resolve().parent / "results"
RES = (128, 128)
CASES: list[tuple[str, dict[str, Any]]] = [
    ("path", dict(method="path", spp=64)),
    ("light", dict(method="light", spp=64)),
    ("bdpt", dict(method="bdpt", spp=16)),
    ("pssmlt", dict(method="pssmlt", spp=32, mlt=dict(bootstrap=20000, direct_spp=4))),
    ("mmlt", dict(method="mmlt", spp=32, mlt=dict(bootstrap=20000, direct_spp=4))),
    ("mlt", dict(method="mlt", spp=32, mlt=dict(bootstrap=20000, direct_spp=4))),
]


def run(repeats: int) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for scene_name, scene in (
        ("cornell", scenes.cornell_box(RES)),
        ("door", scenes.door_ajar(RES)),
    ):
        for name, kw in CASES:
            dualight.render(
                scene, seed=1, progress=False, max_depth=8, **dict(kw, spp=1)
            )  # warm-up
            times = []
            for r in range(repeats):
                start = time.perf_counter()
                dualight.render(scene, seed=r, progress=False, max_depth=8, **kw)
                times.append(time.perf_counter() - start)
            key = f"{scene_name}/{name}"
            out[key] = {"median_seconds": statistics.median(times), "seconds": times}
            print(f"{key}: median {statistics.median(times):.3f} s of {repeats}", flush=True)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--label", required=True)
    parser.add_argument("--against", help="label of an earlier run to compare with")
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    results = run(args.repeats)
    RESULTS.mkdir(exist_ok=True)
    doc = {
        "label": args.label,
        "machine": platform.processor() or platform.machine(),
        "cases": results,
    }
    (RESULTS / f"bench_render_speed_{args.label}.json").write_text(json.dumps(doc, indent=1))
    if args.against:
        before = json.loads((RESULTS / f"bench_render_speed_{args.against}.json").read_text())[
            "cases"
        ]
        for key, value in results.items():
            ratio = value["median_seconds"] / before[key]["median_seconds"]
            print(f"{key}: {args.label}/{args.against} = {ratio:.3f}")


if __name__ == "__main__":
    main()
