"""`dualight.render`: one entry point for every image estimator."""

from __future__ import annotations

import numbers
import os
from collections.abc import Callable
from typing import Any

from dualight.image import Image
from dualight.scene import Camera, Scene

METHODS = ("path", "light", "bdpt", "pssmlt", "mmlt", "mlt")
_MLT = ("pssmlt", "mmlt", "mlt")
SAMPLERS = ("independent", "sobol")
HEURISTICS = ("power", "balance")

ProgressCallback = Callable[[int, int], None]


class _TqdmProgress:
    """Adapts the core's (done, total) callback to a tqdm bar, created on first use and reset
    when the total changes."""

    def __init__(self, description: str) -> None:
        self._description = description
        self._bar: Any = None

    def __call__(self, done: int, total: int) -> None:
        if self._bar is None:
            from tqdm.auto import tqdm

            self._bar = tqdm(
                total=total or None, desc=self._description, unit="spl", unit_scale=True
            )
        elif total and total != self._bar.total:
            # A new phase (the MLT methods: direct light, then the chains' mutations).
            self._bar.reset(total=total)
        self._bar.n = done
        self._bar.refresh()

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()


# Keyword options each MLT method takes through ``mlt=`` (the rest of its core options struct
# comes from render's own keywords). Integers among them must be >= the given minimum.
_MLT_OPTIONS: dict[str, frozenset[str]] = {
    "pssmlt": frozenset(
        {"bootstrap", "chains", "sigma", "large_step_probability", "large_step_mis", "direct_spp"}
    ),
    "mlt": frozenset(
        {
            "bootstrap",
            "chains",
            "direct_spp",
            "bidirectional",
            "lens_subpath",
            "lens_perturbation",
            "caustic_perturbation",
            "multi_chain_perturbation",
            "lens_radius_min",
            "lens_radius_max",
            "angle_min",
            "angle_max",
            "importance",
        }
    ),
}
_MLT_OPTIONS["mmlt"] = _MLT_OPTIONS["pssmlt"]
_MLT_INT_MINIMUM = {"bootstrap": 1, "chains": 1, "direct_spp": 0}


def _check_int(name: str, value: Any, minimum: int, maximum: int | None = None) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    if maximum is not None and value > maximum:
        raise ValueError(f"{name} must be an integer <= {maximum}, got {value!r}")
    return value


def _check_mlt_options(method: str, mlt: Any) -> dict[str, Any]:
    """``mlt=`` as a dict of known keys: a misspelled key is a TypeError naming it, a negative
    count a ValueError (instead of pybind11's list of overloads)."""
    if not isinstance(mlt, dict):
        raise TypeError(f"mlt must be a dict of options, got {type(mlt).__name__}")
    valid = _MLT_OPTIONS[method]
    for key, value in mlt.items():
        if key not in valid:
            raise TypeError(
                f"unknown mlt option {key!r} for method {method!r}; "
                f"valid: {', '.join(sorted(valid))}"
            )
        if key in _MLT_INT_MINIMUM:
            _check_int(f"mlt option {key}", value, _MLT_INT_MINIMUM[key], (1 << 32) - 1)
    return mlt


def _scene_features(scene: Scene, camera: Camera | None = None) -> dict[str, Any]:
    """``scene.features`` plus what depends on the camera: ``camera_enclosed`` (its origin
    strictly inside the convex enclosure) and ``emitters_facing_camera`` (emitter triangles
    whose front faces the camera's origin: none means no emitter can be seen directly)."""
    compiled = scene._compile()
    features = scene.features
    cam = camera or scene.camera
    if cam is not None:
        features["camera_enclosed"] = bool(compiled.encloses(tuple(cam.origin)))
        features["emitters_facing_camera"] = scene.emitters_facing(cam.origin)
    return features


