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


def test_demo_writes_pngs(tmp_path):
    """Files are named after the scene's name (``crank-rocker``), as in every command."""
    assert main(["demo", "-o", str(tmp_path), "--example", "crank_rocker"]) == 0
    for suffix in ("positions", "velocities", "accelerations", "paths", "driving", "reactions",
                   "frame", "shaking", "balance_force_polar", "balance_moment"):
        f = tmp_path / f"crank-rocker_{suffix}.png"
        assert f.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    for suffix in ("result", "balance"):
        assert json.loads((tmp_path / f"crank-rocker_{suffix}.json").read_text())


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
