"""Lenient Mitsuba 3 scene loading (issue 21, part 3): unsupported elements listed together
(``strict=True``) or substituted with one warning (``strict=False``), ``<include>``, PLY and OBJ
normals and texture coordinates, ``disk`` shapes, and ``<shapegroup>`` instances.

Each file is written to ``tmp_path`` (PLY files with numpy, in ASCII and both binary byte
orders), so no binary fixture is committed.
"""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path

import numpy as np
import pytest

import dualight
from dualight.io import _mitsuba_survey

SENSOR = """<sensor type="perspective"><float name="fov" value="40"/>
  <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="6"/>
  <rfilter type="box"/></film></sensor>"""
LIGHT = """<shape type="rectangle" id="light">
  <emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>"""


def _xml(folder: Path, body: str, name: str = "scene.xml") -> Path:
    path = folder / name
    path.write_text(f'<scene version="3.0.0">{SENSOR}{LIGHT}{body}</scene>')
    return path


# Three unsupported elements at different depths, and one supported BSDF between them.
UNSUPPORTED = """
  <bsdf type="principled" id="gold">
    <rgb name="base_color" value="0.8, 0.6, 0.2"/><float name="roughness" value="0.4"/>
  </bsdf>
  <shape type="serialized" id="mesh"><string name="filename" value="m.serialized"/></shape>
  <shape type="sphere"><ref id="gold"/></shape>
  <shape type="cube">
    <bsdf type="bumpmap"><texture name="arbitrary" type="bitmap">
      <string name="filename" value="bump.png"/></texture>
      <bsdf type="diffuse"><rgb name="reflectance" value="0.25"/></bsdf></bsdf>
  </shape>
  <shape type="cube"><bsdf type="diffuse">
    <texture name="reflectance" type="mesh_attribute"><string name="name" value="c"/></texture>
  </bsdf></shape>"""


def test_supported_list_matches_the_builders_tables() -> None:
    for tag, table in _mitsuba_survey._PROPERTY_TABLES.items():
        assert set(table) == set(_mitsuba_survey._SUPPORTED[tag]), tag


def test_strict_lists_every_unsupported_element_in_one_error(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="4 unsupported element") as info:
        dualight.load_mitsuba_xml(_xml(tmp_path, UNSUPPORTED))
    message = str(info.value)
    assert "scene.xml" in message
    for expected in (
        r'scene/bsdf\[1\] <bsdf type="principled" id="gold">: BSDF type .principled.',
        r'scene/shape\[2\] <shape type="serialized" id="mesh">: shape type .serialized.',
        r"scene/shape\[4\]/bsdf\[1\] <bsdf type=\"bumpmap\">: BSDF type .bumpmap.",
        r"scene/shape\[5\]/bsdf\[1\]/texture\[1\] .*texture type .mesh_attribute.",
    ):
        assert len(re.findall(expected, message)) == 1, expected


def test_lenient_warns_once_and_substitutes(tmp_path: Path) -> None:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        scene = dualight.load_mitsuba_xml(_xml(tmp_path, UNSUPPORTED), strict=False)
    assert len(caught) == 1 and caught[0].category is UserWarning
    text = str(caught[0].message)
    assert "serialized" in text and "skipped" in text
    assert "replaced by a roughplastic (alpha 0.16" in text
    assert "replaced by its nested <bsdf type='diffuse'>" in text
    assert "replaced by the colour 0.5" in text
    names = [m.name for m in scene.meshes]
    assert names == ["light", "sphere1", "cube2", "cube3"]  # the serialized shape is skipped
    gold = scene.meshes[1].material
    assert isinstance(gold, dualight.RoughPlastic)
    assert gold.diffuse_reflectance == pytest.approx((0.8, 0.6, 0.2))
    assert gold.alpha == pytest.approx(0.4**2) and gold.distribution == "ggx"
    assert gold.ior == pytest.approx(1.5)  # Mitsuba's principled: specular 0.5 is eta 1.5
    assert scene.meshes[2].material == dualight.Diffuse((0.25, 0.25, 0.25))
    assert scene.meshes[3].material == dualight.Diffuse((0.5, 0.5, 0.5))


