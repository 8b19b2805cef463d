"""``linkage-sym sweep``: the table it writes (CSV, Parquet, standard output) is the API's,
``--list``, and every refusal is one line naming the option (exit 2, no traceback)."""

from __future__ import annotations

import re
import sys

import numpy as np
import pytest

import linkage_sym
from linkage_sym.cli import main
from linkage_sym.design.table import read_table
from linkage_sym.examples import example_path

CRANK = str(example_path("crank_rocker"))


def test_list_prints_names_values_and_meanings(capsys):
    assert main(["sweep", CRANK, "--list"]) == 0
    out = capsys.readouterr().out
    assert "l_AB         0.024" in out and "distance from joint A to B on link crank" in out
    assert "m_coupler" in out and "theta0" not in out


def test_csv_and_parquet_tables_are_the_api_s(tmp_path, capsys):
    res = linkage_sym.sweep(linkage_sym.load_example("crank_rocker"),
                            {"l_AB": np.linspace(0.02, 0.03, 3), "l_BC": np.linspace(0.06, 0.07, 2)},
                            ["assemblable", "grashof", "K", "peak_driving"])
    args = ["sweep", CRANK, "--vary", "l_AB=0.02:0.03:3", "--vary", "l_BC=0.06:0.07:2",
            "--metrics", "assemblable,grashof,K,peak_driving"]
    assert main(args + ["-o", str(tmp_path / "t.csv")]) == 0
    assert main(args + ["-o", str(tmp_path / "new" / "folder" / "t.parquet")]) == 0  # created
    (tmp_path / "new" / "folder" / "t.parquet").rename(tmp_path / "t.parquet")
    out = capsys.readouterr().out
    assert "sweep of 'crank-rocker': 6 design(s) (grid l_AB 3 x l_BC 2)" in out
    for f in ("t.csv", "t.parquet"):
        t = read_table(tmp_path / f)
        assert list(t) == list(res.columns)
        for c in res.columns:
            if res[c].dtype.kind == "U":
                assert t[c].tolist() == res[c].tolist()
            else:
                np.testing.assert_array_equal(np.asarray(t[c], float), res[c])
    assert main(args + ["-o", "-"]) == 0
    assert capsys.readouterr().out == res.to_csv()


def test_samples_and_monte_carlo(tmp_path, capsys):
    f = tmp_path / "s.csv"
    f.write_text("l_AB,m_coupler\n0.02,0.5\n0.025,0.6\n")
    assert main(["sweep", CRANK, "--samples", str(f), "--metrics", "rms_driving",
                 "-o", str(tmp_path / "a.csv")]) == 0
    t = read_table(tmp_path / "a.csv")
    assert t["m_coupler"].tolist() == [0.5, 0.6] and np.isfinite(t["rms_driving_A"]).all()
    args = ["sweep", CRANK, "--monte-carlo", "5", "--tolerance", "l_AB=5e-5", "--random-state", "2"]
    assert main(args + ["-o", str(tmp_path / "m1.csv")]) == 0
    assert main(args + ["-o", str(tmp_path / "m2.csv")]) == 0
    assert (tmp_path / "m1.csv").read_text() == (tmp_path / "m2.csv").read_text()


