"""Mitsuba 3 as the reference renderer: scene conversion and reference renders.

* :func:`variant` picks and sets a Mitsuba variant that works on this machine.
* :func:`scene_dict` turns a :class:`dualight.Scene` into a dict for ``mitsuba.load_dict``
  with the same conventions as dualight (pinhole camera with the full fov along x, box pixel
  filter, face normals, each material's matching BSDF, one-sided area emitters).
* :func:`reference` renders the mean image and the per-pixel variance *of the mean*.

Mitsuba is imported inside the functions only, so ``dualight`` imports without it.

Conventions checked against Mitsuba 3.9 (``tests/test_mitsuba_bridge.py``):

* Mitsuba's face normal of a triangle ``(v0, v1, v2)`` is ``(v1 - v0) x (v2 - v0)``, as in
  dualight, and its ``area`` emitter emits on that side only.
* ``look_at(origin, target, up)`` maps dualight's camera right, ``normalize(forward x up)``, to
  increasing image columns, and ``up`` to row 0 (the top). In the Cornell box the red wall
  (x = 550 mm) is on the left of the image in both renderers.
"""

from __future__ import annotations

import math
import os
import re
import subprocess
import sys
import warnings
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from dualight.materials import Material

if TYPE_CHECKING:
    from dualight.scene import Scene

__all__ = ["reference", "scene_dict", "variant"]

#: Samples per pixel of one pass at most (the LLVM variants keep every sample's path state in
#: memory at once: about 1 GiB per 4M samples).
MAX_SPP_PER_PASS = 1024
#: Samples (pixels x spp) of one pass at most.
MAX_SAMPLES_PER_PASS = 1 << 22

_MOMENT_INTEGRATOR = "dualight_rgb_moment"
#: Default number of passes of scalar variants, whose variance comes from the pass means.
_MIN_SCALAR_PASSES = 64
_probe_results: dict[str, tuple[bool, str]] = {}
_registered: set[str] = set()
_warned: set[str] = set()


# --------------------------------------------------------------------------------------------
# Variant selection


def _probe_command(name: str) -> list[str]:
    """The command that renders a tiny scene with ``name`` in a fresh interpreter."""
    import dualight

    root = os.path.dirname(os.path.dirname(os.path.abspath(dualight.__file__)))
    code = (
        "import sys; sys.path.insert(0, sys.argv[1]); "
        "from dualight.mitsuba import _probe_render; _probe_render(sys.argv[2])"
    )
    return [sys.executable, "-c", code, root, name]


def _probe_render(name: str) -> None:
    """Render a small furnace with every feature :func:`reference` uses (run in a subprocess).

    An LLVM too old for Dr.Jit (e.g. LLVM 15 with Mitsuba 3.9: "Cannot select: fminimum")
    aborts the whole process while compiling, which is why this runs in a child process.
    """
    import mitsuba as mi

    from dualight.scenes import furnace

    mi.set_variant(name)
    mean, var = reference(furnace(0.5, 1.0, (8, 8)), spp=16, max_depth=6, rr_depth=2, variant=name)
    if not (np.all(np.isfinite(mean)) and np.all(np.isfinite(var)) and 1.0 < mean.mean() < 3.0):
        raise SystemExit(f"probe render of {name} gave a wrong furnace: mean {mean.mean()}")


def _probe(name: str) -> tuple[bool, str]:
    """Whether the JIT variant ``name`` renders without crashing (cached per process)."""
    if name not in _probe_results:
        try:
            proc = subprocess.run(
                _probe_command(name), capture_output=True, text=True, timeout=300, check=False
            )
        except (OSError, subprocess.TimeoutExpired) as exc:
            _probe_results[name] = (False, f"probe failed: {exc}")
        else:
            lines = [ln for ln in (proc.stderr or "").splitlines() if ln.strip()]
            error = next((ln for ln in lines if "LLVM ERROR" in ln or "Error" in ln), None)
            reason = error or (lines[-1] if lines else f"exit code {proc.returncode}")
            _probe_results[name] = (proc.returncode == 0, reason.strip()[:300])
    return _probe_results[name]


