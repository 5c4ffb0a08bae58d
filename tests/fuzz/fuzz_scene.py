"""Fuzz the scene builder and the estimators with atheris.

Fuzzed vertex and index arrays (quads, out-of-range and negative indices, NaN, Inf, huge and tiny
coordinates), materials, emission, camera parameters and render options build a
``dualight.Scene``; then a tiny image is rendered by one of the estimators or a tiny radiosity
system is solved. The only acceptable failures are clean Python exceptions with a message
(``ValueError``, ``TypeError``, ...); anything else -- a segfault, an abort, a sanitizer report,
another exception, a NaN, Inf or negative value in an image or a solution -- is a crash.

Run: ``python tests/fuzz/fuzz_scene.py -max_total_time=60 [corpus_dir]`` (libFuzzer flags).
"""

from __future__ import annotations

import atexit
import sys
import warnings

import atheris
import numpy as np

with atheris.instrument_imports():
    import dualight

from dualight.radiosity import SOLVERS as PATCH_SOLVERS
from dualight.radiosity import solve

# Clean, documented refusals; RuntimeError only with a message.
ACCEPTED = (ValueError, TypeError, FileNotFoundError, RuntimeError)
# In this order, so that the regression inputs keep choosing the same methods.
METHODS = (*dualight.METHODS, "radiosity")
SOLVERS = (*PATCH_SOLVERS, "hierarchical")

# Interesting coordinates: zero, tiny, huge, non-finite, beyond float32.
SPECIAL = (0.0, 1e-30, -1e-30, 1e-7, 1e7, 1e30, 3e38, 1e39, np.inf, -np.inf, np.nan)


def _float(fdp: atheris.FuzzedDataProvider, lo: float, hi: float, wild: bool) -> float:
    """A float in [lo, hi]; in a wild part of the input, now and then a special value or any
    float at all."""
    kind = fdp.ConsumeIntInRange(0, 7) if wild else 2
    if kind == 0:
        return SPECIAL[fdp.ConsumeIntInRange(0, len(SPECIAL) - 1)]
    if kind == 1:
        return fdp.ConsumeFloat()
    return fdp.ConsumeFloatInRange(lo, hi)


def _vec3(fdp: atheris.FuzzedDataProvider, lo: float, hi: float, wild: bool) -> list[float]:
    return [_float(fdp, lo, hi, wild) for _ in range(3)]


def _wild(fdp: atheris.FuzzedDataProvider) -> bool:
    """One part of the scene (the camera, a mesh) in eight takes wild values; the rest stay
    plausible, so that most scenes pass validation and reach the renderer."""
    return fdp.ConsumeIntInRange(0, 7) == 0


def _faces(fdp: atheris.FuzzedDataProvider, n_vertices: int, wild: bool) -> list[list[int]]:
    corners = 4 if fdp.ConsumeBool() else 3
    faces = []
    for _ in range(fdp.ConsumeIntInRange(1, 6)):
        if wild:
            faces.append([fdp.ConsumeIntInRange(-2, n_vertices + 1) for _ in range(corners)])
        else:  # distinct corners
            order = list(range(n_vertices))
            faces.append([order.pop(fdp.ConsumeIntInRange(0, len(order) - 1))
                          for _ in range(min(corners, n_vertices))])
    return faces


def _material(fdp: atheris.FuzzedDataProvider, wild: bool) -> dualight.Material | None:
    kind = fdp.ConsumeIntInRange(0, 3)
    if kind == 0:
        return None
    if kind == 1:
        return dualight.Diffuse(_vec3(fdp, 0.0, 1.0, wild))
    if kind == 2:
        return dualight.Mirror(_vec3(fdp, 0.0, 1.0, wild))
    return dualight.Dielectric(ior=_float(fdp, 1.0, 3.0, wild))