def test_lenient_metal_sensor_and_pixel_filter(tmp_path: Path) -> None:
    path = tmp_path / "s.xml"
    path.write_text(f"""<scene version="3.0.0">
      <sensor type="thinlens"><float name="fov" value="30"/>
        <float name="aperture_radius" value="0.1"/><film type="specfilm"/></sensor>{LIGHT}
      <shape type="cube"><bsdf type="principled"><float name="metallic" value="1"/>
        <rgb name="base_color" value="0.9, 0.5, 0.3"/></bsdf></shape>
      <emitter type="sunsky"/><medium type="homogeneous" id="fog"/></scene>""")
    with pytest.raises(ValueError, match="5 unsupported") as info:
        dualight.load_mitsuba_xml(path)
    for reason in ("sensor type 'thinlens'", "film type 'specfilm'", "type 'sunsky'", "<medium"):
        assert reason in str(info.value)
    with pytest.warns(UserWarning) as record:
        scene = dualight.load_mitsuba_xml(path, strict=False)
    assert len(record) == 1
    assert "'gaussian' pixel filter is replaced by a box" in str(record[0].message)
    assert scene.camera.resolution == (768, 576)
    metal = scene.meshes[1].material
    assert isinstance(metal, dualight.RoughConductor)
    assert metal.specular_reflectance == pytest.approx((0.9, 0.5, 0.3))


def test_values_the_core_cannot_hold_still_raise_when_lenient(tmp_path: Path) -> None:
    body = '<shape type="cube"><bsdf type="principled"><rgb name="base_color" value="3"/>'
    with (
        pytest.raises(ValueError, match=r"diffuse_reflectance must be .*in \[0, 1\]"),
        pytest.warns(UserWarning, match="principled"),
    ):
        dualight.load_mitsuba_xml(_xml(tmp_path, body + "</bsdf></shape>"), strict=False)


def test_include_reads_the_included_scene_in_place(tmp_path: Path) -> None:
    (tmp_path / "parts").mkdir()
    (tmp_path / "parts" / "a.xml").write_text(
        '<scene version="3.0.0"><bsdf type="diffuse" id="red">'
        '<rgb name="reflectance" value="0.7, 0.1, 0.1"/></bsdf>'
        '<include filename="b.xml"/></scene>'
    )
    (tmp_path / "parts" / "b.xml").write_text(
        '<scene version="3.0.0"><shape type="cube" id="box"><ref id="red"/></shape></scene>'
    )
    scene = dualight.load_mitsuba_xml(_xml(tmp_path, '<include filename="parts/a.xml"/>'))
    assert [m.name for m in scene.meshes] == ["light", "box"]
    assert scene.meshes[1].material == dualight.Diffuse((0.7, 0.1, 0.1))


def test_include_cycle_and_errors_name_the_included_file(tmp_path: Path) -> None:
    (tmp_path / "a.xml").write_text('<scene version="3.0.0"><include filename="b.xml"/></scene>')
    (tmp_path / "b.xml").write_text('<scene version="3.0.0"><include filename="a.xml"/></scene>')
    with pytest.raises(ValueError, match="include cycle: 'scene.xml' -> 'a.xml' -> 'b.xml'"):
        dualight.load_mitsuba_xml(_xml(tmp_path, '<include filename="a.xml"/>'))
    (tmp_path / "c.xml").write_text('<scene version="3.0.0"><shape type="cylinder"/></scene>')
    with pytest.raises(ValueError, match=r"shape\[2\] <shape type=\"cylinder\"> \(in .*c.xml'\)"):
        dualight.load_mitsuba_xml(_xml(tmp_path, '<include filename="c.xml"/>'))
    with pytest.raises(FileNotFoundError, match="no such included XML file"):
        dualight.load_mitsuba_xml(_xml(tmp_path, '<include filename="gone.xml"/>'))


# A quad whose vertices carry distinct normals and texture coordinates.
V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float64)
N = np.array([[0, 0, 1], [0, 0.6, 0.8], [0.6, 0, 0.8], [0, -0.6, 0.8]])
UV = np.array([[0, 0], [1, 0], [1, 1], [0.25, 0.75]])
F = np.array([[0, 1, 2], [0, 2, 3]])


