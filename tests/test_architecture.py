"""Architecture contracts: the numeric core never imports SymPy or Matplotlib.

Checked two ways: import-linter's contracts in pyproject.toml, and a fresh
interpreter that runs a whole analysis and then looks at ``sys.modules``.
"""

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def test_numeric_core_does_not_load_sympy_or_matplotlib():
    code = (
        "import sys, linkage_sym\n"
        "linkage_sym.analyze(linkage_sym.load_example('crank_rocker'))\n"
        "bad = [m for m in ('sympy', 'matplotlib') if m in sys.modules]\n"
        "print(','.join(bad))\n"
    )
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == ""


def test_import_contracts():
    exe = shutil.which("lint-imports") or str(Path(sys.executable).parent / "lint-imports")
    if not Path(exe).exists():
        pytest.skip("import-linter is not installed (it is in the [test] extra)")
    p = subprocess.run([exe], capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stdout + p.stderr
