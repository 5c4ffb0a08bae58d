"""Wavefront OBJ + MTL: :func:`load_obj` (read with trimesh, a maintained mesh library)."""

from __future__ import annotations

import math
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from dualight.io._common import (
    RGB,
    PathLike,
    _existing_file,
    _loaded_normals,
    _loaded_uv,
    _mesh_arrays,
    _trimesh_geometries,
)
from dualight.materials import Diffuse, Material, RoughConductor, RoughPlastic
from dualight.scene import Scene
from dualight.textures import Bitmap, Texture

__all__ = ["load_obj"]

# --------------------------------------------------------------------------------------------
# Wavefront OBJ + MTL

# MTL statements that change how a surface looks but that dualight does not model.
_MTL_IGNORED = ("map_ke", "map_ks", "map_bump", "bump", "map_d", "ks", "tr", "d", "ni")


def _mtl_floats(value: Any, key: str, where: str) -> RGB:
    items = value if isinstance(value, list | tuple) else str(value).split()
    try:
        numbers = [float(x) for x in items]
    except (TypeError, ValueError):
        raise ValueError(f"{where}: {key} must be numbers, got {value!r}") from None
    if len(numbers) == 1:
        numbers *= 3
    if len(numbers) != 3 or not all(math.isfinite(x) for x in numbers):
        raise ValueError(f"{where}: {key} must be 1 or 3 finite numbers, got {value!r}")
    return (numbers[0], numbers[1], numbers[2])


def _read_mtl_files(obj: Path, text: str) -> dict[str, dict[str, Any]]:
    """The materials of every ``mtllib`` the OBJ's ``text`` names, parsed by trimesh (keys lower
    case)."""
    from trimesh.exchange.obj import parse_mtl

    materials: dict[str, dict[str, Any]] = {}
    for line in text.splitlines():
        parts = line.strip().split(maxsplit=1)
        if len(parts) == 2 and parts[0] == "mtllib":
            mtl = obj.parent / parts[1].strip()
            try:  # a name the file system cannot hold (too long, NUL) is a bad file too
                found = mtl.is_file()
                mtl_text = mtl.read_text(errors="replace") if found else ""
            except (OSError, ValueError) as exc:
                raise ValueError(
                    f"cannot read MTL file {parts[1].strip()[:80]!r} named by mtllib in "
                    f"{str(obj)!r}: {exc}"
                ) from exc
            if not found:
                raise FileNotFoundError(
                    f"no such MTL file: {str(mtl)!r} (named by mtllib in {str(obj)!r})"
                )
            try:
                parsed = parse_mtl(mtl_text)
            except Exception as exc:  # noqa: BLE001
                raise ValueError(f"cannot read MTL file {str(mtl)!r}: {exc}") from exc
            # trimesh consumes texture statements (map_Kd, ...) while it parses: note which
            # statements each material had, to warn about those dualight ignores.
            current = None
            for statement in mtl_text.splitlines():
                words = statement.split()
                if not words:
                    continue
                if words[0] == "newmtl" and len(words) > 1:
                    current = statement.split(maxsplit=1)[1].strip()
                elif current in parsed:
                    parsed[current].setdefault("_statements", {})[words[0].lower()] = words[1:]
            for props in parsed.values():
                props["_folder"] = mtl.parent  # where its texture files are
            materials.update(parsed)
    return materials


