"""Hierarchical radiosity: importance-driven refinement [SAS92] against BF refinement [HSA91].

For each scene (``rooms(4)``, ``rooms(10)``, ``rooms(25)`` and ``cube()``, 64x64 cameras) the
script

1. path-traces a reference of the camera's VIEW MEASUREMENT, the mean pixel value per RGB
   channel (``dualight.render(scene, spp=..., seed=3)``; the path tracer is verified against
   Mitsuba 3), with its standard error ``sqrt(sum of pixel variances) / pixels``; the value is
   cached in ``benchmarks/results/cache/`` as JSON keyed by scene, resolution, spp and seed and
   checked against a fingerprint of the scene;
2. for each oracle (``bf``, ``importance``) solves the scene with
   :class:`dualight.radiosity.hierarchical.HierarchicalSolver` for a log grid of ``epsilon``
   (coarse to fine), recording links, leaves, elements, steps, rays, memory, seconds
   (``solution.stats["seconds"]``: setup plus every step; solves under 2 s are repeated and
   the fastest run kept) and the VIEW ERROR ``max over RGB |v / v_ref - 1|`` of
   ``solution.measurement_primal``. A sweep stops after the first solve over the budget
   (``--budget-seconds``, ``--budget-links``); a solve is abandoned between steps when it passes
   ``--hard-links`` links or 4 budgets of time (it is kept as a point, marked ``aborted``: the
   hierarchy after any step is a valid, less refined, solution);
3. compares the oracles at equal view error: each oracle's cost-error points are reduced to
   their monotone envelope (the points that lower the error below every cheaper point) and
   interpolated log-log; for every importance point, and at a grid of common errors, the
   ratios BF / importance of links and of seconds. Where BF never reaches an error within its
   budget the ratio is a lower bound, ``> (BF's largest cost) / (importance's cost)``; where an
   error is above a method's coarsest point its cost is at most that point's (an upper bound on
   it). Errors below 3 reference standard errors are flagged as noise-limited;
4. checks the issue's acceptance: on ``rooms(10)`` and larger, importance needs >= 5x fewer
   links and >= 3x less time than BF at equal view error; on the cube at most 1.1x BF's links.

Writes ``benchmarks/results/bench_hierarchical.json`` (every point, envelope, ratio and
verdict), ``bench_hierarchical.png`` (view error against links and against seconds, one column
per scene) and ``bench_hierarchical_pictures.png`` (``rooms(10)`` from a 128x128 camera:
radiosity, elements, links and superposition pictures of both oracles at about the same view
error). ``--quick`` writes ``bench_hierarchical_quick.*`` instead (so it never overwrites a full
run).

    python benchmarks/bench_hierarchical.py          # full run (about 15-30 min on 2 cores)
    python benchmarks/bench_hierarchical.py --quick  # short grids, 1024-spp references (< 3 min)
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import os
import platform
import resource
import subprocess
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

import dualight
from dualight.radiosity.hierarchical import HierarchicalSolver

RESULTS = Path(__file__).resolve().parent / "results"
CACHE = RESULTS / "cache"
ORACLES = ("bf", "importance")
SCENES: dict[str, Callable[[], dualight.Scene]] = {
    "rooms4": lambda: dualight.scenes.rooms(4),
    "rooms10": lambda: dualight.scenes.rooms(10),
    "rooms25": lambda: dualight.scenes.rooms(25),
    "cube": lambda: dualight.scenes.cube(),
}
LABELS = {"rooms4": "rooms(4)", "rooms10": "rooms(10)", "rooms25": "rooms(25)", "cube": "cube()"}
# Acceptance of the issue: minimum BF / importance ratios at equal view error.
ACCEPTANCE: dict[str, dict[str, float]] = {
    "rooms10": {"links": 5.0, "seconds": 3.0},
    "rooms25": {"links": 5.0, "seconds": 3.0},
    "cube": {"links": 1.0 / 1.1},
}
TARGET_ERRORS = [5e-2, 3e-2, 2e-2, 1.5e-2, 1e-2, 7e-3, 5e-3, 3e-3, 2e-3, 1.5e-3, 1e-3, 7e-4, 5e-4]
FULL_EPS = {
    "importance": [1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6, 1e-6],
    "bf": [1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4],
}
QUICK_EPS = {"importance": [1e-2, 1e-3, 1e-4, 3e-5, 1e-5], "bf": [1e-1, 1e-2, 1e-3]}


def log(msg: str) -> None:
    print(msg, flush=True)


# Reference ------------------------------------------------------------------------------------
def scene_fingerprint(scene: dualight.Scene) -> str:
    """A hash of the triangles, materials and camera: a cached reference of a changed scene is
    recomputed, not silently reused."""
    positions, triangles, mesh_of = scene.triangle_arrays()
    h = hashlib.sha256()
    for arr in (positions.astype(np.float64), triangles.astype(np.int64), mesh_of):
        h.update(np.ascontiguousarray(arr).tobytes())
    for m in scene.meshes:
        h.update(repr((m.reflectance, m.emission)).encode())
    h.update(repr(scene.camera).encode())
    return h.hexdigest()[:16]


def reference(name: str, scene: dualight.Scene, spp: int, seed: int) -> dict[str, Any]:
    """Path-traced view measurement and its standard error, cached as JSON."""
    cam = scene.camera
    assert cam is not None
    key = f"hier_ref_{name}_{cam.width}x{cam.height}_spp{spp}_seed{seed}"
    path = CACHE / f"{key}.json"
    fingerprint = scene_fingerprint(scene)
    if path.exists():
        cached = json.loads(path.read_text())
        if cached.get("fingerprint") == fingerprint:
            cached["cached"] = True
            return cached
        log(f"  cached reference {path.name} is for another version of the scene: recomputing")
    start = time.perf_counter()
    img = dualight.render(scene, spp=spp, seed=seed, progress=False)
    seconds = time.perf_counter() - start
    pixels = np.asarray(img, dtype=np.float64)
    n = pixels.shape[0] * pixels.shape[1]
    value = pixels.mean(axis=(0, 1))
    se = np.sqrt(np.asarray(img.variance, dtype=np.float64).sum(axis=(0, 1))) / n
    ref = {
        "key": key,
        "fingerprint": fingerprint,
        "spp": spp,
        "seed": seed,
        "resolution": [cam.width, cam.height],
        "value": value.tolist(),
        "std_error": se.tolist(),
        "relative_std_error": (se / value).tolist(),
        "seconds": seconds,
        "render_stats": {k: v for k, v in img.stats.items() if isinstance(v, int | float | str)},
    }
    CACHE.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(ref, indent=2) + "\n")
    ref["cached"] = False
    return ref


# Solves ---------------------------------------------------------------------------------------
def solve_once(
    scene: dualight.Scene, oracle: str, eps: float, hard_links: int, hard_seconds: float
) -> tuple[Any, dict[str, Any]]:
    """One hierarchical solve, stepped until converged or past the hard limits."""
    solver = HierarchicalSolver(scene, oracle=oracle, epsilon=eps)  # type: ignore[arg-type]
    aborted = ""
    while len(solver.history) < 100:
        last = solver.history[-1] if solver.history else None
        elapsed = solver.setup_seconds + sum(h.seconds for h in solver.history)
        if last is not None:
            if last.converged:
                break
            # The next step refines about as many links as the last one did, 4 for 1.
            predicted = last.links + 3 * last.links_refined
            if last.links > hard_links or predicted > 2 * hard_links:
                aborted = f"{last.links} links (next step ~{predicted})"
                break
            if elapsed > hard_seconds:
                aborted = f"{elapsed:.0f} s"
                break
        solver.step()
    sol = solver.solution()
    history = solver.history
    info = {
        "steps": len(history),
        "converged": bool(solver.converged),
        "aborted": aborted,
        "links_per_step": [h.links for h in history],
    }
    return sol, info


def measure(
    scene: dualight.Scene,
    oracle: str,
    eps: float,
    v_ref: np.ndarray,
    *,
    hard_links: int,
    hard_seconds: float,
    repeat_below: float,
    repeats: int,
) -> dict[str, Any]:
    sol, info = solve_once(scene, oracle, eps, hard_links, hard_seconds)
    st = sol.stats
    runs = [float(st["seconds"])]
    # Short solves are timed again (the results are deterministic): the fastest run counts.
    while runs[0] < repeat_below and len(runs) < repeats:
        again, _ = solve_once(scene, oracle, eps, hard_links, hard_seconds)
        if again.stats["links"] != st["links"]:
            raise RuntimeError(f"{oracle} eps={eps}: repeated solve gave other links")
        runs.append(float(again.stats["seconds"]))
        del again
    v = np.asarray(sol.measurement_primal, dtype=np.float64)
    rel = v / v_ref - 1.0
    point = {
        "oracle": oracle,
        "epsilon": eps,
        "links": int(st["links"]),
        "leaves": int(st["leaves"]),
        "elements": int(st["elements"]),
        "rays": int(st["rays"]),
        "memory_bytes": int(st["memory_bytes"]),
        "seconds": min(runs),
        "seconds_runs": runs,
        "measurement": v.tolist(),
        "relative_error_rgb": rel.tolist(),
        "error": float(np.max(np.abs(rel))),
        "duality_gap": float(sol.duality_gap),
        # The process's peak resident memory so far (it only grows: telling when it does).
        "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
        **info,
    }
    del sol
    return point


def sweep(
    scene: dualight.Scene,
    oracle: str,
    eps_grid: list[float],
    v_ref: np.ndarray,
    args: argparse.Namespace,
) -> list[dict[str, Any]]:
    points = []
    for eps in eps_grid:
        p = measure(
            scene,
            oracle,
            eps,
            v_ref,
            hard_links=args.hard_links,
            hard_seconds=4 * args.budget_seconds,
            repeat_below=args.repeat_below,
            repeats=args.repeats,
        )
        points.append(p)
        flag = "" if p["converged"] else f"  NOT CONVERGED ({p['aborted'] or 'max steps'})"
        log(
            f"  {oracle:>10} eps {eps:7.0e}: {p['links']:>10,d} links {p['leaves']:>8,d} leaves "
            f"{p['elements']:>8,d} elements {p['steps']:>2d} steps {p['seconds']:8.3f} s  "
            f"view error {100 * p['error']:.3f}%{flag}"
        )
        if p["seconds"] > args.budget_seconds or p["links"] > args.budget_links or p["aborted"]:
            log(f"  {oracle}: over the budget, sweep stops at eps {eps:.0e}")
            break
    return points


# Equal-error comparison -----------------------------------------------------------------------
def envelope(points: list[dict[str, Any]], cost: str) -> list[tuple[float, float]]:
    """(cost, error) of the points that lower the error below every cheaper point."""
    out: list[tuple[float, float]] = []
    for p in sorted(points, key=lambda p: (p[cost], p["error"])):
        if p["error"] > 0 and (not out or p["error"] < out[-1][1]):
            out.append((float(p[cost]), float(p["error"])))
    return out


def cost_at(env: list[tuple[float, float]], max_cost: float, error: float) -> tuple[float, str]:
    """Cost to reach ``error`` on an envelope: ``("=", interpolated)``, ``("<=", the cheapest
    point's cost)`` when even that point is better, ``(">", max_cost)`` when no point is."""
    if error >= env[0][1]:
        return env[0][0], "<=" if error > env[0][1] else "="
    if error < env[-1][1]:
        return max_cost, ">"
    for (c0, e0), (c1, e1) in zip(env, env[1:], strict=False):
        if e0 >= error >= e1:
            t = math.log(e0 / error) / math.log(e0 / e1)
            return math.exp(math.log(c0) + t * math.log(c1 / c0)), "="
    raise AssertionError("unreachable")


def ratio_at(
    bf: dict[str, Any], imp: dict[str, Any], cost: str, error: float
) -> dict[str, Any] | None:
    """BF / importance cost at one view error, with what kind of number it is."""
    c_imp, k_imp = cost_at(imp["env"][cost], imp["max"][cost], error)
    if k_imp == ">":
        return None  # importance does not reach this error either
    c_bf, k_bf = cost_at(bf["env"][cost], bf["max"][cost], error)
    if k_bf == "<=" and k_imp == "<=":
        return None  # both reach it at their coarsest point: nothing to compare
    if k_bf == ">":
        kind = ">"  # BF needs more than it spent; importance at most c_imp
    elif k_bf == "<=":
        kind = "<="
    elif k_imp == "<=":
        kind = ">="
    else:
        kind = "="
    return {"bf": c_bf, "importance": c_imp, "ratio": c_bf / c_imp, "kind": kind}


def describe(r: dict[str, Any] | None, cost: str, error: float) -> str:
    if r is None:
        return "-"
    if r["kind"] == ">":
        return (
            f"BF does not reach {100 * error:.3g}% within its budget: ratio > "
            f"{r['bf']:,.4g}/{r['importance']:,.4g} = {r['ratio']:.3g}"
        )
    return f"{r['kind']} {r['ratio']:.3g} ({r['bf']:,.4g} / {r['importance']:,.4g} {cost})"


def verdict(r: dict[str, Any] | None, threshold: float) -> bool | None:
    """True / False when the (bounded) ratio settles ``ratio >= threshold``, else None."""
    if r is None:
        return None
    x, kind = r["ratio"], r["kind"]
    if kind == "=":
        return x >= threshold
    if kind in (">", ">="):
        return True if x >= threshold else None
    return False if x < threshold else None  # "<="


def compare(name: str, scene_result: dict[str, Any]) -> dict[str, Any]:
    pts = scene_result["points"]
    curves = {}
    for oracle in ORACLES:
        ps = pts[oracle]
        curves[oracle] = {
            "env": {c: envelope(ps, c) for c in ("links", "seconds")},
            "max": {c: max(float(p[c]) for p in ps) for c in ("links", "seconds")},
            "best_error": min(p["error"] for p in ps),
        }
    bf, imp = curves["bf"], curves["importance"]
    noise = 3.0 * max(scene_result["reference"]["relative_std_error"])
    per_point = []
    for p in pts["importance"]:
        entry: dict[str, Any] = {"epsilon": p["epsilon"], "error": p["error"]}
        for c in ("links", "seconds"):
            entry[c] = ratio_at(bf, imp, c, p["error"])
        entry["noise_limited"] = p["error"] < noise
        per_point.append(entry)
    at_targets = []
    for e in TARGET_ERRORS:
        entry = {"error": e, "noise_limited": e < noise}
        entry.update({c: ratio_at(bf, imp, c, e) for c in ("links", "seconds")})
        if entry["links"] is None and entry["seconds"] is None:
            continue
        at_targets.append(entry)
    acceptance = None
    if name in ACCEPTANCE:
        need = ACCEPTANCE[name]
        rows = []
        for entry in at_targets:
            checks = {c: verdict(entry[c], t) for c, t in need.items()}
            known = [v for v in checks.values() if v is not None]
            if not known:
                ok = None
            elif False in known:
                ok = False
            else:
                ok = True if len(known) == len(checks) else None
            rows.append({"error": entry["error"], "checks": checks, "holds": ok})
        decided = [r for r in rows if r["holds"] is not None]
        acceptance = {
            "required_ratios": need,
            "at_errors": rows,
            "holds_at": [r["error"] for r in decided if r["holds"]],
            "fails_at": [r["error"] for r in decided if not r["holds"]],
            "holds_everywhere_decided": bool(decided) and all(r["holds"] for r in decided),
        }
    return {
        "envelopes": {o: curves[o]["env"] for o in ORACLES},
        "max_cost": {o: curves[o]["max"] for o in ORACLES},
        "best_error": {o: curves[o]["best_error"] for o in ORACLES},
        "noise_floor_3se": noise,
        "per_importance_point": per_point,
        "at_errors": at_targets,
        "acceptance": acceptance,
    }


def print_comparison(name: str, comp: dict[str, Any]) -> None:
    log(
        f"\n{LABELS[name]}: BF / importance at equal view error (noise floor 3 SE = "
        f"{100 * comp['noise_floor_3se']:.3f}%)"
    )
    for entry in comp["at_errors"]:
        tag = "  (noise-limited)" if entry["noise_limited"] else ""
        log(f"  error {100 * entry['error']:6.3f}%{tag}")
        for c in ("links", "seconds"):
            log(f"      {c:>7}: {describe(entry[c], c, entry['error'])}")
    log("  at each importance point:")
    for entry in comp["per_importance_point"]:
        parts = []
        for c in ("links", "seconds"):
            r = entry[c]
            parts.append(f"{c} " + ("-" if r is None else f"{r['kind']}{r['ratio']:.3g}"))
        log(
            f"    eps {entry['epsilon']:7.0e} error {100 * entry['error']:6.3f}%: "
            + ", ".join(parts)
        )
    acc = comp["acceptance"]
    if acc is not None:
        need = ", ".join(f"{c} >= {t:.3g}x" for c, t in acc["required_ratios"].items())
        log(f"  acceptance (BF / importance {need}):")
        for row in acc["at_errors"]:
            checks = ", ".join(f"{c} {v}" for c, v in row["checks"].items())
            log(f"    error {100 * row['error']:6.3f}%: {row['holds']}  ({checks})")
        log(
            f"    holds at {[f'{100 * e:.3g}%' for e in acc['holds_at']]}, "
            f"fails at {[f'{100 * e:.3g}%' for e in acc['fails_at']]}"
        )


# Plots ----------------------------------------------------------------------------------------
def plot_curves(results: dict[str, Any], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    names = list(results)
    fig, axes = plt.subplots(2, len(names), figsize=(4.2 * len(names), 7.5), squeeze=False)
    styles = {"bf": ("tab:blue", "s-"), "importance": ("tab:orange", "o-")}
    for col, name in enumerate(names):
        res = results[name]
        noise = res["comparison"]["noise_floor_3se"]
        for row, cost in enumerate(("links", "seconds")):
            ax = axes[row, col]
            for oracle in ORACLES:
                ps = res["points"][oracle]
                colour, style = styles[oracle]
                ax.loglog(
                    [p[cost] for p in ps],
                    [100 * p["error"] for p in ps],
                    style,
                    color=colour,
                    label=oracle,
                    ms=4,
                )
                for p in ps:
                    ax.annotate(
                        f"{p['epsilon']:.0e}",
                        (p[cost], 100 * p["error"]),
                        fontsize=6,
                        color=colour,
                        xytext=(3, 3),
                        textcoords="offset points",
                    )
                    if not p["converged"]:
                        ax.plot(p[cost], 100 * p["error"], "x", color="red", ms=8)
            ax.axhline(100 * noise, color="grey", ls=":", lw=1, label="3 SE of reference")
            ax.set_xlabel("links" if cost == "links" else "seconds (setup + steps)")
            ax.set_ylabel("view error (%)")
            ax.grid(True, which="both", alpha=0.3)
            ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
            ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
            if row == 0:
                ax.set_title(LABELS[name])
            if col == 0 and row == 0:
                ax.legend(fontsize=8)
    fig.suptitle("Hierarchical radiosity: view error against cost (BF vs importance oracle)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_pictures(
    scene_name: str, result: dict[str, Any], v_ref: np.ndarray, path: Path
) -> dict[str, Any]:
    """Both oracles at about equal view error: BF's best point within 10M links, and the
    importance point closest to its error (log scale)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    bf_pts = [p for p in result["points"]["bf"] if p["links"] <= 10_000_000] or result["points"][
        "bf"
    ][:1]
    p_bf = min(bf_pts, key=lambda p: p["error"])
    p_imp = min(
        result["points"]["importance"], key=lambda p: abs(math.log(p["error"] / p_bf["error"]))
    )
    scene = SCENES[scene_name]()
    cam = scene.camera.with_resolution(128, 128)
    modes = ("radiosity", "elements", "links", "superposition")
    fig, axes = plt.subplots(2, 4, figsize=(14, 7.6))
    chosen = {}
    for row, p in enumerate((p_bf, p_imp)):
        solver = HierarchicalSolver(scene, oracle=p["oracle"], epsilon=p["epsilon"])
        solver.solve(max_iter=100)
        sol = solver.solution()
        err = float(np.max(np.abs(np.asarray(sol.measurement_primal) / v_ref - 1)))
        chosen[p["oracle"]] = {"epsilon": p["epsilon"], "links": sol.stats["links"], "error": err}
        for col, mode in enumerate(modes):
            img = sol.render(camera=cam, mode=mode)
            pixels = img.tonemap() if mode == "radiosity" else np.clip(np.asarray(img), 0, 1)
            ax = axes[row, col]
            ax.imshow(pixels)
            ax.set_xticks([])
            ax.set_yticks([])
            if row == 0:
                ax.set_title(mode)
        axes[row, 0].set_ylabel(
            f"{p['oracle']}  eps {p['epsilon']:.0e}\n{sol.stats['links']:,d} links, "
            f"{sol.stats['leaves']:,d} leaves\nview error {100 * err:.2f}%",
            fontsize=9,
        )
        del solver, sol
    fig.suptitle(
        f"{LABELS[scene_name]}, 128x128: BF and importance oracles at about equal view error\n"
        "(links: log links per unit area, each picture scaled to its own range)"
    )
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return chosen


# Main -----------------------------------------------------------------------------------------
def git_commit() -> str:
    try:
        out = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"],
            cwd=Path(__file__).resolve().parent,
            capture_output=True,
            text=True,
            check=True,
        )
        return out.stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="short grids, 1024-spp references")
    parser.add_argument("--scenes", type=str, default=",".join(SCENES))
    parser.add_argument("--ref-spp", type=int, default=None, help="default 8192 (quick: 1024)")
    parser.add_argument("--ref-seed", type=int, default=3)
    parser.add_argument("--budget-seconds", type=float, default=None, help="60 (quick: 10)")
    parser.add_argument("--budget-links", type=int, default=None, help="5M (quick: 1M)")
    parser.add_argument("--hard-links", type=int, default=None, help="12M (quick: 3M)")
    parser.add_argument("--repeat-below", type=float, default=2.0)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--no-pictures", action="store_true")
    args = parser.parse_args()
    quick = args.quick
    args.ref_spp = args.ref_spp or (1024 if quick else 8192)
    args.budget_seconds = args.budget_seconds or (10.0 if quick else 60.0)
    args.budget_links = args.budget_links or (1_000_000 if quick else 5_000_000)
    args.hard_links = args.hard_links or (3_000_000 if quick else 12_000_000)
    if quick:
        args.repeats = 1
    eps_grids = QUICK_EPS if quick else FULL_EPS
    names = [s.strip() for s in args.scenes.split(",") if s.strip()]
    unknown = [n for n in names if n not in SCENES]
    if unknown:
        parser.error(f"unknown scene(s) {unknown}; choose from {list(SCENES)}")
    suffix = "_quick" if quick else ""

    t_start = time.perf_counter()
    load_start = os.getloadavg()
    log(f"load average at start: {load_start[0]:.2f} ({os.cpu_count()} cores)")
    results: dict[str, Any] = {}
    for name in names:
        scene = SCENES[name]()
        log(
            f"\n== {LABELS[name]}: {scene.triangle_count} triangles, camera "
            f"{scene.camera.width}x{scene.camera.height}"
        )
        ref = reference(name, scene, args.ref_spp, args.ref_seed)
        v_ref = np.asarray(ref["value"])
        log(
            f"  reference ({ref['spp']} spp{', cached' if ref['cached'] else ''}, "
            f"{ref['seconds']:.1f} s): v_ref = {np.round(v_ref, 5).tolist()}, std error "
            f"{np.round(ref['std_error'], 6).tolist()} "
            f"(relative {max(ref['relative_std_error']):.2e})"
        )
        points = {}
        for oracle in ORACLES:
            points[oracle] = sweep(scene, oracle, eps_grids[oracle], v_ref, args)
        result = {
            "label": LABELS[name],
            "triangles": scene.triangle_count,
            "reference": ref,
            "points": points,
            "load_average_after": os.getloadavg()[0],
        }
        result["comparison"] = compare(name, result)
        print_comparison(name, result["comparison"])
        results[name] = result

    pictures = None
    if not args.no_pictures and "rooms10" in results:
        log("\npictures of rooms(10) ...")
        pictures = plot_pictures(
            "rooms10",
            results["rooms10"],
            np.asarray(results["rooms10"]["reference"]["value"]),
            RESULTS / f"bench_hierarchical_pictures{suffix}.png",
        )
        log(f"  chosen: {pictures}")

    total = time.perf_counter() - t_start
    summary = {
        "benchmark": "bench_hierarchical",
        "quick": quick,
        "commit": git_commit(),
        "machine": {"cpu_count": os.cpu_count(), "platform": platform.platform()},
        "load_average_start": load_start[0],
        "load_average_end": os.getloadavg()[0],
        "args": vars(args),
        "solver_defaults": {"min_area": "1e-4 of the largest input triangle", "shadow_rays": 1},
        "eps_grids": eps_grids,
        "target_errors": TARGET_ERRORS,
        "acceptance_required": ACCEPTANCE,
        "view_error": "max over RGB of |measurement_primal / v_ref - 1|",
        "scenes": results,
        "pictures": pictures,
        "total_seconds": total,
    }
    RESULTS.mkdir(parents=True, exist_ok=True)
    out = RESULTS / f"bench_hierarchical{suffix}.json"
    out.write_text(json.dumps(summary, indent=2) + "\n")
    plot_curves(results, RESULTS / f"bench_hierarchical{suffix}.png")

    log("\nsummary (BF / importance at equal view error):")
    for name, res in results.items():
        acc = res["comparison"]["acceptance"]
        ref = res["reference"]
        log(
            f"  {LABELS[name]:>9}: v_ref {np.round(ref['value'], 4).tolist()} +- "
            f"{max(ref['relative_std_error']):.1e} rel; best error bf "
            f"{100 * res['comparison']['best_error']['bf']:.3f}%, importance "
            f"{100 * res['comparison']['best_error']['importance']:.3f}%"
        )
        if acc is not None:
            log(
                f"{'':13}acceptance holds at {[f'{100 * e:.3g}%' for e in acc['holds_at']]}, "
                f"fails at {[f'{100 * e:.3g}%' for e in acc['fails_at']]}"
            )
    log(
        f"\ntotal {total / 60:.1f} min; wrote {out}, {out.with_suffix('.png').name}"
        + ("" if pictures is None else f", bench_hierarchical_pictures{suffix}.png")
    )


if __name__ == "__main__":
    main()
