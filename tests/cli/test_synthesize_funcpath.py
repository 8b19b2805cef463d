"""``linkage-sym synthesize function`` and ``synthesize path``: what they write, and refusals
naming their options (exit status 2)."""

import csv
import json

import numpy as np
import pytest

import linkage_sym
from linkage_sym.cli import main
from tests.support.funcpath_reference import coupler_points


def test_function_writes_scene_plot_and_error(tmp_path, capsys):
    out, png, err = tmp_path / "f.json", tmp_path / "e.png", tmp_path / "e.csv"
    assert main(["synthesize", "function", "--function", "log10(x)", "--x-range", "1,10",
                 "--phi-range", "30,120", "--psi-range", "240,330", "-o", str(out),
                 "--plot", str(png), "--error-csv", str(err)]) == 0
    text = capsys.readouterr().out
    assert "3 precision points (exact)" in text and "structural error (solver" in text
    linkage_sym.load_scene(out)
    assert png.stat().st_size > 0
    with err.open() as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["x", "phi_deg", "error_deg"] and len(rows) == 362


def test_function_from_a_table(tmp_path, capsys):
    tab = tmp_path / "t.csv"
    tab.write_text("x,y\n" + "".join(f"{x},{x * x}\n" for x in np.linspace(0, 1, 21)))
    assert main(["synthesize", "function", "--table", str(tab), "--phi-range", "60,150",
                 "--psi-range", "100,40", "--precision-points", "5"]) == 0
    assert "5 precision points (least squares)" in capsys.readouterr().out


def test_path_writes_designs_table_and_plot(tmp_path, capsys):
    pts = tmp_path / "p.json"
    T = [[0.0, 0.0], [1.0, 0.3], [2.0, 0.2]]
    pts.write_text(json.dumps(T))
    folder, table, png = tmp_path / "out", tmp_path / "t.csv", tmp_path / "c.png"
    assert main(["synthesize", "path", "--points", str(pts), "--keep", "2", "-o", str(folder),
                 "--csv", str(table), "--plot", str(png)]) == 0
    assert "exact (three points)" in capsys.readouterr().out
    with table.open() as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 2 and rows[0]["defects"] == "none"
    for k, row in enumerate(rows):
        scene = json.loads((folder / f"design-{k + 1:02d}.json").read_text())
        drv = scene["drivers"][0]
        q = np.radians([drv["start_deg"], drv["stop_deg"]])
        P = coupler_points(scene, q)
        assert np.hypot(*(P - np.array(T)[[0, 2]]).T).max() <= 1e-9
    assert png.stat().st_size > 0


@pytest.mark.slow  # 3-5 s: the fast lane stays under two minutes
def test_path_slider_crank_scenes_sweep_through_the_targets(tmp_path, capsys):
    from tests.support.slider_reference import coupler_points as slider_points
    from tests.support.slider_reference import random_slider_crank

    known = random_slider_crank(np.random.default_rng(3))
    th = np.radians(known["drivers"][0]["start_deg"] + np.array([0.0, 60.0, 130.0, 190.0]))
    T = slider_points(known, th)
    pts = tmp_path / "p.json"
    pts.write_text(json.dumps(T.tolist()))
    folder, table, png = tmp_path / "out", tmp_path / "t.csv", tmp_path / "c.png"
    assert main(["synthesize", "path", "--points", str(pts), "--type", "slider-crank", "--keep",
                 "2", "--starts", "1000", "-o", str(folder), "--csv", str(table), "--plot",
                 str(png)]) == 0
    assert "slider-crank path generation through 4 points, exact (optimisation)" in \
        capsys.readouterr().out
    with table.open() as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 2 and all(r["defects"] == "none" and r["exact"] == "True" for r in rows)
    for k, row in enumerate(rows):
        scene = linkage_sym.load_scene(folder / f"design-{k + 1:02d}.json")
        res = linkage_sym.analyze(scene)  # the scene's own sweep, first target to last
        assert (res.status == "ok").all()
        P = res.points["P"].position
        b = float(np.hypot(*np.subtract(scene.joint("C").at, scene.joint("B").at)))
        assert np.hypot(*(P[[0, -1]] - T[[0, -1]]).T).max() <= 1e-9 * b
        assert row["grashof"] in ("slider-crank", "slider-rocker")
    assert png.stat().st_size > 0


@pytest.mark.parametrize("args,option", [
    (["function", "--function", "os.system(1)", "--x-range", "0,1", "--phi-range", "0,90",
      "--psi-range", "90,180"], "--function"),
    (["function", "--function", "x", "--phi-range", "0,90", "--psi-range", "90,180"], "--x-range"),
    (["path", "--curve", "missing.csv"], "--curve"),
])
def test_refusals_name_the_option(args, option, capsys):
    assert main(["synthesize", *args]) == 2
    assert option in capsys.readouterr().err
