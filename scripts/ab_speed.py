"""Samples per second of two builds of dualight side by side, for A/B checks of a change.

Two worker processes, one per build, are pinned to the same core and render in turns (A B, then
B A, ...), each turn a short render of one scene. Both see the same share of whatever else the
machine does. On a 2-core VM whose speed drifted over minutes, one build's BDPT on the Cornell
box ran at 0.12 M samples/s in one minute and 0.19 M in the next; an A/A run of this script (the
same build twice, BDPT, 24 turns) gave paired ratios of 1.006, 0.987 and 1.004.

A build is a folder holding a built ``dualight`` package (``pip install --target DIR``, below),
or ``installed`` for the one the running Python imports. Environment variables can be set per
build (``--env-a NAME=VALUE``), for switches of a scratch build.

    pip install --no-deps --no-build-isolation --target /tmp/ab/new \\
        --config-settings=build-dir=/tmp/ab/build .
    .venv/bin/python scripts/ab_speed.py --a installed --b /tmp/ab/new --method bdpt
    .venv/bin/python scripts/ab_speed.py --a installed --b installed     # A/A: the noise
    .venv/bin/python scripts/ab_speed.py --b /tmp/ab/new --method path --intersections fast

Prints, per scene, each build's median samples per second and the median of the per-turn ratios
B / A (> 1: B is faster); ``--out`` writes every turn's figures as JSON.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

SCENES = ("cornell", "caustics", "door")
RES = 64


def make_scene(name: str, robust: bool = True) -> Any:
    """Scene ``name`` with Embree's robust mode on or off."""
    from dualight import scenes

    if name == "cornell":
        scene = scenes.cornell_box(resolution=(RES, RES))
    elif name == "caustics":
        scene = scenes.cornell_box(resolution=(RES, RES), variant="caustics")
    elif name == "door":
        scene = scenes.door_ajar(resolution=(RES, RES))
    else:
        raise ValueError(f"unknown scene {name!r}; choose from {', '.join(SCENES)}")
    scene.robust_intersections = robust
    return scene


def worker(
    site: str, method: str, options: dict[str, Any], scene_names: list[str], robust: bool
) -> None:
    """Renders `scene spp seed` lines from stdin, one samples-per-second figure each to stdout."""
    if site != "installed":
        sys.path.insert(0, site)
    import dualight

    built = {name: make_scene(name, robust) for name in scene_names}
    for scene in built.values():  # warm-up: first-call costs stay out of the figures
        dualight.render(scene, method, spp=2, seed=1, threads=1, progress=False, **options)
    print(json.dumps({"ready": dualight.__file__}), flush=True)
    for line in sys.stdin:
        name, spp, seed = line.split()
        start = time.perf_counter()
        dualight.render(
            built[name], method, spp=int(spp), seed=int(seed), threads=1, progress=False, **options
        )
        print(RES * RES * int(spp) / (time.perf_counter() - start), flush=True)


def start_worker(
    site: str, env_vars: list[str], args: argparse.Namespace
) -> tuple[subprocess.Popen[str], str]:
    if site != "installed" and not (Path(site) / "dualight").is_dir():
        raise SystemExit(f"{site}: no dualight package in it (pip install --target {site} ...)")
    env = dict(os.environ)
    for item in env_vars:
        name, sep, value = item.partition("=")
        if not name or not sep:
            raise SystemExit(f"--env-a/--env-b take NAME=VALUE, got {item!r}")
        env[name] = value
    command = [
        sys.executable,
        __file__,
        "--worker",
        site,
        "--method",
        args.method,
        "--options",
        args.options,
        "--scenes",
        args.scenes,
        "--intersections",
        args.intersections,
    ]
    process = subprocess.Popen(
        command,
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
        env=env,
        preexec_fn=lambda: os.sched_setaffinity(0, {args.core}),
    )
    assert process.stdout is not None
    ready = process.stdout.readline()
    if not ready:
        raise SystemExit(f"the worker for {site} ended before it was ready")
    return process, json.loads(ready)["ready"]


