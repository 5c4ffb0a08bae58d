"""Writing a :class:`~dualight.Scene` as a Mitsuba 3 XML file: :func:`save_mitsuba_xml`."""

from __future__ import annotations

import functools
import xml.etree.ElementTree as ET
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from dualight.emitters import (
    ConstantEnvironment,
    DirectionalLight,
    Emitter,
    EnvironmentMap,
    PointLight,
)
from dualight.io._common import PathLike
from dualight.materials import Material
from dualight.scene import Scene
from dualight.textures import uv_matrix4

__all__ = ["save_mitsuba_xml"]

# --------------------------------------------------------------------------------------------
# Writer


def _fmt(values: Any) -> str:
    return ", ".join(repr(float(x)) for x in np.atleast_1d(values))


def _element(parent: ET.Element, tag: str, **attrib: Any) -> ET.Element:
    return ET.SubElement(parent, tag, {k: str(v) for k, v in attrib.items()})


def _write_plugin(
    parent: ET.Element,
    tag: str,
    plugin: dict[str, Any],
    name: str = "",
    save_texels: Callable[[np.ndarray], str] | None = None,
) -> None:
    """A Mitsuba plugin dict (``mitsuba.load_dict`` form, textures as
    :meth:`dualight.textures.Texture._mitsuba_dict` gives them) as an XML element; an array
    texture's texels go to a file through ``save_texels``, which returns its name."""
    attrib = {"type": plugin["type"]} | ({"name": name} if name else {})
    element = _element(parent, tag, **attrib)
    for key, value in plugin.items():
        if key == "type":
            continue
        if isinstance(value, dict) and value.get("type") == "rgb":
            _element(element, "rgb", name=key, value=_fmt(value["value"]))
        elif isinstance(value, dict) and value.get("type") in _TEXTURES:
            _write_plugin(element, "texture", value, key, save_texels)
        elif isinstance(value, dict):
            _write_plugin(element, tag, value, save_texels=save_texels)
        elif key == "to_uv":
            transform = _element(element, "transform", name="to_uv")
            _element(transform, "matrix", value=_fmt(np.ravel(uv_matrix4(value))))
        elif key == "texels":
            if save_texels is None:
                raise ValueError("a texture made from an array needs a folder for its image")
            _element(element, "string", name="filename", value=save_texels(value))
        elif isinstance(value, bool):
            _element(element, "boolean", name=key, value=str(value).lower())
        elif isinstance(value, str):
            _element(element, "string", name=key, value=value)
        else:
            _element(element, "float", name=key, value=repr(float(value)))


_TEXTURES = ("bitmap", "checkerboard")


def _save_texels(folder: Path, key: str, texels: np.ndarray) -> str:
    """Writes an array texture's linear texels as ``<key>_texture<n>.exr`` in ``folder``;
    returns its name relative to the XML file."""
    from dualight import _core

    n = len(list(folder.glob(f"{key}_texture*.exr")))
    path = folder / f"{key}_texture{n}.exr"
    data = np.ascontiguousarray(np.repeat(texels, 3, axis=2) if texels.shape[2] == 1 else texels)
    _core.write_image(str(path), data.astype(np.float32), {})
    return f"{folder.name}/{path.name}"


def _write_bsdf(
    parent: ET.Element, material: Material, save_texels: Callable[[np.ndarray], str] | None = None
) -> None:
    if not isinstance(material, Material):
        raise TypeError(f"unknown material {type(material).__name__}")
    _write_plugin(parent, "bsdf", material._mitsuba_bsdf(), save_texels=save_texels)


def _write_emitter(
    root: ET.Element, light: Emitter, save_texels: Callable[[np.ndarray], str]
) -> None:
    """An emitter without a surface as Mitsuba 3's stand-alone emitter (an environment map made
    from an array writes its image through ``save_texels``)."""
    if isinstance(light, DirectionalLight):
        emitter = _element(root, "emitter", type="directional")
        _element(emitter, "vector", name="direction", value=_fmt(light.direction))
        _element(emitter, "rgb", name="irradiance", value=_fmt(light.irradiance))
        return
    if isinstance(light, ConstantEnvironment):
        emitter = _element(root, "emitter", type="constant")
        _element(emitter, "rgb", name="radiance", value=_fmt(light.radiance))
        return
    if isinstance(light, EnvironmentMap):
        emitter = _element(root, "emitter", type="envmap")
        name = str(light.filename) if light.filename is not None else save_texels(light.texels)
        _element(emitter, "string", name="filename", value=name)
        _element(emitter, "float", name="scale", value=repr(light.scale))
        m = np.eye(4)
        m[:3, :3] = light.to_world
        transform = _element(emitter, "transform", name="to_world")
        _element(transform, "matrix", value=_fmt(np.ravel(m)))
        return
    if isinstance(light, PointLight):
        emitter = _element(root, "emitter", type="point")
        _element(emitter, "point", name="position", value=_fmt(light.position))
    else:
        emitter = _element(root, "emitter", type="spot")
        origin, target, up = light._look_at()
        transform = _element(emitter, "transform", name="to_world")
        _element(transform, "lookat", origin=_fmt(origin), target=_fmt(target), up=_fmt(up))
        _element(emitter, "float", name="cutoff_angle", value=repr(light.cutoff_angle))
        _element(emitter, "float", name="beam_width", value=repr(light.beam_width))
    _element(emitter, "rgb", name="intensity", value=_fmt(light.intensity))


