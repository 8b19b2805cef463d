"""``linkage-sym view``: the page written, options and scenes refused with nothing written."""

import subprocess
import sys

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


def test_a_cam_scene_is_refused_naming_the_joint(tmp_path):
    out = tmp_path / "cam.html"
    p = run("view", str(example_path("cam_eccentric_rocker")), "-o", str(out))
    assert p.returncode == 2
    assert "joint 'K'" in p.stderr and "cam" in p.stderr
    assert "Traceback" not in p.stderr
    assert not out.exists()


def test_view_to_standard_output(capsys):
    """``-o -``: the page itself on standard output (nothing else there)."""
    assert main(["view", str(example_path("slider_crank_offset")), "-o", "-"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("<!DOCTYPE html>") and out.rstrip().endswith("</html>")
