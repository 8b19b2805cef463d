"""What the chunks of a sweep add up to: statuses, peaks and the warnings of one whole run
(:class:`SweepStats`), merged chunk by chunk by :func:`linkage_sym.output.write_sweep`."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np

from linkage_sym.numeric.engine.run import WARN_COND, cancelling_warning, ill_conditioned_warning, run_warnings
from linkage_sym.numeric.results.efficiency import driver_work
from linkage_sym.numeric.results.result import OK, UNASSEMBLABLE, Analysis
from linkage_sym.numeric.results.strict_json import LeftOut
from linkage_sym.numeric.results.wording import driver_number
from linkage_sym.numeric.forces.policy import AMPLIFICATION_LIMIT



# ------------------------------------------------------------------ merging chunks


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
class StepRuns:
    """Runs of consecutive steps of one status over the chunks of a sweep: each run's first and
    last step with the drivers' values there (``runs``: ``[first, last, q_first, q_last]``).

    ``count`` steps in ``n_runs`` runs; ``runs`` keeps the first :data:`MAX_RANGES` and the
    latest (to join the next chunk's), so memory stays bounded on any sweep.
    """

    count: int = 0
    n_runs: int = 0
    runs: list = field(default_factory=list)

    def add(self, mask, offset: int, q: dict) -> None:
        """Add the steps of ``mask`` (sweep steps ``offset...``; ``q[name]``: the drivers'
        values at those steps)."""
        mask = np.asarray(mask, bool)
        if not mask.any():
            return
        self.count += int(mask.sum())
        edges = np.flatnonzero(np.diff(np.concatenate([[0], mask.astype(np.int8), [0]])))
        for a, b in zip(edges[::2].tolist(), (edges[1::2] - 1).tolist()):
            qa = {k: float(v[a]) for k, v in q.items()}
            qb = {k: float(v[b]) for k, v in q.items()}
            if self.runs and self.runs[-1][1] == offset + a - 1:  # continues the last chunk's
                self.runs[-1][1], self.runs[-1][3] = offset + b, qb
                continue
            self.n_runs += 1
            if len(self.runs) > MAX_RANGES:  # only the latest is needed beyond the first
                self.runs.pop()
            self.runs.append([offset + a, offset + b, qa, qb])


def step_ranges(mask, drivers: dict) -> StepRuns:
    """The runs of ``True`` in ``mask`` (a boolean per step) of one whole run, with the
    drivers' values (``drivers[name]``: the values at every step).

    Examples
    --------
    >>> r = step_ranges([False, True, True, False, True], {"A": [0.0, 0.1, 0.2, 0.3, 0.4]})
    >>> r.count, [run[:2] for run in r.runs]
    (3, [[1, 2], [4, 4]])
    """
    out = StepRuns()
    out.add(mask, 0, {k: np.asarray(v, float) for k, v in drivers.items()})
    return out


def step_at(q: dict, drivers: dict, n_steps: int) -> int | None:
    """The step of a sweep at the driver values ``drivers`` (one value per driver), or None.

    ``q[name]``: the sweep's values of each driver, at its ``n_steps`` steps.  The rule: the
    first step at which every driver has exactly (``==``) the value given.  A step's result
    carries the sweep's own driver values (the same float64 numbers), so its step is found;
    values computed anew (rounded otherwise, e.g. by a solver in more precision) name no
    step, and a sweep that passes the same driver values twice names its first.

    Examples
    --------
    >>> q = {"A": [0.0, 0.5, 1.0, 0.5]}
    >>> step_at(q, {"A": 0.5}, 4), step_at(q, {"A": 0.5 + 2e-16}, 4)
    (1, None)
    >>> step_at(q, {}, 4)
    0
    """
    mask = np.ones(n_steps, bool)
    for name, value in drivers.items():
        mask &= np.asarray(q[name], float) == value
    hits = np.flatnonzero(mask)
    return int(hits[0]) if len(hits) else None


MAX_RANGES = 8
"""Driver ranges a summary names before it says how many more there are."""


def ranges_text(what: str, runs: StepRuns, kinds: dict) -> str:
    """One line on steps of one kind: how many, and the driver ranges they cover.

    The one wording of every message that counts steps of a status (``analyze``'s summary,
    ``demo``): ``unassemblable: 12 steps, A 100°..155°, 205°..260°``.

    Parameters
    ----------
    what : str
        The steps' status (``"unassemblable"``).
    runs : StepRuns
    kinds : dict
        Each driver's joint type (``"R"``: values in degrees, ``"P"``: in m).

    Examples
    --------
    >>> import math
    >>> r = step_ranges([0, 1, 1, 0, 1, 1, 1], {"A": [math.radians(x) for x in range(0, 70, 10)]})
    >>> ranges_text("unassemblable", r, {"A": "R"})
    'unassemblable: 5 steps, A 10°..20°, 40°..60°'
    >>> r = step_ranges([1, 0], {"A": [0.0, 1.0], "s": [0.25, 0.5]})
    >>> ranges_text("unassemblable", r, {"A": "R", "s": "P"})
    'unassemblable: 1 step, A 0° with s 0.25 m'
    >>> r = step_ranges([k % 2 for k in range(21)], {"A": [math.radians(x) for x in range(21)]})
    >>> ranges_text("unassemblable", r, {"A": "R"})
    'unassemblable: 10 steps, A 1°, 3°, 5°, 7°, 9°, 11°, 13°, 15° and 2 more ranges'
    """
    def value(name, v):  # the number of driver_number's words, without its unit
        return driver_number(v, kinds[name]).removesuffix("°").removesuffix(" m")

    def span(name, qa, qb, first):
        unit = "°" if kinds[name] == "R" else " m"
        a, b = value(name, qa[name]), value(name, qb[name])
        text = f"{a}{unit}" if a == b else (f"{a}{unit}..{b}{unit}" if kinds[name] == "R"
                                            else f"{a}..{b}{unit}")
        return f"{name} {text}" if first else text

    names = list(kinds)
    parts = []
    for k, (_, _, qa, qb) in enumerate(runs.runs[:MAX_RANGES]):
        if len(names) == 1:
            parts.append(span(names[0], qa, qb, k == 0))
        else:
            parts.append(" with ".join(span(n, qa, qb, True) for n in names))
    more = runs.n_runs - MAX_RANGES
    tail = f" and {more} more range{'s' if more != 1 else ''}" if more > 0 else ""
    sep = ", " if len(names) <= 1 else "; "
    steps = f"{runs.count} step{'s' if runs.count != 1 else ''}"
    return f"{what}: {steps}" + (f", {sep.join(parts)}{tail}" if parts else "")


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


@dataclass
class DriverWork:
    """The work of a sole driver over the ``ok`` steps of a sweep's chunks, with its joints'
    friction (``work_in``) and with it left out (``work_out``): the trapezoidal rule on each
    pair of consecutive ``ok`` steps (contract part two: the mean efficiency is
    ``work_out / work_in``).  ``friction_peak``: the largest power the friction dissipates."""

    work_in: float = 0.0
    work_out: float = 0.0
    friction_peak: Peak = field(default_factory=Peak)

    def add(self, res: Analysis, offset: int, skip: int) -> None:
        """Add the pairs of steps of ``res`` not added before (from step ``skip - 1`` on)."""
        f = res.forces
        (name,) = f.driving
        a = max(skip - 1, 0)
        q = np.asarray(res.drivers[name]["q"], float)[a:]
        ok = (res.status == OK)[a:]
        for key, e in (("work_in", f.driving[name][a:]), ("work_out", f.driving_ideal[name][a:])):
            setattr(self, key, getattr(self, key) + driver_work(q, ok, e))
        self.friction_peak.add(f.friction_power[skip:], offset, res, skip)

    def efficiency(self) -> float | None:
        """``work_out / work_in`` when the driver's work (with the friction) is positive."""
        return self.work_out / self.work_in if self.work_in > 0 else None


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
        self.unassemblable = StepRuns()  # the unassemblable steps' runs, with driver values
        forces = template.forces
        self.work = (DriverWork() if forces is not None and forces.driving_ideal is not None
                     and len(forces.driving) == 1 else None)  # friction: the mean efficiency
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
        self.unassemblable.add(status == UNASSEMBLABLE, offset,
                               {k: np.asarray(d["q"], float)[skip:] for k, d in res.drivers.items()})
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
        if self.work is not None:
            self.work.add(res, offset, skip)
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
            out.append(ill_conditioned_warning(f.count, f.first, f.worst, f.worst_step))
        if self.template.forces is not None:
            for g, f in zip(self.template.forces.groups, self._amplified):
                if f is not None and f.count:
                    out.append(cancelling_warning(g.links, f.count, f.first, f.worst, f.worst_step))
        return out

    def tail(self) -> dict:
        """The result's keys after ``steps`` for the whole sweep."""
        work = None if self.work is None else (self.work.work_in, self.work.work_out)
        return self.template.tail(warnings=self.warnings, dropped=self.left_out,
                                  steps_per_choice=self._choices, work=work)

    def meta(self) -> dict:
        """The result's keys but ``steps`` (the metadata of the columnar formats)."""
        return {**self.template.head(), **self.tail()}

    @property
    def any_assembled(self) -> bool:
        return any(n for s, n in self.counts.items() if s != UNASSEMBLABLE)


# ------------------------------------------------------------------ columns


