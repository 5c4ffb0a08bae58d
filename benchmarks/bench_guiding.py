"""Path guiding at equal time (issue 22): the path tracer guided by radiance, the light
tracer guided by importance and BDPT guided by both (``render(..., guiding=True)``: training
included in the time) against the unguided ones and path-space MLT, on the door, the caustic
box and the Cornell box, against their Mitsuba 3 references (64x64, ``max_depth`` as each
reference).

relMSE (reference noise removed) and Delta E 2000 against the measured seconds, at every budget
and ``--seeds`` seeds; the equal-time efficiency ratios (1 / (relMSE x seconds)) at the longest
budget. Also, at equal samples per pixel (``--spp``, training on top), the median and mean over
pixels of each render's own relative variance, which shows what the guide does per sample
without its cost.

Writes ``benchmarks/results/bench_guiding.json`` and ``bench_guiding.png``; ``--quick`` writes
``*_quick`` files (git ignores them).

    python benchmarks/bench_guiding.py                # budgets 1,4,8 s, 3 seeds: about 25 minutes
    python benchmarks/bench_guiding.py --quick        # a smoke run
    python benchmarks/bench_guiding.py --scenes rooms10_dark --suffix _rooms10_dark
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

import dualight
from dualight import scenes

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_mlt  # noqa: E402
from bench_bdpt import RESULTS, SCENES  # noqa: E402

# Veach's door scaled up: rooms(10), diffuse, so radiosity can seed its guides; its camera room
# is lit, "rooms10_dark" sees the building from a dark room lit only through its doors.
SCENES["rooms10"] = ("rooms10_64", lambda: scenes.rooms(10, resolution=(64, 64)))
SCENES["rooms10_dark"] = (
    "rooms10_dark_64",
    lambda: scenes.rooms(10, resolution=(64, 64), camera_room=1, camera_room_lit=False),
)
SEEDABLE = ("rooms10", "rooms10_dark")  # diffuse: a radiosity solution seeds the guides
SEEDED = ("path_seeded", "light_seeded", "bdpt_seeded")  # guide_from=solution, diffuse scenes
bench_mlt.VARIANTS.update(
    {
        "path_guided": ("path", {"guiding": True}),
        "light_guided": ("light", {"guiding": True}),
        "bdpt_guided": ("bdpt", {"guiding": True}),
    }
)
METHODS = ("path", "path_guided", "light", "light_guided", "bdpt", "bdpt_guided", "mlt")
RATIOS = [
    ("path_guided", "path"),
    ("light_guided", "light"),
    ("bdpt_guided", "bdpt"),
    ("path_guided", "bdpt"),
    ("path_guided", "mlt"),
    ("bdpt_guided", "mlt"),
    ("light_guided", "bdpt"),
    ("path_seeded", "path_guided"),
    ("light_seeded", "light_guided"),
    ("bdpt_seeded", "bdpt_guided"),
]
NAMES = ("door", "caustics", "cornell", "rooms10", "rooms10_dark")


def add_seeded_variants(name: str) -> dict[str, Any]:
    """The seeded variants of scene ``name`` (render(guide_from=solution) with a Gauss-Seidel
    radiosity and importance solution of it, default patches); returns the solve's cost, which
    the renders' seconds do not include."""
    start = time.perf_counter()
    solution = dualight.radiosity.solve(SCENES[name][1](), "gauss_seidel")
    seconds = time.perf_counter() - start
    seeded = {"guiding": True, "guide_from": solution}
    for label in SEEDED:
        bench_mlt.VARIANTS[label] = (label.split("_")[0], seeded)
    print(f"  {name}: radiosity solve {seconds:.1f} s, {len(solution.patches)} patches")
    return {"solve_seconds": seconds, "patches": len(solution.patches)}


def per_sample(name: str, spp: int, seeds: int) -> dict[str, Any]:
    """Each render's own relative variance per pixel (variance of the mean over (ref^2 + 0.01)),
    median and mean over pixels, at equal spp: guided against unguided, without the time."""
    _, scene, ref, _, info = bench_mlt.prepare(name)
    lum_ref = ref.mean(-1)
    out: dict[str, Any] = {}
    for method, options in (
        ("path", {}),
        ("path_guided", {"guiding": True}),
        ("light", {}),
        ("light_guided", {"guiding": True}),
        ("bdpt", {}),
        ("bdpt_guided", {"guiding": True}),
    ):
        real = method.split("_")[0]
        rows = []
        for k in range(seeds):
            image = dualight.render(
                scene,
                real,
                spp=spp,
                max_depth=int(info["max_depth"]),
                seed=200 + k,
                progress=False,
                **options,
            )
            rel = image.variance.mean(-1) / (lum_ref**2 + 1e-2)
            rows.append((float(np.median(rel)), float(rel.mean()), float(image.stats["seconds"])))
        med, mean, secs = (float(np.mean(c)) for c in zip(*rows, strict=True))
        out[method] = {"median_relvar": med, "mean_relvar": mean, "seconds": secs}
        print(
            f"  {name} {method:>12} {spp} spp: relative variance median {med:.3g} "
            f"mean {mean:.3g}, {secs:.2f} s"
        )
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--budgets", type=str, default="1,4,8")
    parser.add_argument("--scenes", type=str, default=",".join(NAMES))
    parser.add_argument("--methods", type=str, default=",".join(METHODS))
    parser.add_argument("--seeds", type=int, default=3, help="renders per method and budget")
    parser.add_argument("--spp", type=int, default=512, help="the equal-spp comparison's spp")
    parser.add_argument("--quick", action="store_true", help="budgets 0.25,0.5, 1 seed, 64 spp")
    parser.add_argument(
        "--suffix", type=str, default="", help="of the output files (a study of some scenes)"
    )
    args = parser.parse_args()
    if args.quick:
        args.budgets, args.seeds, args.spp = "0.25,0.5", 1, 64
    budgets = [float(b) for b in args.budgets.split(",")]
    methods = [m for m in args.methods.split(",") if m]
    names = [n for n in args.scenes.split(",") if n]
    unknown = set(methods) - set(METHODS) - set(SEEDED) | set(names) - set(SCENES)
    if unknown:
        parser.error(f"unknown scene or method: {', '.join(sorted(unknown))}")
    suffix = args.suffix + ("_quick" if args.quick else "")
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
    for name in names:
        study = methods
        seeding = None
        if name in SEEDABLE:
            seeding = add_seeded_variants(name)
            study = methods + [m for m in SEEDED if m not in methods]
        entry = bench_mlt.scene_study(name, study, budgets, args.seeds, skipped, RATIOS)
        if seeding is not None:
            entry["radiosity_seeding"] = seeding
        entry["equal_spp"] = per_sample(name, args.spp, args.seeds)
        summary["scenes"][name] = entry
    bench_mlt.print_ratios(summary, max(budgets), RATIOS)
    summary["environment"]["load_average_at_end"] = list(os.getloadavg())
    summary["environment"]["wall_seconds"] = time.perf_counter() - start
    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / f"bench_guiding{suffix}.json").write_text(json.dumps(summary, indent=2) + "\n")
    bench_mlt.plot(summary, RESULTS / f"bench_guiding{suffix}.png", (*METHODS, *SEEDED))
    print(f"wrote {RESULTS / f'bench_guiding{suffix}.json'} and bench_guiding{suffix}.png")


if __name__ == "__main__":
    main()