def _ply(fmt: str, uv_names: tuple[str, str]) -> bytes:
    props = ["x", "y", "z", "nx", "ny", "nz", *uv_names]
    header = f"ply\nformat {fmt} 1.0\nelement vertex {len(V)}\n"
    header += "".join(f"property float {p}\n" for p in props)
    header += f"element face {len(F)}\nproperty list uchar int vertex_indices\nend_header\n"
    rows = np.hstack([V, N, UV])
    if fmt == "ascii":
        body = "".join(" ".join(f"{x:g}" for x in r) + "\n" for r in rows)
        body += "".join("3 " + " ".join(map(str, f)) + "\n" for f in F)
        return header.encode() + body.encode()
    order = "<" if fmt == "binary_little_endian" else ">"
    faces = np.zeros(len(F), dtype=[("n", "u1"), ("i", f"{order}i4", 3)])
    faces["n"], faces["i"] = 3, F
    return header.encode() + rows.astype(f"{order}f4").tobytes() + faces.tobytes()


def _mesh_shape(folder: Path, kind: str, extra: str = "") -> dualight.Mesh:
    shape = f'<shape type="{kind}"><string name="filename" value="m.{kind}"/>{extra}</shape>'
    return dualight.load_mitsuba_xml(_xml(folder, shape)).meshes[1]


@pytest.mark.parametrize("fmt", ["ascii", "binary_little_endian", "binary_big_endian"])
@pytest.mark.parametrize(
    "uv_names", [("u", "v"), ("s", "t"), ("texture_u", "texture_v"), ("texture_s", "texture_t")]
)
def test_ply_normals_and_uv(tmp_path: Path, fmt: str, uv_names: tuple[str, str]) -> None:
    (tmp_path / "m.ply").write_bytes(_ply(fmt, uv_names))
    mesh = _mesh_shape(tmp_path, "ply")
    np.testing.assert_allclose(mesh.vertices, V)
    np.testing.assert_array_equal(mesh.triangles, F)
    np.testing.assert_allclose(mesh.normals, N, atol=1e-7)
    np.testing.assert_allclose(mesh.uv, UV, atol=1e-7)


def test_ply_face_normals_flip_and_to_world(tmp_path: Path) -> None:
    (tmp_path / "m.ply").write_bytes(_ply("binary_little_endian", ("u", "v")))
    assert (
        _mesh_shape(tmp_path, "ply", '<boolean name="face_normals" value="true"/>').normals is None
    )
    moved = _mesh_shape(
        tmp_path,
        "ply",
        '<boolean name="flip_normals" value="true"/><transform name="to_world">'
        '<scale x="2"/><translate z="1"/></transform>',
    )
    np.testing.assert_allclose(moved.vertices, V * [2, 1, 1] + [0, 0, 1])
    np.testing.assert_array_equal(moved.triangles, F[:, ::-1])
    expected = -N * [0.5, 1, 1]  # inverse transpose of the scale, then flipped
    np.testing.assert_allclose(moved.normals, expected / np.linalg.norm(expected, axis=1)[:, None])


def test_obj_separate_index_streams_split_into_vertex_triples(tmp_path: Path) -> None:
    # Position 1 has a different texture coordinate and normal in each face.
    (tmp_path / "m.obj").write_text(
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
        "vn 0 0 1\nvn 0 1 1\nf 1/1/1 2/2/1 3/3/1\nf 1/5/2 3/3/1 4/4/1\n"
    )
    mesh = _mesh_shape(tmp_path, "obj")
    corners = mesh.vertices[mesh.triangles]  # (2, 3, 3): positions per face corner
    np.testing.assert_allclose(corners, V[F])
    uv = mesh.uv[mesh.triangles]
    np.testing.assert_allclose(uv[0], [[0, 1], [1, 1], [1, 0]])  # v flipped, as Mitsuba reads
    np.testing.assert_allclose(uv[1], [[0.5, 0.5], [1, 0], [0, 0]])
    normals = mesh.normals[mesh.triangles]
    np.testing.assert_allclose(normals[1, 0], [0, math.sqrt(0.5), math.sqrt(0.5)])
    np.testing.assert_allclose(normals[0, 0], [0, 0, 1])
    loaded = dualight.load_obj(tmp_path / "m.obj").meshes[0]
    np.testing.assert_allclose(loaded.uv[loaded.triangles], mesh.uv[mesh.triangles])


def test_obj_without_normals_gets_smooth_ones(tmp_path: Path) -> None:
    (tmp_path / "m.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 4\nf 1 4 3\n")
    normals = _mesh_shape(tmp_path, "obj").normals
    assert normals is not None  # two faces at a right angle: angle-weighted normals
    # Faces with normals -y and -x meet at right angles at the origin (equal weights).
    np.testing.assert_allclose(normals[0], [-math.sqrt(0.5), -math.sqrt(0.5), 0], atol=1e-12)


