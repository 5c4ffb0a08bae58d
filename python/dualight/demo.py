"""``python -m dualight demo``: the main job of the README (``make demo``).

One page, ``out/index.html`` (with ``report.md`` and ``report.json`` beside it), that shows
the library's idea in about three minutes on two cores:

1. the Cornell box by path tracing, with its speed against Embree's ray-casting limit;
2. radiosity and importance: ``M B = E`` and the dual ``M^T I = R`` answer one measurement,
   ``<R, B> = <I, E>``, for the Cornell box and a building of four rooms, with the radiosity,
   importance and superposition pictures [Smits, Arvo and Salesin 1992];
3. importance-driven against plain (BF) hierarchical radiosity on the rooms: links, seconds
   and the view's error against a path-traced measurement;
4. duality of estimators: path tracing (radiance gathered from the eye) against light tracing
   (importance shot from the lights) of the caustic box, two estimates of one image, with a
   Welch test on the pixels both can render;
5. Veach's door: BDPT at 40 samples per pixel against path-space MLT in the same wall time,
   each one's relMSE against the Mitsuba 3 reference [Veach and Guibas 1997].

Progress: bars on a terminal; otherwise (a log, CI) one line per phase.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from dualight import metrics, scenes
from dualight._cli import add_subcommand, resolution
from dualight._page import Figure, Section, markdown, write_html
from dualight.image import Image, srgb_decode
from dualight.render import render
from dualight.scene import Scene

TITLE = "dualight: radiance and importance, one measurement"
CONTROL_SCALE = 0.97  # the duality test's negative control: a light 3 % too dim
LIMIT_RAYS = 20_000_000  # rays cast to measure Embree's limit (enough for 1 % timing)
WELCH_BLOCK = 16  # the test suite's judge of the path tracer on the caustic box (heavy tails)
MLT_DEPTH = 8  # the door reference's max_depth (tests/references)


@dataclass(frozen=True)
class Budget:
    """Sizes and times of the demo's phases (``full``: the README's ``make demo``; ``quick``:
    seconds, for the tests)."""

    cornell_spp: int
    cornell_resolution: tuple[int, int]
    radiosity_resolution: tuple[int, int]
    duality_seconds: float
    duality_resolution: tuple[int, int]
    bdpt_spp: int
    epsilons: dict[str, tuple[float, ...]]  # hierarchical radiosity, per oracle
    measurement_spp: int
    patches_per_extent: float  # radiosity patch size: the scene's largest extent / this


# Where each oracle's error falls from 1 % to 0.5 % on rooms(4) (benchmarks/bench_hierarchical).
_EPSILONS = {"importance": (1e-3, 1e-4, 3e-5), "bf": (1e-2, 1e-3)}
FULL = Budget(256, (256, 256), (192, 192), 10.0, (128, 128), 40, _EPSILONS, 256, 10.0)
QUICK = Budget(
    4, (48, 48), (48, 48), 0.5, (32, 32), 4, {"importance": (1e-2,), "bf": (1e-2,)}, 8, 4.0
)


@dataclass
class Demo:
    """What the phases share: the output folder, options, the report being filled."""

    out: Path
    budget: Budget
    seed: int
    threads: int | None
    bars: bool  # progress bars (a terminal) or one line per phase
    report: dict[str, Any] = field(default_factory=dict)
    files: list[str] = field(default_factory=list)

    @contextmanager
    def phase(self, name: str) -> Iterator[None]:
        start = time.perf_counter()
        print(f"{name} ...", flush=True)
        yield
        print(f"  done in {time.perf_counter() - start:.1f} s", flush=True)

    def render(self, scene: Scene, method: str, **kw: Any) -> Image:
        return render(scene, method, seed=self.seed, threads=self.threads, progress=self.bars, **kw)

    def save(self, image: Image, stem: str, caption: str, **figure: Any) -> Figure:
        """PNG (for the page) and EXR (linear, with stats) of a rendered image."""
        exposure = figure.pop("exposure", 0.0)
        image.save(self.out / f"{stem}.exr")
        image.save(self.out / f"{stem}.png", exposure=exposure)
        self.files += [f"{stem}.exr", f"{stem}.png"]
        return Figure(f"{stem}.png", caption, **figure)

    def save_display(self, pixels: np.ndarray, stem: str, caption: str, **figure: Any) -> Figure:
        """A picture already in display values (the false-colour modes): written as they are."""
        Image(srgb_decode(np.clip(np.asarray(pixels, np.float64), 0.0, 1.0))).save(
            self.out / f"{stem}.png"
        )
        self.files.append(f"{stem}.png")
        return Figure(f"{stem}.png", caption, **figure)


def _vec(v: np.ndarray) -> str:
    return "(" + ", ".join(f"{x:.6f}" for x in np.asarray(v, dtype=float)) + ")"


def _cornell_path(demo: Demo) -> Section:
    from dualight import _core

    b = demo.budget
    scene = scenes.cornell_box(resolution=b.cornell_resolution)
    image = demo.render(scene, "path", spp=b.cornell_spp)
    s = image.stats
    limit = _core.cast_random_rays(
        scene._compile(),
        scene.camera._compile(),
        min(int(s["rays"]), LIMIT_RAYS),
        seed=1,  # type: ignore[union-attr]
    )
    fraction = s["rays_per_second"] / limit["rays_per_second"]
    demo.report.update(
        scene="cornell",
        method=s["method"],
        resolution=list(b.cornell_resolution),
        spp=s["spp"],
        seconds=s["seconds"],
        samples_per_second=s["samples_per_second"],
        rays_per_second=s["rays_per_second"],
        embree_limit_rays_per_second=limit["rays_per_second"],
        fraction_of_embree_limit=fraction,
        threads=s["threads"],
    )
    w, h = b.cornell_resolution
    return Section(
        "The Cornell box by path tracing",
        "The measured Cornell box (Cornell Program of Computer Graphics), path traced from the "
        "eye with next-event estimation and BSDF sampling combined by MIS.",
        [
            f"{w}x{h}, {s['spp']} spp, seed {demo.seed}: {s['seconds']:.2f} s on "
            f"{s['threads']} threads",
            f"{s['samples_per_second'] / 1e6:.2f} M samples/s, {s['rays_per_second'] / 1e6:.1f} M "
            f"rays/s: {100 * fraction:.0f}% of Embree's limit on this machine "
            f"({limit['rays_per_second'] / 1e6:.1f} M rays/s casting the same rays alone)",
        ],
        figures=[demo.save(image, "cornell_path", "path tracing, linear EXR beside it")],
    )


def _radiosity_pictures(demo: Demo, key: str, label: str, scene: Scene) -> Section:
    from dualight import radiosity

    positions, _, _ = scene.triangle_arrays()
    extent = float(np.max(positions.max(axis=0) - positions.min(axis=0)))
    solution = radiosity.solve(
        scene,
        "direct",
        max_edge=extent / demo.budget.patches_per_extent,
        threads=demo.threads,
        progress=demo.bars,
        seed=demo.seed,
    )
    primal, dual = solution.measurement_primal, solution.measurement_dual
    demo.report.setdefault("radiosity", {})[key] = {
        "patches": solution.stats["patches"],
        "seconds": solution.stats["seconds"],
        "R_B": np.asarray(primal).tolist(),
        "I_E": np.asarray(dual).tolist(),
        "duality_gap": solution.duality_gap,
    }
    captions = {
        "radiosity": "radiosity B: what the camera sees",
        "importance": "importance I: where light would count for this view",
        "superposition": "superposition: reflected light times importance (yellow)",
    }
    figures = [
        demo.save(solution.render(mode="radiosity"), f"{key}_radiosity", captions["radiosity"])
    ]
    for mode in ("importance", "superposition"):
        pixels = np.asarray(solution.render(mode=mode))
        figures.append(demo.save_display(pixels, f"{key}_{mode}", captions[mode]))
    return Section(
        f"Radiosity and importance: {label}",
        "Radiosity solves `M B = E` with `M = I - diag(rho) F`; the camera's measurement is "
        "`<R, B>`, `R_i > 0` on the patches it sees. The dual system `M^T I = R` gives each "
        "patch's importance, and the same measurement is `<I, E>` (dense LU on both sides).",
        [
            f"{solution.stats['patches']} patches, {solution.stats['seconds']:.2f} s "
            "(form factors and both solves)",
            f"`<R, B>` = {_vec(primal)}",
            f"`<I, E>` = {_vec(dual)}",
            f"largest relative difference {solution.duality_gap:.1e}",
        ],
        figures=figures,
    )


def _view_measurement(demo: Demo, scene: Scene) -> tuple[np.ndarray, np.ndarray]:
    """The camera's mean pixel value per channel by path tracing, and its standard error."""
    image = demo.render(scene, "path", spp=demo.budget.measurement_spp, max_depth=-1)
    pixels = np.asarray(image, dtype=np.float64)
    n = pixels.shape[0] * pixels.shape[1]
    var = np.asarray(image.variance, dtype=np.float64)
    return pixels.mean(axis=(0, 1)), np.sqrt(var.sum(axis=(0, 1))) / n


