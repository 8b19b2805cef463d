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
