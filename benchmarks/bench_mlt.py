"""Metropolis light transport against BDPT (issue 6): Veach's door figure and equal-time error
of the path tracer, BDPT, PSSMLT, multiplexed MLT and path-space (Veach) MLT.

The figure: on the door scene, BDPT at 40 spp (timed), then path-space MLT given the same wall
time (``time_limit``; its start-up then takes a share of it), with Veach's luminance target
(``mlt``) and with the flattened importance (``mlt_flat``, ``mlt={"importance": "flattened"}``),
side by side with the reference, each titled with its samples or mutations per pixel, seconds
and relMSE (mean over ``--seeds``), as Veach and Guibas's figure (BDPT 40 spp against MLT 250
mutations per pixel in the same time). Where this build has no path-space MLT
(``dualight.render`` raises "unknown method") the script says so and shows PSSMLT, labelled so.

The curves: every method renders every scene (``bench_bdpt``'s scenes and references: 64x64,
``max_depth`` 8, relMSE with the reference's own noise removed) for a series of budgets,
``--seeds`` times each (MLT errors vary much from seed to seed; the mean relMSE and seconds are
plotted and compared).
Each render gets its budget as ``time_limit``; a method that rejects ``time_limit`` is
calibrated instead: renders at
two ``mutations_per_pixel`` fit its fixed cost (direct light, bootstrap) and its mutations per
second, and each budget gets the count expected to fill it. Either way the measured seconds,
not the budget, are what is plotted and compared, so overshoot (e.g. an MLT's fixed cost
larger than the budget) shows. Efficiency is ``1 / (relMSE * seconds)``; ratios of efficiency
(times to equal error) are printed for the longest budget.

Writes ``benchmarks/results/bench_mlt.json`` (environment; per scene, method and budget: seconds,
relMSE, spp or mutations per pixel, and the render's stats, e.g. acceptance rates and ``b``),
``bench_mlt.png`` (relMSE against seconds, one panel per scene) and ``bench_mlt_door.png`` (the
figure). ``--quick`` writes the same files with a ``_quick`` suffix (git ignores them).

    python benchmarks/bench_mlt.py            # budgets 0.5..8 s, 3 seeds (about 15 minutes)
    python benchmarks/bench_mlt.py --quick    # budgets 0.25..1 s, 1 seed: a smoke run
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
from dualight import metrics
from dualight.methods import METROPOLIS
from dualight.plotting import save_relmse_against_time

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from bench_bdpt import (  # noqa: E402
    RESULTS,
    SCENES,
    efficiency_ratios,
    errors,
    load_reference,
)

# Labels that are a method with options: path-space MLT with its flattened importance.
VARIANTS: dict[str, tuple[str, dict[str, Any]]] = {
    "mlt_flat": ("mlt", {"mlt": {"importance": "flattened"}}),
}
MLT_METHODS = (*METROPOLIS, *VARIANTS)
# The path tracer with one sampling strategy alone (bench_scenes.py on Veach's MIS plates).
VARIANTS.update(
    {
        "path_bsdf": ("path", {"strategies": "bsdf"}),
        "path_light": ("path", {"strategies": "light"}),
    }
)
METHODS = ("path", "bdpt", *MLT_METHODS)
# (faster?, than) pairs whose equal-time efficiency ratio is reported.
RATIOS = [
    ("mlt", "bdpt"),
    ("mlt_flat", "bdpt"),
    ("mlt_flat", "mlt"),
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


def run_counted(scene: dualight.Scene, method: str, max_depth: int, seed: int, **count: Any):
    """A render of ``method`` (or of a label in ``VARIANTS``) with ``spp=``,
    ``mutations_per_pixel=`` or ``time_limit=``; returns the image, wall seconds and stats."""
    real, options = VARIANTS.get(method, (method, {}))
    start = time.perf_counter()
    image = dualight.render(
        scene, real, max_depth=max_depth, seed=seed, progress=False, **options, **count
    )
    return np.asarray(image), time.perf_counter() - start, image.stats


def run_dualight(scene: dualight.Scene, method: str, budget: float, max_depth: int, seed: int):
    """A render given ``budget`` seconds as ``time_limit``."""
    return run_counted(scene, method, max_depth, seed, spp=None, time_limit=budget)


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
    """Seconds, spp (path, BDPT) or mutations per pixel (MLT) and the render's scalar stats (with
    a guided render's scalar guiding stats)."""
    out: dict[str, Any] = {"method": method, "seconds": secs}
    if method in MLT_METHODS:
        out["mpp"] = mutations(stats) / pixels_of(scene)
    else:
        out["spp"] = int(stats["spp"])
    out["stats"] = _scalars(stats, STATS_SKIP)
    if isinstance(stats.get("guiding"), dict):  # guided renders: training, trial, decision
        out["stats"]["guiding"] = _scalars(stats["guiding"], ())
    return out


