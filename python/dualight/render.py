"""`dualight.render`: one entry point for every image estimator."""

from __future__ import annotations

import numbers
import os
import time
from collections.abc import Callable, Mapping
from typing import Any, Literal

import numpy as np

from dualight import _core
from dualight._progress import TqdmProgress as _TqdmProgress
from dualight.executor import as_executor, render_chain_split, render_split
from dualight.image import Image
from dualight.methods import (
    ESTIMATORS,
    METHODS,
    METROPOLIS,
    Estimator,
    Heuristic,
    Lanes,
    Method,
    Sampler,
    Strategies,
)
from dualight.radiosity.solution import Solution
from dualight.scene import Camera, Scene, _freezes_scene

# The core's defaults of the keywords render shares with the options (BDPT's have them all).
_DEFAULT = _core.BdptOptions()

ProgressCallback = Callable[[int, int], None]


def _check_int(name: str, value: Any, minimum: int, maximum: int | None = None) -> int:
    """``value`` as a Python int: any integer (numpy's too) but a bool, ``>= minimum``."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    if maximum is not None and value > maximum:
        raise ValueError(f"{name} must be an integer <= {maximum}, got {value!r}")
    return int(value)


def _plain(value: Any) -> Any:
    """A numpy integer or float as the Python number (for the core's options and the stats,
    which are saved as JSON); anything else unchanged, for the core to check and name."""
    if isinstance(value, bool | np.bool_):
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, numbers.Real):
        return float(value)
    return value


def _only_for(keyword: str, unset: bool, estimator: Estimator, method: str) -> None:
    """A keyword that only some methods' options take must stay unset for the others."""
    if not unset and not estimator.takes(keyword):
        takers = ", ".join(repr(n) for n, e in ESTIMATORS.items() if e.takes(keyword))
        raise ValueError(f"{keyword} applies to method {takers} only, not {method!r}")


def _seed_guides(scene: Scene, method: str, options: Any, solution: Solution) -> tuple[Any, Any]:
    """The guides a radiosity solution seeds for ``method`` (``render(guide_from=...)``):
    radiance for camera paths, importance for light paths (None where not needed)."""
    from dualight.guiding import solution_records  # guiding imports this module

    if not isinstance(solution, Solution):
        raise TypeError(
            f"guide_from must be a dualight.radiosity.Solution, got {type(solution).__name__}"
        )
    lo, hi = (np.asarray(b, dtype=np.float64) for b in scene.bounds())
    slack = 1e-3 * float(np.max(hi - lo)) + 1e-6
    # The patches subdivide the scene's triangles: the same scene has the same box.
    vertices = solution.patches.vertices
    if (np.abs(vertices.min(axis=0) - lo) > slack).any() or (
        np.abs(vertices.max(axis=0) - hi) > slack
    ).any():
        raise ValueError(
            "guide_from's solution is of another scene: its patches' box is not this scene's"
        )
    compiled = scene._compile()
    settings = {
        "bsdf_fraction": options.guide_bsdf_fraction,
        "spatial_threshold": options.guide_spatial_threshold,
        "rho": options.guide_rho,
    }

    def guide(transport: Literal["radiance", "importance"]) -> Any:
        records = solution_records(solution, transport, seed=options.seed)
        return _core.guide_from_records(compiled, records, **settings)

    radiance = guide("radiance") if method in ("path", "bdpt") else None
    importance = guide("importance") if method in ("light", "bdpt") else None
    return radiance, importance


def _guiding_fields(
    guiding: bool | Mapping[str, Any], estimator: Estimator, method: str
) -> dict[str, Any]:
    """The core's ``guide_*`` option fields of ``render(guiding=...)``: ``True``, ``False`` or a
    dict of the guide's options without their ``guide_`` prefix."""
    if guiding is False:
        return {}
    if guiding is not True and not isinstance(guiding, Mapping):
        raise TypeError(f"guiding must be True, False or a dict of guide options, got {guiding!r}")
    if not estimator.takes("guiding"):
        takers = ", ".join(repr(n) for n, e in ESTIMATORS.items() if e.takes("guiding"))
        raise ValueError(f"guiding applies to method {takers} only, not {method!r}")
    fields: dict[str, Any] = {"guiding": True}
    valid = [f[len("guide_") :] for f in estimator.options._fields if f.startswith("guide_")]
    for key, value in guiding.items() if isinstance(guiding, Mapping) else ():
        if key not in valid:
            raise TypeError(f"unknown guiding option {key!r}; valid: {', '.join(valid)}")
        fields["guide_" + key] = _plain(value)
    return fields


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


