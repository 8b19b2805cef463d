"""What the builders and the syntheses share: the error, the design record, checks, geometry.

NumPy only (and the standard library); never SymPy (import contract in
``pyproject.toml``).

Conventions of every scene written here (the builders'): the crank's ground
pivot ``A`` at the origin, the frame along ``+x`` (the rocker's pivot ``D`` at
``(d, 0)``; a slider's line parallel to ``x``), links named ``crank``,
``coupler``, ``rocker`` or ``slider``, one driver on ``A`` over a full turn
from the assembly angle, and ``"outputs": ["kinematics"]`` (add masses, loads
and outputs to the written file for forces).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from linkage_sym.errors import finite_number

PI = math.pi

TANGENCY = 1e-9
"""Smallest sine of the transmission angle (or its analogue) accepted in an
assembly configuration: below it the configuration is a dead-centre position
whose assembly mode the solver cannot tell (the plan would refuse it)."""


class SynthesisError(ValueError):
    """A request that no linkage meets, or that is malformed.

    ``field`` names the offending parameter as the API spells it (``"K"``,
    ``"swing_deg"``, ``"positions[1]"``); the command line prints it as its
    option (``--K``, ``--swing-deg``).  ``reason`` says why.

    Examples
    --------
    >>> err = SynthesisError("K", "must be > 1, got 0.5")
    >>> print(err)
    K: must be > 1, got 0.5
    >>> err.field, err.reason
    ('K', 'must be > 1, got 0.5')
    """

    def __init__(self, field_name: str, reason: str):
        self.field = field_name
        self.reason = reason
        super().__init__(f"{field_name}: {reason}")


@dataclass(frozen=True)
class Design:
    """A linkage built from dimensions or synthesized from a requirement.

    Attributes
    ----------
    kind : str
        ``"fourbar"``, ``"slider-crank"`` or ``"guide-bar"``.
    scene : dict
        The scene, in the JSON layout of the scene format (``json.dumps`` it
        to write it; ``linkage_sym.load_scene`` reads it).
    lengths : dict of str to float
        The dimensions (m): ``crank``, ``coupler``, ``rocker``, ``ground`` for
        a four-bar; ``crank``, ``coupler``, ``offset`` for a slider-crank;
        ``crank``, ``ground`` for a guide-bar.
    notes : tuple of str
        What the user must know: choices made on their behalf, a crank that
        cannot turn fully.
    K, theta : float or None
        Stroke-time ratio and extreme-position angle (rad) of a synthesis by
        ``K``; also set for builds whose crank turns fully and whose output
        has extreme positions.
    gamma_min : float or None
        Minimum transmission angle (rad, 0..pi/2) over a full turn of the
        crank (or between the positions of a synthesis by positions).
    gamma_min_where : str or None
        Where it occurs, in words.
    extra : dict
        Further results of a synthesis (the stroke, the swing, the positions'
        crank angles ...), by name.
    """

    kind: str
    scene: dict
    lengths: dict
    notes: tuple = ()
    K: float | None = None
    theta: float | None = None
    gamma_min: float | None = None
    gamma_min_where: str | None = None
    extra: dict = field(default_factory=dict)


# ------------------------------------------------------------------ checks of the request


def number(name: str, value) -> float:
    """``value`` as a finite float, or :class:`SynthesisError` naming ``name``.

    Examples
    --------
    >>> number("rocker", "0.5")
    0.5
    >>> number("rocker", float("nan"))
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: rocker: a finite number is expected, got nan
    """
    return finite_number(name, value, SynthesisError)


def positive(name: str, value) -> float:
    """``value`` as a finite float > 0, or :class:`SynthesisError` naming ``name``.

    Examples
    --------
    >>> positive("crank", 2)
    2.0
    >>> positive("crank", 0)
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: crank: a length > 0 is expected, got 0
    """
    x = number(name, value)
    if not x > 0:
        raise SynthesisError(name, f"a length > 0 is expected, got {value!r}")
    return x


def sweep_options(steps, speed) -> tuple[int, float]:
    """The driver's ``steps`` (an integer >= 2) and ``speed`` (finite), checked."""
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 2:
        raise SynthesisError("steps", f"an integer >= 2 is expected, got {steps!r}")
    return int(steps), number("speed", speed)


def scene_name(name) -> str:
    """A non-empty scene name, checked."""
    if not isinstance(name, str) or not name.strip():
        raise SynthesisError("name", f"a non-empty name is expected, got {name!r}")
    return name


# ------------------------------------------------------------------ geometry


def cross(u, v) -> float:
    """z-component of the cross product of two plane vectors.

    Examples
    --------
    >>> cross((1.0, 0.0), (0.0, 2.0))
    2.0
    """
    return float(u[0] * v[1] - u[1] * v[0])


def acute(gamma: float) -> float:
    """The transmission angle's deviation measure ``min(gamma, pi - gamma)`` (0..pi/2).

    The angle between two links at their joint is 0..pi; as a transmission
    angle only its distance from the straight line counts.

    Examples
    --------
    >>> round(math.degrees(acute(math.radians(130))), 9)
    50.0
    """
    return min(gamma, PI - gamma)


def triangle_angle(p: float, q: float, r: float) -> float:
    """The angle (rad, 0..pi) of a triangle with sides ``p``, ``q`` between them and ``r`` opposite.

    The law of cosines, with the argument of ``arccos`` clipped to [-1, 1]
    (a degenerate triangle gives 0 or pi).

    Examples
    --------
    >>> round(math.degrees(triangle_angle(3.0, 4.0, 5.0)), 12)
    90.0
    """
    cos = (p * p + q * q - r * r) / (2.0 * p * q)
    return math.acos(min(1.0, max(-1.0, cos)))


def half_chord(r: float, p: float, q: float) -> float:
    """Height over the base ``r`` of the triangle with sides ``r``, ``p``, ``q`` (Heron's form).

    0 when the triangle is flat; ``nan`` when the sides do not close (the
    product under the root is negative).  Accurate near flatness, where the
    form ``sqrt(p**2 - x**2)`` loses digits.

    Examples
    --------
    >>> half_chord(5.0, 3.0, 4.0)
    2.4
    """
    prod = (p + q + r) * (p + q - r) * (p - q + r) * (-p + q + r)
    if prod < 0:
        return float("nan")
    return math.sqrt(prod) / (2.0 * r)


def fmt_len(x: float) -> str:
    """A length for messages: 6 significant digits and its unit.

    Examples
    --------
    >>> fmt_len(0.0123456789)
    '0.0123457 m'
    """
    return f"{x:.6g} m"


def fmt_deg(x: float) -> str:
    """An angle (rad) for messages, in degrees with 6 significant digits.

    Examples
    --------
    >>> fmt_deg(math.pi / 6)
    '30°'
    """
    return f"{math.degrees(x):.6g}°"
