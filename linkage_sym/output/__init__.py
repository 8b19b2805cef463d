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

This module is outside the numeric core: it may use tqdm (a progress bar,
optional extra ``progress``) and pyarrow (optional extra ``parquet``), which
the core never imports.
"""

from __future__ import annotations

import io
import json
import math
import os
import re
import shutil
import sys
import tempfile
import zipfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

from linkage_sym.numeric.sweep import WARN_COND, run_warnings
from linkage_sym.numeric.result import OK, UNASSEMBLABLE, Analysis, LeftOut
from linkage_sym.numeric.superposition import AMPLIFICATION_LIMIT

FORMATS = ("json", "csv", "npz", "parquet")
SUFFIXES = {".json": "json", ".csv": "csv", ".npz": "npz", ".parquet": "parquet", ".pq": "parquet"}

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

Measured with tracemalloc on the shipped examples (tests/test_output_formats.py
holds every example's measured peak under the estimate): a run's result block
plus its temporaries peak at 1.8 (dyad), 5.5 (global: the sparse systems),
2.3 (symbolic) times the result."""
NEWTON_FACTOR = 4.0
"""Added to :data:`PEAK_FACTOR` for mechanisms with Newton groups (the path's solutions,
about 4.2 times the result for the class-III six-bar)."""
WRITER_BYTES = {"json": 0, "csv": 0, "npz": 0, "parquet": 24}
"""Bytes per number and step a writer holds while it writes a chunk (parquet: the
Arrow arrays with their validity masks, and the encoded pages)."""
FIXED_BYTES = 64 * 2**20
"""Memory a run needs besides its chunk (a JSON or CSV block of records, buffers)."""

ProgressFn = Callable[[int], None]


class OutputError(Exception):
    """A result file that will not be written: refused before anything is computed or written.

    ``problems``: one sentence each (the command line exits with status 2).
    """

    def __init__(self, problems):
        self.problems = [problems] if isinstance(problems, str) else list(problems)
        super().__init__("; ".join(self.problems))


def output_format(path: str | None, given: str | None = None) -> str:
    """The format of a result file: ``given``, else from the suffix of ``path``, else ``json``."""
    if given is not None:
        if given not in FORMATS:
            raise OutputError(f"--format: {given!r} is not one of {', '.join(FORMATS)}")
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
        raise OutputError(
            "--format parquet needs pyarrow, which is not installed: "
            "pip install 'linkage_sym[parquet]'") from err
    return pa, pq


# ------------------------------------------------------------------ memory


def _read_int(path: str) -> int | None:
    try:
        text = Path(path).read_text().strip()
    except OSError:
        return None
    return int(text) if text.isdigit() else None


