"""The motors of the drivers (``drivers[i].motor``) and the ``simulate`` section of a scene.

Both belong to the contract's second part (``docs/scene-format.md``, "Motors and the motion
of the machine"): a motor gives its driver's effort as a function of the driver's speed, a
constant or a table ``[[speed, effort], ...]`` (speeds strictly increasing, linear between
rows, the end rows' effort held beyond them); ``simulate`` says from which state and for how
long the motion of the machine driven by its motors is integrated.  The readers here are
parts of the scene reader of :mod:`linkage_sym.scene.validate` and report each problem with
its field, as every section does.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from linkage_sym.model.scene import Driver, Motor, Simulation
from linkage_sym.scene.fields import ANGLE, FieldReader, show_value

__all__ = ["MAX_SAMPLES", "MOTOR_KEYS", "SIMULATE_KEYS", "read_motor", "read_simulation"]

MOTOR_KEYS = ("torque", "force")
SIMULATE_KEYS = ("duration", "start_deg", "start", "start_speed", "samples")

MAX_SAMPLES = 10_000_000
"""Most ``simulate.samples``: each sample is a step of the result, analysed as ``analyze``
analyses a step (a few hundred numbers for a six-bar with every output), so ten million
of them take tens of gigabytes; a count below it is still checked against the memory this
process can take when the simulation runs."""


def read_motor(reader: FieldReader, entry: Mapping[str, Any], path: str,
               kind: str | None) -> Motor | None:
    """The ``motor`` of the driver ``entry`` at ``path`` on a joint of type ``kind``
    (``None`` when unknown: only what is given is checked); ``None`` without a motor."""
    if "motor" not in entry:
        return None
    where = f"{path}.motor"
    motor = entry["motor"]
    if not reader.object(motor, where):
        return None
    reader.keys(motor, where, MOTOR_KEYS)
    key = {"R": "torque", "P": "force"}.get(kind or "")
    if key is not None:
        other = "force" if key == "torque" else "torque"
        unit = "N m against rad/s" if key == "torque" else "N against m/s"
        reader.forbid(motor, where, (other,), f"on the motor of a{'n' if kind == 'R' else ''} "
                      f"{kind} driver (give '{key}', {unit})")
        if key not in motor:
            reader.missing(f"{where}.{key}", f"the motor of a{'n' if kind == 'R' else ''} {kind} "
                           f"driver gives its {key} (a constant or a table [[speed, {key}], ...])")
            return None
    for name in MOTOR_KEYS if key is None else (key,):
        if name in motor:
            table = _effort_table(reader, motor[name], f"{where}.{name}")
            if key is not None and table is not None:
                return Motor(key, *table)
    return None


def _effort_table(reader: FieldReader, value: Any, field: str) -> tuple | None:
    """``(speeds, efforts)`` of a motor's constant or table at ``field``."""
    before = len(reader.problems)
    if not isinstance(value, (list, tuple)):
        number = reader.number({"v": value}, "v", "", default=None)
        if number is None or len(reader.problems) > before:
            del reader.problems[before:]
            reader.add(field, f"must be a number or a table [[speed, effort], ...], "
                       f"got {show_value(value)}")
            return None
        return (0.0,), (number,)
    if not value:
        reader.add(field, "must have at least one row [speed, effort], got []")
        return None
    speeds, efforts = [], []
    for i, row in enumerate(value):
        point = reader.point({"r": row}, "r", "", default=None,
                             expected="a row [speed, effort] of 2 finite numbers")
        if len(reader.problems) > before:  # reword the row's problem with its field
            problem = reader.problems[before].split(": ", 1)[1]
            del reader.problems[before:]
            reader.add(f"{field}[{i}]", problem)
            return None
        assert point is not None
        if speeds and not point[0] > speeds[-1]:
            reader.add(f"{field}[{i}][0]", f"speeds must increase strictly from row to row: "
                       f"{point[0]:g} follows {speeds[-1]:g}")
            return None
        speeds.append(point[0])
        efforts.append(point[1])
    return tuple(speeds), tuple(efforts)


