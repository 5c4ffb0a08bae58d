"""Task data from another process is untrusted (issue 18, item 1): a chain start-up a worker
receives, the chain part or the block of samples it returns. Each is crafted here as a corrupt
or hostile worker could send it (tests/task_bytes.py decodes and encodes the bytes) and must be
refused with a ValueError naming the problem, before any work: no segfault (a part with empty
sums but counted mutations, an MMLT start-up of path length 10**6, an empty direct-light image
all crashed), no corrupted heap (path length -5), no hang (a mutation target of 2**62) and no
NaN image. Every case starts from a valid result that is accepted (the control)."""

from __future__ import annotations

import concurrent.futures
import copy
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import dualight
import task_bytes
from dualight import _core, executor, scenes
from dualight.methods import ESTIMATORS

RES = (8, 6)
MLT = dict(bootstrap=2000, chains=20, direct_spp=2)


class _Forger(concurrent.futures.Executor):
    """Runs each task at once, in this process, keeps its arguments, and hands back what
    ``forge`` makes of its result (the identity: a faithful worker)."""

    def __init__(self, forge: Callable[[Any], Any] = lambda r: r) -> None:
        self.forge = forge
        self.calls: list[tuple[Any, ...]] = []

    def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> Any:
        self.calls.append(args)
        future: concurrent.futures.Future[Any] = concurrent.futures.Future()
        future.set_result(self.forge(fn(*args, **kwargs)))
        return future


def _render(method: str, forger: _Forger) -> dualight.Image:
    kw: dict[str, Any] = dict(seed=3, progress=False, executor=forger, max_depth=5)
    if method in ("path", "light", "bdpt"):  # two blocks of samples
        return dualight.render(scenes.cornell_box(RES), method, spp=20, **kw)
    return dualight.render(scenes.cornell_box(RES), method, mutations_per_pixel=4, mlt=MLT, **kw)


def _rebuilt(cls: Any, data: bytes) -> Any:
    obj = cls.__new__(cls)
    obj.__setstate__(data)
    return obj


def _forged_part(change: Callable[[dict[str, Any]], None]) -> Callable[[Any], Any]:
    def forge(result: dict[str, Any]) -> dict[str, Any]:
        d = task_bytes.decode_part(result["part"].__getstate__())
        change(d)
        return {**result, "part": _rebuilt(_core.ChainPart, task_bytes.encode_part(d))}

    return forge


def _empty_sums(d: dict[str, Any]) -> None:
    for p in d["populations"]:
        p["metropolis"] = (p["metropolis"][0], [])
        p["large"] = (p["large"][0], [])
        p["mutations"] = max(p["mutations"], 1)


def _first(d: dict[str, Any]) -> dict[str, Any]:
    return next(p for p in d["populations"] if p["mutations"] > 0)


