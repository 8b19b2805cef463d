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
    start_speed = reader.number(sim, "start_speed", "simulate", default=0.0)
    if n_drivers != 1:
        reader.add("simulate", f"the scene has {n_drivers} drivers; simulating several motors "
                   "(a mechanism of several degrees of freedom) is not implemented yet: "
                   "simulate drives a mechanism of one degree of freedom by one motor")
        return None
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
