"""Time saved by each skip, with the answer unchanged.

Every skip runs on a scene that allows it, with ``skip=True`` (the default) and ``skip=False``
(all the work), alternating, ``--repeats`` times each; the median times give the saving.
That the answer is unchanged is tested three ways:

* same seed: the two runs make the same random draws, so the images (or radiosity solutions)
  must agree to float rounding: a skipped shadow ray is one that would have arrived;
* independent seeds (the Monte Carlo renders): the skip-on image of seed 1 against the
  skip-off image of seed 2, a Welch test per 4x4 block at a family-wise 1 % (Sidak) for the
  estimators with per-pixel variances (path, light, bdpt), and for the Metropolis methods
  (correlated pixels) a Welch t test of the image means over ``--seeds`` seeds each;
* a negative control: the same test against a deliberately wrong scene (albedo 0.45 instead
  of 0.5 in the furnace; a 10 % brighter light in the rooms) must fail.

Skips measured:

* shadow rays in a convex enclosure holding the camera (the furnace, 64x64): path, light,
  bdpt, pssmlt, mlt;
* MLT's caustic and multi-chain perturbations in a diffuse scene (the Cornell box): they never
  suit a path there, so only the per-step suitability checks are saved;
* form-factor visibility rays in a convex enclosure (furnace; Gauss-Seidel and hierarchical);
* form-factor rows of patches of zero importance when only the view is wanted
  (``solve(view_only=True)``; four rooms without doors, the camera in one).

Writes ``benchmarks/results/bench_skipping.json`` and ``bench_skipping.png`` (time with and
without each skip) and prints a markdown table. ``--quick``: one repeat, smaller budgets.

    python benchmarks/bench_skipping.py
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import statistics
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

import dualight as dl
from dualight import metrics, scenes
from dualight.radiosity import solve

RESULTS = Path(__file__).resolve().parent / "results"
RES = (64, 64)


def welch_means(a: list[float], b: list[float]) -> dict[str, float]:
    """Welch's t test of two samples' means: t, degrees of freedom, two-sided p."""
    va, vb = statistics.variance(a) / len(a), statistics.variance(b) / len(b)
    t = (statistics.fmean(a) - statistics.fmean(b)) / math.sqrt(va + vb)
    dof = (va + vb) ** 2 / (va**2 / (len(a) - 1) + vb**2 / (len(b) - 1))
    return {"t": t, "dof": dof, "p": metrics.student_t_p_value(t, dof)}


def timed(run: Callable[[bool], Any], repeats: int) -> tuple[float, float, Any, Any]:
    """Median seconds with and without the skip (alternating) and the last results."""
    on_times, off_times = [], []
    on = off = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        on = run(True)
        on_times.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        off = run(False)
        off_times.append(time.perf_counter() - t0)
    return statistics.median(on_times), statistics.median(off_times), on, off


def render_case(method: str, budget: int, repeats: int, seeds: int) -> dict[str, Any]:
    furnace = scenes.furnace(0.5, 1.0, resolution=RES)
    wrong = scenes.furnace(0.45, 1.0, resolution=RES)
    mlt_like = method in ("pssmlt", "mlt")
    kw: dict[str, Any] = {"progress": False}
    if mlt_like:
        kw.update(mutations_per_pixel=budget, mlt={"bootstrap": 20000, "direct_spp": 8})
    else:
        kw.update(spp=budget)

    def run(skip: bool, seed: int = 1, scene: dl.Scene = furnace) -> dl.Image:
        return dl.render(scene, method, seed=seed, skip=skip, **kw)

    t_on, t_off, on, off = timed(run, repeats)
    same_seed = float(np.max(np.abs(np.asarray(on) - np.asarray(off))))
    out: dict[str, Any] = {
        "skip": "shadow rays (convex enclosure)",
        "method": method,
        "scene": "furnace 64x64, rho 0.5",
        "budget": budget,
        "seconds_on": t_on,
        "seconds_off": t_off,
        "skipped": on.stats["skipped"],
        "rays_on": on.stats["rays"],
        "rays_off": off.stats["rays"],
        "same_seed_max_abs_difference": same_seed,
    }
    if not mlt_like:
        other = run(False, seed=2)
        bad = run(False, seed=2, scene=wrong)
        ok = metrics.welch_test(on, on.variance, other, other.variance, block=4)
        ctl = metrics.welch_test(on, on.variance, bad, bad.variance, block=4)
        out["welch"] = {
            "test": "per 4x4 block, family-wise 1 %",
            "max_z": ok.max_z,
            "passed": ok.pass_fraction == 1.0,
            "control_max_z": ctl.max_z,
            "control_failed": ctl.pass_fraction < 1.0,
        }
    else:
        means_on = [float(np.mean(run(True, seed=s))) for s in range(10, 10 + seeds)]
        means_off = [float(np.mean(run(False, seed=s))) for s in range(100, 100 + seeds)]
        means_bad = [
            float(np.mean(run(False, seed=s, scene=wrong))) for s in range(100, 100 + seeds)
        ]
        ok = welch_means(means_on, means_off)
        ctl = welch_means(means_on, means_bad)
        out["welch"] = {
            "test": f"image means over {seeds} seeds each",
            **ok,
            "passed": ok["p"] > 0.01,
            "control_t": ctl["t"],
            "control_p": ctl["p"],
            "control_failed": ctl["p"] <= 0.01,
        }
    return out


def mlt_mutation_case(budget: int, repeats: int) -> dict[str, Any]:
    cornell = scenes.cornell_box(RES)
    kw = {
        "mutations_per_pixel": budget,
        "progress": False,
        "mlt": {"bootstrap": 20000, "direct_spp": 8},
    }
    t_on, t_off, on, off = timed(
        lambda skip: dl.render(cornell, "mlt", seed=1, skip=skip, **kw), repeats
    )
    return {
        "skip": "MLT caustic and multi-chain perturbations (diffuse scene)",
        "method": "mlt",
        "scene": "Cornell box 64x64",
        "budget": budget,
        "seconds_on": t_on,
        "seconds_off": t_off,
        "skipped": on.stats["skipped"],
        "same_seed_max_abs_difference": float(np.max(np.abs(np.asarray(on) - np.asarray(off)))),
        "welch": {"test": "same draws: identical images", "passed": bool(np.array_equal(on, off))},
    }


def radiosity_case(kind: str, repeats: int, quick: bool) -> dict[str, Any]:
    if kind == "view_only":
        scene = scenes.rooms(n=4, doors=False)
        wrong = scenes.rooms(n=4, doors=False, light_radiance=11.0)
        edge = 1.0 if quick else 0.5
        method = "gauss_seidel"

        def run(skip: bool, sc: dl.Scene = scene) -> Any:
            return solve(sc, method, max_edge=edge, view_only=skip, tol=1e-9)

        label = "form-factor rows of zero-importance patches (view only)"
        where = f"4 rooms without doors, camera in one; max_edge {edge}"
    else:
        scene = scenes.furnace(0.5, 1.0)
        wrong = scenes.furnace(0.45, 1.0)
        method = kind
        edge = 0.1 if quick else 0.05

        def run(skip: bool, sc: dl.Scene = scene) -> Any:
            if kind == "hierarchical":
                return solve(sc, "hierarchical", skip=skip, epsilon=1e-3)
            return solve(sc, method, max_edge=edge, skip=skip, tol=1e-9)

        label = "form-factor visibility rays (convex enclosure)"
        where = "furnace, rho 0.5" + ("" if kind == "hierarchical" else f"; max_edge {edge}")
    t_on, t_off, on, off = timed(run, repeats)
    m_on, m_off = on.measurement_primal, off.measurement_primal
    m_bad = run(True, wrong).measurement_primal
    return {
        "skip": label,
        "method": method,
        "scene": where,
        "seconds_on": t_on,
        "seconds_off": t_off,
        "skipped": on.stats["skipped"],
        "patches": on.stats.get("patches", on.stats.get("leaves")),
        "measurement_on": m_on.tolist(),
        "measurement_off": m_off.tolist(),
        "welch": {
            "test": "deterministic: relative difference of the measurement <R, B>",
            "relative_difference": float(np.max(np.abs(m_on / m_off - 1))),
            "passed": bool(np.max(np.abs(m_on / m_off - 1)) < 1e-5),
            "control_relative_difference": float(np.max(np.abs(m_bad / m_off - 1))),
            "control_failed": bool(np.max(np.abs(m_bad / m_off - 1)) >= 1e-5),
        },
    }


SHORT = {
    "shadow rays (convex enclosure)": "shadow rays",
    "MLT caustic and multi-chain perturbations (diffuse scene)": "specular\nperturbations",
    "form-factor visibility rays (convex enclosure)": "visibility\nrays",
    "form-factor rows of zero-importance patches (view only)": "rows off\nthe view",
}


def plot(rows: list[dict[str, Any]], path: Path) -> None:
    """Bars of the median time with and without each skip (log scale)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 4.5))
    labels = [f"{r['method']}\n{SHORT.get(r['skip'], r['skip'])}" for r in rows]
    x = np.arange(len(rows))
    ax.bar(x - 0.2, [r["seconds_off"] for r in rows], 0.4, label="skip=False (all the work)")
    ax.bar(x + 0.2, [r["seconds_on"] for r in rows], 0.4, label="skip=True")
    ax.set_yscale("log")
    ax.set_xticks(x, labels, fontsize=7)
    ax.set_ylabel("seconds (median)")
    ax.set_title("Time with and without each skip (answers unchanged)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--repeats", type=int, default=None)
    parser.add_argument("--seeds", type=int, default=None)
    parser.add_argument("--plot-only", action="store_true", help="redraw the PNG from the JSON")
    args = parser.parse_args()
    suffix = "_quick" if args.quick else ""
    if args.plot_only:
        saved = json.loads((RESULTS / f"bench_skipping{suffix}.json").read_text())
        plot(saved["rows"], RESULTS / f"bench_skipping{suffix}.png")
        return
    repeats = args.repeats or (1 if args.quick else 5)
    seeds = args.seeds or (4 if args.quick else 8)
    scale = 1 if args.quick else 4
    # Budgets of a few tenths of a second each (the light tracer is cheap and noisy per sample).
    budgets = {"path": 16, "light": 64, "bdpt": 8, "pssmlt": 8, "mlt": 8}
    rows: list[dict[str, Any]] = []
    for method, budget in budgets.items():
        rows.append(render_case(method, budget * scale, repeats, seeds))
        print(f"{method}: {rows[-1]['seconds_off'] / rows[-1]['seconds_on']:.2f}x", flush=True)
    rows.append(mlt_mutation_case(8 * scale, repeats))
    for kind in ("gauss_seidel", "hierarchical", "view_only"):
        rows.append(radiosity_case(kind, repeats, args.quick))
        print(f"{kind}: {rows[-1]['seconds_off'] / rows[-1]['seconds_on']:.2f}x", flush=True)

    for r in rows:
        r["saved_fraction"] = 1 - r["seconds_on"] / r["seconds_off"]
        r["speedup"] = r["seconds_off"] / r["seconds_on"]
    lines = [
        "| skip | method | scene | time without skip (s) | with (s) | saved | speed-up "
        "| unchanged | control fails |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        w = r["welch"]
        control = w.get("control_failed")
        lines.append(
            f"| {r['skip']} | {r['method']} | {r['scene']} | {r['seconds_off']:.3f} "
            f"| {r['seconds_on']:.3f} | {100 * r['saved_fraction']:.0f} % | {r['speedup']:.2f}x "
            f"| {'yes' if w['passed'] else 'NO'} | "
            f"{'-' if control is None else ('yes' if control else 'NO')} |"
        )
    table = "\n".join(lines)
    print(table)
    RESULTS.mkdir(exist_ok=True)
    summary = {
        "machine": {"platform": platform.platform(), "cpus": __import__("os").cpu_count()},
        "date": time.strftime("%Y-%m-%d %H:%M"),
        "repeats": repeats,
        "seeds": seeds,
        "rows": rows,
        "table": table,
    }
    (RESULTS / f"bench_skipping{suffix}.json").write_text(
        json.dumps(summary, indent=1, default=float)
    )

    plot(rows, RESULTS / f"bench_skipping{suffix}.png")
    print(f"wrote {RESULTS / f'bench_skipping{suffix}.json'}")


if __name__ == "__main__":
    main()
