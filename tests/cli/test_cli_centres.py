"""``linkage-sym centres``: the table, the JSON, the pictures, and its refusals."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import linkage_sym
from linkage_sym.centres import instant_centres
from linkage_sym.cli import main
from linkage_sym.examples import example_path

ROOT = Path(__file__).resolve().parents[2]
PNG = b"\x89PNG\r\n\x1a\n"


def run(*args):
    return subprocess.run([sys.executable, "-m", "linkage_sym", "centres", *map(str, args)],
                          capture_output=True, text=True, cwd=ROOT)


@pytest.mark.slow
def test_table_json_and_plots(tmp_path):
    out = tmp_path / "c.json"
    p = run(example_path("guide_bar_quick_return"), "--step", 0, "--polygons", "-o", out,
            "--plots", tmp_path / "plots")
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    assert lines[0] == "guide-bar-quick-return: 6 = 4·3/2 instant centres at step 0 (A = 60°)"
    assert any(ln.startswith("  P13  ground-block") and "three-centre lines P12-P23 and P14-P34" in ln
               for ln in lines)
    assert any("P34" in ln and "at infinity" in ln and "slide of joint B_slide" in ln for ln in lines)
    assert any("Coriolis" in ln for ln in lines)
    data = json.loads(out.read_text())
    assert data["step"] == 0 and data["numbering"] == {"ground": 1, "crank": 2, "block": 3,
                                                       "guide_bar": 4}
    assert len(data["instant_centres"]) == 6
    s = data["polygons"]["sliding"][0]
    assert s["joint"] == "B_slide" and abs(np.hypot(*s["coriolis"]) - 2.515) < 1e-3
    files = sorted(x.name for x in (tmp_path / "plots").iterdir())
    assert files == ["guide-bar-quick-return_centres.png", "guide-bar-quick-return_centrodes.png",
                     "guide-bar-quick-return_polygons.png"]
    for f in (tmp_path / "plots").iterdir():
        data = f.read_bytes()
        assert data.startswith(PNG) and len(data) > 20_000


def test_deg_solves_at_that_angle(tmp_path):
    """--deg 40 is the crank-rocker solved at 40 deg: the sweep's step 40 (1 deg apart)."""
    out = tmp_path / "c.json"
    assert main(["centres", str(example_path("crank_rocker")), "--deg", "40", "-o", str(out)]) == 0
    got = json.loads(out.read_text())["instant_centres"]
    scene = linkage_sym.load_example("crank_rocker")
    want = instant_centres(scene, linkage_sym.analyze(scene)).records(40)
    L = scene.characteristic_length()
    assert [r["links"] for r in got] == [r["links"] for r in want]
    for a, b in zip(got, want):
        assert np.hypot(*np.subtract(a["position"], b["position"])) <= 1e-12 * max(
            L, float(np.hypot(*b["position"])))


def test_json_to_standard_output():
    p = run(example_path("fivebar"), "--step", 100, "-o", "-")
    assert p.returncode == 0, p.stderr
    data = json.loads(p.stdout)
    assert sum(r.get("method") == "velocity" for r in data["instant_centres"]) == 5
    assert "from the velocities" in p.stderr


@pytest.mark.slow
def test_no_floating_link_no_centrodes(tmp_path):
    """A lone slider on the ground has one centre (at infinity, normal to the slide) and no
    floating link, so no centrodes to draw."""
    scene = {"name": "lone slider", "links": [{"name": "slider"}],
             "joints": [{"name": "S", "type": "P", "links": ["ground", "slider"], "at": [0, 0],
                         "axis_deg": 30}],
             "drivers": [{"joint": "S", "start": 0, "stop": 0.1, "steps": 3, "speed": 1.0}]}
    path = tmp_path / "lone.json"
    path.write_text(json.dumps(scene))
    p = run(path, "--plots", tmp_path / "plots", "-o", "-")
    assert p.returncode == 0, p.stderr
    assert "no centrodes drawn" in p.stderr
    rec = json.loads(p.stdout)["instant_centres"]
    assert len(rec) == 1 and rec[0]["at_infinity"] is True
    assert np.allclose(rec[0]["direction"], [-0.5, 3**0.5 / 2], rtol=0, atol=1e-15) or np.allclose(
        rec[0]["direction"], [0.5, -(3**0.5) / 2], rtol=0, atol=1e-15)
    assert sorted(x.name for x in (tmp_path / "plots").iterdir()) == ["lone_slider_centres.png"]


@pytest.mark.parametrize("args, message", [
    (["--step", "400"], "--step: 400 is not a step of the sweep (0 to 360)"),
    (["--deg", "nan"], "--deg: nan is not a finite angle"),
])
def test_refusals(args, message):
    p = run(example_path("crank_rocker"), *args)
    assert p.returncode == 2
    assert message in p.stderr


@pytest.mark.slow
def test_deg_needs_one_r_driver():
    p = run(example_path("hydraulic_boom"), "--deg", "10")
    assert p.returncode == 2
    assert "--deg: needs a scene with one R driver" in p.stderr


@pytest.mark.slow
def test_output_path_checked_first(tmp_path):
    p = run(example_path("crank_rocker"), "-o", tmp_path)
    assert p.returncode == 2 and "-o/--output" in p.stderr