def _skipped(stats: dict[str, Any], skip: bool) -> dict[str, Any]:
    """What a render left out, from its counters: shadow rays known unneeded (convex
    enclosure), connections that could not carry light (a specular end, a zero BSDF or
    emission term, a point outside the view), mutations the scene cannot use."""
    out: dict[str, Any] = {
        "enabled": skip,
        "shadow_rays": int(stats.get("skipped_shadow_rays", 0)),
        "connections": int(stats.get("skipped_connections", 0)),
    }
    if "skipped_mutations" in stats:
        out["mutations"] = list(stats["skipped_mutations"])
    return out


def _estimator(
    method: str,
    *,
    spp: int,
    max_depth: int,
    rr_depth: int,
    seed: int,
    threads: int,
    time_limit: float,
    sampler: str,
    heuristic: str,
    strategy_images: bool = False,
    mlt: dict[str, Any] | None = None,
    skip: bool = True,
) -> tuple[Callable[..., dict[str, Any]], Any]:
    """The core's render function for ``method`` and its options (arguments already checked):
    shared by :func:`render` and the tasks of :mod:`dualight.executor`."""
    from dualight import _core

    common = dict(
        spp=spp,
        max_depth=max_depth,
        rr_depth=rr_depth,
        seed=seed,
        threads=threads,
        time_limit=time_limit,
        sampler=getattr(_core.SamplerType, sampler),
    )
    if method == "path":
        run, options = _core.render_path, _core.PathTracerOptions(**common)
    elif method == "light":
        run, options = _core.render_light, _core.LightTracerOptions(**common)
    elif method == "mlt":
        common["mutations_per_pixel"] = common.pop("spp")
        common.pop("sampler")
        run, options = (
            _core.render_mlt,
            _core.MltOptions(
                **common, heuristic=getattr(_core.MisHeuristic, heuristic), **(mlt or {})
            ),
        )
    elif method in _MLT:
        common["mutations_per_pixel"] = common.pop("spp")
        common.pop("sampler")
        run, options = (
            _core.render_pssmlt,
            _core.PssmltOptions(
                **common,
                heuristic=getattr(_core.MisHeuristic, heuristic),
                multiplexed=method == "mmlt",
                **(mlt or {}),
            ),
        )
    else:
        run, options = (
            _core.render_bdpt,
            _core.BdptOptions(
                **common,
                heuristic=getattr(_core.MisHeuristic, heuristic),
                strategy_images=strategy_images,
            ),
        )
    options.skip_unneeded = skip
    return run, options


