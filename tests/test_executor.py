"""render(executor=...): samples (or Metropolis chains) split into tasks on a process pool or a
Dask cluster give the single-process image bit for bit (mean and variance; MLT's b), with the
same seed and spp."""

from __future__ import annotations

import pickle
from collections.abc import Iterator
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

import dualight
from dualight import _core, scenes
from dualight.executor import CHAINS_PER_TASK
from dualight.methods import ESTIMATORS

SPP = 40  # blocks of 16, 16 and 8 samples per pixel: a short last block too
# Small Metropolis renders: 40 chains make tasks of 16, 16 and 8 chains (mmlt: as its path
# lengths' populations come out); direct light on so that the start-up's image counts too.
MLT_OPTIONS = dict(bootstrap=3000, chains=40, direct_spp=4)
MUTATIONS = 24


@pytest.fixture(scope="module")
def scene() -> dualight.Scene:
    return scenes.cornell_box(resolution=(40, 32))


@pytest.fixture(scope="module")
def pool() -> Iterator[ProcessPoolExecutor]:
    with ProcessPoolExecutor(2) as executor:
        yield executor


def _same(a: dualight.Image, b: dualight.Image) -> bool:
    return np.array_equal(np.asarray(a), np.asarray(b)) and np.array_equal(a.variance, b.variance)


def test_blocks_are_sixteen_samples() -> None:
    assert _core.BLOCK_SPP == 16


@pytest.mark.parametrize("method", ["path", "light", "bdpt"])
def test_process_pool_gives_the_single_process_image_bit_for_bit(
    scene: dualight.Scene, pool: ProcessPoolExecutor, method: str
) -> None:
    single = dualight.render(scene, method, spp=SPP, seed=11, progress=False)
    split = dualight.render(scene, method, spp=SPP, seed=11, progress=False, executor=pool)
    assert _same(single, split)
    assert np.any(np.asarray(split) > 0)
    s = split.stats
    assert s["tasks"] == 3 and s["spp"] == SPP == single.stats["spp"]
    assert s["samples"] == single.stats["samples"] and s["rays"] == single.stats["rays"]
    if method != "path":
        assert s["light_paths"] == single.stats["light_paths"] == 40 * 32 * SPP
    # Negative controls: equality above is not vacuous.
    other_seed = dualight.render(scene, method, spp=SPP, seed=12, progress=False, executor=pool)
    assert not np.array_equal(np.asarray(other_seed), np.asarray(single))
    other_spp = dualight.render(scene, method, spp=SPP + 8, seed=11, progress=False, executor=pool)
    assert not np.array_equal(np.asarray(other_spp), np.asarray(single))


def test_sobol_sampler_and_thread_count_do_not_change_the_image(
    scene: dualight.Scene, pool: ProcessPoolExecutor
) -> None:
    kwargs = dict(spp=32, seed=3, sampler="sobol", max_depth=4, progress=False)
    single = dualight.render(scene, threads=2, **kwargs)
    split = dualight.render(scene, threads=2, executor=pool, **kwargs)
    assert _same(single, split)


def test_dask_local_cluster_gives_the_single_process_image_bit_for_bit(
    scene: dualight.Scene,
) -> None:
    distributed = pytest.importorskip("distributed")
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0"
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        for method in ("bdpt", "light"):
            single = dualight.render(scene, method, spp=SPP, seed=4, progress=False)
            by_client = dualight.render(
                scene, method, spp=SPP, seed=4, progress=False, executor=client
            )
            assert _same(single, by_client)
            assert by_client.stats["workers"] == 2
        single = dualight.render(scene, "path", spp=SPP, seed=4, progress=False)
        by_executor = dualight.render(
            scene, "path", spp=SPP, seed=4, progress=False, executor=client.get_executor()
        )
        assert _same(single, by_executor)
        other = dualight.render(scene, "path", spp=SPP, seed=5, progress=False, executor=client)
        assert not np.array_equal(np.asarray(other), np.asarray(single))
        for method in ("mmlt", "mlt"):
            single = _mlt(scene, method, threads=2)
            by_client = _mlt(scene, method, executor=client)
            assert np.array_equal(np.asarray(single), np.asarray(by_client))
            assert by_client.stats["b"] == single.stats["b"]
            assert by_client.stats["workers"] == 2


def test_scene_pickles_without_its_compiled_form(scene: dualight.Scene) -> None:
    scene._compile()
    copy = pickle.loads(pickle.dumps(scene))
    assert copy._compiled is None and not copy.meshes[0].vertices.flags.writeable
    a = dualight.render(scene, spp=4, seed=1, progress=False)
    b = dualight.render(copy, spp=4, seed=1, progress=False)
    assert _same(a, b)


def test_progress_per_task_and_ctrl_c_keeps_the_finished_blocks(
    scene: dualight.Scene, pool: ProcessPoolExecutor
) -> None:
    calls: list[tuple[int, int]] = []

    def progress(done: int, total: int) -> None:
        calls.append((done, total))

    image = dualight.render(scene, spp=64, progress=progress, executor=pool)
    assert len(calls) == 4 and calls[-1] == (40 * 32 * 64,) * 2
    assert image.stats["tasks"] == 4

    def interrupt(done: int, total: int) -> None:
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt) as info:
        dualight.render(scene, spp=16 * 6, progress=interrupt, executor=pool)
    partial = info.value.partial_result  # type: ignore[attr-defined]
    assert partial.stats["interrupted"]
    assert 0 < partial.stats["samples"] < 40 * 32 * 16 * 6
    assert partial.stats["samples"] % (40 * 32 * 16) == 0  # whole blocks only


