"""Architecture contracts: the numeric core never imports SymPy or Matplotlib.

Checked two ways: import-linter's contracts in pyproject.toml, and a fresh
interpreter that runs a whole analysis and then looks at ``sys.modules``.
"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


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


@pytest.mark.slow
def test_cached_mechanism_loads_and_runs_without_sympy(tmp_path):
    """A second process runs the symbolic method from the disk cache with NumPy only."""
    env = {**os.environ, "LINKAGE_SYM_CACHE": str(tmp_path)}
    first = (
        "import linkage_sym\n"
        "linkage_sym.compile_mechanism(linkage_sym.load_example('crank_rocker'))\n"
    )
    p = subprocess.run([sys.executable, "-c", first], capture_output=True, text=True, cwd=ROOT, env=env)
    assert p.returncode == 0, p.stderr
    assert len(list(tmp_path.glob("*.json"))) == 1
    second = (
        "import sys, linkage_sym\n"
        "from linkage_sym.codegen.runtime import load_compiled\n"
        "cm = load_compiled(linkage_sym.load_example('crank_rocker'))\n"
        "r = cm.run()\n"
        "print(r.forces.method, 'sympy' in sys.modules, 'matplotlib' in sys.modules)\n"
    )
    p = subprocess.run([sys.executable, "-c", second], capture_output=True, text=True, cwd=ROOT, env=env)
    assert p.returncode == 0, p.stderr
    assert p.stdout.split() == ["symbolic", "False", "False"]