def variant(preferred: str | Sequence[str] = ("llvm_ad_rgb", "scalar_rgb")) -> str:
    """Set and return the first Mitsuba variant of ``preferred`` that works here.

    JIT variants (``llvm_*``, ``cuda_*``) are tried by rendering a tiny scene in a child
    process first, because a missing or too old libLLVM either fails to load or aborts the
    process while compiling (Mitsuba 3.9 with Debian 12's LLVM 15 aborts with "Cannot select:
    fminimum"; LLVM 19 works: ``apt-get install libllvm19``, or point ``DRJIT_LIBLLVM_PATH`` at
    a ``libLLVM.so``). The outcome is cached for the process. Variants not compiled into the
    installed Mitsuba are skipped.

    Parameters
    ----------
    preferred : str or sequence of str, optional
        A variant name, or names in order of preference. Use ``*_rgb`` variants for comparisons
        with dualight (spectral ones upsample RGB colours).

    Returns
    -------
    str
        The variant now set with ``mitsuba.set_variant``.

    Raises
    ------
    RuntimeError
        If none of the variants works; the message gives each one's reason.
    """
    import mitsuba as mi

    names = [preferred] if isinstance(preferred, str) else list(preferred)
    if not names:
        raise ValueError("preferred must name at least one Mitsuba variant")
    available = set(mi.variants())
    reasons: list[str] = []
    for name in names:
        if name not in available:
            reasons.append(f"{name}: not in this Mitsuba build ({sorted(available)})")
            continue
        if name.startswith(("llvm_", "cuda_")):
            ok, why = _probe(name)
            if not ok:
                reasons.append(f"{name}: {why}")
                continue
        try:
            mi.set_variant(name)
        except Exception as exc:  # noqa: BLE001 - report every variant's failure together
            reasons.append(f"{name}: {exc}")
            continue
        message = f"Mitsuba variant {name} is used; skipped: " + "; ".join(reasons)
        if reasons and message not in _warned:  # once per process
            _warned.add(message)
            warnings.warn(message, stacklevel=2)
        return name
    raise RuntimeError("no usable Mitsuba variant: " + "; ".join(reasons))


def _ensure_variant(name: str | None) -> str:
    """The variant to use: ``name`` if given, the current one if set, else :func:`variant`."""
    import mitsuba as mi

    if name is not None:
        return name if mi.variant() == name else variant(name)
    current = mi.variant()
    return current if current else variant()


# --------------------------------------------------------------------------------------------
# Scene conversion


def _bsdf(material: Material, name: str) -> dict[str, Any]:
    """The Mitsuba BSDF dict matching a dualight material (see :func:`scene_dict`)."""
    if not isinstance(material, Material):
        raise TypeError(f"mesh {name!r}: unknown material {type(material).__name__}")
    return _mitsuba_objects(material._mitsuba_bsdf())


def _mitsuba_objects(plugin: dict[str, Any]) -> dict[str, Any]:
    """A plugin dict with textures' plain entries as Mitsuba objects: ``to_uv`` as a transform,
    ``texels`` as a ``mitsuba.Bitmap``."""
    import mitsuba as mi

    from dualight.textures import uv_matrix4

    out: dict[str, Any] = {}
    for key, value in plugin.items():
        if isinstance(value, dict):
            out[key] = _mitsuba_objects(value)
        elif key == "to_uv":
            out[key] = mi.ScalarTransform4f(uv_matrix4(value))
        elif key == "texels":
            out["bitmap"] = mi.Bitmap(np.array(value, dtype=np.float32, copy=True))
        else:
            out[key] = value
    return out


def _mesh(mesh: Any, key: str) -> Any:
    """A ``mitsuba.Mesh`` (flat, or with the mesh's shading normals), its material's BSDF and
    maybe an emitter."""
    import mitsuba as mi

    smooth = mesh.normals is not None
    props = mi.Properties("mesh")
    props["face_normals"] = not smooth
    props["bsdf"] = mi.load_dict(_bsdf(mesh.material, mesh.name))
    if mesh.is_emitter:
        props["emitter"] = mi.load_dict(_mitsuba_objects(mesh._mitsuba_emitter()))
    textured = mesh.uv is not None
    out = mi.Mesh(
        key,
        len(mesh.vertices),
        len(mesh.triangles),
        props,
        has_vertex_normals=smooth,
        has_vertex_texcoords=textured,
    )
    params = mi.traverse(out)
    positions = np.ascontiguousarray(mesh.vertices, dtype=np.float32).ravel()
    faces = np.ascontiguousarray(mesh.triangles, dtype=np.uint32).ravel()
    params["vertex_positions"] = type(params["vertex_positions"])(positions)
    params["faces"] = type(params["faces"])(faces)
    if smooth:
        normals = np.ascontiguousarray(mesh.normals, dtype=np.float32).ravel()
        params["vertex_normals"] = type(params["vertex_normals"])(normals)
    if textured:
        uv = np.ascontiguousarray(mesh.uv, dtype=np.float32).ravel()
        params["vertex_texcoords"] = type(params["vertex_texcoords"])(uv)
    params.update()
    return out


