"""The result file formats (``json``, ``csv``, ``npz``, ``parquet``): one writer each,
fed a chunk of steps at a time by :func:`linkage_sym.output.write_sweep`."""

from __future__ import annotations

import io
import json
from pathlib import Path
from typing import TYPE_CHECKING, Callable

import numpy as np

from linkage_sym.numeric.results.result import Analysis

if TYPE_CHECKING:
    from linkage_sym.output.stats import SweepStats

ProgressFn = Callable[[int], None]


FORMATS = ("json", "csv", "npz", "parquet")
SUFFIXES = {".json": "json", ".csv": "csv", ".npz": "npz", ".parquet": "parquet", ".pq": "parquet"}


class OutputError(Exception):
    """A result file that will not be written: refused before anything is computed or written.

    ``reason`` says why; ``field``, when given, names the argument that cannot be used
    (``format``, ``keep``, ``path`` of :func:`~linkage_sym.output.write_sweep`), so that a
    caller can name its own option for it.  ``problems``: the one sentence,
    ``"field: reason"`` (the command line exits with status 2).

    Examples
    --------
    >>> err = OutputError("'xml' is not one of json, csv", field="format")
    >>> err.problems, err.field
    (["format: 'xml' is not one of json, csv"], 'format')
    """

    def __init__(self, reason: str, field: str | None = None):
        self.reason = reason
        self.field = field
        self.problems = [f"{field}: {reason}" if field else reason]
        super().__init__(self.problems[0])


def output_format(path: str | None, given: str | None = None) -> str:
    """The format of a result file: ``given``, else from the suffix of ``path``, else ``json``."""
    if given is not None:
        if given not in FORMATS:
            raise OutputError(f"{given!r} is not one of {', '.join(FORMATS)}", field="format")
        return given
    if path is None or path == "-":
        return "json"
    return SUFFIXES.get(Path(path).suffix.lower(), "json")


def require_pyarrow():
    """pyarrow's ``(pa, pq)`` modules, or :class:`OutputError` naming the extra to install."""
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError as err:
        raise OutputError("parquet needs pyarrow, which is not installed: "
                          "pip install 'linkage_sym[parquet]'", field="format") from err
    return pa, pq


# ------------------------------------------------------------------ writers


class Writer:
    """A result file being written chunk by chunk, the base of each format's writer:
    :meth:`begin` once, :meth:`write` for each chunk of steps, then :meth:`finish`, or
    :meth:`discard` when the run fails."""

    def begin(self, stats: SweepStats) -> None:
        pass

    def write(self, res: Analysis, skip: int, offset: int, stats: SweepStats, progress: ProgressFn):
        raise NotImplementedError

    def finish(self, stats: SweepStats) -> None:
        pass

    def discard(self) -> None:
        pass


class JsonWriter(Writer):
    """The contract's JSON, step by step: the same bytes as ``json.dumps(to_dict(), indent=...)``."""

    def __init__(self, fh, indent: int | None = None):
        self.fh = fh
        self.indent = indent
        self.n = 0

    def begin(self, stats):
        text = json.dumps({**stats.template.head(), "steps": []}, indent=self.indent)
        self.fh.write(text[: text.rindex('"steps": []') + len('"steps": [')])

    def write(self, res, skip, offset, stats, progress):
        ind = self.indent
        pad = "\n" + " " * (2 * ind) if ind is not None else None
        sep = "," if ind is not None else ", "
        parts = []
        for rec in res.step_records(skip, number_from=offset, dropped=stats.left_out):
            text = json.dumps(rec, indent=ind, allow_nan=False)
            if pad is not None:
                text = pad + text.replace("\n", pad)
            parts.append(text if self.n == 0 else sep + text)
            self.n += 1
            if len(parts) == 1024:
                self.fh.write("".join(parts))
                parts = []
                progress(1024)
        self.fh.write("".join(parts))
        progress(len(parts))

    def finish(self, stats):
        if self.n and self.indent is not None:
            self.fh.write("\n" + " " * self.indent)
        text = json.dumps({**stats.template.head(), "steps": [], **stats.tail()},
                          indent=self.indent, allow_nan=False)
        self.fh.write(text[text.rindex('"steps": []') + len('"steps": [') :] + "\n")