def save_mitsuba_xml(
    scene: Scene,
    path: PathLike,
    *,
    spp: int = 64,
    max_depth: int = -1,
    rr_depth: int = 5,
) -> Path:
    """Write ``scene`` as a Mitsuba 3 XML file, with its meshes as binary PLY files beside it.

    The file describes the same scene as :func:`dualight.mitsuba.scene_dict` (path tracer
    with ``max_depth``, ``rr_depth`` and visible emitters; perspective sensor with the fov
    along x and ``look_at``; ``hdrfilm`` with a box filter; independent sampler with ``spp``;
    each mesh a ``ply`` shape with ``face_normals``, or with its shading normals, its
    material's BSDF and maybe an area emitter), so ``mitsuba.load_file(path)`` renders what
    ``mitsuba.load_dict(scene.to_mitsuba(...))`` renders. The meshes go to the folder
    ``<stem>_meshes`` next to the XML file (created or overwritten), one ``<name>.ply`` each,
    with float32 vertices (as both renderers use them). :func:`load_mitsuba_xml` reads the file
    back.

    Parameters
    ----------
    scene : dualight.Scene
        A scene with a camera, meshes and at least one emitter.
    path : str or pathlib.Path
        The XML file to write; its folder must exist.
    spp : int, optional
        The sampler's ``sample_count``.
    max_depth, rr_depth : int, optional
        The path tracer's settings (``-1``: unbounded), as in
        :func:`dualight.mitsuba.scene_dict`.

    Returns
    -------
    pathlib.Path
        The XML file's path.

    Raises
    ------
    FileNotFoundError
        If the folder of ``path`` does not exist.
    ValueError
        If the scene cannot be rendered (no camera, no emitter, empty) or a setting is invalid.
    """
    import trimesh

    from dualight.mitsuba import _key

    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a dualight.Scene, got {type(scene).__name__}")
    scene.validate_for_rendering()
    for name, value, low in (("spp", spp, 1), ("rr_depth", rr_depth, 1)):
        if isinstance(value, bool) or int(value) != value or value < low:
            raise ValueError(f"{name} must be a positive integer, got {value!r}")
    if int(max_depth) != max_depth or (max_depth < 1 and max_depth != -1):
        raise ValueError(f"max_depth must be -1 or a positive integer, got {max_depth}")
    out = Path(path)
    if not out.parent.is_dir():
        raise FileNotFoundError(f"directory does not exist: {str(out.parent)!r}")
    mesh_dir = out.parent / f"{out.stem}_meshes"
    mesh_dir.mkdir(exist_ok=True)

    cam = scene.camera
    assert cam is not None  # validate_for_rendering checked it
    lo, hi = scene.bounds()
    corners = np.array(
        [[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    )
    far_clip = max(4.0 * float(np.max(np.linalg.norm(corners - cam.origin, axis=1))), 1e-3)

    root = ET.Element("scene", version="3.0.0")
    robust = "true" if scene.robust_intersections else "false"
    _element(root, "boolean", name="embree_use_robust_intersections", value=robust)
    integrator = _element(root, "integrator", type="path")
    _element(integrator, "integer", name="max_depth", value=int(max_depth))
    _element(integrator, "integer", name="rr_depth", value=int(rr_depth))
    _element(integrator, "boolean", name="hide_emitters", value="false")
    sensor = _element(root, "sensor", type="perspective")
    _element(sensor, "float", name="fov", value=repr(float(cam.fov)))
    _element(sensor, "string", name="fov_axis", value="x")
    _element(sensor, "float", name="near_clip", value=repr(far_clip * 1e-6))
    _element(sensor, "float", name="far_clip", value=repr(far_clip))
    to_world = _element(sensor, "transform", name="to_world")
    _element(
        to_world,
        "lookat",
        origin=_fmt(cam.origin),
        target=_fmt(cam.target),
        up=_fmt(cam.up),
    )
    film = _element(sensor, "film", type="hdrfilm")
    _element(film, "integer", name="width", value=cam.width)
    _element(film, "integer", name="height", value=cam.height)
    _element(film, "string", name="pixel_format", value="rgb")
    _element(film, "string", name="component_format", value="float32")
    _element(film, "rfilter", type="box")
    sampler = _element(sensor, "sampler", type="independent")
    _element(sampler, "integer", name="sample_count", value=int(spp))

    used = {"integrator", "sensor", "type"}
    for mesh in scene.meshes:
        key = _key(mesh.name, used)
        ply = mesh_dir / f"{key}.ply"
        smooth = mesh.normals is not None
        tm = trimesh.Trimesh(
            mesh.vertices.astype(np.float32),
            mesh.triangles,
            vertex_normals=mesh.normals if smooth else None,
            visual=None if mesh.uv is None else trimesh.visual.TextureVisuals(uv=mesh.uv),
            process=False,
            validate=False,
        )
        tm.export(str(ply), file_type="ply", encoding="binary", vertex_normal=smooth)
        shape = _element(root, "shape", type="ply", id=key)
        _element(shape, "string", name="filename", value=f"{mesh_dir.name}/{ply.name}")
        _element(shape, "boolean", name="face_normals", value="false" if smooth else "true")
        _write_bsdf(shape, mesh.material, functools.partial(_save_texels, mesh_dir, key))
        if mesh.is_emitter:
            save = functools.partial(_save_texels, mesh_dir, f"{key}_emitter")
            _write_plugin(shape, "emitter", mesh._mitsuba_emitter(), save_texels=save)
    for i, light in enumerate(scene.emitters):
        _write_emitter(root, light, functools.partial(_save_texels, mesh_dir, f"emitter{i}"))
    ET.indent(root)
    out.write_text(
        "<!-- Written by dualight.save_mitsuba_xml -->\n"
        + ET.tostring(root, encoding="unicode")
        + "\n"
    )
    return out
