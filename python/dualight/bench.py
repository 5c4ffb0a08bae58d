"""``python -m dualight bench``: error against run time for every method on the scene set.

Every Monte Carlo method (``path``, ``light``, ``bdpt``, ``pssmlt``, ``mmlt``, ``mlt``) renders
every scene of the set (the Cornell box, its caustic variant, Veach's door, the furnace and a
building of rooms; 64x64, ``max_depth`` 8) for a series of time budgets (``time_limit``), and
the radiosity solvers (Gauss-Seidel on uniform meshes of three sizes, importance-driven
hierarchical radiosity at three thresholds) solve the scenes that are all diffuse, their view
drawn with smooth shading. Each result is compared with the scene's reference:

* the Mitsuba 3 references that the tests use, shipped with the package
  (``dualight/data/references``, :data:`REFERENCE_DIR`: mean and variance of the mean), or one
  rendered by Mitsuba on first use and cached (``--cache``; the rooms); without Mitsuba those
  scenes are skipped, and said so in one line;
* the furnace's analytic radiance ``Le / (1 - rho)``.

What an install lacks is said in one line each, and the rest runs: without colour-science no
Delta E (``null`` in the JSON), without matplotlib no ``bench.png`` (``pip install
"dualight[bench]"`` has both, and Mitsuba).

Errors: relMSE (pbrt-v4's ``(x - y)^2 / (y + 0.01)^2``, mean over pixels and channels) minus
the reference's own noise term (``var / (y + 0.01)^2``), and the mean CIE Delta E 2000 of the
two images tone-mapped alike (``dualight.metrics.delta_e2000``). Efficiency is
``1 / (relMSE * seconds)``; at the longest budget each method's efficiency is divided by
BDPT's on the same scene (the equal-time table).

Writes to ``--out`` (default ``out/bench``): ``bench.json`` (every run: method, scene, budget,
seconds, relMSE, Delta E, spp or mutations, stats), ``bench.png`` (log relMSE against log
seconds, one panel per scene, one line per method) and ``bench.md`` (the equal-time table).

    python -m dualight bench            # budgets 0.5, 1, 2, 4 s (about 15 minutes on 2 cores)
    python -m dualight bench --quick    # budgets 0.25, 0.5, 1 s: under 5 minutes
"""

from __future__ import annotations

import argparse
import functools
import importlib.util
import json
import os
import platform
import sys
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from dualight import metrics, scenes
from dualight._cli import add_subcommand
from dualight.image import Image
from dualight.methods import METHODS
from dualight.plotting import curves_by, save_relmse_against_time
from dualight.render import render
from dualight.scene import Scene

MC_METHODS = METHODS  # every Monte Carlo method of render
MAX_DEPTH = 8
EPS = 1e-2  # relMSE's offset (pbrt-v4)
ROOMS_REFERENCE_SPP = 8192
EXACT = 1e-10  # relMSE at float rounding: no efficiency ratio is meaningful
REFERENCE_DIR = Path(__file__).resolve().parent / "data" / "references"
"""The Mitsuba 3 references shipped with the package: ``NAME_mean.exr`` and ``NAME_var.exr``
(variance of the mean); how they were made is in the README.md beside them."""
INSTALL_HINT = 'pip install "dualight[bench]"'


@dataclass(frozen=True)
class Reference:
    """The image a method is compared with: mean, variance of the mean, and where it came from."""

    mean: np.ndarray
    variance: np.ndarray
    source: str


@dataclass(frozen=True)
class BenchScene:
    build: Callable[[], Scene]
    reference: str  # "test:NAME" (REFERENCE_DIR), "mitsuba" (rendered, cached) or "furnace"


SCENE_SET: dict[str, BenchScene] = {
    "cornell": BenchScene(lambda: scenes.cornell_box(resolution=(64, 64)), "test:cornell_64"),
    "caustics": BenchScene(
        lambda: scenes.cornell_box(resolution=(64, 64), variant="caustics"), "test:caustics_64"
    ),
    "door": BenchScene(lambda: scenes.door_ajar(resolution=(64, 64)), "test:door_64"),
    "furnace": BenchScene(lambda: scenes.furnace(0.5, 1.0, resolution=(64, 64)), "furnace"),
    "rooms": BenchScene(lambda: scenes.rooms(4, resolution=(64, 64)), "mitsuba"),
}

