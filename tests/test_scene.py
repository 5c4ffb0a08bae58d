"""Scene description: validation of every kind of bad input, and the compiled scene's rays."""

from __future__ import annotations

import numpy as np
import pytest

import dualight
from dualight import _core

QUAD_V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float64)
QUAD_F = np.array([[0, 1, 2, 3]])


@pytest.mark.parametrize(
    ("vertices", "faces", "kwargs", "message"),
    [
        (QUAD_V * np.nan, QUAD_F, {}, "not finite"),
        (np.where(QUAD_V == 1, np.inf, QUAD_V), QUAD_F, {}, "not finite"),
        (QUAD_V[:, :2], QUAD_F, {}, r"shape \(V, 3\)"),
        (np.zeros((0, 3)), QUAD_F, {}, r"shape \(V, 3\)"),
        (QUAD_V, np.array([[0, 1, 7]]), {}, "out of range"),
        (QUAD_V, np.array([[0, -1, 2]]), {}, "out of range"),
        (QUAD_V, np.array([[0, 1]]), {}, r"\(F, 3\) or \(F, 4\)"),
        (QUAD_V, np.zeros((0, 3), int), {}, "faces is empty"),
        (QUAD_V, np.array([[0, 1.5, 2]]), {}, "integer"),
        (QUAD_V, np.array([[0, 1, 1]]), {}, "zero-area"),
        (QUAD_V, QUAD_F, {"reflectance": (0.5, 1.2, 0.5)}, "<= 1"),
        (QUAD_V, QUAD_F, {"reflectance": (-0.1, 0.5, 0.5)}, ">= 0"),
        (QUAD_V, QUAD_F, {"reflectance": (0.5, np.nan, 0.5)}, "finite"),
        (QUAD_V, QUAD_F, {"reflectance": (0.5, 0.5)}, "3 numbers"),
        (QUAD_V, QUAD_F, {"emission": (1.0, -1.0, 1.0)}, ">= 0"),
        (QUAD_V, QUAD_F, {"emission": (1.0, np.inf, 1.0)}, "finite"),
        (QUAD_V * 1e31, QUAD_F, {}, "1e12"),
        (QUAD_V, QUAD_F, {"normals": np.ones((3, 3))}, r"shape \(4, 3\), one per vertex"),
        (QUAD_V, QUAD_F, {"normals": np.zeros((4, 3))}, "normal 0 is .* finite and non-zero"),
        (QUAD_V, QUAD_F, {"normals": np.full((4, 3), np.nan)}, "finite and non-zero"),
        (QUAD_V, QUAD_F, {"normals": np.full((4, 3), 1e300)}, "finite and non-zero"),
        (QUAD_V, QUAD_F, {"normals": np.full((4, 3), "a")}, "real numbers"),
    ],
)
def test_add_mesh_rejects_bad_input(vertices, faces, kwargs, message) -> None:
    scene = dualight.Scene()
    with pytest.raises(ValueError, match=message):
        scene.add_mesh(vertices, faces, **kwargs)
    assert scene.meshes == ()


def test_zero_area_triangles_can_be_dropped_with_a_warning() -> None:
    scene = dualight.Scene()
    faces = np.array([[0, 1, 2], [0, 1, 1], [0, 2, 3]])
    with pytest.warns(UserWarning, match="dropped 1 zero-area"):
        scene.add_mesh(QUAD_V, faces, degenerate="drop")
    assert scene.triangle_count == 2
    with pytest.raises(ValueError, match="every triangle has zero area"), pytest.warns(UserWarning):
        scene.add_mesh(QUAD_V, np.array([[0, 0, 1]]), degenerate="drop")


def test_quads_are_split_and_areas_kept() -> None:
    scene = dualight.Scene()
    scene.add_mesh(QUAD_V * 2.0, QUAD_F)
    mesh = scene.meshes[0]
    assert mesh.triangles.tolist() == [[0, 1, 2], [0, 2, 3]]
    np.testing.assert_allclose(mesh.areas, [2.0, 2.0])
    assert not mesh.vertices.flags.writeable


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"origin": (0, 0, 0), "target": (0, 0, 0)}, "target equals its origin"),
        ({"up": (0, 0, 1)}, "parallel"),
        ({"up": (0, 0, 0)}, "parallel"),
        ({"fov": 0}, "fov"),
        ({"fov": 180}, "fov"),
        ({"fov": float("nan")}, "fov"),
        ({"resolution": (0, 10)}, "resolution"),
        ({"resolution": (10.5, 10)}, "resolution"),
        ({"resolution": (10,)}, "resolution"),
        ({"origin": (np.nan, 0, 0)}, "finite"),
    ],
)
def test_camera_rejects_bad_input(kwargs, message) -> None:
    with pytest.raises(ValueError, match=message):
        dualight.Camera(**kwargs)


