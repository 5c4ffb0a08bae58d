"""Fuzz the task data of split renders with atheris: what a worker receives (a chain start-up)
and what it returns (a chain part, a block of samples), as bytes from another process.

The first input byte picks the kind and the method; the rest is the data:
  * a chain start-up's bytes (``_core.ChainStartUp``'s pickled state) for PSSMLT, MMLT or MLT,
    run as a worker runs it (``executor.render_chains``) and merged (``_core.finish_chains``);
  * a chain part's bytes, merged with a valid start-up (``_core.finish_chains``);
  * changes to a valid block of samples of the path tracer, light tracer or BDPT (fields set to
    special values, resized or dropped), merged as ``render(executor=...)`` merges tasks.
The seed corpus holds the valid bytes of each, so the fuzzer starts from real layouts. The only
acceptable failure is a ValueError (or TypeError) with a message; a segfault, an abort, a
sanitizer report, a hang (libFuzzer's -timeout), another exception, or an accepted input that
gives a non-finite or negative image is a crash.

Run: ``python tests/fuzz/fuzz_tasks.py -max_total_time=60 corpus_dir`` (libFuzzer flags).
"""

from __future__ import annotations

import concurrent.futures
import copy
import sys
from pathlib import Path
from typing import Any

import atheris
import numpy as np

with atheris.instrument_imports():
    import dualight
    from dualight import _core, executor, scenes
    from dualight.methods import ESTIMATORS

ACCEPTED = (ValueError, TypeError)
CHAIN_METHODS = ("pssmlt", "mmlt", "mlt")
BLOCK_METHODS = ("path", "light", "bdpt")
RES = (6, 4)
SCENE = scenes.cornell_box(RES)
SPECIAL = (0.0, -1.0, 1e300, np.inf, np.nan, 2**32 - 1, 2**63, -(2**63))


class _Recorder(concurrent.futures.Executor):
    """Runs each task at once in this process, keeps its arguments and results, and hands back
    ``forge(result)`` (the result itself unless set)."""

    def __init__(self) -> None:
        self.calls: list[tuple[Any, ...]] = []
        self.results: list[Any] = []
        self.forge = lambda result: result

    def submit(self, fn: Any, /, *args: Any, **kwargs: Any) -> Any:
        self.calls.append(args)
        result = fn(*args, **kwargs)
        self.results.append(result)
        future: concurrent.futures.Future[Any] = concurrent.futures.Future()
        future.set_result(self.forge(result))
        return future


def _render(method: str, recorder: _Recorder) -> dualight.Image:
    kw: dict[str, Any] = dict(seed=1, progress=False, executor=recorder, max_depth=5)
    if method in BLOCK_METHODS:
        return dualight.render(SCENE, method, spp=20, **kw)  # two blocks
    mlt = dict(bootstrap=500, chains=8, direct_spp=1)
    return dualight.render(SCENE, method, mutations_per_pixel=2, mlt=mlt, **kw)


# A faithful render of each method: its first chain task's arguments, and its task results.
RECORDED = {m: _Recorder() for m in CHAIN_METHODS + BLOCK_METHODS}
for _method, _recorder in RECORDED.items():
    _render(_method, _recorder)


def _check_image(mean: Any) -> None:
    mean = np.asarray(mean)
    if not np.all(np.isfinite(mean)) or np.any(mean < 0):
        raise AssertionError("accepted task data gave a non-finite or negative image")


def _fuzz_start_up(method: str, data: bytes) -> None:
    token, scene, camera, _, keywords, _, first, count = RECORDED[method].calls[0]
    start = _core.ChainStartUp.__new__(_core.ChainStartUp)
    start.__setstate__(data)
    result = executor.render_chains(
        token, scene, camera, method, keywords, start, first, min(count, start.chains - first)
    )
    options = ESTIMATORS[method].options(**keywords)
    merged = _core.finish_chains(
        scene._compile(), camera._compile(), options, start, [result["part"]]
    )
    _check_image(merged["mean"])


def _fuzz_part(method: str, data: bytes) -> None:
    _, scene, camera, _, keywords, start, _, _ = RECORDED[method].calls[0]
    part = _core.ChainPart.__new__(_core.ChainPart)
    part.__setstate__(data)
    options = ESTIMATORS[method].options(**keywords)
    merged = _core.finish_chains(scene._compile(), camera._compile(), options, start, [part])
    _check_image(merged["mean"])


def _changed_block(result: dict[str, Any], fdp: atheris.FuzzedDataProvider) -> Any:
    """``result`` with a few fields set to special values, resized or dropped."""
    result = copy.deepcopy(result)
    for _ in range(fdp.ConsumeIntInRange(1, 4)):
        inner = result.get("accumulators")
        where = inner if isinstance(inner, dict) and inner and fdp.ConsumeBool() else result
        if not where:
            return result
        key = sorted(where)[fdp.ConsumeIntInRange(0, len(where) - 1)]
        value = where[key]
        how = fdp.ConsumeIntInRange(0, 3)
        if how == 0:
            del where[key]
        elif how == 1 and isinstance(value, np.ndarray):
            where[key] = np.resize(value, fdp.ConsumeIntInRange(0, value.size + 2))
        elif isinstance(value, np.ndarray) and value.size:
            value = value.copy()
            special = SPECIAL[fdp.ConsumeIntInRange(0, len(SPECIAL) - 1)]
            try:
                value.flat[fdp.ConsumeIntInRange(0, value.size - 1)] = special
            except (OverflowError, ValueError):
                value.flat[0] = 0
            where[key] = value
        else:
            where[key] = SPECIAL[fdp.ConsumeIntInRange(0, len(SPECIAL) - 1)]
    return result


def _fuzz_block(method: str, data: bytes) -> None:
    fdp = atheris.FuzzedDataProvider(data)
    recorder = _Recorder()
    recorder.forge = lambda result: _changed_block(result, fdp)
    _check_image(_render(method, recorder))


def test_one_input(data: bytes) -> None:
    if not data:
        return
    kind, pick = divmod(data[0] % 9, 3)
    try:
        if kind == 0:
            _fuzz_start_up(CHAIN_METHODS[pick], data[1:])
        elif kind == 1:
            _fuzz_part(CHAIN_METHODS[pick], data[1:])
        else:
            _fuzz_block(BLOCK_METHODS[pick], data[1:])
    except ACCEPTED as exc:
        if not str(exc):
            raise AssertionError(f"{type(exc).__name__} without a message") from exc


def seed_corpus(folder: Path) -> None:
    """The valid start-up and first part of each Metropolis method, and a few block changes."""
    for pick, method in enumerate(CHAIN_METHODS):
        start = RECORDED[method].calls[0][5].__getstate__()
        part = RECORDED[method].results[0]["part"].__getstate__()
        (folder / f"start_{method}").write_bytes(bytes([pick]) + start)
        (folder / f"part_{method}").write_bytes(bytes([3 + pick]) + part)
    for pick, method in enumerate(BLOCK_METHODS):
        (folder / f"block_{method}").write_bytes(bytes([6 + pick]) + bytes(range(16)))


def main() -> None:
    folders = [Path(a) for a in sys.argv[1:] if not a.startswith("-")]
    if folders and folders[0].is_dir() and not any(folders[0].iterdir()):
        seed_corpus(folders[0])
    atheris.Setup(sys.argv, test_one_input)
    atheris.Fuzz()


if __name__ == "__main__":
    main()