# Radiosity "budgets": coarse to fine. Gauss-Seidel on uniform patches (max_edge as a share of
# the scene's extent); hierarchical radiosity by its refinement threshold.
RADIOSITY_LEVELS: dict[str, list[dict[str, float]]] = {
    "radiosity_gs": [{"edge": 0.4}, {"edge": 0.2}, {"edge": 0.1}],
    "radiosity_hier": [{"epsilon": 1e-2}, {"epsilon": 3e-3}, {"epsilon": 1e-3}],
}


def _importable(module: str) -> bool:
    """Whether ``module`` can be imported (without importing it: Mitsuba takes seconds)."""
    if module in sys.modules:
        return sys.modules[module] is not None
    return importlib.util.find_spec(module) is not None


def load_reference(name: str, spec: str, scene: Scene, cache: Path) -> Reference | None:
    """The scene's reference, or None (with the reason printed in one line) when it cannot be
    had.

    ``spec`` is ``"furnace"`` (the analytic radiance), ``"test:KEY"`` (the shipped Mitsuba
    reference ``KEY`` in :data:`REFERENCE_DIR`) or ``"mitsuba"`` (rendered by Mitsuba once,
    ``ROOMS_REFERENCE_SPP`` samples per pixel, and kept in ``cache``).
    """
    if spec == "furnace":
        mean = np.full((64, 64, 3), scenes.furnace_radiance(0.5, 1.0), dtype=np.float32)
        return Reference(mean, np.zeros_like(mean), "analytic Le / (1 - rho)")
    if spec.startswith("test:"):
        key = spec[5:]
        mean_path, var_path = REFERENCE_DIR / f"{key}_mean.exr", REFERENCE_DIR / f"{key}_var.exr"
        if not (mean_path.exists() and var_path.exists()):
            print(f"  {name}: reference {key} not in {REFERENCE_DIR} (reinstall dualight): skipped")
            return None
        mean = np.asarray(Image.load(mean_path))
        var = np.asarray(Image.load(var_path))
        return Reference(mean, var, f"Mitsuba 3, dualight/data/references/{key}")
    if spec != "mitsuba":
        raise ValueError(f"unknown reference {spec!r}: 'furnace', 'test:KEY' or 'mitsuba'")
    return _mitsuba_reference(name, scene, cache)


def _mitsuba_reference(name: str, scene: Scene, cache: Path) -> Reference | None:
    cam = scene.camera
    assert cam is not None
    key = f"{name}_{cam.width}x{cam.height}_d{MAX_DEPTH}_spp{ROOMS_REFERENCE_SPP}"
    mean_path, var_path = cache / f"{key}_mean.exr", cache / f"{key}_var.exr"
    if not (mean_path.exists() and var_path.exists()):
        if not _importable("mitsuba"):
            print(
                f"  {name}: its reference is rendered once by Mitsuba 3, which is not installed "
                f"({INSTALL_HINT}): skipped"
            )
            return None
        try:
            from dualight import mitsuba as dmi

            print(f"  {name}: rendering a Mitsuba reference ({ROOMS_REFERENCE_SPP} spp), once")
            start = time.perf_counter()
            mean, var = dmi.reference(scene, ROOMS_REFERENCE_SPP, seed=0, max_depth=MAX_DEPTH)
            print(f"    took {time.perf_counter() - start:.0f} s; cached in {cache}")
        except Exception as err:  # noqa: BLE001 - any failure of the optional peer
            print(f"  {name}: no Mitsuba reference ({type(err).__name__}: {err}): skipped")
            return None
        cache.mkdir(parents=True, exist_ok=True)
        Image(mean).save(mean_path)
        Image(var).save(var_path)
    mean = np.asarray(Image.load(mean_path))
    var = np.asarray(Image.load(var_path))
    return Reference(mean, var, f"Mitsuba 3, {ROOMS_REFERENCE_SPP} spp (cached)")


def errors(image: np.ndarray, ref: Reference) -> dict[str, float | None]:
    """relMSE (minus the reference's noise term) and mean Delta E 2000 against ``ref``; Delta
    E is None without colour-science."""
    raw = metrics.relmse(image, ref.mean, EPS)
    floor = float(np.mean(ref.variance / (ref.mean + EPS) ** 2))
    de = metrics.delta_e2000(image, ref.mean)["mean"] if _importable("colour") else None
    return {
        "relmse": max(raw - floor, 1e-12),
        "relmse_raw": raw,
        "reference_floor": floor,
        "delta_e2000": de,
    }


def _mc_run(scene: Scene, method: str, budget: float, seed: int) -> tuple[np.ndarray, float, dict]:
    start = time.perf_counter()
    image = render(
        scene, method, spp=None, time_limit=budget, max_depth=MAX_DEPTH, seed=seed, progress=False
    )
    return np.asarray(image), time.perf_counter() - start, dict(image.stats)


