"""Radiosity on the Cornell box: cost of the form factors and of the four solvers against N.

For each patch count N (``--max-edges``; the defaults give about 1k, 2k, 5k, 9k and 21k
patches) the script measures:

* form factors (``_core.compute_form_factors``, 3 quadrature points and 4 shadow rays per
  point, all cores): wall time, shadow rays and rays/s, non-zeros of F, the memory F and F^T
  take (float32 value + uint32 column index each, so 16 bytes per non-zero, plus the row
  pointers) and the peak resident memory the computation added; then, separately, the
  Python reciprocity/closure checks that :func:`dualight.radiosity.form_factors` adds (skipped
  when their temporaries would not fit, see ``CHECK_BYTES_PER_NONZERO``);
* the reference solution of ``M B = E`` and of the dual ``M^T I = R``: the dense LU solver
  (``DirectSolver``; its factorisation is timed and shared by both sides) for N <= 12000 when
  its extrapolated factor time is within ``--direct-budget``, else Gauss-Seidel to a relative
  residual of 1e-12;
* each iterative solver (``jacobi``, ``gauss_seidel``, ``southwell``) stepped one ``.step()``
  at a time on both sides, recording per step the cumulative seconds (the ``.step()`` calls
  alone, best of ``--repeats`` runs per step) and the VIEW ERROR against the reference:

  - primal: the relative error of the measurement ``<R, B>`` (max over RGB of
    ``|m - m_ref| / m_ref``, R from :func:`dualight.radiosity.receiver`) and of the flat
    rendered image (``||img - img_ref||_2 / ||img_ref||_2`` over pixels and channels; the
    image of the camera's view at 64x64, 4x4 samples per pixel, each patch drawn with
    ``B / pi``, as ``Solution.render(smooth=False)``); the view error is the larger of the two;
  - dual: the relative error of the measurement ``<I, E>`` (the importance has no image);

  and the seconds until the view error is at most ``--target`` (1e-4). The direct solver's
  time to that error is its factor time plus one solve.

The growth with N is summarised by least-squares exponents of ``log seconds`` against
``log N`` (printed and stored).

Writes ``benchmarks/results/bench_radiosity.json`` and ``bench_radiosity.png``: (a) form-factor
seconds against N with the fitted exponent, (b) view error against seconds per solver at the
middle N, (c) seconds to ``--target`` view error against N per solver.

    python benchmarks/bench_radiosity.py            # N ~ 1k .. 21k (about 15-25 min on 2 cores)
    python benchmarks/bench_radiosity.py --quick    # N ~ 0.5k .. 1.1k, one repeat: a smoke run
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

import dualight
from dualight import _core
from dualight.radiosity import (
    DirectSolver,
    GaussSeidelSolver,
    JacobiSolver,
    PatchMesh,
    Solution,
    SouthwellSolver,
    form_factor_checks,
    receiver,
)

RESULTS = Path(__file__).resolve().parent / "results"
#: max_edge (mm) -> patches on the Cornell box: 90 -> 1126, 70 -> 1938, 40 -> 5282, 30 -> 9376,
#: 20 -> 20620.
DEFAULT_EDGES = "90,70,40,30,20"
QUICK_EDGES = "150,110,90"
DIRECT_LIMIT = 12000  # dualight's kMaxDirectPatches: a dense N x N double matrix per channel
#: F and F^T: a float32 value and a uint32 column index per non-zero, each.
BYTES_PER_NONZERO = 16
#: Peak temporaries of form_factor_checks per non-zero (measured: ~85 bytes at N = 4352).
CHECK_BYTES_PER_NONZERO = 96
ITERATIVE = {
    "jacobi": JacobiSolver,
    "gauss_seidel": GaussSeidelSolver,
    "southwell": SouthwellSolver,
}
PAGE = os.sysconf("SC_PAGE_SIZE")


# ----------------------------------------------------------------------------------------------
# measuring


def rss() -> int:
    """Resident memory of this process in bytes."""
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * PAGE


def with_peak_memory(work: Callable[[], Any]) -> tuple[Any, float, int, int]:
    """Run ``work`` (which must release the GIL) while a thread samples the resident memory.

    Returns (result, seconds, peak RSS added during the call, RSS added after it).
    """
    base = rss()
    peak = [base]
    done = threading.Event()

    def sample() -> None:
        while not done.is_set():
            peak[0] = max(peak[0], rss())
            done.wait(0.01)

    thread = threading.Thread(target=sample, daemon=True)
    thread.start()
    start = time.perf_counter()
    try:
        result = work()
    finally:
        seconds = time.perf_counter() - start
        done.set()
        thread.join()
    after = rss()
    return result, seconds, max(peak[0], after) - base, after - base


class FlatView:
    """The camera's flat-shaded view of per-patch radiosity as a linear map: image(x).

    The same hits as ``Solution.render(smooth=False, samples_per_axis, seed)``: the mean over
    each pixel's samples of ``x / pi`` of the patch seen from its front side (0 elsewhere).
    """

    def __init__(self, patches: PatchMesh, camera: dualight.Camera, samples_per_axis: int = 4):
        prim, _ = _core.trace_camera_hits(
            patches._compile(), camera._compile(), samples_per_axis=samples_per_axis, seed=0
        )
        h, w, s = prim.shape
        hit = prim >= 0
        idx = np.where(hit, prim, 0)
        front = (
            np.einsum(
                "...j,...j->...",
                patches.normals[idx],
                np.asarray(camera.origin) - patches.centroids[idx],
            )
            > 0
        )
        visible = hit & front
        pixel = np.broadcast_to(np.arange(h * w).reshape(h, w, 1), prim.shape)
        self.pixel = pixel[visible]
        self.patch = idx[visible]
        self.shape = (h, w)
        self.scale = 1.0 / (s * np.pi)

    def __call__(self, x: np.ndarray) -> np.ndarray:
        n = self.shape[0] * self.shape[1]
        out = np.stack(
            [np.bincount(self.pixel, weights=x[self.patch, c], minlength=n) for c in range(3)], -1
        )
        return (out * self.scale).reshape(*self.shape, 3)


def relative(a: np.ndarray, b: np.ndarray) -> float:
    """Largest relative difference over channels of two per-channel measurements."""
    return float(np.max(np.abs(a - b) / np.maximum(np.abs(b), 1e-300)))


def first_time_below(steps: list[dict[str, float]], key: str, target: float) -> float | None:
    for s in steps:
        if s[key] <= target:
            return s["seconds"]
    return None


def fit_exponent(ns: list[int], ys: list[float | None]) -> float | None:
    pts = [(n, y) for n, y in zip(ns, ys, strict=True) if y is not None and y > 0]
    if len(pts) < 2:
        return None
    x, y = np.log([p[0] for p in pts]), np.log([p[1] for p in pts])
    return float(np.polyfit(x, y, 1)[0])


# ----------------------------------------------------------------------------------------------
# one patch count


def stepped_run(
    make: Callable[[], Any],
    error: Callable[[np.ndarray], dict[str, float]],
    *,
    repeats: int,
    max_steps: int,
    stop: float,
) -> list[dict[str, float]]:
    """Step a fresh solver up to ``repeats`` times; per step the best time, errors, residual.

    Every run takes the same steps (the solvers are deterministic); the first stops once the
    view error is below ``stop``, the residual below 1e-13, or after ``max_steps``. Runs of
    more than 10 s are not repeated (their timing noise is small).
    """
    times: list[list[float]] = []
    records: list[dict[str, float]] = []
    for r in range(repeats):
        if times and sum(times[0]) > 10.0:
            break
        solver = make()
        run_times = []
        for k in range(max_steps if r == 0 else len(records)):
            t0 = time.perf_counter()
            step = solver.step()
            run_times.append(time.perf_counter() - t0)
            if r == 0:
                rec = {"step": k + 1, "residual": step.residual, **error(solver.solution)}
                records.append(rec)
                if (
                    rec["view_error"] <= stop
                    or step.residual <= 1e-13
                    or not np.isfinite(step.residual)
                ):
                    break
        times.append(run_times)
    best = np.min(np.array(times), axis=0)
    for rec, cum in zip(records, np.cumsum(best), strict=True):
        rec["seconds"] = float(cum)
    return records


def bench_n(
    scene: dualight.Scene,
    max_edge: float,
    args: argparse.Namespace,
    previous: dict[str, Any] | None,
) -> dict[str, Any]:
    cam = scene.camera
    assert cam is not None
    out: dict[str, Any] = {"max_edge": max_edge, "notes": []}
    patches = PatchMesh(scene, max_edge=max_edge)
    n = len(patches)
    out["patches"] = n
    print(f"\n=== max_edge {max_edge:g} mm: N = {n} patches", flush=True)

    # Form factors ------------------------------------------------------------------------
    if previous is not None:
        density = previous["nonzeros"] / previous["patches"] ** 2
        est = density * n * n * BYTES_PER_NONZERO * 1.5  # F, F^T and the rows being built
        if est > args.memory_budget * 2**30:
            out["skipped"] = (
                f"form factors would need about {est / 2**30:.1f} GiB "
                f"(> {args.memory_budget:g} GiB budget)"
            )
            print("  skipped:", out["skipped"])
            return out
    scene_c = patches._compile()
    options = _core.FormFactorOptions(quadrature=3, shadow_rays=4, seed=0, threads=0)
    (F, ff), wall, peak, kept = with_peak_memory(
        lambda: _core.compute_form_factors(scene_c, options, None)
    )
    ff = dict(ff)
    nnz = int(F.nonzeros)
    out.update(
        ff_seconds=wall,
        ff_core_seconds=ff["seconds"],
        rays=int(ff["rays"]),
        rays_per_second=ff["rays"] / ff["seconds"],
        pairs_tested=int(ff["pairs_tested"]),
        pairs_facing=int(ff["pairs_facing"]),
        nonzeros=nnz,
        nonzeros_per_n2=nnz / n**2,
        memory_bytes=nnz * BYTES_PER_NONZERO + 2 * 8 * (n + 1),
        rss_peak_added_bytes=peak,
        rss_kept_bytes=kept,
    )
    print(
        f"  form factors {wall:.2f} s, {ff['rays'] / 1e6:.1f} M rays, "
        f"{out['rays_per_second'] / 1e6:.2f} M rays/s, nnz {nnz / 1e6:.2f} M "
        f"({out['nonzeros_per_n2']:.3f} N^2), F+F^T {out['memory_bytes'] / 2**30:.2f} GiB, "
        f"peak RSS +{peak / 2**30:.2f} GiB, kept +{kept / 2**30:.2f} GiB",
        flush=True,
    )
    if nnz * CHECK_BYTES_PER_NONZERO <= args.memory_budget * 2**30:
        t0 = time.perf_counter()
        checks = form_factor_checks(F, patches.areas)
        out["checks_seconds"] = time.perf_counter() - t0
        out["checks"] = checks
        print(
            f"  form_factor_checks {out['checks_seconds']:.2f} s "
            f"({100 * out['checks_seconds'] / wall:.0f}% of the form factors): row sums "
            f"{checks['row_sum_min']:.3f}..{checks['row_sum_max']:.4f}, reciprocity mean "
            f"{checks['reciprocity_mean_relative_error']:.2e}",
            flush=True,
        )
    else:
        out["notes"].append(
            f"form_factor_checks skipped: its temporaries need about "
            f"{nnz * CHECK_BYTES_PER_NONZERO / 2**30:.0f} GiB"
        )
        print("  " + out["notes"][-1])

    system = _core.RadiositySystem(F, patches.reflectance, patches.areas)
    E = patches.emission
    t0 = time.perf_counter()
    R = receiver(patches, cam)
    out["receiver_seconds"] = time.perf_counter() - t0
    R3 = np.ascontiguousarray(np.repeat(R[:, None], 3, axis=1))
    view = FlatView(patches, cam)

    # Reference -----------------------------------------------------------------------------
    direct_ok = n <= DIRECT_LIMIT
    if direct_ok and previous is not None and previous.get("direct"):
        est = previous["direct"]["factor_seconds"] * (n / previous["patches"]) ** 3
        if est > args.direct_budget:
            direct_ok = False
            out["notes"].append(f"direct skipped: factorisation estimated at {est:.0f} s")
    if direct_ok:
        (primal, wall_f, peak_d, _) = with_peak_memory(lambda: DirectSolver(system, E))
        t0 = time.perf_counter()
        primal.step()
        primal_solve = time.perf_counter() - t0
        dual = DirectSolver(system, R3, dual=True, factors=primal.factors)
        t0 = time.perf_counter()
        dual.step()
        dual_solve = time.perf_counter() - t0
        B_ref, I_ref = primal.solution, dual.solution
        out["direct"] = {
            "factor_seconds": primal.factors.factor_seconds,
            "construct_seconds": wall_f,
            "primal_solve_seconds": primal_solve,
            "dual_solve_seconds": dual_solve,
            "primal_residual": primal.residual,
            "dual_residual": dual.residual,
            "rss_peak_added_bytes": peak_d,
            "dense_bytes": 3 * n * n * 8,
        }
        out["reference"] = "direct"
        print(
            f"  direct: factor {primal.factors.factor_seconds:.2f} s (3 channels), solve "
            f"{primal_solve * 1e3:.1f} ms primal / {dual_solve * 1e3:.1f} ms dual, "
            f"peak RSS +{peak_d / 2**30:.2f} GiB",
            flush=True,
        )
        del primal, dual
    else:
        refs = []
        for rhs, is_dual in ((E, False), (R3, True)):
            s = GaussSeidelSolver(system, rhs, dual=is_dual)
            s.solve(tol=1e-12, max_iter=2000)
            refs.append(np.array(s.solution))
        B_ref, I_ref = refs
        out["reference"] = "gauss_seidel tol 1e-12"
        print("  reference: Gauss-Seidel to a relative residual of 1e-12", flush=True)
    m_ref = np.sum(R3 * B_ref, axis=0)
    d_ref = np.sum(I_ref * E, axis=0)
    img_ref = view(B_ref)
    img_norm = float(np.linalg.norm(img_ref))
    out["measurement"] = m_ref.tolist()
    out["duality_gap"] = relative(d_ref, m_ref)
    out["image_mean_vs_measurement"] = relative(img_ref.mean(axis=(0, 1)), m_ref)
    if previous is None:  # the view operator draws what Solution.render(smooth=False) draws
        sol = Solution(patches, B_ref, I_ref, E, R3, F, cam, out["reference"])
        drawn = np.asarray(sol.render(mode="radiosity", smooth=False, samples_per_axis=4))
        out["flat_view_vs_render"] = float(np.abs(drawn - img_ref).max() / np.abs(img_ref).max())
        assert out["flat_view_vs_render"] < 1e-6, out["flat_view_vs_render"]

    def primal_error(x: np.ndarray) -> dict[str, float]:
        me = relative(np.sum(R3 * x, axis=0), m_ref)
        ie = float(np.linalg.norm(view(x) - img_ref)) / img_norm
        return {"measurement_error": me, "image_error": ie, "view_error": max(me, ie)}

    def dual_error(x: np.ndarray) -> dict[str, float]:
        me = relative(np.sum(x * E, axis=0), m_ref)
        return {"measurement_error": me, "view_error": me}

    # Iterative solvers -----------------------------------------------------------------------
    out["solvers"] = {}
    for name, cls in ITERATIVE.items():
        entry = {}
        for side, rhs, err in (("primal", E, primal_error), ("dual", R3, dual_error)):
            is_dual = side == "dual"
            steps = stepped_run(
                lambda cls=cls, rhs=rhs, is_dual=is_dual: cls(system, rhs, dual=is_dual),
                err,
                repeats=args.repeats,
                max_steps=args.max_steps,
                stop=args.stop,
            )
            t_target = first_time_below(steps, "view_error", args.target)
            entry[side] = {
                "steps": steps,
                "seconds_per_step": steps[-1]["seconds"] / len(steps),
                "seconds_to_target": t_target,
                "steps_to_target": next(
                    (s["step"] for s in steps if s["view_error"] <= args.target), None
                ),
                "final_view_error": steps[-1]["view_error"],
            }
            if side == "primal":
                entry[side]["seconds_to_target_measurement_only"] = first_time_below(
                    steps, "measurement_error", args.target
                )
        out["solvers"][name] = entry
        p, d = entry["primal"], entry["dual"]

        def fmt(t: float | None) -> str:
            return f"{t:.3f} s" if t is not None else "not reached"

        print(
            f"  {name:>12}: {p['seconds_per_step'] * 1e3:7.1f} ms/step; to view error "
            f"{args.target:g}: primal {fmt(p['seconds_to_target'])} "
            f"({p['steps_to_target']} steps), dual {fmt(d['seconds_to_target'])} "
            f"({d['steps_to_target']} steps)",
            flush=True,
        )
    if "direct" in out:
        d = out["direct"]
        d["seconds_to_target_primal"] = d["factor_seconds"] + d["primal_solve_seconds"]
        d["seconds_to_target_dual"] = d["factor_seconds"] + d["dual_solve_seconds"]
    return out


# ----------------------------------------------------------------------------------------------


def plot(summary: dict[str, Any], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    runs = [r for r in summary["runs"] if "nonzeros" in r]
    ns = [r["patches"] for r in runs]
    fits = summary["fits"]
    colours = {"direct": "k", "jacobi": "C0", "gauss_seidel": "C1", "southwell": "C2"}
    fig, axes = plt.subplots(1, 3, figsize=(17, 5))

    ax = axes[0]
    ax.loglog(ns, [r["ff_seconds"] for r in runs], "o-", label="form factors")
    if fits.get("ff_seconds") is not None:
        c = np.exp(
            np.mean(np.log([r["ff_seconds"] for r in runs]) - fits["ff_seconds"] * np.log(ns))
        )
        ax.loglog(
            ns,
            c * np.array(ns, float) ** fits["ff_seconds"],
            "k:",
            label=f"fit: N^{fits['ff_seconds']:.2f}",
        )
    checks = [(r["patches"], r["checks_seconds"]) for r in runs if "checks_seconds" in r]
    if checks:
        ax.loglog(*zip(*checks, strict=True), "s--", label="+ form_factor_checks (Python)")
    ax.set_xlabel("patches N")
    ax.set_ylabel("seconds")
    ax.set_title("(a) form factors")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()

    ax = axes[1]
    mid = runs[len(runs) // 2]
    for name, entry in mid["solvers"].items():
        p, d = entry["primal"]["steps"], entry["dual"]["steps"]
        ax.loglog(
            [s["seconds"] for s in p],
            [max(s["view_error"], 1e-16) for s in p],
            "-",
            color=colours[name],
            label=f"{name} B (view)",
        )
        ax.loglog(
            [s["seconds"] for s in d],
            [max(s["view_error"], 1e-16) for s in d],
            "--",
            color=colours[name],
            label=f"{name} I (<I,E>)",
        )
    if "direct" in mid:
        ax.axvline(
            mid["direct"]["seconds_to_target_primal"],
            color="k",
            ls="-.",
            label="direct: factor + solve",
        )
    ax.axhline(summary["target"], color="grey", lw=0.8)
    ax.set_xlabel("seconds (cumulative .step() time)")
    ax.set_ylabel("relative view error")
    ax.set_title(f"(b) convergence at N = {mid['patches']}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)

    ax = axes[2]
    for name in ITERATIVE:
        for side, style in (("primal", "o-"), ("dual", "s--")):
            pts = [(r["patches"], r["solvers"][name][side]["seconds_to_target"]) for r in runs]
            pts = [p for p in pts if p[1] is not None]
            e = fits.get(f"{name}_{side}")
            label = f"{name} {'B' if side == 'primal' else 'I'}" + (f" N^{e:.2f}" if e else "")
            if pts:
                ax.loglog(*zip(*pts, strict=True), style, color=colours[name], label=label)
    pts = [(r["patches"], r["direct"]["seconds_to_target_primal"]) for r in runs if "direct" in r]
    if pts:
        e = fits.get("direct_primal")
        ax.loglog(
            *zip(*pts, strict=True), "^-", color="k", label="direct" + (f" N^{e:.2f}" if e else "")
        )
    ax.set_xlabel("patches N")
    ax.set_ylabel(f"seconds to view error {summary['target']:g}")
    ax.set_title("(c) solver time to target error")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--max-edges", default=DEFAULT_EDGES, help="comma-separated, mm")
    parser.add_argument("--quick", action="store_true", help=f"max edges {QUICK_EDGES}, 1 repeat")
    parser.add_argument("--repeats", type=int, default=3, help="timed runs per solver (best)")
    parser.add_argument("--target", type=float, default=1e-4, help="view error to time")
    parser.add_argument("--stop", type=float, default=1e-9, help="view error to stop stepping")
    parser.add_argument("--max-steps", type=int, default=300)
    parser.add_argument(
        "--direct-budget",
        type=float,
        default=900.0,
        help="skip the direct solver if its factorisation would take longer (s)",
    )
    parser.add_argument("--memory-budget", type=float, default=8.0, help="GiB")
    parser.add_argument("--out", type=Path, default=RESULTS)
    args = parser.parse_args()
    if args.quick:
        args.max_edges, args.repeats = QUICK_EDGES, 1
    edges = [float(e) for e in args.max_edges.split(",")]
    scene = dualight.scenes.cornell_box(resolution=(64, 64))

    load_before = os.getloadavg()
    start = time.perf_counter()
    runs: list[dict[str, Any]] = []
    previous = None
    for e in edges:
        r = bench_n(scene, e, args, previous)
        runs.append(r)
        if "nonzeros" in r:
            previous = r
    total = time.perf_counter() - start

    done = [r for r in runs if "nonzeros" in r]
    ns = [r["patches"] for r in done]
    fits: dict[str, float | None] = {
        "ff_seconds": fit_exponent(ns, [r["ff_seconds"] for r in done]),
        "nonzeros": fit_exponent(ns, [r["nonzeros"] for r in done]),
        "rays": fit_exponent(ns, [r["rays"] for r in done]),
        "direct_factor": fit_exponent(
            [r["patches"] for r in done if "direct" in r],
            [r["direct"]["factor_seconds"] for r in done if "direct" in r],
        ),
    }
    fits["direct_primal"] = fits["direct_factor"]
    for name in ITERATIVE:
        for side in ("primal", "dual"):
            fits[f"{name}_{side}"] = fit_exponent(
                ns, [r["solvers"][name][side]["seconds_to_target"] for r in done]
            )
            fits[f"{name}_{side}_seconds_per_step"] = fit_exponent(
                ns, [r["solvers"][name][side]["seconds_per_step"] for r in done]
            )
    summary = {
        "scene": "cornell_box(resolution=(64, 64))",
        "form_factor_options": {"quadrature": 3, "shadow_rays": 4, "seed": 0},
        "view": "64x64 camera view, 4x4 samples per pixel, flat patches",
        "target": args.target,
        "repeats": args.repeats,
        "machine": {"cpu_count": os.cpu_count(), "platform": platform.platform()},
        "load_average_before_after": [list(load_before), list(os.getloadavg())],
        "total_seconds": total,
        "runs": runs,
        "fits": fits,
        "fit_meaning": "exponent a of seconds (or count) ~ N^a, least squares in log-log",
    }
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "bench_radiosity.json").write_text(json.dumps(summary, indent=2) + "\n")
    plot(summary, args.out / "bench_radiosity.png")

    print(f"\nsummary ({total:.0f} s in all)")
    print(
        f"{'N':>6} {'FF s':>8} {'Mrays/s':>8} {'nnz M':>7} {'F+Ft GiB':>8} {'direct s':>9} "
        + " ".join(f"{n + ' B/I s':>22}" for n in ITERATIVE)
    )
    for r in runs:
        if "nonzeros" not in r:
            print(f"{r['patches']:6d} skipped: {r['skipped']}")
            continue
        d = f"{r['direct']['seconds_to_target_primal']:9.2f}" if "direct" in r else f"{'-':>9}"

        def t(x: float | None) -> str:
            return f"{x:.3f}" if x is not None else "-"

        sv = " ".join(
            f"{t(r['solvers'][n]['primal']['seconds_to_target']):>10} / "
            f"{t(r['solvers'][n]['dual']['seconds_to_target']):<9}"
            for n in ITERATIVE
        )
        print(
            f"{r['patches']:6d} {r['ff_seconds']:8.2f} {r['rays_per_second'] / 1e6:8.2f} "
            f"{r['nonzeros'] / 1e6:7.2f} {r['memory_bytes'] / 2**30:8.2f} {d} {sv}"
        )
    print("growth with N (seconds ~ N^a):")
    for k, v in fits.items():
        if v is not None and not k.endswith("seconds_per_step"):
            print(f"  {k:>22}: a = {v:.2f}")
    print(f"wrote {args.out / 'bench_radiosity.json'} and bench_radiosity.png")


if __name__ == "__main__":
    main()
