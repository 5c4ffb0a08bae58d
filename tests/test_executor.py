"""render(executor=...): samples split into tasks on a process pool or a Dask cluster give the
single-process image bit for bit (mean and variance), with the same seed and spp."""

from __future__ import annotations

import pickle
from collections.abc import Iterator
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

import dualight
from dualight import _core, scenes

SPP = 40  # blocks of 16, 16 and 8 samples per pixel: a short last block too


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
    for method in ("pssmlt", "mmlt", "mlt"):
        with pytest.raises(ValueError, match=f"not supported for method '{method}'"):
            dualight.render(scene, method, spp=4, max_depth=4, progress=False, executor=pool)
    with pytest.raises(ValueError, match="time_limit"):
        dualight.render(scene, spp=4, time_limit=1.0, progress=False, executor=pool)
    with pytest.raises(ValueError, match="strategy_images"):
        dualight.render(
            scene, "bdpt", spp=4, max_depth=3, strategy_images=True, progress=False,
            executor=pool,
        )
