"""Sphinx configuration of the linkage_sym documentation.

Build (warnings are errors)::

    python -m sphinx -W --keep-going -b html docs docs/_build/html

Sphinx with MyST rather than MkDocs: the API reference comes from numpydoc docstrings, which
Sphinx's autodoc and numpydoc render as written, and the field's libraries (SymPy, PyDy,
python-control, scikit-rf) document themselves this way; MyST keeps the pages in Markdown,
and myst-nb renders the jupytext notebooks with their outputs.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
# the notebooks' kernels import the package and the paper reproductions' scripts by plain name
# (as tests/paper does); they run in docs/tutorials, so the paths are given here
os.environ["PYTHONPATH"] = os.pathsep.join(
    [str(HERE.parent), str(HERE.parent / "paper_repro"), os.environ.get("PYTHONPATH", "")])
sys.path.insert(0, str(HERE / "_ext"))

from linkage_sym import __version__  # noqa: E402

project = "linkage_sym"
author = "the linkage_sym authors"
copyright = "the linkage_sym authors"
release = version = __version__

extensions = [
    "myst_nb",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "linkage_docs",
]

source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".py": "myst-nb"}
# the tutorials are the jupytext (py:percent) notebooks of notebooks/, linked into tutorials/
nb_custom_formats = {".py": ["jupytext.reads", {"fmt": "py:percent"}]}
# executed once and cached (docs/_build/.jupyter_cache): a rebuild re-runs only a changed notebook
nb_execution_mode = "cache"
nb_execution_cache_path = str(HERE / "_build" / ".jupyter_cache")
nb_execution_timeout = 600
nb_execution_raise_on_error = True
nb_execution_show_tb = True

exclude_patterns = ["_build", "_ext", "conf.py", "**/.ipynb_checkpoints", "gallery/_files/**"]

myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 4

autodoc_default_options = {"members": True, "undoc-members": False}
autodoc_typehints = "none"
autosummary_generate = False
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_validation_checks: set[str] = set()

# option names stay as typed: no "--" turned into a dash, no curly quotes
smartquotes = False

html_theme = "alabaster"
html_title = f"linkage_sym {release}"
html_theme_options = {"page_width": "1100px", "sidebar_width": "240px"}
