"""Helpers shared by the scene-file readers: file checks and trimesh's OBJ/PLY loading."""

from __future__ import annotations

import io
from pathlib import Path
from typing import Any

import numpy as np

PathLike = str | Path
RGB = tuple[float, float, float]

# --------------------------------------------------------------------------------------------
# Shared helpers


def _existing_file(path: PathLike, what: str) -> Path:
    p = Path(path)
    if not p.is_file():
        raise FileNotFoundError(f"no such {what} file: {str(p)!r}")
    return p


def _trimesh_geometries(
    path: Path, file_type: str, text: str | None = None, maintain_order: bool = True
) -> list[tuple[str, Any]]:
    """The triangle meshes of an OBJ or PLY file as ``(name, trimesh.Trimesh)`` pairs, in file
    order, with vertices neither merged nor reordered (unless not ``maintain_order``: an OBJ's
    vertices are then one per distinct ``v/vt/vn`` triple of its faces). ``text``, if given, is
    read instead of the file's contents (files it names are still looked up beside ``path``)."""
    import trimesh
    import trimesh.resolvers

    if file_type == "ply":
        _check_ply_header(path)
    source: Any = str(path)
    resolver = None
    if text is not None:
        source = io.BytesIO(text.encode("utf-8"))
        resolver = trimesh.resolvers.FilePathResolver(str(path))
    try:
        loaded = trimesh.load(
            source,
            file_type=file_type,
            resolver=resolver,
            force="scene",
            process=False,
            maintain_order=maintain_order,
        )
    except Exception as exc:  # noqa: BLE001 - the library raises many kinds on bad files
        raise ValueError(f"cannot read {file_type.upper()} file {str(path)!r}: {exc}") from exc
    meshes = [
        (str(name), geom)
        for name, geom in loaded.geometry.items()
        if isinstance(geom, trimesh.Trimesh) and len(geom.faces) > 0
    ]
    if not meshes:
        raise ValueError(f"{file_type.upper()} file {str(path)!r} has no triangles or polygons")
    return meshes


# A PLY element count beyond this is refused before the body is read: the core holds vertex
# indices in 32 bits, and trimesh would otherwise allocate for the declared count (or report
# the short file as having no triangles).
_PLY_MAX_ELEMENTS = 2**31 - 1


def _check_ply_header(path: Path) -> None:
    """Refuse a PLY file whose header declares absurd element counts, or more elements than
    its body can hold, naming the element; before anything is allocated for them."""
    with path.open("rb") as file:
        header = file.read(65536)
    end = header.find(b"end_header")
    if not header.startswith(b"ply") or end < 0:
        return  # trimesh reports a malformed header itself
    newline = header.find(b"\n", end)
    body = path.stat().st_size - (newline + 1 if newline >= 0 else len(header))
    # Each element with a property takes at least one byte in a binary body and two (a number
    # and a separator) in an ASCII one.
    fits = body if b"binary" in header[:end] else (body + 1) // 2
    elements: list[tuple[str, int, bool]] = []
    for line in header[:end].splitlines():
        words = line.split()
        if len(words) == 3 and words[0] == b"element":
            name = words[1].decode("ascii", "replace")
            try:
                elements.append((name, int(words[2]), False))
            except ValueError:
                raise ValueError(
                    f"cannot read PLY file {str(path)!r}: element {name!r} has count "
                    f"{words[2].decode('ascii', 'replace')!r}, not a whole number"
                ) from None
        elif words[:1] == [b"property"] and elements:
            elements[-1] = (elements[-1][0], elements[-1][1], True)
    for name, n, has_properties in elements:
        if n < 0 or n > _PLY_MAX_ELEMENTS or (has_properties and n > fits):
            raise ValueError(
                f"cannot read PLY file {str(path)!r}: its header declares {n} {name!r} "
                f"elements, more than its {body}-byte body can hold"
                + (f" (and more than {_PLY_MAX_ELEMENTS})" if n > _PLY_MAX_ELEMENTS else "")
            )


