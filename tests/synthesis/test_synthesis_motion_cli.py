"""``linkage-sym synthesize motion``: the table, the scenes, the CSV and the pictures."""

import csv
import json
import math

import numpy as np
import pytest

import linkage_sym
from linkage_sym.cli import main

POSES = [[0.0, 0.0, 0.0], [1.0, 0.2, 10.0], [1.8, 0.7, 25.0], [2.3, 1.5, 45.0], [2.5, 2.4, 70.0]]


@pytest.mark.slow  # over 10 s on a loaded machine: the fast lane stays under 2 min
def test_five_poses_write_scenes_through_the_poses(tmp_path, capsys):
    poses = tmp_path / "p.json"
    poses.write_text(json.dumps(POSES))
    out = tmp_path / "out"
    assert main(["synthesize", "motion", "--poses", str(poses), "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "motion generation through 5 poses: 2 Burmester point pairs" in text
    with open(out / "designs.csv", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["design"] for r in rows] == ["design-01", "design-02"]
    assert rows[0]["defect_free"] == "True"
    for name in ("poses.png", "burmester.png"):
        assert (out / name).stat().st_size > 10_000
    # the best scene's own sweep, run by the solver, starts in pose 1 and ends in pose 5
    scene = linkage_sym.load_scene(out / "design-01.json")
    res = linkage_sym.analyze(scene)
    assert (res.status == "ok").all()
    P = res.points["P"].position
    b = math.dist(scene.joint("B").at, scene.joint("C").at)
    assert np.linalg.norm(P[0] - POSES[0][:2]) <= 1e-9 * b
    assert np.linalg.norm(P[-1] - POSES[-1][:2]) <= 1e-9 * b
    turn = float(res.links["coupler"].rotation[-1])
    assert abs(math.remainder(turn - math.radians(70.0), 2 * math.pi)) <= 1e-9


def test_four_poses_and_refusals(tmp_path, capsys):
    poses = tmp_path / "p.json"
    poses.write_text(json.dumps(POSES[:4]))
    assert main(["synthesize", "motion", "--poses", str(poses), "--dyads", "4"]) == 0
    assert "4 dyads sampled on the centre-point curve, 12 four-bars" in capsys.readouterr().out
    poses.write_text(json.dumps(POSES[:3]))
    assert main(["synthesize", "motion", "--poses", str(poses)]) == 2
    assert "--poses: 4 or 5 poses [x, y, angle_deg] are expected, got 3" in capsys.readouterr().err
