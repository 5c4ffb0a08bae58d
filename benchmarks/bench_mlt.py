"""Metropolis light transport against BDPT (issue 6): Veach's door figure and equal-time error
of the path tracer, BDPT, PSSMLT, multiplexed MLT and path-space (Veach) MLT.

The figure: on the door scene, BDPT at 40 spp (timed), then MLT given the same wall time
(``time_limit``), side by side with the reference, each titled with its samples or mutations per
pixel, seconds and relMSE, as Veach and Guibas's figure (BDPT 40 spp against MLT 250 mutations per
pixel in the same time). Path-space MLT is ``method="mlt"``; where this build has no such method
(``dualight.render`` raises "unknown method") the script says so and shows PSSMLT, labelled so.

The curves: every method renders every scene (``bench_bdpt``'s scenes and references: 64x64,
``max_depth`` 8, relMSE with the reference's own noise removed) for a series of budgets.
Each render gets its budget as ``time_limit``; a method that rejects ``time_limit`` (``mmlt``
does: each path length gets its share of a mutation count) is calibrated instead: renders at
two ``mutations_per_pixel`` fit its fixed cost (direct light, bootstrap) and its mutations per
second, and each budget gets the count expected to fill it. Either way the measured seconds,
not the budget, are what is plotted and compared, so overshoot (e.g. an MLT's fixed cost
larger than the budget) shows. Efficiency is ``1 / (relMSE * seconds)``; ratios of efficiency
(times to equal error) are printed for the longest budget.

Writes ``benchmarks/results/bench_mlt.json`` (environment; per scene, method and budget: seconds,
relMSE, spp or mutations per pixel, and the render's stats, e.g. acceptance rates and ``b``),
``bench_mlt.png`` (relMSE against seconds, one panel per scene) and ``bench_mlt_door.png`` (the
figure). ``--quick`` writes the same files with a ``_quick`` suffix (git ignores them).

    python benchmarks/bench_mlt.py            # budgets 0.5..8 s per render (several minutes)
    python benchmarks/bench_mlt.py --quick    # budgets 0.25..1 s, a smoke run (about a minute)
    python benchmarks/bench_mlt.py --scenes door --methods bdpt,mlt --figure-spp 40
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

import dualight

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from bench_bdpt import (  # noqa: E402
    RESULTS,
    SCENES,
    efficiency_ratios,
    errors,
    load_reference,
    run_dualight,
)

METHODS = ("path", "bdpt", "pssmlt", "mmlt", "mlt")
MLT_METHODS = ("pssmlt", "mmlt", "mlt")
# (faster?, than) pairs whose equal-time efficiency ratio is reported.
RATIOS = [
    ("mlt", "bdpt"),
    ("pssmlt", "bdpt"),
    ("mmlt", "bdpt"),
    ("mlt", "pssmlt"),
    ("mlt", "mmlt"),
    ("mmlt", "pssmlt"),
    ("bdpt", "path"),
    ("mlt", "path"),
]
FIGURE_SCENE = "door"
# Scalar stats kept in the JSON (everything the render reports but the method's name and such).
STATS_SKIP = {"method", "sampler", "seed", "max_depth", "rr_depth", "threads", "heuristic"}


class Unavailable(Exception):
    """The method does not exist in this build, or takes no budget this script can give."""


def run_counted(scene: dualight.Scene, method: str, max_depth: int, seed: int, **count: int):
    """A render with ``spp=`` or ``mutations_per_pixel=``, timed as ``run_dualight``."""
    start = time.perf_counter()
    image = dualight.render(scene, method, max_depth=max_depth, seed=seed, progress=False, **count)
    return np.asarray(image), time.perf_counter() - start, image.stats


def pixels_of(scene: dualight.Scene) -> int:
    cam = scene.camera
    assert cam is not None
    return cam.width * cam.height


def calibrate(scene: dualight.Scene, method: str, max_depth: int, seed: int) -> dict[str, Any]:
    """Fixed seconds and mutations per second of ``method``, from renders at 1 and ``m``
    mutations per pixel (``m`` doubled from 16 until the mutations take 0.3 s or more)."""
    pixels = pixels_of(scene)
    runs = []
    for mpp in (1, 16):
        _, secs, stats = run_counted(scene, method, max_depth, seed, mutations_per_pixel=mpp)
        runs.append({"mutations_per_pixel": mpp, "seconds": secs, "mutations": mutations(stats)})
    while (
        runs[-1]["seconds"] - runs[0]["seconds"] < 0.3 and runs[-1]["mutations_per_pixel"] < 65536
    ):
        mpp = 2 * runs[-1]["mutations_per_pixel"]
        _, secs, stats = run_counted(scene, method, max_depth, seed, mutations_per_pixel=mpp)
        runs.append({"mutations_per_pixel": mpp, "seconds": secs, "mutations": mutations(stats)})
    a, b = runs[0], runs[-1]
    rate = (b["mutations"] - a["mutations"]) / max(b["seconds"] - a["seconds"], 1e-3)
    fixed = max(a["seconds"] - a["mutations"] / rate, 0.0)
    print(
        f"  calibrated {method}: {fixed:.2f} s fixed + {rate / 1e6:.3f} M mutations/s "
        f"({pixels} pixels; runs at {[r['mutations_per_pixel'] for r in runs]} mpp)"
    )
    return {"fixed_seconds": fixed, "mutations_per_second": rate, "runs": runs}


def mutations(stats: dict[str, Any]) -> int:
    return int(stats.get("mutations", stats["samples"]))


def render_budget(
    scene: dualight.Scene,
    method: str,
    budget: float,
    max_depth: int,
    seed: int,
    calibrations: dict[str, dict[str, Any]],
) -> tuple[np.ndarray, float, dict[str, Any], dict[str, Any]]:
    """Render for about ``budget`` seconds: by ``time_limit``, else by a calibrated
    ``mutations_per_pixel`` (see ``calibrate``; the calibration is cached per method in
    ``calibrations``). Returns the image, measured seconds, stats and how the budget was given."""
    if method not in calibrations:
        try:
            img, secs, stats = run_dualight(scene, method, budget, max_depth, seed)
            return img, secs, stats, {"budget_by": "time_limit"}
        except ValueError as err:
            if "unknown method" in str(err):
                raise Unavailable(str(err)) from err
            print(f"  {method} rejects time_limit ({err}); calibrating mutations_per_pixel")
            try:
                calibrations[method] = calibrate(scene, method, max_depth, seed=900)
            except ValueError as err2:
                raise Unavailable(
                    f"takes neither time_limit ({err}) nor mutations_per_pixel ({err2})"
                ) from err2
    cal = calibrations[method]
    target = (budget - cal["fixed_seconds"]) * cal["mutations_per_second"] / pixels_of(scene)
    mpp = max(1, round(target))
    img, secs, stats = run_counted(scene, method, max_depth, seed, mutations_per_pixel=mpp)
    return img, secs, stats, {"budget_by": "mutations_per_pixel", "mutations_per_pixel": mpp}


def record(scene: dualight.Scene, method: str, secs: float, stats: dict[str, Any]) -> dict:
    """Seconds, spp (path, BDPT) or mutations per pixel (MLT) and the render's scalar stats."""
    out: dict[str, Any] = {"method": method, "seconds": secs}
    if method in MLT_METHODS:
        out["mpp"] = mutations(stats) / pixels_of(scene)
    else:
        out["spp"] = int(stats["spp"])
    out["stats"] = {
        k: v
        for k, v in stats.items()
        if k not in STATS_SKIP and (v is None or isinstance(v, bool | int | float | str))
    }
    return out


