"""The notebooks: each pair stays in sync, and each runs top to bottom and shows what it says.

* Pairs: each ``.ipynb`` holds exactly its jupytext ``.py``'s cells and no outputs (so diffs
  stay readable).
* Runs: each notebook is executed in a Jupyter kernel at the tiny budget
  (``DUALIGHT_BUDGET=tiny``, ``MPLBACKEND=Agg``), with its working directory outside the
  repository (so the references and helpers it needs must come with the package). A first
  cell replaces ``plt.show`` by a check of every image of every figure shown (each
  ``imshow``): a blank or constant image, or one with a few levels only (an 8-bit image clipped
  to [0, 1] is black with two levels), stops the notebook with the figure and panel named.
  Every PNG the notebook displays (``dualight.Image`` shows itself) gets the same check, and
  no cell may print a warning. ``make test`` runs them here, not through nbmake.
"""

from __future__ import annotations

import base64
import inspect
import io
from pathlib import Path

import numpy as np
import pytest

jupytext = pytest.importorskip("jupytext")
nbformat = pytest.importorskip("nbformat")

NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"
PAIRS = sorted(p for p in NOTEBOOKS.glob("*.py") if not p.name.startswith(("_", "conftest")))
LEVELS = 8  # an image shown must have more distinct values than this
SPREAD = 0.05  # and span at least this share of the displayed range


def blank_image_problem(pixels: np.ndarray) -> str | None:
    """Why ``pixels`` (an array given to ``imshow``, or a decoded PNG) would show nothing, or
    None. Colour images are shown as imshow shows them: 8-bit as is, floats clipped to [0, 1];
    a single channel is colour-mapped over its own range, so any spread shows."""
    values = np.ma.getdata(pixels)
    mask = np.ma.getmaskarray(pixels)
    values = np.asarray(values, dtype=np.float64)[~mask] if mask.any() else np.asarray(values)
    values = values[np.isfinite(values)].astype(np.float64)
    if values.size == 0:
        return "no finite pixels"
    if np.ndim(pixels) == 3:
        if np.issubdtype(np.asarray(pixels).dtype, np.integer):
            values = values / 255.0
        values = np.clip(values, 0.0, 1.0)
        spread = float(np.ptp(values))
    else:
        spread = 1.0 if np.ptp(values) > 0 else 0.0
    levels = len(np.unique(values))
    if spread < SPREAD or levels <= LEVELS:
        return f"{levels} distinct values spanning {spread:.4f} of the displayed range"
    return None


def _checked_show_cell() -> str:
    """The first cell of every run: ``plt.show`` checks each image of each open figure."""
    return "\n".join(
        [
            "get_ipython().run_line_magic('colors', 'nocolor')  # plain tracebacks",
            "import matplotlib.pyplot as _dl_plt",
            "import numpy as np",
            inspect.getsource(blank_image_problem).replace("LEVELS", str(LEVELS)),
            f"SPREAD = {SPREAD}",
            "",
            "def _dl_checked_show(*args, **kwargs):",
            "    problems = []",
            "    for number in _dl_plt.get_fignums():",
            "        for k, ax in enumerate(_dl_plt.figure(number).axes):",
            "            for image in ax.get_images():",
            "                why = blank_image_problem(image.get_array())",
            "                where = f'figure {number}, panel {k} {ax.get_title()!r}'",
            "                if why:",
            "                    problems.append(f'{where}: {why}')",
            "    _dl_plt.close('all')",
            "    assert not problems, 'blank images shown: ' + '; '.join(problems)",
            "",
            "_dl_plt.show = _dl_checked_show",
        ]
    )


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


def _displayed_pngs(nb) -> list[tuple[int, np.ndarray]]:
    import matplotlib.image

    found = []
    for number, cell in enumerate(nb.cells):
        for output in cell.get("outputs", []):
            data = output.get("data", {}).get("image/png")
            if data:
                png = io.BytesIO(base64.b64decode(data))
                found.append((number, matplotlib.image.imread(png, format="png")[..., :3]))
    return found


@pytest.mark.parametrize("script", PAIRS, ids=lambda p: p.stem)
def test_notebook_runs_and_shows_no_blank_image(
    script: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    monkeypatch.setenv("DUALIGHT_BUDGET", "tiny")
    monkeypatch.setenv("MPLBACKEND", "Agg")
    nb = nbformat.read(script.with_suffix(".ipynb"), as_version=4)
    nb.cells.insert(0, nbformat.v4.new_code_cell(_checked_show_cell()))
    client = nbclient.NotebookClient(
        nb, timeout=900, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}
    )
    try:
        client.execute()
    except nbclient.exceptions.CellExecutionError as err:
        pytest.fail(f"{script.stem} (run in {tmp_path}): {err}", pytrace=False)
    for number, pixels in _displayed_pngs(nb):
        why = blank_image_problem(pixels)
        assert why is None, f"{script.stem}: cell {number} displays a blank image: {why}"
    warned = [
        o["text"]
        for cell in nb.cells
        for o in cell.get("outputs", [])
        if o.get("name") == "stderr" and "Warning" in o.get("text", "")
    ]
    assert not warned, f"{script.stem} warns: {warned}"