def _obj_text(obj: Path) -> tuple[str, list[str], bool]:
    """The OBJ file's text with its relative (negative) indices made absolute, the material
    names its ``usemtl`` statements use, in order, and whether a position is used with more
    than one texture coordinate or normal (``f 1/1/1 ... f 1/5/2``; trimesh then has to split
    the faces' ``v/vt/vn`` index streams into unique vertex triples, see :func:`_obj_meshes`).

    The OBJ format counts a negative index back from the elements read *so far*; trimesh
    counts it from the end of the file, so such indices are resolved here first. Index 0 and a
    relative index before the first element are refused with the line number."""
    try:
        text = obj.read_bytes().decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ValueError(
            f"cannot read OBJ file {str(obj)!r}: not a UTF-8 or ASCII text file "
            f"({exc.reason} at byte {exc.start})"
        ) from None
    except OSError as exc:
        raise ValueError(f"cannot read OBJ file {str(obj)!r}: {exc}") from exc
    counts = {"v": 0, "vt": 0, "vn": 0}
    materials: list[str] = []
    lines = text.splitlines()
    changed = False
    attributes: dict[str, str] = {}  # position index -> its first "vt/vn" indices
    split = False
    for number, line in enumerate(lines, start=1):
        words = line.split()
        if not words:
            continue
        if words[0] in counts:
            counts[words[0]] += 1
        elif words[0] == "usemtl" and len(words) > 1:
            materials.append(line.split(maxsplit=1)[1].strip())
        elif words[0] in ("f", "l", "p"):
            resolved = [_absolute(w, counts, obj, number) for w in words[1:]]
            if resolved != words[1:]:
                lines[number - 1] = " ".join([words[0], *resolved])
                changed = True
            for corner in resolved:
                position, _, rest = corner.partition("/")
                split = split or attributes.setdefault(position, rest) != rest
    return ("\n".join(lines) + "\n" if changed else text), materials, split


def _obj_meshes(obj: Path, text: str, split: bool) -> list[tuple[str, Any]]:
    """The triangle meshes of an OBJ file's (resolved) ``text``, as trimesh reads them.

    Vertices keep the file's order unless a position carries different texture coordinates or
    normals in different faces (``split``): trimesh then makes one vertex per distinct
    ``v/vt/vn`` triple, as Mitsuba does, since keeping the order would give such a position
    only one of its texture coordinates and normals."""
    return _trimesh_geometries(obj, "obj", text, maintain_order=not split)


def _absolute(token: str, counts: dict[str, int], obj: Path, line: int) -> str:
    """One face corner ``v[/vt[/vn]]`` with negative indices resolved against ``counts``."""
    parts = token.split("/")
    for i, (part, kind) in enumerate(zip(parts, ("v", "vt", "vn"), strict=False)):
        if not part:
            continue
        try:
            index = int(part)
        except ValueError:
            continue  # trimesh reports what is not a number
        if index == 0:
            raise ValueError(
                f"OBJ file {str(obj)!r}, line {line}: face index 0 in {token!r} "
                "(OBJ indices start at 1; negative ones count back from the last element read)"
            )
        if index < 0:
            if -index > counts[kind]:
                raise ValueError(
                    f"OBJ file {str(obj)!r}, line {line}: relative index {index} in {token!r} "
                    f"refers before the first {kind!r} ({counts[kind]} read so far)"
                )
            parts[i] = str(counts[kind] + 1 + index)
    return "/".join(parts)


