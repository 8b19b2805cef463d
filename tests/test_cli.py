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
                   "frame", "shaking", "shaking_force_polar", "shaking_moment"):
        f = tmp_path / f"crank-rocker_{suffix}.png"
        assert f.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    for suffix in ("result", "balance"):
        assert json.loads((tmp_path / f"crank-rocker_{suffix}.json").read_text())