def _hierarchical_run(scene: Scene, oracle: str, eps: float, reference: np.ndarray, demo: Demo):
    from dualight import radiosity

    sol = radiosity.solve(scene, "hierarchical", oracle=oracle, epsilon=eps, threads=demo.threads)
    error = float(np.max(np.abs(sol.measurement_primal / reference - 1.0)))
    run = {
        "oracle": oracle,
        "epsilon": eps,
        "links": sol.stats["links"],
        "seconds": sol.stats["seconds"],
        "view_error": error,
    }
    return sol, run


def _oracles_compared(runs: list[dict[str, Any]]) -> str:
    """The finest importance-driven solve against the finest BF solve."""
    imp = [r for r in runs if r["oracle"] == "importance"][-1]
    bf = [r for r in runs if r["oracle"] == "bf"][-1]
    text = (
        f"importance-driven at epsilon {imp['epsilon']:g}: {100 * imp['view_error']:.2f}% with "
        f"{imp['links']:,} links in {imp['seconds']:.2f} s; BF at epsilon {bf['epsilon']:g}: "
        f"{100 * bf['view_error']:.2f}% with {bf['links']:,} links in {bf['seconds']:.2f} s"
    )
    if bf["view_error"] >= imp["view_error"]:
        text += (
            f": BF spends {bf['links'] / imp['links']:.0f}x the links and "
            f"{bf['seconds'] / imp['seconds']:.0f}x the time for a larger error"
        )
    return text