def test_disk_is_a_fan_of_the_disk_area(tmp_path: Path) -> None:
    shape = (
        '<shape type="disk"><emitter type="area"><rgb name="radiance" value="2"/></emitter>'
        '<transform name="to_world"><scale value="3"/><translate z="2"/></transform></shape>'
    )
    scene = dualight.load_mitsuba_xml(_xml(tmp_path, shape), sphere_subdivisions=2)
    disk = scene.meshes[1]
    assert len(disk.triangles) == 32 and disk.areas.sum() == pytest.approx(9 * math.pi)
    np.testing.assert_allclose(disk.vertices[:, 2], 2.0)
    e = disk.vertices[disk.triangles]
    assert np.all(np.cross(e[:, 1] - e[:, 0], e[:, 2] - e[:, 0])[:, 2] > 0)  # facing +z


def test_shapegroup_instances(tmp_path: Path) -> None:
    body = """
      <bsdf type="diffuse" id="grey"><rgb name="reflectance" value="0.3"/></bsdf>
      <shapegroup id="group">
        <shape type="rectangle" id="quad"><ref id="grey"/>
          <transform name="to_world"><translate z="1"/></transform></shape>
      </shapegroup>
      <shape type="instance" id="a"><ref id="group"/>
        <transform name="to_world"><translate x="10"/></transform></shape>
      <shape type="instance" id="b"><ref id="group"/>
        <transform name="to_world"><rotate y="1" angle="90"/></transform></shape>"""
    scene = dualight.load_mitsuba_xml(_xml(tmp_path, body))
    assert [m.name for m in scene.meshes] == ["light", "a/quad", "b/quad"]
    quad = np.array([[-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=np.float64)
    np.testing.assert_allclose(scene.meshes[1].vertices, quad + [10, 0, 0])
    # rotate y by 90 degrees: (x, y, z) -> (z, y, -x)
    rotated = np.column_stack([quad[:, 2], quad[:, 1], -quad[:, 0]])
    np.testing.assert_allclose(scene.meshes[2].vertices, rotated, atol=1e-12)
    assert scene.meshes[2].material == dualight.Diffuse((0.3, 0.3, 0.3))
    with pytest.raises(ValueError, match="no shapegroup with id 'nope'"):
        dualight.load_mitsuba_xml(
            _xml(tmp_path, '<shape type="instance"><ref id="nope"/></shape>', "bad.xml")
        )


def test_spectra_are_listed_and_replaced_by_their_mean(tmp_path: Path) -> None:
    body = """<shape type="cube"><bsdf type="roughconductor">
        <spectrum name="alpha" value="0.01"/></bsdf></shape>
      <emitter type="directional"><spectrum name="irradiance" value="400:1, 700:3"/>
        <vector name="direction" value="0, 0, -1"/></emitter>"""
    with pytest.raises(ValueError, match="2 unsupported") as info:
        dualight.load_mitsuba_xml(_xml(tmp_path, body))
    assert "roughconductor property 'alpha' must be given as <float>" in str(info.value)
    with pytest.warns(UserWarning, match=r'replaced by its mean, <float value="2">'):
        scene = dualight.load_mitsuba_xml(_xml(tmp_path, body), strict=False)
    assert scene.meshes[1].material.alpha == pytest.approx(0.01)
    assert scene.emitters[0].irradiance == pytest.approx((2, 2, 2))


# References before the objects they name (as Mitsuba 3 allows): a BSDF, one through a default
# given after the reference, a texture, a twosided around a later BSDF, a shapegroup, and a BSDF
# in a file included at the end.
LATER = """
  <shape type="rectangle" id="plain"><ref id="grey"/></shape>
  <shape type="rectangle" id="textured"><ref id="checked"/></shape>
  <shape type="rectangle" id="two"><ref id="both"/></shape>
  <shape type="rectangle" id="defaulted"><ref id="dark"/></shape>
  <shape type="rectangle" id="included"><ref id="far"/></shape>
  <shape type="instance" id="copy"><ref id="group"/></shape>
  <bsdf type="diffuse" id="checked"><ref name="reflectance" id="checks"/></bsdf>
  <bsdf type="twosided" id="both"><ref id="metal"/></bsdf>
  <shapegroup id="group"><shape type="rectangle" id="quad"><ref id="grey"/></shape></shapegroup>
  <bsdf type="diffuse" id="grey"><rgb name="reflectance" value="0.3"/></bsdf>
  <texture type="checkerboard" id="checks"><rgb name="color0" value="0.1"/></texture>
  <bsdf type="conductor" id="metal"/>
  <default name="r" value="0.2"/>
  <bsdf type="diffuse" id="dark"><float name="reflectance" value="$r"/></bsdf>
  <include filename="more.xml"/>"""


@pytest.mark.parametrize("strict", [True, False])
def test_references_may_come_before_what_they_name(tmp_path: Path, strict: bool) -> None:
    (tmp_path / "more.xml").write_text(
        '<scene version="3.0.0"><bsdf type="diffuse" id="far">'
        '<rgb name="reflectance" value="0.7"/></bsdf></scene>'
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        scene = dualight.load_mitsuba_xml(_xml(tmp_path, LATER), strict=strict)
    m = {mesh.name: mesh.material for mesh in scene.meshes}
    assert list(m) == ["light", "plain", "textured", "two", "defaulted", "included", "copy/quad"]
    assert m["plain"] == m["copy/quad"] == dualight.Diffuse((0.3, 0.3, 0.3))
    assert isinstance(m["textured"].reflectance, dualight.Checkerboard)
    assert isinstance(m["two"], dualight.Mirror)
    assert m["defaulted"] == dualight.Diffuse((0.2, 0.2, 0.2))
    assert m["included"] == dualight.Diffuse((0.7, 0.7, 0.7))


def test_lenient_substitutes_objects_referenced_before_they_are_defined(tmp_path: Path) -> None:
    """mitsuba-blender's exports reference a bumpmap and a principled BSDF before defining them
    (and the bumpmap holds a reference to the principled BSDF defined after it)."""
    body = """
      <shape type="rectangle" id="bumpy"><ref id="bump"/></shape>
      <shape type="rectangle" id="noisy"><bsdf type="diffuse">
        <ref name="reflectance" id="noise"/></bsdf></shape>
      <bsdf type="bumpmap" id="bump"><ref id="gold"/>
        <texture type="bitmap" name="arbitrary"><string name="filename" value="b.png"/></texture>
      </bsdf>
      <bsdf type="principled" id="gold"><rgb name="base_color" value="0.8, 0.6, 0.2"/></bsdf>
      <texture type="mesh_attribute" id="noise"><string name="name" value="c"/></texture>"""
    with pytest.raises(ValueError, match="3 unsupported element"):
        dualight.load_mitsuba_xml(_xml(tmp_path, body))
    with pytest.warns(UserWarning, match="replaced by the BSDF 'gold' it holds"):
        scene = dualight.load_mitsuba_xml(_xml(tmp_path, body), strict=False)
    m = {mesh.name: mesh.material for mesh in scene.meshes}
    assert isinstance(m["bumpy"], dualight.RoughPlastic)
    assert m["bumpy"].diffuse_reflectance == pytest.approx((0.8, 0.6, 0.2))
    assert m["noisy"] == dualight.Diffuse((0.5, 0.5, 0.5))


@pytest.mark.parametrize("strict", [True, False])
def test_undefined_and_cyclic_references_raise(tmp_path: Path, strict: bool) -> None:
    undefined = '<shape type="cube"><ref id="missing"/></shape><bsdf type="diffuse" id="x"/>'
    with pytest.raises(ValueError, match="no BSDF with id 'missing' is defined"):
        dualight.load_mitsuba_xml(_xml(tmp_path, undefined), strict=strict)
    wrong = '<shape type="cube"><ref id="x"/></shape><texture type="checkerboard" id="x"/>'
    with pytest.raises(ValueError, match="no BSDF with id 'x': it names a <texture>"):
        dualight.load_mitsuba_xml(_xml(tmp_path, wrong), strict=strict)
    cycle = """<shape type="cube"><ref id="a"/></shape>
      <bsdf type="twosided" id="a"><ref id="b"/></bsdf>
      <bsdf type="twosided" id="b"><ref id="a"/></bsdf>"""
    with pytest.raises(ValueError, match="reference cycle: 'a' -> 'b' -> 'a'"):
        dualight.load_mitsuba_xml(_xml(tmp_path, cycle), strict=strict)
