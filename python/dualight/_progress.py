"""The tqdm bar behind ``progress=True`` (``dualight.render``, ``dualight.radiosity.solve``).

The core calls ``progress(done, total)`` about every 100 ms. The bar

* picks its class itself: the widget bar (``tqdm.notebook``) in a Jupyter kernel that has
  ipywidgets, the text bar otherwise. ``tqdm.auto`` would warn (``TqdmWarning: IProgress not
  found``) in every kernel without ipywidgets;
* starts its clock when the work starts (this object's creation), not when the bar is drawn at
  the first callback, and a new phase's clock at the previous phase's last callback: otherwise
  the first rate is ``done`` over a few microseconds (billions of samples per second);
* advances by ``update`` (throttled by ``mininterval``), never by ``refresh`` on every call;
* writes to a terminal or a notebook at tqdm's usual pace, and elsewhere (a CI log, ``make demo
  > log``) at most every ``LOG_INTERVAL`` seconds: a short render logs two lines, start and end.
"""

from __future__ import annotations

import importlib.util
import sys
import time
from typing import Any

LOG_INTERVAL = 30.0  # seconds between lines when stderr is neither a terminal nor a notebook
LIVE_INTERVAL = 0.1  # tqdm's default


def _in_kernel() -> bool:
    """Whether this process is a Jupyter kernel (its output is shown live, not logged)."""
    return "ipykernel.zmqshell" in sys.modules


def bar_class() -> Any:
    """The tqdm class for this process: the widget bar in a kernel with ipywidgets, else text."""
    if _in_kernel() and importlib.util.find_spec("ipywidgets") is not None:
        from tqdm.notebook import tqdm as notebook_bar

        return notebook_bar
    from tqdm.std import tqdm as text_bar

    return text_bar


def _interval() -> float:
    """How often the bar may redraw: live output redraws often, a log file rarely."""
    stream = sys.stderr
    live = _in_kernel() or bool(getattr(stream, "isatty", lambda: False)())
    return LIVE_INTERVAL if live else LOG_INTERVAL


class TqdmProgress:
    """Adapts the core's ``(done, total)`` callback to a tqdm bar, drawn on first use (when the
    total is known) and reset when the total changes (a new phase)."""

    def __init__(self, description: str) -> None:
        self._description = description
        self._bar: Any = None
        self._last_call = time.time()  # the work starts now: the bar's clock starts here

    def __call__(self, done: int, total: int) -> None:
        now = time.time()
        if self._bar is None:
            self._bar = bar_class()(
                total=total or None,
                desc=self._description,
                unit="spl",
                unit_scale=True,
                mininterval=_interval(),
                miniters=1,
            )
            self._restart_clock(self._last_call)
        elif total and total != self._bar.total:
            # A new phase (the MLT methods: direct light, then the chains' mutations); it began
            # about when the previous phase last reported.
            self._bar.reset(total=total)
            self._restart_clock(self._last_call)
        self._bar.update(done - self._bar.n)
        self._last_call = now

    def _restart_clock(self, started: float) -> None:
        self._bar.start_t = self._bar.last_print_t = started

    def close(self) -> None:
        """Draw the final state and release the bar."""
        if self._bar is not None:
            self._bar.close()
