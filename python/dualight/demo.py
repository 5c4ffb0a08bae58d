"""``python -m dualight demo``: the main job of the README (``make demo``)."""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path
from typing import Any

import numpy as np

from dualight import scenes
from dualight._cli import resolution
from dualight.render import render


def _command(args: argparse.Namespace) -> int:
    """The main job: render the Cornell box, write EXR and PNG, and a short report."""
    from dualight import _core

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    scene = scenes.cornell_box(resolution=args.resolution)
    start = time.perf_counter()
    image = render(scene, "path", spp=args.spp, seed=args.seed, progress=not args.quiet)
    wall = time.perf_counter() - start
    image.stats["scene"] = "cornell"
    image.save(out / "cornell_path.exr")
    image.save(out / "cornell_path.png")
    s = image.stats
    limit = _core.cast_random_rays(
        scene._compile(),
        scene.camera._compile(),
        int(s["rays"]),
        seed=1,  # type: ignore[union-attr]
    )
    report = {
        "scene": "cornell",
        "method": s["method"],
        "resolution": list(args.resolution),
        "spp": s["spp"],
        "seconds": s["seconds"],
        "wall_seconds_including_setup": wall,
        "samples_per_second": s["samples_per_second"],
        "rays_per_second": s["rays_per_second"],
        "embree_limit_rays_per_second": limit["rays_per_second"],
        "fraction_of_embree_limit": s["rays_per_second"] / limit["rays_per_second"],
        "threads": s["threads"],
        "files": ["cornell_path.exr", "cornell_path.png"],
    }
    lines = [
        "# dualight demo",
        "",
        f"- scene: Cornell box, {args.resolution[0]}x{args.resolution[1]}",
        f"- method: path tracing (NEE + MIS), {s['spp']} spp, seed {args.seed}",
        f"- time: {s['seconds']:.2f} s on {s['threads']} threads",
        f"- samples/s: {s['samples_per_second'] / 1e6:.2f} M",
        f"- rays/s: {s['rays_per_second'] / 1e6:.1f} M "
        f"({100 * report['fraction_of_embree_limit']:.0f}% of the Embree-only limit, "
        f"{limit['rays_per_second'] / 1e6:.1f} M rays/s)",
        "- images: cornell_path.exr (linear, float32), cornell_path.png (sRGB)",
    ]
    lines += _duality_section(out, args, report)
    (out / "report.json").write_text(json.dumps(report, indent=2) + "\n")
    (out / "report.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    print(f"\nwrote {out}/: {', '.join(report['files'])}, report.md, report.json")
    return 0


def _duality_section(out: Path, args: argparse.Namespace, report: dict) -> list[str]:
    """Path tracing, light tracing and BDPT of the caustic Cornell box at equal time: three
    estimators of one image (the light tracer leaves mirror and glass seen directly dark)."""
    from dualight import metrics

    scene = scenes.cornell_box(resolution=args.resolution, variant="caustics")
    images = {}
    for method in ("path", "light", "bdpt"):
        image = render(
            scene,
            method,
            spp=None,
            time_limit=args.duality_seconds,
            max_depth=8,
            seed=args.seed,
            progress=not args.quiet,
        )
        image.stats["scene"] = "cornell caustics"
        for suffix in (".exr", ".png"):
            image.save(out / f"caustics_{method}{suffix}")
            report["files"].append(f"caustics_{method}{suffix}")
        images[method] = image
    pt, bd = images["path"], images["bdpt"]
    blocks = metrics.welch_test(bd, bd.variance, pt, pt.variance, block=16)
    report["duality"] = {
        method: {
            "spp": im.stats["spp"],
            "seconds": im.stats["seconds"],
            "image_mean": float(np.mean(im)),
        }
        for method, im in images.items()
    }
    report["duality"]["bdpt_vs_path_16x16_blocks_pass"] = blocks.pass_fraction
    rows = [
        f"- {m}: {im.stats['spp']} spp in {im.stats['seconds']:.1f} s, image mean "
        f"{float(np.mean(im)):.4f}"
        for m, im in images.items()
    ]
    return [
        "",
        f"## Duality: the caustic Cornell box, {args.duality_seconds:g} s per method",
        "",
        *rows,
        f"- BDPT against path tracing, Welch test on 16x16 blocks: "
        f"{100 * blocks.pass_fraction:.0f}% pass (the light tracer misses mirror and glass "
        "seen directly, by design)",
        "- images: caustics_path.png, caustics_light.png, caustics_bdpt.png (and EXR)",
    ]


def add_parser(sub: Any) -> None:
    """Add the ``demo`` subcommand to the ``python -m dualight`` argument parser."""
    d = sub.add_parser("demo", help="render the Cornell box and write images and a report")
    d.add_argument("--out", default="out")
    d.add_argument("--spp", type=int, default=512)
    d.add_argument("--seed", type=int, default=0)
    d.add_argument("--resolution", type=resolution, default=(256, 256), help="WxH")
    d.add_argument("--duality-seconds", type=float, default=5.0, help="per method")
    d.add_argument("-q", "--quiet", action="store_true")
    d.set_defaults(run=_command)