PARTS: dict[str, tuple[Callable[[dict[str, Any]], None], str]] = {
    "empty sums, mutations counted": (_empty_sums, "no image"),
    "image of another size": (
        lambda d: _first(d).update(metropolis=(_first(d)["metropolis"][0], [0, 0] * 7)),
        "another size|different sizes",
    ),
    "negative sums": (
        lambda d: _first(d).update(
            metropolis=(
                _first(d)["metropolis"][0],
                [0, 2**63] * (len(_first(d)["metropolis"][1]) // 2),
            )
        ),
        "negative sums",
    ),
    "NaN in a large-step estimate": (
        lambda d: _first(d).update(large_f=[(float("nan"), 0.0, 1)] * len(_first(d)["large_f"])),
        "not finite",
    ),
    "more accepted than proposed": (
        lambda d: _first(d).update(accepted=_first(d)["mutations"] + 1),
        "do not add up",
    ),
    "chains shifted": (lambda d: d.update(first_chain=d["first_chain"] + 1), "malformed result"),
    "chain count wrapping around": (
        lambda d: d.update(first_chain=2**64 - 1, chains=2),
        "malformed result",
    ),
}


@pytest.mark.parametrize("method", ["pssmlt", "mmlt", "mlt"])
@pytest.mark.parametrize("case", sorted(PARTS))
def test_a_crafted_chain_part_is_refused(method: str, case: str) -> None:
    change, message = PARTS[case]
    if method == "mlt" and "large-step" in case:
        pytest.skip("path-space MLT has no large steps")
    faithful = _render(method, _Forger())
    assert np.all(np.isfinite(np.asarray(faithful))) and np.any(np.asarray(faithful) > 0)
    with pytest.raises(ValueError, match=message):
        _render(method, _Forger(_forged_part(change)))


def _start_up(method: str) -> tuple[tuple[Any, ...], dict[str, Any]]:
    """A chain task's arguments from a faithful render, and its start-up decoded."""
    forger = _Forger()
    _render(method, forger)
    args = forger.calls[0]
    return args, task_bytes.decode_start_up(args[5].__getstate__())


def _pop(d: dict[str, Any]) -> dict[str, Any]:
    """The first population with chains (and a bootstrap: the first task's chains are its)."""
    return next(p for p in d["populations"] if p["chains"] > 0)


def _chains(d: dict[str, Any]) -> int:
    return sum(p["chains"] for p in d["populations"])


STARTS: dict[str, tuple[Callable[[dict[str, Any]], None], str]] = {
    "path length 10**6": (lambda d: _pop(d).update(depth=10**6), "path length"),
    "path length -5": (lambda d: _pop(d).update(depth=-5), "path length"),
    "empty direct-light image": (lambda d: d.update(image=[]), "direct-light image"),
    "NaN in the image": (lambda d: d["image"].__setitem__(0, float("nan")), "direct-light image"),
    "pilot of another size": (lambda d: d.update(pilot=[1.0] * 5), "pilot image"),
    "negative bootstrap weight": (
        lambda d: _pop(d)["weights"].__setitem__(0, -1.0),
        "finite and non-negative",
    ),
    "bootstrap without light": (
        lambda d: _pop(d).update(weights=[0.0] * len(_pop(d)["weights"])),
        "without light",
    ),
    "mutation target of 2**62": (lambda d: _pop(d).update(target=2**62), "more chains or mut"),
    "no mutation target": (lambda d: _pop(d).update(target=0), "mutation target"),
    "a second population of one length": (
        lambda d: d["populations"].append(
            {**copy.deepcopy(_pop(d)), "chains": 0, "first_chain": _chains(d), "chain_ids": []}
        ),
        "populations|path length",
    ),
}


@pytest.mark.parametrize("method", ["pssmlt", "mmlt", "mlt"])
@pytest.mark.parametrize("case", sorted(STARTS))
def test_a_crafted_start_up_is_refused_by_the_worker_and_the_merge(method: str, case: str) -> None:
    change, message = STARTS[case]
    args, d = _start_up(method)
    token, scene, camera, method_, keywords, start, first, count = args
    faithful = executor.render_chains(*args)  # the control: the start-up as it came
    assert faithful["part"].chains == count
    change(d)
    forged = _rebuilt(_core.ChainStartUp, task_bytes.encode_start_up(d))
    with pytest.raises(ValueError, match=message):
        executor.render_chains(token, scene, camera, method_, keywords, forged, first, count)
    options = ESTIMATORS[method].options(**keywords)
    compiled = scene._compile()
    with pytest.raises(ValueError, match=message):
        _core.finish_chains(compiled, camera._compile(), options, forged, [faithful["part"]])


def _forged_block(change: Callable[[dict[str, Any]], Any]) -> Callable[[Any], Any]:
    return lambda result: change(copy.deepcopy(result))


def _set(path: str, value: Any) -> Callable[[dict[str, Any]], dict[str, Any]]:
    """A change of one field (``a.b``: field b of field a) to ``value``, or to what
    ``value(old)`` gives."""

    def change(result: dict[str, Any]) -> dict[str, Any]:
        *parents, key = path.split(".")
        target = result
        for p in parents:
            target = target[p]
        target[key] = value(target.get(key)) if callable(value) else value
        return result

    return change


def _first_value(value: Any) -> Callable[[np.ndarray], np.ndarray]:
    def change(array: np.ndarray) -> np.ndarray:
        array = np.array(array, copy=True)
        array.flat[0] = value
        return array

    return change


BLOCKS: dict[str, tuple[Callable[[dict[str, Any]], Any], str]] = {
    "not a dict": (lambda r: list(r.items()), "list, not a result dict"),
    "NaN radiance": (_set("accumulators.sum", _first_value(np.nan)), "non-finite"),
    "radiance beyond float32": (
        _set("accumulators.sum", _first_value(1e300)),
        "float32|without samples",
    ),
    "negative radiance": (_set("accumulators.sum", _first_value(-1.0)), "negative"),
    "negative square sum": (_set("accumulators.sum_sq", _first_value(-1.0)), "negative"),
    "image of another size": (_set("accumulators.sum", np.zeros(7)), "malformed accumulators"),
    "count wrapping around": (_set("accumulators.count", _first_value(2**32 - 1)), "overflow"),
    "no stats": (_set("stats", None), "'stats'"),
    "negative ray count": (_set("stats.rays", -4), "'stats'"),
    "worker as text": (_set("worker", "me"), "'worker'"),
    "interrupt flag as a number": (_set("keyboard_interrupt", 2), "'keyboard_interrupt'"),
}


@pytest.mark.parametrize("method", ["path", "light", "bdpt"])
@pytest.mark.parametrize("case", sorted(BLOCKS))
def test_a_crafted_block_of_samples_is_refused(method: str, case: str) -> None:
    change, message = BLOCKS[case]
    faithful = _render(method, _Forger())
    assert np.all(np.isfinite(np.asarray(faithful))) and np.any(np.asarray(faithful) > 0)
    with pytest.raises(ValueError, match=message):
        _render(method, _Forger(_forged_block(change)))


def test_task_bytes_round_trip() -> None:
    """The codec the tests craft with reads and writes the core's bytes exactly."""
    for method in ("pssmlt", "mmlt", "mlt"):
        args, d = _start_up(method)
        assert task_bytes.encode_start_up(d) == args[5].__getstate__()
        part = executor.render_chains(*args)["part"].__getstate__()
        assert task_bytes.encode_part(task_bytes.decode_part(part)) == part
