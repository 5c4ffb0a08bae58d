"""Meshes the built-in scenes are made of: oriented quads, axis-aligned rectangles, boxes,
icospheres, open cylinders (as used by :mod:`dualight.scenes`)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np


def _orient(quad: np.ndarray, towards: np.ndarray, inward: bool) -> np.ndarray:
    """Reverse a quad's vertex order if its normal does not face (or face away from) a point."""
    n = np.cross(quad[1] - quad[0], quad[2] - quad[0])
    facing = float(np.dot(n, towards - quad.mean(axis=0))) > 0.0
    return quad if facing == inward else quad[::-1]


def _quads_mesh(quads: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    vertices = np.concatenate(quads)
    faces = np.arange(len(vertices)).reshape(-1, 4)
    return vertices, faces


def _axis_rect(axis: int, value: float, lo: Sequence[float], hi: Sequence[float]) -> np.ndarray:
    """The axis-aligned rectangle ``coordinate[axis] == value`` spanning ``lo..hi`` in the other
    two coordinates (``lo[axis]`` and ``hi[axis]`` are ignored), as a quad."""
    a, b = (axis + 1) % 3, (axis + 2) % 3
    quad = np.empty((4, 3), dtype=np.float64)
    quad[:, axis] = value
    quad[:, a] = (lo[a], hi[a], hi[a], lo[a])
    quad[:, b] = (lo[b], lo[b], hi[b], hi[b])
    return quad


_ICOSAHEDRON_FACES = np.array(
    [
        [0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11],
        [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6], [7, 1, 8],
        [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9],
        [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1],
    ],
    dtype=np.int64,
)  # fmt: skip


def _icosahedron() -> np.ndarray:
    """The 12 unit vertices of a regular icosahedron (the order of ``_ICOSAHEDRON_FACES``)."""
    phi = 0.5 * (1.0 + math.sqrt(5.0))
    v = np.array(
        [
            [-1, phi, 0], [1, phi, 0], [-1, -phi, 0], [1, -phi, 0],
            [0, -1, phi], [0, 1, phi], [0, -1, -phi], [0, 1, -phi],
            [phi, 0, -1], [phi, 0, 1], [-phi, 0, -1], [-phi, 0, 1],
        ],
        dtype=np.float64,
    )  # fmt: skip
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def icosphere(
    centre: Sequence[float], radius: float, subdivisions: int = 3
) -> tuple[np.ndarray, np.ndarray]:
    """A sphere as a subdivided icosahedron: flat triangles facing outward.

    Each subdivision splits every triangle into four at its edge midpoints, which are then
    pushed out to the sphere, so the mesh has ``20 * 4**subdivisions`` triangles and
    ``10 * 4**subdivisions + 2`` vertices, all at distance ``radius`` from ``centre``. It is
    closed (every edge is shared by exactly two triangles) and every triangle's right-hand-rule
    normal points away from the centre. Its area is a little less than the sphere's, ``4 pi
    r^2``: by 24 %, 7.2 %, 1.9 %, 0.48 % and 0.12 % at 0 to 4 subdivisions (a
    factor of about 4 per subdivision).

    The sphere renders faceted (Mitsuba gets the same flat triangles, ``face_normals=True`` in
    :mod:`dualight.mitsuba`) unless it is added with shading normals:
    ``scene.add_mesh(v, f, normals=v - centre)``.

    Parameters
    ----------
    centre : sequence of 3 floats
        The sphere's centre.
    radius : float
        Its radius, ``> 0``.
    subdivisions : int, optional
        Number of 1-to-4 splits, in ``[0, 8]`` (8 makes 1,310,720 triangles).

    Returns
    -------
    vertices : ndarray of shape (V, 3), float64
    faces : ndarray of shape (F, 3), int64
        Ready for :meth:`dualight.Scene.add_mesh`.

    Raises
    ------
    ValueError
        If ``centre`` is not 3 finite numbers, ``radius`` is not finite and positive, or
        ``subdivisions`` is not an int in ``[0, 8]``.
    """
    c = np.asarray(centre, dtype=np.float64)
    if c.shape != (3,) or not np.all(np.isfinite(c)):
        raise ValueError(f"icosphere: centre must be 3 finite numbers, got {centre!r}")
    r = float(radius)
    if not (math.isfinite(r) and r > 0.0):
        raise ValueError(f"icosphere: radius must be finite and > 0, got {radius!r}")
    if (
        isinstance(subdivisions, bool)
        or not isinstance(subdivisions, int | np.integer)
        or not 0 <= subdivisions <= 8
    ):
        raise ValueError(f"icosphere: subdivisions must be an int in [0, 8], got {subdivisions!r}")
    v = _icosahedron()
    f = _ICOSAHEDRON_FACES.copy()
    for _ in range(int(subdivisions)):
        # One midpoint per undirected edge, numbered after the existing vertices.
        edges = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
        unique, inverse = np.unique(np.sort(edges, axis=1), axis=0, return_inverse=True)
        mid = v[unique[:, 0]] + v[unique[:, 1]]
        v = np.concatenate([v, mid / np.linalg.norm(mid, axis=1, keepdims=True)])
        m01, m12, m20 = len(v) - len(unique) + np.ravel(inverse).reshape(3, -1)
        a, b, cc = f[:, 0], f[:, 1], f[:, 2]
        f = np.concatenate(
            [
                np.stack([a, m01, m20], axis=1),
                np.stack([m01, b, m12], axis=1),
                np.stack([m20, m12, cc], axis=1),
                np.stack([m01, m12, m20], axis=1),
            ]
        )
    # The icosahedron's face list is wound outward and splitting keeps the winding; check it.
    tri = v[f]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    outward = np.einsum("ij,ij->i", normals, tri.sum(axis=1))
    if np.any(outward <= 0.0):  # pragma: no cover - a broken face table
        raise AssertionError("icosphere: a face is wound inward")
    return c + r * v, f


def _box(lo: Sequence[float], hi: Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
    """The axis-aligned box ``lo..hi`` as 6 quads facing out (vertices, faces)."""
    lo_, hi_ = np.asarray(lo, dtype=np.float64), np.asarray(hi, dtype=np.float64)
    centre = 0.5 * (lo_ + hi_)
    quads = [_axis_rect(a, x, lo_, hi_) for a in range(3) for x in (lo_[a], hi_[a])]
    return _quads_mesh([_orient(q, centre, inward=False) for q in quads])


def _open_cylinder(
    base: Sequence[float], radii: tuple[float, float], height: float, sides: int
) -> tuple[np.ndarray, np.ndarray]:
    """A vertical open frustum (a lamp shade): ``sides`` quads from radius ``radii[0]`` at
    ``base`` up to ``radii[1]`` at ``base + height`` along y, facing out (vertices, faces)."""
    b = np.asarray(base, dtype=np.float64)
    phi = 2.0 * math.pi * np.arange(sides + 1) / sides
    ring = np.stack([np.cos(phi), np.zeros_like(phi), np.sin(phi)], axis=1)
    quads = []
    for i in range(sides):
        lower = b + radii[0] * ring[[i, i + 1]]
        upper = b + radii[1] * ring[[i + 1, i]] + np.array([0.0, height, 0.0])
        quad = np.concatenate([lower, upper])
        # Outward: away from the axis at the quad's height.
        axis_point = np.array([b[0], quad[:, 1].mean(), b[2]])
        quads.append(_orient(quad, axis_point, inward=False))
    return _quads_mesh(quads)
