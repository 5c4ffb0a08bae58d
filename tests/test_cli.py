"""``python -m dualight`` (the ``dualight`` script): ``--version``, help that shows every
option's default, and ``render`` of a built-in scene, a Mitsuba XML file or an OBJ file, with
clear errors for an unknown scene, a missing file and a bad resolution."""

from __future__ import annotations

import argparse
import re
from pathlib import Path

import numpy as np
import pytest

import dualight
from dualight import scenes
from dualight.__main__ import SCENES, main
from dualight._cli import resolution

SMALL = ["--spp", "1", "--resolution", "8x6", "-q"]


def _help(capsys: pytest.CaptureFixture[str], *argv: str) -> str:
    with pytest.raises(SystemExit) as exit_info:
        main([*argv, "--help"])
    assert exit_info.value.code == 0
    return capsys.readouterr().out


def _entries(text: str) -> dict[str, str]:
    """The options and positionals of an argparse help text: name -> help (joined lines)."""
    entries: dict[str, str] = {}
    name = None
    in_list = False
    for line in text.splitlines():
        if line.endswith(":") and not line.startswith(" "):
            in_list, name = line in ("options:", "positional arguments:"), None
        elif in_list and re.match(r"^  \S", line):
            name, _, rest = line.strip().partition("  ")
            entries[name] = rest.strip()
        elif in_list and name is not None and line.startswith("   "):
            entries[name] = (entries[name] + " " + line.strip()).strip()
    return entries


def test_version(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(["--version"])
    assert exit_info.value.code == 0
    assert capsys.readouterr().out == f"dualight {dualight.__version__}\n"


def test_every_option_has_help_showing_its_default(capsys: pytest.CaptureFixture[str]) -> None:
    top = _entries(_help(capsys))
    assert set(top) >= {"-h, --help", "--version", "{render,demo,bench}"}
    assert all(top.values()), top
    entries = {}
    for command, least in (("render", 16), ("demo", 8), ("bench", 7)):
        entries[command] = _entries(_help(capsys, command))
        assert len(entries[command]) >= least, entries[command]
        for name, text in entries[command].items():
            if name != "-h, --help":
                assert "default" in text, f"{command} {name}: {text!r}"
    assert "default: 64" in entries["render"]["--spp SPP"]
    assert "(default: out.exr)" in entries["render"]["-o OUTPUT, --output OUTPUT"]
    assert "default: 256x256" in entries["demo"]["--resolution RESOLUTION"]


@pytest.mark.parametrize("how", ["positional", "--scene"])
def test_render_a_builtin_scene(tmp_path: Path, how: str) -> None:
    out = tmp_path / "a.exr"
    scene = ["furnace"] if how == "positional" else ["--scene", "furnace"]
    assert main(["render", *scene, *SMALL, "-o", str(out)]) == 0
    image = dualight.Image.load(out)
    assert image.shape == (6, 8, 3) and image.stats["scene"] == "furnace"
    assert image.stats["method"] == "path" and image.stats["spp"] == 1


@pytest.mark.parametrize("name", ["veach_mis", "veach_bidir", "door_glossy"])
def test_render_veachs_scenes_with_one_strategy(tmp_path: Path, name: str) -> None:
    out = tmp_path / "a.exr"
    assert main(["render", name, *SMALL, "--strategies", "light", "-o", str(out)]) == 0
    image = dualight.Image.load(out)
    assert image.stats["scene"] == name and image.stats["strategies"] == "light"


def test_render_a_mitsuba_file_with_its_settings(tmp_path: Path) -> None:
    xml = dualight.save_mitsuba_xml(
        scenes.cornell_box(resolution=(12, 8)), tmp_path / "cbox.xml", spp=3, max_depth=4
    )
    out = tmp_path / "a.exr"
    assert main(["render", str(xml), "-q", "-o", str(out)]) == 0
    stats = dualight.Image.load(out).stats
    assert (stats["method"], stats["spp"], stats["max_depth"]) == ("path", 3, 4)
    assert dualight.Image.load(out).shape == (8, 12, 3)
    # the options given win over the file's
    args = ["render", str(xml), "--method", "bdpt", "--spp", "2", "--resolution", "6x4", "-q"]
    assert main([*args, "-o", str(out)]) == 0
    image = dualight.Image.load(out)
    assert (image.stats["method"], image.stats["spp"], image.stats["max_depth"]) == ("bdpt", 2, 4)
    assert image.shape == (4, 6, 3)


def test_render_an_obj_file_gets_a_camera_framing_it(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "lamp.mtl").write_text("newmtl lamp\nKd 0 0 0\nKe 4 4 4\n")
    (tmp_path / "lamp.obj").write_text(
        "mtllib lamp.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nusemtl lamp\nf 1 2 3 4\n"
    )
    out = tmp_path / "a.exr"
    assert main(["render", str(tmp_path / "lamp.obj"), *SMALL, "-o", str(out)]) == 0
    assert "lamp.obj has no camera: looking from (0, 0, " in capsys.readouterr().err
    pixels = np.asarray(dualight.Image.load(out))
    # the lamp faces +z, towards the camera, and fills the middle of the view
    assert pixels[3, 4].tolist() == pytest.approx([4, 4, 4])
    # from behind, the one-sided lamp is not seen (and warns that it faces nothing)
    behind = ["--look-from", "0,0,-5", "--look-at", "0,0,0"]
    with pytest.warns(UserWarning, match="faces nothing"):
        assert main(["render", str(tmp_path / "lamp.obj"), *SMALL, *behind, "-o", str(out)]) == 0
    assert np.asarray(dualight.Image.load(out)).max() == 0.0


def test_render_errors_name_the_problem(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = ["-o", str(tmp_path / "a.exr")]
    assert main(["render", "cornel", *SMALL, *out]) == 2
    err = capsys.readouterr().err
    assert "unknown scene 'cornel'" in err and ", ".join(sorted(SCENES)) in err
    assert main(["render", str(tmp_path / "gone.xml"), *SMALL, *out]) == 2
    assert "no such scene file" in capsys.readouterr().err
    (tmp_path / "a.ply").write_text("ply\n")
    assert main(["render", str(tmp_path / "a.ply"), *SMALL, *out]) == 2
    assert "unknown scene file type" in capsys.readouterr().err
    assert main(["render", "furnace", "--scene", "door", *SMALL, *out]) == 2
    assert "two scenes given" in capsys.readouterr().err


@pytest.mark.parametrize("text", ["0x5", "-3x4", "abc", "5x", "4x0", "2.5x3"])
def test_resolution_rejects_bad_sizes(text: str, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(argparse.ArgumentTypeError, match="positive whole pixels"):
        resolution(text)
    with pytest.raises(SystemExit) as exit_info:
        main(["render", "--resolution", text])
    assert exit_info.value.code == 2
    assert "resolution must be WIDTHxHEIGHT" in capsys.readouterr().err
    assert resolution(" 320X240 ") == (320, 240)
