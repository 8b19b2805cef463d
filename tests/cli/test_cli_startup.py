"""The command line starts without the libraries its command does not need.

``--version`` and the help import neither NumPy, SciPy, SymPy, Matplotlib nor the design
package (``sweep --help`` only its list of metric names);
``analyze`` of a kinematics-only scene imports neither SymPy nor Matplotlib, nor SciPy,
``numpy.ma``, the force layer or the cam and gear solvers (:data:`NOT_FOR_KINEMATICS`).  Each case
runs in a fresh interpreter (this one has them all loaded) and prints what it loaded.
"""

import json
import subprocess
import sys
from pathlib import Path

import pytest

from tests.support.marks import fast_cases

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("scipy", "sympy", "matplotlib", "linkage_sym.design")


def loaded_after(argv, watched=HEAVY):
    """The modules of ``watched`` in ``sys.modules`` after ``main(argv)`` in a fresh process."""
    code = (
        "import contextlib, io, json, sys\n"
        "from linkage_sym.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    try:\n"
        f"        code = main({list(argv)!r})\n"
        "    except SystemExit as e:\n"
        "        code = e.code\n"
        f"print(json.dumps([code, [m for m in {list(watched)!r} if m in sys.modules]]))\n"
    )
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout.strip().splitlines()[-1])


# a Python process each: four in the fast lane, every command's help in the default run
@pytest.mark.parametrize("argv", fast_cases([
    ["--version"], ["--help"], ["analyze", "--help"], ["derive", "--help"],
    ["structure", "--help"], ["demo", "--help"], ["examples", "--help"],
    ["new", "fourbar", "--help"], ["synthesize", "crank-rocker", "--help"],
    ["balance", "--help"], ["centres", "--help"], ["animate", "--help"],
    ["view", "--help"],
], {"--version", "--help", "analyze --help", "view --help"}, key=" ".join))
def test_version_and_help_import_no_library(argv):
    code, loaded = loaded_after(argv, HEAVY + ("numpy",))
    assert code == 0
    assert loaded == []


def test_sweep_help_lists_the_metrics_without_the_sweep_machinery():
    """The help names the metrics (linkage_sym.design.names, which imports nothing)."""
    code, loaded = loaded_after(["sweep", "--help"], ("numpy", "scipy", "sympy", "matplotlib",
                                                      "linkage_sym.design.api",
                                                      "linkage_sym.design.metrics"))
    assert code == 0
    assert loaded == []


NOT_FOR_KINEMATICS = (
    "scipy",  # no part of it: the numeric path is NumPy only
    "numpy.ma",  # np.unique's masked-array check loads it (a sixth of the start-up)
    "linkage_sym.numeric.forces.kinetostatics", "linkage_sym.numeric.forces.superposition",
    "linkage_sym.numeric.forces.statics",  # the force layer: a scene that asks for forces
    "linkage_sym.numeric.kinematics.cams", "linkage_sym.numeric.kinematics.gears",  # cams, gears
    "tempfile", "zipfile",  # an npz written
)
"""What a kinematics-only ``analyze`` of a four-bar does not need, besides SymPy and Matplotlib."""


def test_analyze_of_kinematics_imports_neither_sympy_nor_matplotlib(tmp_path):
    scene = json.loads((ROOT / "linkage_sym" / "examples" / "crank_rocker.json").read_text())
    scene["outputs"] = ["kinematics"]
    path = tmp_path / "kinematics.json"
    path.write_text(json.dumps(scene))
    code, loaded = loaded_after(["analyze", str(path)],
                                ("sympy", "matplotlib", "linkage_sym.design", "scipy.interpolate",
                                 "scipy.sparse", *NOT_FOR_KINEMATICS))
    assert code == 0
    assert loaded == []