def _hierarchical(demo: Demo) -> Section:
    scene = scenes.rooms(4, resolution=demo.budget.radiosity_resolution)
    reference, stderr = _view_measurement(demo, scene)
    rows: list[list[str]] = [["oracle", "epsilon", "links", "seconds", "view error"]]
    runs, figures = [], []
    for oracle in ("importance", "bf"):
        for eps in demo.budget.epsilons[oracle]:
            sol, run = _hierarchical_run(scene, oracle, eps, reference, demo)
            runs.append(run)
            rows.append(
                [
                    oracle,
                    f"{eps:g}",
                    f"{run['links']:,}",
                    f"{run['seconds']:.2f}",
                    f"{100 * run['view_error']:.2f}%",
                ]
            )
        links = np.asarray(sol.render(mode="links"))
        caption = f"{oracle} oracle, epsilon {eps:g}: links per unit area (log)"
        figures.append(demo.save_display(links, f"rooms_links_{oracle}", caption))
    noise = float(np.max(stderr / reference))
    demo.report["hierarchical"] = {"reference": reference.tolist(), "noise": noise, "runs": runs}
    return Section(
        "Importance-driven hierarchical radiosity: four rooms",
        "Hierarchical radiosity links element trees and refines a link where its energy "
        "transfer is large (BF, Hanrahan et al. 1991) or where transfer times importance is "
        "large (Smits, Arvo and Salesin 1992): the camera sees one room, so the others need "
        "little refinement. View error: the largest relative error over RGB of the mean pixel "
        "value against path tracing of the same scene.",
        [
            f"reference: path tracing, {demo.budget.measurement_spp} spp, relative standard "
            f"error {100 * noise:.3f}%",
            _oracles_compared(runs),
        ],
        table=rows,
        figures=figures,
    )


def _welch(
    pt: Image, lt: Image, mask: np.ndarray, scale: float
) -> tuple[metrics.WelchResult, metrics.WelchResult]:
    """Path against light tracing (the latter times ``scale``), per pixel and per block."""
    lt_mean, lt_var = scale * np.asarray(lt), scale**2 * np.asarray(lt.variance)
    return (
        metrics.welch_test(pt, pt.variance, lt_mean, lt_var, mask=mask),
        metrics.welch_test(pt, pt.variance, lt_mean, lt_var, block=WELCH_BLOCK, mask=mask),
    )


