"""How messages word steps and driver values: one module, used by every message.

A run's warnings, the continuation's notes, the summaries' ranges, the accuracy report and
the limit positions all name steps (:func:`steps_text`) and driver values
(:func:`driver_number`, :func:`driver_values_text`) with these functions: an ``R``
driver's angle in degrees with a degree sign, a ``P`` driver's slide in metres, six
significant digits unless a message needs fixed decimals, never ``-0``.
"""

from __future__ import annotations

import math

__all__ = ["driver_number", "driver_values_text", "steps_text"]


def steps_text(first, count: int) -> str:
    """The steps of a warning: the first five, and how many more.

    Examples
    --------
    >>> steps_text(range(7), 7)
    '0, 1, 2, 3, 4 and 2 more'
    """
    return ", ".join(str(int(i)) for i in list(first)[:5]) + (
        f" and {count - 5} more" if count > 5 else "")


def driver_number(value: float, kind: str, decimals: int | None = None) -> str:
    """A driver's value in words: ``kind`` ``"R"`` an angle (rad, shown in degrees with
    ``°``), ``"P"`` a slide (m).  Six significant digits, or ``decimals`` fixed decimals;
    a value that shows as zero shows as ``0`` (never ``-0``).

    Examples
    --------
    >>> import math
    >>> driver_number(math.radians(30.0), "R"), driver_number(0.25, "P")
    ('30°', '0.25 m')
    >>> driver_number(-1e-12, "R", decimals=6)
    '0.000000°'
    """
    v = math.degrees(value) if kind == "R" else float(value)
    text = f"{v:.{decimals}f}" if decimals is not None else f"{v:.6g}"
    if float(text) == 0:
        text = text.lstrip("-")
    return text + ("°" if kind == "R" else " m")


def driver_values_text(values: dict, kinds: dict, decimals: int | None = None) -> str:
    """``A = 30°, s = 0.25 m``: each driver's value (:func:`driver_number`); ``kinds`` maps
    each driver's joint to ``"R"`` or ``"P"``.

    Examples
    --------
    >>> import math
    >>> driver_values_text({"A": math.radians(90.0), "s": 0.1}, {"A": "R", "s": "P"})
    'A = 90°, s = 0.1 m'
    """
    return ", ".join(f"{n} = {driver_number(v, kinds[n], decimals)}" for n, v in values.items())