def count_label(run: dict[str, Any]) -> str:
    return f"{run['spp']} spp" if "spp" in run else f"{run['mpp']:.1f} mutations/pixel"


def environment() -> dict[str, Any]:
    try:
        commit = subprocess.run(
            ["git", "rev-parse", "HEAD"], cwd=HERE, capture_output=True, text=True, check=True
        ).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        commit = None
    return {
        "cpu_count": os.cpu_count(),
        "platform": platform.platform(),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "dualight": dualight.__version__,
        "git_commit": commit,
        "load_average_at_start": list(os.getloadavg()),
    }


def prepare(name: str) -> tuple[str, dualight.Scene, np.ndarray, np.ndarray, dict[str, Any]]:
    """A scene of the set with its reference (name, mean, variance, metadata); its BVH is built
    by a 1-spp render, so no timed render pays for it."""
    ref_name, build = SCENES[name]
    ref, ref_var, info = load_reference(ref_name)
    scene = build()
    dualight.render(scene, "path", spp=1, max_depth=int(info["max_depth"]), progress=False)
    return ref_name, scene, ref, ref_var, info


def figure(spp: int, skipped: dict[str, str], suffix: str) -> dict[str, Any] | None:
    """Veach's figure on the door scene: BDPT at ``spp`` against MLT in the same wall time."""
    ref_name, scene, ref, ref_var, info = prepare(FIGURE_SCENE)
    max_depth = int(info["max_depth"])
    full = np.ones(ref.shape[:2], dtype=bool)
    img_b, secs_b, stats_b = run_counted(scene, "bdpt", max_depth, seed=40, spp=spp)
    bdpt = {**record(scene, "bdpt", secs_b, stats_b), **errors(img_b, ref, ref_var, full)}
    mlt = None
    for method in ("mlt", "pssmlt"):
        if method in skipped:
            continue
        try:
            img_m, secs_m, stats_m, how = render_budget(scene, method, secs_b, max_depth, 41, {})
        except Unavailable as err:
            skipped[method] = str(err)
            print(f"figure: no {method!r} in this build ({err}); showing the next MLT instead")
            continue
        mlt = {**record(scene, method, secs_m, stats_m), **how, **errors(img_m, ref, ref_var, full)}
        break
    if mlt is None:
        print("figure: no MLT method available; skipped")
        return None
    for r in (bdpt, mlt):
        r.pop("relmse_lt_pixels")
    note = "" if mlt["method"] == "mlt" else " (path-space MLT not available)"
    # An MLT's fixed cost (direct light, bootstrap) can take all of BDPT's time.
    starved = "no mutation: its fixed cost took the whole time" if mlt["mpp"] == 0 else ""
    print(
        f"figure ({FIGURE_SCENE}): BDPT {count_label(bdpt)} in {bdpt['seconds']:.2f} s, "
        f"relMSE {bdpt['relmse']:.3e}; {mlt['method']}{note} {count_label(mlt)} "
        f"in {mlt['seconds']:.2f} s, relMSE {mlt['relmse']:.3e}"
        + (f"; {starved}" if starved else "")
    )

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # One exposure for all panels: the reference's 99th percentile luminance maps to white.
    y99 = float(np.percentile(dualight.Image(ref).luminance(), 99))
    exposure = -float(np.log2(y99)) if y99 > 0 else 0.0
    panels = [
        (img_b, f"BDPT, {count_label(bdpt)}\n{bdpt['seconds']:.2f} s, relMSE {bdpt['relmse']:.3g}"),
        (
            img_m,
            f"{mlt['method'].upper()}{note}, {count_label(mlt)}\n"
            f"{mlt['seconds']:.2f} s, relMSE {mlt['relmse']:.3g}"
            + (f"\n{starved}" if starved else ""),
        ),
        (ref, f"reference (Mitsuba path, {info.get('spp')} spp)\n{ref_name}"),
    ]
    fig, axes = plt.subplots(1, 3, figsize=(12, 4.8), layout="constrained")
    for ax, (img, title) in zip(axes, panels, strict=True):
        ax.imshow(dualight.Image(img).tonemap(exposure), interpolation="nearest")
        ax.set_title(title, fontsize=9)
        ax.axis("off")
    fig.suptitle(
        f"Veach's door at equal time: {ref.shape[1]}x{ref.shape[0]}, max_depth {max_depth}"
    )
    path = RESULTS / f"bench_mlt_{FIGURE_SCENE}{suffix}.png"
    RESULTS.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"wrote {path}")
    return {
        "scene": FIGURE_SCENE,
        "reference": ref_name,
        "exposure": exposure,
        "bdpt": bdpt,
        "mlt": mlt,
    }


