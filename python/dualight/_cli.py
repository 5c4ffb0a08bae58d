"""What the ``python -m dualight`` subcommands share: the help formatter that shows every
option's default, :func:`add_subcommand` (use it for every subcommand), argument types, and the
camera given to a scene file that has none."""

from __future__ import annotations

import argparse
import math
import re
from typing import Any

import numpy as np

from dualight.scene import Camera, Scene


class HelpFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """Adds ``(default: ...)`` to each option's help unless the help already says its
    default (write it there when ``None`` or a tuple would read badly)."""

    def _get_help_string(self, action: argparse.Action) -> str:
        text = action.help or ""
        if "default" in text or action.default in (None, argparse.SUPPRESS):
            return text
        return super()._get_help_string(action) or text


def add_subcommand(sub: Any, name: str, help: str) -> argparse.ArgumentParser:  # noqa: A002
    """A subcommand ``name`` of the ``sub`` subparsers whose ``--help`` shows every
    option's default (:class:`HelpFormatter`); ``help`` is its one-line summary."""
    return sub.add_parser(name, help=help, description=help, formatter_class=HelpFormatter)


_RESOLUTION = re.compile(r"\s*(\d+)\s*[xX]\s*(\d+)\s*")


def resolution(text: str) -> tuple[int, int]:
    """``WIDTHxHEIGHT`` (``128x96``) as ``(width, height)``, both positive integers."""
    match = _RESOLUTION.fullmatch(text)
    if match is None or min(int(match[1]), int(match[2])) < 1:
        raise argparse.ArgumentTypeError(
            f"resolution must be WIDTHxHEIGHT in positive whole pixels, like 128x96, got {text!r}"
        )
    return int(match[1]), int(match[2])


def point(text: str) -> tuple[float, float, float]:
    """``X,Y,Z`` as 3 finite floats."""
    try:
        values = tuple(float(v) for v in text.split(","))
    except ValueError:
        values = ()
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(f"a point must be X,Y,Z (3 numbers), got {text!r}")
    return values  # type: ignore[return-value]


def framing_camera(scene: Scene, resolution: tuple[int, int], fov: float = 40.0) -> Camera:
    """A camera for a scene without one (an OBJ file): on the +z side of the bounding box's
    centre, looking along -z with y up (OBJ's usual convention), far enough that the
    bounding sphere fills the narrower field of view."""
    lo, hi = scene.bounds()
    centre = (lo + hi) / 2.0
    radius = max(float(np.linalg.norm(hi - lo)) / 2.0, 1e-9)
    width, height = resolution
    tan_half = math.tan(math.radians(fov) / 2.0) * min(1.0, height / width)
    distance = radius / math.sin(math.atan(tan_half))
    return Camera(
        origin=tuple(centre + (0.0, 0.0, distance)),
        target=tuple(centre),
        up=(0.0, 1.0, 0.0),
        fov=fov,
        resolution=resolution,
    )