def test_render_rejects_unrenderable_scenes(quad) -> None:
    cam = dualight.Camera(origin=(0.5, 0.5, 2), target=(0.5, 0.5, 0), resolution=(8, 8))
    with pytest.raises(ValueError, match="empty"):
        dualight.render(dualight.Scene(camera=cam), progress=False)
    dark = dualight.Scene(camera=cam)
    dark.add_mesh(*quad)
    with pytest.raises(ValueError, match="no emitter"):
        dualight.render(dark, progress=False)
    no_camera = dualight.Scene()
    no_camera.add_mesh(*quad, emission=(1, 1, 1))
    with pytest.raises(ValueError, match="no camera"):
        dualight.render(no_camera, progress=False)
    dualight.render(no_camera, camera=cam, spp=1, progress=False)  # a camera argument suffices


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"method": "nope"}, "unknown method"),
        ({"spp": 0}, "spp"),
        ({"spp": 2.5}, "spp"),
        ({"spp": None}, "spp, time_limit"),
        ({"time_limit": -1.0}, "time_limit"),
        ({"max_depth": -2}, "max_depth"),
        ({"rr_depth": 0}, "rr_depth"),
        ({"seed": -1}, "seed"),
        ({"threads": 0}, "threads"),
    ],
)
def test_render_rejects_bad_options(tiny_scene, kwargs, message) -> None:
    with pytest.raises(ValueError, match=message):
        dualight.render(tiny_scene, progress=False, **kwargs)


def test_core_options_reject_misspelled_keywords() -> None:
    with pytest.raises(TypeError):
        _core.PathTracerOptions(sp=4)  # typo: an error, never a silent default


OPTIONS = (
    _core.PathTracerOptions,
    _core.LightTracerOptions,
    _core.BdptOptions,
    _core.PssmltOptions,
    _core.MltOptions,
    _core.FormFactorOptions,
    _core.HierarchicalOptions,
)


@pytest.mark.parametrize("cls", OPTIONS, ids=lambda c: c.__name__)
def test_core_options_bind_each_field_once(cls: type) -> None:
    """Every options class (src/bindings/options.h) takes exactly its ``_fields``, by keyword
    only, each a documented read-only property; its repr gives it back field for field."""
    options = cls()
    signature = cls.__init__.__doc__.split("\n")[0]
    for name in cls._fields:
        assert f" {name}: " in signature, name
        assert getattr(cls, name).__doc__, name
        with pytest.raises(AttributeError):
            setattr(options, name, getattr(options, name))
    enums = (_core.MisHeuristic, _core.SamplerType, _core.Strategies, _core.LaneIsa)
    names = {c.__name__: c for c in (*OPTIONS, *enums)}
    names["RefinementOracle"] = _core.RefinementOracle
    again = eval(repr(options), names)  # the repr is Python source
    assert repr(again) == repr(options) and repr(options).startswith(f"{cls.__name__}(")
    with pytest.raises(TypeError, match=f"unknown option 'nope' for {cls.__name__}; valid: "):
        cls(nope=1)
    with pytest.raises(TypeError):
        cls(1)  # keywords only


