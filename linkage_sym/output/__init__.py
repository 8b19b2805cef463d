"""Result files of any length: the sweep solved in chunks of steps, each written as it is solved.

A step's result does not depend on the other steps of its sweep (the solving
path runs from the assembly configuration to every step, and the Newton
groups' continuation is resolution-independent: see
:mod:`linkage_sym.numeric.continuation`), so a sweep can be solved a chunk of
steps at a time with ``run(q, qd, qdd)`` and each chunk written out before the
next is solved: memory is bounded by one chunk, whatever the number of steps
and whatever the format.

* Each chunk after the first also solves the previous chunk's last step
  again (it is not written twice): its continuation warnings then name a jump
  between two chunks as a whole run does, and its rotations are checked
  against the previous chunk's (continuous across the boundary).
* Warnings are merged into what one run of the whole sweep says: step numbers
  offset to the sweep, counts, first steps and worst values of the
  condition-number and superposition warnings gathered over all chunks
  (:class:`SweepStats`).
* Formats (:data:`FORMATS`): ``json`` (the contract's layout, byte for byte
  what ``json.dumps(Analysis.to_dict())`` writes), ``csv`` (one row per step,
  one column per number of a step record, named by its path:
  ``joints.B.position.x``), ``npz`` (one array per column) and ``parquet``
  (through pyarrow, the optional extra ``parquet``).  Column layout:
  ``docs/scene-format.md``.
* A file is written under a temporary name beside its destination and renamed
  only when complete: a failure (a full disk, an interrupt) leaves no partial
  file, and an existing file of that name untouched.
* Before solving, the memory a chunk needs is estimated (:func:`bytes_per_step`)
  and compared with what the machine has (:func:`available_memory`): a chunk
  is made smaller to fit, and a run that cannot fit even so (or a whole sweep
  kept in memory for plots) is refused with :class:`OutputError`, nothing
  written.

The package: this module plans the chunks (memory, chunk size) and runs the
sweep (:class:`Sweep`, :func:`write_sweep`); :mod:`~linkage_sym.output.writers`
holds one writer per format, :mod:`~linkage_sym.output.stats` what the chunks
add up to.

This package is outside the numeric core: it may use tqdm (a progress bar,
optional extra ``progress``) and pyarrow (optional extra ``parquet``), which
the core never imports.
"""

from __future__ import annotations

import contextlib
import math
import os
import signal
import sys
import threading
from pathlib import Path

from linkage_sym.numeric.engine.heap import available_memory
from linkage_sym.numeric.results.result import Analysis
from linkage_sym.output.chunked import Sweep, compiled_sweep, plan_sweep
from linkage_sym.output.stats import Peak, SweepStats
from linkage_sym.output.writers import (
    FORMATS,
    SUFFIXES,
    CsvWriter,
    JsonWriter,
    NpzWriter,
    OutputError,
    ParquetWriter,
    NoWriter,
    ProgressFn,
    Writer,
    output_format,
    require_pyarrow,
)

__all__ = [
    "FORMATS", "SUFFIXES", "OutputError", "output_format", "require_pyarrow", "available_memory",
    "bytes_per_step", "chunk_steps", "check_whole", "Sweep", "plan_sweep", "compiled_sweep",
    "chunk_bounds", "progress_bar", "ChunkError", "write_sweep", "SweepStats", "Peak", "ProgressFn",
    "run_memory", "check_run_memory",
]


CHUNK_MEMORY = 256 * 2**20
"""Memory (bytes, estimated) one chunk may take; smaller when the machine has less."""
NEWTON_CHUNK = 4096
"""Largest chunk of a mechanism with Newton groups (solved step by step, about 0.5 ms a step):
the progress bar moves every few seconds."""
MIN_CHUNK = 256
"""A run is refused when not even a chunk of this many steps (or the whole sweep, if
shorter) fits in the memory available."""
PEAK_FACTOR = {"dyad": 3.0, "global": 8.0, "symbolic": 4.0}
"""Peak memory of a run, per step, in units of its result's numbers (8 bytes each).

Measured with tracemalloc on the shipped examples (tests/output/test_output_formats.py
holds every example's measured peak under the estimate): a run's result block
plus its temporaries peak at 1.8 (dyad), 5.5 (global: the sparse systems),
2.3 (symbolic) times the result."""
NEWTON_FACTOR = 3.0
"""Added to :data:`PEAK_FACTOR` for mechanisms with Newton groups (the path's solutions and
their Jacobians: the peaks measured are 2.2 times the result for the class-III six-bar and the
printing mechanism, solved in loop-closure coordinates, and 4.5 for the hydraulic boom's
actuator group, in pose coordinates)."""
CENTRE_BYTES = 400
"""Added per pair of links and step for a run with the ``instant_centres`` output: Kennedy's
construction in homogeneous coordinates and the velocity method's fields (the peaks measured
on the shipped examples over 2000 steps are 300 to 355 bytes a pair above the same run
without centres)."""
WRITER_BYTES = {"json": 0, "csv": 0, "npz": 0, "parquet": 24}
"""Bytes per number and step a writer holds while it writes a chunk (parquet: the
Arrow arrays with their validity masks, and the encoded pages)."""
FIXED_BYTES = 64 * 2**20
"""Memory a run needs besides its chunk (a JSON or CSV block of records, buffers)."""


