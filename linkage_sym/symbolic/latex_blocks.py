"""The rate matrices ``A`` and ``B`` of ``A xd = B qd`` as block matrices, by group.

The rows of ``Phi`` and the coordinates ``x`` come group by group in solving
order, so ``A = dPhi/dx`` is block lower triangular: block ``A_{i,j}`` holds
the derivatives of group ``i``'s equations by group ``j``'s coordinates, zero
where group ``i`` does not use group ``j``'s links.  A matrix too big to print
whole is written as its grid of blocks (zero blocks shown as ``0``), each
non-zero block then as a matrix of its own (entry by entry where even a block
is too wide for a line).  :func:`linkage_sym.symbolic.latex_sections` calls
:func:`rate_matrix` for ``A`` and ``B``.
"""

from __future__ import annotations

import sympy as sp

from linkage_sym.symbolic.latex_notation import (LINE, MAX_ENTRY, MAX_MATRIX, Doc, Namer,
                                                 typeset_width)

__all__ = ["BLOCK_ROW", "block_grid", "block_matrix", "rate_matrix"]

BLOCK_ROW = LINE + 30
"""A block whose longest row is longer than this (LaTeX characters) is written entry by entry."""
BLOCK_TYPESET = 60
"""... or wider than this typeset (:func:`typeset_width` of its entries, two characters for
each column's gap): a row of numbers (``derive --numeric``) is short in source characters
but wide on the page.  The widest rows of the shipped examples' symbolic blocks are 57."""


def _row_width(row: list[str]) -> float:
    return sum(typeset_width(c) for c in row) + 2 * (len(row) - 1)


def block_grid(M: sp.Matrix, rows: list[slice], cols: list[slice]) -> list[list[sp.Matrix]]:
    """``M`` cut into blocks: ``grid[i][j] = M[rows[i], cols[j]]``.

    Examples
    --------
    >>> a, b = sp.symbols("a b")
    >>> g = block_grid(sp.Matrix([[a, 0], [b, a]]), [slice(0, 1), slice(1, 2)], [slice(0, 1), slice(1, 2)])
    >>> g[0][1].is_zero_matrix, g[1][0]
    (True, Matrix([[b]]))
    """
    return [[M[r, c] for c in cols] for r in rows]


def block_matrix(namer: Namer, M: sp.Matrix, force: bool = False) -> str | None:
    """One block as a ``pmatrix`` (a source line per row), or None when a row is too long
    for a line."""
    cells = [[namer(M[i, j]) for j in range(M.cols)] for i in range(M.rows)]
    if not force and (max(len(c) for r in cells for c in r) > MAX_ENTRY
                      or max(sum(len(c) for c in r) for r in cells) > BLOCK_ROW
                      or max(_row_width(r) for r in cells) > BLOCK_TYPESET
                      or M.rows > MAX_MATRIX or M.cols > 10):  # amsmath's MaxMatrixCols
        return None
    # one matrix row a source line: the .tex reads as the matrix it typesets
    return r"\begin{pmatrix} " + " \\\\\n".join(" & ".join(r) for r in cells) + r" \end{pmatrix}"


def rate_matrix(doc: Doc, namer: Namer, letter: str, M: sp.Matrix, rows: list[slice],
                cols: list[slice]) -> None:
    """Write ``\\mathbf{letter}`` as its grid of blocks, then each non-zero block.

    Parameters
    ----------
    doc : Doc
        The document being written.
    namer : Namer
        The symbols' names.
    letter : str
        The matrix's letter (``A`` or ``B``).
    M : Matrix
        The matrix.
    rows, cols : list of slice
        The row and column blocks (each group's rows; its coordinates, or all drivers).
    """
    grid = block_grid(M, rows, cols)
    one_col = len(cols) == 1

    def name(i, j):
        return rf"\mathbf{{{letter}}}_{{{i + 1}}}" if one_col else \
            rf"\mathbf{{{letter}}}_{{{i + 1},{j + 1}}}"

    cells = [[r"\mathbf{0}" if b.is_zero_matrix else name(i, j) for j, b in enumerate(r)]
             for i, r in enumerate(grid)]
    body = r" \\ ".join(" & ".join(r) for r in cells)
    if one_col:
        doc.text(rf"$\mathbf{{{letter}}}$ by blocks: $\mathbf{{{letter}}}_{{i}}$ holds the rows of "
                 r"group $i$ (its equations in $\Phi$); $\mathbf{0}$ is a zero block:")
    else:
        doc.text(rf"$\mathbf{{{letter}}}$ by blocks: $\mathbf{{{letter}}}_{{i,j}}$ holds the "
                 r"derivatives of group $i$'s equations in $\Phi$ by group $j$'s coordinates; "
                 r"$\mathbf{0}$ is a zero block:")
    doc.align([rf"\mathbf{{{letter}}} &= \begin{{pmatrix}} {body} \end{{pmatrix}}"],
              numbered=False)
    rows_tex = []
    for i, r in enumerate(grid):
        for j, b in enumerate(r):
            if b.is_zero_matrix:
                continue
            tex = block_matrix(namer, b)
            if tex is not None:
                rows_tex.append(f"{name(i, j)} &= {tex}")
            else:
                if rows_tex:
                    doc.align(rows_tex, numbered=False)
                    rows_tex = []
                entry = f"{letter}^{{({i + 1})}}" if one_col else f"{letter}^{{({i + 1},{j + 1})}}"
                doc.entries(namer, name(i, j), b, "the block", entry)
    if rows_tex:
        doc.align(rows_tex, numbered=False)
