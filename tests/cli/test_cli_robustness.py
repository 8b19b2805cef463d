"""The command line never ends in a traceback: bad options and output paths are refused
before anything is computed or written (exit 2, the option named), a closed pipe stops it
quietly, a sweep that never assembles says so (exit 3, no plots), and plot files are
named after the scene in every command."""

import json
from pathlib import Path
import subprocess
import sys

import pytest

import linkage_sym
from linkage_sym.cli import BROKEN_PIPE, NO_STEP_ASSEMBLED, main
from linkage_sym.examples import example_dict, example_names, example_path

CRANK_ROCKER = str(example_path("crank_rocker"))
SLIDER_CRANK = str(example_path("slider_crank_offset"))


def run(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "linkage_sym", *args], capture_output=True,
                          text=True, cwd=cwd)


def files_under(path):
    return sorted(p.relative_to(path).as_posix() for p in path.rglob("*")) if path.exists() else []


def small_scene(tmp_path, name="crank-rocker", steps=13, outputs=None):
    """The crank-rocker with a short sweep (and another name, if asked) as a file."""
    d = example_dict("crank_rocker")
    d["name"] = name
    d["drivers"][0]["steps"] = steps
    if outputs is not None:
        d["outputs"] = outputs
    path = tmp_path / "scene_file.json"
    path.write_text(json.dumps(d))
    return str(path)


def never_assembles(tmp_path):
    """A slider-crank whose rod cannot reach the slide at any step of its sweep (crank 0.5,
    rod 1.0, offset 0.8: unreachable while sin(q) < -0.4; the sweep is 250..290 deg)."""
    x = 0.5 + (1.0 - 0.64) ** 0.5
    d = {
        "name": "never assembles",
        "links": [{"name": "crank", "mass": 1.0, "com": [0.2, 0.0], "inertia": 0.01},
                  {"name": "rod", "mass": 1.0, "com": [0.6, 0.4], "inertia": 0.01},
                  {"name": "slider", "mass": 1.0, "com": [x, 0.8], "inertia": 0.01}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
            {"name": "B", "type": "R", "links": ["crank", "rod"], "at": [0.5, 0.0]},
            {"name": "C", "type": "R", "links": ["rod", "slider"], "at": [x, 0.8]},
            {"name": "G", "type": "P", "links": ["ground", "slider"], "at": [x, 0.8],
             "axis_deg": 0.0},
        ],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": 250, "stop_deg": 290,
                     "steps": 5, "speed": 2.0}],
        "effects": {"inertia": True, "gravity": [0.0, -9.81], "loads": True},
        "outputs": ["kinematics", "reactions", "driving", "frame"],
    }
    path = tmp_path / "never.json"
    path.write_text(json.dumps(d))
    return str(path)


def no_traceback(text):
    assert "Traceback" not in text, text


# -- 1. demo --example with an unknown name ------------------------------------------


def test_demo_unknown_example_names_the_option_and_lists_examples(tmp_path):
    out = tmp_path / "d"
    p = run("demo", "-o", str(out), "--example", "nosuch")
    assert p.returncode == 2
    no_traceback(p.stderr)
    assert "--example" in p.stderr and "'nosuch'" in p.stderr
    for name in example_names():
        assert name in p.stderr
    assert not out.exists()


# -- 2. output paths checked before anything is computed or written ---------------------


@pytest.mark.slow  # about 1-3 s each: the fast lane stays under two minutes
@pytest.mark.parametrize("command, option, extra", [
    ("analyze", "-o", []),
    ("analyze", "-o", ["--plots", "PICS"]),
    ("derive", "-o", []),
    ("balance", "-o", []),
    ("balance", "--balanced-scene", ["-o", "OUT"]),
    ("balance", "--optimize", ["-o", "OUT"]),
    ("animate", "-o", []),
])
def test_an_output_file_that_is_a_folder_is_refused(tmp_path, command, option, extra):
    folder = tmp_path / "existing"
    folder.mkdir()
    extra = [str(tmp_path / "pics") if a == "PICS" else str(tmp_path / "out.json")
             if a == "OUT" else a for a in extra]
    p = run(command, CRANK_ROCKER, option, str(folder), *extra)
    assert p.returncode == 2, p.stderr
    no_traceback(p.stderr)
    assert f"{option}" in p.stderr and "is a folder" in p.stderr
    assert files_under(tmp_path) == ["existing"]