def read_simulation(reader: FieldReader, data: Mapping[str, Any],
                    drivers: tuple[Driver, ...], n_drivers: int) -> Simulation | None:
    """The top-level ``simulate`` section (``None`` when absent), read against the valid
    ``drivers`` among the scene's ``n_drivers`` entries."""
    if "simulate" not in data:
        return None
    sim = data["simulate"]
    if not reader.object(sim, "simulate"):
        return None
    reader.keys(sim, "simulate", SIMULATE_KEYS)
    before = len(reader.problems)
    duration = reader.number(sim, "duration", "simulate", why="how long to simulate (s)")
    if duration is not None and not duration > 0:
        reader.add("simulate.duration", f"must be a number > 0 (seconds), got {duration:g}")
    samples = reader.integer(sim, "samples", "simulate", minimum=2)
    if samples is not None and samples > MAX_SAMPLES:
        reader.add("simulate.samples", f"{samples} samples are too many for memory: each is a "
                   f"step of the result, analysed as analyze analyses a step (a few hundred "
                   f"numbers each); at most {MAX_SAMPLES} are allowed")
    if n_drivers > 1:  # several motors: the starts are lists over the drivers (an extension)
        if len(drivers) != n_drivers:  # a driver has a problem of its own
            return None
        starts = _several_starts(reader, sim, drivers)
        if len(reader.problems) > before or starts is None:
            return None
        assert duration is not None and samples is not None
        return Simulation(duration, starts[0], starts[1], samples)
    start_speed = reader.number(sim, "start_speed", "simulate", default=0.0)
    if not drivers:  # the driver has a problem of its own
        return None
    driver = drivers[0]
    if driver.kind == "R":
        reader.forbid(sim, "simulate", ("start",), f"with an R driver (give start_deg in degrees)")
        start_deg = reader.number(sim, "start_deg", "simulate", default=None, **ANGLE)
        start = driver.start if start_deg is None else math.radians(start_deg)
    else:
        reader.forbid(sim, "simulate", ("start_deg",), f"with a P driver (give start in metres)")
        start = reader.number(sim, "start", "simulate", default=driver.start)
        if start is not None and "start" in sim:
            reader.slides.append(("simulate.start", start))  # type: ignore[attr-defined]
    if len(reader.problems) > before or start is None:
        return None
    assert duration is not None and samples is not None and start_speed is not None
    return Simulation(duration, start, start_speed, samples)


def _several_starts(reader: FieldReader, sim: Mapping[str, Any],
                    drivers: tuple[Driver, ...]) -> tuple[tuple, tuple] | None:
    """The starts ``(values, speeds)`` of several drivers: ``start_deg`` (the ``R`` drivers'),
    ``start`` (the ``P`` drivers') and ``start_speed``, each a list with one entry per driver
    in the order of ``drivers``, ``null`` where a driver keeps its default (its sweep's
    start; a speed of 0) or where the entry is the other kind's."""
    n = len(drivers)
    lists = {}
    for key in ("start_deg", "start", "start_speed"):
        if key not in sim:
            lists[key] = [None] * n
            continue
        value = sim[key]
        if not isinstance(value, (list, tuple)) or len(value) != n:
            reader.add(f"simulate.{key}", f"with {n} drivers, must be a list of {n} entries, "
                       f"one per driver in the order of drivers (null for the default), got "
                       f"{show_value(value)}")
            return None
        lists[key] = list(value)
    values, speeds, ok = [], [], True
    for i, d in enumerate(drivers):
        key, other = ("start_deg", "start") if d.kind == "R" else ("start", "start_deg")
        if lists[other][i] is not None:
            unit = "start_deg, degrees" if d.kind == "R" else "start, metres"
            reader.add(f"simulate.{other}[{i}]", f"must be null: driver {i} is an {d.kind} "
                       f"driver (its start goes in {unit})")
            ok = False
        got = _entry(reader, lists[key][i], f"simulate.{key}[{i}]",
                     ANGLE if d.kind == "R" else {})
        speed = _entry(reader, lists["start_speed"][i], f"simulate.start_speed[{i}]", {})
        ok = ok and got is not False and speed is not False
        if got is None or got is False:
            values.append(d.start)
        elif d.kind == "R":
            values.append(math.radians(got))
        else:
            values.append(got)
            reader.slides.append((f"simulate.start[{i}]", got))  # type: ignore[attr-defined]
        speeds.append(speed if isinstance(speed, float) else 0.0)
    return (tuple(values), tuple(speeds)) if ok else None


def _entry(reader: FieldReader, value: Any, field: str, limits: dict) -> float | bool | None:
    """One list entry at ``field``: its number, ``None`` for ``null``, ``False`` (the problem
    reported) for anything else."""
    if value is None:
        return None
    before = len(reader.problems)
    got = reader.number({"v": value}, "v", "", **limits)
    if got is None or len(reader.problems) > before:
        problem = reader.problems[before].split(": ", 1)[1]
        del reader.problems[before:]
        reader.add(field, problem)
        return False
    return float(got)