def _float_text(v: np.ndarray) -> list:
    """The shortest text that reads back as each value (``repr``); empty if not finite."""
    out = list(map(repr, v.tolist()))
    bad = ~np.isfinite(v)
    if bad.any():
        for i in np.flatnonzero(bad):
            out[i] = ""
    return out


def _csv_field(text: str) -> str:
    """``text`` as one CSV field (RFC 4180: quoted when it holds a comma, quote or line break)."""
    if any(c in text for c in ',"\r\n'):
        return '"' + text.replace('"', '""') + '"'
    return text


class CsvWriter(Writer):
    """One row per step: ``step``, ``status``, ``message`` and one column per number.

    Numbers as Python writes them (``repr``: the shortest text that reads back
    as the same double); a value the JSON leaves out is an empty field.
    """

    BLOCK = 4096

    def __init__(self, fh):
        self.fh = fh

    def begin(self, stats):
        names = ["step", *(n for n, _, _ in stats.template.columns())]
        self.fh.write(",".join(map(_csv_field, names)) + "\n")

    def write(self, res, skip, offset, stats, progress):
        _count_left_out(res, skip, offset, stats)
        cols = res.columns()
        for a in range(skip, res.n_steps, self.BLOCK):
            b = min(res.n_steps, a + self.BLOCK)
            text = [list(map(str, range(offset + a - skip, offset + b - skip)))]
            for name, v, _ in cols:
                if name == "status":
                    text.append(v[a:b].tolist())
                elif name == "message":
                    text.append(["" if m is None else _csv_field(m) for m in v[a:b]])
                else:
                    text.append(_float_text(v[a:b]))
            self.fh.write("\n".join(map(",".join, zip(*text))) + "\n")
            progress(b - a)


def _count_left_out(res, skip, offset, stats):
    """Name, in the warnings, the values a JSON file would leave out as not finite."""
    for i in np.flatnonzero(res.not_finite(skip)) + skip:
        for _ in res.step_records(int(i), int(i) + 1, number_from=offset + int(i) - skip,
                                  dropped=stats.left_out):
            pass


def _npy_header(dtype: np.dtype, n: int) -> bytes:
    buf = io.BytesIO()
    np.lib.format.write_array_header_1_0(
        buf, {"descr": np.lib.format.dtype_to_descr(dtype), "fortran_order": False, "shape": (n,)})
    return buf.getvalue()