def _radiosity_run(
    scene: Scene, label: str, level: dict[str, float]
) -> tuple[np.ndarray, float, dict]:
    from dualight import radiosity

    lo, hi = scene.bounds()
    extent = float(np.max(np.asarray(hi) - np.asarray(lo)))
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if label == "radiosity_gs":
            solution = radiosity.solve(scene, "gauss_seidel", max_edge=level["edge"] * extent)
        else:
            solution = radiosity.solve(scene, "hierarchical", epsilon=level["epsilon"])
        image = solution.render(smooth=True)
    seconds = time.perf_counter() - start
    stats = {k: v for k, v in solution.stats.items() if isinstance(v, bool | int | float | str)}
    return np.asarray(image), seconds, stats


def _count(method: str, stats: dict[str, Any], pixels: int) -> str:
    if method.startswith("radiosity"):
        n = stats.get("patches", stats.get("elements", stats.get("leaves")))
        return f"{n} patches" if n is not None else ""
    if "mutations" in stats:
        return f"{stats['mutations'] / pixels:.0f} mutations/px"
    return f"{stats.get('spp', 0)} spp"


def _jobs(
    scene: Scene, method: str, budgets: list[float]
) -> list[tuple[dict[str, float], Callable[[], tuple[np.ndarray, float, dict]]]]:
    """The runs of ``method`` on ``scene``: (its level or budget, the job)."""
    if method in RADIOSITY_LEVELS:
        return [
            (level, functools.partial(_radiosity_run, scene, method, level))
            for level in RADIOSITY_LEVELS[method]
        ]
    return [
        ({"budget": b}, functools.partial(_mc_run, scene, method, b, 100 + i))
        for i, b in enumerate(budgets)
    ]


def _bench_scene(name: str, methods: list[str], budgets: list[float], cache: Path) -> dict:
    """Every method on scene ``name`` of the set: its summary entry."""
    spec = SCENE_SET[name]
    scene = spec.build()
    print(f"{name}:", flush=True)
    ref = load_reference(name, spec.reference, scene, cache)
    if ref is None:
        return {"skipped": "no reference"}
    render(scene, "path", spp=1, max_depth=1, progress=False)  # BVH built outside the timings
    cam = scene.camera
    assert cam is not None
    runs: list[dict[str, Any]] = []
    skipped: dict[str, str] = {}
    for method in methods:
        if method in RADIOSITY_LEVELS and scene.has_specular:
            skipped[method] = "specular surfaces: radiosity needs an all-diffuse scene"
            print(f"  {method:>14} skipped: {skipped[method]}", flush=True)
            continue
        for level, job in _jobs(scene, method, budgets):
            image, seconds, stats = job()
            r = {"method": method, **level, "seconds": seconds, **errors(image, ref)}
            r["efficiency"] = 1.0 / (r["relmse"] * seconds)
            r["count"] = _count(method, stats, cam.width * cam.height)
            r["stats"] = {
                k: v
                for k, v in stats.items()
                if v is None or isinstance(v, bool | int | float | str)
            }
            runs.append(r)
            de = "-" if r["delta_e2000"] is None else f"{r['delta_e2000']:.2f}"
            print(
                f"  {method:>14} {seconds:6.2f} s {r['count']:>20} relMSE {r['relmse']:.3e} "
                f"dE2000 {de}",
                flush=True,
            )
    return {"reference": ref.source, "runs": runs, "skipped": skipped}


def _say_what_is_missing() -> None:
    """One line for each optional package whose part of the bench cannot run here."""
    if not _importable("colour"):
        print(f"Delta E 2000 needs colour-science ({INSTALL_HINT}): not computed")
    if not _importable("matplotlib"):
        print(f"bench.png needs matplotlib ({INSTALL_HINT}): not written")