def _scalars(stats: dict[str, Any], skip: Any) -> dict[str, Any]:
    return {
        k: v
        for k, v in stats.items()
        if k not in skip and (v is None or isinstance(v, bool | int | float | str))
    }


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


def figure(
    spp: int,
    skipped: dict[str, str],
    suffix: str,
    seeds: int,
    scene_name: str = FIGURE_SCENE,
    stem: str = "bench_mlt",
) -> dict[str, Any] | None:
    """Veach's figure on the door scene (or ``scene_name``): BDPT at ``spp`` against MLT
    (Veach's luminance target, and the flattened importance) in the same wall time, each
    seed's MLT given the time that seed's BDPT took. relMSE is the mean over ``seeds``; the
    images are the first seed's. Saved as ``{stem}_{scene_name}{suffix}.png``."""
    ref_name, scene, ref, ref_var, info = prepare(scene_name)
    max_depth = int(info["max_depth"])
    full = np.ones(ref.shape[:2], dtype=bool)
    entries: dict[str, list[dict[str, Any]]] = {}
    images: dict[str, np.ndarray] = {}
    for k in range(seeds):
        img_b, secs_b, stats_b = run_counted(scene, "bdpt", max_depth, seed=40 + k, spp=spp)
        row = {**record(scene, "bdpt", secs_b, stats_b), **errors(img_b, ref, ref_var, full)}
        entries.setdefault("bdpt", []).append(row)
        images.setdefault("bdpt", img_b)
        for method in ("mlt", "mlt_flat", "pssmlt"):
            if method in skipped or (method == "pssmlt" and "mlt" in entries):
                continue
            try:
                img_m, secs_m, stats_m, how = render_budget(
                    scene, method, secs_b, max_depth, 41 + k, {}
                )
            except Unavailable as err:
                skipped[method] = str(err)
                print(f"figure: no {method!r} in this build ({err})")
                continue
            row = {**record(scene, method, secs_m, stats_m), **how}
            row.update(errors(img_m, ref, ref_var, full))
            entries.setdefault(method, []).append(row)
            images.setdefault(method, img_m)
    if len(entries) < 2:
        print("figure: no MLT method available; skipped")
        return None
    summary: dict[str, Any] = {"scene": scene_name, "reference": ref_name, "seeds": seeds}
    for method, rows in entries.items():
        for r in rows:
            r.pop("relmse_lt_pixels", None)
        rel = np.array([r["relmse"] for r in rows])
        summary[method] = {
            "runs": rows,
            "seconds": float(np.mean([r["seconds"] for r in rows])),
            "relmse": float(rel.mean()),
            "relmse_stderr": float(rel.std(ddof=1) / np.sqrt(len(rel))) if len(rel) > 1 else None,
            "count": count_label(
                {"spp": rows[0]["spp"]}
                if "spp" in rows[0]
                else {"mpp": float(np.mean([r["mpp"] for r in rows]))}
            ),
        }
    bdpt = summary["bdpt"]
    line = (
        f"figure ({scene_name}, {seeds} seeds): BDPT {bdpt['count']} in "
        f"{bdpt['seconds']:.2f} s, relMSE {bdpt['relmse']:.3e}"
    )
    for method in entries:
        if method != "bdpt":
            m = summary[method]
            line += (
                f"; {method} {m['count']} in {m['seconds']:.2f} s, relMSE {m['relmse']:.3e} "
                f"(BDPT / {method}: x{bdpt['relmse'] / m['relmse']:.2f})"
            )
    print(line)

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # One exposure for all panels: the reference's 99th percentile luminance maps to white.
    y99 = float(np.percentile(dualight.Image(ref).luminance(), 99))
    exposure = -float(np.log2(y99)) if y99 > 0 else 0.0
    titles = {
        "bdpt": "BDPT",
        "mlt": "MLT (luminance)",
        "mlt_flat": "MLT (flattened)",
        "pssmlt": "PSSMLT (no path-space MLT)",
    }
    panels = [
        (
            images[m],
            f"{titles[m]}, {summary[m]['count']}\n{summary[m]['seconds']:.2f} s, "
            f"relMSE {summary[m]['relmse']:.3g}",
        )
        for m in entries
    ]
    panels.append((ref, f"reference (Mitsuba path, {info.get('spp')} spp)\n{ref_name}"))
    fig, axes = plt.subplots(1, len(panels), figsize=(4 * len(panels), 4.8), layout="constrained")
    for ax, (img, title) in zip(axes, panels, strict=True):
        ax.imshow(dualight.Image(img).tonemap(exposure), interpolation="nearest")
        ax.set_title(title, fontsize=9)
        ax.axis("off")
    fig.suptitle(
        f"{scene_name} at equal time: {ref.shape[1]}x{ref.shape[0]}, max_depth {max_depth}; "
        f"relMSE: mean of {seeds} seeds"
    )
    path = RESULTS / f"{stem}_{scene_name}{suffix}.png"
    RESULTS.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"wrote {path}")
    summary["exposure"] = exposure
    return summary


