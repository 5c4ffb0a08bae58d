"""Fuzz the file loaders with atheris: ``dualight.Image.load``, ``dualight.load_mitsuba_xml``
and ``dualight.load_obj`` on fuzzed bytes.

The first input byte picks the suffix (``.exr``, ``.png``, ``.hdr``, ..., ``.xml``, ``.obj``), the
rest is written to a temporary file that the matching loader reads (images through OpenImageIO,
scenes through the XML parser and trimesh). The only acceptable failures are clean Python
exceptions with a message (``ValueError`` for a file that cannot be read or decoded, ...); a
segfault, an abort, a sanitizer report, an image that is not H x W x 3 float32 or a scene with
non-finite vertices is a crash.

Run: ``python tests/fuzz/fuzz_loaders.py -max_total_time=60 corpus_dir`` (libFuzzer flags). An
empty corpus directory is first seeded with small valid files of each format, so the fuzzer
starts from real headers.
"""

from __future__ import annotations

import atexit
import os
import shutil
import sys
import tempfile
import warnings
from pathlib import Path

import atheris
import numpy as np

with atheris.instrument_imports():
    import dualight

SUFFIXES = (".exr", ".png", ".hdr", ".tif", ".jpg", ".pfm", ".ppm", ".bmp", ".tga", ".xml", ".obj")
SCENE_SUFFIXES = (".xml", ".obj")
# A valid scene file of each kind to start from (tests/data/room.xml, and a lit OBJ quad).
ROOM_XML = Path(__file__).resolve().parents[1] / "data" / "room.xml"
QUAD_OBJ = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n"
ACCEPTED = (ValueError, TypeError, FileNotFoundError, RuntimeError)
_TMP = Path(tempfile.mkdtemp(prefix="dualight-fuzz-"))
# Removed at a normal exit; libFuzzer ends with C exit(), which skips this, so test_fuzz.py runs
# the target with TMPDIR in its pytest tmp_path (100 runs had left their folders in /tmp).
atexit.register(shutil.rmtree, _TMP, ignore_errors=True)


def load(data: bytes) -> dualight.Image | dualight.Scene:
    suffix = SUFFIXES[data[0] % len(SUFFIXES)] if data else ".exr"
    path = _TMP / f"input{suffix}"
    path.write_bytes(data[1:])
    if suffix == ".xml":
        return dualight.load_mitsuba_xml(path)
    if suffix == ".obj":
        return dualight.load_obj(path)
    return dualight.Image.load(path)


def test_one_input(data: bytes) -> None:
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # approximations the loaders announce are fine
            loaded = load(data)
    except ACCEPTED as exc:
        if not str(exc):
            raise AssertionError(f"{type(exc).__name__} without a message") from exc
        return
    if isinstance(loaded, dualight.Scene):
        for mesh in loaded.meshes:
            if not np.all(np.isfinite(mesh.vertices)):
                raise AssertionError(f"mesh {mesh.name} has non-finite vertices")
        return
    pixels = np.asarray(loaded)
    if pixels.dtype != np.float32 or pixels.ndim != 3 or pixels.shape[2] != 3:
        raise AssertionError(f"loaded image has dtype {pixels.dtype}, shape {pixels.shape}")


def seed_corpus(folder: Path) -> None:
    """Small valid files of each format (a 5 x 3 gradient with stats as metadata)."""
    rng = np.random.default_rng(0)
    image = dualight.Image(rng.random((3, 5, 3), dtype=np.float32) * 4.0, stats={"spp": 4})
    for suffix, content in ((".xml", ROOM_XML.read_bytes()), (".obj", QUAD_OBJ)):
        (folder / f"seed{suffix}").write_bytes(bytes([SUFFIXES.index(suffix)]) + content)
    for i, suffix in enumerate(SUFFIXES):
        if suffix in SCENE_SUFFIXES:
            continue
        path = _TMP / f"seed{suffix}"
        try:
            image.save(path)
        except ValueError:
            continue  # a format this OpenImageIO cannot write
        (folder / f"seed{suffix}").write_bytes(bytes([i]) + path.read_bytes())


def main() -> None:
    for arg in sys.argv[1:]:
        if not arg.startswith("-") and os.path.isdir(arg) and not os.listdir(arg):
            seed_corpus(Path(arg))
    atheris.Setup(sys.argv, test_one_input)
    atheris.Fuzz()


if __name__ == "__main__":
    main()
