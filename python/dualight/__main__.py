"""Command line: ``python -m dualight render ...``, ``python -m dualight demo`` and
``python -m dualight bench``."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence
from pathlib import Path

from dualight import scenes
from dualight._cli import resolution
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
    p.add_argument("--resolution", type=resolution, default=(256, 256), help="WxH")
    p.add_argument("--exposure", type=float, default=0.0, help="stops, for 8-bit outputs")
    p.add_argument("-o", "--output", default="out.exr")
    p.add_argument("-q", "--quiet", action="store_true")
    p.set_defaults(run=_render_command)

    from dualight import bench, demo

    demo.add_parser(sub)
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