class NpzWriter(Writer):
    """One array per column in a NumPy ``.npz`` (a zip of ``.npy`` files).

    Each chunk's columns are appended to one raw file per column in a
    temporary folder beside the result; :meth:`finish` copies them into the
    zip (numbers stored, the text columns compressed), so no column is ever
    whole in memory.  ``meta`` holds the JSON's keys but ``steps``.
    """

    def __init__(self, path: Path):
        import tempfile  # shutil, tempfile, zipfile: only where an npz is written (start-up)

        self.path = path
        self.tmp = Path(tempfile.mkdtemp(prefix=f".{path.name}.", dir=path.parent))
        self.names: list = []
        self.n = 0

    def _file(self, k: int) -> Path:
        return self.tmp / f"{k}.raw"

    def begin(self, stats):
        self.names = ["step", *(n for n, _, _ in stats.template.columns())]

    def write(self, res, skip, offset, stats, progress):
        _count_left_out(res, skip, offset, stats)
        n = res.n_steps - skip
        arrays = [np.arange(offset, offset + n, dtype=np.int64)]
        for name, v, _ in res.columns():
            if name == "status":
                arrays.append(np.asarray(v[skip:], dtype="<U13"))
            elif name != "message":
                arrays.append(np.ascontiguousarray(v[skip:], dtype=float))
        cols = [nm for nm in self.names if nm != "message"]
        for k, a in enumerate(arrays):
            with open(self._file(k), "ab") as fh:
                fh.write(a.tobytes())
        with open(self.tmp / "message.jsonl", "a", encoding="utf-8") as fh:  # (step, message)
            fh.write("".join(json.dumps([offset + i, m]) + "\n"
                             for i, m in enumerate(res.messages[skip:]) if m is not None))
        self.dtypes = [a.dtype for a in arrays]
        self.cols = cols
        self.n += n
        progress(n)

    def finish(self, stats):
        import shutil
        import zipfile

        with zipfile.ZipFile(self.path, "w", zipfile.ZIP_STORED, allowZip64=True) as zf:
            raw = dict(zip(self.cols, range(len(self.cols))))
            for name in self.names:
                if name == "message":
                    self._messages(zf)
                    continue
                k = raw[name]
                info = zipfile.ZipInfo(f"{name}.npy", date_time=(1980, 1, 1, 0, 0, 0))
                if name == "status":
                    info.compress_type = zipfile.ZIP_DEFLATED
                with zf.open(info, "w", force_zip64=True) as out, open(self._file(k), "rb") as src:
                    out.write(_npy_header(self.dtypes[k], self.n))
                    shutil.copyfileobj(src, out, 2**24)
            meta = np.array(json.dumps(stats.meta(), allow_nan=False))
            info = zipfile.ZipInfo("meta.npy", date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            with zf.open(info, "w") as out:
                np.lib.format.write_array(out, meta)
        shutil.rmtree(self.tmp, ignore_errors=True)

    def _messages(self, zf):
        """The ``message`` column: fixed-width text as wide as the longest ("" for none)."""
        import zipfile

        src = self.tmp / "message.jsonl"
        width = 1
        with open(src, encoding="utf-8") as fh:
            for line in fh:
                width = max(width, len(json.loads(line)[1]))
        dtype = np.dtype(f"<U{width}")
        info = zipfile.ZipInfo("message.npy", date_time=(1980, 1, 1, 0, 0, 0))
        info.compress_type = zipfile.ZIP_DEFLATED
        with zf.open(info, "w", force_zip64=True) as out, open(src, encoding="utf-8") as fh:
            out.write(_npy_header(dtype, self.n))
            pending = None
            for a in range(0, self.n, 65536):
                block = np.zeros(min(self.n, a + 65536) - a, dtype=dtype)
                while True:
                    if pending is None:
                        line = fh.readline()
                        if not line:
                            break
                        pending = json.loads(line)
                    if pending[0] >= a + len(block):
                        break
                    block[pending[0] - a] = pending[1]
                    pending = None
                out.write(block.tobytes())

    def discard(self):
        import shutil

        shutil.rmtree(self.tmp, ignore_errors=True)


class ParquetWriter(Writer):
    """One row group per chunk (pyarrow); values left out of the JSON are nulls here.

    The schema's metadata ``linkage_sym`` holds the JSON's keys but ``steps``.
    """

    def __init__(self, path: Path):
        self.pa, self.pq = require_pyarrow()
        self.path = path
        self.writer = None

    def begin(self, stats):
        pa = self.pa
        fields = [pa.field("step", pa.int64(), nullable=False)]
        for name, _, _ in stats.template.columns():
            kind = pa.string() if name in ("status", "message") else pa.float64()
            fields.append(pa.field(name, kind, nullable=name != "status"))
        self.schema = pa.schema(fields)
        # dictionary encoding only for the text columns: tried on 100+ float columns it
        # costs six times the rest of the write and saves nothing
        self.writer = self.pq.ParquetWriter(str(self.path), self.schema,
                                            use_dictionary=["status", "message"])

    def write(self, res, skip, offset, stats, progress):
        pa = self.pa
        _count_left_out(res, skip, offset, stats)
        n = res.n_steps - skip
        arrays = [pa.array(np.arange(offset, offset + n, dtype=np.int64))]
        for name, v, _ in res.columns():
            if name == "status":
                arrays.append(pa.array(np.asarray(v[skip:]).astype(str).tolist(), pa.string()))
            elif name == "message":
                arrays.append(pa.array(v[skip:], pa.string()))
            else:
                a = np.asarray(v[skip:], dtype=float)
                arrays.append(pa.array(a, pa.float64(), mask=~np.isfinite(a)))
        self.writer.write_table(pa.Table.from_arrays(arrays, schema=self.schema))
        progress(n)

    def finish(self, stats):
        meta = {"linkage_sym": json.dumps(stats.meta(), allow_nan=False)}
        self.writer.add_key_value_metadata(meta)
        self.writer.close()

    def discard(self):
        if self.writer is not None:
            self.writer.close()


class NoWriter(Writer):
    """No file: the statistics only (:func:`~linkage_sym.output.write_sweep` given neither a
    path nor a stream)."""

    def write(self, res, skip, offset, stats, progress):
        progress(res.n_steps - skip)


# ------------------------------------------------------------------ the run