def build_scene(fdp: atheris.FuzzedDataProvider) -> dualight.Scene:
    wild = _wild(fdp)
    camera = dualight.Camera(
        origin=_vec3(fdp, -4.0, 4.0, wild),
        target=_vec3(fdp, -4.0, 4.0, wild),
        up=_vec3(fdp, -1.0, 1.0, wild),
        fov=_float(fdp, 1.0, 179.0, wild),
        resolution=(fdp.ConsumeIntInRange(1, 6), fdp.ConsumeIntInRange(1, 6)),
    )
    scene = dualight.Scene(camera=camera)
    for i in range(fdp.ConsumeIntInRange(1, 3)):
        wild = _wild(fdp)
        n_vertices = fdp.ConsumeIntInRange(1 if wild else 3, 8)
        vertices = np.array([_vec3(fdp, -4.0, 4.0, wild) for _ in range(n_vertices)])
        faces = _faces(fdp, n_vertices, wild)
        emitter = fdp.ConsumeIntInRange(0, 7) != 0 if i == 0 else fdp.ConsumeBool()
        emission = _vec3(fdp, 0.0, 20.0, wild) if emitter else (0.0, 0.0, 0.0)
        material = _material(fdp, wild)
        reflectance = _vec3(fdp, 0.0, 1.0, wild) if material is None else (0.5, 0.5, 0.5)
        scene.add_mesh(
            vertices,
            faces,
            reflectance=reflectance,
            emission=emission,
            material=material,
            degenerate="drop" if fdp.ConsumeBool() else "raise",
        )
    return scene


def _check_finite(name: str, values: np.ndarray, allow_negative: bool = False) -> None:
    values = np.asarray(values)
    if not np.all(np.isfinite(values)):
        raise AssertionError(f"{name}: non-finite values {values[~np.isfinite(values)][:4]}")
    if not allow_negative and np.any(values < 0):
        raise AssertionError(f"{name}: negative values {values[values < 0][:4]}")


REACHED = {"built": 0, "rendered": 0}


def run(fdp: atheris.FuzzedDataProvider) -> None:
    scene = build_scene(fdp)
    REACHED["built"] += 1
    method = METHODS[fdp.ConsumeIntInRange(0, len(METHODS) - 1)]
    max_depth = fdp.ConsumeIntInRange(-1, 6)
    seed = fdp.ConsumeIntInRange(0, 1 << 20)
    if method == "radiosity":
        solver = SOLVERS[fdp.ConsumeIntInRange(0, len(SOLVERS) - 1)]
        solution = solve(
            scene, solver, max_iter=50, quadrature=1, shadow_rays=1, seed=seed, threads=1,
        )
        REACHED["rendered"] += 1
        # Coincident or overlapping coplanar patches get form-factor rows summing past 1 (the
        # stats report it); then I - rho F is no longer an M-matrix and a negative solution is
        # the honest solution of that system. Otherwise B and I must be >= 0.
        ill_posed = solution.stats.get("form_factors", {}).get("row_sum_max", 0.0) > 1.0 + 1e-3
        _check_finite("radiosity B", solution.B, allow_negative=ill_posed)
        if solution.I is not None:
            _check_finite("radiosity I", solution.I, allow_negative=ill_posed)
        return
    options = {}
    if method in ("pssmlt", "mmlt", "mlt"):
        options = {"bootstrap": fdp.ConsumeIntInRange(1, 64), "chains": fdp.ConsumeIntInRange(1, 4),
                   "direct_spp": fdp.ConsumeIntInRange(0, 2)}
    image = dualight.render(
        scene, method, spp=fdp.ConsumeIntInRange(1, 2), max_depth=max_depth,
        rr_depth=fdp.ConsumeIntInRange(1, 6), seed=seed, threads=1, progress=False,
        sampler="sobol" if fdp.ConsumeBool() else "independent",
        mlt=options or None,
        **({"heuristic": "balance"} if method != "path" and method != "light"
           and fdp.ConsumeBool() else {}),
    )
    REACHED["rendered"] += 1
    _check_finite(f"{method} image", np.asarray(image))
    if image.variance is not None:
        _check_finite(f"{method} variance", image.variance)


def test_one_input(data: bytes) -> None:
    fdp = atheris.FuzzedDataProvider(data)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            run(fdp)
        except ACCEPTED as exc:
            if not str(exc):
                raise AssertionError(f"{type(exc).__name__} without a message") from exc


def main() -> None:
    atheris.Setup(sys.argv, test_one_input)
    atexit.register(lambda: print(f"fuzz_scene: scenes built {REACHED['built']}, "
                                  f"rendered or solved {REACHED['rendered']}", file=sys.stderr))
    atheris.Fuzz()


if __name__ == "__main__":
    main()
