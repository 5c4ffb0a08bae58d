"""Helpers shared by the scene-file readers: file checks and trimesh's OBJ/PLY loading."""

from __future__ import annotations

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


def _trimesh_geometries(path: Path, file_type: str) -> list[tuple[str, Any]]:
    """The triangle meshes of an OBJ or PLY file as ``(name, trimesh.Trimesh)`` pairs, in file
    order, with vertices neither merged nor reordered."""
    import trimesh

    if file_type == "obj":
        try:
            path.read_bytes().decode("utf-8")
        except UnicodeDecodeError as exc:
            raise ValueError(
                f"cannot read OBJ file {str(path)!r}: not a UTF-8 or ASCII text file "
                f"({exc.reason} at byte {exc.start})"
            ) from None
    try:
        loaded = trimesh.load(
            str(path),
            file_type=file_type,
            force="scene",
            process=False,
            maintain_order=True,
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


def _mesh_arrays(geom: Any, where: str) -> tuple[np.ndarray, np.ndarray]:
    v = np.asarray(geom.vertices, dtype=np.float64)
    f = np.asarray(geom.faces, dtype=np.int64)
    if not np.all(np.isfinite(v)):
        raise ValueError(f"{where}: a vertex is not finite (NaN or Inf)")
    if f.size and (f.min() < 0 or f.max() >= len(v)):
        raise ValueError(f"{where}: a face index is out of range for {len(v)} vertices")
    return v, f