def load_obj(
    path: PathLike,
    *,
    scene: Scene | None = None,
    default_reflectance: RGB = (0.5, 0.5, 0.5),
    emission_scale: float = 1.0,
    face_normals: bool = False,
) -> Scene:
    """Load a Wavefront OBJ file and its MTL materials into a scene.

    The file is read with trimesh (a maintained mesh library): polygons are triangulated, and
    the faces are split into one dualight mesh per material (``usemtl``), named
    ``"<file stem>/<material>"``. Each material becomes a :class:`~dualight.Diffuse` with the
    MTL's diffuse colour ``Kd`` and an emission (W m^-2 sr^-1, one-sided, on the
    right-hand-rule normal's side) from its ``Ke``, its ``map_Kd`` image (a
    :class:`~dualight.Bitmap`, which replaces ``Kd``) read beside the MTL file; a material
    with a specular ``Ks`` becomes the nearest microfacet material instead (a
    :class:`~dualight.RoughPlastic` over ``Kd``, or without ``Kd`` a
    :class:`~dualight.RoughConductor`, Beckmann roughness from ``Ns``),
    with a ``UserWarning`` that it is approximate. Faces without a material get
    ``default_reflectance`` and no emission. MTL statements dualight does not model (other
    texture maps, transparency ``d``/``Tr``, ``Ni``) are ignored with a
    ``UserWarning``. Texture coordinates (``vt``) become the mesh's ``uv`` (v flipped as
    Mitsuba reads them, so images appear upright). Vertex normals (``vn``) shade the
    mesh smoothly, as in Mitsuba and pbrt, unless ``face_normals``; faces without them are
    flat. Zero-area triangles are dropped with a warning.

    Parameters
    ----------
    path : str or pathlib.Path
        The ``.obj`` file; ``mtllib`` files are looked up beside it.
    scene : dualight.Scene, optional
        Add the meshes to this scene (its camera is kept) instead of a new one without a
        camera.
    default_reflectance : tuple of 3 float, optional
        Albedo of faces without a material.
    emission_scale : float, optional
        Factor applied to every ``Ke`` (MTL files carry no unit), ``>= 0``.
    face_normals : bool, optional
        Ignore the file's vertex normals and shade every triangle flat (Mitsuba's
        ``face_normals``).

    Returns
    -------
    dualight.Scene
        ``scene`` if given, else a new scene; set its ``camera`` before rendering.

    Raises
    ------
    FileNotFoundError
        If the OBJ file or an MTL file it names does not exist.
    ValueError
        If the file cannot be parsed, has no faces, a colour is not finite or a ``Kd`` lies
        outside ``[0, 1]``.

    Examples
    --------
    >>> scene = dualight.load_obj("room.obj")
    >>> scene.camera = dualight.Camera(origin=(0, 1, 4), target=(0, 1, 0))
    """
    obj = _existing_file(path, "OBJ")
    scale = float(emission_scale)
    if not (math.isfinite(scale) and scale >= 0.0):
        raise ValueError(f"emission_scale must be finite and >= 0, got {emission_scale!r}")
    if scene is None:
        scene = Scene()
    elif not isinstance(scene, Scene):
        raise TypeError(f"scene must be a dualight.Scene, got {type(scene).__name__}")
    text, used, split = _obj_text(obj)
    mtl = _read_mtl_files(obj, text)
    undefined = list(dict.fromkeys(m for m in used if m not in mtl))
    if undefined:
        warnings.warn(
            f"{str(obj)!r}: usemtl names materials no mtllib defines "
            f"({', '.join(repr(m) for m in undefined[:10])}"
            f"{', ...' if len(undefined) > 10 else ''}); their faces get default_reflectance "
            f"{tuple(default_reflectance)} and no emission",
            UserWarning,
            stacklevel=2,
        )
    geometries = _obj_meshes(obj, text, split)
    ignored: dict[str, list[str]] = {}
    approximated: dict[str, str] = {}
    pending: list[tuple[np.ndarray, np.ndarray, Material, RGB, str, Any, Any]] = []
    for key, geom in geometries:
        material = getattr(getattr(geom, "visual", None), "material", None)
        mname = getattr(material, "name", None)
        where = f"{str(obj)!r}, material {mname!r}"
        props = mtl.get(mname) if mname else None
        rho, Le = tuple(default_reflectance), (0.0, 0.0, 0.0)
        if props is not None:
            if "kd" in props:
                rho = _mtl_floats(props["kd"], "Kd", where)
            if "ke" in props:
                Le = _mtl_floats(props["ke"], "Ke", where)
            statements = props.get("_statements", {})
            skipped = [
                k for k in _MTL_IGNORED if k in statements and not _neutral(k, statements[k])
            ]
        albedo: Any = rho
        if props is not None and statements.get("map_kd"):
            albedo = _map_kd(statements["map_kd"], props["_folder"], where)
        try:
            diffuse: Material = Diffuse(albedo)
        except ValueError as exc:
            raise ValueError(f"{where}: Kd: {exc}") from None
        if props is not None:
            phong = _phong_material(albedo, statements, where)
            if phong is not None:
                diffuse = phong
                approximated[str(mname)] = type(phong).__name__
                skipped = [k for k in skipped if k != "ks"]
            if skipped:
                ignored[str(mname)] = skipped
        name = f"{obj.stem}/{mname}" if mname else f"{obj.stem}/{key}"
        v, f = _mesh_arrays(geom, str(obj))
        normals = None if face_normals else _loaded_normals(geom)
        emission = (Le[0] * scale, Le[1] * scale, Le[2] * scale)
        pending.append((v, f, diffuse, emission, name, normals, _loaded_uv(geom, "obj")))
    for v, f, material, emission, name, normals, uv in pending:
        scene.add_mesh(
            v,
            f,
            emission=emission,
            material=material,
            name=name,
            degenerate="drop",
            normals=normals,
            uv=uv,
        )
    if approximated:
        what = ", ".join(f"{m} as {kind}" for m, kind in approximated.items())
        warnings.warn(
            f"{str(obj)!r}: MTL Phong lobes (Ks, Ns) approximated by microfacet materials "
            f"({what}; Beckmann alpha = sqrt(2 / (Ns + 2)))",
            UserWarning,
            stacklevel=2,
        )
    if ignored:
        what = "; ".join(f"{m}: {', '.join(keys)}" for m, keys in ignored.items())
        warnings.warn(
            f"{str(obj)!r}: MTL statements dualight does not model were ignored ({what}); "
            "only Kd and map_Kd (diffuse), Ks and Ns (a Phong lobe) and Ke (emission) are used",
            UserWarning,
            stacklevel=2,
        )
    return scene


