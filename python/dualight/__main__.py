"""Command line: ``python -m dualight render ...``, ``python -m dualight demo`` and
``python -m dualight bench``."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, get_args

from dualight import __version__, scenes
from dualight._cli import HelpFormatter, add_subcommand, framing_camera, point, resolution
from dualight.image import Image
from dualight.io import load_mitsuba_xml, load_obj, read_mitsuba_settings
from dualight.methods import METHODS, Sampler, Strategies
from dualight.render import render
from dualight.scene import Camera, Scene

SCENES: dict[str, Callable[[tuple[int, int]], Scene]] = {
    "cornell": lambda res: scenes.cornell_box(resolution=res),
    "furnace": lambda res: scenes.furnace(resolution=res),
    "caustics": lambda res: scenes.cornell_box(resolution=res, variant="caustics"),
    "door": lambda res: scenes.door_ajar(resolution=res),
    "door_glossy": lambda res: scenes.door_ajar(resolution=res, variant="glossy"),
    "veach_mis": lambda res: scenes.veach_mis(resolution=res),
    "veach_bidir": lambda res: scenes.veach_bidir(resolution=res),
}
SCENE_FILES = (".xml", ".obj")  # Mitsuba XML, Wavefront OBJ
# render's defaults on the command line, where neither an option nor a scene file sets them.
DEFAULTS: dict[str, Any] = {"method": "path", "spp": 64, "max_depth": -1, "seed": 0}
DEFAULT_RESOLUTION = (256, 256)


def _scene_file(path: Path, res: tuple[int, int] | None) -> tuple[Scene, dict[str, Any]]:
    """A Mitsuba XML or OBJ scene and the render settings it asks for; a scene without a
    camera gets :func:`dualight._cli.framing_camera` (said on stderr)."""
    if not path.is_file():
        raise FileNotFoundError(f"no such scene file: {str(path)!r}")
    if path.suffix.lower() == ".xml":
        scene, settings = load_mitsuba_xml(path), read_mitsuba_settings(path)
    else:
        scene, settings = load_obj(path), {}
    if scene.camera is None:
        scene.camera = framing_camera(scene, res or DEFAULT_RESOLUTION)
        cam = scene.camera
        print(
            f"dualight: {path.name} has no camera: looking from "
            f"({', '.join(f'{v:.3g}' for v in cam.origin)}) at the centre of its bounding box "
            f"({', '.join(f'{v:.3g}' for v in cam.target)}) along -z, y up, fov {cam.fov:g}; "
            "choose with --look-from and --look-at",
            file=sys.stderr,
        )
    elif res is not None:
        scene.camera = scene.camera.with_resolution(*res)
    return scene, settings


def _scene(args: argparse.Namespace) -> tuple[Scene, str, dict[str, Any]]:
    """The scene to render (a built-in name or a file, positional or ``--scene``), its label
    and the settings it asks for."""
    if args.scene and args.scene_file and args.scene != args.scene_file:
        raise ValueError(f"two scenes given: {args.scene_file!r} and --scene {args.scene!r}")
    name = args.scene_file or args.scene or "cornell"
    if name in SCENES:
        scene, settings = SCENES[name](args.resolution or DEFAULT_RESOLUTION), {}
    elif Path(name).suffix.lower() in SCENE_FILES:
        scene, settings = _scene_file(Path(name), args.resolution)
    else:
        what = "scene file type" if Path(name).is_file() else "scene"
        raise ValueError(
            f"unknown {what} {name!r}: give a built-in scene ({', '.join(sorted(SCENES))}) or "
            f"a scene file ({', '.join(SCENE_FILES)})"
        )
    if args.look_from is not None or args.look_at is not None:
        cam = scene.camera
        assert cam is not None
        scene.camera = Camera(
            args.look_from or cam.origin,
            args.look_at or cam.target,
            cam.up,
            cam.fov,
            cam.resolution,
        )
    return scene, name, settings


def _render_command(args: argparse.Namespace) -> int:
    scene, label, settings = _scene(args)
    given = {k: getattr(args, k) for k in ("method", "spp", "max_depth", "rr_depth", "seed")}
    given["sampler"] = args.sampler
    given["strategies"] = args.strategies
    keywords = {**DEFAULTS, **settings, **{k: v for k, v in given.items() if v is not None}}
    image = render(
        scene,
        time_limit=args.time_limit,
        threads=args.threads,
        progress=not args.quiet,
        **keywords,
    )
    image.stats["scene"] = label
    out = image.save(args.output, exposure=args.exposure)
    s = image.stats
    print(
        f"{out}: {label} {s['method']} {s['spp']} spp in {s['seconds']:.2f} s "
        f"({s['samples_per_second'] / 1e6:.2f} M samples/s, "
        f"{s['rays_per_second'] / 1e6:.1f} M rays/s)"
    )
    return 0


def _add_render_parser(sub: Any) -> None:
    p = add_subcommand(
        sub, "render", "render a built-in scene or a scene file (.xml, .obj) to an image file"
    )
    names = ", ".join(sorted(SCENES))
    file_note = "or the scene file's"
    p.add_argument(
        "scene_file",
        nargs="?",
        metavar="SCENE",
        help=f"a built-in scene ({names}), a Mitsuba 3 XML file (its camera and settings) or "
        "an OBJ file (a camera is made, see --look-from); default: cornell",
    )
    p.add_argument("--scene", help="the same as SCENE (kept for scripts); default: cornell")
    p.add_argument("--method", choices=METHODS, help=f"default: path, {file_note} integrator")
    p.add_argument("--spp", type=int, help=f"samples per pixel; default: 64, {file_note}")
    p.add_argument("--time-limit", type=float, help="seconds; default: none (the spp budget alone)")
    p.add_argument(
        "--max-depth", type=int, help=f"path segments, -1 unbounded; default: -1, {file_note}"
    )
    p.add_argument(
        "--rr-depth", type=int, help=f"Russian roulette from this vertex; default: 5, {file_note}"
    )
    p.add_argument("--seed", type=int, help=f"default: 0, {file_note} sampler's")
    p.add_argument(
        "--sampler", choices=get_args(Sampler), help=f"default: independent, {file_note}"
    )
    p.add_argument(
        "--strategies",
        choices=get_args(Strategies),
        help="path and bdpt: MIS of every sampling strategy, or BSDF or light sampling alone; "
        "default: mis",
    )
    p.add_argument("--threads", type=int, help="default: every core")
    p.add_argument(
        "--resolution",
        type=resolution,
        help="WxH, e.g. 320x240; default: 256x256, or the scene file's film",
    )
    p.add_argument(
        "--look-from",
        type=point,
        metavar="X,Y,Z",
        help="camera position; default: the scene's camera (for an OBJ: on the +z side of its "
        "bounding box, far enough to see all of it)",
    )
    p.add_argument(
        "--look-at",
        type=point,
        metavar="X,Y,Z",
        help="a point the camera looks at; default: the scene's (for an OBJ: its centre)",
    )
    p.add_argument("--exposure", type=float, default=0.0, help="stops, for 8-bit outputs")
    p.add_argument(
        "-o", "--output", default="out.exr", help="image file; its suffix picks the format"
    )
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=_render_command)


def _negative_sizes_as_values(argv: Sequence[str]) -> list[str]:
    """``--resolution -3x4`` as ``--resolution=-3x4``: argparse takes ``-3x4`` for an option
    and would say only "expected one argument"; as a value it gets the clear message."""
    out: list[str] = []
    for arg in argv:
        if out and out[-1] == "--resolution" and arg[:1] == "-" and arg[1:2].isdigit():
            out[-1] = f"--resolution={arg}"
        else:
            out.append(arg)
    return out


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``python -m dualight`` and the ``dualight`` script."""
    parser = argparse.ArgumentParser(
        prog="dualight", description=__doc__, formatter_class=HelpFormatter
    )
    parser.add_argument(
        "--version",
        action="version",
        version=f"dualight {__version__}",
        help="print the version and exit",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    _add_render_parser(sub)

    from dualight import bench, demo

    demo.add_parser(sub)
    bench.add_parser(sub)

    args = parser.parse_args(_negative_sizes_as_values(sys.argv[1:] if argv is None else argv))
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
