"""``python -m dualight demo`` (``make demo``) at its quick budget: the page has every section,
every image it shows exists, decodes and is not blank (read back by dualight, and in headless
Chromium when the Debian ``chromium`` package is installed), and the reports agree with it.
Each check runs on a deliberately broken copy of the page too, which it must reject."""

from __future__ import annotations

import importlib.util
import json
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

import dualight
from dualight.__main__ import main

SECTIONS = (
    "The Cornell box by path tracing",
    "Radiosity and importance: the Cornell box",
    "Radiosity and importance: a building of four rooms",
    "Importance-driven hierarchical radiosity: four rooms",
    "Duality of estimators: path tracing against light tracing",
    "Metropolis light transport against BDPT: Veach&#x27;s door",
)


def _check_page() -> object:
    path = Path(__file__).resolve().parents[1] / "scripts" / "check_page.py"
    spec = importlib.util.spec_from_file_location("check_page", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def page(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("demo")
    assert main(["demo", "--quick", "--quiet", "--out", str(out)]) == 0
    return out / "index.html"


def _images(page: Path) -> list[str]:
    return re.findall(r'<img src="([^"]+)"', page.read_text())


def _blank_images(page: Path) -> list[str]:
    """Images of the page that are missing, unreadable or constant."""
    bad = []
    for src in _images(page):
        try:
            pixels = np.asarray(dualight.Image.load(page.parent / src))
        except (FileNotFoundError, ValueError, RuntimeError):
            bad.append(src)
            continue
        if np.ptp(pixels) == 0:
            bad.append(src)
    return bad


def test_the_page_has_every_section_and_the_reports_agree(page: Path) -> None:
    text = page.read_text()
    for title in SECTIONS:
        assert f"<h2>{title}</h2>" in text
    report = json.loads((page.parent / "report.json").read_text())
    for key in ("radiosity", "hierarchical", "duality", "mlt_vs_bdpt", "wall_seconds"):
        assert key in report
    for scene in ("cornell", "rooms"):
        r = report["radiosity"][scene]
        np.testing.assert_allclose(r["R_B"], r["I_E"], rtol=1e-6)
        assert r["duality_gap"] < 1e-6
    assert {r["oracle"] for r in report["hierarchical"]["runs"]} == {"importance", "bf"}
    assert set(report["mlt_vs_bdpt"]) == {"BDPT", "MLT"}
    md = (page.parent / "report.md").read_text()
    assert all(title.replace("&#x27;", "'") in md for title in SECTIONS)
    for name in report["files"]:
        assert (page.parent / name).is_file(), name


def test_every_image_on_the_page_loads_and_is_not_blank(page: Path, tmp_path: Path) -> None:
    assert len(_images(page)) >= 15
    assert _blank_images(page) == []
    # Negative control: a copy with one image gone and one painted flat.
    broken = tmp_path / "broken"
    shutil.copytree(page.parent, broken)
    (broken / "door_mlt.png").unlink()
    dualight.Image(np.full((8, 8, 3), 0.5, np.float32)).save(broken / "cornell_path.png")
    assert sorted(_blank_images(broken / "index.html")) == ["cornell_path.png", "door_mlt.png"]


def test_every_image_loads_in_headless_chromium(page: Path, tmp_path: Path) -> None:
    check = _check_page()
    if check.chromium() is None:  # type: ignore[attr-defined]
        pytest.skip("Debian's chromium package is not installed")
    images = check.probe_images(page)  # type: ignore[attr-defined]
    assert len(images) == len(_images(page))
    assert all(im["ok"] and im["width"] > 0 for im in images), images
    broken = tmp_path / "broken"
    shutil.copytree(page.parent, broken)
    (broken / "door_mlt.png").write_bytes(b"not a png")
    failed = [im["src"] for im in check.probe_images(broken / "index.html") if not im["ok"]]  # type: ignore[attr-defined]
    assert failed == ["door_mlt.png"]
