"""The command line: exit codes, files written or not, the result contract."""

import json
import subprocess
import sys

import pytest

from linkage_sym.cli import main
from linkage_sym.examples import example_dict, example_path


def run(*args, cwd=None):
    return subprocess.run(
        [sys.executable, "-m", "linkage_sym", *args], capture_output=True, text=True, cwd=cwd
    )


def test_analyze_writes_the_contract(tmp_path):
    out = tmp_path / "r.json"
    assert main(["analyze", str(example_path("crank_rocker")), "-o", str(out)]) == 0
    r = json.loads(out.read_text())
    assert r["scene"] == "crank-rocker"
    assert r["stages"] == ["position", "velocity", "acceleration", "forces"]
    assert len(r["steps"]) == 361
    s = r["steps"][0]
    assert s["status"] == "ok"
    # R joints: reaction_moment may be left out (spec), and is
    assert set(s["joints"]["C"]) == {"position", "velocity", "acceleration", "reaction"}
    assert set(s["links"]["coupler"]) >= {"rotation", "omega", "alpha", "com", "com_velocity",
                                          "com_acceleration"}
    assert set(s["driving"]) == {"A"}
    assert set(s["frame"]) == {"force", "moment"} and len(s["frame"]["force"]) == 2
    assert r["force_method"] == "dyad"
    assert "warnings" not in r


def test_output_folders_are_created(tmp_path):
    out = tmp_path / "new" / "deeper" / "r.json"
    assert main(["analyze", str(example_path("crank_rocker")), "-o", str(out)]) == 0
    assert json.loads(out.read_text())["scene"] == "crank-rocker"


@pytest.mark.slow
def test_analyze_plots(tmp_path, capsys):
    """``--plots DIR`` writes the sweep's pictures; with the JSON on standard output
    (``-o -``) the list of pictures goes to standard error, so standard output stays one
    JSON document."""
    d = example_dict("crank_rocker")
    d["drivers"][0]["steps"] = 37
    d["outputs"] = ["kinematics", "driving"]
    scene = tmp_path / "s.json"
    scene.write_text(json.dumps(d))
    pics = tmp_path / "pics"
    assert main(["analyze", str(scene), "-o", "-", "--plots", str(pics)]) == 0
    out, err = capsys.readouterr()
    assert json.loads(out)["scene"] == "crank-rocker"
    names = sorted(p.name for p in pics.iterdir())
    assert names == sorted(f"crank-rocker_{k}.png" for k in
                           ("positions", "velocities", "accelerations", "transmission", "paths",
                            "driving"))
    for p in pics.iterdir():
        assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", p
        assert p.name in err


def test_analyze_global_method_and_p_joint_moments(tmp_path):
    out_d, out_g = tmp_path / "d.json", tmp_path / "g.json"
    path = str(example_path("slider_crank_offset"))
    assert main(["analyze", path, "-o", str(out_d)]) == 0
    assert main(["analyze", path, "--method", "global", "-o", str(out_g)]) == 0
    d, g = json.loads(out_d.read_text()), json.loads(out_g.read_text())
    assert g["force_method"] == "global"
    sd, sg = d["steps"][40], g["steps"][40]
    assert "reaction_moment" in sd["joints"]["C_guide"]  # a P joint carries a couple
    for a, b in zip(sd["joints"]["C_guide"]["reaction"], sg["joints"]["C_guide"]["reaction"]):
        assert a == pytest.approx(b, rel=1e-9, abs=1e-9)


def test_analyze_refuses_an_unknown_disconnection(tmp_path, capsys):
    out = tmp_path / "r.json"
    code = main(["analyze", str(example_path("sixbar_class3")), "--disconnection", "99",
                 "-o", str(out)])
    assert code == 2
    assert "disconnection" in capsys.readouterr().err
    assert not out.exists()


@pytest.mark.slow
def test_python_m_is_the_same_program(tmp_path):
    out = tmp_path / "r.json"
    p = run("analyze", str(example_path("crank_rocker")), "-o", str(out))
    assert p.returncode == 0, p.stderr
    assert out.exists()


@pytest.mark.parametrize(
    "mutate, field",
    [
        (lambda d: d["joints"][2]["links"].__setitem__(1, "cuopler"), "joints[2].links[1]"),
        (lambda d: d["links"][0].__setitem__("mass", -1.0), "links[0].mass"),
        (lambda d: d["drivers"][0].__setitem__("joint", "Z"), "drivers[0].joint"),
        (lambda d: d["joints"].pop(), "drivers"),  # mobility no longer matches
    ],
)
def test_invalid_scene_exits_2_and_writes_nothing(tmp_path, mutate, field):
    d = example_dict("crank_rocker")
    mutate(d)
    scene = tmp_path / "bad.json"
    scene.write_text(json.dumps(d))
    out = tmp_path / "r.json"
    p = run("analyze", str(scene), "-o", str(out))
    assert p.returncode == 2
    assert field in p.stderr
    assert not out.exists()