def _duality(demo: Demo) -> Section:
    b = demo.budget
    scene = scenes.cornell_box(resolution=b.duality_resolution, variant="caustics")
    images = {
        method: demo.render(scene, method, spp=None, time_limit=b.duality_seconds, max_depth=8)
        for method in ("path", "light")
    }
    pt, lt = images["path"], images["light"]
    mask = metrics.renderable_by_light_tracing(scene)
    pixels, blocks = _welch(pt, lt, mask, 1.0)
    control_pixels, control_blocks = _welch(pt, lt, mask, CONTROL_SCALE)
    agree = blocks.pass_fraction == 1.0
    control_agrees = control_blocks.pass_fraction == 1.0
    demo.report["duality"] = {
        m: {
            "spp": im.stats["spp"],
            "seconds": im.stats["seconds"],
            "image_mean": float(np.mean(im)),
        }
        for m, im in images.items()
    }
    demo.report["duality"].update(
        tested_pixels=int(mask.sum()),
        pixels=int(mask.size),
        pixel_pass_fraction=pixels.pass_fraction,
        block_pass_fraction=blocks.pass_fraction,
        verdict="agree" if agree else "differ",
        control_scale=CONTROL_SCALE,
        control_pixel_pass_fraction=control_pixels.pass_fraction,
        control_block_pass_fraction=control_blocks.pass_fraction,
        control_verdict="agree" if control_agrees else "differ",
    )
    lines = [
        f"{m} tracing: {im.stats['spp']} spp in {im.stats['seconds']:.1f} s, mean over the "
        f"tested pixels {float(np.mean(np.asarray(im)[mask])):.4f}"
        for m, im in images.items()
    ]
    lines += [
        f"Welch test (family-wise alpha 0.01, Sidak) on {WELCH_BLOCK}x{WELCH_BLOCK} blocks of the "
        f"{int(mask.sum())} of {mask.size} pixels a light tracer can render: "
        f"{100 * blocks.pass_fraction:.1f}% of {blocks.n_units} blocks pass: "
        + ("the two estimate the same image" if agree else "the two images DIFFER"),
        f"per pixel (reported, not judged: the path tracer's caustics seen via the mirror are "
        f"heavy-tailed, so its per-pixel variance is too low where it missed them): "
        f"{100 * pixels.pass_fraction:.1f}% pass",
        f"negative control, the light tracer's image times {CONTROL_SCALE:g}: "
        f"{100 * control_blocks.pass_fraction:.1f}% of blocks pass: "
        + ("NOT detected (too few samples)" if control_agrees else "detected"),
    ]
    return Section(
        "Duality of estimators: path tracing against light tracing",
        "The path tracer gathers radiance from the eye (`L = Le + T L`); the light tracer "
        "shoots power from the lights and splats what the camera's importance sees "
        "(`W = We + T* W`). Both estimate `<L, We> = <Le, W>`, the same image, at equal time. "
        "The caustic box's mirror and glass seen directly are left out of the test: a light "
        "path cannot reach the pinhole through them.",
        lines,
        figures=[
            demo.save(pt, "caustics_path", "path tracing", width=256),
            demo.save(
                lt,
                "caustics_light",
                "light tracing (mirror and glass seen directly stay dark)",
                width=256,
            ),
            demo.save_display(
                np.repeat(mask[..., None], 3, axis=2).astype(float),
                "caustics_tested",
                "pixels in the test (white)",
                width=256,
                pixelated=True,
            ),
        ],
    )


def _mlt_vs_bdpt(demo: Demo) -> Section:
    from dualight import bench

    scene = scenes.door_ajar(resolution=(64, 64))
    reference = bench.load_reference("door", "test:door_64", scene, demo.out / "cache")
    bdpt = demo.render(scene, "bdpt", spp=demo.budget.bdpt_spp, max_depth=MLT_DEPTH)
    seconds = bdpt.stats["seconds"]
    mlt = demo.render(scene, "mlt", spp=None, time_limit=seconds, max_depth=MLT_DEPTH)
    rows: list[list[str]] = [["method", "seconds", "per pixel", "relMSE"]]
    runs = {}
    for name, img in (("BDPT", bdpt), ("MLT", mlt)):
        per_pixel = img.stats["samples"] / (64 * 64)
        err = bench.errors(np.asarray(img), reference)["relmse"] if reference else float("nan")
        runs[name] = {"seconds": img.stats["seconds"], "per_pixel": per_pixel, "relmse": err}
        unit = "samples" if name == "BDPT" else "mutations"
        rows.append([name, f"{img.stats['seconds']:.2f}", f"{per_pixel:.0f} {unit}", f"{err:.3f}"])
    demo.report["mlt_vs_bdpt"] = runs
    exposure = 2.0
    figures = []
    if reference is not None:
        figures.append(
            demo.save(
                Image(reference.mean),
                "door_reference",
                "Mitsuba 3 reference (524288 spp)",
                exposure=exposure,
                pixelated=True,
            )
        )
    figures += [
        demo.save(
            bdpt,
            "door_bdpt",
            f"BDPT, {demo.budget.bdpt_spp} spp",
            exposure=exposure,
            pixelated=True,
        ),
        demo.save(mlt, "door_mlt", "MLT, same time", exposure=exposure, pixelated=True),
    ]
    ratio = runs["BDPT"]["relmse"] / runs["MLT"]["relmse"]
    return Section(
        "Metropolis light transport against BDPT: Veach's door",
        "A room lit only through a door ajar: almost all light reaches the camera through the "
        "gap, so independent bidirectional paths rarely find it, while Metropolis light "
        "transport, once it holds a path that carries light, explores its neighbours by "
        "mutations. Veach and Guibas (1997) compared BDPT at 40 samples per pixel with MLT at "
        "about 250 mutations per pixel in the same time. relMSE: pbrt-v4's, minus the "
        "reference's own noise; images at +2 stops.",
        [f"BDPT's relMSE is {ratio:.1f}x MLT's at equal time"],
        table=rows,
        figures=figures,
    )