def _mesh_arrays(geom: Any, where: str) -> tuple[np.ndarray, np.ndarray]:
    v = np.asarray(geom.vertices, dtype=np.float64)
    f = np.asarray(geom.faces, dtype=np.int64)
    if not np.all(np.isfinite(v)):
        raise ValueError(f"{where}: a vertex is not finite (NaN or Inf)")
    if f.size and (f.min() < 0 or f.max() >= len(v)):
        raise ValueError(f"{where}: a face index is out of range for {len(v)} vertices")
    return v, f


def _loaded_normals(geom: Any) -> np.ndarray | None:
    """The vertex normals an OBJ/PLY file gave (``vn``, ``nx ny nz``), or None: trimesh
    computes normals on request, so only those it holds from loading are taken."""
    if "vertex_normals" not in geom._cache:
        return None
    n = np.asarray(geom._cache["vertex_normals"], dtype=np.float64)
    if n.shape != (len(geom.vertices), 3):
        return None
    length = np.linalg.norm(n, axis=1)
    return n if np.all(np.isfinite(length) & (length > 0.0)) else None


def _angle_weighted_normals(v: np.ndarray, f: np.ndarray) -> np.ndarray | None:
    """Smooth vertex normals as Mitsuba 3 computes them for meshes without any: each face's unit
    normal weighted by its angle at the vertex [Thuermer and Wuethrich 1998]. None where they
    equal the face normals everywhere (every vertex shared only by coplanar triangles), so flat
    meshes stay flat."""
    e = [v[f[:, (k + 1) % 3]] - v[f[:, k]] for k in range(3)]
    n = np.cross(e[0], -e[2])
    length = np.linalg.norm(n, axis=1, keepdims=True)
    n = n / np.where(length > 0, length, 1.0)
    summed = np.zeros_like(v)
    for k in range(3):
        d0, d1 = e[k], -e[(k + 2) % 3]
        l0 = np.linalg.norm(d0, axis=1)
        l1 = np.linalg.norm(d1, axis=1)
        cos = np.einsum("ij,ij->i", d0, d1) / np.maximum(l0 * l1, 1e-300)
        np.add.at(summed, f[:, k], n * np.arccos(np.clip(cos, -1.0, 1.0))[:, None])
    length = np.linalg.norm(summed, axis=1, keepdims=True)
    vn = summed / np.where(length > 0, length, 1.0)
    if not np.any(np.einsum("tkj,tj->tk", vn[f], n) < 1.0 - 1e-6):
        return None
    used = np.zeros(len(v), dtype=bool)
    used[f.ravel()] = True
    vn[~used | (length[:, 0] == 0)] = (0.0, 0.0, 1.0)  # unused vertices need some valid normal
    return vn


def _loaded_uv(geom: Any, file_type: str) -> np.ndarray | None:
    """The texture coordinates an OBJ/PLY file gave per vertex, as Mitsuba reads them (an OBJ's
    ``vt`` with v flipped, ``1 - v``, so images appear upright; a PLY's as they are: ``u v``,
    ``s t``, ``texture_u texture_v`` or ``texture_s texture_t``), or None."""
    uv = getattr(getattr(geom, "visual", None), "uv", None)
    if uv is None and file_type == "ply":
        uv = _ply_texture_st(geom)
    if uv is None:
        return None
    uv = np.asarray(uv, dtype=np.float64)
    if uv.shape != (len(geom.vertices), 2) or not np.all(np.isfinite(uv)):
        return None
    if file_type == "obj":
        uv = np.column_stack([uv[:, 0], 1.0 - uv[:, 1]])
    return uv


def _ply_texture_st(geom: Any) -> np.ndarray | None:
    """A PLY's ``texture_s``/``texture_t`` vertex properties (which Mitsuba reads as texture
    coordinates and trimesh does not), from trimesh's raw PLY data, or None."""
    raw = getattr(geom, "metadata", {}).get("_ply_raw", {}).get("vertex", {}).get("data")
    # A structured array for a binary body, a dict of (V, 1) columns for an ASCII one.
    names = (
        raw.keys() if isinstance(raw, dict) else getattr(getattr(raw, "dtype", None), "names", None)
    )
    if not names or "texture_s" not in names or "texture_t" not in names:
        return None
    return np.column_stack([np.ravel(raw["texture_s"]), np.ravel(raw["texture_t"])])
