"""The rate matrices printed as block matrices: the grid of blocks, zero blocks shown.

The reference for which blocks are zero is the structure of the position equations
alone: block ``(i, j)`` of ``A = dPhi/dx`` is zero exactly where no equation of group
``i`` uses a coordinate of group ``j`` (a zero derivative of a used coordinate is not
possible for these loop equations: each coordinate enters through a sine or cosine, or
linearly with a non-zero factor).
"""

from __future__ import annotations

import re

import pytest

from linkage_sym.examples import load_example
from linkage_sym.symbolic import derive
from linkage_sym.symbolic.latex import latex_document

GRID = re.compile(r"\\mathbf\{A\} &= \\begin\{pmatrix\} (.*?) \\end\{pmatrix\}")


def _printed_grid(doc: str) -> list[list[str]]:
    m = GRID.search(doc)
    assert m, "A is not printed by blocks"
    return [[c.strip() for c in row.split("&")] for row in m.group(1).split(r"\\")]


@pytest.mark.slow
@pytest.mark.parametrize("name", ["shaper", "watt_sixbar", "sixbar_class3"])
def test_the_rate_matrix_is_a_grid_of_blocks_with_its_zero_blocks(name):
    eqs = derive(load_example(name), forces=True)
    doc = latex_document(eqs)
    grid = _printed_grid(doc)
    n = len(eqs.groups)
    assert len(grid) == n and all(len(r) == n for r in grid)
    used = [set().union(*(e.free_symbols for e in eqs.Phi[ge.rows, :])) for ge in eqs.groups]
    for i, gi in enumerate(eqs.groups):
        for j, gj in enumerate(eqs.groups):
            zero = not (used[i] & set(gj.x))
            want = r"\mathbf{0}" if zero else rf"\mathbf{{A}}_{{{i + 1},{j + 1}}}"
            assert grid[i][j] == want, (i, j, grid[i][j])
            if zero:
                continue
            # each non-zero block is written out: as a matrix of its shape, or entry by entry
            block = re.search(re.escape(want) + r" &= \\begin\{pmatrix\} (.*?) \\end\{pmatrix\}",
                              doc, re.S)
            if block:
                rows = block.group(1).split(r"\\")
                assert len(rows) == len(eqs.Phi[gi.rows, :].tolist())
                assert all(len(r.split("&")) == len(gj.x) for r in rows)
            else:
                assert f"of the block ${want}$" in doc, want
    # the list of the whole matrix's non-zero entries is gone
    assert "entries $A_{ij}$ of the matrix" not in doc
    # block lower triangular: a group uses no coordinate of a group solved after it
    assert all(grid[i][j] == r"\mathbf{0}" for i in range(n) for j in range(i + 1, n))


def test_a_force_group_matrix_is_printed_as_a_matrix_with_its_zeros():
    """The four-bar's dyad: A_2 (6 x 6) as a matrix, a source line a row, its zero entries
    shown, not as the list of its non-zero entries."""
    eqs = derive(load_example("crank_rocker"), forces=True)
    doc = latex_document(eqs)
    Ag = eqs.readable_force_blocks[1][0]
    m = re.search(r"\\mathbf\{A\}_\{2\} &= \\begin\{pmatrix\} (.*?) \\end\{pmatrix\}", doc, re.S)
    assert m, "A_2 is not printed as a matrix"
    rows = [r.split("&") for r in m.group(1).split("\\\\")]
    assert len(rows) == Ag.rows and all(len(r) == Ag.cols for r in rows)
    zeros = sum(c.strip() == "0" for r in rows for c in r)
    assert zeros == sum(1 for v in Ag if v == 0) > 0
    assert "entries $A^{(2)}_{ij}$" not in doc
