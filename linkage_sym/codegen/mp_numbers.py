"""The mpmath number type of the evaluator's mpmath backend (``--precision``).

What :class:`~linkage_sym.codegen.precision.PreciseMechanism` computes with: the digits
asked for (:func:`parse_precision`), scene numbers and parameter recipes in mpmath
(:class:`MpNumbers`), each step's exact driver value from the scene's numbers
(:func:`driver_step_mp`), a load's factor over the cycle (:func:`factor_mp`), real roots
only (:func:`real_sqrt`, :class:`NotReal`), and the rate matrix by its entries solved
block by block with mpmath LU (:class:`MpBlocks`).
"""

from __future__ import annotations

import math
from dataclasses import replace

import mpmath as mp
import numpy as np

from linkage_sym.numeric.forces.loads import load_factor
from linkage_sym.structure.recipes import Numbers

__all__ = ["DOUBLE", "MAX_DIGITS", "MIN_DIGITS", "MpBlocks", "MpNumbers", "MpOps", "NotReal",
           "driver_numbers", "driver_step_mp", "factor_mp", "mp_namespace", "parse_precision",
           "real", "real_sqrt"]

DOUBLE = "double"
MIN_DIGITS, MAX_DIGITS = 10, 1000


def parse_precision(value) -> int | None:
    """``None`` for float64 (``"double"`` or ``None``), else the number of digits.

    Raises ``ValueError`` naming the option for anything else.
    """
    if value is None or (isinstance(value, str) and value.strip().lower() == DOUBLE):
        return None
    if isinstance(value, bool):
        raise ValueError(f"precision: expected 'double' or a number of digits, got {value!r}")
    try:
        digits = int(str(value).strip()) if not isinstance(value, int) else value
    except ValueError:
        raise ValueError(
            f"precision: expected 'double' or a number of digits, got {value!r}") from None
    if not MIN_DIGITS <= digits <= MAX_DIGITS:
        raise ValueError(
            f"precision: {digits} digits is outside {MIN_DIGITS}..{MAX_DIGITS} "
            "('double' is float64's 16)")
    return digits


# ------------------------------------------------------------------ parameters in mpmath


def mpf_of(v):
    return mp.mpf(float(v))


class MpNumbers(Numbers):
    """mpmath numbers for the parameters' recipes
    (:mod:`linkage_sym.structure.recipes`): a scene number is the ``mpf`` of its binary64
    value (exact), the functions mpmath's at the working precision (``mp.dps``)."""

    number = staticmethod(mpf_of)
    atan2 = staticmethod(mp.atan2)
    hypot = staticmethod(mp.hypot)
    cos = staticmethod(mp.cos)
    sin = staticmethod(mp.sin)


def factor_mp(load, x, x_float: float | None = None):
    """A load's factor at the driver value ``x`` (mpf), as
    :func:`linkage_sym.numeric.forces.loads.load_factor` defines it, in mpmath.

    ``x_float`` is the step's float64 driver value (``x`` rounded unless given): whether
    the step lies in the table and in the ``active`` range is decided on it, as the
    float64 run decides it (a step at an end of the range, in the scene's degrees, is at
    the end in both: the range's radians are rounded, the step's exact value is not); the
    table is interpolated at ``x`` (continuous, so a step an ulp beyond a table's end
    extrapolates by an ulp).
    """
    if x_float is None:
        x_float = float(x)
    f = mp.mpf(1)
    period = None if load.period is None else mp.mpf(float(load.period))
    if load.table is not None:
        tq = [mp.mpf(float(v)) for v in load.table.q]
        ts = [mp.mpf(float(v)) for v in load.table.scale]
        if period is not None:  # periodic: the table's first point again a period on
            x = tq[0] + mp.fmod(mp.fmod(x - tq[0], period) + period, period)
            tq, ts = tq + [tq[0] + period], ts + [ts[0]]
        elif not load.table.q[0] <= x_float <= load.table.q[-1]:
            raise ValueError(f"load on {load.link}: driver {load.driver} at {x_float:g} is "
                             "outside its table, where the factor is not defined")
        k = max([0] + [i for i in range(len(tq) - 1) if tq[i] <= x]) if x < tq[-1] else len(tq) - 2
        f = ts[k] + (ts[k + 1] - ts[k]) * (x - tq[k]) / (tq[k + 1] - tq[k])
    if load.active is not None:
        span = replace(load, table=None)  # the factor of the range alone: 1 inside, 0 outside
        if not load_factor(span, {load.driver: np.array([x_float])})[0] > 0:
            f = mp.mpf(0)
    return f


# ------------------------------------------------------------------ driver values in mpmath


def driver_numbers(driver):
    """``(start, stop, degrees)``: the scene's numbers of a driver's sweep, and whether they
    are degrees (an ``R`` driver read from a scene, whose radians are their rounding)."""
    if (driver.kind == "R" and driver.start_deg is not None and driver.stop_deg is not None
            and math.radians(driver.start_deg) == driver.start
            and math.radians(driver.stop_deg) == driver.stop):
        return driver.start_deg, driver.stop_deg, True
    return driver.start, driver.stop, False