def plot(summary: dict[str, Any], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(summary["scenes"])
    if not names:
        return
    colours = {m: f"C{i}" for i, m in enumerate(METHODS)}
    fig, axes = plt.subplots(1, len(names), figsize=(5 * len(names), 4.2), squeeze=False)
    for ax, name in zip(axes[0], names, strict=True):
        runs = summary["scenes"][name]["runs"]
        for method in METHODS:
            rs = sorted((r for r in runs if r["method"] == method), key=lambda r: r["seconds"])
            if not rs:
                continue
            label = method + (" (calibrated mpp)" if rs[0]["budget_by"] != "time_limit" else "")
            ax.loglog(
                [r["seconds"] for r in rs],
                [r["relmse"] for r in rs],
                "o-",
                color=colours[method],
                label=label,
            )
        ax.set_title(f"{name} 64x64, max_depth {summary['scenes'][name]['max_depth']}")
        ax.set_xlabel("render time (s)")
        ax.set_ylabel("relMSE (reference noise removed)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--budgets", type=str, default="0.5,1,2,4,8")
    parser.add_argument("--scenes", type=str, default=",".join(SCENES))
    parser.add_argument("--methods", type=str, default=",".join(METHODS))
    parser.add_argument("--figure-spp", type=int, default=40, help="BDPT's spp in the figure")
    parser.add_argument("--quick", action="store_true", help="budgets 0.25,0.5,1; *_quick files")
    args = parser.parse_args()
    if args.quick:
        args.budgets = "0.25,0.5,1"
    budgets = [float(b) for b in args.budgets.split(",")]
    methods = [m for m in args.methods.split(",") if m]
    unknown = set(methods) - set(METHODS) | set(args.scenes.split(",")) - set(SCENES)
    if unknown:
        parser.error(f"unknown scene or method: {', '.join(sorted(unknown))}")
    suffix = "_quick" if args.quick else ""
    start = time.perf_counter()

    skipped: dict[str, str] = {}  # method -> why (shared: asked once)
    summary: dict[str, Any] = {
        "environment": environment(),
        "budgets_seconds": budgets,
        "methods": methods,
        "skipped_methods": skipped,
        "figure": figure(args.figure_spp, skipped, suffix),
        "scenes": {},
    }
    for name in args.scenes.split(","):
        ref_name, scene, ref, ref_var, info = prepare(name)
        max_depth = int(info["max_depth"])
        full = np.ones(ref.shape[:2], dtype=bool)
        calibrations: dict[str, dict[str, Any]] = {}
        runs: list[dict[str, Any]] = []
        print(f"{name}:")
        for method in methods:
            if method in skipped:
                continue
            for i, budget in enumerate(budgets):
                try:
                    img, secs, stats, how = render_budget(
                        scene, method, budget, max_depth, 100 + i, calibrations
                    )
                except Unavailable as err:
                    skipped[method] = str(err)
                    print(f"  skipping {method!r}: not available in this build ({err})")
                    break
                r = {"budget": budget, **how, **record(scene, method, secs, stats)}
                r.update(errors(img, ref, ref_var, full))
                r.pop("relmse_lt_pixels")  # the whole image here: the same as relmse
                r["efficiency"] = 1.0 / (r["relmse"] * r["seconds"])
                runs.append(r)
                st = r["stats"]
                extra = (
                    f" acc {st['acceptance_rate']:.2f} b {st['b']:.4g}"
                    if "acceptance_rate" in st and "b" in st
                    else ""
                )
                print(
                    f"  {method:>7} {budget:5.2f} s -> {secs:6.2f} s {count_label(r):>24} "
                    f"relMSE {r['relmse']:.3e} (raw {r['relmse_raw']:.3e}, "
                    f"floor {r['reference_floor']:.1e}){extra}"
                )

        top = {r["method"]: r for r in runs if r["budget"] == max(budgets)}
        ratios = efficiency_ratios(top, RATIOS)
        summary["scenes"][name] = {
            "reference": ref_name,
            "reference_spp": info.get("spp"),
            "max_depth": max_depth,
            "calibrations": calibrations,
            "runs": runs,
            "equal_time_efficiency_ratios_at_budget": max(budgets),
            "equal_time_efficiency_ratios": ratios,
        }

    names = list(summary["scenes"])
    keys = [f"{a} / {b}" for a, b in RATIOS]
    keys = [
        k
        for k in keys
        if any(k in summary["scenes"][n]["equal_time_efficiency_ratios"] for n in names)
    ]
    print(
        f"\nefficiency ratios at {max(budgets)} s, 1 / (relMSE * seconds): "
        "time to equal relMSE, > 1: the first is faster"
    )
    print(f"{'':>16}" + "".join(f"{n:>11}" for n in names))
    for k in keys:
        cells = [summary["scenes"][n]["equal_time_efficiency_ratios"].get(k) for n in names]
        print(f"{k:>16}" + "".join(f"{'-' if c is None else f'x{c:.2f}':>11}" for c in cells))
    for method, why in skipped.items():
        print(f"skipped {method!r}: {why}")

    summary["environment"]["load_average_at_end"] = list(os.getloadavg())
    summary["environment"]["wall_seconds"] = time.perf_counter() - start
    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / f"bench_mlt{suffix}.json").write_text(json.dumps(summary, indent=2) + "\n")
    plot(summary, RESULTS / f"bench_mlt{suffix}.png")
    print(
        f"wrote {RESULTS / f'bench_mlt{suffix}.json'} and bench_mlt{suffix}.png "
        f"in {time.perf_counter() - start:.0f} s"
    )


if __name__ == "__main__":
    main()
