"""Build the notebooks: each jupytext text here becomes an executed ``.ipynb`` with its outputs.

    python notebooks/build.py            # every notebook
    python notebooks/build.py NAME ...   # some (file stems)

Needs the ``notebooks`` extra (``pip install '.[notebooks]'``: jupytext, nbclient, ipykernel).
The notebooks are kept as text (jupytext ``py:percent``) so that they diff and review like
code; the ``.ipynb`` files, with their plots and rendered equations, are generated and not
kept in the repository.  ``tests/paper/test_notebooks.py`` executes every notebook the same way.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent


def notebook_sources() -> list[Path]:
    """The jupytext notebooks of this folder (text files with a jupytext header)."""
    return sorted(p for p in HERE.glob("*.py") if p.read_text().startswith("# ---\n# jupyter:"))


def execute(path: Path, timeout: int = 600):
    """The notebook of ``path`` executed in a fresh kernel (its folder as working directory)."""
    import jupytext
    from nbclient import NotebookClient

    nb = jupytext.read(path)
    NotebookClient(nb, timeout=timeout, kernel_name="python3",
                   resources={"metadata": {"path": str(path.parent)}}).execute()
    return nb


def main(argv: list[str]) -> int:
    import nbformat

    paths = notebook_sources()
    if argv:
        unknown = sorted(set(argv) - {p.stem for p in paths})
        if unknown:
            print(f"unknown notebook(s): {', '.join(unknown)}; known: "
                  f"{', '.join(p.stem for p in paths)}", file=sys.stderr)
            return 2
        paths = [p for p in paths if p.stem in argv]
    for path in paths:
        nb = execute(path)
        out = path.with_suffix(".ipynb")
        nbformat.write(nb, out)
        print(f"wrote {out.relative_to(HERE.parent)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