@pytest.mark.slow  # about 1-3 s each: the fast lane stays under two minutes
@pytest.mark.parametrize("command, option, where, extra", [
    ("analyze", "--plots", "folder", ["-o", "OUT"]),
    ("analyze", "--plots", "under", ["-o", "OUT"]),
    ("analyze", "-o", "under", ["--plots", "PICS"]),
    ("derive", "-o", "under", []),
    ("balance", "--plots", "folder", ["-o", "OUT"]),
    ("balance", "--optimize", "under", ["-o", "OUT", "--plots", "PICS"]),
    ("balance", "--balanced-scene", "under", ["-o", "OUT"]),
    ("demo", "-o", "folder", ["--example", "crank_rocker"]),
    ("demo", "-o", "under", ["--example", "crank_rocker"]),
])
def test_a_path_through_a_regular_file_is_refused(tmp_path, command, option, where, extra):
    """A folder option naming a regular file, or any path under a regular file (its folder
    cannot be created): exit 2, the option named, nothing written."""
    blocker = tmp_path / "plain_file"
    blocker.write_text("keep me\n")
    bad = blocker if where == "folder" else blocker / "sub" / "x.json"
    extra = [str(tmp_path / "pics") if a == "PICS" else str(tmp_path / "out.json")
             if a == "OUT" else a for a in extra]
    args = [command] + ([] if command == "demo" else [CRANK_ROCKER]) + [option, str(bad), *extra]
    p = run(*args)
    assert p.returncode == 2, p.stderr
    no_traceback(p.stderr)
    assert f"{option}" in p.stderr and "plain_file" in p.stderr
    assert files_under(tmp_path) == ["plain_file"]
    assert blocker.read_text() == "keep me\n"


def test_two_options_naming_one_file_are_refused(tmp_path):
    out = tmp_path / "same.json"
    p = run("balance", CRANK_ROCKER, "-o", str(out), "--optimize", str(out))
    assert p.returncode == 2 and "--optimize" in p.stderr and "-o/--output" in p.stderr
    assert not out.exists()


@pytest.mark.slow
def test_missing_output_folders_are_still_created(tmp_path):
    out = tmp_path / "a" / "b" / "r.json"
    pics = tmp_path / "c" / "pics"
    scene = small_scene(tmp_path, outputs=["kinematics"])
    assert main(["analyze", scene, "-o", str(out), "--plots", str(pics)]) == 0
    assert out.exists() and any(pics.iterdir())


# -- 3. a closed pipe ------------------------------------------------------------------


@pytest.mark.parametrize("args", [
    ["analyze", CRANK_ROCKER, "-o", "-"],
    ["analyze", CRANK_ROCKER],
    ["structure", CRANK_ROCKER],
    ["examples"],
])
def test_a_pipe_closed_before_the_output_stops_quietly(args):
    """The reader is gone before the first byte is written: no traceback, status 141."""
    p = subprocess.Popen([sys.executable, "-m", "linkage_sym", *args], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE)
    p.stdout.close()
    err = p.stderr.read().decode()
    p.stderr.close()
    assert p.wait() == BROKEN_PIPE, err
    no_traceback(err)
    assert "BrokenPipe" not in err and "Exception ignored" not in err


