"""Textures (issue 19, item 2): lookups against Mitsuba 3's own texture plugins, each with a
control (the texture moved by one texel) that fails the same comparison; texture coordinates
from meshes and files; validation of every kind of bad input."""

from __future__ import annotations

import itertools
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import dualight
from dualight import _core
from dualight.textures import Bitmap, Checkerboard

RNG = np.random.default_rng(19)
UV = RNG.uniform(-1.7, 2.6, size=(4000, 2)).astype(np.float32)
TO_UV = [[1.5, 0.25, 0.1], [-0.3, 0.75, 0.4]]  # a skewed affine map


@pytest.fixture(scope="module")
def mi():
    mitsuba = pytest.importorskip("mitsuba")
    mitsuba.set_variant("scalar_rgb")
    return mitsuba


def _mitsuba_lookup(mi, texture: dict, uv: np.ndarray, scalar: bool = False) -> np.ndarray:
    from dualight.mitsuba import _mitsuba_objects

    t = mi.load_dict(_mitsuba_objects(texture))
    si = mi.SurfaceInteraction3f()
    out = []
    for u, v in uv:
        si.uv = mi.Point2f(float(u), float(v))
        out.append(t.eval_1(si) if scalar else np.array(t.eval(si)))
    return np.array(out, dtype=np.float64)


@pytest.fixture(scope="module")
def png(tmp_path_factory) -> Path:
    """A 5 x 7 RGB 8-bit PNG (sRGB-encoded, as Mitsuba and dualight both decode it)."""
    path = tmp_path_factory.mktemp("tex") / "t.png"
    pixels = RNG.integers(0, 256, size=(5, 7, 3)).astype(np.float32) / 255.0
    _core.write_image(str(path), pixels, {})
    return path


@pytest.mark.parametrize(
    ("wrap", "filt"),
    list(itertools.product(("repeat", "mirror", "clamp"), ("bilinear", "nearest"))),
)
def test_bitmap_lookups_match_mitsuba(mi, png: Path, wrap: str, filt: str) -> None:
    tex = Bitmap(png, wrap_mode=wrap, filter_type=filt, to_uv=TO_UV)
    ours = tex.eval(UV)
    theirs = _mitsuba_lookup(mi, tex._mitsuba_dict(), UV)
    # Nearest lookups exactly on a texel edge may round either way: a few of 4000
    agree = np.all(np.abs(ours - theirs) < 2e-5, axis=1)
    assert agree.mean() > 0.998, np.abs(ours - theirs).max()
    moved = Bitmap(
        png, wrap_mode=wrap, filter_type=filt, to_uv=np.add(TO_UV, [[0, 0, 1 / 7], [0] * 3])
    )
    # (with clamp most lookups fall beyond the image's edges, where a shift changes nothing)
    assert np.all(np.abs(moved.eval(UV) - theirs) < 2e-5, axis=1).mean() < 0.9


def test_texel_data_scalar_lookups_and_means_match_mitsuba(mi) -> None:
    grey = RNG.uniform(0.0, 1.0, size=(6, 4))
    rgb = RNG.uniform(0.0, 1.0, size=(3, 9, 3))
    for data in (grey, rgb):
        tex = Bitmap(data=data, wrap_mode="mirror", to_uv=TO_UV)
        theirs = _mitsuba_lookup(mi, tex._mitsuba_dict(), UV, scalar=True)
        np.testing.assert_allclose(tex.eval_scalar(UV), theirs, atol=5e-6)
        np.testing.assert_allclose(tex.mean, data.mean(axis=(0, 1)) * np.ones(3), rtol=1e-6)
    # 8-bit data are sRGB-encoded unless raw, as mitsuba.Bitmap(uint8)
    codes = RNG.integers(0, 256, size=(4, 4, 3)).astype(np.uint8)
    decoded = Bitmap(data=codes, filter_type="nearest").eval([[0.1, 0.1]])[0]
    bmp = mi.load_dict({"type": "bitmap", "bitmap": mi.Bitmap(codes), "filter_type": "nearest"})
    si = mi.SurfaceInteraction3f()
    si.uv = mi.Point2f(0.1, 0.1)
    np.testing.assert_allclose(decoded, np.array(bmp.eval(si)), atol=1e-6)
    raw = Bitmap(data=codes, raw=True, filter_type="nearest").eval([[0.1, 0.1]])[0]
    np.testing.assert_allclose(raw, codes[0, 0] / 255.0, atol=1e-6)