def turn(process: subprocess.Popen[str], scene: str, spp: int, seed: int) -> float:
    assert process.stdin is not None and process.stdout is not None
    process.stdin.write(f"{scene} {spp} {seed}\n")
    process.stdin.flush()
    line = process.stdout.readline()
    if not line:
        raise SystemExit(f"a worker ended while rendering {scene} (its error is above)")
    return float(line)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument(
        "--a", default="installed", help="build A: a folder with dualight in it, or 'installed'"
    )
    parser.add_argument("--b", default="installed", help="build B, likewise")
    parser.add_argument("--env-a", action="append", default=[], metavar="NAME=VALUE")
    parser.add_argument("--env-b", action="append", default=[], metavar="NAME=VALUE")
    parser.add_argument("--method", default="bdpt")
    parser.add_argument(
        "--options", default='{"max_depth": 8}', help="render()'s other keywords, as JSON"
    )
    parser.add_argument("--scenes", default=",".join(SCENES))
    parser.add_argument(
        "--intersections", choices=("robust", "fast"), default="robust", help="Embree's mode"
    )
    parser.add_argument("--spp", type=int, default=16, help="samples per pixel per turn")
    parser.add_argument("--turns", type=int, default=24, help="turns per build and scene")
    parser.add_argument("--core", type=int, default=0, help="the CPU both workers run on")
    parser.add_argument("--out", type=Path, help="JSON with every turn's samples per second")
    parser.add_argument("--worker", help=argparse.SUPPRESS)
    args = parser.parse_args()
    scene_names = [s for s in args.scenes.split(",") if s]
    if args.worker is not None:
        worker(
            args.worker,
            args.method,
            json.loads(args.options),
            scene_names,
            args.intersections == "robust",
        )
        return
    for name in scene_names:
        if name not in SCENES:
            raise SystemExit(f"unknown scene {name!r}; choose from {', '.join(SCENES)}")
    if args.spp < 1 or args.turns < 2:
        raise SystemExit("--spp must be >= 1 and --turns >= 2")
    try:
        options = json.loads(args.options)
    except json.JSONDecodeError as e:
        raise SystemExit(f"--options is not JSON: {e}") from None
    if not isinstance(options, dict):
        raise SystemExit("--options must be a JSON object of render() keywords")
    if not hasattr(os, "sched_setaffinity"):
        raise SystemExit("pinning both workers to one core needs os.sched_setaffinity (Linux)")

    builds = {
        "a": start_worker(args.a, args.env_a, args),
        "b": start_worker(args.b, args.env_b, args),
    }
    figures: dict[str, dict[str, list[float]]] = {
        label: {s: [] for s in scene_names} for label in builds
    }
    for i in range(args.turns):
        order = ("a", "b") if i % 2 == 0 else ("b", "a")
        for scene in scene_names:
            for label in order:
                figures[label][scene].append(turn(builds[label][0], scene, args.spp, i + 1))
    for process, _ in builds.values():
        assert process.stdin is not None
        process.stdin.close()
        process.wait()

    summary: dict[str, dict[str, float]] = {}
    print(f"A: {builds['a'][1]} {' '.join(args.env_a)}\nB: {builds['b'][1]} {' '.join(args.env_b)}")
    for scene in scene_names:
        a, b = figures["a"][scene], figures["b"][scene]
        ratio = statistics.median(y / x for x, y in zip(a, b, strict=True))
        summary[scene] = {
            "a_median": statistics.median(a),
            "b_median": statistics.median(b),
            "b_over_a": ratio,
        }
        a_m, b_m = statistics.median(a) / 1e6, statistics.median(b) / 1e6
        print(
            f"{scene:9s} A {a_m:.4f} M/s  B {b_m:.4f} M/s  "
            f"B / A (median of {args.turns} paired turns) {ratio:.3f}"
        )
    if args.out is not None:
        record = {
            "a": args.a,
            "b": args.b,
            "env_a": args.env_a,
            "env_b": args.env_b,
            "method": args.method,
            "options": options,
            "spp": args.spp,
            "turns": args.turns,
            "summary": summary,
            "samples_per_second": figures,
        }
        args.out.write_text(json.dumps(record, indent=2))


if __name__ == "__main__":
    main()