def available_memory() -> int | None:
    """Bytes this process can still take (``None`` if unknown).

    Linux's estimate of memory available without swapping (``MemAvailable``
    of ``/proc/meminfo``), lowered to what a cgroup's memory limit leaves
    (v2 ``memory.max - memory.current``, v1 ``limit_in_bytes -
    usage_in_bytes``); elsewhere the free physical pages.
    """
    found = []
    try:
        for line in Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemAvailable:"):
                found.append(int(line.split()[1]) * 1024)
                break
    except (OSError, ValueError, IndexError):
        pass
    for limit, usage in (("/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current"),
                         ("/sys/fs/cgroup/memory/memory.limit_in_bytes",
                          "/sys/fs/cgroup/memory/memory.usage_in_bytes")):
        lim, use = _read_int(limit), _read_int(usage)
        if lim is not None and use is not None and lim < 2**60:
            found.append(max(0, lim - use))
    if not found:
        try:
            found.append(os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
        except (ValueError, OSError, AttributeError):
            return None
    return min(found)


def bytes_per_step(n_values: int, method: str, newton: bool, fmt: str | None = None) -> int:
    """Estimated peak memory per step of a chunk: solving it, and writing it in ``fmt``.

    ``n_values``: the numbers of one step's result (its numeric columns).
    """
    factor = PEAK_FACTOR[method] + (NEWTON_FACTOR if newton else 0.0)
    per_value = 8 * factor + WRITER_BYTES.get(fmt, 0)
    return int(math.ceil(per_value * (n_values + 16)))  # + status, message, condition, drivers


def _size(n: float) -> str:
    return f"{n / 2**30:.2f} GB" if n >= 2**30 else f"{n / 2**20:.0f} MB"


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


def check_whole(n_steps: int, per_step: int, available: int | None, why: str) -> None:
    """Refuse (:class:`OutputError`) a whole sweep held in memory at once that would not fit."""
    need = n_steps * per_step + FIXED_BYTES
    if available is not None and need > available:
        raise OutputError(
            f"not enough memory: {why} needs the whole sweep in memory, about {_size(need)} for "
            f"{n_steps} steps ({_size(per_step)} a step), and the machine has {_size(available)} "
            "available; nothing written (fewer steps, or leave it out)")


# ------------------------------------------------------------------ the sweep


@dataclass
class Sweep:
    """A sweep to solve in chunks: ``run(q, qd, qdd)`` solves any of its steps.

    ``heads`` are the Newton groups' names as their warnings begin
    (``"triad (b1, t, b2, b3)"``), in the order a run lists their warnings.
    ``q0`` is each driver's value in the assembly configuration and
    ``limits`` its largest increment along a solving path (see
    :func:`linkage_sym.numeric.sweep.solving_path`): with them,
    :meth:`waypoints` lets a chunk's path take the whole sweep's route.
    """

    run: Callable[..., Analysis]
    q: dict
    qd: dict
    qdd: dict
    method: str = "dyad"
    heads: list = field(default_factory=list)
    q0: dict = field(default_factory=dict)
    limits: dict = field(default_factory=dict)

    @property
    def n_steps(self) -> int:
        return len(next(iter(self.q.values())))

    def solve(self, a: int, b: int, waypoints=()) -> Analysis:
        """Steps ``a`` to ``b`` of the sweep, after the steps ``waypoints`` (indices)."""
        idx = np.concatenate([np.asarray(waypoints, dtype=np.intp), np.arange(a, b)])
        part = [{k: np.asarray(v)[idx] for k, v in d.items()} for d in (self.q, self.qd, self.qdd)]
        return self.run(*part)

    def waypoints(self, a: int) -> np.ndarray:
        """Steps of the sweep a chunk starting at step ``a`` solves first, so that its path
        takes the whole sweep's route: from the assembly configuration to the sweep's first
        step, then along the sweep.

        A run's path goes from the assembly configuration straight to its
        first step.  Where the sweep does not start at the assembly
        configuration, the whole sweep's path first goes back to its start;
        a Newton group may pass a limit position on the way and go on in
        another configuration of its assembly mode (a jump, warned), which
        the straight path to a later step would not.  So such a chunk also
        solves every ``m``-th step before it, ``m`` the most steps whose
        driver increments stay within the path's limits (so the path's
        refinement is the sweep's).  Closed-form groups have no such memory
        (their rotations are joined across chunks by whole turns): no
        waypoints for them, nor where the sweep starts at the assembly
        configuration.
        """
        if a <= 0 or not self.heads or self._straight(a):
            return np.zeros(0, dtype=np.intp)
        m = math.inf
        for k, v in self.q.items():
            h = abs(float(v[1]) - float(v[0])) if len(v) > 1 else 0.0
            if h > 0:
                m = min(m, self.limits[k] / h)
        m = 1 if not math.isfinite(m) else max(1, int(m))
        return np.arange(0, a, m, dtype=np.intp)

    def _straight(self, a: int) -> bool:
        """Whether the straight path from the assembly configuration to step ``a`` is the
        sweep's route: the sweep starts at the assembly configuration (to a millionth of a
        path increment), or its one driver starts between the assembly value and step ``a``."""
        if all(abs(float(self.q[k][0]) - v) <= 1e-6 * self.limits[k] for k, v in self.q0.items()):
            return True
        if len(self.q) == 1:
            (k, v), = self.q.items()
            return (float(v[0]) - self.q0[k]) * (float(v[a]) - float(v[0])) >= 0
        return False

    def most_waypoints(self) -> int:
        """The most waypoints of any chunk (the last)."""
        return len(self.waypoints(self.n_steps - 1))


def _limits(scene, L) -> dict:
    from linkage_sym.numeric.sweep import MAX_ANGLE_STEP, MAX_SLIDE_STEP

    return {d.joint: MAX_ANGLE_STEP if scene.joint(d.joint).type == "R" else MAX_SLIDE_STEP * L
            for d in scene.drivers}


def plan_sweep(plan, method: str = "dyad") -> Sweep:
    """The scene's sweep solved by a numeric plan (``compile_plan``) with a force method."""
    from linkage_sym.numeric.newton import NewtonSolver

    q, qd, qdd = plan.sweep()
    heads = [f"{sv.group.label} ({', '.join(sv.links)})" for sv in plan.solvers
             if isinstance(sv, NewtonSolver)]
    return Sweep(lambda q, qd, qdd: plan.run(q, qd, qdd, method=method), q, qd, qdd, method, heads,
                 dict(plan.q0), _limits(plan.scene, plan.L))


def compiled_sweep(mechanism) -> Sweep:
    """The scene's sweep evaluated by a compiled mechanism (``compile_mechanism``)."""
    art = mechanism.art
    groups = {g["index"]: g for g in art["groups"]}
    heads = [f"{groups[st['group']]['label']} ({', '.join(groups[st['group']]['links'])})"
             for st in art["steps"] if st["kind"] != "closed"]
    q, qd, qdd = mechanism.sweep()
    return Sweep(lambda q, qd, qdd: mechanism.run(q, qd, qdd), q, qd, qdd, "symbolic", heads,
                 dict(mechanism.q0), _limits(mechanism.scene, mechanism.L))


def chunk_bounds(n_steps: int, size: int):
    """``(start, stop)`` of each chunk of ``size`` steps."""
    return [(a, min(n_steps, a + size)) for a in range(0, n_steps, size)]


# ------------------------------------------------------------------ merging chunks


def _steps_text(first: list, count: int) -> str:
    """The steps of a warning: the first five, and how many more (as a whole run words them)."""
    return ", ".join(map(str, first[:5])) + (f" and {count - 5} more" if count > 5 else "")


@dataclass
class _Flagged:
    """Steps flagged by a warning over the chunks: how many, the first five, the worst."""

    count: int = 0
    first: list = field(default_factory=list)
    worst: float = -math.inf
    worst_step: int = -1

    def add(self, steps: np.ndarray, values: np.ndarray) -> None:
        if not len(steps):
            return
        self.count += len(steps)
        self.first += [int(i) for i in steps[: 5 - len(self.first)]]
        k = int(np.argmax(values))
        if values[k] > self.worst:  # strictly: the earliest of equal values, as argmax
            self.worst, self.worst_step = values[k], int(steps[k])


@dataclass
class Peak:
    """The largest ``|value|`` of a series over the chunks: its step, signed value, driver values."""

    step: int = -1
    value: float = 0.0
    drivers: dict = field(default_factory=dict)

    def add(self, values: np.ndarray, offset: int, res: Analysis, skip: int) -> None:
        v = np.abs(np.asarray(values, dtype=float))
        finite = np.isfinite(v)
        if not finite.any():
            return
        i = int(np.nanargmax(np.where(finite, v, np.nan)))
        if self.step < 0 or v[i] > abs(self.value):
            self.step = offset + i
            self.value = float(np.asarray(values, dtype=float)[i])
            self.drivers = {k: float(d["q"][skip + i]) for k, d in res.drivers.items()}

    def __bool__(self) -> bool:
        return self.step >= 0


_NOTE_STEP = re.compile(r"; at step (\d+)( \(reached from (?:step (\d+)|the assembly configuration)\))?"
                        r" it continues")


class SweepStats:
    """What a sweep's chunks add up to: statuses, peaks and warnings of the whole sweep.

    ``SweepStats.of(analysis)`` gives a whole run's; :func:`write_sweep` adds
    its chunks one after the other (:meth:`add`).  The peaks and counts are
    those the command line's summary prints; :attr:`warnings` are those a whole
    run's ``Analysis.warnings`` holds.
    """

    def __init__(self, template: Analysis, heads=()):
        self.template = template  # a run of one step: the result's head, groups, stages
        self.heads = list(heads)
        self.n_steps = 0
        self.counts: dict = {}
        self.first_message = None
        self.stages = template.stages
        self.outputs = template.outputs
        self.has_forces = template.forces is not None
        self.driving: dict = {}
        self.reactions: dict = {}
        self.frame_force = Peak()
        self.frame_moment = Peak()
        self._notes: list = []  # (group order, text) of the Newton groups' jumps
        self._other: list = []  # a chunk's warnings of another kind, as they are
        self._ill = _Flagged()
        groups = template.forces.groups if template.forces is not None else []
        self._amplified = [_Flagged() if g.amplification is not None else None for g in groups]
        self._choices = [None if g.used is None else [0] * len(g.choices) for g in groups]
        self.left_out = LeftOut()
        self.analysis: Analysis | None = None  # the whole run, when it was kept

    @classmethod
    def of(cls, analysis: Analysis) -> "SweepStats":
        """The statistics of one whole run."""
        stats = cls(analysis)
        stats.add(analysis, 0, 0, keep_warnings=True)
        return stats

    # -- adding a chunk -------------------------------------------------------------
    def add(self, res: Analysis, offset: int, skip: int, keep_warnings: bool = False) -> None:
        """Add the steps ``skip:`` of ``res``, steps ``offset...`` of the sweep.

        ``skip``: leading steps of the chunk that an earlier chunk added (the
        previous chunk's last step, solved again).  ``keep_warnings``: the
        chunk is the whole sweep; its warnings are taken as they are.
        """
        n = res.n_steps - skip
        status = res.status[skip:]
        values, counts = np.unique(status, return_counts=True)
        first_seen = sorted(zip(values, counts), key=lambda p: int(np.argmax(status == p[0])))
        for s, c in first_seen:
            self.counts[str(s)] = self.counts.get(str(s), 0) + int(c)
        if self.n_steps == 0 and n:
            self.first_message = res.messages[skip]
        self.n_steps += n
        ok = status == OK
        forces = res.forces
        if forces is not None:
            if "driving" in res.outputs:
                for name, v in forces.driving.items():
                    self.driving.setdefault(name, Peak()).add(v[skip:], offset, res, skip)
            if "reactions" in res.outputs:
                for name, r in forces.reactions.items():
                    self.reactions.setdefault(name, Peak()).add(
                        np.hypot(r[skip:, 0], r[skip:, 1]), offset, res, skip)
            if "frame" in res.outputs:
                f = forces.frame_force[skip:]
                self.frame_force.add(np.hypot(f[:, 0], f[:, 1]), offset, res, skip)
                self.frame_moment.add(forces.frame_moment[skip:], offset, res, skip)
            for k, g in enumerate(forces.groups):
                if g.used is not None:
                    used = g.used[skip:]
                    for c in range(len(g.choices)):
                        self._choices[k][c] += int((used == c).sum())
                if g.amplification is not None:
                    with np.errstate(invalid="ignore"):
                        bad = np.flatnonzero(ok & (g.amplification[skip:] > AMPLIFICATION_LIMIT))
                    self._amplified[k].add(bad + offset, g.amplification[skip:][bad])
        with np.errstate(invalid="ignore"):
            ill = np.flatnonzero(ok & (res.condition[skip:] > WARN_COND))
        self._ill.add(ill + offset, res.condition[skip:][ill])
        self._add_notes(res, offset - skip, skip, keep_warnings)

    def _add_notes(self, res: Analysis, base: int, skip: int, whole: bool) -> None:
        """The chunk's own warnings but the merged kinds: the Newton groups' jumps, step
        numbers offset by ``base`` (the sweep's step of the chunk's step 0)."""
        own = run_warnings(res)
        notes = res.warnings[: len(res.warnings) - len(own)] if own else list(res.warnings)
        if own and res.warnings[len(notes):] != own:  # not the layout of a run's warnings
            self._other += [w for w in res.warnings if w not in own]
            return
        for text in notes:
            m = _NOTE_STEP.search(text)
            if m is None or whole:
                self._other.append(text)
                continue
            k = int(m.group(1))
            if k < skip:
                continue  # a step an earlier chunk solved, and warned about
            if m.group(2) is None:
                where = f"step {base + k}"
            elif m.group(3) is not None:
                where = f"step {base + k} (reached from step {base + int(m.group(3))})"
            else:  # only the first chunk's first step is reached from the assembly configuration
                where = f"step {base + k} (reached from the assembly configuration)"
            key = next((i for i, h in enumerate(self.heads) if text.startswith(h + " ")), len(self.heads))
            self._notes.append((key, text[: m.start()] + f"; at {where} it continues" + text[m.end():]))

    # -- the whole sweep -------------------------------------------------------------
    @property
    def warnings(self) -> list:
        """The warnings of a whole run: the Newton groups' jumps, group by group, then
        the condition-number and superposition warnings (``run_warnings``)."""
        out = [t for _, t in sorted(self._notes, key=lambda p: p[0])] + self._other
        f = self._ill
        if f.count:
            out.append(
                f"{f.count} ok step(s) have a condition number above {WARN_COND:.0e} (steps "
                f"{_steps_text(f.first, f.count)}; largest {f.worst:.3g} at step {f.worst_step}): "
                f"their velocities and accelerations carry about {np.log10(f.worst):.0f} "
                "fewer significant digits than their positions"
            )
        if self.template.forces is not None:
            for g, f in zip(self.template.forces.groups, self._amplified):
                if f is None or not f.count:
                    continue
                out.append(
                    f"group ({', '.join(g.links)}): the superposition cancels at {f.count} "
                    f"step(s) (steps {_steps_text(f.first, f.count)}; amplification up to "
                    f"{f.worst:.3g} at step {f.worst_step}) with every disconnection: "
                    f"its reactions lose about {np.log10(f.worst):.0f} digits there"
                )
        return out

    def tail(self) -> dict:
        """The result's keys after ``steps`` for the whole sweep."""
        return self.template.tail(warnings=self.warnings, dropped=self.left_out,
                                  steps_per_choice=self._choices)

    def meta(self) -> dict:
        """The result's keys but ``steps`` (the metadata of the columnar formats)."""
        return {**self.template.head(), **self.tail()}

    @property
    def any_assembled(self) -> bool:
        return any(n for s, n in self.counts.items() if s != UNASSEMBLABLE)


# ------------------------------------------------------------------ columns


def _numeric_columns(res: Analysis) -> list:
    return [(n, v, w) for n, v, w in res.columns() if n not in ("status", "message")]


# ------------------------------------------------------------------ writers


class _Writer:
    """A result file being written chunk by chunk."""

    def begin(self, stats: SweepStats) -> None:
        pass

    def write(self, res: Analysis, skip: int, offset: int, stats: SweepStats, progress: ProgressFn):
        raise NotImplementedError

    def finish(self, stats: SweepStats) -> None:
        pass

    def discard(self) -> None:
        pass


class JsonWriter(_Writer):
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


class CsvWriter(_Writer):
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


class NpzWriter(_Writer):
    """One array per column in a NumPy ``.npz`` (a zip of ``.npy`` files).

    Each chunk's columns are appended to one raw file per column in a
    temporary folder beside the result; :meth:`finish` copies them into the
    zip (numbers stored, the text columns compressed), so no column is ever
    whole in memory.  ``meta`` holds the JSON's keys but ``steps``.
    """

    def __init__(self, path: Path):
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
        shutil.rmtree(self.tmp, ignore_errors=True)


class ParquetWriter(_Writer):
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


class _NoWriter(_Writer):
    """No file: the statistics only (``analyze`` without ``-o``)."""

    def write(self, res, skip, offset, stats, progress):
        progress(res.n_steps - skip)


# ------------------------------------------------------------------ the run


def _progress_bar(total: int, enabled: bool):
    """A tqdm bar on standard error: only on a terminal, only after a second, only if installed."""
    if not enabled or not sys.stderr.isatty():
        return None
    try:
        from tqdm import tqdm
    except ImportError:  # the optional extra `progress` is not installed: no bar
        return None
    return tqdm(total=total, unit="step", unit_scale=True, file=sys.stderr, delay=1.0,
                leave=False, dynamic_ncols=True)


class ChunkError(RuntimeError):
    """Two chunks disagree at the step they share (a solver's path from the assembly
    configuration reached another configuration): never expected; nothing is written."""


def _last_rotations(res: Analysis) -> dict:
    """Each link's rotation at the chunk's last step (for the next chunk's :func:`_join`)."""
    return {n: float(lk.rotation[-1]) for n, lk in res.links.items()}


def _join(prev: dict, res: Analysis, at: int, step: int) -> None:
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
        raise OutputError(f"--format: {fmt!r} is not one of {', '.join(FORMATS)}")
    if fmt == "parquet" and (path is not None or stream is not None):
        require_pyarrow()
    N = sweep.n_steps
    template = sweep.solve(0, 1)
    stats = SweepStats(template, sweep.heads)
    per_step = bytes_per_step(len(_numeric_columns(template)), sweep.method, bool(sweep.heads), fmt)
    available = available_memory() if memory == "probe" else memory
    if keep:
        check_whole(N, per_step, available, "--plots")
        size = N
    else:
        size = chunk or chunk_steps(N, per_step, available, bool(sweep.heads),
                                    sweep.most_waypoints())
    target = tmp = None
    fh = None
    if path is not None:
        target = Path(path)
        target.parent.mkdir(parents=True, exist_ok=True)
        tmp = target.with_name(f".{target.name}.{os.getpid()}.partial")
    writer: _Writer
    bar = None
    try:
        if path is None and stream is None:
            writer = _NoWriter()
        elif fmt in ("json", "csv"):
            if stream is not None:
                fh = stream
            else:
                fh = open(tmp, "w", encoding="utf-8", newline="")
            writer = JsonWriter(fh, indent) if fmt == "json" else CsvWriter(fh)
        elif stream is not None:
            raise OutputError(f"--format {fmt}: a binary file; give -o FILE, not standard output")
        elif fmt == "npz":
            writer = NpzWriter(tmp)
        else:
            writer = ParquetWriter(tmp)
        bar = _progress_bar(N, progress)
        advance = bar.update if bar is not None else (lambda n: None)
        writer.begin(stats)
        prev = None
        for a, b in chunk_bounds(N, size):
            lo = a - 1 if a > 0 else 0  # the previous chunk's last step, solved again
            before = sweep.waypoints(lo)
            res = sweep.solve(lo, b, before)
            skip = len(before) + a - lo
            if prev is not None:
                _join(prev, res, skip - 1, lo)
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
