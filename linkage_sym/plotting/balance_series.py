"""The balancing plots' input series and what both figures share.

The series as drawn (:class:`Series`: its steps not ``ok`` set to NaN, its
colour and line style), which of them are numerically zero or small enough
for the zoom panel (:func:`scales`), the driver-value axis, the legend's
wording of peaks and gaps, the title and the tick labels; see
:mod:`linkage_sym.plotting.balance`.

Examples
--------
>>> import numpy as np
>>> from types import SimpleNamespace
>>> q = np.linspace(0.0, 2 * np.pi, 5)
>>> s = SimpleNamespace(label="s", q=q, status=np.array(["ok", "ok", "singular", "ok", "ok"]),
...                     force=np.ones((5, 2)), moment=np.sin(q))
>>> (one,) = read_series([s], "moment")
>>> one.n_bad, one.ok.tolist()
(1, [True, True, False, True, True])
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from linkage_sym.plotting import style

__all__ = [
    "OK_STATUS", "SMALL_RATIO", "ZERO_ABS", "ZERO_REL", "Series", "at_text", "cyclic", "finish",
    "gap_note", "read_series", "readable_ticks", "scales", "skipped_text", "x_axis", "zoom_factor",
]

SMALL_RATIO = 0.2
"""A series whose peak is below this fraction of the largest peak also gets the zoom panel."""

ZERO_ABS = 1e-12
"""A peak at or below this (N or N·m) is numerically zero."""

ZERO_REL = 1e-9
"""A peak at or below this fraction of the largest peak is numerically zero."""

OK_STATUS = "ok"
"""The status of a solved step; any other is a gap."""

_LINESTYLES = ("-", "--", "-.", ":")


@dataclass
class Series:
    """One input series, checked and with its non-``ok`` steps set to NaN."""

    label: str
    q: np.ndarray  # (N,) finite: NaN driver values interpolated over the step index
    status: np.ndarray  # (N,) str
    ok: np.ndarray  # (N,) bool: status ok and the value finite
    values: np.ndarray  # (N, 2) force or (N,) moment, NaN where not ok
    color: str
    linestyle: str
    q_known: bool = True  # False: no finite driver value, ``q`` is the step index

    @property
    def n(self) -> int:
        return len(self.q)

    @property
    def n_bad(self) -> int:
        """Steps whose status is not ``ok`` (skipped)."""
        return int(np.count_nonzero(self.status != OK_STATUS))

    def magnitude(self) -> np.ndarray:
        v = self.values
        return np.hypot(v[:, 0], v[:, 1]) if v.ndim == 2 else np.abs(v)

    def peak(self) -> tuple[float, int] | None:
        """``(largest magnitude, its step)`` over the solved steps, or None."""
        if not self.ok.any():
            return None
        mag = np.where(self.ok, self.magnitude(), -np.inf)
        k = int(np.argmax(mag))
        return float(mag[k]), k


def _fill_q(q: np.ndarray) -> np.ndarray:
    """``q`` with non-finite entries interpolated (or extrapolated flat) over the step index."""
    good = np.isfinite(q)
    if good.all():
        return q
    if not good.any():
        return np.arange(len(q), dtype=float)
    idx = np.arange(len(q))
    return np.interp(idx, idx[good], q[good])


def read_series(series_list, quantity: str) -> list:
    """Check the inputs and return one :class:`Series` per input, in order."""
    if hasattr(series_list, "status"):  # a single series
        series_list = [series_list]
    series_list = list(series_list)
    if not series_list:
        raise ValueError("no series to plot")
    out = []
    for i, s in enumerate(series_list):
        q = np.asarray(s.q, dtype=float).reshape(-1)
        n = len(q)
        status = np.asarray(s.status).astype(str).reshape(-1)
        if quantity == "force":
            values = np.array(s.force, dtype=float)
            if values.shape != (n, 2):
                raise ValueError(f"series {i} ({s.label!r}): force has shape {values.shape}, "
                                 f"expected ({n}, 2)")
            finite = np.all(np.isfinite(values), axis=1)
        else:
            values = np.array(s.moment, dtype=float)
            if values.shape != (n,):
                raise ValueError(f"series {i} ({s.label!r}): moment has shape {values.shape}, "
                                 f"expected ({n},)")
            finite = np.isfinite(values)
        if status.shape != (n,):
            raise ValueError(f"series {i} ({s.label!r}): status has shape {status.shape}, "
                             f"expected ({n},)")
        ok = (status == OK_STATUS) & finite
        values[~ok] = np.nan
        label = str(s.label) if str(s.label) else f"series {i + 1}"
        out.append(Series(label, _fill_q(q), status, ok, values,
                           style.PALETTE[i % len(style.PALETTE)],
                           _LINESTYLES[i % len(_LINESTYLES)], bool(np.isfinite(q).any())))
    return out


def scales(series: list) -> tuple[list, list, float]:
    """Which series are numerically zero, which go to the zoom panel, and the largest peak.

    Returns
    -------
    zero : list of bool
    small : list of bool
        Non-zero series whose peak is below ``SMALL_RATIO`` times the largest
        (only when some other series is large).
    largest : float
        Largest peak over all series (0.0 when none has a solved step).
    """
    peaks = [p[0] if p is not None else None for p in (s.peak() for s in series)]
    largest = max((p for p in peaks if p is not None), default=0.0)
    tol = max(ZERO_ABS, ZERO_REL * largest)
    zero = [p is not None and p <= tol for p in peaks]
    small = [p is not None and not z and p < SMALL_RATIO * largest
             for p, z in zip(peaks, zero)]
    return zero, small, largest


def cyclic(q: np.ndarray, driver_kind: str) -> bool:
    """Whether the driver sweeps a whole number of turns (the last step closes the cycle)."""
    if driver_kind != "R" or len(q) < 3:
        return False
    span = abs(float(q[-1] - q[0]))
    step = span / (len(q) - 1)
    turns = round(span / (2 * math.pi))
    return turns >= 1 and abs(span - 2 * math.pi * turns) <= 1.5 * step


def x_axis(q: np.ndarray, driver_kind: str, known: bool = True
            ) -> tuple[np.ndarray, str, str, str]:
    """``(x, axis label, unit, symbol)`` of the driver coordinate (the step when not ``known``)."""
    if not known:
        return q, "step (no driver value known)", "", "step"
    if driver_kind == "R":
        return np.degrees(q), "driver angle θ (deg)", "deg", "θ"
    return q, "driver displacement s (m)", "m", "s"


def at_text(s: Series, k: int, driver_kind: str) -> str:
    """Where step ``k`` is, as the legend says it (``θ = 90°``, ``s = 0.1 m``, ``step = 3``)."""
    x, _, unit, sym = x_axis(s.q[k:k + 1], driver_kind, s.q_known)
    return f"{sym} = {style.fmt_number(float(x[0]))}{'°' if unit == 'deg' else ' ' + unit}".rstrip()


def skipped_text(series: list) -> str:
    """The figure's note on skipped steps ("" when every step is ok)."""
    if not any(s.n_bad for s in series):
        return ""
    counts = {(s.n_bad, s.n) for s in series}
    if len(counts) == 1:
        bad, n = counts.pop()
        who = "in every series" if len(series) > 1 else ""
        return f"{bad} of {n} steps skipped {who} (status not ok): gaps in the curves".replace(
            "  ", " ")
    parts = ", ".join(f"{s.label} {s.n_bad} of {s.n}" for s in series if s.n_bad)
    return f"steps skipped (status not ok), gaps in the curves: {parts}"


def gap_note(s: Series) -> str:
    """The legend's note on a series' skipped steps ("" when none)."""
    return f"; {s.n_bad} of {s.n} steps skipped (gaps)" if s.n_bad else ""


def zoom_factor(series: list, small: list, largest: float) -> float:
    """How much the zoom panel magnifies: the largest peak over the largest small one."""
    top = max(s.peak()[0] for s, m in zip(series, small) if m)
    return largest / top


def finish(fig, head: str, lines: list) -> None:
    """The figure's title: ``head``, then the non-empty ``lines``."""
    lines = [line for line in lines if line]
    fig.suptitle("\n".join([head] + lines), fontsize=11)


def readable_ticks(ax, axis: str) -> None:
    """Few ticks, and a ×10ⁿ offset instead of long labels for very small or large values."""
    from matplotlib.ticker import MaxNLocator

    nice = [1, 2, 2.5, 5, 10]
    if axis in ("x", "both"):
        ax.xaxis.set_major_locator(MaxNLocator(7, steps=nice))
    if axis in ("y", "both"):
        ax.yaxis.set_major_locator(MaxNLocator(8, steps=nice))
    ax.ticklabel_format(axis=axis, style="sci", scilimits=(-3, 4), useMathText=True)
