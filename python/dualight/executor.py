"""Rendering split into tasks on a ``concurrent.futures.Executor``: a process pool, or a Dask
cluster (``distributed.Client`` or ``client.get_executor()``), on one machine or many.

Bit for bit the same image as one process, by construction (``src/film/film.h``): the core sums
samples and splats within fixed blocks of ``_core.BLOCK_SPP`` sample indices (for the light
tracer, of ``BLOCK_SPP`` x pixels particles), each block from zero in a fixed order, and adds
the blocks' sums to the film's totals in block order, whether it renders in one process or not.
Each task here renders exactly one block (``first_sample`` = k x ``BLOCK_SPP``) into a film of
its own, so its raw accumulators *are* that block's sums; the merge adds them to an empty
``_core.Film`` in block order with the same C++ additions, and the mean and variance come from
the same C++ code. Several blocks per task would not do: their sum would round differently.

The Metropolis methods split by chains instead (``src/pathspace/chain_split.h``): this process
runs the start-up once (direct light, pilot, bootstrap, which chains start; with all its cores,
as the workers would idle meanwhile), each task runs a range of chains from a copy of it and
returns their part, and the parts merge in chain order. A chain's mutations depend only on its
index, its splats sum exactly (fixed point, ``src/core/exact_sum.h``) and the large steps'
estimates of b merge in chain order, so any split gives the single-process image bit for bit.
"""

from __future__ import annotations

import concurrent.futures
import math
import os
import time
import uuid
from collections.abc import Callable, Iterable
from typing import Any

import numpy as np

from dualight.methods import ESTIMATORS
from dualight.scene import Camera, Scene

# Chains per task of a Metropolis render: 16 tasks for the default 256 chains, enough to keep a
# few workers busy while the stragglers finish, few enough that the start-up sent to each task
# (the bootstrap, about 0.8 MB per 100,000 samples and path length) stays cheap.
CHAINS_PER_TASK = 16

# Compiled scenes of the renders this worker process has run tasks for (by render token), so
# that a worker builds Embree's BVH once per render, not once per task.
_COMPILED: dict[str, Any] = {}
_COMPILED_KEEP = 2


def as_executor(executor: Any) -> concurrent.futures.Executor:
    """``executor`` as a ``concurrent.futures.Executor``: a ``distributed.Client`` gives its
    ``get_executor()``; anything else that is not an Executor is a TypeError."""
    if isinstance(executor, concurrent.futures.Executor):
        return executor
    if type(executor).__module__.split(".")[0] == "distributed" and hasattr(
        executor, "get_executor"
    ):
        return executor.get_executor()
    raise TypeError(
        "executor must be a concurrent.futures.Executor (e.g. ProcessPoolExecutor, or a Dask "
        f"client's get_executor()) or a distributed.Client, got {type(executor).__name__}"
    )


def _compiled_scene(token: str, scene: Scene) -> Any:
    """The scene compiled once per render in this worker process."""
    compiled = _COMPILED.get(token)
    if compiled is None:
        compiled = scene._compile()
        while len(_COMPILED) >= _COMPILED_KEEP:
            _COMPILED.pop(next(iter(_COMPILED)))
        _COMPILED[token] = compiled
    return compiled


def render_block(
    token: str,
    scene: Scene,
    camera: Camera,
    method: str,
    keywords: dict[str, Any],
    first_sample: int,
    spp: int,
) -> dict[str, Any]:
    """One task: sample indices ``[first_sample, first_sample + spp)`` (one block) of the render
    named by ``token``, its other options ``keywords``; returns the film's raw accumulators and
    the core's stats."""
    cpu_start = time.process_time()
    compiled = _compiled_scene(token, scene)
    estimator = ESTIMATORS[method]
    options = estimator.options(**{**keywords, "spp": spp, "first_sample": first_sample})
    result = estimator.render(compiled, camera._compile(), options, None, accumulators=True)
    stats = dict(result["stats"])
    stats["cpu_seconds"] = time.process_time() - cpu_start  # the worker's, compile included
    return {
        "accumulators": result["accumulators"],
        "stats": stats,
        "keyboard_interrupt": result["keyboard_interrupt"],
        "worker": os.getpid(),
    }


_SUMMED = ("samples", "rays", "skipped_connections", "skipped_shadow_rays", "invalid_samples")


def _is_count(value: Any) -> bool:
    return isinstance(value, int | np.integer) and not isinstance(value, bool) and value >= 0


def _is_seconds(value: Any) -> bool:
    return (
        isinstance(value, float | int | np.floating | np.integer)
        and not isinstance(value, bool)
        and math.isfinite(value)
        and value >= 0
    )


