"""The path tracer in lanes (``render(..., lanes=...)``): a tile row's paths together in SIMD
lanes, built for SSE2, AVX2 and AVX-512. Its contract is the scalar tracer's image, bit for bit, on
every build the CPU runs; these tests hold it to that (images, variances and counters) across
samplers, strategies, path lengths, thread counts and image sizes, and check where it falls back."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import dualight
from dualight import scenes
from dualight._shapes import icosphere

ISAS = ("sse2", "avx2", "avx512")


def _runs(isa: str) -> bool:
    """Whether this CPU runs the lanes' build for `isa`."""
    try:
        dualight.render(scenes.cornell_box((16, 1)), spp=1, max_depth=2, progress=False, lanes=isa)
    except ValueError:
        return False
    return True


RUNNABLE = [isa for isa in ISAS if _runs(isa)]
COUNTERS = (
    "rays",
    "skipped_connections",
    "skipped_shadow_rays",
    "invalid_samples",
    "samples",
    "spp",
)


def _render(scene: dualight.Scene, lanes: str, **kw: Any) -> dualight.Image:
    options: dict[str, Any] = {"spp": 8, "max_depth": 8, "seed": 5, "threads": 1, "progress": False}
    return dualight.render(scene, "path", lanes=lanes, **{**options, **kw})


def _assert_same(a: dualight.Image, b: dualight.Image) -> None:
    assert np.array_equal(np.asarray(a), np.asarray(b))
    assert a.variance is not None and b.variance is not None
    assert np.array_equal(a.variance, b.variance)
    for key in COUNTERS:
        assert a.stats[key] == b.stats[key], key


def _smooth_glossy_box() -> dualight.Scene:
    """The Cornell box with two spheres of interpolated vertex normals, a rough conductor and a
    rough plastic: shading normals on BSDFs the lanes hand to the scalar code."""
    scene = scenes.cornell_box((40, 36))
    for centre, radius, material in [
        ((278.0, 120.0, 150.0), 90.0, dualight.RoughConductor()),
        ((380.0, 330.0, 350.0), 70.0, dualight.RoughPlastic()),
    ]:
        c = np.array(centre)
        vertices, faces = icosphere(c, radius, 2)
        normals = (vertices - c) / np.linalg.norm(vertices - c, axis=1, keepdims=True)
        scene.add_mesh(vertices, faces, material=material, normals=normals)
    return scene


CASES: list[tuple[str, Any, dict[str, Any]]] = [
    ("cornell", lambda: scenes.cornell_box((40, 36)), {}),
    ("cornell sobol", lambda: scenes.cornell_box((40, 36)), {"sampler": "sobol"}),
    ("cornell bsdf only", lambda: scenes.cornell_box((40, 36)), {"strategies": "bsdf"}),
    ("cornell light only", lambda: scenes.cornell_box((40, 36)), {"strategies": "light"}),
    ("cornell depth 1", lambda: scenes.cornell_box((40, 36)), {"max_depth": 1}),
    ("cornell depth 2", lambda: scenes.cornell_box((40, 36)), {"max_depth": 2}),
    ("cornell unbounded", lambda: scenes.cornell_box((40, 36)), {"max_depth": -1, "rr_depth": 2}),
    ("cornell two threads", lambda: scenes.cornell_box((40, 36)), {"threads": 2}),
    # A mirror and a glass sphere: delta lobes, refraction and its roulette scale.
    ("caustic box", lambda: scenes.cornell_box((40, 36), variant="caustics"), {"spp": 16}),
    (
        "caustic box deep",
        lambda: scenes.cornell_box((40, 36), variant="caustics", ior=1.33),
        {"max_depth": 16, "rr_depth": 3},
    ),
    # BSDFs the lanes hand to the scalar code lane by lane: rough conductor and dielectric and
    # a rough plastic floor; conductor and thin dielectric; textured materials.
    ("glossy box", lambda: scenes.cornell_box((40, 36), variant="glossy"), {}),
    ("coated box", lambda: scenes.cornell_box((40, 36), variant="coated"), {}),
    ("textured box", lambda: scenes.cornell_box((40, 36), variant="textured"), {}),
    ("glossy door", lambda: scenes.door_ajar((24, 20), variant="glossy"), {"spp": 16}),
    # Vertex normals: the shading normal's frame and cosines, the geometric normal's offsets.
    ("smooth box", lambda: scenes.cornell_box((40, 36), variant="smooth"), {}),
    (
        "smooth box sobol",
        lambda: scenes.cornell_box((17, 5), variant="smooth"),
        {"sampler": "sobol"},
    ),
    ("smooth glossy box", _smooth_glossy_box, {}),
    ("door", lambda: scenes.door_ajar((24, 20)), {"spp": 16}),
    ("rooms", lambda: scenes.rooms(3, resolution=(20, 18)), {}),
    # Emitters other than area lights (next-event estimation, the emission a path hits, the
    # environment it escapes to): point, spot, directional and constant sky, lane-wide; an
    # environment map and a textured area light, which the lanes hand to the scalar code lane by
    # lane; among them the Sobol sampler, each strategy alone and an unbounded depth.
    ("point light", lambda: scenes.cornell_box((40, 36), variant="point"), {}),
    ("spot light", lambda: scenes.cornell_box((40, 36), variant="spot"), {"sampler": "sobol"}),
    ("sun", lambda: scenes.cornell_box((40, 36), variant="sun"), {}),
    ("sky mis", lambda: scenes.cornell_box((40, 36), variant="sky"), {}),
    ("sky", lambda: scenes.cornell_box((40, 36), variant="sky"), {"strategies": "bsdf"}),
    ("sky light", lambda: scenes.cornell_box((40, 36), variant="sky"), {"strategies": "light"}),
    (
        "envmap",
        lambda: scenes.cornell_box((40, 36), variant="envmap"),
        {"max_depth": -1, "rr_depth": 2},
    ),
    ("textured lamp", lambda: scenes.cornell_box((40, 36), variant="lamp"), {}),
    # A convex enclosure: connections known unoccluded (no shadow rays), and with skip=False traced.
    ("furnace", lambda: scenes.furnace(0.7, 1.0, resolution=(17, 5)), {"max_depth": -1}),
    (
        "furnace, every shadow ray",
        lambda: scenes.furnace(0.7, 1.0, resolution=(17, 5)),
        {"skip": False},
    ),
]


