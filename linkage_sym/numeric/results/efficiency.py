"""The mean efficiency of a sweep with joint friction (contract part two; an extension of
its result: the top-level ``mean_efficiency``).

With one driver and ``effects.friction``, the driver's work over the sweep is the
trapezoidal rule on each pair of consecutive ``ok`` steps in its coordinate, with the
friction (``work_in``, its effort) and with it left out (``work_out``, its effort without
friction); the mean efficiency is ``work_out / work_in`` where ``work_in`` is positive.
The console summary and the result file say the same numbers, from a whole run or from
its chunks (:class:`linkage_sym.output.stats.DriverWork` adds them chunk by chunk).

Examples
--------
>>> import numpy as np
>>> ok = np.array([True, True, False, True, True])
>>> driver_work(np.arange(5.0), ok, np.array([1.0, 3.0, 9.0, 2.0, 2.0]))
4.0
>>> mean_efficiency_record(4.0, 3.0)
{'efficiency': 0.75, 'work_in': 4.0, 'work_out': 3.0}
"""

from __future__ import annotations

import numpy as np

__all__ = ["driver_work", "mean_efficiency_record", "run_work"]


def driver_work(q, ok, effort) -> float:
    """The trapezoidal rule of ``effort`` over ``q`` on each pair of consecutive ``ok`` steps."""
    q = np.asarray(q, float)
    pair = ok[1:] & ok[:-1]
    mid = 0.5 * (effort[1:] + effort[:-1])
    return float(np.sum(mid[pair] * np.diff(q)[pair]))


def mean_efficiency_record(work_in: float, work_out: float) -> dict:
    """The result's ``mean_efficiency``: ``efficiency`` (only where ``work_in`` is positive),
    ``work_in`` and ``work_out`` (J, or J/m... the driver's work: N·m·rad or N·m)."""
    out = {"efficiency": work_out / work_in} if work_in > 0 else {}
    return {**out, "work_in": work_in, "work_out": work_out}


def run_work(res) -> tuple | None:
    """``(work_in, work_out)`` of a whole run ``res`` (an Analysis), or ``None`` where it has
    no mean efficiency (not one driver, or no ``effects.friction``)."""
    f = res.forces
    if f is None or f.driving_ideal is None or len(f.driving) != 1:
        return None
    (name,) = f.driving
    ok = res.status == "ok"
    q = res.drivers[name]["q"]
    return driver_work(q, ok, f.driving[name]), driver_work(q, ok, f.driving_ideal[name])