def _task_result(result: Any, fields: dict[str, Callable[[Any], bool]]) -> dict[str, Any]:
    """``result`` of an executor task, checked field by field before it is merged: it comes
    from another process (or machine), so a corrupt or foreign result raises ValueError naming
    the field instead of reaching the core."""
    if not isinstance(result, dict):
        raise ValueError(f"an executor task returned {type(result).__name__}, not a result dict")
    for key, valid in fields.items():
        if key not in result or not valid(result[key]):
            raise ValueError(f"an executor task returned a malformed result: {key!r}")
    return result


def _block_stats_valid(stats: Any) -> bool:
    return (
        isinstance(stats, dict)
        and all(_is_count(stats.get(key)) for key in _SUMMED)
        and all(_is_seconds(stats.get(key)) for key in ("seconds", "cpu_seconds"))
        and isinstance(stats.get("unoccluded"), bool)
    )


_BLOCK_RESULT: dict[str, Callable[[Any], bool]] = {
    "accumulators": lambda a: isinstance(a, dict),  # sizes and values: Film.add_accumulators
    "stats": _block_stats_valid,
    "keyboard_interrupt": lambda k: isinstance(k, bool),
    "worker": _is_count,
}


def _cancel(futures: Iterable[concurrent.futures.Future[Any]]) -> None:
    """Cancels the tasks not started (those running finish on their worker)."""
    for future in futures:
        future.cancel()


def _add_wall_stats(
    stats: dict[str, Any],
    start: float,
    *,
    interrupted: bool,
    tasks: int,
    workers: set[int],
    executor: concurrent.futures.Executor,
) -> None:
    """Adds what every split render reports of its wall time (``start`` on
    ``time.perf_counter``) and its tasks to ``stats``."""
    seconds = time.perf_counter() - start
    stats.update(
        seconds=seconds,
        samples_per_second=stats["samples"] / seconds if seconds > 0 else 0.0,
        rays_per_second=stats["rays"] / seconds if seconds > 0 else 0.0,
        interrupted=interrupted,
        time_limited=False,
        tasks=tasks,
        workers=len(workers),
        executor=type(executor).__name__,
    )