def render(
    scene: Scene,
    method: str = "path",
    *,
    spp: int | None = 64,
    time_limit: float | None = None,
    max_depth: int = -1,
    rr_depth: int = 5,
    seed: int = 0,
    threads: int | None = None,
    progress: bool | ProgressCallback = True,
    camera: Camera | None = None,
    sampler: str = "independent",
    heuristic: str = "power",
    strategy_images: bool = False,
    mutations_per_pixel: int | None = None,
    mlt: dict[str, Any] | None = None,
    skip: bool = True,
    executor: Any = None,
) -> Image:
    """Render ``scene`` from its camera and return a linear RGB :class:`Image`.

    Parameters
    ----------
    method:
        ``"path"``: path tracing with next-event estimation and MIS (power heuristic).
        ``"light"``: light (particle) tracing, the adjoint estimator: ``spp`` x pixels
        particles leave the emitters and every diffuse vertex is connected to the camera, as
        Mitsuba's ``ptracer``. Surfaces seen only through a mirror or glass next to the camera
        (specular-to-camera paths) stay dark: no particle can reach the pinhole through them.
        ``"bdpt"``: bidirectional path tracing, every (s, t) strategy combined by MIS.
        ``"pssmlt"``: primary-sample-space Metropolis light transport over BDPT (Kelemen et
        al. 2002); its budget is ``mutations_per_pixel`` (or ``spp``) and/or ``time_limit``.
        Emitters seen directly and direct lighting (paths of 1 and 2 segments) are rendered
        apart by BDPT (``direct_spp``, default 128) and left out of the chains. Large steps
        also count as independent samples, combined with the chains' by Kelemen's MIS
        (``large_step_mis``). Its pixels are correlated, so ``image.variance`` is ``None``;
        ``image.stats`` has the normalisation ``b`` with its 95 % interval ``b_ci95`` (from
        the bootstrap and every large step) and the acceptance rates.
        ``"mmlt"``: multiplexed MLT (Hachisuka et al. 2014): chains per path length, each
        sample one BDPT strategy; chains, mutations and (with ``time_limit``) time are
        allocated to lengths in proportion to their bootstrap b_d, so the allocation is fixed
        by the seed. Each b_d is refined by its chains' large steps: ``stats["b_per_depth"]``
        and ``["b_per_depth_ci95"]``, with ``["mutations_per_depth"]``, indexed by path length
        in segments. Needs a bounded ``max_depth``.
        ``"mlt"``: path-space Metropolis light transport (Veach and Guibas 1997) with Veach's
        mutations: bidirectional, lens subpath, and lens, caustic and multi-chain
        perturbations, each chosen among those that suit the current path in proportion to
        its weight (``mlt={"lens_perturbation": 1.0, ...}``). Chains start from BDPT samples
        resampled in proportion to their contribution; budget, direct light, ``b`` and
        ``variance`` as for ``"pssmlt"``; ``image.stats["mutation_types"]`` has each
        mutation's proposals, acceptances and failures.
    spp:
        Samples per pixel (particles per pixel for ``"light"``). ``None`` renders until
        ``time_limit``. With both, whichever ends first stops the render (at a whole pass, so
        every pixel has the same count).
    time_limit:
        Seconds of wall time, or ``None``.
    max_depth:
        Longest path in segments, as in Mitsuba: 1 shows emitters only, 2 adds direct
        lighting, -1 is unbounded.
    rr_depth:
        Russian roulette starts at this path vertex (Mitsuba's default 5).
    seed:
        The image is a deterministic function of the seed, whatever ``threads`` is.
    threads:
        Worker threads; ``None`` uses every core.
    progress:
        ``True`` shows a tqdm bar, ``False`` nothing; a callable gets ``(done, total)``
        samples about every 100 ms.
    camera:
        Overrides ``scene.camera``.
    sampler:
        ``"independent"`` (uniform random numbers, as Mitsuba's default; per-pixel variances
        are honest error estimates) or ``"sobol"`` (Owen-scrambled padded Sobol, as pbrt-v4's
        default: lower error at the same spp, but its per-pixel sample variance overstates the
        error, so use independent sampling for statistical tests).
    heuristic:
        BDPT's MIS heuristic: ``"power"`` (exponent 2, the default) or ``"balance"``.
    mlt:
        ``"pssmlt"`` and ``"mmlt"``: keyword options of ``dualight._core.PssmltOptions``:
        ``bootstrap`` (100000 independent samples for b, per path length for MMLT, and the
        chains' starts), ``chains`` (256), ``sigma`` (0.01, small-step deviation),
        ``large_step_probability`` (0.3), ``large_step_mis`` (True: Kelemen's MIS of large
        steps; False: the chains' expected values only), ``direct_spp`` (128; 0 keeps direct
        light in the chains).
        ``"mlt"``: of ``dualight._core.MltOptions``: ``bootstrap``, ``chains``,
        ``direct_spp`` as above; mutation weights ``bidirectional`` (1), ``lens_subpath``
        (0.25), ``lens_perturbation``, ``caustic_perturbation``,
        ``multi_chain_perturbation`` (1 each; 0 disables); ``lens_radius_min`` (0.1 pixel),
        ``lens_radius_max`` (0: a tenth of the film width), ``angle_min`` (1e-4 rad),
        ``angle_max`` (0.1 rad); ``importance``: the chains' target, ``"luminance"`` (Veach's
        image luminance, the default) or ``"flattened"`` (luminance over the square root of a
        smoothed pilot estimate of the pixel's brightness: mutations spread towards dark
        pixels, lower relMSE where brightness varies a lot, as on the door; costs
        ``bootstrap / 4`` more BDPT samples).
    strategy_images:
        BDPT only, with a bounded ``max_depth``: also return each strategy's MIS-weighted
        contribution as ``image.strategies[(s, t)]`` (H x W x 3 arrays; ``s`` light vertices,
        ``t`` camera vertices, ``s + t - 1`` segments). They sum to the image.
    skip:
        Skip work the scene makes pointless (the default), as its features
        (``scene.features``) allow: no shadow rays in a convex enclosure without glass that
        holds the camera (nothing can block a connection there), no caustic or multi-chain
        perturbations without mirrors or glass, no connection to a specular vertex or along a
        zero BSDF. ``image.stats["skipped"]`` says what was skipped, ``["scene"]`` the
        features. ``False`` does all the work (to measure what skipping saves); the image's
        expected value is the same.
    executor:
        A ``concurrent.futures.Executor`` (e.g. ``ProcessPoolExecutor``, or a Dask client's
        ``get_executor()``) or a ``distributed.Client`` to render on. ``"path"``,
        ``"light"`` and ``"bdpt"``: the samples are split into one task per block of
        ``dualight._core.BLOCK_SPP`` (16) samples per pixel (particles per pixel for
        ``"light"``), and the blocks merged in order. ``"pssmlt"``, ``"mmlt"`` and
        ``"mlt"``: the start-up (direct light, bootstrap, chain starts) runs here on
        ``threads`` threads (default: every core), then the chains run as tasks of 16 chains
        and their parts merge in chain order. Either way the image equals the single-process
        image with the same seed and ``spp`` bit for bit (mean and variance; ``b`` too). Each
        task uses ``threads`` threads (default 1: the executor's workers give the
        parallelism) and gets the scene description pickled; workers need the same dualight
        version. Needs ``spp`` (no ``time_limit``); ``progress`` advances per finished task;
        ``stats`` adds ``tasks``, ``workers``, ``task_seconds`` and ``task_cpu_seconds``
        (and ``chains`` and ``start_up_seconds`` for the Metropolis methods).

    Returns
    -------
    Image
        With ``.variance`` (variance of each pixel's mean) and ``.stats`` (method, spp,
        samples, rays, seconds, samples_per_second, ...).

    Raises
    ------
    KeyboardInterrupt
        On Ctrl-C, within about 0.1 s; the partial image is ``exc.partial_result``.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a dualight.Scene, got {type(scene).__name__}")
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}; choose one of {', '.join(METHODS)}")
    if spp is None and time_limit is None:
        raise ValueError("give spp, time_limit, or both")
    if spp is not None:
        _check_int("spp", spp, 1)
        if spp >= 1 << 32:
            raise ValueError(f"spp must be < 2**32, got {spp}")
    if time_limit is not None and (
        isinstance(time_limit, bool)
        or not isinstance(time_limit, numbers.Real)
        or not 0 < time_limit < float("inf")
    ):
        raise ValueError(f"time_limit must be a finite number > 0 of seconds, got {time_limit!r}")
    if (
        isinstance(max_depth, bool)
        or not isinstance(max_depth, int)
        or not -1 <= max_depth < 1 << 31
    ):
        raise ValueError(f"max_depth must be -1 (unbounded) or an integer >= 0, got {max_depth!r}")
    _check_int("rr_depth", rr_depth, 1, (1 << 31) - 1)
    _check_int("seed", seed, 0, (1 << 64) - 1)
    if threads is not None:
        _check_int("threads", threads, 1)
        threads = min(threads, os.cpu_count() or threads)
    if sampler not in SAMPLERS:
        raise ValueError(f"unknown sampler {sampler!r}; choose one of {', '.join(SAMPLERS)}")
    if mutations_per_pixel is not None:
        if method not in _MLT:
            raise ValueError("mutations_per_pixel applies to pssmlt, mmlt and mlt only")
        _check_int("mutations_per_pixel", mutations_per_pixel, 1)
        spp = mutations_per_pixel
    if mlt is not None and method not in _MLT:
        raise ValueError("mlt options apply to the MLT methods only (pssmlt, mmlt, mlt)")
    if mlt is not None:
        mlt = _check_mlt_options(method, mlt)
    if heuristic not in HEURISTICS:
        raise ValueError(f"unknown heuristic {heuristic!r}; choose one of {', '.join(HEURISTICS)}")
    if method not in ("bdpt", *_MLT) and heuristic != "power":
        raise ValueError("heuristic applies to method='bdpt' and the MLT methods only")
    if method != "bdpt" and strategy_images:
        raise ValueError("strategy_images applies to method='bdpt' only")
    if strategy_images and max_depth < 1:
        raise ValueError("strategy_images needs a bounded max_depth >= 1")
    if camera is not None and not isinstance(camera, Camera):
        raise TypeError(f"camera must be a dualight.Camera, got {type(camera).__name__}")
    if not isinstance(skip, bool):
        raise TypeError(f"skip must be True or False, got {skip!r}")
    if executor is not None:
        from dualight.executor import as_executor

        executor = as_executor(executor)
        if time_limit is not None or spp is None:
            raise ValueError(
                "executor= needs spp (mutations_per_pixel) and no time_limit: tasks are blocks "
                "of samples or ranges of chains, fixed before they run"
            )
        if strategy_images:
            raise ValueError("strategy_images is not supported with executor= yet")
    scene.validate_for_rendering(camera)
    cam = camera or scene.camera
    assert cam is not None

    run, options = _estimator(
        method,
        spp=spp or 0,
        max_depth=max_depth,
        rr_depth=rr_depth,
        seed=seed,
        threads=threads or 0,
        time_limit=time_limit or 0.0,
        sampler=sampler,
        heuristic=heuristic,
        strategy_images=strategy_images,
        mlt=mlt,
        skip=skip,
    )
    bar = None
    callback: ProgressCallback | None
    if progress is True:
        bar = _TqdmProgress(f"dualight {method}")
        callback = bar
    elif progress is False or progress is None:
        callback = None
    elif callable(progress):
        callback = progress
    else:
        raise TypeError("progress must be True, False or a callable(done, total)")
    try:
        if executor is not None:
            from dualight.executor import CHAIN_SPLIT, render_chain_split, render_split

            task_options = dict(
                max_depth=max_depth,
                rr_depth=rr_depth,
                seed=seed,
                threads=threads or 1,
                sampler=sampler,
                heuristic=heuristic,
                skip=skip,
            )
            assert spp is not None
            if method in CHAIN_SPLIT:
                task_options["mlt"] = mlt
                result = render_chain_split(
                    executor, scene, cam, method, task_options, spp, callback, threads or 0
                )
            else:
                result = render_split(executor, scene, cam, method, task_options, spp, callback)
        else:
            result = run(scene._compile(), cam._compile(), options, callback)
    finally:
        if bar is not None:
            bar.close()

    stats = dict(result["stats"])
    stats.update(method=method, sampler=sampler, seed=seed, max_depth=max_depth, rr_depth=rr_depth)
    # What the scene asks for: without mirrors or glass no connection is skipped as specular.
    stats["specular_surfaces"] = scene.has_specular
    stats["scene"] = _scene_features(scene, cam)
    stats["skipped"] = _skipped(stats, skip)
    if method != "path":
        stats["light_paths"] = result["light_paths"]
    if method == "bdpt":
        stats["heuristic"] = heuristic
    stats["threads"] = (threads or 1) if executor is not None else (threads or os.cpu_count())
    image = Image(result["mean"], variance=result["variance"], stats=stats)
    if strategy_images:
        image.strategies = dict(result["strategies"])
    if result["keyboard_interrupt"]:
        interrupt = KeyboardInterrupt(f"render interrupted after {stats['samples']} samples")
        interrupt.partial_result = image  # type: ignore[attr-defined]
        raise interrupt
    return image