def test_checkerboard_matches_mitsuba(mi) -> None:
    tex = Checkerboard((0.9, 0.5, 0.1), 0.2, to_uv=TO_UV)
    np.testing.assert_allclose(tex.eval(UV), _mitsuba_lookup(mi, tex._mitsuba_dict(), UV))
    # Mitsuba 3.9's eval_1 gives color1 where eval gives color0: roughness follows eval_1
    scalar = _mitsuba_lookup(mi, tex._mitsuba_dict(), UV, scalar=True)
    np.testing.assert_allclose(tex.eval_scalar(UV), scalar, rtol=1e-6)
    np.testing.assert_allclose(tex.mean, (0.55, 0.35, 0.15))
    swapped = Checkerboard(0.2, (0.9, 0.5, 0.1), to_uv=TO_UV)
    assert not np.allclose(swapped.eval(UV), _mitsuba_lookup(mi, tex._mitsuba_dict(), UV))


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({}, ValueError, "either filename or data"),
        ({"filename": "nowhere.png"}, FileNotFoundError, "no such image"),
        ({"data": np.zeros((2, 2)), "wrap_mode": "wrap"}, ValueError, "wrap_mode"),
        ({"data": np.zeros((2, 2)), "filter_type": "cubic"}, ValueError, "filter_type"),
        ({"data": np.full((2, 2), np.nan)}, ValueError, "finite"),
        ({"data": np.zeros((2, 2, 5))}, ValueError, "5 channels"),
        ({"data": np.zeros((0, 2))}, ValueError, "height, width"),
        ({"data": np.array([["a"]])}, ValueError, "numbers"),
        ({"data": np.zeros((2, 2)), "to_uv": [[1, 0], [0, 1]]}, ValueError, "to_uv"),
        (
            {"data": np.zeros((2, 2)), "to_uv": [[1, 0, 0], [0, 1, 0], [1, 0, 1]]},
            ValueError,
            "affine",
        ),
        ({"data": np.zeros((2, 2)), "to_uv": [[np.inf, 0, 0], [0, 1, 0]]}, ValueError, "finite"),
    ],
)
def test_bad_bitmaps_are_refused(kwargs: dict, error: type, match: str) -> None:
    with pytest.raises(error, match=match):
        Bitmap(**kwargs)


def test_materials_check_their_textures() -> None:
    bright = Bitmap(data=np.full((2, 2, 3), 1.5))
    with pytest.raises(ValueError, match=r"reflectance: the texture's values must lie in \[0, 1\]"):
        dualight.Diffuse(bright)
    with pytest.raises(ValueError, match="Checkerboard color1 must be finite and >= 0"):
        Checkerboard(0.5, -1.0)
    rough = dualight.RoughConductor(alpha=Checkerboard(0.1, 0.3), material="Au")
    assert rough.textured and rough.alpha_u is rough.alpha_v
    assert dualight.Diffuse(Checkerboard(0.2, 0.6)).rgb_reflectance == pytest.approx((0.4,) * 3)
    assert not dualight.Diffuse().textured
    # a texture the core BSDF has no such parameter for is refused by the compiled scene too
    with pytest.raises(ValueError, match="no texturable 'alpha'"):
        _core.Scene(
            np.eye(3, dtype=np.float32),
            np.array([[0, 1, 2]], np.uint32),
            np.zeros(1, np.uint32),
            np.full((1, 3), 0.5, np.float32),
            np.zeros((1, 3), np.float32),
            textures=[[("alpha", Checkerboard()._core_texture())]],
        )


def test_add_mesh_checks_uv() -> None:
    quad = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float64)
    scene = dualight.Scene()
    for uv, match in [
        (np.zeros((3, 2)), r"shape \(4, 2\)"),
        (np.full((4, 2), np.nan), "finite"),
        (np.full((4, 2), 1e13), "finite"),
        (np.full((4, 2), "x"), "real numbers"),
    ]:
        with pytest.raises(ValueError, match=match):
            scene.add_mesh(quad, [[0, 1, 2, 3]], uv=uv)
    scene.add_mesh(quad, [[0, 1, 2, 3]], uv=quad[:, :2])
    assert not scene.meshes[0].uv.flags.writeable


def test_obj_texture_coordinates_are_flipped_as_mitsuba_reads_them(tmp_path: Path) -> None:
    obj = tmp_path / "q.obj"
    obj.write_text(
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 0.25\nvt 0 1\n"
        "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"
    )
    mesh = dualight.load_obj(obj).meshes[0]
    np.testing.assert_allclose(mesh.uv, [[0, 1], [1, 1], [1, 0.75], [0, 0]])


