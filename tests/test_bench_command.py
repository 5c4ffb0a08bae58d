"""``python -m dualight bench``: it runs, writes its JSON, table and plot, and its errors mean
what they say (the furnace's analytic reference)."""

from __future__ import annotations

import json
from pathlib import Path

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