def driver_step_mp(driver, i: int):
    """Step ``i`` of a driver's sweep in mpmath, at the working precision (``mp.dps``).

    ``start + i (stop - start) / (steps - 1)`` from the scene's numbers, each taken as the
    binary64 number it is: for an ``R`` driver read from a scene its ``start_deg`` and
    ``stop_deg``, converted to radians with ``mpmath.pi`` (the float64 sweep's radians
    are their rounding: 180 degrees is ``float(pi)`` there, 1.2e-16 short of pi); else
    ``start`` and ``stop`` (radians or metres) themselves.

    Examples
    --------
    >>> import mpmath as mp
    >>> from linkage_sym.model import Driver
    >>> d = Driver("A", "R", math.radians(90.0), math.radians(180.0), 3, 1.0, toward="B",
    ...            start_deg=90.0, stop_deg=180.0)
    >>> with mp.workdps(30):
    ...     print(driver_step_mp(d, 2) - mp.pi, mp.nstr(mp.mpf(d.stop) - mp.pi, 5))
    0.0 -1.2246e-16
    """
    start, stop, degrees = driver_numbers(driver)
    a, b = mp.mpf(start), mp.mpf(stop)
    n = driver.steps
    v = a if n == 1 else (a * (n - 1 - i) + b * i) / (n - 1)
    return v * mp.pi / 180 if degrees else v


# ------------------------------------------------------------------ the generated functions


def mp_namespace() -> dict:
    ns: dict = {}
    exec("from mpmath import *", ns)  # the names SymPy's mpmath printer uses
    ns["sqrt"] = real_sqrt  # a closed form's root: real, or no position at this precision
    return ns


class NotReal(Exception):
    """A closed form with no real value at this precision (a tangency missed by rounding)."""


def real(v):
    """``v`` as an ``mpf``; :class:`NotReal` for a complex value."""
    if isinstance(v, mp.mpc):
        if v.imag != 0:
            raise NotReal
        v = v.real
    return mp.mpf(v)


def real_sqrt(x):
    """``mpmath.sqrt`` of a real argument; a negative one (a tangency the float64 run took,
    missed at this precision) raises :class:`NotReal` instead of giving a complex root
    that the closed form's ``atan2`` cannot take."""
    x = real(x)
    if x < 0:
        raise NotReal
    return mp.sqrt(x)


class MpBlocks:
    """``A`` of the rate problems at one step in mpmath, kept as its non-zero entries
    ``{(i, j): mpf}``: solved group block by group block (mpmath LU), and the blocks'
    Hadamard ratios (the float64 runtime's indicator,
    :meth:`~linkage_sym.codegen.blocks.BlockSystem.ratios`, here at this precision)."""

    def __init__(self, entries: dict, blocks, m: int):
        self.entries, self.blocks, self.m = entries, blocks, m

    def _block(self, r0, c0, n):
        M = mp.matrix(n, n)
        for i in range(n):
            for j in range(n):
                M[i, j] = self.entries.get((r0 + i, c0 + j), 0)
        return M

    def ratios(self) -> list:
        """Each group block's Hadamard ratio: ``|det|`` over the product of its row norms,
        or of its column norms, whichever is larger (``None`` for a 1x1 block)."""
        out = []
        for r0, _, c0, c1 in self.blocks:
            n = c1 - c0
            if n < 2:
                out.append(None)
                continue
            M = self._block(r0, c0, n)
            rows = mp.fprod(mp.norm(M[i, :]) for i in range(n))
            cols = mp.fprod(mp.norm(M[:, j]) for j in range(n))
            big = max(rows, cols)
            out.append(abs(mp.det(M)) / big if big else mp.mpf(0))
        return out

    def solve(self, rhs) -> list:
        """``x`` (list of ``m`` mpf) of ``A x = rhs``, from the first group's block on;
        ``ZeroDivisionError`` where a block is exactly singular."""
        A, x = self.entries, [mp.mpf(0)] * self.m
        for r0, r1, c0, c1 in self.blocks:
            b = [rhs[i] - mp.fsum(A[i, j] * x[j] for j in range(c0) if (i, j) in A)
                 for i in range(r0, r1)]
            sol = mp.lu_solve(self._block(r0, c0, c1 - c0), mp.matrix(b))
            for j in range(c1 - c0):
                x[c0 + j] = sol[j]
        return x


class MpOps:
    """The arithmetic of the joints' friction solve (:mod:`linkage_sym.codegen.friction`) in
    mpmath: one step, its numbers ``mpf`` and its masks booleans; Newton carried to the
    working precision (a step below ``10^(2 - digits)`` of the frictions' size)."""

    nan = mp.nan
    sqrt, sign, finite = staticmethod(mp.sqrt), staticmethod(mp.sign), staticmethod(mp.isfinite)
    abs = staticmethod(abs)

    def __init__(self, digits: int):
        self.tol = mp.mpf(10) ** (2 - digits)

    @staticmethod
    def where(mask, a, b):
        return a if mask else b

    @staticmethod
    def and_(a, b) -> bool:
        return bool(a) and bool(b)

    @staticmethod
    def or_(a, b) -> bool:
        return bool(a) or bool(b)

    @staticmethod
    def not_(a) -> bool:
        return not a

    @staticmethod
    def const(value, like):
        return value

    @staticmethod
    def any(mask) -> bool:
        return bool(mask)

    @staticmethod
    def maximum(values):
        return max(values)

    @staticmethod
    def ratio(a, b):
        """``a / b`` where ``b > 0``, else 0."""
        return a / b if b > 0 else mp.mpf(0)

    @staticmethod
    def step(J, g, live):
        """``(det J > 0, -J^-1 g)`` (the step 0 where not ``live`` or not positive)."""
        M = mp.matrix(J)
        good = bool(mp.det(M) > 0)
        if not (good and live):
            return good, [mp.mpf(0)] * len(g)
        d = mp.lu_solve(M, mp.matrix(g))
        return good, [-d[i] for i in range(len(g))]

    @staticmethod
    def null_joints(J, locked) -> dict:
        """``{0: indices of the frictions in the singular direction of J}`` where locked."""
        if not locked:
            return {}
        v = np.abs(np.linalg.svd(np.array([[float(x) for x in row] for row in J]))[2][-1])
        return {0: [k for k, x in enumerate(v) if x >= 0.1 * v.max()]}
