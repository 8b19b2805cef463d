"""The result of a sweep: one row per design, its parameters then its metrics.

Written as CSV (numbers as Python writes them, ``repr``: read back exactly; an
empty field where a value is NaN) or Parquet (through pyarrow, the ``sweep``
extra), by the file's suffix.
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from linkage_sym.design.errors import SweepError

__all__ = ["SweepResult", "table_format"]

FORMATS = {".csv": "csv", ".parquet": "parquet"}


def table_format(path) -> str:
    """``"csv"`` or ``"parquet"`` from a file's suffix."""
    fmt = FORMATS.get(Path(str(path)).suffix.lower())
    if fmt is None:
        raise SweepError("path", f"{str(path)!r}: a .csv or .parquet file is expected")
    return fmt


@dataclass
class SweepResult:
    """One row per design: ``columns["design"]`` (its index), one column per varied
    parameter (:attr:`parameters`), then the metric columns (:attr:`metrics`).

    Attributes
    ----------
    columns : dict of str to ndarray
        Every column, in order (numbers as float, the Grashof classes as str).
    parameters, metrics : tuple of str
        The names of the parameter and metric columns.
    kind : str
        ``"grid"``, ``"monte-carlo"`` or ``"samples"``.
    axes : tuple
        A grid's ``(name, values)`` per axis (the first varies slowest).
    scene : str
        The scene's name.
    files : list of str
        The design scenes written (``scenes``, a :class:`~linkage_sym.design.scenes.SceneFiles`).
    one_at_a_time : tuple of str
        The scene's groups without a closed form: when not empty, each design was
        solved on its own by the numeric plan (:mod:`linkage_sym.design.newton_groups`).
    no_scene : tuple of int
        Designs whose scene was asked for but that cannot be assembled (no scene).
    bad_scene : tuple of (int, str)
        Designs whose scene was asked for but breaks the scene's rules, with the first
        problem (no scene): the invalid designs, and any whose scene the scene reader
        refuses.

    A sweep with designs that break the scene's rules (a negative mass, a length <= 0, a
    number beyond 1e30 ...: :func:`~linkage_sym.design.parameters.design_problems`) has an
    ``invalid`` column after the parameters: the reason, empty for a valid design.  An
    invalid design is not solved: its metrics are empty (NaN, or "" in a text column).
    """

    columns: dict
    parameters: tuple
    metrics: tuple
    kind: str
    axes: tuple = ()
    scene: str = ""
    files: list = field(default_factory=list)
    one_at_a_time: tuple = ()
    no_scene: tuple = ()
    bad_scene: tuple = ()

    def __len__(self) -> int:
        return len(self.columns["design"])

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self.columns[name]
        except KeyError:
            raise KeyError(f"no column {name!r}; the columns are {', '.join(self.columns)}") from None

    def write(self, path) -> str:
        """Write the table to ``path`` (.csv or .parquet), creating its folder as every
        command's output does; returns the path."""
        fmt = table_format(path)
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        if fmt == "csv":
            Path(path).write_text(self.to_csv())
        else:
            self.to_parquet(path)
        return str(path)

    def to_csv(self) -> str:
        """The table as CSV text."""
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(list(self.columns))
        cols = [_texts(v) for v in self.columns.values()]
        w.writerows(zip(*cols))
        return buf.getvalue()

    def to_parquet(self, path) -> None:
        """Write the table as Parquet (pyarrow)."""
        try:
            import pyarrow as pa
            import pyarrow.parquet as pq
        except ImportError:
            raise SweepError("path", "a Parquet file needs pyarrow, which is not "
                                            "installed: pip install 'linkage_sym[sweep]'") from None
        arrays = {k: pa.array(v) for k, v in self.columns.items()}
        table = pa.table(arrays, metadata={"linkage_sym": f"sweep of {self.scene}"})
        pq.write_table(table, str(path))


def _texts(v: np.ndarray) -> list:
    if v.dtype.kind in "US":
        return v.tolist()
    if v.dtype.kind in "iu":
        return [str(x) for x in v.tolist()]
    return ["" if not math.isfinite(x) else repr(x) for x in v.tolist()]


def read_table(path) -> dict:
    """A table written by :meth:`SweepResult.write` as a dict of columns (for tests and
    plots): numbers as float arrays, text columns as str arrays."""
    if table_format(path) == "parquet":
        import pyarrow.parquet as pq

        t = pq.read_table(str(path))
        return {k: np.asarray(t.column(k).to_numpy(zero_copy_only=False)) for k in t.column_names}
    rows = list(csv.reader(Path(path).read_text().splitlines()))
    head, body = rows[0], rows[1:]
    out = {}
    for k, name in enumerate(head):
        col = [r[k] for r in body]
        if is_text(name):
            out[name] = np.array(col, dtype=str)
            continue
        out[name] = np.array([float(x) if x != "" else math.nan for x in col])
    return out


def is_text(column: str) -> bool:
    """Whether a sweep's column holds text (the Grashof classes, ``K_note``, ``invalid``), not numbers
    (in CSV an empty field is an empty text there, a NaN elsewhere)."""
    return column in ("K_note", "invalid") or column.startswith("grashof")