def run(args: argparse.Namespace) -> int:
    """Run ``python -m dualight bench`` with parsed ``args``; returns the exit code."""
    budgets = [float(b) for b in args.budgets.split(",")]
    names = [s for s in args.scenes.split(",") if s]
    methods = [m for m in args.methods.split(",") if m]
    unknown = set(names) - set(SCENE_SET) | set(methods) - set(MC_METHODS) - set(RADIOSITY_LEVELS)
    if unknown:
        raise SystemExit(f"unknown scene or method: {', '.join(sorted(unknown))}")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    summary: dict[str, Any] = {
        "environment": {
            "cpu_count": os.cpu_count(),
            "platform": platform.platform(),
            "python": platform.python_version(),
            "load_average_at_start": list(os.getloadavg()),
        },
        "budgets_seconds": budgets,
        "max_depth": MAX_DEPTH,
        "scenes": {},
    }
    _say_what_is_missing()
    for name in names:
        summary["scenes"][name] = _bench_scene(name, methods, budgets, Path(args.cache))
    summary["equal_time"] = equal_time_table(summary, max(budgets))
    summary["environment"]["load_average_at_end"] = list(os.getloadavg())
    summary["environment"]["wall_seconds"] = time.perf_counter() - start
    (out / "bench.json").write_text(json.dumps(summary, indent=1) + "\n")
    table = markdown_table(summary)
    (out / "bench.md").write_text(table)
    written = "bench.json and bench.md"
    if _importable("matplotlib"):
        plot(summary, out / "bench.png")
        written = "bench.json, bench.md and bench.png"
    print("\n" + table)
    print(f"wrote {written} to {out} in {time.perf_counter() - start:.0f} s")
    return 0


def equal_time_table(summary: dict[str, Any], budget: float) -> dict[str, dict[str, float]]:
    """Per scene: each method's efficiency at ``budget`` over BDPT's (radiosity: its finest
    level, whatever its time; its bias shows in relMSE, which time does not reduce)."""
    table: dict[str, dict[str, float]] = {}
    for name, entry in summary["scenes"].items():
        runs = entry.get("runs", [])
        top: dict[str, dict[str, Any]] = {}
        for r in runs:
            if r.get("budget") == budget or (r["method"] in RADIOSITY_LEVELS):
                top[r["method"]] = r  # radiosity: the last (finest) level
        if "bdpt" not in top:
            continue
        base = top["bdpt"]["efficiency"]
        table[name] = {m: r["efficiency"] / base for m, r in top.items()}
    return table


def markdown_table(summary: dict[str, Any]) -> str:
    """The equal-time efficiency table (relative to BDPT) as markdown."""
    table = summary["equal_time"]
    names = list(table)
    methods = [m for m in (*MC_METHODS, *RADIOSITY_LEVELS) if any(m in table[n] for n in names)]
    budget = max(summary["budgets_seconds"])
    lines = [
        f"Efficiency 1 / (relMSE x seconds) relative to BDPT at {budget:g} s "
        "(> 1: faster to equal error; radiosity: its finest level; exact: relMSE under "
        f"{EXACT:g}, e.g. radiosity in the furnace)",
        "",
        "| method | " + " | ".join(names) + " |",
        "|---|" + "---|" * len(names),
    ]
    exact = {
        (n, r["method"])
        for n in names
        for r in summary["scenes"][n]["runs"]
        if r["relmse_raw"] <= EXACT
    }
    for m in methods:
        cells = [
            "exact" if (n, m) in exact else f"{table[n][m]:.2f}" if m in table[n] else "-"
            for n in names
        ]
        lines.append(f"| {m} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def plot(summary: dict[str, Any], path: Path) -> None:
    """Write log relMSE against log seconds, one panel per scene, to ``path``."""
    methods = [*MC_METHODS, *RADIOSITY_LEVELS]
    panels = {
        f"{name} 64x64": curves_by(entry["runs"], "method")
        for name, entry in summary["scenes"].items()
        if entry.get("runs")
    }
    save_relmse_against_time(
        panels,
        path,
        panel_size=(4.5, 4),
        dpi=100,
        xlabel="seconds",
        colours={m: f"C{i}" for i, m in enumerate(methods)},
        legend_size=7,
    )


def add_parser(sub: Any) -> None:
    """Add the ``bench`` subcommand to the ``python -m dualight`` argument parser."""
    p = add_subcommand(sub, "bench", "error against run time for every method on the scene set")
    p.add_argument("--budgets", default="0.5,1,2,4", help="seconds per render, comma-separated")
    p.add_argument("--scenes", default=",".join(SCENE_SET), help="scenes, comma-separated")
    p.add_argument(
        "--methods",
        default=",".join((*MC_METHODS, *RADIOSITY_LEVELS)),
        help="methods and radiosity levels, comma-separated",
    )
    p.add_argument("--out", default="out/bench", help="output folder")
    p.add_argument(
        "--cache",
        default=str(Path.home() / ".cache" / "dualight" / "references"),
        help="where references rendered on first use are kept",
    )
    p.add_argument("--quick", action="store_true", help="budgets 0.25,0.5,1 (under 5 minutes)")
    p.set_defaults(run=_command)


def _command(args: argparse.Namespace) -> int:
    if args.quick:
        args.budgets = "0.25,0.5,1"
    return run(args)