def _map_kd(words: list[str], folder: Path, where: str) -> Any:
    """An MTL ``map_Kd`` as a :class:`~dualight.Bitmap` (the file is its last word, relative to
    the MTL file), which replaces ``Kd`` as in pbrt (Mitsuba reads no MTL)."""
    path = folder / words[-1]
    if len(words) > 1:
        warnings.warn(
            f"{where}: map_Kd options {' '.join(words[:-1])!r} are ignored",
            UserWarning,
            stacklevel=4,
        )
    try:
        return Bitmap(path)
    except (ValueError, FileNotFoundError) as exc:
        raise type(exc)(f"{where}: map_Kd: {exc}") from None


def _phong_material(rho: Any, statements: dict[str, Any], where: str) -> Material | None:
    """The nearest dualight material to an MTL Phong lobe (``Ks`` non-zero), or None.

    The Phong exponent ``Ns`` becomes a Beckmann roughness ``alpha = sqrt(2 / (Ns + 2))``
    [Walter et al. 2007, eq. 32]; with a diffuse ``Kd`` the surface is a
    :class:`~dualight.RoughPlastic` (IOR 1.5, ``Ks`` as its specular reflectance, each channel
    clipped to ``[0, 1]``), without one a white :class:`~dualight.RoughConductor` scaled by
    ``Ks``. Both are approximations: an MTL Phong lobe has no Fresnel term and no coat.
    """
    if "ks" not in statements:
        return None
    try:
        ks = [float(x) for x in statements["ks"]]
        ns = float(statements["ns"][0]) if statements.get("ns") else 0.0
    except (TypeError, ValueError, IndexError):
        raise ValueError(f"{where}: Ks and Ns must be numbers") from None
    if len(ks) == 1:
        ks = ks * 3
    if len(ks) != 3 or not all(math.isfinite(x) for x in [*ks, ns]) or ns < 0:
        raise ValueError(f"{where}: Ks must be 1 or 3 finite numbers and Ns finite and >= 0")
    if not any(x > 0.0 for x in ks):
        return None
    spec = tuple(min(max(x, 0.0), 1.0) for x in ks)
    alpha = max(math.sqrt(2.0 / (ns + 2.0)), 1e-3)
    if isinstance(rho, Texture) or any(c > 0.0 for c in rho):
        return RoughPlastic(
            diffuse_reflectance=rho, specular_reflectance=spec, alpha=alpha, ior=1.5
        )
    return RoughConductor(alpha=alpha, specular_reflectance=spec)


def _neutral(key: str, value: Any) -> bool:
    """Whether an ignored MTL statement leaves the look of a diffuse surface unchanged."""
    try:
        numbers = [float(x) for x in (value if isinstance(value, list | tuple) else [value])]
    except (TypeError, ValueError):
        return False
    if key in ("ks",):
        return all(x == 0.0 for x in numbers)
    if key == "d":
        return all(x == 1.0 for x in numbers)
    if key == "tr":
        return all(x == 0.0 for x in numbers)
    return key == "ni"  # an index of refraction alone does nothing without transparency