def numeric_columns(res: Analysis) -> list:
    """The ``(name, values, width)`` columns of ``res`` that hold numbers (all but
    ``status`` and ``message``): what a step costs in memory is counted in them."""
    return [(n, v, w) for n, v, w in res.columns() if n not in ("status", "message")]


def bytes_per_step(n_values: int, method: str, newton: bool, fmt: str | None = None,
                   centre_pairs: int = 0) -> int:
    """Estimated peak memory per step of a chunk: solving it, and writing it in ``fmt``.

    ``n_values``: the numbers of one step's result (its numeric columns);
    ``centre_pairs``: the pairs of links whose instant centres it finds (0 without the
    ``instant_centres`` output).
    """
    factor = PEAK_FACTOR[method] + (NEWTON_FACTOR if newton else 0.0)
    per_value = 8 * factor + WRITER_BYTES.get(fmt, 0)
    # + status, message, condition, drivers
    return int(math.ceil(per_value * (n_values + 16))) + CENTRE_BYTES * centre_pairs


def _centre_pairs(res) -> int:
    """The pairs of links whose instant centres a run of ``res``'s scene finds."""
    if res.instant_centres is None or "instant_centres" not in res.outputs:
        return 0
    return len(res.instant_centres.pairs)


def _size(n: float) -> str:
    return f"{n / 2**30:.2f} GB" if n >= 2**30 else f"{n / 2**20:.0f} MB"


SMALL_RUN = 10**4
"""Steps up to which :func:`check_run_memory` does not estimate (a few tens of MB at most)."""

RESULTS = ("whole", "chunks", "path", "none")
"""What of a run's results :func:`run_memory` counts: every step's at once (``centres``,
``balance``, ``analyze --plots``), a chunk's (``analyze``), one design's along its
solving path (a design sweep), none (``sweep --list``)."""