def render_split(
    executor: concurrent.futures.Executor,
    scene: Scene,
    camera: Camera,
    method: str,
    keywords: dict[str, Any],
    progress: Callable[[int, int], None] | None,
) -> dict[str, Any]:
    """Renders ``method`` (``"path"``, ``"light"``, ``"bdpt"``) with the keywords of its core
    options (``spp`` samples per pixel, no time limit) as one task per block on ``executor``
    and merges the blocks in order. Returns a dict like the core's (mean, variance,
    light_paths, stats, keyboard_interrupt). Ctrl-C cancels the tasks not started and returns
    what has finished."""
    from dualight import _core

    spp = keywords["spp"]
    block = int(_core.BLOCK_SPP)
    token = uuid.uuid4().hex
    width, height = camera.resolution
    pixels = width * height
    blocks = [(first, min(block, spp - first)) for first in range(0, spp, block)]
    start = time.perf_counter()
    futures = {
        executor.submit(render_block, token, scene, camera, method, keywords, first, count): k
        for k, (first, count) in enumerate(blocks)
    }
    film = _core.Film(width, height)
    stats: dict[str, Any] = {key: 0 for key in _SUMMED}
    stats.update(task_seconds=0.0, task_cpu_seconds=0.0, unoccluded=False, workers=set())
    done: dict[int, dict[str, Any]] = {}
    merged = 0
    interrupted = False

    def merge(result: dict[str, Any]) -> None:
        try:
            film.add_accumulators(result["accumulators"])
        except (ValueError, TypeError, KeyError, RuntimeError) as error:
            raise ValueError(f"an executor task returned malformed accumulators: {error}") from None
        task = result["stats"]
        for key in _SUMMED:
            stats[key] += task[key]
        stats["task_seconds"] += task["seconds"]
        stats["task_cpu_seconds"] += task["cpu_seconds"]
        stats["unoccluded"] = task["unoccluded"]
        stats["workers"].add(result["worker"])

    try:
        for future in concurrent.futures.as_completed(futures):
            k = futures[future]
            done[k] = _task_result(future.result(), _BLOCK_RESULT)
            interrupted = interrupted or done[k]["keyboard_interrupt"]
            # Blocks are added in block order: a finished block waits for those before it.
            while merged in done:
                merge(done.pop(merged))
                merged += 1
            if progress is not None:
                finished = sum(blocks[j][1] for j in range(merged)) + sum(
                    blocks[j][1] for j in done
                )
                progress(finished * pixels, spp * pixels)
    except KeyboardInterrupt:
        interrupted = True
        _cancel(futures)
        for k in sorted(done):  # still in block order, with the unfinished blocks left out
            merge(done.pop(k))
    except BaseException:
        _cancel(futures)
        raise

    # The light tracer's samples are particles, not the pixels' own samples.
    light = method == "light"
    stats["spp"] = int(film.light_paths // pixels) if light else int(film.counts().min())
    _add_wall_stats(
        stats,
        start,
        interrupted=interrupted,
        tasks=len(blocks),
        workers=stats["workers"],
        executor=executor,
    )
    mean, variance = np.asarray(film.mean()), np.asarray(film.variance())
    if not (np.all(np.isfinite(mean)) and np.all(np.isfinite(variance))):
        raise ValueError("the executor tasks' sums give an image beyond float32's range")
    return {
        "mean": mean,
        "variance": variance,
        "light_paths": int(film.light_paths),
        "stats": stats,
        "keyboard_interrupt": interrupted,
    }


def render_chains(
    token: str,
    scene: Scene,
    camera: Camera,
    method: str,
    keywords: dict[str, Any],
    start: Any,
    first_chain: int,
    chain_count: int,
) -> dict[str, Any]:
    """One task of a Metropolis render: chains ``[first_chain, first_chain + chain_count)`` of
    the start-up ``start`` (a ``_core.ChainStartUp``), the options' keywords ``keywords``;
    returns their ``_core.ChainPart``."""
    from dualight import _core

    cpu_start = time.process_time()
    compiled = _compiled_scene(token, scene)
    options = ESTIMATORS[method].options(**keywords)
    part = _core.run_chains(compiled, camera._compile(), options, start, first_chain, chain_count)
    return {
        "part": part,
        "cpu_seconds": time.process_time() - cpu_start,
        "worker": os.getpid(),
    }


def render_chain_split(
    executor: concurrent.futures.Executor,
    scene: Scene,
    camera: Camera,
    method: str,
    keywords: dict[str, Any],
    progress: Callable[[int, int], None] | None,
    start_threads: int = 0,
) -> dict[str, Any]:
    """Renders a Metropolis method (``pssmlt``, ``mmlt``, ``mlt``) with the keywords of its
    core options (``mutations_per_pixel``, no time limit): the start-up here on
    ``start_threads`` threads (0: every core), then the chains as tasks of ``CHAINS_PER_TASK``
    chains on ``executor``, merged in chain order. Returns a dict like the core's. Ctrl-C
    during the start-up returns its image (direct light); during the chains it cancels the
    tasks not started and merges those that finished."""
    from dualight import _core

    start_time = time.perf_counter()
    token = uuid.uuid4().hex
    width, height = camera.resolution
    compiled_scene, compiled_camera = scene._compile(), camera._compile()
    spp = keywords["mutations_per_pixel"]
    options = ESTIMATORS[method].options(**{**keywords, "threads": start_threads})
    start = _core.start_chains(compiled_scene, compiled_camera, options, progress)
    total = start.chains
    ranges = [
        (first, min(CHAINS_PER_TASK, total - first)) for first in range(0, total, CHAINS_PER_TASK)
    ]
    chain_counts = dict(ranges)
    parts: dict[int, Any] = {}
    task_seconds = task_cpu_seconds = 0.0
    workers: set[int] = set()
    interrupted = bool(start.cancelled)
    futures: dict[concurrent.futures.Future[dict[str, Any]], int] = {}
    target = width * height * spp
    try:
        if not interrupted:
            futures = {
                executor.submit(
                    render_chains,
                    token,
                    scene,
                    camera,
                    method,
                    keywords,
                    start.for_chains(first, count),
                    first,
                    count,
                ): first
                for first, count in ranges
            }
        for future in concurrent.futures.as_completed(futures):
            first = futures[future]
            result = _task_result(
                future.result(),
                {
                    "part": lambda p, first=first: (
                        isinstance(p, _core.ChainPart)
                        and p.first_chain == first
                        and p.chains == chain_counts[first]
                    ),
                    "cpu_seconds": _is_seconds,
                    "worker": _is_count,
                },
            )
            part = result["part"]
            parts[first] = part
            interrupted = interrupted or part.interrupted
            task_seconds += part.seconds
            task_cpu_seconds += result["cpu_seconds"]
            workers.add(result["worker"])
            if progress is not None:
                progress(sum(p.mutations for p in parts.values()), target)
    except KeyboardInterrupt:
        interrupted = True
        _cancel(futures)
    except BaseException:
        _cancel(futures)
        raise

    result = _core.finish_chains(
        compiled_scene,
        compiled_camera,
        options,
        start,
        [parts[first] for first in sorted(parts)],  # chain order
        interrupted,
    )
    stats = dict(result["stats"])
    stats.update(
        start_up_seconds=start.seconds,
        chains=total,
        task_seconds=task_seconds,
        task_cpu_seconds=task_cpu_seconds,
    )
    _add_wall_stats(
        stats,
        start_time,
        interrupted=interrupted,
        tasks=len(ranges),
        workers=workers,
        executor=executor,
    )
    result["stats"] = stats
    result["keyboard_interrupt"] = interrupted
    return result