def run(args: argparse.Namespace) -> int:
    """Every phase, then the page and the reports."""
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    budget = QUICK if args.quick else FULL
    overrides = {
        "cornell_spp": args.spp,
        "cornell_resolution": args.resolution,
        "duality_seconds": args.duality_seconds,
    }
    budget = replace(budget, **{k: v for k, v in overrides.items() if v is not None})
    bars = not args.quiet and sys.stderr.isatty()
    demo = Demo(out, budget, args.seed, args.threads, bars)
    start = time.perf_counter()
    sections = []
    with demo.phase("Cornell box, path tracing"):
        sections.append(_cornell_path(demo))
    with demo.phase("radiosity and importance, Cornell box"):
        sections.append(
            _radiosity_pictures(
                demo,
                "cornell",
                "the Cornell box",
                scenes.cornell_box(resolution=budget.radiosity_resolution),
            )
        )
    with demo.phase("radiosity and importance, four rooms"):
        sections.append(
            _radiosity_pictures(
                demo,
                "rooms",
                "a building of four rooms",
                scenes.rooms(4, resolution=budget.radiosity_resolution),
            )
        )
    with demo.phase("hierarchical radiosity, importance-driven against BF"):
        sections.append(_hierarchical(demo))
    with demo.phase("path tracing against light tracing, caustic box"):
        sections.append(_duality(demo))
    with demo.phase("BDPT against MLT at equal time, the door"):
        sections.append(_mlt_vs_bdpt(demo))
    wall = time.perf_counter() - start
    demo.report["wall_seconds"] = wall
    demo.report["files"] = demo.files + ["index.html", "report.md", "report.json"]
    summary = (
        f"Made by `python -m dualight demo` in {wall:.0f} s (seed {args.seed}). Radiance and "
        "importance are adjoint: every section answers one measurement two ways."
    )
    write_html(out / "index.html", TITLE, summary, sections)
    (out / "report.md").write_text(markdown(TITLE, summary, sections))
    (out / "report.json").write_text(json.dumps(demo.report, indent=2) + "\n")
    print(
        f"wrote {out / 'index.html'} (and report.md, report.json, {len(demo.files)} images) "
        f"in {wall:.0f} s"
    )
    return 0


def add_parser(sub: Any) -> None:
    """Add the ``demo`` subcommand to the ``python -m dualight`` argument parser."""
    d = add_subcommand(
        sub, "demo", "the whole idea on one page: out/index.html (about 2 minutes on 2 cores)"
    )
    d.add_argument("--out", default="out", help="output folder")
    d.add_argument("--seed", type=int, default=0, help="seed of every render and solve")
    d.add_argument("--threads", type=int, default=None, help="threads (default: all cores)")
    d.add_argument(
        "--spp",
        type=int,
        default=None,
        help=f"the Cornell box's samples per pixel (default: {FULL.cornell_spp})",
    )
    d.add_argument(
        "--resolution",
        type=resolution,
        default=None,
        help="the Cornell box's WxH (default: {}x{})".format(*FULL.cornell_resolution),
    )
    d.add_argument(
        "--duality-seconds",
        type=float,
        default=None,
        help=f"path and light tracing, each (default: {FULL.duality_seconds:g})",
    )
    d.add_argument("--quick", action="store_true", help="tiny sizes and budgets, seconds in all")
    d.add_argument("-q", "--quiet", action="store_true", help="no progress bars")
    d.set_defaults(run=run)