def test_bad_executor_and_unsupported_options(
    scene: dualight.Scene, pool: ProcessPoolExecutor
) -> None:
    for bad in ("pool", object(), 2):
        with pytest.raises(TypeError, match="concurrent.futures.Executor"):
            dualight.render(scene, spp=4, progress=False, executor=bad)
    with pytest.raises(ValueError, match="time_limit"):
        dualight.render(scene, spp=4, time_limit=1.0, progress=False, executor=pool)
    with pytest.raises(ValueError, match="time_limit"):
        dualight.render(scene, "mlt", spp=None, time_limit=1.0, progress=False, executor=pool)
    with pytest.raises(ValueError, match="strategy_images"):
        dualight.render(
            scene, "bdpt", spp=4, max_depth=3, strategy_images=True, progress=False,
            executor=pool,
        )


def _mlt(scene: dualight.Scene, method: str, **kwargs: object) -> dualight.Image:
    options = dict(spp=MUTATIONS, seed=9, max_depth=6, progress=False, mlt=dict(MLT_OPTIONS))
    options.update(kwargs)
    return dualight.render(scene, method, **options)  # type: ignore[arg-type]


@pytest.mark.parametrize("method", ["pssmlt", "mmlt", "mlt"])
def test_process_pool_gives_the_single_process_mlt_image_bit_for_bit(
    scene: dualight.Scene, pool: ProcessPoolExecutor, method: str
) -> None:
    single = _mlt(scene, method, threads=2)
    split = _mlt(scene, method, executor=pool)
    assert np.array_equal(np.asarray(single), np.asarray(split))
    assert np.any(np.asarray(split) > 0)
    s, t = split.stats, single.stats
    assert s["tasks"] >= 3 and s["chains"] == 40 and s["workers"] >= 1
    assert s["b"] == t["b"] and s["b_ci95"] == t["b_ci95"]
    assert s["mutations"] == t["mutations"] == 40 * 32 * MUTATIONS
    assert s["rays"] == t["rays"] and s["acceptance_rate"] == t["acceptance_rate"]
    if method == "mlt":
        assert s["mutation_types"] == t["mutation_types"]
    if method == "mmlt":
        assert s["b_per_depth"] == t["b_per_depth"]
        assert s["mutations_per_depth"] == t["mutations_per_depth"]
    # Negative controls: the equality above is not vacuous.
    other_seed = _mlt(scene, method, seed=10, executor=pool)
    assert not np.array_equal(np.asarray(other_seed), np.asarray(single))
    other_spp = _mlt(scene, method, spp=MUTATIONS + 1, executor=pool)
    assert not np.array_equal(np.asarray(other_spp), np.asarray(single))


@pytest.mark.parametrize(
    ("method", "extra"),
    [("pssmlt", {"large_step_mis": False}), ("mlt", {"importance": "flattened", "direct_spp": 0})],
)
def test_any_split_of_the_chains_gives_the_same_image(
    scene: dualight.Scene, method: str, extra: dict[str, object]
) -> None:
    """Uneven ranges, a single chain, parts pickled: always the single-process image."""
    estimator = ESTIMATORS[method]
    fields = dict(mutations_per_pixel=MUTATIONS, max_depth=6, seed=2, threads=2)
    options = estimator.options(**estimator.keywords(fields, {**MLT_OPTIONS, **extra}))
    compiled, camera = scene._compile(), scene.camera._compile()  # type: ignore[union-attr]
    single = estimator.render(compiled, camera, options)
    start = pickle.loads(pickle.dumps(_core.start_chains(compiled, camera, options)))
    assert start.chains == 40 and not start.cancelled
    cuts = [0, 1, 2, 19, 40]
    parts = [
        pickle.loads(
            pickle.dumps(
                _core.run_chains(compiled, camera, options, start.for_chains(a, b - a), a, b - a)
            )
        )
        for a, b in zip(cuts[:-1], cuts[1:], strict=True)
    ]
    merged = _core.finish_chains(compiled, camera, options, start, parts)
    assert np.array_equal(single["mean"], merged["mean"])
    assert merged["stats"]["b"] == single["stats"]["b"]
    # Negative control: a part left out changes the image (and counts fewer mutations).
    missing = _core.finish_chains(compiled, camera, options, start, parts[:2] + parts[3:])
    assert not np.array_equal(single["mean"], missing["mean"])
    assert missing["stats"]["mutations"] < single["stats"]["mutations"]
    # Bad input is a clear error.
    with pytest.raises(ValueError, match="chain order"):
        _core.finish_chains(compiled, camera, options, start, parts[::-1])
    with pytest.raises(ValueError, match="not all in the start-up"):
        _core.run_chains(compiled, camera, options, start, 30, 11)
    broken = _core.ChainPart.__new__(_core.ChainPart)
    with pytest.raises(ValueError, match="chain"):
        broken.__setstate__(pickle.dumps(parts[0])[10:40])


def test_ctrl_c_keeps_the_finished_chains(
    scene: dualight.Scene, pool: ProcessPoolExecutor
) -> None:
    target = 40 * 32 * MUTATIONS
    calls: list[tuple[int, int]] = []

    def interrupt(done: int, total: int) -> None:
        if total == target and done > 0:  # a task of chains has finished
            calls.append((done, total))
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt) as info:
        no_direct = dict(MLT_OPTIONS, direct_spp=0)
        _mlt(scene, "pssmlt", progress=interrupt, executor=pool, mlt=no_direct)
    partial = info.value.partial_result  # type: ignore[attr-defined]
    assert calls and partial.stats["interrupted"]
    assert 0 < partial.stats["mutations"] < target
    assert np.all(np.isfinite(np.asarray(partial))) and np.any(np.asarray(partial) > 0)


def test_chains_per_task() -> None:
    assert CHAINS_PER_TASK == 16
