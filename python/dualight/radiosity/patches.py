"""Patches: every input triangle (quads arrive split in two) subdivided into a regular grid of
``n x n`` smaller triangles, with ``n`` chosen from ``max_edge`` or ``max_area``.

Patches are one-sided, as in classical radiosity: each sends and receives light on the side of
its normal (the right-hand rule on the input triangle's vertex order, as everywhere in
dualight). Two-sided surfaces need a mesh per side.

Radiosity assumes diffuse surfaces: scenes with a :class:`~dualight.Mirror` or
:class:`~dualight.Dielectric` mesh are refused (:func:`require_diffuse`).
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from dualight.scene import Scene

if TYPE_CHECKING:
    from dualight import _core


def require_diffuse(scene: Scene) -> None:
    """Raise ``ValueError`` naming the first mesh of ``scene`` whose material is not a diffuse
    reflector (by its flags, :attr:`dualight.Material.is_diffuse_reflector`).

    Radiosity's linear system ``B = E + rho F B`` holds for Lambertian surfaces only; a mirror
    or glass would silently be rendered as something else.
    """
    for mesh in scene.meshes:
        if not mesh.material.is_diffuse_reflector:
            raise ValueError(
                f"radiosity assumes diffuse surfaces; mesh {mesh.name!r} is a "
                f"{type(mesh.material).__name__} (use dualight.render for specular scenes)"
            )


# Bytes a patch takes while a PatchMesh is built (numpy's peak, measured by tracemalloc at
# 0.1 to 0.5 million patches: 295 to 345; tests/test_radiosity.py checks this bound holds).
PATCH_BYTES = 360


def _available_bytes() -> int | None:
    """Memory the system can give without swapping (Linux's MemAvailable), or None."""
    try:
        with open("/proc/meminfo", encoding="ascii") as meminfo:
            for line in meminfo:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (AttributeError, ValueError, OSError):
        return None


def _check_memory(patches: float) -> None:
    """Refuse a subdivision whose patches would not fit in the memory available now."""
    needed = patches * PATCH_BYTES
    available = _available_bytes()
    if available is not None and needed > available:
        raise MemoryError(
            f"this subdivision makes {patches:.4g} patches, which need about "
            f"{needed / 2**30:.3g} GiB ({PATCH_BYTES} bytes each) while building them, but "
            f"{available / 2**30:.3g} GiB is available; use a larger max_edge or max_area"
        )


def _grid(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Barycentrics (b1, b2) of the grid vertices and the sub-triangles, for n divisions.

    Vertex (i, j), j <= n - i, is number ``i (n + 1) - i (i - 1) / 2 + j``; cell (i, j),
    j < n - i, holds an upright triangle and, where i + j <= n - 2, an inverted one after it.
    In numpy arrays throughout: Python tuples per vertex took over 100 bytes each."""
    i = np.repeat(np.arange(n + 1), np.arange(n + 1, 0, -1))
    j = np.arange(len(i)) - (i * (n + 1) - i * (i - 1) // 2)
    bary = np.stack([i, j], axis=1).astype(np.float64) / n
    ci = np.repeat(np.arange(n), np.arange(n, 0, -1))
    cj = np.arange(len(ci)) - (ci * n - ci * (ci - 1) // 2)

    def index(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return a * (n + 1) - a * (a - 1) // 2 + b

    up = np.stack([index(ci, cj), index(ci + 1, cj), index(ci, cj + 1)], axis=1)
    down = np.stack([index(ci + 1, cj), index(ci + 1, cj + 1), index(ci, cj + 1)], axis=1)
    keep = np.stack([np.ones(len(ci), bool), ci + cj <= n - 2], axis=1).reshape(-1)
    return bary, np.stack([up, down], axis=1).reshape(-1, 3)[keep].astype(np.int64)


def _albedo_points(n: int) -> np.ndarray:
    """Points where a textured patch's albedo is averaged: the centroids of an n x n split of
    the patch (n^2 sub-triangles), as barycentrics of its corners (equal areas, so the plain
    mean is the area mean)."""
    return np.array(
        [
            [1.0 - a - b, a, b]
            for i in range(n)
            for j in range(n - i)
            for a, b in [((i + 1 / 3) / n, (j + 1 / 3) / n), ((i + 2 / 3) / n, (j + 2 / 3) / n)][
                : 2 if i + j <= n - 2 else 1
            ]
        ]
    )


# Patches of the uniform solvers: 16 points each. Hierarchical radiosity's input triangles,
# larger and whose elements all keep their root's albedo: up to 4096 each (a checkerboard's
# edge crossing a triangle moved its 256-point mean by 0.03), about 4 million in all.
_ALBEDO_POINTS = _albedo_points(4)
_ROOT_POINTS_IN_ALL = 4_000_000


def _triangle_uv(mesh: Any, sel: np.ndarray) -> np.ndarray:
    """The (u, v) of the corners of mesh triangles ``sel``: (S, 3, 2). A mesh without texture
    coordinates uses each triangle's barycentrics, as the renderers do."""
    if mesh.uv is None:
        return np.broadcast_to([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], (len(sel), 3, 2))
    return mesh.uv[mesh.triangles[sel]]


def _patch_uv(
    mesh: Any, sel: np.ndarray, corner_bary: np.ndarray, *, textured: bool | None = None
) -> np.ndarray:
    """The (u, v) of the corners of mesh triangles ``sel``'s sub-triangles (barycentrics
    ``corner_bary``, (K, 3, 2)): (S * K, 3, 2), NaN where ``textured`` is false (by default,
    where the mesh's reflectance is not a texture)."""
    if not (mesh.material.textured if textured is None else textured):
        return np.full((len(sel) * len(corner_bary), 3, 2), np.nan)
    src = _triangle_uv(mesh, sel)  # (S, 3, 2)
    b1, b2 = corner_bary[None, :, :, 0:1], corner_bary[None, :, :, 1:2]
    uv = (
        (1 - b1 - b2) * src[:, None, None, 0]
        + b1 * src[:, None, None, 1]
        + b2 * src[:, None, None, 2]
    )
    return uv.reshape(-1, 3, 2)


def _texture_means(
    scene: Scene,
    mesh_index: np.ndarray,
    uv_corners: np.ndarray,
    at: np.ndarray = _ALBEDO_POINTS,
    *,
    emission: bool = False,
) -> np.ndarray:
    """Each patch's mean albedo over its area (its reflectance texture at the points ``at``),
    or (``emission``) its mean emitted radiance (its emission texture's)."""
    out = np.empty((len(mesh_index), 3))
    for m in np.unique(mesh_index):
        rows = np.nonzero(mesh_index == m)[0]
        points = np.einsum("qk,pkc->pqc", at, uv_corners[rows])  # (P, Q, 2)
        mesh = scene.meshes[m]
        texture = mesh.emission_texture if emission else mesh.material.reflectance
        values = texture.eval(points.reshape(-1, 2)).reshape(len(rows), -1, 3)
        out[rows] = values.mean(axis=1)
    return out


def triangle_albedo(scene: Scene) -> np.ndarray | None:
    """Per triangle of the compiled scene, ``(T, 3)``: its mesh's albedo, a texture's mean over
    the triangle where the mesh is textured (hierarchical radiosity's roots); None when no mesh
    is textured."""
    if not any(mesh.material.textured for mesh in scene.meshes):
        return None
    textured = sum(len(m.triangles) for m in scene.meshes if m.material.textured)
    at = _albedo_points(int(np.clip(np.sqrt(_ROOT_POINTS_IN_ALL / textured), 4, 64)))
    out = []
    for m, mesh in enumerate(scene.meshes):
        rows = np.broadcast_to(np.asarray(mesh.reflectance, np.float64), (len(mesh.triangles), 3))
        if mesh.material.textured:
            uv = _triangle_uv(mesh, np.arange(len(mesh.triangles)))
            rows = _texture_means(scene, np.full(len(rows), m), uv, at)
        out.append(rows)
    return np.concatenate(out)


def sub_triangle_uv(scene: Scene, root: np.ndarray, vertices: np.ndarray) -> np.ndarray:
    """The (u, v) of the corners ``vertices`` ``(N, 3, 3)`` of sub-triangles of the compiled
    scene's triangles ``root`` ``(N,)`` (hierarchical radiosity's leaves): ``(N, 3, 2)``, NaN
    where the mesh is not textured."""
    positions, triangles, mesh_of = scene.triangle_arrays()
    first = np.cumsum([0] + [len(m.triangles) for m in scene.meshes[:-1]])
    corners = positions[triangles[root]]  # (N, 3, 3)
    e1, e2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
    d = vertices - corners[:, None, 0]  # (N, 3 corners, 3)
    g = np.stack([np.einsum("nj,nj->n", a, b) for a in (e1, e2) for b in (e1, e2)], 1)
    r1, r2 = np.einsum("nkj,nj->nk", d, e1), np.einsum("nkj,nj->nk", d, e2)
    det = g[:, 0] * g[:, 3] - g[:, 1] * g[:, 2]
    b1 = (g[:, None, 3] * r1 - g[:, None, 1] * r2) / det[:, None]
    b2 = (g[:, None, 0] * r2 - g[:, None, 2] * r1) / det[:, None]
    bary = np.stack([b1, b2], axis=-1)  # (N, 3, 2)
    out = np.full((len(root), 3, 2), np.nan)
    for m in np.unique(mesh_of[root]):
        mesh = scene.meshes[m]
        if not mesh.material.textured:
            continue
        pick = np.nonzero(mesh_of[root] == m)[0]
        src = _triangle_uv(mesh, root[pick] - first[m])  # (P, 3, 2)
        b = bary[pick]  # (P, 3 corners, 2)
        out[pick] = (
            (1 - b[..., :1] - b[..., 1:]) * src[:, None, 0]
            + b[..., :1] * src[:, None, 1]
            + b[..., 1:] * src[:, None, 2]
        )
    return out



class PatchMesh:
    """The scene's triangles subdivided into patches.

    Parameters
    ----------
    scene:
        A :class:`dualight.Scene` whose meshes are all :class:`~dualight.Diffuse`.
    max_edge:
        Longest allowed patch edge (scene units).
    max_area:
        Largest allowed patch area; used when ``max_edge`` is not given.

    Attributes
    ----------
    vertices, triangles:
        ``(P, 3)`` positions and ``(N, 3)`` vertex indices of the N patches (vertices are shared
        within each input triangle).
    areas, normals, centroids:
        Per patch, ``(N,)``, ``(N, 3)``, ``(N, 3)``.
    reflectance, emission:
        Per patch RGB, ``(N, 3)``: the mesh's diffuse albedo (a texture's mean over the
        patch) and emitted radiosity ``E = pi * Le`` (W m^-2; a radiance texture's mean over
        the patch; point and spot lights are not in it: see :meth:`direct_irradiance`).
    uv_corners:
        ``(N, 3, 2)`` the texture coordinates of each patch's corners (NaN on untextured
        meshes), from which :meth:`Solution.render` draws textures.
    mesh_index:
        ``(N,)`` which mesh of the scene each patch comes from.
    """

    def __init__(
        self, scene: Scene, *, max_edge: float | None = None, max_area: float | None = None
    ) -> None:
        if not isinstance(scene, Scene):
            raise TypeError(f"scene must be a dualight.Scene, got {type(scene).__name__}")
        if not scene.meshes:
            raise ValueError("scene is empty: add a mesh with Scene.add_mesh")
        require_diffuse(scene)
        if max_edge is None and max_area is None:
            raise ValueError("give max_edge or max_area")
        for name, value in (("max_edge", max_edge), ("max_area", max_area)):
            if value is not None and not (math.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be a positive number, got {value!r}")
        self.max_edge = max_edge
        self.max_area = max_area
        grids: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        vertices, triangles, mesh_index = [], [], []
        offset = 0
        # The number of patches first, to refuse what memory cannot hold before allocating.
        planned = 0.0
        subdivisions: list[np.ndarray] = []
        for mesh in scene.meshes:
            corners = mesh.vertices[mesh.triangles]  # (T, 3, 3)
            if max_edge is not None:
                edges = np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=2).max(axis=1)
                per_edge = np.ceil(edges / max_edge)
            else:
                per_edge = np.ceil(np.sqrt(mesh.areas / max_area))
            # Counted in floats before any integer cast: max_edge=1e-100 overflowed int64 and
            # made 32 patches.
            per_edge = np.maximum(per_edge, 1.0)
            planned += float((per_edge**2).sum())
            if planned > 50_000_000:
                raise ValueError("this subdivision would make more than 50 million patches")
            subdivisions.append(per_edge)
        _check_memory(planned)
        uv_corners: list[np.ndarray] = []  # per patch, its corners' (u, v); NaN if untextured
        lamp_uv: list[np.ndarray] = []  # the same where the mesh's emission is a texture
        lamp_rows: list[np.ndarray] = []  # those patches' indices
        patch_count = 0
        for m, (mesh, per_edge) in enumerate(zip(scene.meshes, subdivisions, strict=True)):
            corners = mesh.vertices[mesh.triangles]  # (T, 3, 3)
            divisions = per_edge.astype(np.int64)
            for n in np.unique(divisions):
                bary, sub = grids.setdefault(int(n), _grid(int(n)))
                sel = np.nonzero(divisions == n)[0]
                uv_corners.append(_patch_uv(mesh, sel, bary[sub]))
                if mesh.emission_texture is not None:
                    lamp_uv.append(_patch_uv(mesh, sel, bary[sub], textured=True))
                    lamp_rows.append(np.arange(patch_count, patch_count + len(sel) * len(sub)))
                patch_count += len(sel) * len(sub)
                c = corners[sel]  # (S, 3, 3)
                pts = (
                    c[:, None, 0] * (1.0 - bary[:, 0] - bary[:, 1])[None, :, None]
                    + c[:, None, 1] * bary[None, :, 0, None]
                    + c[:, None, 2] * bary[None, :, 1, None]
                )  # (S, G, 3)
                vertices.append(pts.reshape(-1, 3))
                base = offset + np.arange(len(sel))[:, None, None] * len(bary)
                triangles.append((sub[None, :, :] + base).reshape(-1, 3))
                mesh_index.append(np.full(len(sel) * len(sub), m, dtype=np.int64))
                offset += len(sel) * len(bary)
        self._set_triangles(
            scene, np.concatenate(vertices), np.concatenate(triangles), np.concatenate(mesh_index)
        )
        self.uv_corners = np.concatenate(uv_corners)
        textured = ~np.isnan(self.uv_corners[:, 0, 0])
        if np.any(textured):
            self.reflectance = self.reflectance.copy()
            self.reflectance[textured] = _texture_means(
                scene, self.mesh_index[textured], self.uv_corners[textured]
            )
        if lamp_rows:  # E = pi x the radiance texture's mean over each patch
            lamps = np.concatenate(lamp_rows)
            self.emission = self.emission.copy()
            self.emission[lamps] = np.pi * _texture_means(
                scene, self.mesh_index[lamps], np.concatenate(lamp_uv), emission=True
            )

    uv_corners: np.ndarray | None = None

    @classmethod
    def from_triangles(
        cls,
        scene: Scene,
        vertices: np.ndarray,
        triangles: np.ndarray,
        mesh_index: np.ndarray,
        *,
        uv_corners: np.ndarray | None = None,
        reflectance: np.ndarray | None = None,
    ) -> PatchMesh:
        """Patches given directly (e.g. the leaves of a hierarchical solution). Where meshes
        are textured, ``uv_corners`` ``(N, 3, 2)`` places each patch in its texture (NaN rows
        for untextured patches) and ``reflectance`` ``(N, 3)`` gives the albedo the solver used
        for it (a texture's mean over its patch or over the input triangle it lies in)."""
        textured = any(mesh.material.textured for mesh in scene.meshes)
        if textured and (uv_corners is None or reflectance is None):
            raise ValueError(
                "patches of textured meshes need uv_corners and reflectance (where each patch "
                "lies in its texture, and the albedo its solver used)"
            )
        patches = cls.__new__(cls)
        patches.max_edge = patches.max_area = None
        patches._set_triangles(scene, vertices, triangles, mesh_index)
        if textured:
            patches.uv_corners = np.asarray(uv_corners, np.float64).reshape(len(patches), 3, 2)
            patches.reflectance = np.asarray(reflectance, np.float64).reshape(len(patches), 3)
        return patches

    def _set_triangles(
        self, scene: Scene, vertices: np.ndarray, triangles: np.ndarray, mesh_index: np.ndarray
    ) -> None:
        require_diffuse(scene)
        self.vertices = np.asarray(vertices, dtype=np.float64)
        self.triangles = np.asarray(triangles, dtype=np.int64)
        self.mesh_index = np.asarray(mesh_index, dtype=np.int64)
        v = self.vertices[self.triangles]
        cross = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
        self.areas = 0.5 * np.linalg.norm(cross, axis=1)
        self.normals = cross / (2.0 * self.areas[:, None])
        self.centroids = v.mean(axis=1)
        rho = np.array([mesh.reflectance for mesh in scene.meshes], dtype=np.float64)
        Le = np.array([mesh.emission for mesh in scene.meshes], dtype=np.float64)
        self.reflectance = rho[self.mesh_index]
        self.emission = np.pi * Le[self.mesh_index]
        self._scene = scene
        self._compiled: _core.Scene | None = None

    def __len__(self) -> int:
        return len(self.triangles)

    @property
    def scene(self) -> Scene:
        """The scene the patches subdivide."""
        return self._scene

    def _compile(self) -> _core.Scene:
        """The patches as an Embree scene: triangle k of it is patch k."""
        robust = self._scene.robust_intersections
        if self._compiled is None or self._compiled.robust_intersections != robust:
            from dualight import _core

            n_mesh = len(self._scene.meshes)
            rho = np.array([m.reflectance for m in self._scene.meshes], dtype=np.float32)
            Le = np.array([m.emission for m in self._scene.meshes], dtype=np.float32)
            self._compiled = _core.Scene(
                self.vertices.astype(np.float32),
                self.triangles.astype(np.uint32),
                self.mesh_index.astype(np.uint32),
                rho.reshape(n_mesh, 3),
                Le.reshape(n_mesh, 3),
                robust_intersections=robust,
            )
        return self._compiled

    def direct_irradiance(
        self,
        points_per_axis: int = 4,
        threads: int = 0,
        progress: Callable[[int, int], None] | None = None,
        *,
        env_strata: int = 8,
        seed: int = 0,
    ) -> np.ndarray:
        """``(N, 3)`` mean irradiance over each patch straight from the scene's point, spot and
        directional lights and its environment (:meth:`dualight.Scene.add_emitter`), with
        visibility, at the centroids of a ``points_per_axis`` x ``points_per_axis`` split of
        the patch; zeros without such emitters. The environment's irradiance at a point is an
        integral over its hemisphere, estimated from ``env_strata``^2 stratified pairs of a
        cosine-weighted direction and one the environment samples (multiple importance
        sampling; random shifts from ``seed``). The uniform solvers add
        ``reflectance * direct_irradiance()`` to the emitted radiosity: the emitters' first
        shot."""
        if not self._scene.emitters:
            return np.zeros((len(self), 3))
        from dualight import _core

        n_mesh = len(self._scene.meshes)
        lit = _core.Scene(
            self.vertices.astype(np.float32),
            self.triangles.astype(np.uint32),
            self.mesh_index.astype(np.uint32),
            np.zeros((n_mesh, 3), np.float32),
            np.zeros((n_mesh, 3), np.float32),
            emitters=[e._core_emitter() for e in self._scene.emitters],
            robust_intersections=self._scene.robust_intersections,
        )
        return _core.direct_irradiance(lit, points_per_axis, env_strata, seed, threads, progress)

    def __repr__(self) -> str:
        return f"PatchMesh({len(self)} patches, {len(self.vertices)} vertices)"