def _textured_box(texture: Any, uv: bool = True) -> dualight.Scene:
    """The Cornell box with a textured Diffuse floor (its quad spans the unit square of uv)."""
    from dualight import scenes

    box = scenes.cornell_box(resolution=(32, 32))
    scene = dualight.Scene(camera=box.camera)
    for mesh in box.meshes:
        if mesh.name == "floor":
            coords = np.tile(
                [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], (len(mesh.vertices) // 4, 1)
            )
            scene.add_mesh(
                mesh.vertices,
                mesh.triangles,
                material=dualight.Diffuse(texture),
                name="floor",
                uv=coords if uv else None,
            )
        else:
            scene.add_mesh(
                mesh.vertices,
                mesh.triangles,
                material=mesh.material,
                emission=mesh.emission,
                name=mesh.name,
            )
    return scene


def test_radiosity_averages_a_texture_over_each_patch_and_draws_it() -> None:
    from dualight import radiosity

    checker = Checkerboard((0.8, 0.8, 0.8), (0.1, 0.2, 0.3), to_uv=[[2.3, 0, 0], [0, 2.3, 0]])
    scene = _textured_box(checker)
    patches = radiosity.PatchMesh(scene, max_edge=100.0)
    floor = np.nonzero(patches.mesh_index == [m.name for m in scene.meshes].index("floor"))[0]
    rho = patches.reflectance[floor]
    # patches inside one square have its colour; those across an edge lie in between
    inside = np.all(np.isclose(rho, 0.8), axis=1) | np.all(np.isclose(rho, [0.1, 0.2, 0.3]), axis=1)
    assert 0.2 < inside.mean() < 0.9
    area_mean = (rho * patches.areas[floor, None]).sum(0) / patches.areas[floor].sum()
    grid = (np.stack(np.meshgrid(np.arange(400), np.arange(400)), -1).reshape(-1, 2) + 0.5) / 400
    np.testing.assert_allclose(area_mean, checker.eval(grid).mean(axis=0), rtol=2e-3)
    solution = radiosity.solve(scene, max_edge=100.0, importance=False, method="jacobi")
    drawn = np.asarray(solution.render(smooth=False))
    uv_corners, solution.patches.uv_corners = solution.patches.uv_corners, None
    per_patch = np.asarray(solution.render(smooth=False))  # each patch's mean albedo only
    solution.patches.uv_corners = uv_corners
    # The texture shows within patches (the floor's lower rows), and keeps each patch's mean
    floor_pixels = (slice(26, 32), slice(8, 24))
    change = np.abs(drawn - per_patch)[floor_pixels].mean() / per_patch[floor_pixels].mean()
    assert change > 0.05
    assert drawn.mean() == pytest.approx(per_patch.mean(), rel=0.02)


def _triangle_means(texture: Any, uv: np.ndarray, n: int = 200) -> np.ndarray:
    """A texture's mean over each triangle of corners ``uv`` ``(T, 3, 2)``: a dense grid of
    n(n+1)/2 sub-triangle centroids (independent of the library's 16-point rule)."""
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    keep = i + j < n
    b = np.stack([(i[keep] + 1 / 3) / n, (j[keep] + 1 / 3) / n], 1)  # lower sub-triangles
    points = (
        (1 - b[:, :1] - b[:, 1:])[None] * uv[:, None, 0]
        + b[:, :1][None] * uv[:, None, 1]
        + b[:, 1:][None] * uv[:, None, 2]
    )
    return texture.eval(points.reshape(-1, 2)).reshape(len(uv), -1, 3).mean(axis=1)


def test_hierarchical_radiosity_takes_each_triangles_mean_albedo_and_draws_the_texture() -> None:
    """Each input triangle's albedo is its texture's mean over it (its elements keep it), and
    the drawing agrees with the uniform solver's on the floor pixels. Controls: the same
    solution drawn without its texture (each leaf's mean albedo), and the solution of the
    texture moved by a tenth of the floor, both against the unmoved uniform solution."""
    from dualight import radiosity

    def checker(du: float) -> Checkerboard:
        return Checkerboard((0.8, 0.8, 0.8), (0.1, 0.2, 0.3), to_uv=[[1.2, 0, du], [0, 0.7, 0]])

    uniform = radiosity.solve(_textured_box(checker(0.0)), max_edge=60.0, method="jacobi")
    reference = np.asarray(uniform.render(smooth=False))[26:32, 8:24]  # floor pixels

    def floor_error(shift: float, drawn_textured: bool = True) -> float:
        scene = _textured_box(checker(1.2 * shift))
        solver = radiosity.HierarchicalSolver(scene, epsilon=2e-3, seed=3)
        solver.solve()
        solution = solver.solution()
        floor = [m.name for m in scene.meshes].index("floor")
        leaves = solution.patches
        mesh = scene.meshes[floor]
        means = _triangle_means(checker(1.2 * shift), mesh.uv[mesh.triangles])
        assert shift or np.ptp(means, axis=0).max() > 0.1  # the two triangles' means differ
        first = int(np.nonzero(scene.triangle_arrays()[2] == floor)[0][0])
        root = solver._core.leaves()["root"][leaves.mesh_index == floor] - first
        np.testing.assert_allclose(
            leaves.reflectance[leaves.mesh_index == floor], means[root], atol=0.01
        )
        if not drawn_textured:
            leaves.uv_corners = None
        drawn = np.asarray(solution.render(smooth=False))[26:32, 8:24]
        return float(np.abs(drawn - reference).mean() / reference.mean())

    # Measured: 0.110; untextured drawing 0.49, moved texture 0.41 (0.129, 0.49 and 0.415
    # against max_edge=30; the hierarchical floor is 6 % darker than the uniform one at this
    # epsilon with or without textures, 2 % at 5e-4).
    error, untextured, moved = floor_error(0.0), floor_error(0.0, False), floor_error(0.1)
    print(
        f"\nfloor pixels against the uniform solution: {error:.3f}; controls: drawn "
        f"untextured {untextured:.3f}, texture moved by 0.1 {moved:.3f}"
    )
    assert error < 0.2
    assert untextured > 0.3 and moved > 0.3


def test_textured_scenes_pickle() -> None:
    import pickle

    scene = _textured_box(Bitmap(data=RNG.uniform(size=(4, 4, 3))))
    scene._compile()
    scene.meshes[0].material.reflectance.mean  # noqa: B018 - builds the core texture
    again = pickle.loads(pickle.dumps(scene))
    texture = [m for m in again.meshes if m.name == "floor"][0].material.reflectance
    assert not texture.texels.flags.writeable
    np.testing.assert_array_equal(
        np.asarray(dualight.render(again, spp=2, seed=3, progress=False)),
        np.asarray(dualight.render(scene, spp=2, seed=3, progress=False)),
    )


def test_xml_textures_load_write_back_and_reach_mitsuba(mi, png: Path, tmp_path: Path) -> None:
    """Mitsuba XML textures (inline and by reference, on colours and roughness) load as the
    same lookups Mitsuba makes; the writer writes them back (array textures as EXR files) and
    Mitsuba loads what it wrote; a rectangle's (u, v) are Mitsuba's."""
    import shutil

    shutil.copy(png, tmp_path / "t.png")
    body = """
  <sensor type="perspective"><float name="fov" value="40"/><transform name="to_world">
    <lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/>
    <rfilter type="box"/></film>
  </sensor>
  <texture type="checkerboard" id="checks"><rgb name="color0" value="0.1"/>
    <transform name="to_uv"><scale x="3" y="2"/></transform></texture>
  <shape type="rectangle" id="light"><transform name="to_world"><translate z="3"/></transform>
    <emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>
  <shape type="rectangle" id="wall"><bsdf type="diffuse">
    <texture type="bitmap" name="reflectance"><string name="filename" value="t.png"/>
      <string name="wrap_mode" value="mirror"/></texture></bsdf></shape>
  <shape type="rectangle" id="metal"><bsdf type="roughconductor">
    <ref name="alpha" id="checks"/><ref name="specular_reflectance" id="checks"/></bsdf></shape>
"""
    path = tmp_path / "tex.xml"
    path.write_text(f'<scene version="3.0.0">{body}</scene>')
    scene = dualight.load_mitsuba_xml(path)
    meshes = {m.name: m for m in scene.meshes}
    wall = meshes["wall"]
    np.testing.assert_allclose(wall.uv, [[0, 0], [1, 0], [1, 1], [0, 1]])
    texture = wall.material.reflectance
    assert isinstance(texture, Bitmap) and texture.wrap_mode == "mirror"
    np.testing.assert_allclose(texture.eval(UV), Bitmap(png, wrap_mode="mirror").eval(UV))
    metal = meshes["metal"].material
    assert metal.alpha is metal.specular_reflectance and metal.alpha.to_uv == (3, 0, 0, 0, 2, 0)
    loaded = mi.load_file(str(path))
    si = loaded.ray_intersect(mi.Ray3f(mi.Point3f(0.3, -0.5, 1.0), mi.Vector3f(0, 0, -1)))
    np.testing.assert_allclose(np.array(si.uv), [0.65, 0.25], atol=1e-6)
    # written back: the same textures; an array texture becomes an EXR beside the meshes
    scene.add_mesh(
        wall.vertices + [0, 0, 0.5],
        wall.triangles,
        material=dualight.Diffuse(Bitmap(data=RNG.uniform(size=(3, 5, 3)))),
        name="array",
        uv=wall.uv,
    )
    (tmp_path / "out").mkdir()
    out = dualight.save_mitsuba_xml(scene, tmp_path / "out" / "back.xml")
    again = {m.name: m for m in dualight.load_mitsuba_xml(out).meshes}
    for name in ("wall", "metal", "array"):
        ours = scene.meshes[[m.name for m in scene.meshes].index(name)]
        back = again[f"mesh_{name}"]
        np.testing.assert_allclose(back.uv, ours.uv, atol=1e-6)
        a, b = ours.material, back.material
        field = "reflectance" if name != "metal" else "alpha"
        np.testing.assert_allclose(
            getattr(b, field).eval(UV), getattr(a, field).eval(UV), atol=1e-6
        )
    mi.load_file(str(out))
    for kind, bad, match in [
        ("diffuse", '<texture type="noise" name="reflectance"/>', "texture type 'noise'"),
        ("diffuse", '<ref name="reflectance" id="nothing"/>', "no texture with id 'nothing'"),
        ("roughplastic", '<ref name="alpha" id="checks"/>', "must be given as <float>"),
        ("dielectric", '<ref name="specular_reflectance" id="checks"/>', "must be given as"),
    ]:
        text = body.replace(
            "</bsdf></shape>\n",
            f"</bsdf></shape>\n<shape type='rectangle'><bsdf type='{kind}'>{bad}</bsdf></shape>\n",
            1,
        )
        path.write_text(f'<scene version="3.0.0">{text}</scene>')
        with pytest.raises(ValueError, match=match):
            dualight.load_mitsuba_xml(path)
    cube = body.replace('<shape type="rectangle" id="wall">', '<shape type="cube" id="wall">')
    path.write_text(f'<scene version="3.0.0">{cube}</scene>')
    with pytest.raises(ValueError, match="textured BSDF on a cube shape is not supported"):
        dualight.load_mitsuba_xml(path)


def test_mtl_map_kd_and_ply_texture_coordinates(png: Path, tmp_path: Path) -> None:
    import shutil

    import trimesh

    shutil.copy(png, tmp_path / "wood.png")
    (tmp_path / "m.mtl").write_text("newmtl wood\nKd 0.5 0.5 0.5\nmap_Kd wood.png\n")
    (tmp_path / "m.obj").write_text(
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nusemtl wood\n"
        "f 1/1 2/2 3/3\n"
    )
    mesh = dualight.load_obj(tmp_path / "m.obj").meshes[0]
    texture = mesh.material.reflectance
    assert isinstance(texture, Bitmap) and texture.filename == (tmp_path / "wood.png").resolve()
    (tmp_path / "m.mtl").write_text("newmtl wood\nmap_Kd missing.png\n")
    with pytest.raises(FileNotFoundError, match="map_Kd: no such image"):
        dualight.load_obj(tmp_path / "m.obj")
    # a PLY's texture coordinates are taken as they are (Mitsuba flips only an OBJ's)
    uv = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.25]])
    geom = trimesh.Trimesh(
        [[0, 0, 0], [1, 0, 0], [1, 1, 0]],
        [[0, 1, 2]],
        process=False,
        visual=trimesh.visual.TextureVisuals(uv=uv),
    )
    geom.export(str(tmp_path / "t.ply"))
    body = (
        '<shape type="ply"><string name="filename" value="t.ply"/>'
        '<bsdf type="diffuse"><texture type="checkerboard" name="reflectance"/></bsdf></shape>'
    )
    (tmp_path / "p.xml").write_text(f'<scene version="3.0.0">{body}</scene>')
    np.testing.assert_allclose(dualight.load_mitsuba_xml(tmp_path / "p.xml").meshes[0].uv, uv)
