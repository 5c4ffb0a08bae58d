"""The bad-input table (issue 7, item 4): every kind of bad input to the scene builder, the
camera, the materials, the image loader, ``dualight.render`` and ``dualight.radiosity.solve``
raises a clear Python exception whose message names the problem.

Each row is one kind of bad input: ``(id, call, exception type, message regex)``. The table
collects the cases scattered over the area tests (``test_scene``, ``test_image``,
``test_radiosity``, ...) and extends them; the rows marked ``# fixed`` used to crash with an
unrelated message, hang, or be accepted silently (see the commit that added this file). The file
rows cover images (``dualight.Image.load``) and scene files (``dualight.load_obj``,
``dualight.load_mitsuba_xml``, ``dualight.save_mitsuba_xml``; more cases in ``test_io.py``).

``test_table_is_large_enough`` pins the count (the issue asks for at least 20 kinds) and prints
it; ``test_valid_calls_pass`` is the control: the same calls with the bad argument put right do
not raise, so each row fails for its bad argument and not for something else in the call.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import dualight
from dualight import radiosity, scenes

QV = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float64)
QF = np.array([[0, 1, 2, 3]])
CAM = dict(origin=(0.5, 0.5, 2.0), target=(0.5, 0.5, 0.0), fov=40.0, resolution=(8, 8))


def _add(vertices: Any = QV, faces: Any = QF, **kw: Any) -> Callable[[], Any]:
    return lambda: dualight.Scene().add_mesh(vertices, faces, **kw)


def _quiet(call: Callable[[], Any]) -> Callable[[], Any]:
    """``call`` with its UserWarnings (such as 'dropped 1 zero-area triangle') silenced."""

    def run() -> Any:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)
            return call()

    return run


def _camera(**kw: Any) -> Callable[[], Any]:
    return lambda: dualight.Camera(**{**CAM, **kw})


def _lit(camera: bool = True, emission: tuple[float, float, float] = (1, 1, 1)) -> dualight.Scene:
    scene = dualight.Scene(camera=dualight.Camera(**CAM) if camera else None)
    scene.add_mesh(QV, QF, emission=emission)
    return scene


def _render(method: str = "path", scene: Callable[[], Any] = _lit, **kw: Any) -> Callable[[], Any]:
    return lambda: dualight.render(scene(), method, **{"spp": 1, "progress": False, **kw})


def _mirror_scene() -> dualight.Scene:
    scene = _lit()
    scene.add_mesh(QV + [0, 0, -1], QF, material=dualight.Mirror())
    return scene


def _solve(method: str = "direct", scene: Callable[[], Any] | None = None, **kw: Any):
    def run() -> Any:
        s = scene() if scene is not None else scenes.furnace(0.5, 1.0, (8, 8))
        return radiosity.solve(s, method, **{"max_edge": 0.5, **kw})

    return run


def _write(tmp: Path, name: str, data: bytes) -> Path:
    path = tmp / name
    path.write_bytes(data)
    return path


def _truncated(tmp: Path, suffix: str) -> Path:
    good = dualight.Image(np.full((16, 16, 3), 0.5)).save(tmp / f"good{suffix}")
    data = good.read_bytes()
    return _write(tmp, f"truncated{suffix}", data[: len(data) // 2])


# (id, call, exception, message). Calls taking a path get the test's tmp_path.
SCENE_BUILDER = [
    ("vertex NaN", _add(QV * np.nan), ValueError, "vertex 0 is not finite"),
    ("vertex Inf", _add(np.where(QV == 1, np.inf, QV)), ValueError, "not finite"),
    ("vertex beyond 1e30", _add(QV * 1e31), ValueError, "beyond 1e12"),
    # fixed (issue 18, item 6): accepted up to 1e30; from about 5e12 light tracing and BDPT
    # render wrong, from 1.4e9 triangle normals overflowed (now computed in double there)
    ("vertex at 2e13", _add(QV * 2e13), ValueError, r"beyond 1e12 .*areas and pdfs"),
    ("vertices (V, 2)", _add(QV[:, :2]), ValueError, r"vertices must have shape \(V, 3\)"),
    ("vertices empty", _add(np.zeros((0, 3))), ValueError, r"shape \(V, 3\) with V > 0"),
    ("vertices not numbers", _add([["a", "b", "c"]] * 4), ValueError, "vertices must be"),  # fixed
    # fixed (issue 18): the imaginary part was dropped, datetimes were taken as seconds
    ("vertices complex", _add(QV + 1j), ValueError, "real numbers, got complex128"),
    ("vertices datetime64", _add(QV.astype("datetime64[s]")), ValueError, "got datetime64"),
    ("face index too large", _add(faces=[[0, 1, 7]]), ValueError, "out of range for 4 vertices"),
    ("face index negative", _add(faces=[[0, -1, 2]]), ValueError, "out of range"),
    ("faces (F, 2)", _add(faces=[[0, 1]]), ValueError, r"\(F, 3\) or \(F, 4\)"),
    ("faces empty", _add(faces=np.zeros((0, 3), int)), ValueError, "faces is empty"),
    ("faces fractional", _add(faces=[[0, 1.5, 2]]), ValueError, "integer vertex indices"),
    ("faces not numbers", _add(faces=[["a", "b", "c"]]), ValueError, "integer vertex"),  # fixed
    ("zero-area triangle", _add(faces=[[0, 1, 1]]), ValueError, "zero-area triangle"),
    (
        "every triangle dropped",
        _quiet(_add(faces=[[0, 1, 1]], degenerate="drop")),
        ValueError,
        "every triangle has zero area",
    ),
    ("degenerate option", _add(degenerate="ignore"), ValueError, "degenerate must be"),  # fixed
    ("albedo > 1", _add(reflectance=(0.5, 1.2, 0.5)), ValueError, "reflectance must be <= 1"),
    ("albedo < 0", _add(reflectance=(-0.1, 0.5, 0.5)), ValueError, "reflectance must be >= 0"),
    ("albedo NaN", _add(reflectance=(0.5, np.nan, 0.5)), ValueError, "reflectance must be finite"),
    ("albedo 2 numbers", _add(reflectance=(0.5, 0.5)), ValueError, "reflectance must be 3 numbers"),
    ("emission < 0", _add(emission=(1, -1, 1)), ValueError, "emission must be >= 0"),
    ("emission Inf", _add(emission=(1, np.inf, 1)), ValueError, "emission must be finite"),
    ("emission a word", _add(emission="bright"), ValueError, "emission must be 3 numbers"),  # fixed
    # fixed (issue 18, item 6): rendered black (above 3.4e38), 0 by light tracing and BDPT
    # (1.8e34 up), an Inf variance (1e30), "no emitter" (1e-46)
    ("emission 1e39", _add(emission=(1e39,) * 3), ValueError, r"0 or within \[1e-12, 1e12\]"),
    ("emission 1e30", _add(emission=(1, 1e30, 1)), ValueError, "squares of such values"),
    ("emission 1e-46", _add(emission=(1e-46, 0, 0)), ValueError, r"within \[1e-12, 1e12\]"),
    ("material not one", _add(material="glass"), TypeError, "material must be a dualight"),
    (
        "material and albedo",
        _add(reflectance=(0.2,) * 3, material=dualight.Mirror()),
        ValueError,
        "not both",
    ),
    ("mirror albedo > 1", lambda: dualight.Mirror((2, 2, 2)), ValueError, r"in \[0, 1\]"),
    ("diffuse albedo < 0", lambda: dualight.Diffuse((-1, 0, 0)), ValueError, r"in \[0, 1\]"),
    ("ior 0", lambda: dualight.Dielectric(ior=0.0), ValueError, "ior must be finite and > 0"),
    ("ior NaN", lambda: dualight.Dielectric(ior=np.nan), ValueError, "ior must be finite"),
    # fixed (issue 18, item 6): accepted, then infinite or zero in the core's float32
    ("ior 1e39", lambda: dualight.Dielectric(ior=1e39), ValueError, r"within \[1e-18, 1e18\]"),
    ("ior 1e-300", lambda: dualight.Dielectric(ior=1e-300), ValueError, "square it in float32"),
    ("scene camera a string", lambda: dualight.Scene(camera="cam"), TypeError, "camera must be"),
]

CAMERA = [
    ("fov a bool", _camera(fov=True), ValueError, "fov must be a number"),  # fixed: 1 degree
    ("resolution zero", _camera(resolution=(0, 8)), ValueError, "resolution"),
    ("resolution negative", _camera(resolution=(-4, 4)), ValueError, "resolution"),
    ("resolution fractional", _camera(resolution=(8.5, 8)), ValueError, "resolution"),
    ("resolution one number", _camera(resolution=(8,)), ValueError, "resolution"),
    (
        "resolution an int",
        _camera(resolution=32),
        ValueError,  # fixed: "'int' object is not iterable"
        r"resolution must be a pair.*resolution=\(32, 32\)",
    ),
    ("resolution bools", _camera(resolution=(True, 8)), ValueError, "resolution"),  # fixed
    ("fov 0", _camera(fov=0), ValueError, r"fov must be in \(0, 180\)"),
    ("fov 180", _camera(fov=180), ValueError, r"fov must be in \(0, 180\)"),
    # fixed (issue 18, item 6): accepted, then refused by the core when rendering
    ("fov 179.9999999", _camera(fov=179.9999999), ValueError, r"rounds to 180.0 degrees"),
    # fixed (issue 18, item 6): "camera up is parallel to the view" (the core's float32 overflowed)
    ("camera origin 3e19", _camera(origin=(0.5, 0.5, 3e19)), ValueError, "beyond 1e12"),
    ("camera up 1e30", _camera(up=(0, 1e30, 0)), ValueError, "camera up .* beyond 1e12"),
    ("fov negative", _camera(fov=-5), ValueError, "fov"),
    ("fov NaN", _camera(fov=np.nan), ValueError, "fov"),
    ("fov a word", _camera(fov="wide"), ValueError, "fov must be a number"),  # fixed
    ("look-at equals eye", _camera(target=CAM["origin"]), ValueError, "target equals its origin"),
    ("up parallel to view", _camera(up=(0, 0, 1)), ValueError, "parallel"),
    ("up zero", _camera(up=(0, 0, 0)), ValueError, "zero or parallel"),
    ("eye NaN", _camera(origin=(np.nan, 0, 0)), ValueError, "origin must be finite"),
]

FILES = [
    (
        "image save path with a NUL byte",  # fixed: the core wrote the file named up to it
        lambda t: dualight.Image(np.full((4, 4, 3), 0.5)).save(t / "a\0b.png"),
        ValueError,
        "NUL byte",
    ),
    *(
        (
            f"image exposure {name}",  # fixed: nan was accepted, 1e6 an OverflowError (issue 18)
            lambda t, e=e: dualight.Image(np.full((4, 4, 3), 0.5)).save(t / "a.png", exposure=e),
            error,
            "exposure must be a",
        )
        for name, e, error in [
            ("nan", float("nan"), ValueError),
            ("1e6", 1e6, ValueError),
            ("-inf", float("-inf"), ValueError),
            ("a bool", True, TypeError),
            ("a string", "2", TypeError),
        ]
    ),
    (
        "tonemap exposure 1e6",
        lambda t: dualight.Image(np.full((4, 4, 3), 0.5)).tonemap(1e6),
        ValueError,
        "exposure must be a finite number of stops",
    ),
    (
        "image missing",
        lambda t: dualight.Image.load(t / "missing.exr"),
        FileNotFoundError,
        "no such image file",
    ),
    ("image is a directory", lambda t: dualight.Image.load(t), FileNotFoundError, "no such image"),
    (
        "image not an image",
        lambda t: dualight.Image.load(_write(t, "a.exr", b"plain text")),
        ValueError,
        "cannot read image",
    ),
    (
        "image empty file",
        lambda t: dualight.Image.load(_write(t, "a.png", b"")),
        ValueError,
        "cannot read image",
    ),
    (
        "image truncated EXR",
        lambda t: dualight.Image.load(_truncated(t, ".exr")),
        ValueError,
        "cannot (read|decode) image",
    ),
    (
        "image truncated PNG",
        lambda t: dualight.Image.load(_truncated(t, ".png")),
        ValueError,
        "cannot (read|decode) image",
    ),
    (
        "save to missing folder",
        lambda t: dualight.Image(np.zeros((2, 2, 3))).save(t / "no" / "a.exr"),
        FileNotFoundError,
        "directory does not exist",
    ),
    (
        "save unknown format",
        lambda t: dualight.Image(np.zeros((2, 2, 3))).save(t / "a.xyz"),
        ValueError,
        "cannot write",
    ),
    ("image 2 channels", lambda t: dualight.Image(np.zeros((4, 4, 2))), ValueError, "H x W x 3"),
]

XML_LIGHT = '<shape type="rectangle"><emitter type="area"><rgb name="radiance" value="1"/>'


def _scene_xml(tmp: Path, body: str) -> Path:
    xml = f'<scene version="3.0.0">{XML_LIGHT}</emitter></shape>{body}</scene>'
    return _write(tmp, "s.xml", xml.encode())


NESTED_BSDF = '<bsdf type="twosided" id="b">'
PLY_CLAIMING_1E9 = (
    b"ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\nproperty float y\n"
    b"property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
    b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
)


def _xml_with_ply(tmp: Path, ply: bytes) -> Path:
    _write(tmp, "m.ply", ply)
    return _scene_xml(tmp, '<shape type="ply"><string name="filename" value="m.ply"/></shape>')


def _obj_with_kd(tmp: Path, kd: str) -> Path:
    _write(tmp, "a.mtl", f"newmtl m\nKd {kd}\n".encode())
    return _write(tmp, "a.obj", b"mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n")


SCENE_FILES = [
    ("obj missing", lambda t: dualight.load_obj(t / "a.obj"), FileNotFoundError, "no such OBJ"),
    (
        "obj names a missing mtl",
        lambda t: dualight.load_obj(_write(t, "a.obj", b"mtllib gone.mtl\nv 0 0 0\n")),
        FileNotFoundError,
        "no such MTL file",
    ),
    (
        "obj face index 0",  # fixed: said "every triangle has zero area" (issue 18)
        lambda t: dualight.load_obj(_write(t, "a.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n")),
        ValueError,
        r"line 4: face index 0 .*OBJ indices start at 1",
    ),
    (
        "obj relative index before the first vertex",  # fixed: resolved from the file's end
        lambda t: dualight.load_obj(_write(t, "a.obj", b"v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n")),
        ValueError,
        r"line 3: relative index -3 .*before the first 'v' \(2 read so far\)",
    ),
    (
        "ply declaring 1e9 vertices",  # fixed: said "no triangles or polygons" (issue 18)
        lambda t: dualight.load_mitsuba_xml(_xml_with_ply(t, PLY_CLAIMING_1E9)),
        ValueError,
        r"declares 1000000000 'vertex' elements, more than its 26-byte body can hold",
    ),
    (
        "xml nested 2000 deep",  # fixed: RecursionError (issue 18)
        lambda t: dualight.load_mitsuba_xml(
            _scene_xml(t, NESTED_BSDF * 2000 + '<bsdf type="diffuse"/>' + "</bsdf>" * 2000)
        ),
        ValueError,
        "nested more than 64 deep",
    ),
    (
        "obj without faces",
        lambda t: dualight.load_obj(_write(t, "a.obj", b"plain text\n")),
        ValueError,
        "has no triangles",
    ),
    (
        "obj binary",
        lambda t: dualight.load_obj(_write(t, "a.obj", bytes(range(128, 256)))),
        ValueError,
        "cannot read OBJ file",
    ),
    (
        "obj Kd > 1",
        lambda t: dualight.load_obj(_obj_with_kd(t, "2 2 2")),
        ValueError,
        r"Kd.*\[0, 1\]",
    ),
    (
        "xml missing",
        lambda t: dualight.load_mitsuba_xml(t / "a.xml"),
        FileNotFoundError,
        "no such Mitsuba XML file",
    ),
    (
        "xml malformed",
        lambda t: dualight.load_mitsuba_xml(_write(t, "a.xml", b"<scene><shape></scene>")),
        ValueError,
        "not well-formed XML",
    ),
    (
        "xml unsupported shape",
        lambda t: dualight.load_mitsuba_xml(_scene_xml(t, '<shape type="cylinder"/>')),
        ValueError,
        "shape type 'cylinder' is not supported",
    ),
    (
        "xml unsupported bsdf",
        lambda t: dualight.load_mitsuba_xml(
            _scene_xml(t, '<shape type="cube"><bsdf type="hair"/></shape>')
        ),
        ValueError,
        "BSDF type 'hair' is not supported",
    ),
    (
        "xml NaN",
        lambda t: dualight.load_mitsuba_xml(
            _scene_xml(t, '<shape type="sphere"><float name="radius" value="nan"/></shape>')
        ),
        ValueError,
        "not finite",
    ),
    (
        "xml names a missing ply",
        lambda t: dualight.load_mitsuba_xml(
            _scene_xml(t, '<shape type="ply"><string name="filename" value="x.ply"/></shape>')
        ),
        FileNotFoundError,
        "no such PLY file",
    ),
    (
        "save xml to missing folder",
        lambda t: dualight.save_mitsuba_xml(_lit(), t / "no" / "a.xml"),
        FileNotFoundError,
        "directory does not exist",
    ),
]
FILES += SCENE_FILES

RENDER = [
    ("scene not a Scene", lambda: dualight.render("scene"), TypeError, "scene must be"),
    (
        "empty scene",
        _render(scene=lambda: dualight.Scene(dualight.Camera(**CAM))),
        ValueError,
        "scene is empty",
    ),
    ("no light", _render(scene=lambda: _lit(emission=(0, 0, 0))), ValueError, "no emitter"),
    ("no camera", _render(scene=lambda: _lit(camera=False)), ValueError, "no camera"),
    ("camera not a Camera", _render(camera="cam"), TypeError, "camera must be"),
    ("unknown method", _render("photon_mapping"), ValueError, "unknown method 'photon_mapping'"),
    ("spp 0", _render(spp=0), ValueError, "spp must be an integer >= 1"),
    ("spp negative", _render(spp=-3), ValueError, "spp must be"),
    ("spp fractional", _render(spp=2.5), ValueError, "spp must be"),
    ("spp >= 2**32", _render(spp=1 << 32), ValueError, "spp must be < 2"),
    ("spp a bool", _render(spp=True), ValueError, "spp must be an integer"),
    ("spp numpy bool", _render(spp=np.True_), ValueError, "spp must be an integer"),
    ("no budget", _render(spp=None), ValueError, "spp, time_limit"),
    ("time_limit negative", _render(time_limit=-1.0), ValueError, "time_limit must be"),
    ("time_limit NaN", _render(time_limit=np.nan), ValueError, "time_limit must be"),
    (
        "time_limit Inf alone",
        _render(spp=None, time_limit=np.inf),
        ValueError,  # fixed: hung
        "time_limit must be a finite",
    ),
    ("time_limit a string", _render(time_limit="1"), ValueError, "time_limit must be"),  # fixed
    ("max_depth -2", _render(max_depth=-2), ValueError, "max_depth must be"),
    ("max_depth fractional", _render(max_depth=1.5), ValueError, "max_depth must be"),
    ("max_depth >= 2**31", _render(max_depth=1 << 31), ValueError, "max_depth must be"),  # fixed
    ("rr_depth 0", _render(rr_depth=0), ValueError, "rr_depth must be"),
    ("rr_depth >= 2**31", _render(rr_depth=1 << 31), ValueError, "rr_depth must be"),  # fixed
    ("seed negative", _render(seed=-1), ValueError, "seed must be"),
    ("seed a bool", _render(seed=True), ValueError, "seed must be an integer"),
    ("max_depth a bool", _render(max_depth=True), ValueError, "max_depth must be an integer"),
    ("threads a bool", _render(threads=True), ValueError, "threads must be an integer"),
    ("seed NaN", _render(seed=np.nan), ValueError, "seed must be an integer"),
    ("seed >= 2**64", _render(seed=1 << 64), ValueError, "seed must be an integer <="),  # fixed
    ("threads 0", _render(threads=0), ValueError, "threads must be"),
    ("threads negative", _render(threads=-1), ValueError, "threads must be"),
    (
        "unknown sampler",
        _render(sampler="halton"),
        ValueError,
        "sampler must be one of 'independent', 'sobol', got 'halton'",
    ),
    (
        "unknown sampler (pssmlt)",
        _render("pssmlt", sampler="halton"),
        ValueError,  # the Metropolis methods use none, but the name is checked
        "sampler must be one of",
    ),
    ("unknown heuristic", _render("bdpt", heuristic="cutoff"), ValueError, "heuristic must be one"),
    ("heuristic for path", _render(heuristic="balance"), ValueError, "heuristic applies"),
    (
        "strategy images unbounded",
        _render("bdpt", strategy_images=True),
        ValueError,
        "bounded max_depth",
    ),
    ("strategy images for path", _render(strategy_images=True), ValueError, "bdpt' only"),
    (
        "light_pool 0",
        _render("bdpt", light_pool=0),
        ValueError,
        "light_pool must be an integer >= 1",
    ),
    (
        "light_pool 17",
        _render("bdpt", light_pool=17),
        ValueError,
        "light_pool must be an integer <= 16",
    ),
    ("light_pool fractional", _render("bdpt", light_pool=2.5), ValueError, "light_pool must be"),
    ("light_pool a bool", _render("bdpt", light_pool=True), ValueError, "light_pool must be"),
    ("light_pool for path", _render(light_pool=4), ValueError, "light_pool applies"),
    ("progress not callable", _render(progress="yes"), TypeError, "progress must be"),
    ("mutations for path", _render(mutations_per_pixel=4), ValueError, "mutations_per_pixel"),
    (
        "mutations_per_pixel 2**32",  # fixed: pybind11's overload list (issue 18)
        _render("pssmlt", mutations_per_pixel=2**32),
        ValueError,
        r"mutations_per_pixel must be an integer <= 4294967295",
    ),
    ("mmlt unbounded depth", _render("mmlt"), ValueError, "bounded max_depth"),
    (
        "max_depth 2**31 - 1",  # fixed: MMLT took GBs, deaf to Ctrl-C (issue 18)
        _render("mmlt", max_depth=2**31 - 1),
        ValueError,
        r"max_depth must be an integer <= 1024 \(longer paths",
    ),
    (
        "rr_depth 2**31 - 1",  # fixed: a 0.99 furnace ran 48 s past time_limit=2 (issue 18)
        _render(rr_depth=2**31 - 1, time_limit=2.0, spp=None),
        ValueError,
        r"rr_depth must be an integer <= 1024",
    ),
    (
        "chains 10**7",  # fixed: minutes of start-up, deaf to Ctrl-C (issue 18)
        _render("mlt", mlt={"chains": 10**7}),
        ValueError,
        r"chains must be an integer <= 1048576 \(each chain",
    ),
    (
        "bootstrap 2**31",  # fixed: 16 GB of bootstrap weights (issue 18)
        _render("pssmlt", mlt={"bootstrap": 2**31}),
        ValueError,
        r"bootstrap must be an integer <= 67108864",
    ),
    ("mlt options for path", _render(mlt={"chains": 4}), ValueError, "MLT methods only"),
    (
        "mlt options not a dict",
        _render("pssmlt", mlt=[("chains", 4)]),
        TypeError,  # fixed
        "mlt must be a dict",
    ),
    (
        "mlt key misspelled",
        _render("pssmlt", mlt={"chainz": 4}),
        TypeError,  # fixed
        "unknown option 'chainz' for PssmltOptions; valid: mutations_per_pixel, ",
    ),
    (
        "mlt key of another method",
        _render("pssmlt", mlt={"importance": "flattened"}),
        TypeError,
        "unknown option 'importance' for PssmltOptions",
    ),  # fixed
    (
        "mlt key shadowing render's",
        _render("mlt", mlt={"max_depth": 3}),
        TypeError,  # fixed
        "mlt option 'max_depth' is set by render's own keywords",
    ),
    (
        "mlt chains negative",
        _render("pssmlt", mlt={"chains": -1}),
        ValueError,  # fixed
        "chains must be an integer >= 1",
    ),
    ("mlt chains 0", _render("mlt", mlt={"chains": 0}), ValueError, "chains must be"),
    ("mlt bootstrap 0", _render("pssmlt", mlt={"bootstrap": 0}), ValueError, "bootstrap must be"),
    (
        "mlt sigma 2",
        _render("pssmlt", mlt={"sigma": 2.0}),
        ValueError,
        r"sigma must be in \(0, 1\)",
    ),
    (
        "mlt large step > 1",
        _render("pssmlt", mlt={"large_step_probability": 1.5}),
        ValueError,
        "large_step_probability",
    ),
    (
        "mlt weight negative",
        _render("mlt", mlt={"lens_perturbation": -1.0}),
        ValueError,
        "lens_perturbation must be >= 0, got -1.0",
    ),
    (
        "mlt no bidirectional",
        _render("mlt", mlt={"bidirectional": 0.0}),
        ValueError,
        "bidirectional must be > 0",
    ),
    (
        "mlt angles",
        _render("mlt", mlt={"angle_min": 0.2, "angle_max": 0.1}),
        ValueError,
        "angle_min < angle_max",
    ),
    (
        "mlt importance",
        _render("mlt", mlt={"importance": "fancy"}),
        ValueError,
        "importance must be one of 'luminance', 'flattened', got 'fancy'",
    ),
]

SOLVE = [
    (
        "direct solver 20,000 patches",  # fixed: refused after the form factors (issue 18)
        _solve(max_edge=0.01),
        ValueError,
        r"dense n x n matrix: \d+ patches is more than 12000",
    ),
    (
        "solve max_edge 1e-100",  # fixed: the int64 cast overflowed, 32 patches (issue 18)
        _solve(max_edge=1e-100),
        ValueError,
        "more than 50 million patches",
    ),
    ("solve scene not a Scene", _solve(scene=lambda: "scene"), TypeError, "scene must be"),  # fixed
    ("solve camera not a Camera", _solve(camera="cam"), TypeError, "camera must be"),  # fixed
    (
        "solve empty scene",
        _solve(scene=lambda: dualight.Scene(dualight.Camera(**CAM))),
        ValueError,
        "scene is empty",
    ),  # fixed: said "no emitter"
    ("solve no light", _solve(scene=lambda: _lit(emission=(0, 0, 0))), ValueError, "no emitter"),
    ("solve no camera", _solve(scene=lambda: _lit(camera=False)), ValueError, "needs a camera"),
    ("solve specular scene", _solve(scene=_mirror_scene), ValueError, "assumes diffuse surfaces"),
    ("unknown solver", _solve("cholesky"), ValueError, "unknown method 'cholesky'"),
    ("tol 0", _solve("jacobi", tol=0.0), ValueError, "tol must be"),
    ("tol negative", _solve("gauss_seidel", tol=-1e-6), ValueError, "tol must be"),
    ("tol NaN", _solve("southwell", tol=np.nan), ValueError, "tol must be"),
    ("tol a word", _solve("jacobi", tol="small"), ValueError, "tol must be a finite number"),
    ("max_iter 0", _solve("jacobi", max_iter=0), ValueError, "max_iter must be"),
    ("max_iter 0 direct", _solve("direct", max_iter=0), ValueError, "max_iter must be"),  # fixed
    ("max_iter fractional", _solve("jacobi", max_iter=2.5), ValueError, "max_iter must be"),
    ("max_iter a bool", _solve("jacobi", max_iter=True), ValueError, "max_iter must be"),
    (
        "hierarchical max_iter 0",
        _solve("hierarchical", max_iter=0),
        ValueError,  # fixed
        "max_iter must be",
    ),
    ("seed negative (solve)", _solve(seed=-1), ValueError, "seed must be"),  # fixed
    ("max_edge 0", _solve(max_edge=0.0), ValueError, "max_edge must be a positive number"),
    ("max_edge NaN", _solve(max_edge=np.nan), ValueError, "max_edge must be"),
    ("max_area negative", _solve(max_edge=None, max_area=-1.0), ValueError, "max_area must be"),
    ("quadrature 2", _solve(quadrature=2), ValueError, "quadrature must be 1, 3 or 7"),
    (
        "shadow_rays negative",
        _solve(shadow_rays=-1),
        ValueError,
        "shadow_rays must be an integer >= 0",
    ),
    ("solve threads negative", _solve(threads=-1), ValueError, "threads must be an integer >= 0"),
    ("window outside image", _solve(window=(0, 0, 100, 100)), ValueError, "not inside"),
    ("oracle unknown", _solve("hierarchical", oracle="psychic"), ValueError, "oracle must be"),
    ("epsilon negative", _solve("hierarchical", epsilon=-1.0), ValueError, "epsilon must be > 0"),
    (
        "max_links 0",
        _solve("hierarchical", max_links=0),
        ValueError,
        "max_links must be an integer >= 1",
    ),
]

TABLE = SCENE_BUILDER + CAMERA + RENDER + SOLVE


@pytest.mark.parametrize(
    ("call", "error", "message"), [r[1:] for r in TABLE], ids=[r[0] for r in TABLE]
)
def test_bad_input_raises_a_clear_error(call, error, message) -> None:
    with pytest.raises(error, match=message):
        call()


@pytest.mark.parametrize(
    ("call", "error", "message"), [r[1:] for r in FILES], ids=[r[0] for r in FILES]
)
def test_bad_file_raises_a_clear_error(tmp_path, call, error, message) -> None:
    with pytest.raises(error, match=message):
        call(tmp_path)


def test_table_is_large_enough() -> None:
    kinds = len(TABLE) + len(FILES)
    ids = [r[0] for r in TABLE + FILES]
    assert len(set(ids)) == kinds, "duplicate row ids"
    print(
        f"\nbad-input kinds: {kinds} ({len(SCENE_BUILDER)} scene builder and materials, "
        f"{len(CAMERA)} camera, {len(FILES)} files, {len(RENDER)} render, {len(SOLVE)} solve)"
    )
    assert kinds >= 20


@pytest.mark.parametrize(
    "call",
    [
        pytest.param(_add(), id="add_mesh"),
        pytest.param(
            _add(faces=[[0, 1, 2], [0, 1, 1]], degenerate="drop"),
            id="drop",
            marks=pytest.mark.filterwarnings("ignore:.*zero-area:UserWarning"),
        ),
        pytest.param(_camera(), id="camera"),
        pytest.param(_render(), id="render"),
        pytest.param(
            _render(
                "bdpt", max_depth=3, strategy_images=True, heuristic="balance", seed=(1 << 64) - 1
            ),
            id="bdpt",
        ),
        pytest.param(_render(spp=None, time_limit=0.05), id="time_limit"),
        pytest.param(
            _render("pssmlt", max_depth=3, mlt={"chains": 4, "bootstrap": 64, "direct_spp": 1}),
            id="pssmlt",
        ),
        pytest.param(
            _render(
                "mlt", max_depth=3, mlt={"chains": 4, "bootstrap": 64, "importance": "flattened"}
            ),
            id="mlt",
        ),
        pytest.param(_solve("jacobi", tol=1e-3, max_iter=50), id="jacobi"),
        pytest.param(_solve("direct", max_iter=1, seed=3), id="direct"),
    ],
)
def test_valid_calls_pass(call) -> None:
    """Control: the table's helpers with good arguments succeed."""
    call()