def run_memory(scene, results: str = "whole", *, method: str = "dyad", fmt: str | None = None,
               copies: int = 1, available: int | None = None) -> dict:
    """Estimated peak memory (bytes) of a run of ``scene``'s sweep, by part, and its ``total``.

    * ``driver values``: the steps' ``q``, ``qd``, ``qdd`` (``copies`` of them: ``analyze``
      holds the plan's and its chunked sweep's, 2; a design sweep's model the scene's, its
      own and its compiled mechanism's with that one's path, 4 -- measured: 137 bytes a
      step of a four-bar's model, 249 of the five-bar's, against 144 and 272 estimated);
    * ``solving path``: while it is built, the steps stacked, the path with its pieces and
      temporaries and the steps' indices (:func:`~linkage_sym.numeric.engine.run.solving_path`),
      then the path kept (:func:`~linkage_sym.numeric.engine.run.path_size` points, an upper bound);
    * ``results``: ``results`` (:data:`RESULTS`) steps at :func:`bytes_per_step` each, from
      the columns of a run of the scene at two steps, and :data:`FIXED_BYTES` (a chunk as
      :func:`chunk_steps` makes it with ``available`` bytes); none for ``"none"``.

    The path is built before the results are made: the total is the driver values and the
    larger of the path being built and the path kept with the results.

    Examples
    --------
    >>> import linkage_sym
    >>> m = run_memory(linkage_sym.load_example("crank_rocker"), "whole")
    >>> sorted(m), m["driver values"]
    (['driver values', 'results', 'solving path', 'total'], 8664)
    """
    import dataclasses

    from linkage_sym.numeric.plan import compile_plan
    from linkage_sym.numeric.engine.run import path_size

    if results not in RESULTS:
        raise ValueError(f"results must be one of {', '.join(RESULTS)}, got {results!r}")
    D, N = len(scene.drivers), scene.drivers[0].steps
    K, n_ref = path_size(scene)
    drivers = copies * 3 * 8 * D * N
    build = 8 * (D * N + 3 * D * K + 2 * N)
    kept = 8 * (D * K + N)
    count = 0
    per_step = 0
    if results != "none":
        two = dataclasses.replace(scene, drivers=tuple(dataclasses.replace(d, steps=2)
                                                       for d in scene.drivers))
        sweep = plan_sweep(compile_plan(two), "dyad" if method == "symbolic" else method)
        template = sweep.solve(0, 1)
        per_step = bytes_per_step(len(numeric_columns(template)), method, bool(sweep.heads),
                                  fmt, _centre_pairs(template))
        budget = (CHUNK_MEMORY if available is None
                  else min(CHUNK_MEMORY, max(0, available - FIXED_BYTES) // 2))
        count = {"whole": N, "path": K,
                 "chunks": min(N, max(MIN_CHUNK, budget // per_step))}[results]
    res = count * per_step + FIXED_BYTES if results != "none" else 0
    return {"driver values": drivers, "solving path": max(build, kept), "results": res,
            "total": drivers + max(build, kept + res)}


def check_run_memory(scene, results: str = "whole", *, method: str = "dyad",
                     fmt: str | None = None, copies: int = 1) -> None:
    """Refuse (:class:`~linkage_sym.errors.SceneError` naming ``drivers[0].steps``) a run
    whose :func:`run_memory` exceeds what this process can still take
    (:func:`available_memory`); runs of up to :data:`SMALL_RUN` steps are not estimated."""
    from linkage_sym.errors import SceneError
    from linkage_sym.numeric.engine.heap import gib

    N = scene.drivers[0].steps if scene.drivers else 0
    if N <= SMALL_RUN:
        return
    available = available_memory()
    m = run_memory(scene, results, method=method, fmt=fmt, copies=copies, available=available)
    if available is not None and m["total"] > available:
        parts = ", ".join(f"{k} {gib(v)}" for k, v in m.items() if k != "total")
        raise SceneError([
            f"drivers[0].steps: {N} steps do not fit in memory: the run needs about "
            f"{gib(m['total'])} at its peak ({parts}), and this process can take "
            f"{gib(available)} more; give fewer steps (or split the sweep into several scenes)"])


def chunk_steps(n_steps: int, per_step: int, available: int | None, newton: bool,
                extra: int = 0) -> int:
    """Steps per chunk: as many as :data:`CHUNK_MEMORY` (or half the memory available) holds.

    ``extra``: steps a chunk solves besides its own (its waypoints, see
    :meth:`Sweep.waypoints`).  Raises :class:`OutputError` if not even
    :data:`MIN_CHUNK` steps fit.
    """
    budget = CHUNK_MEMORY if available is None else min(CHUNK_MEMORY, max(0, available - FIXED_BYTES) // 2)
    size = max(MIN_CHUNK, budget // per_step - extra)
    if newton:
        size = min(size, NEWTON_CHUNK)
    size = min(size, n_steps)
    need = (size + 1 + extra) * per_step + FIXED_BYTES
    if available is not None and need > available:
        raise OutputError(
            f"not enough memory: solving even {size} step(s) at a time needs about {_size(need)} "
            f"({_size(per_step)} a step), and the machine has {_size(available)} available; "
            "nothing written")
    return size


def check_whole(n_steps: int, per_step: int, available: int | None, field: str) -> None:
    """Refuse (:class:`OutputError`) a whole sweep held in memory at once that would not fit.

    ``field``: the argument that asks for the whole sweep (``keep`` of :func:`write_sweep`),
    named by the error.

    Examples
    --------
    >>> check_whole(10, 100, None, "keep")  # memory unknown: no check
    >>> try:
    ...     check_whole(10**6, 1000, FIXED_BYTES + 10**6, "keep")
    ... except OutputError as err:
    ...     print(err.field, "|", err.reason[:55])
    keep | not enough memory: the whole sweep in memory takes abou
    """
    need = n_steps * per_step + FIXED_BYTES
    if available is not None and need > available:
        raise OutputError(
            f"not enough memory: the whole sweep in memory takes about {_size(need)} for "
            f"{n_steps} steps ({_size(per_step)} a step), and the machine has {_size(available)} "
            "available; nothing written (fewer steps, or leave it out)", field=field)


def chunk_bounds(n: int, size: int) -> list[tuple[int, int]]:
    """``(start, stop)`` of each chunk of ``size`` items (steps of a sweep, designs of a
    design sweep)."""
    return [(a, min(n, a + size)) for a in range(0, n, size)]


def progress_bar(total: int, enabled: bool, unit: str = "step"):
    """A tqdm bar on standard error: only on a terminal, only after a second, only if installed."""
    if not enabled or not sys.stderr.isatty():
        return None
    try:
        from tqdm import tqdm
    except ImportError:  # the optional extra `progress` is not installed: no bar
        return None
    return tqdm(total=total, unit=unit, unit_scale=True, file=sys.stderr, delay=1.0,
                leave=False, dynamic_ncols=True)


class ChunkError(RuntimeError):
    """Two chunks disagree at the step they share (a solver's path from the assembly
    configuration reached another configuration): never expected; nothing is written."""


def _last_rotations(res: Analysis) -> dict:
    """Each link's rotation at the chunk's last step (for the next chunk's :func:`join_rotations`)."""
    return {n: float(lk.rotation[-1]) for n, lk in res.links.items()}


def join_rotations(prev: dict, res: Analysis, at: int, step: int) -> None:
    """Make the chunk's rotations continue the previous chunk's at the step they share.

    ``at``: the chunk's index of the step both solved (the sweep's ``step``).
    A chunk's path runs from the assembly configuration to its first step
    (along the sweep's route where it matters, see :meth:`Sweep.waypoints`),
    so a link's rotation there can only differ from the previous chunk's by
    whole turns, and only where the sweep's path crossed a gap of
    unassemblable steps that the chunk's path crossed elsewhere.  Such whole
    turns are added to the chunk's rotations (the values a whole run has);
    any other difference is a :class:`ChunkError`.
    """
    for name, lk in res.links.items():
        a, b = prev[name], float(lk.rotation[at])
        if not (math.isfinite(a) and math.isfinite(b)) or a == b:
            continue
        turns = round((a - b) / (2 * math.pi))
        if abs(a - b - 2 * math.pi * turns) > 1e-9 * max(1.0, abs(a)):
            raise ChunkError(
                f"link {name!r} at step {step}: rotation {a!r} in one chunk, {b!r} in the next; "
                "the chunks of the sweep do not join (nothing written)")
        if turns:
            lk.rotation += 2 * math.pi * turns


class _Signalled(BaseException):
    """Raised by :func:`_signals_unwind`'s handler: a signal that ends the process arrived."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum


SIGNALS = tuple(getattr(signal, n) for n in ("SIGTERM", "SIGINT", "SIGHUP") if hasattr(signal, n))
"""The signals that end a run (``kill``, Ctrl-C, a closed terminal) whose partial file
:func:`write_sweep` removes before the process ends."""


@contextlib.contextmanager
def _signals_unwind():
    """While the block runs, a signal of :data:`SIGNALS` unwinds it as an exception (its
    ``except``/``finally`` clauses remove what it was writing), then is handed to the
    handler it had before -- restored first -- so the process ends as that signal ends it
    (killed by SIGTERM, a ``KeyboardInterrupt`` for SIGINT ...).

    A signal the process ignores stays ignored; outside the main thread (where Python
    runs no handler) nothing changes.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = {}

    def unwind(signum, frame):
        raise _Signalled(signum)

    for sig in SIGNALS:
        old = signal.getsignal(sig)
        if old is signal.SIG_IGN or old is None:  # ignored, or not set from Python: leave it
            continue
        previous[sig] = old
        signal.signal(sig, unwind)

    def restore():
        for sig, old in previous.items():
            signal.signal(sig, old)

    try:
        yield
    except _Signalled as got:
        restore()
        old = previous[got.signum]
        if callable(old):
            old(got.signum, None)
        else:  # SIG_DFL: the default action, now that the file is gone
            os.kill(os.getpid(), got.signum)
        raise
    finally:
        restore()


def write_sweep(sweep: Sweep, path=None, fmt: str = "json", *, indent: int | None = None,
                stream=None, progress: bool = False, keep: bool = False,
                chunk: int | None = None, memory: int | None | str = "probe") -> SweepStats:
    """Solve ``sweep`` in chunks and write its result to ``path`` (or ``stream``) in ``fmt``.

    Parameters
    ----------
    path : str or Path, optional
        The result file (written under a temporary name, renamed when complete).
    stream : text file, optional
        Instead of ``path``: write JSON or CSV there (standard output).
        Neither: nothing is written; the statistics are returned.
    indent : int, optional
        JSON indentation (as ``json.dumps``).
    progress : bool
        A progress bar on standard error (when it is a terminal; tqdm).
    keep : bool
        Solve the whole sweep at once and keep it (``SweepStats.analysis``),
        e.g. for plots; refused when it would not fit in memory.
    chunk : int, optional
        Steps per chunk (default: from the memory estimate).
    memory : int or None
        Bytes available (default: :func:`available_memory`; ``None``: unknown, no check).

    Returns
    -------
    SweepStats
        Statuses, peaks and the merged warnings of the whole sweep.

    Raises
    ------
    OutputError
        Before anything is written: not enough memory, or pyarrow missing.
    """
    if fmt not in FORMATS:
        raise OutputError(f"{fmt!r} is not one of {', '.join(FORMATS)}", field="format")
    if fmt == "parquet" and (path is not None or stream is not None):
        require_pyarrow()
    N = sweep.n_steps
    template = sweep.solve(0, 1)
    stats = SweepStats(template, sweep.heads)
    per_step = bytes_per_step(len(numeric_columns(template)), sweep.method, bool(sweep.heads), fmt,
                              _centre_pairs(template))
    available = available_memory() if memory == "probe" else memory
    if keep:
        check_whole(N, per_step, available, "keep")
        size = N
    else:
        size = chunk or chunk_steps(N, per_step, available, bool(sweep.heads),
                                    sweep.most_waypoints())
    target = tmp = None
    if path is not None:
        # a symbolic link: the file it names is replaced, not the link
        target = Path(os.path.realpath(path)) if os.path.islink(path) else Path(path)
        if target.exists() and not target.is_file():  # checked by the command line before
            raise OutputError(f"{path!r} is not a regular file (a device, pipe or socket): "
                              "the result is written to a new file that replaces it", field="path")
        target.parent.mkdir(parents=True, exist_ok=True)
        tmp = target.with_name(f".{target.name}.{os.getpid()}.partial")
    with _signals_unwind():  # a kill or Ctrl-C removes the partial file, as an error does
        return _write(sweep, path, fmt, indent, stream, progress, keep, N, size, stats, target,
                      tmp)


def _write(sweep, path, fmt, indent, stream, progress, keep, N, size, stats, target, tmp):
    """The chunks of :func:`write_sweep`, solved and written into ``tmp`` (renamed to
    ``target`` when complete)."""
    fh = None
    writer: Writer
    bar = None
    try:
        if path is None and stream is None:
            writer = NoWriter()
        elif fmt in ("json", "csv"):
            if stream is not None:
                fh = stream
            else:
                fh = open(tmp, "w", encoding="utf-8", newline="")
            writer = JsonWriter(fh, indent) if fmt == "json" else CsvWriter(fh)
        elif stream is not None:
            raise OutputError(f"{fmt} is a binary format: give a path, not a text stream",
                              field="format")
        elif fmt == "npz":
            writer = NpzWriter(tmp)
        else:
            writer = ParquetWriter(tmp)
        bar = progress_bar(N, progress)
        advance = bar.update if bar is not None else (lambda n: None)
        writer.begin(stats)
        prev = None
        for a, b in chunk_bounds(N, size):
            lo = a - 1 if a > 0 else 0  # the previous chunk's last step, solved again
            before = sweep.waypoints(lo)
            res = sweep.solve(lo, b, before)
            skip = len(before) + a - lo
            if prev is not None:
                join_rotations(prev, res, skip - 1, lo)
            stats.add(res, a, skip, keep_warnings=keep)
            writer.write(res, skip, a, stats, advance)
            if keep:
                stats.analysis = res
            prev = _last_rotations(res)  # the next chunk joins this one's last step
            del res
        writer.finish(stats)
        if fh is not None and fh is not stream:
            fh.close()
            fh = None
        if tmp is not None:
            os.replace(tmp, target)
    except BaseException:
        if fh is not None and fh is not stream:
            fh.close()
        if path is not None:
            writer_obj = locals().get("writer")
            if writer_obj is not None:
                writer_obj.discard()
            if tmp is not None and tmp.exists():
                tmp.unlink()
        raise
    finally:
        if bar is not None:
            bar.close()
    return stats