def test_core_options_convert_and_check_each_value() -> None:
    """Names stand for enum members and numpy scalars for numbers; a bad value is a ValueError
    naming its field (a bool's: a TypeError), and the struct's validate() checks the rest."""
    o = _core.MltOptions(
        chains=np.int64(4), heuristic="balance", importance="flattened", lens_subpath=np.float32(1)
    )
    assert (o.chains, o.heuristic, o.importance) == (4, _core.MisHeuristic.balance, "flattened")
    assert o.lens_subpath == 1.0 and _core.MltOptions().importance == "luminance"
    assert _core.MltOptions(skip_unneeded=np.bool_(False)).skip_unneeded is False
    for kwargs, error, message in [
        ({"chains": 0}, ValueError, "chains must be an integer >= 1, got 0"),
        ({"chains": 2.0}, ValueError, "chains must be an integer >= 1, got 2.0"),
        ({"seed": 1 << 64}, ValueError, "seed must be an integer <= 18446744073709551615"),
        ({"angle_max": float("nan")}, ValueError, "angle_max must be a finite number in"),
        ({"bidirectional": True}, ValueError, "bidirectional must be a finite number > 0"),
        ({"skip_unneeded": 1}, TypeError, "skip_unneeded must be True or False, got 1"),
        ({"heuristic": "cubic"}, ValueError, "heuristic must be one of 'power', 'balance'"),
        ({"angle_min": 0.2}, ValueError, "angle_min < angle_max"),  # validate()
        ({"mutations_per_pixel": 0}, ValueError, "give spp > 0 or a time_limit"),  # validate()
    ]:
        with pytest.raises(error, match=message):
            _core.MltOptions(**kwargs)


def test_compiled_scene_is_cached_and_rebuilt_on_change(tiny_scene) -> None:
    first = tiny_scene._compile()
    assert tiny_scene._compile() is first
    tiny_scene.add_mesh(QUAD_V + [0, 0, -1], QUAD_F)
    assert tiny_scene._compile() is not first
    assert tiny_scene._compile().triangle_count == 4


def _add_from_another_thread(scene: dualight.Scene, errors: list[BaseException]) -> None:
    """scene.add_mesh (then the camera setter) in a new thread, waited for; errors recorded."""
    import threading

    def change() -> None:
        for attempt in (
            lambda: scene.add_mesh(QUAD_V + [0, 0, -1], QUAD_F),
            lambda: setattr(scene, "camera", scene.camera),
        ):
            try:
                attempt()
            except Exception as error:  # noqa: BLE001 - recorded for the test to look at
                errors.append(error)

    thread = threading.Thread(target=change)
    thread.start()
    thread.join()


@pytest.mark.parametrize("what", ["render", "solve"])
def test_a_scene_is_frozen_while_it_is_rendered_or_solved(tiny_scene, what: str) -> None:
    # Issue 18: add_mesh from another thread during a render failed with "zip() argument 2 is
    # shorter than argument 1". A scene in use now refuses changes with a clear error, and
    # takes them again once the render or solve is over.
    tiny_scene.add_mesh(QUAD_V + [0, 0, -0.5], QUAD_F, reflectance=(0.5, 0.5, 0.5))
    errors: list[BaseException] = []

    def progress(done: int, total: int) -> None:
        if not errors:
            _add_from_another_thread(tiny_scene, errors)

    if what == "render":
        dualight.render(tiny_scene, spp=64, progress=progress)
    else:
        dualight.radiosity.solve(tiny_scene, "jacobi", max_edge=0.5, progress=progress)
    assert len(errors) == 2, errors
    for error in errors:
        assert isinstance(error, RuntimeError)
        assert "being rendered or solved" in str(error) and "frozen" in str(error)
    assert len(tiny_scene.meshes) == 2
    tiny_scene.add_mesh(QUAD_V + [0, 0, -1], QUAD_F)  # free again
    assert len(tiny_scene.meshes) == 3


def test_a_hierarchical_solver_refuses_a_scene_changed_after_it_was_built(tiny_scene) -> None:
    # Its steps work on the scene compiled when it was built; its solution would pair the new
    # meshes with the old elements.
    tiny_scene.add_mesh(QUAD_V + [0, 0, -0.5], QUAD_F, reflectance=(0.5, 0.5, 0.5))
    solver = dualight.radiosity.HierarchicalSolver(tiny_scene)
    solver.step()
    solver.solution()
    tiny_scene.add_mesh(QUAD_V + [0, 0, -1], QUAD_F)
    with pytest.raises(RuntimeError, match="meshes were added to the scene after"):
        solver.solution()


def test_a_pickled_scene_is_not_in_use(tiny_scene) -> None:
    import pickle

    with tiny_scene._in_use():
        copy = pickle.loads(pickle.dumps(tiny_scene))
    copy.add_mesh(QUAD_V + [0, 0, -1], QUAD_F)
    assert len(copy.meshes) == 2