@pytest.mark.parametrize("method", ["pssmlt", "mmlt", "mlt"])
def test_mlt_reaches_every_core_option_render_does_not_set(method: str) -> None:
    """``mlt=`` passes every field of the method's core options on (each here at its core
    default), except those ``render`` sets from its own keywords or the method's name: those
    are refused (the negative control), as a misspelled key is."""
    from dualight.methods import ESTIMATORS

    options = ESTIMATORS[method].options
    defaults = options()
    small = {"chains": 4, "bootstrap": 64, "direct_spp": 1}
    refused = set()
    for key in options._fields:
        try:
            _render(method, max_depth=3, mlt={**small, key: getattr(defaults, key)})()
        except TypeError:
            refused.add(key)
    own = {"mutations_per_pixel", "max_depth", "rr_depth", "seed", "threads", "time_limit"}
    own |= {"skip_unneeded", "heuristic"} | ({"multiplexed"} if method != "mlt" else set())
    assert refused == own, refused ^ own
    with pytest.raises(TypeError, match="unknown option 'chainz'"):
        _render(method, max_depth=3, mlt={**small, "chainz": 4})()


N = np.int64


@pytest.mark.parametrize(
    "call",
    [
        pytest.param(_camera(resolution=(N(8), np.int32(8)), fov=np.float32(40)), id="camera"),
        pytest.param(
            _render(
                spp=N(2),
                max_depth=N(3),
                rr_depth=np.int32(2),
                seed=np.uint64(5),
                threads=N(1),
                time_limit=np.float64(30),
            ),
            id="render",
        ),
        pytest.param(
            _render(
                "pssmlt",
                max_depth=N(3),
                mutations_per_pixel=N(1),
                mlt={"chains": N(4), "bootstrap": N(64), "sigma": np.float32(0.02)},
            ),
            id="pssmlt",
        ),
        pytest.param(
            _solve(
                "jacobi",
                tol=np.float32(1e-3),
                max_iter=N(50),
                seed=N(1),
                threads=N(1),
                quadrature=N(3),
                shadow_rays=N(2),
                max_edge=np.float64(0.5),
            ),
            id="solve",
        ),
        pytest.param(
            _solve("hierarchical", max_iter=N(2), epsilon=np.float32(0.05), max_links=N(10**5)),
            id="hierarchical",
        ),
    ],
)
def test_numpy_numbers_are_numbers(call) -> None:
    """numpy integers (not bools) are accepted wherever ints are, numpy floats wherever
    floats are; what a render records of them is a plain Python number."""
    result = call()
    if isinstance(result, dualight.Image):
        stats = result.stats
        assert all(type(stats[k]) is int for k in ("spp", "max_depth", "rr_depth", "seed"))