@pytest.mark.skipif(not RUNNABLE, reason="this CPU runs no build of the lanes")
@pytest.mark.parametrize(("name", "build", "kw"), CASES, ids=[c[0] for c in CASES])
def test_lanes_render_the_scalar_image_bit_for_bit(
    name: str, build: Any, kw: dict[str, Any]
) -> None:
    scene = build()
    scalar = _render(scene, "off", **kw)
    assert scalar.stats["lanes"] == "off"
    for isa in RUNNABLE:
        lanes = _render(scene, isa, **kw)
        assert lanes.stats["lanes"] == isa
        _assert_same(scalar, lanes)
    # Negative control: the comparison tells another seed's image apart.
    other = _render(scene, RUNNABLE[-1], **{**kw, "seed": 6})
    assert not np.array_equal(np.asarray(other), np.asarray(scalar))


@pytest.mark.skipif(not RUNNABLE, reason="this CPU runs no build of the lanes")
def test_paths_of_no_segments_are_black_in_lanes_as_one_at_a_time() -> None:
    # max_depth 0: no ray, no radiance, whichever runs (the lanes skip their batch loop).
    scene = scenes.cornell_box((20, 18))
    scalar = _render(scene, "off", max_depth=0)
    assert not np.asarray(scalar).any() and scalar.stats["rays"] == 0
    for isa in RUNNABLE:
        _assert_same(scalar, _render(scene, isa, max_depth=0))
    # Negative control: one segment already sees the light.
    assert np.asarray(_render(scene, RUNNABLE[-1], max_depth=1)).any()


@pytest.mark.skipif(not RUNNABLE, reason="this CPU runs no build of the lanes")
def test_negative_control_a_reflectance_one_ulp_off_changes_the_image() -> None:
    scene = scenes.cornell_box((32, 16))
    nudged = scenes.cornell_box(
        (32, 16), reflectance_scale=float(np.nextafter(np.float32(1), np.float32(2)))
    )
    a = _render(scene, "off")
    b = _render(nudged, RUNNABLE[-1])
    assert not np.array_equal(np.asarray(a), np.asarray(b))


def test_auto_takes_avx512_else_avx2_where_the_cpu_has_it_and_says_so() -> None:
    image = _render(scenes.cornell_box((16, 16)), "auto")
    wide = [isa for isa in ("avx512", "avx2") if isa in RUNNABLE]
    if wide:
        assert image.stats["lanes"] == wide[0]
        assert "lanes_off_because" not in image.stats
    else:
        assert image.stats["lanes"] == "off"
        assert "AVX2" in image.stats["lanes_off_because"]


@pytest.mark.parametrize(
    "build",
    [
        lambda: scenes.door_ajar((24, 20), variant="glossy"),  # 3 % of its area lane by lane
        lambda: scenes.cornell_box((16, 16), variant="glossy"),  # 30 %
        lambda: scenes.cornell_box((16, 16), variant="textured"),  # 44 %
    ],
)
def test_auto_runs_lanes_whatever_share_other_materials_cover(build: Any) -> None:
    # Rough conductor, rough glass, rough plastic and textured materials go lane by lane through
    # the scalar code on any share of the scene (faster than one path at a time there too:
    # path_tracer_lanes.cpp), and the image is the one-path one.
    scene = build()
    image = _render(scene, "auto")
    wide = [isa for isa in ("avx512", "avx2") if isa in RUNNABLE]
    assert image.stats["lanes"] == (wide[0] if wide else "off")
    _assert_same(image, _render(scene, "off"))


@pytest.mark.parametrize("variant", ["point", "spot", "sun", "sky", "envmap", "lamp"])
def test_auto_runs_lanes_with_every_kind_of_emitter(variant: str) -> None:
    # Untextured area emitters run lane-wide, every other emitter lane by lane through the
    # scalar code (next_event.h): auto takes them all, and says which build ran.
    image = _render(scenes.cornell_box((16, 16), variant=variant), "auto")
    wide = [isa for isa in ("avx512", "avx2") if isa in RUNNABLE]
    assert image.stats["lanes"] == (wide[0] if wide else "off")
    assert ("lanes_off_because" in image.stats) == (not wide)


def test_guided_renders_run_one_path_at_a_time() -> None:
    image = dualight.render(
        scenes.cornell_box((16, 16)),
        spp=8,
        max_depth=4,
        progress=False,
        guiding={"max_records": 10_000},
    )
    assert image.stats["lanes"] == "off"


def test_lanes_is_checked_and_only_for_the_path_tracer() -> None:
    with pytest.raises(ValueError, match="lanes"):
        _render(scenes.cornell_box((16, 16)), "avx1024")
    with pytest.raises(ValueError, match="lanes"):
        dualight.render(scenes.cornell_box((16, 16)), "bdpt", spp=1, progress=False, lanes="off")