def test_malformed_json_exits_2(tmp_path):
    scene = tmp_path / "bad.json"
    scene.write_text('{"name": "x", "links": [}')
    out = tmp_path / "r.json"
    p = run("analyze", str(scene), "-o", str(out))
    assert p.returncode == 2 and "line 1" in p.stderr
    assert not out.exists()


def test_repeated_key_exits_2(tmp_path):
    scene = tmp_path / "bad.json"
    scene.write_text(example_path("crank_rocker").read_text().replace(
        '"name":', '"name": "x", "name":', 1))
    out = tmp_path / "r.json"
    p = run("analyze", str(scene), "-o", str(out))
    assert p.returncode == 2 and "name: given more than once" in p.stderr
    assert not out.exists()


def test_structure_command(capsys):
    assert main(["structure", str(example_path("crank_rocker"))]) == 0
    text = capsys.readouterr().out
    assert "dyad RRR (class II): coupler, rocker" in text


@pytest.mark.slow
def test_demo_writes_pngs(tmp_path):
    """Files are named after the scene's name (``crank-rocker``), as in every command."""
    assert main(["demo", "-o", str(tmp_path), "--example", "crank_rocker"]) == 0
    for suffix in ("positions", "velocities", "accelerations", "paths", "driving", "reactions",
                   "frame", "shaking", "shaking_force_polar", "shaking_moment"):
        f = tmp_path / f"crank-rocker_{suffix}.png"
        assert f.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    for suffix in ("result", "balance"):
        assert json.loads((tmp_path / f"crank-rocker_{suffix}.json").read_text())


# -- balance: a summary on the console, the JSON only with -o ------------------------------


def _small_crank_rocker(tmp_path, steps=25):
    d = example_dict("crank_rocker")
    d["drivers"][0]["steps"] = steps
    path = tmp_path / "crank_rocker.json"
    path.write_text(json.dumps(d))
    return str(path)


def _rms_of_solver(scene_path):
    """RMS shaking force and moment over the sweep, from the numeric force solver with
    inertia as the only effect (no code of the balancing module)."""
    import dataclasses

    import numpy as np

    import linkage_sym
    from linkage_sym.model import Effects

    scene = linkage_sym.load_scene(scene_path)
    res = linkage_sym.analyze(dataclasses.replace(
        scene, effects=Effects(inertia=True, gravity=None, loads=False)))
    F = np.hypot(res.forces.frame_force[:, 0], res.forces.frame_force[:, 1])
    M = res.forces.frame_moment
    return float(np.sqrt(np.mean(F * F))), float(np.sqrt(np.mean(M * M)))


def _numbers(line, unit):
    """The numbers before ``unit`` in a summary line, in order."""
    import re

    return [float(x) for x in re.findall(rf"([-+0-9.e]+) {re.escape(unit)} ", line + " ")]


def test_balance_prints_a_summary_not_the_json(tmp_path, capsys):
    """``balance SCENE --balanced-scene OUT`` without -o printed the whole JSON (76 KB for
    the crank-rocker) on standard output: now a summary -- the conditions, the counterweights,
    RMS shaking force and moment before and after -- and the JSON only with -o.  The RMS
    printed (4 significant digits) against the force solver's frame loads of the scene as
    given and of the balanced scene written: 5e-4 relative (the printed rounding); the
    balanced force, ~1e-16 N, against 1e-9 of the unbalanced."""
    scene = _small_crank_rocker(tmp_path)
    bal = tmp_path / "balanced.json"
    assert main(["balance", scene, "--balanced-scene", str(bal)]) == 0
    out = capsys.readouterr().out
    assert len(out) < 3000 and '"symbols"' not in out
    lines = out.splitlines()
    assert f"wrote {bal}" in lines and "force balance conditions (each = 0):" in lines
    assert "  Re_crank: m_coupler + m_crank*xG_crank/a_crank - m_coupler*xG_coupler/a_coupler" in lines
    assert any(line.startswith("  yG_coupler: cancels") for line in lines)
    cw = next(line for line in lines if line.startswith("counterweights balancing the force: "))
    written = json.loads(bal.read_text())
    for link in ("crank", "rocker"):
        assert f"{link} " in cw
    F0, M0 = _rms_of_solver(scene)
    F1, M1 = _rms_of_solver(str(bal))
    f_line = next(line for line in lines if line.startswith("RMS shaking force: "))
    m_line = next(line for line in lines if line.startswith("RMS shaking moment: "))
    assert "as given" in f_line and "force-balanced" in f_line
    (f0, f1), (m0, m1) = _numbers(f_line, "N"), _numbers(m_line, "N·m")
    assert f0 == pytest.approx(F0, rel=5e-4) and abs(f1) <= 1e-9 * F0
    assert m0 == pytest.approx(M0, rel=5e-4) and m1 == pytest.approx(M1, rel=5e-4)
    assert "(the balance JSON: -o FILE, or -o - for standard output)" in lines
    assert written["name"] == "crank-rocker with counterweights"