@pytest.mark.parametrize("args, message", [
    (["--vary", "l_XY=1:2:3"], "--vary: unknown parameter 'l_XY'; the scene's parameters are x_A"),
    (["--vary", "l_AB=1:2"], "--vary: 'l_AB=1:2': NAME=LO:HI:N"),
    (["--vary", "l_AB=0.02:0.03:2", "-o", "t.txt"], "-o/--output: 't.txt': a .csv or .parquet"),
    (["--tolerance", "l_AB=1e-5"], "--tolerance: used only with --monte-carlo N"),
    (["--monte-carlo", "3"], "--tolerance: a Monte Carlo sweep needs at least one NAME=SIGMA"),
    (["--vary", "l_AB=0.02:0.03:2", "--metrics", "K,speed"], "--metrics: unknown metric 'speed'"),
    (["--vary", "l_AB=0.02:0.03:2", "--workers", "0"], "--workers: at least 1 process"),
    (["--samples", "missing.csv"], "--samples: 'missing.csv'"),
    (["--vary", "l_AB=0.02:0.03:2", "--scene-rows", "1"],
     "--scene-rows: used only with --write-scenes DIR"),
    (["--vary", "l_AB=0.02:0.03:2", "--write-scenes", "s", "--scene-rows", "0,2"],
     "--scene-rows: no design 2: the designs are 0 to 1"),
    (["--vary", "l_AB=0.02:0.03:2", "--write-scenes", "s", "--scene-rows", "0,x"],
     "--scene-rows: 'x': design numbers (0,5,17) or ranges"),
    ([], "--vary: give exactly one of --vary, --samples or --monte-carlo"),
    # issue 27: a repeated --tolerance, and names of options whose metric is not asked for
    (["--monte-carlo", "3", "--tolerance", "l_AB=1e-5", "--tolerance", "l_AB=2e-5"],
     "--tolerance: 'l_AB' given twice"),
    (["--vary", "l_AB=0.02:0.03:2", "--metrics", "grashof", "--output-link", "rockr"],
     "--output-link: unknown link 'rockr'; the moving links are crank, coupler, rocker"),
    (["--vary", "l_AB=0.02:0.03:2", "--output-link", "rockr"],  # default metrics
     "--output-link: unknown link 'rockr'; the moving links are crank, coupler, rocker"),
    (["--vary", "l_AB=0.02:0.03:2", "--metrics", "K", "--trace", "P", "--trace", "Q"],
     "--trace: unknown traced point 'Q'; the scene's are P"),
    (["--vary", "l_AB=-0.02:0:3", "--vary", "m_crank=0.1,0.2"],
     "--vary: no value of l_AB gives a valid design: l_AB: joints[1].at: a length must be > 0"),
    (["--monte-carlo", "20", "--tolerance", "l_AB=1e308"],
     "--tolerance: none of the 20 designs is valid; design 0: l_AB: joints[1].at: must be "
     "within +-1e+30"),
])
def test_refusals_name_the_option(capsys, args, message, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["sweep", CRANK] + args) == 2
    err = capsys.readouterr().err
    assert err.startswith("linkage-sym sweep: " + message), err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1


def test_newton_groups_say_one_design_at_a_time(capsys, tmp_path):
    assert main(["sweep", str(example_path("sixbar_class3")), "--vary", "l_AB=0.05,0.052",
                 "--metrics", "assemblable,swing", "-o", str(tmp_path / "t.csv")]) == 0
    out = capsys.readouterr().out
    assert ("one design at a time: the triad (class III) of 'sixbar-class3' has no closed "
            "form") in out, out
    assert read_table(tmp_path / "t.csv")["assemblable"].tolist() == [1.0, 1.0]


def test_missing_extras_are_refused(capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "dask.distributed", None)
    assert main(["sweep", CRANK, "--vary", "l_AB=0.02:0.03:2", "--dask", "local"]) == 2
    assert "pip install 'linkage_sym[sweep]'" in capsys.readouterr().err
    monkeypatch.setitem(sys.modules, "pyarrow", None)
    assert main(["sweep", CRANK, "--vary", "l_AB=0.02:0.03:2", "-o", "x.parquet"]) == 2
    assert "-o/--output: a Parquet file needs pyarrow" in capsys.readouterr().err


def test_write_scenes_of_some_designs(tmp_path, capsys):
    args = ["sweep", CRANK, "--vary", "l_AB=0.02:0.03:3", "--vary", "l_BC=0.06,0.2",
            "--metrics", "K", "--write-scenes", str(tmp_path / "s")]
    assert main(args + ["--scene-rows", "5,0,3,0"]) == 0
    out = capsys.readouterr().out
    # l_BC = 0.2: no assembly; the rows named once each
    assert "wrote 1 design scene(s)" in out and "no scene for design(s) 3, 5: not assembled" in out
    assert [p.name for p in (tmp_path / "s").iterdir()] == ["design_0.json"]
    assert main(args + ["--scene-rows", ":3"]) == 0
    assert sorted(p.name for p in (tmp_path / "s").iterdir()) == ["design_0.json", "design_2.json"]
    # why K has no value, counted
    assert ("K_note: not assembled at the scene's driver values 3" in capsys.readouterr().out)


@pytest.mark.slow
def test_plots_a_map_per_metric_of_a_grid_and_histograms(tmp_path, capsys):
    assert main(["sweep", CRANK, "--vary", "l_AB=0.015:0.045:6", "--vary", "l_BC=0.05:0.09:5",
                 "--metrics", "grashof,K", "--plots", str(tmp_path / "g")]) == 0
    assert sorted(p.name for p in (tmp_path / "g").iterdir()) == ["crank-rocker_sweep_K.png"]
    assert main(["sweep", CRANK, "--monte-carlo", "12", "--tolerance", "l_AB=5e-5",
                 "--metrics", "K,peak_driving", "--plots", str(tmp_path / "h")]) == 0
    names = sorted(p.name for p in (tmp_path / "h").iterdir())
    assert names == ["crank-rocker_sweep_K.png", "crank-rocker_sweep_peak_driving_A.png"]
    assert all((tmp_path / "h" / n).read_bytes()[:4] == b"\x89PNG" for n in names)


