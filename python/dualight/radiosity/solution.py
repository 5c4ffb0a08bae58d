"""`Solution`: radiosity and importance of one patch mesh, their measurement from both sides,
and the pictures (radiosity, importance, superposition); and the receiver ``R`` that a camera
defines. :func:`dualight.radiosity.solve` and the hierarchical solver both return one."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Literal, get_args

import numpy as np

from dualight import _core
from dualight.image import Image
from dualight.methods import RadiosityMethod
from dualight.radiosity.patches import PatchMesh
from dualight.scene import Camera

Mode = Literal["radiosity", "importance", "superposition", "elements", "links"]
"""``Solution.render(mode=...)``: the pictures of a solution."""


def camera_samples(
    compiled: _core.Scene,
    corners: np.ndarray,
    camera: Camera,
    *,
    window: tuple[int, int, int, int] | None = None,
    samples_per_axis: int = 4,
    seed: int = 0,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Stratified camera samples over the image (or a pixel ``window``): the triangle each hits
    (``-1``: none), its barycentrics, and whether it sees the triangle's front.

    ``corners`` are the ``(T, 3, 3)`` corners of the compiled scene's triangles. Arrays are
    ``(H, W, S)``, ``(H, W, S, 2)`` and ``(H, W, S)``. Patches are one-sided, so a sample that
    sees a back contributes nothing.
    """
    prim, bary = _core.trace_camera_hits(
        compiled, camera._compile(), samples_per_axis=samples_per_axis, seed=seed
    )
    if window is not None:
        x0, y0, x1, y1 = window
        if not (0 <= x0 < x1 <= camera.width and 0 <= y0 < y1 <= camera.height):
            raise ValueError(f"window {window} is not inside the {camera.resolution} image")
        prim, bary = prim[y0:y1, x0:x1], bary[y0:y1, x0:x1]
    c = corners[np.maximum(prim, 0)]
    normal = np.cross(c[..., 1, :] - c[..., 0, :], c[..., 2, :] - c[..., 0, :])
    point = (
        c[..., 0, :]
        + bary[..., :1] * (c[..., 1, :] - c[..., 0, :])
        + bary[..., 1:] * (c[..., 2, :] - c[..., 0, :])
    )
    front = (prim >= 0) & (
        np.einsum("...j,...j->...", normal, np.asarray(camera.origin) - point) > 0
    )
    return prim, bary, front


def receiver(
    patches: PatchMesh,
    camera: Camera,
    *,
    window: tuple[int, int, int, int] | None = None,
    samples_per_axis: int = 4,
    seed: int = 0,
) -> np.ndarray:
    """The receiver ``R``: how much each patch counts in the camera's measurement.

    The measurement is the mean pixel value of the image (or of the pixel ``window``
    ``(x0, y0, x1, y1)``, half-open), each pixel a box-filtered average of radiance. A diffuse
    patch seen from its front leaves radiance ``B / pi``, so ``R_i`` is the share of the
    window's stratified camera samples that land on the front of patch ``i``, divided by pi,
    and ``<R, B>`` is that mean pixel value. ``R_i > 0`` exactly for patches the camera sees.
    """
    prim, _, front = camera_samples(
        patches._compile(),
        patches.vertices[patches.triangles],
        camera,
        window=window,
        samples_per_axis=samples_per_axis,
        seed=seed,
    )
    counts = np.bincount(prim[front], minlength=len(patches)).astype(np.float64)
    return counts / (prim.size * np.pi)


