"""The README's Quick start: exactly two commands, the second is what CI runs."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def quick_start_commands():
    text = (ROOT / "README.md").read_text()
    section = re.search(r"^## quick start\n(.*?)^## ", text, re.S | re.M | re.I).group(1)
    block = re.search(r"```(?:\w+)?\n(.*?)```", section, re.S).group(1)
    return [ln for ln in block.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]


def test_two_commands():
    cmds = quick_start_commands()
    assert len(cmds) == 2
    assert "demo" in cmds[0] and "pytest" in cmds[1]


def test_ci_runs_the_readme_test_command():
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    assert quick_start_commands()[1] in ci


def test_readme_is_the_front_door():
    """Under 300 lines; the reference, design notes and benchmarks live in docs/ pages, and
    every link of the README into the repository names a file that exists."""
    text = (ROOT / "README.md").read_text()
    assert len(text.splitlines()) < 300
    targets = re.findall(r"\]\(((?!https?:|#)[^)#]+)(?:#[^)]*)?\)", text)
    assert any(t.startswith("docs/") for t in targets)
    for target in targets:
        assert (ROOT / target).exists(), target


def test_the_readme_sections_that_moved_are_docs_pages():
    """What the README held before it became the front door, each in a page of docs/."""
    pages = {"usage.md": "# Using it", "checks.md": "# How results are checked",
             "speed.md": "# Speed", "accuracy.md": "# What accuracy costs",
             "sweeps.md": "# Design sweeps", "roadmap.md": "# Roadmap",
             "kinematics.md": "## Kinematics: what is solved how",
             "kinetostatics.md": "## Motion: motors, simulation and flywheel",
             "symbolic.md": "## Symbolic layer: what is derived how",
             "balancing.md": "## Balancing: what is derived how",
             "synthesis.md": "## Synthesis: linkages from what the designer wants"}
    for page, heading in pages.items():
        assert heading in (ROOT / "docs" / page).read_text(), page