def test_summary_gives_units_and_no_empty_K_note(capsys):
    """Efforts in N·m (an R driver), reactions and the shaking force in N, the shaking moment
    in N·m, angles in degrees; a K_note column without a note says K has a value everywhere
    instead of printing an empty line."""
    assert main(["sweep", CRANK, "--vary", "l_AB=0.02:0.03:2", "--metrics",
                 "K,swing,peak_driving,rms_driving,peak_reaction,rms_shaking_force,"
                 "rms_shaking_moment"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert "  K_note: none: K has a value for every design" in lines
    assert not any(ln.rstrip().endswith(":") for ln in lines)
    units = {"peak_driving_A": " N·m", "rms_driving_A": " N·m", "peak_reaction_D": " N",
             "rms_shaking_force": " N", "rms_shaking_moment": " N·m", "swing_deg": "°", "K": ""}
    for col, unit in units.items():
        (line,) = [ln for ln in lines if ln.startswith(f"  {col}: ")]
        num = r"[0-9.e+-]+"
        assert re.fullmatch(rf"  {col}: {num}{unit} \(design \d\) \.\. {num}{unit} \(design \d\), "
                            rf"mean {num}{unit}", line), line
    from linkage_sym.cli.sweep import metric_unit

    assert metric_unit("peak_driving_P", linkage_sym.load_example("hydraulic_boom")) == "N"


@pytest.mark.slow
def test_parallel_note_on_a_small_sweep(capsys):
    """--workers 2 on two designs prints the note naming the rule; the same sweep without the
    option does not; a sweep above the rule's size does not either (the rule only: no
    timing here)."""
    args = ["sweep", CRANK, "--vary", "l_AB=0.02:0.03:2", "--metrics", "assemblable"]
    assert main(args + ["--workers", "2"]) == 0
    out = capsys.readouterr().out
    assert ("note: 2 designs x 361 steps = 722 design-steps, fewer than 5e6: starting 2 worker "
            "processes costs more than it saves, and one process (without --workers 2) is "
            "faster at this size") in out
    assert main(args) == 0
    assert "note:" not in capsys.readouterr().out
    from linkage_sym.cli.sweep import PARALLEL_MIN_ENTRIES, parallel_note

    assert "LocalCluster" in parallel_note(2, 361, 2, "local")
    big = -(-PARALLEL_MIN_ENTRIES["dask"] // 361)
    assert parallel_note(big, 361, 2, "local") == parallel_note(big, 361, 2, None) == ""
    assert parallel_note(2, 361, 1, None) == parallel_note(2, 361, 2, "tcp://host:8786") == ""


def test_invalid_designs_are_counted_and_get_no_scene(tmp_path, capsys):
    """Issue 27: designs the scene's rules refuse were solved with exit 0 and their scenes
    written; they are now counted by the rule they break, and get no scene."""
    assert main(["sweep", CRANK, "--vary", "m_coupler=-1,0.5", "--vary", "T_1=1e308,-0.5",
                 "--metrics", "K", "--write-scenes", str(tmp_path / "s"),
                 "-o", str(tmp_path / "t.csv")]) == 0
    out = capsys.readouterr().out
    assert "  invalid by the scene's rules, not solved (their metrics empty): 3\n" in out, out
    assert "    m_coupler: links[1].mass: must be a finite number >= 0: 2\n" in out
    assert "    T_1: loads[0].torque: must be within +-1e+30 (SI units)" in out
    assert "wrote 1 design scene(s)" in out
    assert ("no scene for design(s) 0, 1, 2: the scene's rules refuse them (design 0: "
            "m_coupler: links[1].mass: must be a finite number >= 0, got -1.0)") in out
    assert [p.name for p in (tmp_path / "s").iterdir()] == ["design_3.json"]
    assert main(["analyze", str(tmp_path / "s" / "design_3.json")]) == 0
    t = read_table(tmp_path / "t.csv")
    assert t["invalid"][3] == "" and t["invalid"][2].startswith("T_1: loads[0].torque")
    assert np.isnan(t["K"][:3]).all() and np.isfinite(t["K"][3])
