"""The atheris fuzz targets in CI: every stored regression input (each once a crash), then a
short time-boxed run of each target (``DUALIGHT_FUZZ_SECONDS``, default 8 s, cut from 15 s to
keep the suite within its time; ``make fuzz`` runs longer). A target fails on anything but a
clean Python exception, see ``fuzz_*.py``."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

atheris = pytest.importorskip("atheris", reason="atheris is installed by scripts/setup.sh")

HERE = Path(__file__).parent
TARGETS = {
    "scene": HERE / "fuzz_scene.py",
    "loaders": HERE / "fuzz_loaders.py",
    "tasks": HERE / "fuzz_tasks.py",
}
REGRESSIONS = sorted((HERE / "regressions").glob("*/*"))


@pytest.mark.fuzz
@pytest.mark.parametrize("path", REGRESSIONS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_regression_input(path: Path) -> None:
    """Run in a child process: a crash (segfault, abort) must fail this test, not pytest."""
    code = (
        f"import sys; sys.path.insert(0, {str(HERE)!r}); import {TARGETS[path.parent.name].stem} "
        f"as t; t.test_one_input(open({str(path)!r}, 'rb').read())"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=120
    )
    assert result.returncode == 0, result.stderr[-3000:]


@pytest.mark.fuzz
@pytest.mark.parametrize("target", sorted(TARGETS))
def test_fuzz_short(target: str, tmp_path: Path) -> None:
    """A fixed seed (``DUALIGHT_FUZZ_SEED``, default 1), so that CI explores the same inputs
    each time (up to how many fit in the time) and a new finding comes with a code change,
    not at random; ``make fuzz`` explores with fresh seeds."""
    seed = int(os.environ.get("DUALIGHT_FUZZ_SEED", "1"))
    seconds = int(os.environ.get("DUALIGHT_FUZZ_SECONDS", "8"))
    corpus = tmp_path / "corpus"
    corpus.mkdir()
    result = subprocess.run(
        [sys.executable, str(TARGETS[target]), f"-max_total_time={seconds}", f"-seed={seed}",
         "-rss_limit_mb=4096", "-timeout=60", f"-artifact_prefix={tmp_path}/", str(corpus)],
        capture_output=True, text=True, timeout=seconds + 180,
        env={**os.environ, "TMPDIR": str(tmp_path)},  # the targets' temporary files go with it
    )
    runs = re.findall(r"Done (\d+) runs", result.stderr)
    assert result.returncode == 0 and runs, result.stderr[-3000:]
    print(f"fuzz_{target}: {runs[-1]} inputs in {seconds} s, no crash")