def _skipped(
    stats: dict[str, Any], skip: bool, scene: Scene, method: str, strategies: str = "mis"
) -> dict[str, Any]:
    """What a render left out, from its counters: shadow rays known unneeded (convex
    enclosure), connections that could not carry light (a specular end, a zero BSDF or
    emission term, a point outside the view), mutations the scene cannot use, and BDPT's
    strategies that cannot find light in a scene lit only by delta lights (point, spot and
    directional: no path hits one, so s = 0 finds nothing; BDPT and PSSMLT do not evaluate
    them, MMLT does not offer them), and the path tracer's shadow rays of light samples that
    ``strategies="bsdf"`` weights 0."""
    out: dict[str, Any] = {
        "enabled": skip,
        "shadow_rays": int(stats.get("skipped_shadow_rays", 0)),
        "connections": int(stats.get("skipped_connections", 0)),
    }
    if "skipped_mutations" in stats:
        out["mutations"] = list(stats["skipped_mutations"])
    bidirectional = method in ("bdpt", "pssmlt") or (method == "mmlt" and skip)
    if bidirectional and not scene._compile().has_hittable_emitter:
        out["strategies"] = ["s = 0: every emitter is a delta light (no path hits one)"]
    if method == "path" and strategies == "bsdf":
        out["light_samples"] = "weighted 0 where BSDF sampling can find the light: no shadow ray"
    return out


def _budget(
    estimator: Estimator,
    spp: int | None,
    time_limit: float | None,
    threads: int | None,
    mutations_per_pixel: int | None,
) -> tuple[int | None, int | None]:
    """render's own keywords where None means something (the core's options take 0 for it),
    checked: ``(spp, threads)`` as the render uses them. The core checks the rest as it builds
    the options."""
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
    if threads is not None:
        _check_int("threads", threads, 1)
        threads = min(threads, os.cpu_count() or threads)
    if mutations_per_pixel is not None:
        if not estimator.metropolis:
            raise ValueError(f"mutations_per_pixel applies to {', '.join(METROPOLIS)} only")
        # The core counts them per pixel in 32 bits, as spp.
        _check_int("mutations_per_pixel", mutations_per_pixel, 1, (1 << 32) - 1)
        spp = mutations_per_pixel
    return spp, threads


def _progress_callback(
    progress: bool | ProgressCallback | None, bar: _TqdmProgress | None
) -> ProgressCallback | None:
    """The core's progress callback for render's ``progress``: the tqdm ``bar`` for True."""
    if progress is True:
        return bar
    if progress is False or progress is None:
        return None
    if callable(progress):
        return progress
    raise TypeError("progress must be True, False or a callable(done, total)")


def _image(result: Mapping[str, Any], stats: dict[str, Any], strategy_images: bool) -> Image:
    """The core's result as an Image; a KeyboardInterrupt carrying it when Ctrl-C stopped it."""
    image = Image(result["mean"], variance=result["variance"], stats=stats)
    if strategy_images:
        image.strategies = dict(result["strategies"])
    if result["keyboard_interrupt"]:
        interrupt = KeyboardInterrupt(f"render interrupted after {stats['samples']} samples")
        interrupt.partial_result = image  # type: ignore[attr-defined]
        raise interrupt
    return image


