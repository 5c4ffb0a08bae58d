"""``python -m dualight bench``: it runs, writes its JSON, table and plot, and its errors mean
what they say (the furnace's analytic reference); from a pip install it uses the references
shipped in the package and says in one line each what it cannot do."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

from dualight import bench
from dualight.__main__ import main


def test_bench_writes_results_and_measures_the_furnace(tmp_path: Path) -> None:
    out = tmp_path / "bench"
    code = main(
        [
            "bench",
            "--budgets",
            "0.1,0.2",
            "--scenes",
            "furnace",
            "--methods",
            "path,bdpt,radiosity_hier",
            "--out",
            str(out),
        ]
    )
    assert code == 0
    summary = json.loads((out / "bench.json").read_text())
    runs = summary["scenes"]["furnace"]["runs"]
    assert {r["method"] for r in runs} == {"path", "bdpt", "radiosity_hier"}
    for r in runs:
        assert r["seconds"] > 0 and r["relmse"] >= 0 and r["delta_e2000"] >= 0
    mc = [r for r in runs if r["method"] in ("path", "bdpt")]
    # More time, less error; and small error: the furnace's radiance is known exactly.
    for method in ("path", "bdpt"):
        short, long = sorted((r for r in mc if r["method"] == method), key=lambda r: r["budget"])
        assert long["relmse"] < short["relmse"] < 0.05
    assert summary["equal_time"]["furnace"]["bdpt"] == 1.0
    table = (out / "bench.md").read_text()
    assert "| path |" in table and "| radiosity_hier |" in table
    assert (out / "bench.png").stat().st_size > 1000


def test_bench_rejects_unknown_names(tmp_path: Path) -> None:
    try:
        main(["bench", "--scenes", "nowhere", "--out", str(tmp_path)])
    except SystemExit as exit_:
        assert "nowhere" in str(exit_.code)
    else:
        raise AssertionError("an unknown scene must stop the command")


def test_bench_says_what_an_install_lacks_and_runs_the_rest(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """A pip install without the references, Mitsuba, colour-science or matplotlib: one line
    for each thing it cannot do, exit code 0, no traceback, and the furnace still measured."""
    monkeypatch.setattr(bench, "REFERENCE_DIR", tmp_path / "no-references")
    for module in ("mitsuba", "colour", "matplotlib"):
        monkeypatch.setitem(sys.modules, module, None)  # import fails, as when not installed
    out = tmp_path / "bench"
    argv = ["bench", "--budgets", "0.05", "--scenes", "cornell,rooms,furnace"]
    argv += ["--methods", "path", "--out", str(out), "--cache", str(tmp_path / "cache")]
    assert main(argv) == 0
    said = capsys.readouterr()
    lines = said.out.splitlines()
    assert "Traceback" not in said.out + said.err
    assert [line for line in lines if "Delta E 2000 needs colour-science" in line]
    assert [line for line in lines if "bench.png needs matplotlib" in line]
    assert [line for line in lines if line.startswith("  cornell: reference cornell_64 not in")]
    assert [line for line in lines if line.startswith("  rooms:") and "Mitsuba 3" in line]
    summary = json.loads((out / "bench.json").read_text())
    assert summary["scenes"]["cornell"] == {"skipped": "no reference"}
    assert summary["scenes"]["rooms"] == {"skipped": "no reference"}
    (furnace,) = summary["scenes"]["furnace"]["runs"]
    assert furnace["relmse"] < 0.1 and furnace["delta_e2000"] is None
    assert not (out / "bench.png").exists()


def test_the_references_ship_inside_the_package(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """What the notebooks and ``bench`` load comes from the installed package, not the
    repository: and a scene with mirrors says in one line why radiosity skips it."""
    import dualight

    assert bench.REFERENCE_DIR.parent.parent == Path(dualight.__file__).resolve().parent
    scene = bench.SCENE_SET["cornell"].build()
    ref = bench.load_reference("cornell", "test:cornell_64", scene, tmp_path)
    assert ref is not None and ref.mean.shape == ref.variance.shape == (64, 64, 3)
    assert ref.mean.std() > 0 and (ref.variance > 0).mean() > 0.9
    argv = ["bench", "--budgets", "0.05", "--scenes", "caustics", "--methods", "path,radiosity_gs"]
    assert main([*argv, "--out", str(tmp_path / "bench")]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert [line for line in lines if "radiosity_gs skipped: specular surfaces" in line]
    assert [line for line in lines if line.strip().startswith("path ") and "relMSE" in line]
