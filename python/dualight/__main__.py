"""Command line: ``python -m dualight render ...``, ``python -m dualight demo`` and
``python -m dualight bench``."""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np

from dualight import scenes
from dualight.image import Image
from dualight.methods import METHODS
from dualight.render import render
from dualight.scene import Scene

SCENES: dict[str, Callable[[tuple[int, int]], Scene]] = {
    "cornell": lambda res: scenes.cornell_box(resolution=res),
    "furnace": lambda res: scenes.furnace(resolution=res),
    "caustics": lambda res: scenes.cornell_box(resolution=res, variant="caustics"),
    "door": lambda res: scenes.door_ajar(resolution=res),
}


def _resolution(text: str) -> tuple[int, int]:
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"resolution must look like 128x128, got {text!r}"
        ) from None
    return w, h


def _render_command(args: argparse.Namespace) -> int:
    scene = SCENES[args.scene](args.resolution)
    image = render(
        scene,
        args.method,
        spp=args.spp,
        time_limit=args.time_limit,
        max_depth=args.max_depth,
        seed=args.seed,
        threads=args.threads,
        progress=not args.quiet,
    )
    image.stats["scene"] = args.scene
    out = image.save(args.output, exposure=args.exposure)
    s = image.stats
    print(
        f"{out}: {args.scene} {s['method']} {s['spp']} spp in {s['seconds']:.2f} s "
        f"({s['samples_per_second'] / 1e6:.2f} M samples/s, "
        f"{s['rays_per_second'] / 1e6:.1f} M rays/s)"
    )
    return 0


def _demo_command(args: argparse.Namespace) -> int:
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


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``python -m dualight`` and the ``dualight`` script."""
    parser = argparse.ArgumentParser(prog="dualight", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("render", help="render a built-in scene to an image file")
    p.add_argument("--scene", choices=sorted(SCENES), default="cornell")
    p.add_argument("--method", choices=METHODS, default="path")
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--time-limit", type=float, default=None, help="seconds")
    p.add_argument("--max-depth", type=int, default=-1)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--threads", type=int, default=None)
    p.add_argument("--resolution", type=_resolution, default=(256, 256), help="WxH")
    p.add_argument("--exposure", type=float, default=0.0, help="stops, for 8-bit outputs")
    p.add_argument("-o", "--output", default="out.exr")
    p.add_argument("-q", "--quiet", action="store_true")
    p.set_defaults(run=_render_command)

    d = sub.add_parser("demo", help="render the Cornell box and write images and a report")
    d.add_argument("--out", default="out")
    d.add_argument("--spp", type=int, default=512)
    d.add_argument("--seed", type=int, default=0)
    d.add_argument("--resolution", type=_resolution, default=(256, 256), help="WxH")
    d.add_argument("--duality-seconds", type=float, default=5.0, help="per method")
    d.add_argument("-q", "--quiet", action="store_true")
    d.set_defaults(run=_demo_command)

    from dualight import bench

    bench.add_parser(sub)

    args = parser.parse_args(argv)
    try:
        return int(args.run(args))
    except (ValueError, FileNotFoundError) as err:
        print(f"dualight: error: {err}", file=sys.stderr)
        return 2
    except KeyboardInterrupt as interrupt:
        partial = getattr(interrupt, "partial_result", None)
        if isinstance(partial, Image) and getattr(args, "output", None):
            path = Path(args.output)
            partial.save(path.with_name(path.stem + "_partial" + path.suffix))
            print(f"interrupted: partial image saved beside {path}", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
