"""The notebooks' pairs stay in sync: each ``.ipynb`` holds exactly its jupytext ``.py``'s cells
and no outputs (so diffs stay readable). Running them is nbmake's job (``make test`` passes
``--nbmake``; notebooks/conftest.py sets the tiny budget)."""

from __future__ import annotations

from pathlib import Path

import pytest

jupytext = pytest.importorskip("jupytext")
nbformat = pytest.importorskip("nbformat")

NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"
PAIRS = sorted(p for p in NOTEBOOKS.glob("*.py") if not p.name.startswith(("_", "conftest")))


def test_every_notebook_is_paired() -> None:
    assert len(PAIRS) >= 5
    for script in PAIRS:
        assert script.with_suffix(".ipynb").exists(), f"{script.name} has no .ipynb"
    for notebook in NOTEBOOKS.glob("*.ipynb"):
        assert notebook.with_suffix(".py").exists(), f"{notebook.name} has no .py"


@pytest.mark.parametrize("script", PAIRS, ids=lambda p: p.stem)
def test_notebook_matches_its_script_and_has_no_outputs(script: Path) -> None:
    from_script = jupytext.read(script)
    stored = nbformat.read(script.with_suffix(".ipynb"), as_version=4)
    cells = [(c.cell_type, c.source) for c in from_script.cells]
    assert [(c.cell_type, c.source) for c in stored.cells] == cells, (
        f"{script.stem}.ipynb is out of sync: run jupytext --sync notebooks/{script.name}"
    )
    for cell in stored.cells:
        if cell.cell_type == "code":
            assert not cell.outputs and cell.execution_count is None, "clear the outputs"