def test_a_pipe_closed_after_some_bytes_stops_quietly():
    """``analyze -o - | head -c 50``: no traceback whether or not the writer saw the close."""
    p = subprocess.Popen([sys.executable, "-m", "linkage_sym", "analyze", CRANK_ROCKER, "-o", "-"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    head = p.stdout.read(50)
    p.stdout.close()
    err = p.stderr.read().decode()
    p.stderr.close()
    assert p.wait() in (0, BROKEN_PIPE), err
    assert head.startswith(b'{"scene": "crank-rocker"')
    no_traceback(err)


# -- 4. balance: prismatic joints and bad options -----------------------------------------


@pytest.mark.slow
def test_balance_of_a_slider_crank_points_to_optimize(tmp_path):
    out = tmp_path / "b.json"
    p = run("balance", SLIDER_CRANK, "-o", str(out))
    assert p.returncode == 2
    no_traceback(p.stderr)
    assert "invalid scene" not in p.stderr
    assert "hinged" in p.stderr and "prismatic" in p.stderr and "--optimize" in p.stderr
    assert not out.exists()


@pytest.mark.parametrize("args, option", [
    (["--weights", "1,x"], "--weights"),
    (["--weights", "1,inf,1"], "--weights"),
    (["--max-mass", "-0.5"], "--max-mass"),
    (["--max-mass", "nan"], "--max-mass"),
    (["--links", "crank,nosuch"], "--links"),
])
# a command line each: the crank-rocker's in the fast lane, the slider-crank's in the default run
@pytest.mark.parametrize("scene", [CRANK_ROCKER, pytest.param(SLIDER_CRANK, marks=pytest.mark.slow)])
def test_balance_bad_optimize_options_are_option_errors(tmp_path, args, option, scene):
    out, opt = tmp_path / "b.json", tmp_path / "opt.json"
    p = run("balance", scene, "-o", str(out), "--optimize", str(opt), *args)
    assert p.returncode == 2
    no_traceback(p.stderr)
    assert option in p.stderr and "invalid scene" not in p.stderr
    assert files_under(tmp_path) == []


def test_balance_optimize_options_without_optimize_are_refused(tmp_path):
    out = tmp_path / "b.json"
    p = run("balance", CRANK_ROCKER, "-o", str(out), "--weights", "1,0,0")
    assert p.returncode == 2 and "--weights" in p.stderr and "--optimize" in p.stderr
    assert not out.exists()


def test_analyze_unknown_disconnection_is_an_option_error(tmp_path):
    out = tmp_path / "r.json"
    p = run("analyze", str(example_path("sixbar_class3")), "--disconnection", "99", "-o", str(out))
    assert p.returncode == 2 and "--disconnection" in p.stderr
    assert "invalid scene" not in p.stderr
    assert not out.exists()


# -- 5. a sweep in which no step assembles ---------------------------------------------


def test_a_sweep_that_never_assembles_writes_the_result_but_no_plots(tmp_path):
    scene = never_assembles(tmp_path)
    out, pics = tmp_path / "r.json", tmp_path / "pics"
    p = run("analyze", scene, "-o", str(out), "--plots", str(pics))
    assert p.returncode == NO_STEP_ASSEMBLED == 3
    no_traceback(p.stderr)
    assert p.stderr.count("no step of the sweep could be assembled") == 1
    assert "step 0: dyad RRP (rod, slider)" in p.stderr and "no plots" in p.stderr
    assert not pics.exists()
    steps = json.loads(out.read_text())["steps"]
    assert [s["status"] for s in steps] == ["unassemblable"] * 5
    assert "5 unassemblable" in p.stdout and "0 ok" in p.stdout


def test_the_exit_status_is_in_the_help():
    p = run("analyze", "--help")
    assert p.returncode == 0 and "exit status" in p.stdout
    assert f"{NO_STEP_ASSEMBLED}    analyze: no step of the sweep could be assembled" in p.stdout


# -- 6. --version ---------------------------------------------------------------------


def test_version():
    p = run("--version")
    assert p.returncode == 0 and p.stdout.strip() == f"linkage-sym {linkage_sym.__version__}"


# -- 7. plot files are named after the scene ---------------------------------------------


@pytest.mark.slow
def test_plot_files_are_named_after_the_scene_in_every_command(tmp_path):
    """The scene's ``name`` made file-name safe, not the scene file's name or the example's."""
    scene = small_scene(tmp_path, name="my rig: v2/3", outputs=["kinematics", "driving"])
    stem = "my_rig_v2_3"
    a, b = tmp_path / "a", tmp_path / "b"
    assert main(["analyze", scene, "-o", str(tmp_path / "r.json"), "--plots", str(a)]) == 0
    assert main(["balance", scene, "-o", str(tmp_path / "b.json"), "--plots", str(b)]) == 0
    for folder in (a, b):
        names = [p.name for p in folder.iterdir()]
        assert names and all(n.startswith(stem + "_") for n in names), names
    assert main(["demo", "-o", str(tmp_path / "d"), "--example", "shaper"]) == 0
    names = [p.name for p in (tmp_path / "d").iterdir()]
    assert names and all(n.startswith("shaper_") for n in names), names


# -- 8. the console summary --------------------------------------------------------------


def test_analyze_to_a_file_prints_a_summary(tmp_path, capsys):
    out = tmp_path / "r.json"
    assert main(["analyze", CRANK_ROCKER, "-o", str(out)]) == 0
    text = capsys.readouterr().out
    r = json.loads(out.read_text())
    lines = text.splitlines()
    assert lines[0] == f"wrote {out}"
    assert lines[1].startswith("crank-rocker: 361 steps: 361 ok")
    # the peak driving torque and where it occurs, from the result file
    torques = [s["driving"]["A"] for s in r["steps"]]
    k = max(range(len(torques)), key=lambda i: abs(torques[i]))
    q = r["steps"][k]["drivers"]["A"]["q"]
    assert f"peak driving torque at A: {torques[k]:.4g} N·m at step {k} (A = " in text
    assert f"{__import__('math').degrees(q):.4g}°" in text
    # the largest reaction, its joint and step
    mags = [(sum(c * c for c in rec["reaction"]) ** 0.5, name, i) for i, s in enumerate(r["steps"])
            for name, rec in s["joints"].items() if "reaction" in rec]
    m, joint, i = max(mags)
    assert f"largest reaction: {m:.4g} N at joint {joint}, step {i} " in text
    assert "peak frame force:" in text and "peak frame moment:" in text
    assert "warning" not in text


def test_analyze_without_output_prints_the_summary_not_the_json(tmp_path, capsys):
    assert main(["analyze", CRANK_ROCKER]) == 0
    text = capsys.readouterr().out
    assert text.startswith("crank-rocker: 361 steps: 361 ok")
    assert '"steps"' not in text and "-o -" in text
    assert files_under(tmp_path) == []


def test_analyze_dash_writes_the_json_to_stdout(capsys):
    assert main(["analyze", CRANK_ROCKER, "-o", "-"]) == 0
    out, err = capsys.readouterr()
    assert json.loads(out)["scene"] == "crank-rocker"
    assert "peak" not in out + err


def test_empty_outputs_return_statuses_and_drivers_and_say_so(tmp_path, capsys):
    """``"outputs": []`` (issue 27): accepted, as the format's 'outputs lists what to
    return' allows, but no longer silently: the summary says what the result holds, and the
    result holds each step's status and driver values, nothing of joints or links."""
    out = tmp_path / "r.json"
    assert main(["analyze", small_scene(tmp_path, outputs=[]), "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert ("the scene's outputs are empty: the result holds each step's status and driver "
            "values only (the position stage ran to find which steps assemble)") in text, text
    r = json.loads(out.read_text())
    assert r["stages"] == ["position"]
    assert {k for s in r["steps"] for k in s} <= {"status", "message", "drivers", "accuracy"}
    assert all(s["status"] == "ok" for s in r["steps"]) and len(r["steps"]) == 13
    assert main(["analyze", small_scene(tmp_path, outputs=["kinematics"])]) == 0
    assert "outputs are empty" not in capsys.readouterr().out


def test_summary_names_shaking_loads_and_warnings(tmp_path):
    """Inertia only: the frame loads are the shaking force and moment; warnings are listed."""
    from linkage_sym.cli.analyze import summary

    d = example_dict("crank_rocker")
    d["effects"] = {"inertia": True, "gravity": None, "loads": False}
    d["drivers"][0]["steps"] = 25
    scene = linkage_sym.load_scene(d)
    res = linkage_sym.analyze(scene)
    res.warnings = ["made-up warning for the test"]
    text = "\n".join(summary(scene, res))
    assert "peak shaking force:" in text and "peak shaking moment:" in text
    assert "warning: made-up warning for the test" in text


# -- found by fuzzing the commands: sizes no machine holds, and malformed sweep options --------

@pytest.mark.parametrize("command", ["analyze", "centres", "balance", "sweep --list"])
# a command line each: 10**12 in the fast lane, the sizes past int64 and float's exact range
# in the default run
@pytest.mark.parametrize("steps", [10**12, pytest.param(2**63, marks=pytest.mark.slow),
                                   pytest.param(10**20, marks=pytest.mark.slow)])
def test_a_sweep_too_large_for_memory_is_refused_by_its_field(tmp_path, command, steps):
    """Each of these ended in a MemoryError, ValueError or IndexError of numpy's linspace."""
    scene = small_scene(tmp_path, steps=steps)
    p = run(*command.split(), scene)
    assert p.returncode == 2, p.stderr
    assert "Traceback" not in p.stderr
    assert f"drivers[0].steps: {steps} steps do not fit in memory" in p.stderr


@pytest.mark.parametrize("command, results, copies, scene_outputs", [
    ("analyze", "chunks", 2, None), ("analyze --plots PLOTS", "whole", 2, None),
    ("centres", "whole", 1, ("kinematics", "instant_centres")), ("balance", "whole", 1, None),
    ("sweep --list", "none", 4, None), ("sweep --vary l_AB=0.02,0.03", "path", 4, None),
])
def test_a_run_whose_peak_does_not_fit_is_refused_in_every_command(
        tmp_path, capsys, monkeypatch, command, results, copies, scene_outputs):
    """Issue 27: 5e8 steps were killed without a message in centres, balance and sweep (their
    driver values alone, 12 GB, fit); now every command estimates its whole run's peak
    (output.run_memory: driver values, solving path, results) before making any of it.
    The memory available is made small here; a million steps is not solved."""
    import dataclasses

    from linkage_sym import output
    from linkage_sym.numeric.engine.heap import gib

    available = 100 * 2**20
    monkeypatch.setattr(output, "available_memory", lambda: available)
    path = small_scene(tmp_path, steps=10**6)
    scene = linkage_sym.load_scene(path)
    if scene_outputs:
        scene = dataclasses.replace(scene, outputs=scene_outputs)
    m = output.run_memory(scene, results, copies=copies, available=available,
                          fmt="json" if command == "analyze" else None)
    assert m["total"] > available
    args = [a.replace("PLOTS", str(tmp_path / "p")) for a in command.split()]
    assert main([args[0], path, *args[1:]]) == 2
    err = capsys.readouterr().err
    assert (f"drivers[0].steps: 1000000 steps do not fit in memory: the run needs about "
            f"{gib(m['total'])} at its peak (driver values {gib(m['driver values'])}, "
            f"solving path {gib(m['solving path'])}, results {gib(m['results'])}), and this "
            f"process can take {gib(available)} more") in err, err
    assert files_under(tmp_path) == ["scene_file.json"]


@pytest.mark.slow
def test_a_solving_path_far_longer_than_the_sweep_is_refused():
    """``centres --deg 1e12`` asked for a path of 5e11 points from the assembly configuration
    (numpy's 3.6 TiB allocation, or 'Maximum allowed size exceeded'): the option is held to a
    scene angle's limit, and a run given such driver values says what its path would take."""
    import numpy as np

    from linkage_sym.errors import SceneError
    from linkage_sym.numeric.plan import compile_plan

    p = run("centres", CRANK_ROCKER, "--deg", "1e12")
    assert p.returncode == 2 and "Traceback" not in p.stderr, p.stderr
    assert p.stderr.startswith("linkage-sym centres: --deg: an angle must be within +-1e+06 degrees")
    assert run("centres", CRANK_ROCKER, "--deg", "3630").returncode == 0  # ten turns: solved
    plan = compile_plan(linkage_sym.load_example("crank_rocker"))
    one = lambda v: {"A": np.array([v])}  # noqa: E731
    with pytest.raises(SceneError) as err:
        plan.run(q=one(1e10), qd=one(1.0), qdd=one(0.0))
    assert err.value.problems[0].startswith("drivers[0]: the solving path from the assembly")
    assert "would add 2.86e+11 points to the 1 step (at most 1000000)" in err.value.problems[0]


@pytest.mark.slow
@pytest.mark.parametrize("args, message", [
    (["--samples", "BINARY"], "--samples: 'BINARY' is not a text (UTF-8) CSV file: byte 0xff at position 0"),
    (["--monte-carlo", "10", "--tolerance", "l_AB=0.001", "--random-state", "-1"],
     "--random-state: a whole number >= 0 is expected, got -1"),
    (["--monte-carlo", "1000000000000", "--tolerance", "l_AB=0.001"],
     "--monte-carlo: 1000000000000 designs do not fit in memory"),
    (["--vary", "l_AB=0.02:0.03:1000000000000"], "--vary: 1000000000000 designs do not fit in memory"),
    (["--vary", "l_AB=0.02:0.03:1000000", "--vary", "l_BC=0.05:0.06:1000000"],
     "--vary: 1000000000000 designs do not fit in memory"),
    (["--vary", "l_AB=0.02:0.03:3", "--dask", ""], "--dask: '' is not a scheduler address"),
])
def test_malformed_sweep_options_are_refused_by_name(tmp_path, args, message):
    (tmp_path / "BINARY").write_bytes(b"\xff\xfe\x00l_AB\n")
    pytest.importorskip("dask.distributed") if "--dask" in args else None
    p = run("sweep", small_scene(tmp_path), *args, cwd=tmp_path)
    assert p.returncode == 2 and "Traceback" not in p.stderr, p.stderr
    assert p.stderr.startswith(f"linkage-sym sweep: {message}"), p.stderr


@pytest.mark.slow
def test_fuzzed_scenes_are_refused_or_solved_without_a_traceback(tmp_path):
    """Scene files that ended in tracebacks: a gear mesh in a scene without ``links`` (a
    TypeError placing the mesh), JSON nested 100,000 deep (RecursionError), a name with a
    NUL and a slash used for plot files (ValueError of the file system), and a slider-crank
    whose sweep ends exactly at the coupler's tangency, run at 20 digits (mpmath's complex
    square root reached atan2)."""
    gears = example_dict("gear_linkage")
    del gears["links"]
    (tmp_path / "gears.json").write_text(json.dumps(gears))
    (tmp_path / "deep.json").write_text("[" * 100_000 + "]" * 100_000)
    named = example_dict("crank_rocker")
    named["name"] = "a/b\\c\n..\x00z"
    named["drivers"][0]["steps"] = 5
    (tmp_path / "named.json").write_text(json.dumps(named))
    tangent = {
        "name": "slider-crank", "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "slider"}],
        "joints": [{"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
                   {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": [0.02, 0.0]},
                   {"name": "C", "type": "R", "links": ["coupler", "slider"], "at": [0.03, 0.0]},
                   {"name": "G", "type": "P", "links": ["ground", "slider"], "at": [0.03, 0.0],
                    "axis_deg": 0.0}],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": 150, "stop_deg": 210, "steps": 5,
                     "speed": 1.0}],
        "outputs": ["kinematics"]}
    (tmp_path / "tangent.json").write_text(json.dumps(tangent))

    p = run("analyze", str(tmp_path / "gears.json"))
    assert p.returncode == 2 and "Traceback" not in p.stderr, p.stderr
    assert "links: required key is missing" in p.stderr
    for command in ("analyze", "structure"):
        p = run(command, str(tmp_path / "deep.json"))
        assert p.returncode == 2 and "Traceback" not in p.stderr, p.stderr
        assert "invalid JSON for a scene: nested deeper than Python's JSON reader goes" in p.stderr
    p = run("analyze", str(tmp_path / "named.json"), "--plots", str(tmp_path / "plots"))
    assert p.returncode == 0, p.stderr
    assert "a_b_c_.._z_positions.png" in files_under(tmp_path / "plots")
    p = run("analyze", str(tmp_path / "tangent.json"), "--precision", "20", "-o",
            str(tmp_path / "t.json"))
    assert p.returncode == 0 and "Traceback" not in p.stderr, p.stderr
    steps = json.loads((tmp_path / "t.json").read_text())["steps"]
    # the float64 run took the ends' tangency; at 20 digits the coupler misses the slide there
    assert [s["status"] for s in steps] == ["unassemblable", "ok", "ok", "ok", "unassemblable"]
    assert steps[0]["message"].startswith("no real position at 20 digits")


@pytest.mark.slow
def test_scene_rows_beyond_the_designs_are_refused_without_listing_them(tmp_path):
    """``--scene-rows 0:99999999999999`` listed 10^14 numbers (MemoryError) and a number over
    2^63 overflowed numpy's int; both name the first design that does not exist."""
    scene = small_scene(tmp_path)
    for rows, first in (("0:99999999999999", 3), ("99999999999999999999999", 99999999999999999999999)):
        p = run("sweep", scene, "--vary", "l_AB=0.02:0.03:3", "--write-scenes",
                str(tmp_path / "ws"), f"--scene-rows={rows}")
        assert p.returncode == 2 and "Traceback" not in p.stderr, p.stderr
        assert p.stderr.startswith(f"linkage-sym sweep: --scene-rows: no design {first}: the designs are 0 to 2")


def test_a_load_schedule_with_an_invalid_period_names_it(tmp_path):
    """A table schedule whose ``period_deg`` is NaN: the period was reported, then the table
    was held to a period of None (TypeError)."""
    d = example_dict("engine_four_stroke")
    [load] = [ld for ld in d["loads"] if "table" in ld]
    load["period_deg"] = float("nan")
    (tmp_path / "s.json").write_text(json.dumps(d))  # Python's json writes NaN, and reads it
    i = d["loads"].index(load)
    p = run("analyze", str(tmp_path / "s.json"))
    assert p.returncode == 2 and "Traceback" not in p.stderr, p.stderr
    assert f"loads[{i}].period_deg: must be a finite number >= 0, got NaN" in p.stderr


@pytest.mark.slow
def test_closed_or_ascii_standard_output_ends_without_a_traceback():
    """Started with standard output closed (``>&-``: ``sys.stdout`` is None) the final flush
    raised AttributeError; an ASCII-only standard output could not take '°' or '·'."""
    import os

    p = subprocess.run([sys.executable, "-m", "linkage_sym", "analyze", CRANK_ROCKER],
                       capture_output=False, stderr=subprocess.PIPE, text=True,
                       preexec_fn=lambda: os.close(1))
    assert p.returncode == 0 and "Traceback" not in p.stderr, p.stderr
    env = dict(os.environ, PYTHONIOENCODING="ascii", LC_ALL="C")
    p = subprocess.run([sys.executable, "-m", "linkage_sym", "analyze", CRANK_ROCKER],
                       capture_output=True, text=True, env=env)
    assert p.returncode == 0 and "Traceback" not in p.stderr, p.stderr
    assert "N\\xb7m" in p.stdout  # escaped, not fatal


@pytest.mark.slow
def test_analyze_replaces_files_not_devices_pipes_or_links(tmp_path):
    """``analyze`` writes a temporary file and renames it over ``-o``: a named pipe (or a
    device, /dev/full as root) was replaced by a regular file, and a symbolic link by the
    result while the file it named kept its old text."""
    import os

    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    p = run("analyze", small_scene(tmp_path), "-o", str(fifo))
    assert p.returncode == 2 and "is not a regular file (a device, pipe or socket)" in p.stderr
    assert not fifo.is_file() and fifo.exists()
    real, link = tmp_path / "real.json", tmp_path / "link.json"
    real.write_text("old")
    link.symlink_to(real)
    assert run("analyze", small_scene(tmp_path), "-o", str(link)).returncode == 0
    assert link.is_symlink() and json.loads(real.read_text())["scene"] == "crank-rocker"


@pytest.mark.slow
def test_samples_header_problems_name_samples_and_a_bom_is_no_name(tmp_path):
    """An unknown column of ``--samples`` was reported as ``--vary``; a spreadsheet's UTF-8
    byte-order mark became part of the first name ('\\ufeffl_AB')."""
    (tmp_path / "bom.csv").write_bytes(b"\xef\xbb\xbfl_AB\n0.024\n0.025\n")
    (tmp_path / "unknown.csv").write_text("l_XY\n0.024\n")
    scene = small_scene(tmp_path)
    p = run("sweep", scene, "--samples", str(tmp_path / "bom.csv"))
    assert p.returncode == 0, p.stderr
    p = run("sweep", scene, "--samples", str(tmp_path / "unknown.csv"))
    assert p.returncode == 2 and "Traceback" not in p.stderr, p.stderr
    assert p.stderr.startswith("linkage-sym sweep: --samples: unknown parameter 'l_XY'")


# -- standard output closed (>&-) for every command ----------------------------------------

_CLOSED_DRIVER = r"""
import json, os, sys, traceback
from linkage_sym.cli import main
results = []
for argv in json.loads(sys.argv[1]):
    try:
        os.close(1)  # as a shell's >&- leaves it: descriptor 1 closed ...
    except OSError:
        pass
    sys.stdout = None  # ... and no sys.stdout
    try:
        code = main(argv)
    except BaseException:  # what the test reports, by command
        traceback.print_exc()
        code = "traceback"
    results.append([argv, code])
sys.stderr.write("RESULTS " + json.dumps(results) + "\n")
"""


def _closed_stdout_commands(tmp_path):
    from linkage_sym.synthesis import builders

    scene = small_scene(tmp_path)
    rows = []
    for phi in (60, 100, 140):
        j = builders.fourbar(1.0, 3.0, 3.0, 3.5, crank_deg=phi).scene["joints"]
        rows.append([*j[1]["at"], *j[2]["at"]])
    (tmp_path / "positions.json").write_text(json.dumps(rows))
    motor = example_dict("crank_rocker_motor")  # a short simulation: two samples after the start
    motor["simulate"].update(duration=0.02, samples=3)
    (tmp_path / "motor.json").write_text(json.dumps(motor))
    (tmp_path / "poses.json").write_text(json.dumps(
        [[0.0, 0.0, 0.0], [0.02, 0.01, 10.0], [0.035, 0.025, 25.0], [0.04, 0.045, 40.0]]))
    (tmp_path / "points.json").write_text(json.dumps([[0.0, 0.0], [0.01, 0.005], [0.02, 0.0]]))
    out = str(tmp_path / "out")
    cr = ["--K", "1.5", "--rocker", "0.075", "--swing-deg", "45", "--ground", "0.1"]
    return [
        ["analyze", scene], ["analyze", scene, "-o", "-"],
        ["analyze", scene, "-o", f"{out}/r.json"],
        ["derive", scene], ["derive", scene, "--latex", "-o", "-"],
        ["derive", scene, "-o", f"{out}/d.txt"],
        ["structure", scene], ["examples"],
        ["demo", "-o", f"{out}/demo", "--example", "crank_rocker"],
        ["new", "fourbar", "--crank", "1", "--coupler", "3", "--rocker", "3", "--ground", "4",
         "-o", "-"],
        ["new", "slider-crank", "--crank", "1", "--coupler", "3", "-o", "-"],
        ["new", "guide-bar", "--crank", "0.03", "--ground", "0.06", "-o", "-"],
        ["synthesize", "crank-rocker", *cr, "-o", "-"], ["synthesize", "crank-rocker", *cr],
        ["synthesize", "slider-crank", "--K", "1.4", "--stroke", "0.1", "--offset", "0.02",
         "-o", "-"],
        ["synthesize", "guide-bar", "--K", "2", "--ground", "0.4", "-o", "-"],
        ["synthesize", "coupler-positions", "--positions", str(tmp_path / "positions.json"),
         "-o", "-"],
        ["synthesize", "equations"], ["synthesize", "equations", "--latex", "-o", "-"],
        ["balance", scene], ["balance", scene, "-o", "-"],
        ["balance", scene, "--balanced-scene", f"{out}/b.json"],
        ["centres", scene, "--step", "3"], ["centres", scene, "--step", "3", "-o", "-"],
        ["sweep", scene, "--list"], ["sweep", scene, "--vary", "l_AB=0.02:0.03:3"],
        ["sweep", scene, "--vary", "l_AB=0.02:0.03:3", "-o", "-"],
        ["animate", scene, "-o", f"{out}/m.gif", "--frames", "2"],
        ["view", scene, "-o", f"{out}/p.html"], ["view", scene, "-o", "-"],
        ["simulate", str(tmp_path / "motor.json"), "-o", "-"],
        ["flywheel", str(tmp_path / "motor.json"), "--fluctuation", "0.2", "-o", "-"],
        ["synthesize", "motion", "--poses", str(tmp_path / "poses.json"), "-o", f"{out}/motion"],
        ["synthesize", "function", "--function", "x", "--x-range", "1,2", "--phi-range", "30,120",
         "--psi-range", "240,330", "-o", "-"],
        ["synthesize", "path", "--points", str(tmp_path / "points.json"), "-o", f"{out}/path"],
    ]


@pytest.mark.slow
def test_every_command_runs_with_standard_output_closed(tmp_path):
    """Started with standard output closed (``>&-``), derive, synthesize, new, balance,
    centres -o - and sweep -o - ended in AttributeError ('NoneType' object has no attribute
    'write'): ``main`` now gives every command a standard output that discards, the way a
    redirection to /dev/null would.  Each command runs as a shell's ``>&-`` leaves it
    (descriptor 1 closed, ``sys.stdout`` None), the first in a process started so."""
    import os
    from linkage_sym.cli import build_parser

    commands = _closed_stdout_commands(tmp_path)
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    covered = {argv[0] for argv in commands}
    assert covered == set(sub.choices)  # every command of the command line
    for kind in ("new", "synthesize"):
        kinds = next(a for a in sub.choices[kind]._actions if a.choices and a.dest != "help")
        assert {argv[1] for argv in commands if argv[0] == kind} == set(kinds.choices)
    env = dict(os.environ, PYTHONPATH=str(Path(linkage_sym.__file__).parent.parent))
    p = subprocess.run([sys.executable, "-c", _CLOSED_DRIVER, json.dumps(commands)],
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                       cwd=tmp_path, env=env, preexec_fn=lambda: os.close(1))
    assert "RESULTS " in p.stderr, p.stderr[-3000:]
    results = json.loads(p.stderr.split("RESULTS ", 1)[1])
    failed = [(argv, code) for argv, code in results if code != 0]
    assert not failed and "Traceback" not in p.stderr, (failed, p.stderr[-3000:])
    assert len(results) == len(commands)
    for name in ("r.json", "d.txt", "b.json", "m.gif"):  # files asked for are still written
        assert (tmp_path / "out" / name).stat().st_size > 0


@pytest.mark.slow
def test_a_shell_closing_standard_output_gets_no_traceback(tmp_path):
    """The same through a shell's own ``>&-`` (not a descriptor closed by the test)."""
    import os

    env = dict(os.environ, PYTHONPATH=str(Path(linkage_sym.__file__).parent.parent))
    p = subprocess.run(["sh", "-c", 'exec "$@" >&-', "sh", sys.executable, "-m", "linkage_sym",
                        "derive", small_scene(tmp_path)],
                       stdin=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=env)
    assert p.returncode == 0 and p.stderr == "", p.stderr


@pytest.mark.slow
def test_a_cache_path_under_a_file_warns_and_the_run_goes_on(tmp_path):
    """``LINKAGE_SYM_CACHE`` under a file ended ``analyze --method symbolic`` with exit 1
    ('Not a directory'); it now warns once and runs without the disk cache."""
    import os

    (tmp_path / "blocker").write_text("x")
    env = dict(os.environ, LINKAGE_SYM_CACHE=str(tmp_path / "blocker" / "cache"))
    p = subprocess.run([sys.executable, "-m", "linkage_sym", "analyze", small_scene(tmp_path),
                        "--method", "symbolic"], capture_output=True, text=True, env=env)
    assert p.returncode == 0, p.stderr
    assert p.stderr.count("cannot be used") == 1 and "running without it" in p.stderr
    assert "13 steps: 13 ok" in p.stdout


_CR = ["--K", "1.5", "--rocker", "0.075", "--swing-deg", "45", "--ground", "0.1"]


@pytest.mark.parametrize("args, option", [
    (["analyze", "SCENE", "-o", ""], "-o/--output"),
    (["analyze", "SCENE", "--plots", ""], "--plots"),
    (["derive", "SCENE", "-o", ""], "-o/--output"),
    (["demo", "--example", "crank_rocker", "-o", ""], "-o/--output"),
    (["new", "guide-bar", "--crank", "0.03", "--ground", "0.06", "-o", ""], "-o/--output"),
    (["synthesize", "crank-rocker", *_CR, "-o", ""], "-o/--output"),
    (["synthesize", "equations", "-o", ""], "-o/--output"),
    (["balance", "SCENE", "-o", ""], "-o/--output"),
    (["balance", "SCENE", "--plots", ""], "--plots"),
    (["balance", "SCENE", "--balanced-scene", ""], "--balanced-scene"),
    (["balance", "SCENE", "--optimize", ""], "--optimize"),
    (["centres", "SCENE", "--step", "1", "-o", ""], "-o/--output"),
    (["centres", "SCENE", "--step", "1", "--plots", ""], "--plots"),
    (["sweep", "SCENE", "--vary", "l_AB=0.02:0.03:2", "-o", ""], "-o/--output"),
    (["sweep", "SCENE", "--vary", "l_AB=0.02:0.03:2", "--plots", ""], "--plots"),
    (["sweep", "SCENE", "--vary", "l_AB=0.02:0.03:2", "--write-scenes", ""], "--write-scenes"),
    (["animate", "SCENE", "-o", ""], "-o/--output"),
])
def test_an_empty_path_is_refused_by_every_path_option(tmp_path, monkeypatch, capsys, args,
                                                        option):
    """``--plots ""``, ``demo -o ""`` and ``sweep --write-scenes ""`` wrote into the current
    folder while ``-o ""`` was refused as 'a folder': one check now refuses an empty path
    for every output option, naming it, before anything is written."""
    scene = small_scene(tmp_path)
    work = tmp_path / "cwd"
    work.mkdir()
    monkeypatch.chdir(work)
    assert main([scene if a == "SCENE" else a for a in args]) == 2
    err = capsys.readouterr().err
    assert f"{option}: an empty path" in err, err
    assert files_under(work) == []
