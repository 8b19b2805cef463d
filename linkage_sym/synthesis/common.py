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

# The scene format's limits (linkage_sym.scene.fields and linkage_sym.scene.validate), which
# every written scene must meet.  Repeated here, not imported: importing linkage_sym.scene loads
# SciPy, and the synthesis is NumPy only; tests/synthesis/test_synthesis_cli.py checks they are equal.

MAX_LENGTH = 1e30
"""Largest length or coordinate (m) of a request or a design: the scene format's
largest magnitude of a number (``linkage_sym.scene.fields.MAX_MAGNITUDE``).  The
synthesis squares lengths and divides them by sines; with every length within
1e30 no product leaves the float64 range (1.8e308), and the written scene's
coordinates are checked against the same limit."""

MIN_LENGTH = 1e-30
"""Smallest length (m) of a request or a design: the scene format's smallest
mechanism (``linkage_sym.scene.validate.MIN_SIZE``); products of up to ten such
lengths stay above float64's smallest normal number (2.2e-308)."""

MAX_ANGLE_DEG = 1e6
"""Largest magnitude of an angle in degrees (``linkage_sym.scene.fields.MAX_ANGLE_DEG``)."""

COINCIDENCE = 1e-9
"""Two joints closer than this fraction of the mechanism's size are one point to
the scene format (``linkage_sym.scene.validate.COINCIDENCE_TOLERANCE``): the
crank pin ``B`` must be farther from the crank's pivot ``A``."""

MAX_SPREAD = 1e9
"""Farthest a joint may lie from the origin, in sizes of the mechanism
(``linkage_sym.scene.validate.MAX_SPREAD``)."""

LENGTH_WHY = (f"a length must lie within {MIN_LENGTH:.0e} m to {MAX_LENGTH:.0e} m (the scene "
              f"format's limits: coordinates within +-{MAX_LENGTH:.0e} m, a mechanism no smaller "
              f"than {MIN_LENGTH:.0e} m): the solver multiplies up to ten lengths, and every product "
              "must stay within the float64 range 2.2e-308 to 1.8e308")
"""Why a length outside ``[MIN_LENGTH, MAX_LENGTH]`` is refused."""

MAGNITUDE_WHY = (f"must be within +-{MAX_LENGTH:.0e} (SI units): the solver multiplies up to ten "
                 "such quantities (e.g. a coordinate x a speed^2 x a length) and every product "
                 "must stay within the float64 range 1.8e308")
"""Why a coordinate, an offset or a speed beyond ``MAX_LENGTH`` is refused (the scene format's words)."""


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
    >>> positive("stroke", 1e308)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: stroke: a length must lie within 1e-30 m to 1e+30 m (the scene format's limits: ..., got 1e+308
    """
    x = number(name, value)
    if not x > 0:
        raise SynthesisError(name, f"a length > 0 is expected, got {value!r}")
    if not MIN_LENGTH <= x <= MAX_LENGTH:
        raise SynthesisError(name, f"{LENGTH_WHY}, got {x:g}")
    return x


def coordinate(name: str, value) -> float:
    """``value`` as a finite float within ``+-MAX_LENGTH``, or :class:`SynthesisError`.

    For a coordinate or an offset (m), of either sign and possibly 0.

    Examples
    --------
    >>> coordinate("offset", -0.02)
    -0.02
    >>> coordinate("offset", -1e31)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: offset: must be within +-1e+30 (SI units): ..., got -1e+31
    """
    x = number(name, value)
    if not abs(x) <= MAX_LENGTH:
        raise SynthesisError(name, f"{MAGNITUDE_WHY}, got {x:g}")
    return x


def sweep_options(steps, speed) -> tuple[int, float]:
    """The driver's ``steps`` (an integer >= 2) and ``speed`` (finite, within ``+-MAX_LENGTH``), checked."""
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 2:
        raise SynthesisError("steps", f"an integer >= 2 is expected, got {steps!r}")
    return int(steps), coordinate("speed", speed)


def crank_apart(name: str, crank: float, size: float, why: str, hint: str = "") -> None:
    """Refuse a crank within :data:`COINCIDENCE` of the mechanism's ``size``, naming ``name``.

    ``size`` is the largest distance between two joints (or a bound above it);
    ``why`` says what made the crank so short, ``hint`` what to change.

    Examples
    --------
    >>> crank_apart("crank", 1e-12, 1.0, "the crank")
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: crank: the crank is 1e-12 m, within 1e-09 of the linkage's size (1 m), where the scene format takes the crank pin B and its pivot A for one point (the driver would have no direction)
    """
    if not crank > COINCIDENCE * size:
        raise SynthesisError(name, f"{why} is {fmt_len(crank)}, within {COINCIDENCE:.0e} of the "
                                   f"linkage's size ({fmt_len(size)}), where the scene format takes "
                                   "the crank pin B and its pivot A for one point (the driver would "
                                   f"have no direction){hint}")


def within_reach(name: str, reach: float, what: str) -> None:
    """Refuse a linkage whose joints come more than :data:`MAX_LENGTH` from the origin.

    ``reach`` is the largest distance from the origin a joint reaches as the
    crank turns (or a bound above it); ``what`` names that distance.

    Examples
    --------
    >>> within_reach("rocker", 2e30, "ground + rocker")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: rocker: the joints come up to ground + rocker = 2e+30 m from the crank pivot A as the crank turns, beyond the scene format's +-1e+30 m on coordinates ...
    """
    if not reach <= MAX_LENGTH:
        raise SynthesisError(name, f"the joints come up to {what} = {fmt_len(reach)} from the crank "
                                   f"pivot A as the crank turns, beyond the scene format's "
                                   f"+-{MAX_LENGTH:.0e} m on coordinates (the solver multiplies up "
                                   "to ten such lengths, and every product must stay within the "
                                   "float64 range 1.8e308)")


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
