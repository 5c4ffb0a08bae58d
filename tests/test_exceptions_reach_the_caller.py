"""Exceptions raised while the core works reach the caller unchanged (issue 18, item 5): one a
Python signal handler raises (SIGALRM raising a custom exception, SIGTERM raising
SystemExit(3)) came out as KeyboardInterrupt, and one the progress callback raised on its last
call (done == total) was swallowed. Each now reaches the caller as it was raised, the render's
partial image on it as ``partial_result``; Ctrl-C still gives KeyboardInterrupt (the control)."""

from __future__ import annotations

import os
import signal
import threading
from collections.abc import Callable, Iterator

import numpy as np
import pytest

import dualight
from dualight import scenes
from dualight.radiosity import HierarchicalSolver, solve


class Deadline(Exception):
    """What a user's SIGALRM handler raises."""


@pytest.fixture
def handlers() -> Iterator[None]:
    saved = {s: signal.getsignal(s) for s in (signal.SIGALRM, signal.SIGTERM, signal.SIGINT)}
    yield
    for s, handler in saved.items():
        signal.signal(s, handler)


def _raise(exc: BaseException) -> Callable[..., None]:
    def handler(*_: object) -> None:
        raise exc

    return handler


def _long_render(method: str) -> dualight.Image:
    depth = {"max_depth": 8} if method == "mmlt" else {}
    return dualight.render(
        scenes.cornell_box(resolution=(32, 32)),
        method,
        spp=1_000_000,
        time_limit=20.0,
        progress=False,
        **depth,
    )


def _signal_soon(signum: int) -> threading.Timer:
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signum))
    timer.start()
    return timer


@pytest.mark.usefixtures("handlers")
@pytest.mark.parametrize("method", ["path", "bdpt", "pssmlt", "mlt"])
def test_a_signal_handlers_exception_reaches_the_caller_with_the_partial_image(
    method: str,
) -> None:
    signal.signal(signal.SIGALRM, _raise(Deadline("out of time")))
    timer = _signal_soon(signal.SIGALRM)
    with pytest.raises(Deadline, match="out of time") as info:
        _long_render(method)
    timer.join()
    partial = info.value.partial_result  # type: ignore[attr-defined]
    assert isinstance(partial, dualight.Image) and partial.stats["interrupted"]
    assert np.all(np.isfinite(np.asarray(partial)))


@pytest.mark.usefixtures("handlers")
def test_systemexit_from_sigterm_keeps_its_code() -> None:
    signal.signal(signal.SIGTERM, _raise(SystemExit(3)))
    timer = _signal_soon(signal.SIGTERM)
    with pytest.raises(SystemExit) as info:
        _long_render("path")
    timer.join()
    assert info.value.code == 3
    assert isinstance(info.value.partial_result, dualight.Image)  # type: ignore[attr-defined]


@pytest.mark.usefixtures("handlers")
def test_ctrl_c_still_gives_keyboard_interrupt() -> None:
    """The control: the default SIGINT handler's KeyboardInterrupt is what comes out."""
    signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = _signal_soon(signal.SIGINT)
    with pytest.raises(KeyboardInterrupt) as info:
        _long_render("path")
    timer.join()
    assert isinstance(info.value.partial_result, dualight.Image)  # type: ignore[attr-defined]


class LastCall(Exception):
    pass


def _fails_when_done(done: int, total: int) -> None:
    if total > 0 and done >= total:
        raise LastCall(f"{done} of {total}")


@pytest.mark.parametrize("method", ["path", "light", "bdpt", "pssmlt", "mmlt", "mlt"])
def test_the_progress_callbacks_last_call_can_raise(method: str) -> None:
    scene = scenes.cornell_box(resolution=(16, 16))
    budget = {"mutations_per_pixel": 4} if method in ("pssmlt", "mmlt", "mlt") else {"spp": 4}
    depth = {"max_depth": 5} if method == "mmlt" else {}
    with pytest.raises(LastCall) as info:
        dualight.render(scene, method, progress=_fails_when_done, **budget, **depth)
    partial = info.value.partial_result  # type: ignore[attr-defined]
    assert isinstance(partial, dualight.Image) and np.any(np.asarray(partial) > 0)
    # The control: a callback that does not raise gives the image.
    image = dualight.render(scene, method, progress=lambda d, t: None, **budget, **depth)
    assert np.array_equal(np.asarray(image), np.asarray(partial))


def test_the_radiosity_solvers_callbacks_can_raise_on_their_last_call() -> None:
    scene = scenes.cornell_box(resolution=(16, 16))
    with pytest.raises(LastCall):
        solve(scene, "gauss_seidel", max_edge=200.0, progress=_fails_when_done)
    solver = HierarchicalSolver(scene, epsilon=1e-3)
    with pytest.raises(LastCall):
        solver.step(progress=_fails_when_done)
