"""Library messages name the library's arguments and functions; the command line says its own
options and commands for them (``linkage_sym.cli.common``: ``OPTIONS``, ``COMMAND_POINTERS``).

Each test takes one message both ways: raised by the library, it names no option (``--``) nor
command (``linkage-sym``); printed by the command line, it names the option or command.
"""

from __future__ import annotations

import re
import sys

import pytest

import linkage_sym
from linkage_sym import output
from linkage_sym.cli import main
from linkage_sym.design.errors import SweepError
from linkage_sym.errors import SceneError
from linkage_sym.examples import example_path
from linkage_sym.numeric.plan import compile_plan
from linkage_sym.structure import structure_report

COMMAND_WORDS = re.compile(r"--[a-z]|linkage-sym")


def _library_text(err) -> str:
    text = str(err)
    assert not COMMAND_WORDS.search(text), text
    return text


def _cli_err(capsys, *args) -> str:
    assert main(list(args)) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return err


def _hide_pyarrow(monkeypatch):
    monkeypatch.setitem(sys.modules, "pyarrow", None)  # import pyarrow -> ImportError
    monkeypatch.setitem(sys.modules, "pyarrow.parquet", None)


def test_a_format_that_cannot_be_written(capsys, monkeypatch, tmp_path):
    with pytest.raises(output.OutputError) as err:
        output.output_format(None, "xml")
    assert _library_text(err.value) == "format: 'xml' is not one of json, csv, npz, parquet"
    assert err.value.field == "format"
    _hide_pyarrow(monkeypatch)
    with pytest.raises(output.OutputError) as err:
        output.require_pyarrow()
    assert _library_text(err.value).startswith("format: parquet needs pyarrow")
    cli = _cli_err(capsys, "analyze", str(example_path("crank_rocker")),
                   "-o", str(tmp_path / "r.parquet"))
    assert cli.startswith("linkage-sym analyze: --format: parquet needs pyarrow"), cli


def test_the_whole_sweep_kept_for_plots(tmp_path):
    """The command line's half (``--plots``): test_output_formats.py's
    test_too_large_runs_are_refused_before_anything_is_written."""
    sweep = output.plan_sweep(compile_plan(linkage_sym.load_example("crank_rocker")))
    with pytest.raises(output.OutputError) as err:
        output.write_sweep(sweep, None, "json", keep=True, memory=output.FIXED_BYTES + 1000)
    assert _library_text(err.value).startswith("keep: not enough memory: the whole sweep")
    assert err.value.field == "keep"


def test_a_path_that_is_not_a_regular_file(tmp_path):
    """The command line refuses it before (its check of -o/--output); the library names its
    own argument."""
    sweep = output.plan_sweep(compile_plan(linkage_sym.load_example("crank_rocker")))
    (tmp_path / "folder").mkdir()
    with pytest.raises(output.OutputError) as err:
        output.write_sweep(sweep, str(tmp_path / "folder"), "json")
    assert _library_text(err.value).startswith(f"path: {str(tmp_path / 'folder')!r} is not a "
                                               "regular file")


def test_a_binary_format_to_a_text_stream():
    import io

    sweep = output.plan_sweep(compile_plan(linkage_sym.load_example("crank_rocker")))
    with pytest.raises(output.OutputError) as err:
        output.write_sweep(sweep, None, "npz", stream=io.StringIO())
    assert _library_text(err.value) == "format: npz is a binary format: give a path, not a text stream"


def test_the_symbolic_method_and_cams(capsys):
    path = example_path("cam_eccentric_rocker")
    with pytest.raises(SceneError) as err:
        linkage_sym.analyze(linkage_sym.load_scene(path), method="symbolic")
    assert _library_text(err.value).endswith("the numeric methods do (method 'dyad' or 'global')")
    cli = _cli_err(capsys, "analyze", str(path), "--method", "symbolic")
    assert cli.rstrip().endswith("the numeric methods do (--method dyad or global)"), cli


def test_a_command_without_a_method_option_names_analyze(capsys):
    """``derive`` has no ``--method``: its refusal of a cam names the command that has one."""
    cli = _cli_err(capsys, "derive", str(example_path("cam_eccentric_rocker")))
    assert cli.rstrip().endswith(
        "the numeric methods do (linkage-sym analyze --method dyad or global)"), cli


def test_the_disconnection_choices_of_a_complex_group(capsys):
    path = example_path("sixbar_class3")
    scene = linkage_sym.load_scene(path)
    text = structure_report(scene, linkage_sym.decompose(scene))
    assert "pick one with disconnection=K)" in text and not COMMAND_WORDS.search(text)
    assert main(["structure", str(path)]) == 0
    assert "pick one with --disconnection K)" in capsys.readouterr().out
    with pytest.raises(SceneError) as err:
        compile_plan(scene, 99)
    assert _library_text(err.value).endswith(
        "in the order linkage_sym.structure.structure_report lists them)")
    cli = _cli_err(capsys, "analyze", str(path), "--disconnection", "99")
    assert cli.startswith("linkage-sym analyze: --disconnection: choice 99 of group"), cli
    assert cli.rstrip().endswith("in the order `linkage-sym structure` lists them)"), cli


def test_an_unknown_design_parameter(capsys):
    scene = linkage_sym.load_example("crank_rocker")
    with pytest.raises(SweepError) as err:
        linkage_sym.sweep(scene, {"l_XY": [1.0]})
    assert _library_text(err.value).endswith(
        "(linkage_sym.design.scene_parameters(scene) lists them with their values)")
    cli = _cli_err(capsys, "sweep", str(example_path("crank_rocker")), "--vary", "l_XY=1,2")
    assert cli.startswith("linkage-sym sweep: --vary: unknown parameter 'l_XY'"), cli
    assert cli.rstrip().endswith("(`linkage-sym sweep SCENE --list` prints them with their "
                                 "values)"), cli


def test_a_design_sweep_of_gear_meshes(capsys):
    path = example_path("gear_linkage")
    with pytest.raises(SweepError) as err:
        linkage_sym.sweep(linkage_sym.load_scene(path), {"l_BC": [0.3, 0.31]})
    assert _library_text(err.value).endswith("; linkage_sym.analyze solves one design")
    cli = _cli_err(capsys, "sweep", str(path), "--vary", "l_BC=0.3,0.31")
    assert cli.rstrip().endswith("; `linkage-sym analyze` solves one design"), cli


def test_a_stroke_time_ratio_of_one(capsys, tmp_path):
    from linkage_sym.synthesis import kratio
    from linkage_sym.synthesis.common import SynthesisError

    with pytest.raises(SynthesisError) as err:
        kratio.guide_bar(1.0, 0.4)
    assert _library_text(err.value).endswith("from its dimensions (linkage_sym.synthesis.builders)")
    cli = _cli_err(capsys, "synthesize", "guide-bar", "--K", "1", "--ground", "0.4",
                   "-o", str(tmp_path / "never.json"))
    assert cli.startswith("linkage-sym synthesize: --K: K = 1 means no quick return"), cli
    assert cli.rstrip().endswith("from its dimensions ('linkage-sym new')"), cli