@_freezes_scene
def render(
    scene: Scene,
    method: Method = "path",
    *,
    spp: int | None = _DEFAULT.spp,
    time_limit: float | None = None,
    max_depth: int = _DEFAULT.max_depth,
    rr_depth: int | None = None,
    seed: int = _DEFAULT.seed,
    threads: int | None = None,
    progress: bool | ProgressCallback = True,
    camera: Camera | None = None,
    sampler: Sampler = _DEFAULT.sampler.name,  # type: ignore[assignment]
    heuristic: Heuristic = _DEFAULT.heuristic.name,  # type: ignore[assignment]
    strategies: Strategies = _DEFAULT.strategies.name,  # type: ignore[assignment]
    lanes: Lanes = "auto",
    strategy_images: bool = _DEFAULT.strategy_images,
    light_pool: int | None = None,
    mutations_per_pixel: int | None = None,
    mlt: Mapping[str, Any] | None = None,
    skip: bool = _DEFAULT.skip_unneeded,
    executor: Any = None,
    guiding: bool | Mapping[str, Any] = False,
    guide_from: Solution | None = None,
) -> Image:
    """Render ``scene`` from its camera and return a linear RGB :class:`Image`.

    Numbers may be Python's or numpy's (``spp=np.int64(64)``, ``time_limit=np.float32(2)``);
    a bool is not taken for an integer. ``method``, ``sampler`` and ``heuristic`` are typed
    with the :mod:`dualight.methods` aliases (``Method``, ...), so a type checker catches a
    misspelled name; at run time a wrong one is a ``ValueError`` listing the valid ones.

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
        apart by BDPT (``direct_spp`` samples per pixel) and left out of the chains. Large steps
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
        Russian roulette starts at this path vertex. ``None``: the method's own default, 5
        (Mitsuba's) for the path and light tracers and the MLT methods, 2 for BDPT, whose
        connections multiply with its subpaths' lengths (1.0-1.6x as efficient as with 5 at
        equal time on the test scenes, 0.54x on the furnace, whose estimate hardly varies
        without roulette; README, "Speed"). ``image.stats["rr_depth"]`` says which ran.
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
        The Metropolis methods' own options, passed on as keywords to their core options
        class, whose docstring gives each one's default and range (``help(
        dualight._core.PssmltOptions)``); a misspelled key is a ``TypeError`` listing the
        valid ones, and so is a key ``render`` sets itself (``max_depth``, ``seed``, ...).
        ``"pssmlt"`` and ``"mmlt"`` (``PssmltOptions``): ``bootstrap`` (independent samples
        for b, per path length for MMLT, and the chains' starts), ``chains``, ``sigma``
        (small-step deviation), ``large_step_probability``, ``large_step_mis`` (True:
        Kelemen's MIS of large steps; False: the chains' expected values only),
        ``direct_spp`` (0 keeps direct light in the chains).
        ``"mlt"`` (``MltOptions``): ``bootstrap``, ``chains``, ``direct_spp`` as above;
        mutation weights ``bidirectional``, ``lens_subpath``, ``lens_perturbation``,
        ``caustic_perturbation``, ``multi_chain_perturbation`` (0 disables one);
        ``lens_radius_min`` and ``lens_radius_max`` (pixels; 0: a tenth of the film width),
        ``angle_min`` and ``angle_max`` (radians); ``importance``: the chains' target,
        ``"luminance"`` (Veach's image luminance, the default) or ``"flattened"``
        (luminance over the square root of a smoothed pilot estimate of the pixel's
        brightness: mutations spread towards dark pixels, lower relMSE where brightness
        varies a lot, as on the door; costs ``bootstrap / 4`` more BDPT samples).
    strategies:
        ``"path"`` and ``"bdpt"``: which sampling strategies make the image (Veach's figure
        9.2 is three renders). ``"mis"`` (the default) combines them all by multiple
        importance sampling. ``"bsdf"``: BSDF sampling alone (the path tracer without
        next-event estimation; BDPT's strategies with the fewest light vertices, ``s = 0``).
        ``"light"``: light sampling alone (next-event estimation; BDPT's ``s = 1``). Each stays
        unbiased: a path goes to the other strategy only where the chosen one cannot sample it
        (a point, spot or directional light for ``"bsdf"``; an emitter seen from the camera or
        through a mirror for ``"light"``), so only the variance differs. The path tracer
        skips the shadow rays that ``"bsdf"`` would weight 0; BDPT still evaluates every
        connection.
    lanes:
        ``"path"`` only: ``"auto"`` (the default) runs sixteen paths together (eight with
        AVX2; a path that ends hands its lane to the next pixel sample), their rays traced as
        Embree packets and their shading in SIMD lanes, on AVX-512 or else AVX2 where the CPU
        has it, unguided. Diffuse, mirror and smooth glass materials and area emitters,
        without textures, run lane-wide; other materials and emitters (environments
        included) go lane by lane through the scalar code (faster than one path at a time
        even where they cover the whole scene). ``"off"`` runs one path at a time; ``"sse2"``,
        ``"avx2"`` and ``"avx512"`` ask for one build (a ``ValueError`` where the CPU lacks
        it; the SSE2 build runs slower than one path at a time and serves checks). The image
        is the same, bit for bit, whichever runs: only the speed differs.
        ``image.stats["lanes"]`` says which ran (``"off"`` with ``["lanes_off_because"]``).
    strategy_images:
        BDPT only, with a bounded ``max_depth``: also return each strategy's MIS-weighted
        contribution as ``image.strategies[(s, t)]`` (H x W x 3 arrays; ``s`` light vertices,
        ``t`` camera vertices, ``s + t - 1`` segments). They sum to the image.
    light_pool:
        BDPT only: each connection of a camera vertex to a light vertex (s, t >= 2) takes the
        light subpath of another pixel of its group of ``light_pool`` pixels (1 to 16; the same
        tile row, the same sample index), a different one for each strategy; each pixel sample
        still traces one light subpath. 1 is classic BDPT (each sample's connections use its
        own). ``None``: 16, where a sample's connections no longer succeed or fail together:
        on Veach's door 0.69x the relMSE at equal spp, with no block size (up to 32x32) losing,
        though the pixels of a group correlate a little (README, "Speed"). The image stays
        unbiased and a function of the seed. Guided BDPT uses 1. ``image.stats["light_pool"]``
        says which ran.
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

    guiding:
        ``"path"``, ``"light"`` and ``"bdpt"``: path guiding (Müller, Gross and Novák 2017).
        ``True`` first trains a guide in iterations of 1, 2, 4, ... samples per pixel, each
        guided by the last: for ``"path"`` the radiance that camera paths found, for
        ``"light"`` the importance that light paths carried to the camera (where a particle
        will be seen); ``"bdpt"`` trains both together from its own samples (each strategy's
        MIS-weighted contribution teaches the radiance guide along its camera subpath and the
        importance guide along its light subpath), samples camera subpaths from the radiance
        guide and light subpaths from the importance guide, and weighs its strategies by MIS
        with the guided densities in both directions (Vorba et al. 2014); its
        ``stats["guiding"]`` holds ``radiance`` and ``importance``.
        The image is then rendered sampling each direction from the guide or the BSDF (one-
        sample MIS), so it stays unbiased; for ``"path"`` its paths also play adjoint-driven
        Russian roulette and splitting (Vorba and Křivánek 2016): a path whose expected
        contribution (its throughput times the guide's estimate of the radiance reflected
        where it is) is far below its pixel's value, estimated by the last training image,
        goes on with probability at least 0.3; one far above it splits into up to 16 paths
        (the training's iterations after the first play it too, from the previous one's).
        A dict sets the guide's options: ``training`` (share of the budget: of ``spp``, added
        on top, or of ``time_limit``, counted in it; default 0.25), ``keep_iterations``
        (the image keeps the samples of that many last training iterations, default 2,
        which hold 3/4 of the training's; with ``strategy_images`` none; every sample is unbiased
        whatever guide drew it, so the image is their plain mean; with ``spp`` it then has
        ``spp`` plus ``stats["guiding"]["kept_spp"]`` samples per pixel), ``trial`` (True:
        under a ``time_limit``, before the training iteration predicted to be the last (or
        after the training), a pass guided by the guide so far and an unguided pass of half
        the last iteration's samples per pixel each (at least 32), both kept in the image,
        measure which is more efficient, 1 / (expected relMSE x seconds), and the image is
        rendered by that one (unguided stops the training there: ``stopped_by_trial``;
        before the last iteration the guided pass must also pay for that iteration's time
        beyond its kept samples: ``trial_ratio_to_pay``), unless the passes disagree
        beyond their own variances (a heavy tail one of them missed: ``trial_disagreement``
        above 1.15), when it stays guided; ``stats["guiding"]`` reports ``trial``, ``trial_spp``,
        ``trial_seconds``, ``efficiency_ratio`` (guided over unguided),
        ``trial_ratio_to_pay``, ``trial_disagreement`` and ``rendered_guided``; with
        ``spp`` alone there is no trial, so the render stays a function of the seed),
        ``bsdf_fraction`` (least probability of sampling the BSDF, 0.5; each spatial leaf
        learns its own from how the previous iteration's guide did on its records unless
        ``learn_bsdf_fraction=False``), ``adjoint_roulette`` (True), ``spatial_threshold``
        (records a spatial leaf may hold at 1 spp, 1000), ``rho`` (directional subdivision,
        0.01) and ``max_records``. ``image.stats["guiding"]`` reports the iterations,
        training and rendering seconds, the trees' sizes, the BSDF fraction, the paths
        splitting added and the roulette stopped, and the kept samples; ``seconds`` includes
        the training and the trial. :func:`dualight.train_guide` returns the guide itself, to
        draw.
    guide_from:
        With ``guiding``: a :class:`dualight.radiosity.Solution` of the same scene (with form
        factors; for ``"light"`` and ``"bdpt"`` solved with ``importance=True``) whose
        radiosity and importance seed the guides (:func:`dualight.guiding.solution_records`):
        the first training iteration samples them instead of the BSDF alone, so light paths
        head for what the camera sees from the start (Peter and Pietrek 1998).
        ``stats["guiding"]`` says ``seeded`` and ``seeding_seconds`` (counted in ``seconds``
        and in ``time_limit``; the solution's own solve is not).

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
    if method not in ESTIMATORS:
        raise ValueError(f"unknown method {method!r}; choose one of {', '.join(METHODS)}")
    estimator = ESTIMATORS[method]
    spp, threads = _budget(estimator, spp, time_limit, threads, mutations_per_pixel)
    if rr_depth is None:
        rr_depth = estimator.default("rr_depth")
    max_depth, rr_depth, seed, time_limit = (
        _plain(v) for v in (max_depth, rr_depth, seed, time_limit)
    )
    if mlt is not None and not estimator.metropolis:
        raise ValueError(f"mlt options apply to the MLT methods only ({', '.join(METROPOLIS)})")
    if mlt is not None and not isinstance(mlt, Mapping):
        raise TypeError(f"mlt must be a dict of options, got {type(mlt).__name__}")
    _only_for("heuristic", heuristic == _DEFAULT.heuristic.name, estimator, method)
    _only_for("strategies", strategies == _DEFAULT.strategies.name, estimator, method)
    _only_for("lanes", lanes == "auto", estimator, method)
    _only_for("strategy_images", not strategy_images, estimator, method)
    _only_for("light_pool", light_pool is None, estimator, method)
    if estimator.takes("light_pool") and light_pool is None:
        light_pool = estimator.default("light_pool")
    if not estimator.takes("sampler"):
        # The Metropolis methods draw their own numbers: the name is checked, not used.
        _core.PathTracerOptions(sampler=sampler)
    if camera is not None and not isinstance(camera, Camera):
        raise TypeError(f"camera must be a dualight.Camera, got {type(camera).__name__}")
    if not isinstance(skip, bool):
        raise TypeError(f"skip must be True or False, got {skip!r}")
    fields: dict[str, Any] = {
        estimator.budget: spp or 0,
        "max_depth": max_depth,
        "rr_depth": rr_depth,
        "seed": seed,
        "threads": threads or 0,
        "time_limit": time_limit or 0.0,
        "skip_unneeded": skip,
    }
    for keyword, value in (
        ("sampler", sampler),
        ("heuristic", heuristic),
        ("strategies", strategies),
        ("lanes", lanes),
        ("strategy_images", strategy_images),
        ("light_pool", None if light_pool is None else _plain(light_pool)),
    ):
        if estimator.takes(keyword):
            fields[keyword] = value
    fields.update(_guiding_fields(guiding, estimator, method))
    keywords = estimator.keywords(fields, mlt)
    options = estimator.options(**keywords)  # the core checks every value, before any work
    if guide_from is not None and guiding is False:
        raise ValueError("guide_from seeds path guiding's guides: give guiding=True (or a dict)")
    if executor is not None:
        executor = as_executor(executor)
        if time_limit is not None or spp is None:
            raise ValueError(
                "executor= needs spp (mutations_per_pixel) and no time_limit: tasks are blocks "
                "of samples or ranges of chains, fixed before they run"
            )
        if strategy_images:
            raise ValueError("strategy_images is not supported with executor= yet")
        if guiding is not False:
            raise ValueError(
                "guiding is not supported with executor= yet (each task would train its own guide)"
            )
    scene.validate_for_rendering(camera)
    cam = camera or scene.camera
    assert cam is not None
    seeding = 0.0
    if guide_from is not None:
        start = time.perf_counter()
        radiance, importance = _seed_guides(scene, method, options, guide_from)
        seeding = time.perf_counter() - start
        if time_limit:  # the seeding counts in the render's time
            left = max(1e-3, time_limit - seeding)
            options = estimator.options(**{**keywords, "time_limit": left})
        options = _core.with_guide_start(options, radiance, importance)

    def finish(result: Mapping[str, Any]) -> Image:
        stats = dict(result["stats"])
        stats.update(
            method=method, sampler=sampler, seed=seed, max_depth=max_depth, rr_depth=rr_depth
        )
        # What the scene asks for: without mirrors or glass no connection is skipped as specular.
        stats["specular_surfaces"] = scene.has_specular
        stats["scene"] = _scene_features(scene, cam)
        stats["skipped"] = _skipped(stats, skip, scene, method, strategies)
        if method != "path":
            stats["light_paths"] = result["light_paths"]
        if method == "bdpt":
            stats["heuristic"] = heuristic
            stats["light_pool"] = 1 if "guiding" in stats else fields["light_pool"]
        if method in ("path", "bdpt"):
            stats["strategies"] = strategies
        if method == "path":
            stats.setdefault("lanes", "off")
        if guide_from is not None and "guiding" in stats:
            stats["guiding"] = {**stats["guiding"], "seeding_seconds": seeding}
            stats["seconds"] += seeding
        stats["threads"] = (threads or 1) if executor is not None else (threads or os.cpu_count())
        return _image(result, stats, strategy_images)

    bar = _TqdmProgress(f"dualight {method}") if progress is True else None
    callback = _progress_callback(progress, bar)
    try:
        if executor is not None:
            # Each task uses `threads` threads (default 1: the workers give the parallelism);
            # the Metropolis methods' start-up runs here, on every core by default.
            tasks = {**keywords, "threads": threads or 1}
            if estimator.metropolis:
                start_threads = threads or 0
                result = render_chain_split(
                    executor, scene, cam, method, tasks, callback, start_threads
                )
            else:
                result = render_split(executor, scene, cam, method, tasks, callback)
        else:
            result = estimator.render(scene._compile(), cam._compile(), options, callback)
    except BaseException as error:
        # A signal handler's or the progress callback's exception (SystemExit, a timeout, ...)
        # comes from the core with the render's partial result: as an Image, like Ctrl-C's.
        partial = getattr(error, "partial_result", None)
        if isinstance(partial, dict):
            error.partial_result = finish({**partial, "keyboard_interrupt": False})
        raise
    finally:
        if bar is not None:
            bar.close()
    return finish(result)
