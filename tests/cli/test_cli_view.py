"""``linkage-sym view``: the page written, options and scenes refused with nothing written."""

import json
import subprocess
import sys

import pytest

from linkage_sym.cli import main
from linkage_sym.examples import example_path


def run(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "linkage_sym", *args], capture_output=True,
                          text=True, cwd=cwd)


def test_view_writes_one_self_contained_page(tmp_path, capsys):
    out = tmp_path / "pages" / "crank.html"
    assert main(["view", str(example_path("crank_rocker")), "-o", str(out)]) == 0
    html = out.read_text()
    assert html.startswith("<!DOCTYPE html>") and html.rstrip().endswith("</html>")
    assert "http://" not in html and "https://" not in html
    assert "<script src" not in html and "<link" not in html
    assert "function positions_0(" in html and "window.linkageSym" in html
    assert f"wrote {out}" in capsys.readouterr().out


def test_view_refuses_another_suffix_naming_the_option(tmp_path):
    out = tmp_path / "page.txt"
    p = run("view", str(example_path("crank_rocker")), "-o", str(out))
    assert p.returncode == 2
    assert "-o/--output" in p.stderr and ".html" in p.stderr
    assert "Traceback" not in p.stderr
    assert not out.exists()


def test_view_needs_the_output_option(tmp_path):
    p = run("view", str(example_path("crank_rocker")), cwd=tmp_path)
    assert p.returncode == 2
    assert "-o/--output" in p.stderr
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow  # about 1-3 s each: the fast lane stays under two minutes
def test_a_cam_scene_writes_a_page_solved_by_the_port(tmp_path):
    """A cam mechanism's page: no generated function, ``cams.js`` and the profile as data."""
    out = tmp_path / "cam.html"
    p = run("view", str(example_path("cam_eccentric_rocker")), "-o", str(out))
    assert p.returncode == 0, p.stderr
    html = out.read_text()
    assert "const LinkageCams" in html and "function positions_0(" not in html
    assert "http://" not in html and "https://" not in html


@pytest.mark.slow  # about 1-3 s each: the fast lane stays under two minutes
def test_a_cam_mechanism_the_page_does_not_solve_is_refused_naming_the_group(tmp_path):
    """An RRP dyad driven by a cam's follower: the page's port solves input links, RRR dyads
    and cam followers only; the refusal names the group and its joints; nothing is written."""
    scene = json.loads(example_path("cam_eccentric_rocker").read_text())
    scene["links"] += [{"name": "c1"}, {"name": "c2"}]
    scene["joints"] += [{"name": "E", "type": "R", "links": ["follower", "c1"], "at": [0.035, 0.015]},
                        {"name": "F", "type": "R", "links": ["c1", "c2"], "at": [0.05, 0.05]},
                        {"name": "G", "type": "P", "links": ["ground", "c2"], "at": [0.08, 0.03],
                         "axis_deg": 0}]
    path = tmp_path / "cam_dyad.json"
    path.write_text(json.dumps(scene))
    out = tmp_path / "cam.html"
    p = run("view", str(path), "-o", str(out))
    assert p.returncode == 2
    assert "dyad RRP group of link(s) c1, c2 (joints E, F, G)" in p.stderr and "cam" in p.stderr
    assert "Traceback" not in p.stderr
    assert not out.exists()


def test_view_to_standard_output(capsys):
    """``-o -``: the page itself on standard output (nothing else there)."""
    assert main(["view", str(example_path("slider_crank_offset")), "-o", "-"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("<!DOCTYPE html>") and out.rstrip().endswith("</html>")


def test_view_embeds_the_warnings_of_the_python_run(tmp_path, capsys):
    """The page opens with the warnings of ``analyze`` of the scene (the guide-slider's joint
    passing through infinity), as JSON in the page's script."""
    from tests.support.parallel_slides import guide_slider

    scene = tmp_path / "gs.json"
    scene.write_text(json.dumps(guide_slider(10)))
    out = tmp_path / "gs.html"
    assert main(["view", str(scene), "-o", str(out)]) == 0
    text = ("dyad PRP (rod, block): the slides of joints A_slide and C_guide become parallel "
            "between A = 1.66667° and A = -1.66667°: joint C passes through infinity there; "
            "at step 5 (reached from step 4) it is on the far side of its slides")
    assert f"const BUILT = {json.dumps([text])};" in out.read_text()
    assert capsys.readouterr().err == ""


def test_view_of_a_scene_the_python_run_refuses_writes_the_page_saying_why(tmp_path, capsys):
    """An assembly at a dead centre: the run fails, the page (where a drag can move the joint
    off it) is written without the run's warnings, the reason on standard error."""
    scene = json.loads(example_path("crank_rocker").read_text())
    scene["joints"][2]["at"] = [0.05, 0.0]  # C on the line of B and D
    path = tmp_path / "dead.json"
    path.write_text(json.dumps(scene))
    out = tmp_path / "dead.html"
    assert main(["view", str(path), "-o", str(out)]) == 0
    assert "const BUILT = null;" in out.read_text()
    err = capsys.readouterr().err
    assert err.startswith("note: the Python run of the scene fails (joints: the assembly "
                          "configuration is a singular position of the dyad RRR")
    assert "the page's warnings panel opens with what its own evaluator finds" in err