@dataclass
class Solution:
    """Radiosity ``B`` and importance ``I`` of a patch mesh, with what produced them.

    ``B`` solves ``M B = E`` and ``I`` solves ``M^T I = R`` (``M = I - diag(rho) F``), per RGB
    channel. Both answer the same measurement, the mean pixel value of the camera's view:
    ``measurement_primal = <R, B>`` and ``measurement_dual = <I, E>`` (per channel).
    """

    patches: PatchMesh
    B: np.ndarray
    I: np.ndarray | None  # noqa: E741 - the literature's name
    E: np.ndarray
    R: np.ndarray
    form_factors: _core.FormFactors | None  # None for hierarchical solutions (links instead)
    camera: Camera
    method: RadiosityMethod
    stats: dict[str, Any] = field(default_factory=dict)
    history: dict[str, list[Any]] = field(default_factory=dict)
    link_density: np.ndarray | None = None  # hierarchical: links per unit area at each patch
    # view_only solves: the patches whose B was solved (non-zero importance); None = all.
    solved: np.ndarray | None = None

    @property
    def areas(self) -> np.ndarray:
        """Patch areas, one per patch."""
        return self.patches.areas

    @property
    def rho(self) -> np.ndarray:
        """Patch reflectances, RGB per patch."""
        return self.patches.reflectance

    @property
    def measurement_primal(self) -> np.ndarray:
        """``<R, B>`` per channel: the camera's mean pixel value from the radiosity solution."""
        return np.sum(self.R * self.B, axis=0)

    @property
    def measurement_dual(self) -> np.ndarray:
        """``<I, E>`` per channel: the same measurement from the importance solution."""
        if self.I is None:
            raise ValueError("importance was not solved: call solve(..., importance=True)")
        return np.sum(self.I * self.E, axis=0)

    @property
    def duality_gap(self) -> float:
        """Largest relative difference between the two measurements over the channels."""
        p, d = self.measurement_primal, self.measurement_dual
        return float(np.max(np.abs(p - d) / np.maximum(np.abs(p), 1e-300)))

    # pictures -------------------------------------------------------------------------
    def vertex_values(self, values: np.ndarray) -> np.ndarray:
        """Per-vertex values: the area-weighted mean of the patches around each vertex.

        Vertices are merged across input triangles when they coincide and their patches share
        a mesh and a plane, so radiosity is smooth across a quad's diagonal but not around
        the corner between a wall and the floor.
        """
        p = self.patches
        key_pos = np.round(p.vertices / max(np.ptp(p.vertices), 1e-30) * 2**20).astype(np.int64)
        tri_normals = np.round(p.normals * 1024).astype(np.int64)
        corners = p.triangles.reshape(-1)
        owner = np.repeat(np.arange(len(p)), 3)
        keys = np.concatenate(
            [key_pos[corners], tri_normals[owner], p.mesh_index[owner, None]], axis=1
        )
        _, group = np.unique(keys, axis=0, return_inverse=True)
        group = group.reshape(-1)
        w = p.areas[owner]
        sums = np.zeros((group.max() + 1, values.shape[1]))
        np.add.at(sums, group, w[:, None] * values[owner])
        weights = np.bincount(group, weights=w)
        per_corner = sums[group] / weights[group, None]
        return per_corner.reshape(len(p), 3, values.shape[1])

    @staticmethod
    def _normalised(values: np.ndarray, visible: np.ndarray) -> np.ndarray:
        """Values / their 99th percentile over the visible pixels, clipped to [0, 1]."""
        seen = values[visible.any(axis=-1)] if visible.ndim == values.ndim + 1 else values
        scale = float(np.percentile(seen, 99)) if seen.size else 0.0
        return np.clip(values / scale, 0.0, 1.0) if scale > 0 else np.zeros_like(values)

    def _texture_scale(
        self, idx: np.ndarray, bary: np.ndarray, visible: np.ndarray
    ) -> np.ndarray | None:
        """Per image sample, a textured patch's albedo at the sample over its mean albedo (1
        elsewhere), or None when no patch is textured: radiosity's reflected light is the
        patch's irradiance times the albedo, so the texture shows in the drawing."""
        uv_corners = self.patches.uv_corners
        if uv_corners is None:
            return None
        textured = visible & ~np.isnan(uv_corners[idx, 0, 0])
        if not np.any(textured):
            return None
        scale = np.ones((*idx.shape, 3))
        rows = idx[textured]
        b = bary[textured]
        corners = uv_corners[rows]
        uv = (
            (1 - b[:, :1] - b[:, 1:]) * corners[:, 0]
            + b[:, :1] * corners[:, 1]
            + b[:, 1:] * corners[:, 2]
        )
        albedo = np.empty((len(rows), 3))
        meshes = self.patches.mesh_index[rows]
        for m in np.unique(meshes):
            pick = meshes == m
            texture = self.patches.scene.meshes[m].material.reflectance
            albedo[pick] = texture.eval(uv[pick])
        mean = self.patches.reflectance[rows]
        scale[textured] = np.divide(albedo, mean, out=np.zeros_like(albedo), where=mean > 0)
        return scale

    def render(
        self,
        camera: Camera | None = None,
        mode: Mode = "radiosity",
        *,
        smooth: bool = True,
        samples_per_axis: int = 4,
        seed: int = 0,
    ) -> Image:
        """Draw the solution from ``camera`` (default: the solution's camera).

        With the defaults (the receiver's samples and seed), the mean of the flat
        (``smooth=False``) radiosity picture is exactly ``measurement_primal``.

        ``"radiosity"``: radiance ``B / pi`` (linear RGB, comparable with a path-traced image),
        flat per patch or (``smooth``) interpolated from vertex values. ``"importance"``: the
        importance in false colour (mean over channels, normalised, a black-red-yellow-white
        ramp). ``"superposition"``: the radiosity picture in grey with the important parts
        tinted yellow, in proportion to importance: where the work matters for the view.
        ``"elements"``: every patch (leaf element) in its own colour, so the mesh shows.
        ``"links"``: hierarchical solutions only, links per unit area in false colour (log
        scale): where the work went.
        """
        cam = camera or self.camera
        prim, bary, visible = camera_samples(
            self.patches._compile(),
            self.patches.vertices[self.patches.triangles],
            cam,
            samples_per_axis=samples_per_axis,
            seed=seed,
        )
        idx = np.maximum(prim, 0)
        if self.solved is not None and not np.all(self.solved[idx[visible]]):
            raise ValueError(
                "this camera sees patches whose radiosity was not solved: the solution was "
                "computed for one view only (view_only=True)"
            )

        def sample(values: np.ndarray, scale: np.ndarray | None = None) -> np.ndarray:
            if smooth:
                corners = self.vertex_values(values)[idx]  # H, W, S, 3, C
                b1, b2 = bary[..., 0:1], bary[..., 1:2]
                v = (
                    (1 - b1 - b2) * corners[..., 0, :]
                    + b1 * corners[..., 1, :]
                    + b2 * corners[..., 2, :]
                )
            else:
                v = values[idx]
            if scale is not None:
                v = v * scale
            return np.where(visible[..., None], v, 0.0).mean(axis=2)

        if mode == "radiosity":
            texture = self._texture_scale(idx, bary, visible)
            if texture is None:
                radiance = sample(self.B / np.pi)
            else:  # emitted, plus reflected light times the albedo here over the patch's mean
                radiance = sample(self.E / np.pi) + sample((self.B - self.E) / np.pi, texture)
            return Image(radiance, stats={"mode": mode, "method": self.method})
        if mode == "elements":
            colours = np.random.default_rng(12345).uniform(0.15, 1.0, size=(len(self.patches), 3))
            flat = np.where(visible[..., None], colours[idx], 0.0)
            return Image(flat.mean(axis=2), stats={"mode": mode, "method": self.method})
        if mode == "links":
            if self.link_density is None:
                raise ValueError("mode 'links' needs a hierarchical solution")
            density = np.log10(np.maximum(self.link_density, 1e-30))[:, None]
            lo = float(np.percentile(density, 1))
            values = np.where(visible[..., None], (density - lo)[idx], 0.0).mean(axis=2)
            t = self._normalised(values[..., 0], visible)
            ramp = np.stack(
                [np.clip(3 * t, 0, 1), np.clip(3 * t - 1, 0, 1), np.clip(3 * t - 2, 0, 1)], -1
            )
            return Image(ramp, stats={"mode": mode, "method": self.method})
        if self.I is None:
            raise ValueError("importance was not solved: call solve(..., importance=True)")
        # Importance per unit area (the adjoint of radiosity): independent of the meshing.
        density = (self.I.mean(axis=1) / self.patches.areas)[:, None]
        if mode == "importance":
            t = self._normalised(sample(density)[..., 0], visible)
            ramp = np.stack(
                [np.clip(3 * t, 0, 1), np.clip(3 * t - 1, 0, 1), np.clip(3 * t - 2, 0, 1)], -1
            )
            return Image(ramp, stats={"mode": mode, "method": self.method})
        if mode == "superposition":
            radiance = sample(self.B / np.pi)
            lum = radiance @ np.array([0.2126, 0.7152, 0.0722])
            grey = self._normalised(lum, visible)[..., None]
            # Reflected light times how much it matters for the view [Smits et al. 1992]
            # (emission is left out: it would only mark the lights).
            luminance_B = ((self.B - self.E) @ np.array([0.2126, 0.7152, 0.0722]))[:, None]
            t = self._normalised(sample(luminance_B * density)[..., 0], visible)[..., None]
            yellow = np.array([1.0, 0.85, 0.0])
            out = (1 - t) * grey * 0.7 + t * yellow * (0.4 + 0.6 * grey)
            return Image(out, stats={"mode": mode, "method": self.method})
        raise ValueError(f"mode must be one of {', '.join(get_args(Mode))}, got {mode!r}")