@pytest.mark.slow
def test_balance_writes_the_json_with_o_only(tmp_path, capsys):
    scene = _small_crank_rocker(tmp_path)
    out = tmp_path / "b.json"
    assert main(["balance", scene, "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert text.startswith(f"wrote {out}\n") and "RMS shaking force: " in text
    assert set(json.loads(out.read_text())) >= {"symbols", "force_balance_conditions", "series"}
    assert main(["balance", scene, "-o", "-"]) == 0  # the JSON alone on standard output
    got = capsys.readouterr()
    assert "force_balance_conditions" in json.loads(got.out) and "RMS" not in got.err


@pytest.mark.slow
def test_balance_latex_writes_a_tex_file(tmp_path, capsys):
    """``--latex`` only added a 'latex' key to the JSON (and to the 76 KB printed without
    -o): it now writes a LaTeX fragment of its own, to the file given or beside -o."""
    scene = _small_crank_rocker(tmp_path)
    out = tmp_path / "b.json"
    assert main(["balance", scene, "-o", str(out), "--latex"]) == 0
    tex = (tmp_path / "b.tex").read_text()
    report = json.loads(out.read_text())
    exprs = (list(report["latex"]["mass_parameters"].values())
             + list(report["latex"]["acceleration_parameters"].values())
             + list(report["latex"]["shaking_moment"].values()))
    assert all(e in tex for e in exprs)
    for c in report["latex"]["force_balance_conditions"] + report["latex"]["moment_balance_conditions"]:
        lhs, _, rhs = c.rpartition(" = ")
        assert f"{lhs} &= {rhs}" in tex
    assert tex.count("\\begin{align*}") == tex.count("\\end{align*}") == 5
    own = tmp_path / "own.tex"
    assert main(["balance", scene, "--latex", str(own)]) == 0
    assert own.read_text() == tex and f"wrote {own}" in capsys.readouterr().out
    assert main(["balance", scene, "--latex"]) == 2
    assert "--latex: give its file" in capsys.readouterr().err


def _triple_rocker(tmp_path, turns=2):
    """The triple-rocker of ``new fourbar`` (crank 0.05, coupler 0.06, rocker 0.05, frame
    0.078) driven over ``turns`` turns in steps of 1°."""
    scene = tmp_path / "tr.json"
    assert main(["new", "fourbar", "--crank", "0.05", "--coupler", "0.06", "--rocker", "0.05",
                 "--ground", "0.078", "--steps", str(360 * turns + 1), "-o", str(scene)]) == 0
    d = json.loads(scene.read_text())
    d["drivers"][0]["stop_deg"] = 360.0 * turns
    scene.write_text(json.dumps(d))
    return scene


def _unreached(turns=2):
    """The crank angles (whole degrees, 0 .. 360 turns) where |BD| exceeds coupler + rocker:
    the law of cosines, written here."""
    import math

    a, b, c, d = 0.05, 0.06, 0.05, 0.078
    return [k for k in range(360 * turns + 1)
            if math.sqrt(a * a + d * d - 2 * a * d * math.cos(math.radians(k))) > b + c]


def test_analyze_summary_names_the_unassemblable_ranges(tmp_path, capsys):
    """The summary names the driver ranges of the unassemblable steps, not only their count;
    the ranges are where the law of cosines says the dyad cannot reach."""
    scene = _triple_rocker(tmp_path)
    capsys.readouterr()
    assert main(["analyze", str(scene)]) == 0
    out = capsys.readouterr().out
    bad = _unreached()
    runs, start = [], bad[0]
    for k, nxt in zip(bad, bad[1:] + [None]):
        if nxt != k + 1:
            runs.append(f"{start}°..{k}°")
            start = nxt
    assert len(runs) == 2  # 117..243 and 477..603
    assert f"unassemblable: {len(bad)} steps, A {', '.join(runs)}\n" in out, out


def test_unassemblable_ranges_do_not_depend_on_the_chunks(tmp_path):
    """Solved in chunks of 50 steps (a range crosses chunk boundaries), the ranges are those of
    the whole run, and the one wording gives the same line."""
    import linkage_sym
    from linkage_sym import output
    from linkage_sym.output.stats import ranges_text, step_ranges

    scene = linkage_sym.load_scene(_triple_rocker(tmp_path))
    plan = linkage_sym.compile_plan(scene)
    whole = plan.run()
    ref = step_ranges(whole.status == "unassemblable",
                      {k: d["q"] for k, d in whole.drivers.items()})
    stats = output.write_sweep(output.plan_sweep(plan, "dyad"), None, "json", chunk=50)
    assert stats.unassemblable.runs == ref.runs and stats.unassemblable.count == ref.count
    assert [r[:2] for r in ref.runs] == [[117, 243], [477, 603]]
    assert (ranges_text("unassemblable", stats.unassemblable, {"A": "R"})
            == f"unassemblable: {len(_unreached())} steps, A 117°..243°, 477°..603°")