def test_ray_triangle_conventions(tiny_scene) -> None:
    """Hits from both sides of a triangle, the hit distance, misses past edges and behind."""
    core = tiny_scene._compile()
    origins = np.array(
        [[0.25, 0.5, 2.0], [0.25, 0.5, -3.0], [1.5, 0.5, 2.0], [0.5, 0.5, 2.0], [0.6, 0.3, 1.0]]
    )
    directions = np.array([[0, 0, -1], [0, 0, 2], [0, 0, -1], [0, 0, 1], [0, 0, -0.5]])
    t, prim = core.intersect(origins, directions)
    np.testing.assert_allclose(t[[0, 1, 4]], [2.0, 1.5, 2.0], rtol=1e-6)
    assert prim[0] >= 0 and prim[1] >= 0 and prim[4] >= 0
    assert prim[2] == -1 and prim[3] == -1 and np.isinf(t[2]) and np.isinf(t[3])


def test_camera_rays_follow_mitsuba_conventions() -> None:
    """Row 0 is the top, x grows to the right, fov is the full angle along x."""
    cam = dualight.Camera(
        origin=(0, 0, 0), target=(0, 0, 1), up=(0, 1, 0), fov=90.0, resolution=(200, 100)
    )._compile()
    _, centre = cam.generate_ray(100.0, 50.0)
    np.testing.assert_allclose(centre, [0, 0, 1], atol=1e-6)
    _, right_edge = cam.generate_ray(200.0, 50.0)
    # Looking down +z with +y up, the right-hand side of the image is -x.
    np.testing.assert_allclose(right_edge, np.array([-1, 0, 1]) / np.sqrt(2), atol=1e-6)
    _, top_edge = cam.generate_ray(100.0, 0.0)
    np.testing.assert_allclose(top_edge, np.array([0, 0.5, 1]) / np.sqrt(1.25), atol=1e-6)


def _room_lit_from(light_faces: np.ndarray) -> dualight.Scene:
    """A floor under a light quad, seen from between them: the light emits down to the floor
    or, with its faces' order reversed, up into nothing."""
    cam = dualight.Camera(origin=(0.5, 0.5, 0.5), target=(0.5, 0.0, 0.5), up=(0, 0, 1))
    scene = dualight.Scene(camera=cam.with_resolution(8, 8))
    floor = np.array([[-1, 0, -1], [-1, 0, 2], [2, 0, 2], [2, 0, -1]], float)  # normal +y
    scene.add_mesh(floor, [[0, 1, 2, 3]], name="floor")
    light = np.array([[0.4, 1, 0.4], [0.6, 1, 0.4], [0.6, 1, 0.6], [0.4, 1, 0.6]], float)
    scene.add_mesh(light, light_faces, emission=(5, 5, 5), name="light")
    return scene


def test_an_emitter_facing_nothing_warns_naming_it() -> None:
    down, up = np.array([[0, 1, 2, 3]]), np.array([[3, 2, 1, 0]])
    lit = _room_lit_from(down)
    assert lit.emitters_facing_nothing() == []
    turned = _room_lit_from(up)
    assert turned.emitters_facing_nothing() == ["light"]
    with pytest.warns(UserWarning, match="emitter 'light' faces nothing.*reverse its faces"):
        image = dualight.render(turned, spp=1, progress=False)
    # the warning is right: its light leaves the box, nothing is lit
    assert float(np.asarray(image).max()) == 0.0
    assert float(np.asarray(dualight.render(lit, spp=1, progress=False)).max()) > 0.0
    # a light the camera sees (given to render) does not warn; turned away from it, it does
    seen = dualight.Scene()
    seen.add_mesh(QUAD_V, QUAD_F, emission=(1, 1, 1))
    front = dualight.Camera(origin=(0.5, 0.5, 2), target=(0.5, 0.5, 0), resolution=(4, 4))
    back = dualight.Camera(origin=(0.5, 0.5, -2), target=(0.5, 0.5, 0), resolution=(4, 4))
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error", UserWarning)
        dualight.render(seen, camera=front, spp=1, progress=False)
    assert seen.emitters_facing_nothing(back) == ["mesh0"]


def _builtin_scenes() -> list:
    import inspect

    builders = [
        pytest.param(f, id=name)
        for name, f in inspect.getmembers(dualight.scenes, inspect.isfunction)
        if f.__module__ == "dualight.scenes"
        and not name.startswith("_")
        and inspect.signature(f).return_annotation == "Scene"
    ]
    caustics = pytest.param(
        lambda: dualight.scenes.cornell_box(variant="caustics"), id="cornell_box_caustics"
    )
    return [*builders, caustics]


