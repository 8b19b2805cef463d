"""``linkage-sym new`` and ``linkage-sym synthesize``: what they print, what they write, and
every refusal (exit status 2, the option named, nothing written)."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

import linkage_sym
from linkage_sym.cli import main

from synthesis_checks import rocker_swing_and_K

ROOT = Path(__file__).resolve().parents[1]


def run(*args):
    return subprocess.run([sys.executable, "-m", "linkage_sym", *args], capture_output=True,
                          text=True, cwd=ROOT)


def test_help_lists_the_commands():
    p = run("--help")
    assert p.returncode == 0 and "new" in p.stdout and "synthesize" in p.stdout
    p = run("synthesize", "--help")
    assert p.returncode == 0 and "crank-rocker" in p.stdout and "coupler-positions" in p.stdout


def test_new_fourbar_writes_a_valid_scene(tmp_path, capsys):
    out = tmp_path / "s.json"
    assert main(["new", "fourbar", "--crank", "0.024", "--coupler", "0.06", "--rocker", "0.05",
                 "--ground", "0.078", "--crank-deg", "30", "--branch", "crossed",
                 "--coupler-point", "0.03,0.02", "--name", "mine", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "crank 0.024 m, coupler 0.06 m, rocker 0.05 m, ground 0.078 m" in text
    assert "minimum transmission angle" in text and f"wrote {out}" in text
    scene = linkage_sym.load_scene(out)
    assert scene.name == "mine" and scene.points[0].name == "P"
    assert (linkage_sym.analyze(scene).status == "ok").all()


def test_new_slider_crank_and_guide_bar(tmp_path):
    for args in (["slider-crank", "--crank", "0.05", "--coupler", "0.2", "--offset", "0.02"],
                 ["guide-bar", "--crank", "0.03", "--ground", "0.06", "--crank-deg", "10"]):
        out = tmp_path / f"{args[0]}.json"
        assert main(["new", *args, "-o", str(out)]) == 0
        assert (linkage_sym.analyze(linkage_sym.load_scene(out)).status == "ok").all()


def test_new_to_standard_output(capsys):
    assert main(["new", "guide-bar", "--crank", "0.03", "--ground", "0.06", "-o", "-"]) == 0
    out, err = capsys.readouterr()
    assert json.loads(out)["name"] == "guide-bar" and "guide-bar: crank 0.03 m" in err


def test_synthesize_crank_rocker_prints_and_writes(tmp_path, capsys):
    out = tmp_path / "cr.json"
    assert main(["synthesize", "crank-rocker", "--K", "1.5", "--rocker", "0.075",
                 "--swing-deg", "45", "--ground", "0.1", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "crank 0.0252241 m, coupler 0.0509887 m, rocker 0.075 m, ground 0.1 m" in text
    assert "extreme-position angle θ = 36°" in text and "rocker swing ψ = 45°" in text
    assert "minimum transmission angle 12.8681° at crank angle 180°" in text
    psi, K = rocker_swing_and_K(json.loads(out.read_text()))
    assert K == pytest.approx(1.5, rel=1e-9)


def test_synthesize_without_condition_says_so(capsys):
    assert main(["synthesize", "crank-rocker", "--K", "1.5", "--rocker", "0.075",
                 "--swing-deg", "45"]) == 0
    text = capsys.readouterr().out
    assert "no extra condition (ground or crank length) given" in text
    assert "largest minimum transmission angle" in text and "-o FILE" in text


def test_synthesize_slider_crank_guide_bar_positions_equations(tmp_path, capsys):
    assert main(["synthesize", "slider-crank", "--K", "1.4", "--stroke", "0.1", "--offset",
                 "0.02"]) == 0
    assert "stroke H = 0.1 m" in capsys.readouterr().out
    assert main(["synthesize", "guide-bar", "--K", "2", "--ground", "0.4"]) == 0
    assert "minimum transmission angle 90° at every crank angle" in capsys.readouterr().out
    from linkage_sym.synthesis import builders
    rows = []
    for phi in (60, 100, 140):
        j = builders.fourbar(1.0, 3.0, 3.0, 3.5, crank_deg=phi).scene["joints"]
        rows.append([*j[1]["at"], *j[2]["at"]])
    pos = tmp_path / "p.json"
    pos.write_text(json.dumps(rows))
    out = tmp_path / "cp.json"
    assert main(["synthesize", "coupler-positions", "--positions", str(pos), "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "circumcentres" in text and "fixed pivots A = (" in text
    linkage_sym.load_scene(out)
    tex = tmp_path / "eq.tex"
    assert main(["synthesize", "equations", "--latex", "-o", str(tex)]) == 0
    assert "\\begin{equation}" in tex.read_text()
    capsys.readouterr()
    assert main(["synthesize", "equations"]) == 0
    assert capsys.readouterr().out.splitlines()[1].startswith("theta = pi*(K - 1)/(K + 1)")


@pytest.mark.parametrize("args, message", [
    (["new", "fourbar", "--crank", "1", "--coupler", "1", "--rocker", "1", "--ground", "2.5",
      "--crank-deg", "180"], "--crank-deg: at 180° the four-bar cannot be assembled"),
    (["new", "fourbar", "--crank", "0", "--coupler", "1", "--rocker", "1", "--ground", "1.5"],
     "--crank: a length > 0 is expected"),
    (["new", "fourbar", "--crank", "1", "--coupler", "3", "--rocker", "3", "--ground", "3.5",
      "--coupler-point", "1"], "--coupler-point: 2 comma-separated numbers U,V expected"),
    (["new", "fourbar", "--crank", "1", "--coupler", "3", "--rocker", "3", "--ground", "3.5",
      "--steps", "1"], "--steps: an integer >= 2 is expected"),
    (["new", "slider-crank", "--crank", "0.05", "--coupler", "0.1", "--offset", "0.2",
      "--crank-deg", "-90"], "--crank-deg: at -90° the connecting rod"),
    (["new", "guide-bar", "--crank", "0.05", "--ground", "0.05"], "--crank: equals ground"),
    (["synthesize", "crank-rocker", "--K", "0.5", "--rocker", "1", "--swing-deg", "40"],
     "--K: the stroke-time ratio is the slower stroke's time over the faster's"),
    (["synthesize", "crank-rocker", "--K", "1.5", "--rocker", "0.075", "--swing-deg", "45",
      "--ground", "0.13"], "--ground: no admissible crank pivot is 0.13 m from D"),
    (["synthesize", "crank-rocker", "--K", "1.5", "--rocker", "0.075", "--swing-deg", "190"],
     "--swing-deg: a crank-rocker's rocker swings"),
    (["synthesize", "slider-crank", "--K", "1.4", "--stroke", "0.1", "--offset", "0.2"],
     "--offset: too large for the stroke"),
    (["synthesize", "slider-crank", "--K", "3.5", "--stroke", "0.1"], "--K: K = 3.5 gives θ"),
    (["synthesize", "guide-bar", "--K", "1", "--ground", "0.4"], "--K: K = 1 means no quick return"),
])
def test_refusals_exit_2_name_the_option_and_write_nothing(tmp_path, args, message):
    out = tmp_path / "never.json"
    p = run(*args, "-o", str(out))
    assert p.returncode == 2, p.stderr
    assert message in p.stderr, p.stderr
    assert "Traceback" not in p.stderr and not out.exists()


def test_both_extra_conditions_are_refused_by_the_parser(tmp_path):
    p = run("synthesize", "crank-rocker", "--K", "1.5", "--rocker", "1", "--swing-deg", "40",
            "--ground", "1", "--crank", "0.2")
    assert p.returncode == 2 and "not allowed with argument" in p.stderr


def test_positions_file_refusals(tmp_path):
    out = tmp_path / "never.json"
    missing = run("synthesize", "coupler-positions", "--positions", str(tmp_path / "no.json"),
                  "-o", str(out))
    assert missing.returncode == 2 and "--positions: cannot read" in missing.stderr
    bad = tmp_path / "bad.json"
    bad.write_text("[[0, 0, 1, 0],")
    p = run("synthesize", "coupler-positions", "--positions", str(bad), "-o", str(out))
    assert p.returncode == 2 and "is not valid JSON" in p.stderr
    bad.write_text(json.dumps([[0, 0, 1, 0], [0, 1, 1, 1.5]]))
    p = run("synthesize", "coupler-positions", "--positions", str(bad), "-o", str(out))
    assert p.returncode == 2 and "--positions [1]: the coupler BC is" in p.stderr
    bad.write_text(json.dumps([[0, 0, 5, 0], [-1, 1, 3, 4], [-3, 1, 0, 5]]))
    p = run("synthesize", "coupler-positions", "--positions", str(bad), "-o", str(out))
    assert p.returncode == 2 and "--positions: branch defect" in p.stderr
    bad.write_text(json.dumps([[0, 0, 1, 0], [0, 1, 1, 1]]))
    p = run("synthesize", "coupler-positions", "--positions", str(bad), "--pivots", "0,0,1",
            "-o", str(out))
    assert p.returncode == 2 and "--pivots: 4 comma-separated numbers" in p.stderr
    assert not out.exists()


def test_an_output_folder_is_refused_before_anything(tmp_path):
    p = run("new", "guide-bar", "--crank", "0.03", "--ground", "0.06", "-o", str(tmp_path))
    assert p.returncode == 2 and "is a folder" in p.stderr


def test_synthesis_loads_no_sympy_scipy_or_matplotlib():
    """The numeric synthesis (the package and its NumPy modules) in a fresh interpreter."""
    code = ("import sys\n"
            "from linkage_sym.synthesis import crank_rocker, coupler_positions, slider_crank_by_K\n"
            "crank_rocker(1.5, 0.075, 45.0)\n"
            "slider_crank_by_K(1.4, 0.1)\n"
            "print(','.join(m for m in ('sympy', 'scipy', 'matplotlib') if m in sys.modules))\n")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == ""
