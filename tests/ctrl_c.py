"""Ctrl-C in tests: a SIGINT sent into a running call, and the seconds it took to stop.

Tests that use it also need Python's own SIGINT handler (the ``ctrl_c_raises`` fixture of
conftest.py): a process started in the background by a non-interactive shell inherits SIGINT
as ignored, and then Ctrl-C never arrives."""

from __future__ import annotations

import os
import signal
import threading
import time
from collections.abc import Callable

import pytest


def interrupted(call: Callable[[], object], after: float) -> tuple[KeyboardInterrupt, float]:
    """Runs ``call``, sends SIGINT ``after`` seconds into it, and returns the KeyboardInterrupt
    it raised and the seconds from the signal to it."""
    sent: list[float] = []

    def interrupt() -> None:
        sent.append(time.perf_counter())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(after, interrupt)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt) as caught:
            call()
    finally:
        timer.cancel()
    assert sent, "the call ended before the interrupt was sent: make it longer"
    return caught.value, time.perf_counter() - sent[0]
