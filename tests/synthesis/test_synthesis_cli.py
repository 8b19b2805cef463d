"""``linkage-sym new`` and ``linkage-sym synthesize``: what they print, what they write, and
every refusal (exit status 2, the option named, nothing written)."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

import linkage_sym
from linkage_sym.cli import main

from tests.support.marks import fast_cases
from tests.support.synthesis_checks import rocker_swing_and_K

ROOT = Path(__file__).resolve().parents[2]


def run(*args):
    return subprocess.run([sys.executable, "-m", "linkage_sym", *args], capture_output=True,
                          text=True, cwd=ROOT)


@pytest.mark.slow
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


@pytest.mark.slow
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


# a Python process each: one refusal of each command in the fast lane, all in the default run
@pytest.mark.parametrize("args, message", fast_cases([
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
], {
    "--crank-deg: at 180° the four-bar cannot be assembled", "--crank-deg: at -90° the connecting rod",
    "--crank: equals ground", "--ground: no admissible crank pivot is 0.13 m from D",
    "--offset: too large for the stroke", "--K: K = 1 means no quick return"}, key=lambda c: c[1]))
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


@pytest.mark.slow
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


# ------------------------------------------------------------------ extreme numbers and unreadable files
# Found by fuzzing: each of these ended in a traceback (the first three), printed numpy's
# RuntimeWarnings, named an option the command does not have, or wrote a scene that the scene
# format refuses.  Every one is now refused by its option, with the range that works.


@pytest.mark.parametrize("args, message", [
    (["synthesize", "slider-crank", "--K", "1.2", "--stroke", "1e308"],  # All-NaN slice
     "linkage-sym synthesize: --stroke: a length must lie within 1e-30 m to 1e+30 m"),
    (["synthesize", "guide-bar", "--K", "1e308", "--ground", "0.1"],  # math domain error
     "linkage-sym synthesize: --K: K = 1e+308 is too large: θ = 180°·(K - 1)/(K + 1) rounds "
     "to 180°"),
    (["synthesize", "coupler-positions", "--positions", "{binary}"],  # UnicodeDecodeError
     "linkage-sym synthesize: --positions: '{binary}' is not a text (UTF-8) JSON file: byte 0xff "
     "at position 0"),
])
def test_the_fuzzers_tracebacks_are_refusals(tmp_path, args, message):
    binary = tmp_path / "binary.json"
    binary.write_bytes(b"\xff\xfe\x00\x01")
    out = tmp_path / "never.json"
    p = run(*(a.format(binary=binary) for a in args), "-o", str(out))
    assert p.returncode == 2, p.stderr
    assert "Traceback" not in p.stderr, p.stderr
    assert p.stderr.startswith(message.format(binary=binary)), p.stderr
    assert not out.exists()


def refused(capsys, tmp_path, *args):
    """The message of a command that must exit 2 without writing (run in this process)."""
    out = tmp_path / "never.json"
    assert main([*args, "-o", str(out)]) == 2
    assert not out.exists()
    return capsys.readouterr().err


LENGTH = "a length must lie within 1e-30 m to 1e+30 m (the scene format's limits"
MAGNITUDE = "must be within +-1e+30 (SI units)"


@pytest.mark.filterwarnings("error")  # numpy's overflow warnings were printed on the way
@pytest.mark.parametrize("args, message", [
    # lengths beyond the scene format's limits, each naming its option
    (["synthesize", "slider-crank", "--K", "1.2", "--stroke", "1e200"], f"--stroke: {LENGTH}"),
    (["synthesize", "slider-crank", "--K", "1.2", "--stroke", "1e308", "--offset", "1e308"],
     f"--stroke: {LENGTH}"),  # was '--crank: a finite number is expected, got nan'
    (["synthesize", "slider-crank", "--K", "1.2", "--stroke", "1e-300"],
     f"--stroke: {LENGTH}"),  # was '--crank-deg: ... dead-centre position'
    (["synthesize", "slider-crank", "--K", "1.2", "--stroke", "0.1", "--offset", "1e31"],
     f"--offset: {MAGNITUDE}"),
    (["synthesize", "slider-crank", "--K", "1.2", "--stroke", "0.1", "--crank", "1e-300"],
     f"--crank: {LENGTH}"),
    (["synthesize", "crank-rocker", "--K", "1.5", "--rocker", "1e308", "--swing-deg", "45"],
     f"--rocker: {LENGTH}"),  # was RuntimeWarnings and '--K: ... leaves no admissible crank pivot'
    (["synthesize", "crank-rocker", "--K", "1.5", "--rocker", "1e-300", "--swing-deg", "45"],
     f"--rocker: {LENGTH}"),
    (["synthesize", "crank-rocker", "--K", "1.5", "--rocker", "0.075", "--swing-deg", "45",
      "--ground", "1e200"], f"--ground: {LENGTH}"),
    (["synthesize", "crank-rocker", "--K", "1.5", "--rocker", "0.075", "--swing-deg", "45",
      "--crank", "1e-300"], f"--crank: {LENGTH}"),
    (["synthesize", "guide-bar", "--K", "2", "--ground", "1e31"], f"--ground: {LENGTH}"),
    (["synthesize", "guide-bar", "--K", "2", "--ground", "1e-300"], f"--ground: {LENGTH}"),
    (["synthesize", "guide-bar", "--K", "2", "--ground", "0.1", "--speed", "1e308"],
     f"--speed: {MAGNITUDE}"),
    # requests within the limits whose designs would not be (each was written, and refused by
    # load_scene only)
    (["synthesize", "slider-crank", "--K", "1.2", "--stroke", "1e30"],
     "--stroke: with K = 1.2 (θ = 16.3636°) the linkage's joints come up to 1.74958e+30 m from "
     "the crank pivot A, beyond the scene format's +-1e+30 m on coordinates"),
    (["synthesize", "crank-rocker", "--K", "1.5", "--rocker", "1e30", "--swing-deg", "45"],
     "--rocker: with K = 1.5 (θ = 36°) the linkage's joints come up to"),
    (["synthesize", "guide-bar", "--K", "2", "--ground", "1e-30"],
     "--ground: with K = 2 (θ = 60°) the crank would be 5e-31 m, below the scene format's smallest "
     "length 1e-30 m"),
    # K at the ends of its range
    (["synthesize", "slider-crank", "--K", "1e200", "--stroke", "0.1"],
     "--K: K = 1e+200 is too large: θ = 180°·(K - 1)/(K + 1) rounds to 180°"),
    (["synthesize", "crank-rocker", "--K", "1e17", "--rocker", "0.075", "--swing-deg", "45"],
     "--K: K = 1e+17 is too large: θ = 180°·(K - 1)/(K + 1) rounds to 180°"),
    (["synthesize", "guide-bar", "--K", "1e7", "--ground", "0.1"],  # was '--crank: equals ground'
     "--K: K = 1e+07 is too large for a guide-bar"),
    (["synthesize", "guide-bar", "--K", "1.0000000001", "--ground", "0.1"],
     "--K: K = 1.0000000001 (θ = 9e-09°) is too close to 1 for a guide-bar"),
    (["synthesize", "crank-rocker", "--K", "1.0000000000000002", "--rocker", "0.075",
      "--swing-deg", "45"], "--K: K = 1.0000000000000002 (θ = 1.9984e-14°) is too close to 1"),
    (["synthesize", "crank-rocker", "--K", "1.5", "--rocker", "0.075", "--swing-deg", "1e-10"],
     "--swing-deg: the swing 1e-10° is too small for this request"),
    # linkage-sym new
    (["new", "fourbar", "--crank", "1e308", "--coupler", "1e308", "--rocker", "1e308",
      "--ground", "1e308"], f"--crank: {LENGTH}"),  # was '... the sum of the other three, inf m'
    (["new", "fourbar", "--crank", "1e29", "--coupler", "1e30", "--rocker", "1e30",
      "--ground", "1e30"], "--ground: the joints come up to ground + rocker = 2e+30 m"),
    (["new", "fourbar", "--crank", "1e-12", "--coupler", "3", "--rocker", "3", "--ground", "3.5"],
     "--crank: the crank is 1e-12 m, within 1e-09 of the linkage's size"),
    (["new", "fourbar", "--crank", "1", "--coupler", "3", "--rocker", "3", "--ground", "3.5",
      "--coupler-point", "1e308,1e308"], f"--coupler-point: {MAGNITUDE}"),
    (["new", "fourbar", "--crank", "1", "--coupler", "3", "--rocker", "3", "--ground", "3.5",
      "--coupler-point", "1e10,1e10"], "--coupler-point: P is 1.41421e+10 m from the crank pivot A"),
    (["new", "fourbar", "--crank", "1", "--coupler", "3", "--rocker", "3", "--ground", "3.5",
      "--crank-deg", "1e308"], "--crank-deg: must be within +-999640 degrees"),
    (["new", "slider-crank", "--crank", "1e-300", "--coupler", "3e-300"], f"--crank: {LENGTH}"),
    (["new", "slider-crank", "--crank", "1e29", "--coupler", "1e30"],
     "--coupler: the joints come up to crank + connecting rod = 1.1e+30 m"),
    (["new", "guide-bar", "--crank", "1", "--ground", "1e308"], f"--ground: {LENGTH}"),
])
def test_extreme_numbers_are_refused_by_option(capsys, tmp_path, args, message):
    err = refused(capsys, tmp_path, *args)
    assert err.startswith(f"linkage-sym {args[0]}: {message}"), err


@pytest.mark.parametrize("text, message", [
    (b'[[1' + b'0' * 400 + b', 0, 1, 0], [0, 1, 1, 1]]',  # was OverflowError
     "--positions [0][0]: a finite number is expected, got inf"),
    (b'[[1' + b'0' * 5000 + b', 0, 1, 0], [0, 1, 1, 1]]',  # was json's ValueError (4300 digits)
     "--positions [0][0]: a finite number is expected, got inf"),
    (b'[' * 100000 + b']' * 100000, "--positions: {path!r} nests its arrays too deeply"),  # RecursionError
    ('[[0, 0, 1, 0], [0, 1, 1, 1]]'.encode("utf-16"),  # was UnicodeDecodeError
     "--positions: {path!r} is not a text (UTF-8) JSON file: byte 0xff at position 0"),
    (b'[[0, 0, 1, 0], [0, 1, 1, 1], [0, 2, 1, \xe9]]',
     "--positions: {path!r} is not a text (UTF-8) JSON file: byte 0xe9 at position 39"),
    (b'[[1e308, 0, 1e308, 1e308], [0, 1e308, 1e308, 0]]', f"--positions [0][0]: {MAGNITUDE}"),
    (b'[[0, 0, 1e-300, 0], [0, 1e-300, 1e-300, 1e-300]]',
     "--positions [0]: the coupler BC is 1e-300 m long, below the scene format's smallest length"),
])
def test_unreadable_or_extreme_positions_files_are_refused(capsys, tmp_path, text, message):
    path = tmp_path / "positions.json"
    path.write_bytes(text)
    err = refused(capsys, tmp_path, "synthesize", "coupler-positions", "--positions", str(path))
    assert err.startswith("linkage-sym synthesize: " + message.format(path=str(path))), err


def test_positions_whose_four_bar_leaves_the_scene_limits_are_refused(capsys, tmp_path):
    from linkage_sym.synthesis import builders
    rows = []
    for phi in (60, 100, 140):
        j = builders.fourbar(1.0, 3.0, 3.0, 3.5, crank_deg=phi).scene["joints"]
        rows.append([*j[1]["at"], *j[2]["at"]])
    path = tmp_path / "p.json"
    path.write_text(json.dumps([[v * 2e29 for v in r] for r in rows]))
    err = refused(capsys, tmp_path, "synthesize", "coupler-positions", "--positions", str(path))
    assert err.startswith("linkage-sym synthesize: --positions: the four-bar's joints come up to "
                          "1.3e+30 m from the origin as the crank turns"), err
    path.write_text(json.dumps(rows[:2]))
    err = refused(capsys, tmp_path, "synthesize", "coupler-positions", "--positions", str(path),
                  "--pivots", "1e308,0,3.5,0")
    assert err.startswith(f"linkage-sym synthesize: --pivots: {MAGNITUDE}"), err


@pytest.mark.parametrize("args", [
    ["synthesize", "slider-crank", "--K", "1.2", "--stroke", "1e29"],
    ["synthesize", "slider-crank", "--K", "2.99", "--stroke", "1e-29"],
    ["synthesize", "crank-rocker", "--K", "1.5", "--rocker", "1e-29", "--swing-deg", "45"],
    ["synthesize", "guide-bar", "--K", "1.0000000013", "--ground", "0.1"],
    ["synthesize", "guide-bar", "--K", "1e4", "--ground", "1e30"],
    ["new", "fourbar", "--crank", "1e-30", "--coupler", "3e-30", "--rocker", "3e-30",
     "--ground", "3.5e-30", "--crank-deg", "999640"],
])
def test_requests_at_the_limits_give_valid_scenes(capsys, tmp_path, args):
    """The limits refuse no more than they must: just inside them the scene loads and runs."""
    out = tmp_path / "s.json"
    assert main([*args, "-o", str(out)]) == 0, capsys.readouterr().err
    assert (linkage_sym.analyze(linkage_sym.load_scene(out)).status == "ok").all()


def test_the_synthesis_limits_are_the_scene_formats():
    """Repeated in synthesis.common (importing the scene package loads SciPy), so checked here."""
    from linkage_sym.scene import fields, validate
    from linkage_sym.synthesis import common
    assert common.MAX_LENGTH == fields.MAX_MAGNITUDE
    assert common.MAX_ANGLE_DEG == fields.MAX_ANGLE_DEG
    assert common.MIN_LENGTH == validate.MIN_SIZE
    assert common.COINCIDENCE == validate.COINCIDENCE_TOLERANCE
    assert common.MAX_SPREAD == validate.MAX_SPREAD


@pytest.mark.parametrize("args, option", [
    (["synthesize", "guide-bar", "--K", "2200000", "--ground", "0.0307"], "--K"),
    (["synthesize", "slider-crank", "--K", "2.2892", "--stroke", "0.238", "--offset=-2.4e-13"],
     "--offset"),
])
def test_a_K_the_scene_cannot_hold_is_refused(capsys, tmp_path, args, option):
    """Issue 27: these wrote scenes whose K was 1.6e-6 and 4.3e-5 off the request."""
    err = refused(capsys, tmp_path, *args)
    assert err.startswith(f"linkage-sym synthesize: {option}: the linkage's joint coordinates "
                          "(float64) do not hold K = "), err
    assert "its limit positions give K = " in err
