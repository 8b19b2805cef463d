"""Every notebook (kept as jupytext py:percent text) runs to the end in a Jupyter kernel
(nbclient), and draws: each produces at least one figure."""

import pytest

import build  # notebooks/build.py (pyproject: pythonpath)
from tests.support.marks import slow_cases


@pytest.mark.parametrize("path", slow_cases(build.notebook_sources(), {
    p.stem for p in build.notebook_sources()} - {"kinematics_fourbar"}, key=lambda p: p.stem),
    ids=lambda p: p.stem)
def test_notebook_runs_and_draws(path):
    nb = build.execute(path)
    kinds = [k for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])
             for k in o.get("data", {})]
    assert "image/png" in kinds, f"{path.stem}: no figure"


def test_the_notebooks_are_found():
    assert {p.stem for p in build.notebook_sources()} >= {
        "kinematics_fourbar", "symbolic_fourbar_slider", "balancing_fourbar_sixbar"}
