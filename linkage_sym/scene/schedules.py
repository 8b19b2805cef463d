"""Loads that vary over the cycle (an extension of the format; ``docs/scene-format.md``).

A load may follow one driver's value: ``table`` scales its force and torque by
a factor interpolated linearly between tabulated driver values, ``active``
lets it act only inside a range of them.  ``driver`` names the driven joint
(needed only when the scene has several drivers); for an ``R`` driver the
values are in degrees (``table.q_deg``, ``active_deg``) and repeat with
``period_deg`` (default 360; 720 for a four-stroke engine's cycle); for a
``P`` driver they are in metres (``table.q``, ``active``) and the table covers
the driver's sweep.

:func:`read_schedule` reads those keys of one load entry with the checks and
wording of :class:`~linkage_sym.scene.fields.FieldReader`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from linkage_sym.model.scene import Driver, LoadTable
from linkage_sym.scene.fields import ANGLE, FieldReader, did_you_mean

SCHEDULE_KEYS = ("driver", "table", "active", "active_deg", "period_deg")
"""The keys of a load entry that make it vary over the cycle."""
TABLE_KEYS = ("q", "q_deg", "scale")
SAME_ANGLE = 1e-12
"""Relative tolerance within which a table's span equals its period (first and last value one angle)."""


def _units(R: bool) -> str:
    return "degrees" if R else "metres"


def read_schedule(r: FieldReader, entry: Mapping[str, Any], path: str, drivers: tuple[Driver, ...]):
    """``(table, active, driver, period)`` of a load entry.

    ``(None, None, None, None)`` for a load that acts alike at every step;
    ``None`` when a problem was recorded in ``r``.
    """
    if not any(k in entry for k in SCHEDULE_KEYS):
        return None, None, None, None
    before = len(r.problems)
    if "table" not in entry and "active" not in entry and "active_deg" not in entry:
        given = [k for k in SCHEDULE_KEYS if k in entry]
        r.add(f"{path}.{given[0]}", "used only with a 'table' or an 'active' range of a driver's value")
        return None
    by_joint = {d.joint: d for d in drivers}
    d = None
    if "driver" in entry:
        name = r.name(entry, "driver", path)
        if name is not None and name not in by_joint:
            known = ", ".join(by_joint) or "none"
            r.add(f"{path}.driver", f"'{name}' is not a driven joint{did_you_mean(name, by_joint)} "
                  f"(driven joints: {known})")
        d = by_joint.get(name)
    elif len(drivers) == 1:
        d = drivers[0]
    elif drivers:
        r.missing(f"{path}.driver", f"the scene has several drivers ({', '.join(by_joint)}): name the "
                  "one whose value the table or range follows")
    if d is None:  # without valid drivers their own problems are reported
        return None
    R = d.kind == "R"
    period = None
    if "period_deg" in entry:
        if not R:
            r.add(f"{path}.period_deg", f"only for an R driver; {d.joint} is a P joint, whose table "
                  "or range is not repeated")
        else:
            pd = r.number(entry, "period_deg", path, minimum=0.0, **ANGLE)
            if pd is not None and pd <= 0:
                r.add(f"{path}.period_deg", f"must be a positive angle in degrees, got {pd:g}")
            elif pd is not None:
                period = math.radians(pd)
    elif R:
        period = 2 * math.pi
    table = _read_table(r, entry, path, d, period) if "table" in entry else None
    akey, wrong = ("active_deg", "active") if R else ("active", "active_deg")
    if wrong in entry:
        r.add(f"{path}.{wrong}", f"the driver {d.joint} is {'an R' if R else 'a P'} joint: give the "
              f"range as '{akey}' ({_units(R)})")
    active = None
    if akey in entry:
        a = r.numbers(entry, akey, path, length=2, angle=R)
        if a is not None:
            lo, hi = (math.radians(v) for v in a) if R else a
            if hi < lo:
                r.add(f"{path}.{akey}", "must be [from, to] with to >= from" + (
                    "; a range across 0 is written past the period, e.g. [300, 420]" if R else ""))
            elif R and period is not None and hi - lo > period * (1 + SAME_ANGLE):
                r.add(f"{path}.{akey}", f"spans {math.degrees(hi - lo):g} degrees, more than the "
                      f"period {math.degrees(period):g}")
            else:
                active = (lo, hi)
    if len(r.problems) > before:
        return None
    return table, active, d.joint, period


def _read_table(r: FieldReader, entry, path, d: Driver, period) -> LoadTable | None:
    tp = f"{path}.table"
    t = entry["table"]
    if not r.object(t, tp):
        return None
    R = d.kind == "R"
    r.keys(t, tp, TABLE_KEYS)
    qkey, wrong = ("q_deg", "q") if R else ("q", "q_deg")
    if wrong in t:
        r.add(f"{tp}.{wrong}", f"the driver {d.joint} is {'an R' if R else 'a P'} joint: give its "
              f"values as '{qkey}' ({_units(R)})")
        return None
    q = r.numbers(t, qkey, tp, min_length=2, angle=R)
    scale = r.numbers(t, "scale", tp, min_length=2)
    if q is None or scale is None:
        return None
    if len(q) != len(scale):
        r.add(f"{tp}.scale", f"must have as many numbers as {qkey} ({len(q)}), got {len(scale)}")
        return None
    if any(b <= a for a, b in zip(q, q[1:])):
        r.add(f"{tp}.{qkey}", "must be strictly increasing")
        return None
    if R:
        q = [math.radians(v) for v in q]
        span = q[-1] - q[0]
        if period is None:  # an invalid period_deg, reported already: nothing to hold it to
            pass
        elif abs(span - period) <= SAME_ANGLE * period:
            if scale[0] != scale[-1]:
                r.add(f"{tp}.scale", f"the first and last {qkey} are one angle (a period apart) with "
                      f"different factors {scale[0]:g} and {scale[-1]:g}")
                return None
            q, scale = q[:-1], scale[:-1]  # the same point of the cycle
        elif span > period:
            r.add(f"{tp}.{qkey}", f"spans {math.degrees(span):g} degrees, more than the period "
                  f"{math.degrees(period):g}: a driver angle must have one factor")
            return None
    else:
        lo, hi = min(d.start, d.stop), max(d.start, d.stop)
        if lo < q[0] or hi > q[-1]:
            r.add(f"{tp}.q", f"must cover the sweep of {d.joint}, {lo:g} to {hi:g} m (the factor "
                  "outside the table is not defined)")
            return None
    return LoadTable(tuple(q), tuple(scale))