@pytest.mark.parametrize("build", _builtin_scenes())
def test_no_builtin_scene_has_an_emitter_facing_nothing(build) -> None:
    scene = build()
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error", UserWarning)
        scene.validate_for_rendering()
    assert scene.emitters_facing_nothing() == []


def test_camera_resolution_must_be_a_pair() -> None:
    with pytest.raises(ValueError, match=r"resolution must be a pair.*got 32.*\(32, 32\)"):
        dualight.Camera(resolution=32)
    with pytest.raises(ValueError, match="resolution"):
        dualight.Camera(resolution=(True, 8))  # a bool is not a pixel count
    cam = dualight.Camera(resolution=(np.int64(32), np.int32(16)))
    assert cam.resolution == (32, 16) and type(cam.resolution[0]) is int


def test_shading_normals_are_unit_read_only_and_optional() -> None:
    scene = dualight.Scene()
    scene.add_mesh(QUAD_V, QUAD_F)
    assert scene.meshes[0].normals is None
    scene.add_mesh(QUAD_V, QUAD_F, normals=[[0, 0, 2], [0, 1, 1], [0, 0, 1], [1, 0, 1]])
    n = scene.meshes[1].normals
    np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1.0)
    np.testing.assert_allclose(n[1], [0, 2**-0.5, 2**-0.5])
    assert not n.flags.writeable


def test_robust_intersections_reach_the_core_radiosity_and_pickles(tiny_scene) -> None:
    import pickle

    with pytest.raises(TypeError, match="robust_intersections must be True or False"):
        dualight.Scene(robust_intersections=1)  # type: ignore[arg-type]
    assert tiny_scene.robust_intersections is True  # dualight's default; Mitsuba 3's is False
    with pytest.raises(TypeError, match="robust_intersections must be True or False"):
        tiny_scene.robust_intersections = "no"  # type: ignore[assignment]
    for robust in (False, True):
        scene = dualight.Scene(tiny_scene.camera, robust_intersections=robust)
        scene.add_mesh(QUAD_V, QUAD_F)
        assert scene.robust_intersections is robust
        assert scene._compile().robust_intersections is robust
        assert pickle.loads(pickle.dumps(scene))._compile().robust_intersections is robust
        patches = dualight.radiosity.PatchMesh(scene, max_area=0.25)
        assert patches._compile().robust_intersections is robust
        scene.robust_intersections = not robust  # the setter recompiles both
        assert scene._compile().robust_intersections is not robust
        assert patches._compile().robust_intersections is not robust


@pytest.mark.mitsuba
def test_robust_intersections_map_to_mitsubas_scene_property(tiny_scene) -> None:
    pytest.importorskip("mitsuba")
    for robust in (False, True):
        tiny_scene.robust_intersections = robust
        exported = tiny_scene.to_mitsuba()
        assert exported["embree_use_robust_intersections"] is robust


@pytest.mark.parametrize("light_scale", [1.0, 1.1])
def test_robust_and_fast_intersections_render_the_same_image(light_scale: float) -> None:
    # Embree's fast mode lets a few rays through where triangles meet (the camera in
    # test_stress's closed cube saw pixels of 1.4e-4 instead of black); in the Cornell box that
    # is far below the noise. The control (the light 10 % brighter in the robust render) fails
    # the same test.
    fast = dualight.scenes.cornell_box(resolution=(32, 32))
    fast.robust_intersections = False
    robust = dualight.scenes.cornell_box(resolution=(32, 32), light_scale=light_scale)
    a = dualight.render(fast, "path", spp=512, seed=1, progress=False)
    b = dualight.render(robust, "path", spp=512, seed=2, progress=False)
    result = dualight.metrics.welch_test(a, a.variance, b, b.variance, block=4)
    assert (result.pass_fraction == 1.0) == (light_scale == 1.0), str(result)


@pytest.mark.parametrize(("prop", "robust"), [("", True), ("false", False), ("true", True)])
def test_robust_intersections_are_read_from_mitsuba_xml(tmp_path, prop: str, robust: bool) -> None:
    line = f'<boolean name="embree_use_robust_intersections" value="{prop}"/>' if prop else ""
    path = tmp_path / "scene.xml"
    path.write_text(f'<scene version="3.0.0">{line}<shape type="rectangle"/></scene>')
    assert dualight.load_mitsuba_xml(path).robust_intersections is robust