def _key(name: str, used: set[str]) -> str:
    base = "mesh_" + (re.sub(r"[^A-Za-z0-9_]", "_", name) or "unnamed")
    key, i = base, 1
    while key in used:
        key, i = f"{base}_{i}", i + 1
    used.add(key)
    return key


def scene_dict(
    scene: Scene,
    *,
    spp: int = 64,
    max_depth: int = -1,
    rr_depth: int = 5,
    integrator: str | dict[str, Any] = "path",
) -> dict[str, Any]:
    """A dict for ``mitsuba.load_dict`` that describes ``scene`` with dualight's conventions.

    * Sensor: ``perspective`` with ``fov`` along x (``fov_axis="x"``) and ``to_world =
      look_at(origin, target, up)``; clip planes cover the whole scene.
    * Film: ``hdrfilm`` of the camera's resolution, ``box`` filter (each pixel averages its own
      uniformly jittered samples), ``rgb`` pixels, float32 components.
    * Sampler: ``independent`` with ``sample_count=spp`` (the seed is given to ``mi.render``).
    * Integrator: ``integrator`` with ``max_depth``, ``rr_depth`` and ``hide_emitters=False``;
      a dict is used as it is. ``max_depth`` counts segments as in dualight (1: emitters seen
      directly, 2: direct lighting, -1: unbounded).
    * Every mesh becomes a ``mitsuba.Mesh`` object (no file) with face normals, its material's
      BSDF and, if it emits, a one-sided ``area`` emitter with RGB radiance. The keys are
      ``"mesh_<name>"``. Materials map to:

      - :class:`~dualight.Diffuse`: ``twosided`` around ``diffuse`` with an RGB
        ``reflectance``;
      - :class:`~dualight.Mirror`: ``twosided`` around ``conductor`` with ``material="none"``
        (a perfect reflector) and an RGB ``specular_reflectance``;
      - :class:`~dualight.Dielectric`: ``dielectric`` with ``int_ior=ior`` and
        ``ext_ior=1.0`` (not ``twosided``: the face normals point to the exterior).

    The meshes are objects of the Mitsuba variant set when this is called (one is chosen with
    :func:`variant` if none is set): load the dict in that variant.

    Parameters
    ----------
    scene : dualight.Scene
        A scene with a camera, meshes and at least one emitter.
    spp : int, optional
        Samples per pixel of the sampler.
    max_depth, rr_depth : int, optional
        Path length bound (-1 for none) and depth at which Russian roulette starts.
    integrator : str or dict, optional
        Mitsuba integrator plugin name (``"path"``, ``"ptracer"``, ...) or a complete dict.

    Returns
    -------
    dict
    """
    import mitsuba as mi

    scene.validate_for_rendering()
    if int(spp) != spp or spp < 1:
        raise ValueError(f"spp must be a positive integer, got {spp}")
    if int(max_depth) != max_depth or (max_depth < 1 and max_depth != -1):
        raise ValueError(f"max_depth must be -1 or a positive integer, got {max_depth}")
    if int(rr_depth) != rr_depth or rr_depth < 1:
        raise ValueError(f"rr_depth must be a positive integer, got {rr_depth}")
    _ensure_variant(None)

    cam = scene.camera
    assert cam is not None  # validate_for_rendering checked it
    lo, hi = scene.bounds()
    corners = np.array(
        [[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    )
    reach = float(np.max(np.linalg.norm(corners - np.asarray(cam.origin), axis=1)))
    far_clip = max(4.0 * reach, 1e-3)
    if isinstance(integrator, dict):
        integrator_dict = dict(integrator)
    else:
        integrator_dict = {
            "type": integrator,
            "max_depth": int(max_depth),
            "rr_depth": int(rr_depth),
            "hide_emitters": False,
        }
    out: dict[str, Any] = {
        "type": "scene",
        "integrator": integrator_dict,
        "sensor": {
            "type": "perspective",
            "fov": float(cam.fov),
            "fov_axis": "x",
            "near_clip": far_clip * 1e-6,
            "far_clip": far_clip,
            "to_world": mi.ScalarTransform4f().look_at(
                origin=list(cam.origin), target=list(cam.target), up=list(cam.up)
            ),
            "film": {
                "type": "hdrfilm",
                "width": cam.width,
                "height": cam.height,
                "rfilter": {"type": "box"},
                "pixel_format": "rgb",
                "component_format": "float32",
            },
            "sampler": {"type": "independent", "sample_count": int(spp)},
        },
    }
    # The same intersections: Mitsuba's default (off) leaks through closed meshes' edges.
    out["embree_use_robust_intersections"] = scene.robust_intersections
    used = set(out)
    for mesh in scene.meshes:
        key = _key(mesh.name, used)
        out[key] = _mesh(mesh, key)
    for i, emitter in enumerate(scene.emitters):  # mesh keys start with "mesh_"
        out[f"emitter_{i}"] = emitter._mitsuba()
    return out


# --------------------------------------------------------------------------------------------
# Reference renders


def _register_moment_integrator() -> None:
    """Register ``dualight_rgb_moment`` for the current variant.

    Mitsuba's own ``moment`` integrator records second moments of the *XYZ* values, which do
    not give per-channel RGB variances (those would need the XYZ cross moments). This one
    records ``R^2, G^2, B^2`` of each sample of its nested integrator as three AOVs.
    """
    import mitsuba as mi

    name = mi.variant()
    if name in _registered:
        return

    class RGBMoment(mi.SamplingIntegrator):  # type: ignore[misc, name-defined]
        def __init__(self, props: Any) -> None:
            super().__init__(props)
            nested = [props[k] for k in props.keys() if isinstance(props[k], mi.SamplingIntegrator)]
            if len(nested) != 1:
                raise ValueError(f"{_MOMENT_INTEGRATOR} needs one nested sampling integrator")
            self.nested = nested[0]

        def aov_names(self) -> list[str]:
            return ["m2.R", "m2.G", "m2.B"]

        def sample(
            self, scene: Any, sampler: Any, ray: Any, medium: Any = None, active: Any = True
        ) -> tuple[Any, Any, list[Any]]:
            spec, valid, _ = self.nested.sample(scene, sampler, ray, medium, active)
            return spec, valid, [spec[0] * spec[0], spec[1] * spec[1], spec[2] * spec[2]]

        def to_string(self) -> str:
            return f"RGBMoment[nested={self.nested}]"

    mi.register_integrator(_MOMENT_INTEGRATOR, lambda props: RGBMoment(props))
    _registered.add(name)


def _split(total: int, parts: int) -> list[int]:
    """``total`` split into ``parts`` near-equal positive integers."""
    q, r = divmod(total, parts)
    return [q + (i < r) for i in range(parts)]


def _pass_seed(seed: int, index: int) -> int:
    """A 32-bit seed for pass ``index`` of a render with ``seed`` (distinct streams)."""
    return int(np.random.SeedSequence([int(seed), int(index)]).generate_state(1)[0])


def reference(
    scene: Scene,
    spp: int,
    seed: int = 0,
    *,
    max_depth: int = -1,
    rr_depth: int = 5,
    variant: str | None = None,
    passes: int | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Render ``scene`` with Mitsuba's path tracer: the mean and the variance of the mean.

    The render is split into passes of at most :data:`MAX_SPP_PER_PASS` spp (fewer for large
    images), each with its own seed derived from ``seed`` and the pass index, and combined
    exactly. How the variance is estimated depends on the variant:

    * JIT variants (``llvm_*``, ``cuda_*``): a small integrator wrapping ``path`` records each
      sample's ``R^2, G^2, B^2`` as AOVs. With ``N = spp`` samples, first moment ``m1`` and
      second moment ``m2`` of a pixel, the unbiased sample variance is
      ``N / (N - 1) * (m2 - m1^2)`` and the variance of the mean is that divided by ``N``:
      ``(m2 - m1^2) / (N - 1)``.
    * Scalar variants (where a Python integrator would run once per sample, about 20 times
      slower): from the ``P`` pass means ``m_p`` of ``n_p`` samples each, the variance of the
      mean is ``sum_p n_p (m_p - mean)^2 / ((P - 1) N)`` (``var(pass means, ddof=1) / P`` for
      equal passes), by default with 64 passes, so it has ``P - 1`` degrees of freedom.

    Parameters
    ----------
    scene : dualight.Scene
        The scene; the film has the camera's resolution.
    spp : int
        Total samples per pixel (at least 2).
    seed : int, optional
        Base seed; different seeds give independent renders.
    max_depth, rr_depth : int, optional
        As in :func:`scene_dict`. Russian roulette keeps the mean but changes the variance.
    variant : str, optional
        An RGB Mitsuba variant, set for the whole process; by default the current one, or
        :func:`variant`'s choice if none is set.
    passes : int, optional
        Number of passes (default: as few as the per-pass limits allow; at least 64 for scalar
        variants). Must not exceed ``spp``.

    Returns
    -------
    mean, variance : numpy.ndarray
        ``H x W x 3`` float32 arrays: the mean radiance and the variance of that mean.
    """
    import drjit as dr
    import mitsuba as mi

    if int(spp) != spp or spp < 2:
        raise ValueError(f"spp must be an integer >= 2, got {spp}")
    spp = int(spp)
    if isinstance(seed, bool) or int(seed) != seed or seed < 0:
        raise ValueError(f"seed must be a non-negative integer, got {seed!r}")
    name = _ensure_variant(variant)
    if not name.endswith("_rgb"):
        raise ValueError(f"reference() needs an RGB variant (e.g. llvm_ad_rgb), not {name}")
    jit = not name.startswith("scalar")
    cam = scene.camera
    if cam is None:
        raise ValueError("scene has no camera: pass camera=dualight.Camera(...)")
    per_pass = max(1, min(MAX_SPP_PER_PASS, MAX_SAMPLES_PER_PASS // (cam.width * cam.height)))
    if passes is None:
        passes = math.ceil(spp / per_pass)
        if not jit:
            passes = min(spp, max(passes, _MIN_SCALAR_PASSES))
    if int(passes) != passes or not 1 <= passes <= spp:
        raise ValueError(f"passes must be an integer in [1, spp={spp}], got {passes}")
    if not jit and passes < 2:
        raise ValueError("scalar variants estimate the variance from passes: use passes >= 2")
    counts = _split(spp, int(passes))

    if jit:
        _register_moment_integrator()
        nested = {
            "type": "path",
            "max_depth": int(max_depth),
            "rr_depth": int(rr_depth),
            "hide_emitters": False,
        }
        integrator: dict[str, Any] = {"type": _MOMENT_INTEGRATOR, "nested": nested}
    else:
        integrator = {
            "type": "path",
            "max_depth": int(max_depth),
            "rr_depth": int(rr_depth),
            "hide_emitters": False,
        }
    mi_scene = mi.load_dict(
        scene_dict(
            scene, spp=counts[0], max_depth=max_depth, rr_depth=rr_depth, integrator=integrator
        )
    )

    shape = (cam.height, cam.width, 3)
    sum1 = np.zeros(shape, np.float64)  # sum over passes of n_p * mean_p
    sum2 = np.zeros(shape, np.float64)  # JIT: sum of n_p * m2_p; scalar: of n_p * mean_p^2
    for i, n in enumerate(counts):
        img = mi.render(mi_scene, spp=n, seed=_pass_seed(seed, i))
        arr = np.array(img, dtype=np.float64)
        del img
        sum1 += n * arr[..., 0:3]
        sum2 += n * (arr[..., 3:6] if jit else arr[..., 0:3] ** 2)
        del arr
        if jit:
            dr.flush_malloc_cache()
    del mi_scene
    if jit:
        dr.flush_malloc_cache()

    mean = sum1 / spp
    if jit:
        var = np.maximum(sum2 / spp - mean**2, 0.0) / (spp - 1)
    else:
        # Pass p's mean has variance sigma^2 / n_p, so sum_p n_p (mean_p - mean)^2 / (P - 1)
        # is an unbiased estimate of the per-sample variance sigma^2, also for unequal n_p.
        sigma2 = np.maximum(sum2 - spp * mean**2, 0.0) / (len(counts) - 1)
        var = sigma2 / spp
    return mean.astype(np.float32), var.astype(np.float32)
