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


def _import_graph(package: Path) -> dict:
    """``module -> modules of the package it imports``, from the source (``ast``).

    Every ``import`` statement counts, at module level or inside a function (a
    lazy import still ties the two modules), except those under ``if
    TYPE_CHECKING:``, which never run.  ``from p import name`` is an edge to the
    module ``p.name`` when there is one, else to ``p``; a package's
    ``__init__`` is the module of the package's own name.
    """
    import ast

    modules = {}
    for path in package.rglob("*.py"):
        parts = list(path.relative_to(package.parent).with_suffix("").parts)
        is_package = parts[-1] == "__init__"
        modules[".".join(parts[:-1] if is_package else parts)] = (path, is_package)

    def imports(node, found):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and "TYPE_CHECKING" in ast.unparse(child.test):
                for other in child.orelse:
                    imports(other, found)
                continue
            if isinstance(child, ast.Import):
                found.extend(a.name for a in child.names)
            elif isinstance(child, ast.ImportFrom):
                found.append((child.level, child.module, [a.name for a in child.names]))
            imports(child, found)
        return found

    graph = {}
    for name, (path, is_package) in modules.items():
        here = name if is_package else name.rpartition(".")[0]
        edges = set()
        for item in imports(ast.parse(path.read_text(encoding="utf-8")), []):
            if isinstance(item, str):
                edges.add(item)
                continue
            level, module, names = item
            if level:
                base = ".".join(here.split(".")[: len(here.split(".")) - level + 1])
                module = f"{base}.{module}" if module else base
            edges.update(f"{module}.{n}" if f"{module}.{n}" in modules else module for n in names)
        graph[name] = sorted(e for e in edges if e in modules and e != name)
    return graph


def _cycles(graph: dict) -> list:
    """The strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in graph:
        if v not in index:
            visit(v)
    return found


@pytest.mark.slow
def test_no_import_cycle():
    """No module of linkage_sym imports, directly or through others, a module that imports it."""
    graph = _import_graph(ROOT / "linkage_sym")
    assert "linkage_sym.numeric.plan" in graph["linkage_sym.numeric.extremes"]  # a lazy import counts
    assert _cycles(graph) == []


def test_cycle_finder_finds_a_cycle():
    graph = {"a": ["b"], "b": ["c"], "c": ["a"], "d": ["a"]}
    assert _cycles(graph) == [["a", "b", "c"]]
