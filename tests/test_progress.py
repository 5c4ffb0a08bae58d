"""``progress=True``: the tqdm bar is quiet where it should be and tells the truth.

* In a Jupyter kernel without ipywidgets it warns nothing (``tqdm.auto`` warned ``TqdmWarning:
  IProgress not found`` in every such kernel).
* Its first rate is bounded by the true rate (the bar's clock used to start at the first
  callback, after the work had started: billions of samples per second).
* Written to a pipe or a file (a CI log), a render writes a handful of lines, not one every
  100 ms.
"""

from __future__ import annotations

import io
import re
import subprocess
import sys
import warnings

import pytest
import tqdm.auto
import tqdm.std

import dualight
from dualight import scenes


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def _recording_bar(rates: list[tuple[float, float]]) -> type:
    class Recording(tqdm.std.tqdm):
        def display(self, *args, **kwargs):  # type: ignore[no-untyped-def]
            d = self.format_dict
            if d["n"] > 0 and d["elapsed"] > 0:
                rates.append((d["n"], d["rate"] or (d["n"] - d["initial"]) / d["elapsed"]))
            return super().display(*args, **kwargs)

    return Recording


def test_the_first_rate_is_bounded_by_the_true_rate(monkeypatch: pytest.MonkeyPatch) -> None:
    rates: list[tuple[float, float]] = []
    monkeypatch.setattr(sys, "stderr", _Terminal())  # a live bar: redrawn every 0.1 s
    for module in (tqdm.auto, tqdm.std):
        monkeypatch.setattr(module, "tqdm", _recording_bar(rates))
    scene = scenes.cornell_box(resolution=(64, 64))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        image = dualight.render(scene, "path", spp=256, seed=1, progress=True)
    true_rate = image.stats["samples"] / image.stats["seconds"]
    assert rates, "the bar never showed a rate"
    first = rates[0][1]
    assert first < 3 * true_rate, (
        f"first rate {first:.3g}/s against a true {true_rate:.3g}/s: {rates[:3]}"
    )
    assert max(r for _, r in rates) < 10 * true_rate, rates
    assert rates[-1][0] == image.stats["samples"]


def test_a_kernel_without_ipywidgets_shows_no_warning(tmp_path) -> None:
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    cell = (
        "import warnings\n"
        "warnings.simplefilter('always')\n"
        "import dualight\n"
        "image = dualight.render(dualight.scenes.cornell_box(resolution=(32, 32)), 'path',\n"
        "                        spp=16, progress=True)\n"
        "print('samples', image.stats['samples'])"
    )
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(cell)])
    nbclient.NotebookClient(
        nb, timeout=300, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}
    ).execute()
    text = "".join(o.get("text", "") for o in nb.cells[0].outputs)
    assert "samples 16384" in text
    assert "Warning" not in text, text


def test_a_log_gets_a_handful_of_lines_per_render(tmp_path) -> None:
    script = (
        "import dualight\n"
        "scene = dualight.scenes.cornell_box(resolution=(64, 64))\n"
        "image = dualight.render(scene, 'path', spp=1024, seed=1, progress=True)\n"
        "print(image.stats['seconds'])\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script],
        capture_output=True,
        text=True,
        check=True,
        cwd=tmp_path,
        timeout=600,
    )
    seconds = float(done.stdout.split()[-1])
    lines = [line for line in re.split(r"[\r\n]", done.stderr) if line.strip()]
    assert seconds > 0.5, "the render must last several of the core's 100 ms callbacks"
    assert 1 <= len(lines) <= 4, f"{len(lines)} lines in {seconds:.1f} s: {lines}"
    assert "100%" in lines[-1]