def plot(summary: dict[str, Any], path: Path, methods: tuple[str, ...] = METHODS) -> None:
    panels, colours = {}, {}
    for name, entry in summary["scenes"].items():
        curves = {}
        for i, method in enumerate(methods):
            runs = [r for r in entry["curves"] if r["method"] == method]
            if runs:
                calibrated = runs[0]["budget_by"] != "time_limit"
                label = method + (" (calibrated mpp)" if calibrated else "")
                curves[label] = [(r["seconds"], r["relmse"]) for r in runs]
                colours[label] = f"C{i}"
        panels[f"{name} 64x64, max_depth {entry['max_depth']}"] = curves
    save_relmse_against_time(
        panels,
        path,
        ylabel=f"relMSE (reference noise removed; mean of {summary['seeds']} seeds)",
        colours=colours,
    )


def scene_study(
    name: str,
    methods: list[str],
    budgets: list[float],
    seeds: int,
    skipped: dict[str, str],
    ratios: list[tuple[str, str]] = RATIOS,
) -> dict[str, Any]:
    """Every method on scene ``name`` at every budget, ``seeds`` renders each: the runs, the
    curves (mean relMSE and seconds per budget) and the equal-time efficiency ratios at the
    longest budget. Methods this build lacks are added to ``skipped`` (method -> why)."""
    ref_name, scene, ref, ref_var, info = prepare(name)
    max_depth = int(info["max_depth"])
    full = np.ones(ref.shape[:2], dtype=bool)
    calibrations: dict[str, dict[str, Any]] = {}
    runs: list[dict[str, Any]] = []
    print(f"{name}:")
    curves: list[dict[str, Any]] = []
    for method in methods:
        if method in skipped:
            continue
        for i, budget in enumerate(budgets):
            rows = []
            for k in range(seeds):
                try:
                    img, secs, stats, how = render_budget(
                        scene, method, budget, max_depth, 100 + i + 1000 * k, calibrations
                    )
                except Unavailable as err:
                    skipped[method] = str(err)
                    print(f"  skipping {method!r}: not available in this build ({err})")
                    break
                r = {"budget": budget, "seed_index": k, **how}
                r.update(record(scene, method, secs, stats))
                r.update(errors(img, ref, ref_var, full))
                r.pop("relmse_lt_pixels")  # the whole image here: the same as relmse
                r["delta_e2000"] = metrics.delta_e2000(img, ref)["mean"]
                r["efficiency"] = 1.0 / (r["relmse"] * r["seconds"])
                runs.append(r)
                rows.append(r)
            if method in skipped:
                break
            rel = np.array([r["relmse"] for r in rows])
            curve = {
                "method": method,
                "budget": budget,
                "budget_by": rows[0]["budget_by"],
                "seeds": len(rows),
                "seconds": float(np.mean([r["seconds"] for r in rows])),
                "relmse": float(rel.mean()),
                "relmse_stderr": (
                    float(rel.std(ddof=1) / np.sqrt(len(rel))) if len(rel) > 1 else None
                ),
            }
            curve["delta_e2000"] = float(np.mean([r["delta_e2000"] for r in rows]))
            curve["efficiency"] = 1.0 / (curve["relmse"] * curve["seconds"])
            curves.append(curve)
            st = rows[0]["stats"]
            extra = (
                f" acc {st['acceptance_rate']:.2f} b {st['b']:.4g}"
                if "acceptance_rate" in st and "b" in st
                else ""
            )
            spread = "" if len(rows) < 2 else f" +- {curve['relmse_stderr']:.1e}"
            print(
                f"  {method:>8} {budget:5.2f} s -> {curve['seconds']:6.2f} s "
                f"{count_label(rows[0]):>24} relMSE {curve['relmse']:.3e}{spread} "
                f"dE {curve['delta_e2000']:.2f} "
                f"({len(rows)} seeds){extra}",
                flush=True,
            )

    top = {c["method"]: c for c in curves if c["budget"] == max(budgets)}
    return {
        "reference": ref_name,
        "reference_spp": info.get("spp"),
        "max_depth": max_depth,
        "calibrations": calibrations,
        "runs": runs,
        "curves": curves,
        "equal_time_efficiency_ratios_at_budget": max(budgets),
        "equal_time_efficiency_ratios": efficiency_ratios(top, ratios),
    }


