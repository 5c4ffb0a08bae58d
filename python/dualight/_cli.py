"""Argument types shared by the ``python -m dualight`` subcommands."""

from __future__ import annotations

import argparse


def resolution(text: str) -> tuple[int, int]:
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"resolution must look like 128x128, got {text!r}"
        ) from None
    return w, h
