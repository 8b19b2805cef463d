"""``linkage-sym animate``: the files it writes, and bad input refused by its option
(exit 2, nothing written, no traceback) before anything is solved."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from matplotlib import animation as mpl_animation
from PIL import Image

from linkage_sym.cli import main
from linkage_sym.cli import animate as cli_animate
from linkage_sym.examples import example_dict
from linkage_sym.plotting import animation
from tests.support import scenes


def scene_file(tmp_path, d=None, steps=13, name="scene.json"):
    """The crank-rocker with a short sweep (or the scene ``d``) as a file."""
    if d is None:
        d = example_dict("crank_rocker")
        d["drivers"][0]["steps"] = steps
    path = tmp_path / name
    path.write_text(json.dumps(d))
    return str(path)


def non_grashof_file(tmp_path):
    """A four-bar whose crank cannot turn fully (0.03 + 0.06 > 0.05 + 0.035): steps 5 to 7
    of 13 (150 to 210 degrees) are unassemblable."""
    d, _ = scenes.fourbar(0.03, 0.05, 0.035, 0.06, steps=13, name="non-Grashof")
    return scene_file(tmp_path, d, name="non_grashof.json")


def files(path):
    return sorted(p.name for p in path.iterdir())


def test_the_layer_names_are_the_librarys():
    assert cli_animate.LAYERS == animation.LAYERS


def test_a_gif_with_the_frames_asked_for(tmp_path, capsys):
    scene = scene_file(tmp_path)
    out = tmp_path / "out" / "motion.gif"
    assert main(["animate", scene, "-o", str(out), "--frames", "3", "--fps", "5",
                 "--layers", "velocity,transmission"]) == 0
    text = capsys.readouterr().out
    assert f"wrote {out}: 3 frames of steps 0 to 12 of 'crank-rocker' at 5 frames per second; " \
           "layers velocity, transmission" in text
    with Image.open(out) as gif:
        assert gif.n_frames == 3 and abs(gif.info["duration"] - 200) <= 10
    assert files(out.parent) == ["motion.gif"]


@pytest.mark.slow  # 13 frames (tests/plotting/test_animation.py checks each frame's mark)
def test_an_unassemblable_sweep_is_animated_and_its_frames_counted(tmp_path, capsys):
    out = tmp_path / "motion.gif"
    assert main(["animate", non_grashof_file(tmp_path), "-o", str(out), "--frames", "13",
                 "--layers", "velocity"]) == 0  # every step
    assert "frames by status: 10 ok, 3 unassemblable" in capsys.readouterr().out
    with Image.open(out) as gif:
        assert gif.n_frames == 13  # no frame skipped


def test_html_is_one_self_contained_file(tmp_path):
    out = tmp_path / "motion.html"
    assert main(["animate", scene_file(tmp_path), "-o", str(out), "--frames", "2",
                 "--method", "global"]) == 0
    html = out.read_text(encoding="utf-8")
    assert "http://" not in html and "https://" not in html
    assert html.count("data:image/png;base64,") == 2


def test_kinematic_layers_add_the_kinematics_the_scene_lacks(tmp_path):
    d = example_dict("crank_rocker")
    d["drivers"][0]["steps"] = 7
    d["outputs"] = ["driving"]
    d["effects"] = {"inertia": False, "gravity": None, "loads": True}  # stages: position, forces
    out = tmp_path / "m.gif"
    assert main(["animate", scene_file(tmp_path, d), "-o", str(out), "--frames", "2",
                 "--layers", "velocity,acceleration,centres,forces"]) == 0


@pytest.mark.parametrize("args, message", [
    (["-o", "OUT.png"], "-o/--output: 'OUT.png': an animation is written as .gif, .mp4 or "
                        ".html, not '.png'"),
    (["-o", "OUT"], "-o/--output: 'OUT': an animation is written as .gif, .mp4 or .html, not "
                    "a name without a suffix"),
    (["-o", "-"], "-o/--output: an animation is a file"),
    (["-o", "OUT.gif", "--frames", "14"], "--frames: from 1 to the sweep's 13 steps"),
    (["-o", "OUT.gif", "--frames", "0"], "--frames: from 1 to the sweep's 13 steps"),
    (["-o", "OUT.gif", "--fps", "0"], "--fps: a positive number of frames per second"),
    (["-o", "OUT.gif", "--fps", "nan"], "--fps: a positive number of frames per second"),
    (["-o", "OUT.gif", "--layers", "speed"], "--layers: unknown layer 'speed'; the layers: "
                                             "velocity, acceleration, forces, centres"),
    (["-o", "OUT.gif", "--layers", "forces,forces"], "--layers: 'forces' is given twice"),
    (["-o", "OUT.gif", "--layers", "velocity,"], "--layers: an empty name"),
])
def test_bad_options_are_refused_by_name_and_nothing_is_written(tmp_path, capsys, args,
                                                                 message):
    scene = scene_file(tmp_path)
    work = tmp_path / "work"
    work.mkdir()
    args = [a.replace("OUT", str(work / "motion")) for a in args]
    message = message.replace("OUT", str(work / "motion"))
    assert main(["animate", scene, *args]) == 2
    err = capsys.readouterr().err
    assert f"linkage-sym animate: {message}" in err, err
    assert files(work) == []


def test_forces_of_a_scene_without_forces_are_refused_after_solving(tmp_path, capsys):
    d = example_dict("crank_rocker")
    d["drivers"][0]["steps"] = 7
    d["outputs"] = ["kinematics"]
    out = tmp_path / "out"
    out.mkdir()
    assert main(["animate", scene_file(tmp_path, d), "-o", str(out / "m.gif"),
                 "--layers", "velocity,forces"]) == 2
    err = capsys.readouterr().err
    assert "linkage-sym animate: --layers forces: the analysis has no forces" in err, err
    assert files(out) == []


def test_mp4_without_ffmpeg_names_the_option_and_the_other_files(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(mpl_animation.writers, "is_available", lambda name: False)
    assert main(["animate", scene_file(tmp_path), "-o", str(tmp_path / "m.mp4")]) == 2
    err = capsys.readouterr().err
    assert "-o/--output: an MP4 file is written by ffmpeg, which is not found" in err
    assert "a .gif or .html file needs nothing more" in err
    assert files(tmp_path) == ["scene.json"]


@pytest.mark.skipif(not mpl_animation.writers.is_available("ffmpeg"),
                    reason="ffmpeg is not installed (its absence is tested above)")
def test_mp4_where_ffmpeg_is_found(tmp_path):
    out = tmp_path / "m.mp4"
    assert main(["animate", scene_file(tmp_path), "-o", str(out), "--frames", "2"]) == 0
    assert out.read_bytes()[4:8] == b"ftyp"


@pytest.mark.slow
def test_bad_input_ends_without_a_traceback(tmp_path):
    p = subprocess.run([sys.executable, "-m", "linkage_sym", "animate", scene_file(tmp_path),
                        "-o", str(tmp_path / "m.gif"), "--frames", "99", "--fps", "-2"],
                       capture_output=True, text=True)
    assert p.returncode == 2
    assert "Traceback" not in p.stderr
    assert "--fps: a positive number" in p.stderr and "--frames: from 1" in p.stderr  # both
    assert files(tmp_path) == ["scene.json"]