def print_ratios(summary: dict[str, Any], budget: float, ratios: list[tuple[str, str]]) -> None:
    """The equal-time efficiency ratios of every scene of ``summary``, as a table."""
    names = list(summary["scenes"])
    keys = [f"{a} / {b}" for a, b in ratios]
    keys = [
        k
        for k in keys
        if any(k in summary["scenes"][n]["equal_time_efficiency_ratios"] for n in names)
    ]
    print(
        f"\nefficiency ratios at {budget} s, 1 / (relMSE * seconds): "
        "time to equal relMSE, > 1: the first is faster"
    )
    print(f"{'':>16}" + "".join(f"{n:>11}" for n in names))
    for k in keys:
        cells = [summary["scenes"][n]["equal_time_efficiency_ratios"].get(k) for n in names]
        print(f"{k:>16}" + "".join(f"{'-' if c is None else f'x{c:.2f}':>11}" for c in cells))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--budgets", type=str, default="0.5,1,2,4,8")
    parser.add_argument("--scenes", type=str, default=",".join(SCENES))
    parser.add_argument("--methods", type=str, default=",".join(METHODS))
    parser.add_argument("--figure-spp", type=int, default=40, help="BDPT's spp in the figure")
    parser.add_argument("--seeds", type=int, default=3, help="renders per method and budget")
    parser.add_argument("--quick", action="store_true", help="budgets 0.25,0.5,1; *_quick files")
    args = parser.parse_args()
    if args.quick:
        args.budgets, args.seeds = "0.25,0.5,1", 1
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
        "seeds": args.seeds,
        "methods": methods,
        "skipped_methods": skipped,
        "figure": figure(args.figure_spp, skipped, suffix, args.seeds),
        "scenes": {},
    }
    for name in args.scenes.split(","):
        summary["scenes"][name] = scene_study(name, methods, budgets, args.seeds, skipped)

    print_ratios(summary, max(budgets), RATIOS)
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
