"""Mitsuba 3 shapes: ``<shape>`` elements as triangle meshes (files, analytic shapes
tessellated), ``<shapegroup>`` elements and the instances that flatten them."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from pathlib import Path
from typing import NamedTuple

import numpy as np

from dualight.io._common import (
    RGB,
    _angle_weighted_normals,
    _loaded_normals,
    _loaded_uv,
    _mesh_arrays,
    _trimesh_geometries,
)
from dualight.io._mitsuba_context import _Context
from dualight.io._mitsuba_emitters import _AREA_PROPERTIES
from dualight.io._mitsuba_materials import _bsdf_or_ref, _rgb_or
from dualight.io._mitsuba_values import (
    _PROPERTY_TAGS,
    _apply,
    _boolean,
    _no_children,
    _number,
    _properties,
    _transform,
    _unsupported_type,
    _vector,
)
from dualight.io.obj import _obj_meshes, _obj_text
from dualight.materials import Diffuse, Material
from dualight.scene import Scene
from dualight.textures import Texture


def _rectangle() -> tuple[np.ndarray, np.ndarray]:
    v = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=np.float64)
    return v, np.array([[0, 1, 2], [0, 2, 3]])


def _cube() -> tuple[np.ndarray, np.ndarray]:
    """[-1, 1]^3 with outward-facing triangles (four vertices per face, as Mitsuba's)."""
    verts, faces = [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            u, w = (axis + 1) % 3, (axis + 2) % 3
            quad = []
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = np.zeros(3)
                p[axis], p[u], p[w] = sign, a, b
                quad.append(p)
            base = len(verts)
            quad_f = [[base, base + 1, base + 2], [base, base + 2, base + 3]]
            if sign < 0:  # (u, w) order gives normal +axis: flip for the -axis face
                quad_f = [f[::-1] for f in quad_f]
            verts.extend(quad)
            faces.extend(quad_f)
    return np.array(verts), np.array(faces)


def _disk(segments: int) -> tuple[np.ndarray, np.ndarray]:
    """Mitsuba's ``disk`` (radius 1 at ``z = 0``, normal ``+z``) as a fan of ``segments``
    triangles, its rim's radius scaled so that the polygon's area is the disk's, pi (an area
    emitter's power and a diffuse disk's irradiance are kept)."""
    phi = 2.0 * math.pi * np.arange(segments) / segments
    r = math.sqrt(2.0 * math.pi / (segments * math.sin(2.0 * math.pi / segments)))
    rim = np.column_stack([r * np.cos(phi), r * np.sin(phi), np.zeros(segments)])
    v = np.vstack([np.zeros((1, 3)), rim])
    k = np.arange(segments)
    return v, np.column_stack([np.zeros(segments, dtype=np.int64), 1 + k, 1 + (k + 1) % segments])


def _file_mesh(
    ctx: _Context, element: ET.Element, kind: str, filename: str, face_normals: bool
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None, np.ndarray | None]:
    """Vertices, faces, shading normals (None: flat) and texture coordinates (None: none) of an
    OBJ/PLY shape. As in Mitsuba, without ``face_normals`` the file's vertex normals are used,
    or smooth ones are computed; an OBJ vertex is a distinct ``v/vt/vn`` triple."""
    path = ctx.folder / filename
    if not path.is_file():
        raise FileNotFoundError(
            f"no such {kind.upper()} file: {str(path)!r} (named by <shape type={kind!r}> in "
            f"{str(ctx.source(element))!r})"
        )
    if kind == "obj":
        text, _, split = _obj_text(path)
        geoms = [g for _, g in _obj_meshes(path, text, split)]
    else:
        geoms = [g for _, g in _trimesh_geometries(path, kind)]
    parts = [_mesh_arrays(g, str(path)) for g in geoms]
    offsets = np.cumsum([0] + [len(v) for v, _ in parts[:-1]])
    v = np.concatenate([p[0] for p in parts])
    f = np.concatenate([p[1] + off for p, off in zip(parts, offsets, strict=True)])
    uvs = [_loaded_uv(g, kind) for g in geoms]
    uv = np.concatenate(uvs) if all(u is not None for u in uvs) else None  # type: ignore[arg-type]
    if face_normals:
        return v, f, None, uv
    loaded = [_loaded_normals(g) for g in geoms]
    if all(n is not None for n in loaded):
        return v, f, np.concatenate(loaded), uv  # type: ignore[arg-type]
    return v, f, _angle_weighted_normals(v, f), uv


_SHAPE_PROPERTIES: dict[str, dict[str, tuple[str, ...]]] = {
    "obj": {
        "filename": ("string",),
        "face_normals": ("boolean",),
        "flip_normals": ("boolean",),
        "to_world": ("transform",),
    },
    "rectangle": {"flip_normals": ("boolean",), "to_world": ("transform",)},
    "cube": {"flip_normals": ("boolean",), "to_world": ("transform",)},
    "sphere": {
        "center": ("point",),
        "radius": ("float",),
        "flip_normals": ("boolean",),
        "to_world": ("transform",),
    },
    "instance": {"to_world": ("transform",)},
}
_SHAPE_PROPERTIES["ply"] = _SHAPE_PROPERTIES["obj"]
_SHAPE_PROPERTIES["disk"] = _SHAPE_PROPERTIES["rectangle"]
# Shapes whose normals Mitsuba transforms as normals, so that a mirroring to_world keeps their
# front side (meshes and spheres take the transformed triangles' orientation), and that have no
# texture coordinates in dualight.
_ANALYTIC = ("rectangle", "cube", "disk")


class _Mesh(NamedTuple):
    """A shape's triangles in world space and what scene.add_mesh takes with them."""

    v: np.ndarray
    f: np.ndarray
    normals: np.ndarray | None
    uv: np.ndarray | None
    material: Material
    emission: RGB | Texture
    name: str


def _shape_children(ctx: _Context, element: ET.Element) -> tuple[Material | None, RGB | Texture]:
    """A shape's BSDF (None: none given) and area emitter's radiance (black: none)."""
    material: Material | None = None
    emission: RGB | Texture = (0.0, 0.0, 0.0)
    for child in element:
        if child.tag in _PROPERTY_TAGS or child.tag == "transform":
            continue
        if child.tag in ("bsdf", "ref"):
            if child.tag == "ref" and child.get("name", "bsdf") != "bsdf":
                raise ctx.error(child, "only a BSDF can be referenced from a shape")
            if material is not None:
                raise ctx.error(child, "a shape can have only one BSDF")
            material = _bsdf_or_ref(ctx, child)
        elif child.tag == "emitter":
            if ctx.attr(child, "type") != "area":
                raise ctx.error(child, "only area emitters can be attached to a shape")
            if sum(c.tag == "emitter" for c in element) > 1:
                raise ctx.error(child, "a shape can have only one emitter")
            eprops = _properties(ctx, child, _AREA_PROPERTIES, "area emitter")
            _no_children(ctx, child)
            if "radiance" not in eprops:
                raise ctx.error(child, 'an area emitter needs a radiance (<rgb name="radiance">)')
            emission = _rgb_or(ctx, eprops, "radiance", None)
        else:
            raise ctx.error(child, f"<{child.tag}> inside a shape is not supported")
    return material, emission


def _shape_geometry(
    ctx: _Context,
    element: ET.Element,
    kind: str,
    props: Mapping[str, ET.Element],
    sphere_subdivisions: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None, np.ndarray | None, str]:
    """A shape's vertices, faces, shading normals, texture coordinates and default name, in
    its object space."""
    from dualight.scenes import icosphere

    if kind in ("obj", "ply"):
        if "filename" not in props:
            raise ctx.error(element, f'a {kind} shape needs <string name="filename">')
        filename = ctx.attr(props["filename"], "value")
        face_normals = _boolean(ctx, props.get("face_normals"), False)
        v, f, normals, uv = _file_mesh(ctx, element, kind, filename, face_normals)
        return v, f, normals, uv, Path(filename).stem
    if kind == "rectangle":
        v, f = _rectangle()
        return v, f, None, (v[:, :2] + 1.0) / 2.0, kind  # Mitsuba's uv: (0, 0) at (-1, -1)
    if kind == "cube":
        return *_cube(), None, None, kind
    if kind == "disk":
        return *_disk(8 * 2**sphere_subdivisions), None, None, kind
    centre = _vector(ctx, props["center"]) if "center" in props else np.zeros(3)
    radius = _number(ctx, props.get("radius"), 1.0)
    if radius <= 0.0:
        raise ctx.error(props["radius"], f"sphere radius must be > 0, got {radius}")
    v, f = icosphere(centre, radius, sphere_subdivisions)
    # The sphere's own normals: smooth, as Mitsuba's analytic sphere.
    return v, f, v - centre, None, "sphere"


def _transformed(mesh: _Mesh, m: np.ndarray, keep_front: bool, name: str) -> _Mesh:
    """``mesh`` moved by the 4 x 4 transform ``m`` (normals by its inverse transpose); with
    ``keep_front``, a mirroring ``m`` turns the triangles round so the front side is kept."""
    normals = None if mesh.normals is None else mesh.normals @ np.linalg.inv(m[:3, :3])
    f = mesh.f[:, ::-1] if keep_front and np.linalg.det(m[:3, :3]) < 0.0 else mesh.f
    return mesh._replace(v=_apply(m, mesh.v), f=f, normals=normals, name=name)


def _shape(
    ctx: _Context,
    element: ET.Element,
    index: int,
    sphere_subdivisions: int,
) -> list[_Mesh]:
    """The meshes of a ``<shape>``: one, or an ``instance``'s copies of its shapegroup's."""
    kind = ctx.attr(element, "type")
    if kind not in _SHAPE_PROPERTIES:
        raise ctx.error(element, _unsupported_type("shape", kind))
    props = _properties(ctx, element, _SHAPE_PROPERTIES[kind], f"shape {kind!r}")
    to_world = _transform(ctx, props["to_world"]) if "to_world" in props else np.eye(4)
    if kind == "instance":
        return _instance(ctx, element, to_world, element.get("id") or f"{kind}{index}")
    material, emission = _shape_children(ctx, element)
    textured_lamp = isinstance(emission, Texture)
    if ((material is not None and material.textured) or textured_lamp) and kind in (
        "cube",
        "sphere",
        "disk",
    ):
        what = "an emitted radiance texture" if textured_lamp else "a textured BSDF"
        raise ctx.error(
            element,
            f"{what} on a {kind} shape is not supported (dualight does not lay out Mitsuba's "
            "texture coordinates on it); use a mesh with texture coordinates",
        )
    v, f, normals, uv, label = _shape_geometry(ctx, element, kind, props, sphere_subdivisions)
    if material is None:  # Mitsuba's default BSDF: diffuse 0.5, black on emitters
        emits = textured_lamp or any(e > 0.0 for e in emission)  # type: ignore[union-attr]
        material = Diffuse((0.0,) * 3 if emits else (0.5,) * 3)
    mesh = _Mesh(v, f, normals, uv, material, emission, element.get("id") or f"{label}{index}")
    mesh = _transformed(mesh, to_world, kind in _ANALYTIC, mesh.name)
    if _boolean(ctx, props.get("flip_normals"), False):
        normals = None if mesh.normals is None else -mesh.normals
        mesh = mesh._replace(f=mesh.f[:, ::-1], normals=normals)
    return [mesh]


def _instance(
    ctx: _Context,
    element: ET.Element,
    to_world: np.ndarray,
    name: str,
) -> list[_Mesh]:
    """An ``instance``'s copies of the meshes of the ``<shapegroup>`` it references, moved by
    its ``to_world`` as Mitsuba's instances move their shapes (normals as normals)."""
    refs = [c for c in element if c.tag == "ref"]
    others = [c for c in element if c.tag not in ("ref", "transform")]
    if len(refs) != 1 or others:
        raise ctx.error(element, "an instance holds one <ref id> to a shapegroup (and to_world)")
    group: list[_Mesh] = ctx.ref(refs[0], "shapegroup")
    return [_transformed(m, to_world, True, f"{name}/{m.name}") for m in group]


def _shapegroup(
    ctx: _Context,
    element: ET.Element,
    sphere_subdivisions: int,
) -> list[_Mesh]:
    """A ``<shapegroup id>``'s meshes (they render only where instanced)."""
    if element.get("id") is None:
        raise ctx.error(element, "a shapegroup needs an id to be instanced")
    meshes: list[_Mesh] = []
    for index, child in enumerate(element):
        if child.tag != "shape" or ctx.attr(child, "type") == "instance":
            raise ctx.error(child, "a shapegroup holds shapes only (not instances)")
        meshes += _shape(ctx, child, index, sphere_subdivisions)
    return meshes


def _add_meshes(ctx: _Context, element: ET.Element, scene: Scene, meshes: list[_Mesh]) -> None:
    for mesh in meshes:
        try:
            scene.add_mesh(
                mesh.v,
                mesh.f,
                emission=mesh.emission,
                material=mesh.material,
                name=mesh.name,
                degenerate="drop",
                normals=mesh.normals,
                uv=mesh.uv,
            )
        except ValueError as exc:
            raise ctx.error(element, str(exc)) from None
