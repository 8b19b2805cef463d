"""Synthesis by two or three given positions of the coupler.

The textbook section *Design of four-bar mechanisms* (Sources [2] of the
README; "design by given coupler positions", Fig. 2-66): the moving pivots
``B`` and ``C`` of the coupler travel on circles about the fixed pivots, so
``A`` lies on the perpendicular bisector ``b12`` of ``B1 B2`` and ``D`` on
``c12`` of ``C1 C2``.  Three positions give each fixed pivot as a
circumcentre (``B1 B2 B3``, ``C1 C2 C3``): the design is unique.  Two leave
each pivot anywhere on its bisector: the pivots are given (``pivots``), or
chosen here -- on a grid of :data:`SEARCH_POINTS` x :data:`SEARCH_POINTS`
points of the two bisectors within :data:`SEARCH_SPAN` coupler lengths of the
chords' midpoints, the pair without a branch or order defect with the
largest minimum transmission angle between the positions.

**Branch and order defects.**  The crank ``AB`` drives.  The positions must
be reached in one assembly mode (the sign of ``(D - B) x (C - B)`` equal at
every position: a *branch defect* otherwise), in the given order as the
crank turns one way, and with no dead centre (coupler and rocker in line,
``|BD| = |b +- c|``) between them, where the crank-driven linkage would stop
(an *order defect* for three positions when the crank meets them out of
order, and a dead centre either way for two).  For two positions the crank
may turn either way: the sense without a dead centre is taken (the shorter
turn if both are free).  A design with a defect is refused, the defect
named.

NumPy only (import contract in ``pyproject.toml``).
"""

from __future__ import annotations

import math

import numpy as np

from linkage_sym.synthesis.common import (
    MAX_LENGTH,
    MAX_SPREAD,
    MIN_LENGTH,
    PI,
    TANGENCY,
    Design,
    SynthesisError,
    acute,
    coordinate,
    crank_apart,
    cross,
    fmt_deg,
    fmt_len,
    scene_name,
    sweep_options,
    triangle_angle,
)

RIGID_TOL = 1e-9
"""The coupler length may differ between positions by this fraction of it (the
positions' coordinates rarely carry more digits); more is refused."""

PIVOT_TOL = 1e-9
"""Given pivots must be equidistant from their two positions to this fraction of
the coupler length (they must lie on the perpendicular bisectors)."""

SEARCH_SPAN = 4.0
"""Two positions without ``pivots``: each pivot is searched within this many
coupler lengths of its chord's midpoint along its bisector."""

SEARCH_POINTS = 161
"""Grid points per bisector in that search."""


def read_positions(positions) -> list[np.ndarray]:
    """The positions ``[[Bx, By, Cx, Cy], ...]`` as arrays, checked.

    Raises
    ------
    SynthesisError
        Not 2 or 3 rows of 4 finite numbers within +-1e30 (m); a coupler
        shorter than 1e-30 m (the scene format's smallest mechanism); a coupler whose
        length changes between positions by more than :data:`RIGID_TOL`; a
        moving pivot that does not move.

    Examples
    --------
    >>> read_positions([[0, 0, 1, 0], [0, 1, 1, 1.5]])
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: positions[1]: the coupler BC is 1.11803 m long here but 1 m in positions[0]: a rigid coupler keeps its length
    """
    if not isinstance(positions, (list, tuple)) or len(positions) not in (2, 3):
        n = len(positions) if isinstance(positions, (list, tuple)) else type(positions).__name__
        raise SynthesisError("positions", f"2 or 3 positions [Bx, By, Cx, Cy] are expected, got {n}")
    rows = []
    for i, row in enumerate(positions):
        if not isinstance(row, (list, tuple)) or len(row) != 4:
            raise SynthesisError(f"positions[{i}]", f"four numbers [Bx, By, Cx, Cy] are expected, "
                                                    f"got {row!r}")
        rows.append(np.array([coordinate(f"positions[{i}][{k}]", v) for k, v in enumerate(row)]))
    L = math.hypot(rows[0][2] - rows[0][0], rows[0][3] - rows[0][1])
    if L == 0:
        raise SynthesisError("positions[0]", "B and C coincide: the coupler has no length")
    if L < MIN_LENGTH:
        raise SynthesisError("positions[0]", f"the coupler BC is {fmt_len(L)} long, below the scene "
                             f"format's smallest length {MIN_LENGTH:.0e} m (products of up to ten "
                             "lengths must stay above float64's smallest normal number 2.2e-308)")
    for i, r in enumerate(rows[1:], 1):
        Li = math.hypot(r[2] - r[0], r[3] - r[1])
        if abs(Li - L) > RIGID_TOL * L:
            raise SynthesisError(f"positions[{i}]", f"the coupler BC is {fmt_len(Li)} long here but "
                                 f"{fmt_len(L)} in positions[0]: a rigid coupler keeps its length")
    for k, p in ((0, "B"), (2, "C")):
        for i in range(len(rows)):
            for j in range(i):
                if math.dist(rows[i][k:k + 2], rows[j][k:k + 2]) <= RIGID_TOL * L:
                    raise SynthesisError(f"positions[{i}]", f"{p} is where it is in positions[{j}]: "
                                         f"a moving pivot {p} that does not move fixes no circle")
    return rows


def circumcentre(P1, P2, P3, what: str) -> np.ndarray:
    """Centre of the circle through three points; refused when they are in line.

    Examples
    --------
    >>> circumcentre(np.array([1.0, 0.0]), np.array([0.0, 1.0]), np.array([-1.0, 0.0]), "A")
    array([0., 0.])
    """
    b, c = P2 - P1, P3 - P1
    den = 2.0 * cross(b, c)
    if abs(den) <= 1e-12 * (b @ b + c @ c):
        raise SynthesisError("positions", f"the three positions of the pivot {what}'s moving point "
                             "are in line: no circle passes through them (the fixed pivot would be "
                             "at infinity: a slider)")
    bb, cc = b @ b, c @ c
    return P1 + np.array([c[1] * bb - b[1] * cc, b[0] * cc - c[0] * bb]) / den


def _bd_range(A, D, a, phi_from, phi_to):
    """Extremes of ``|B D|`` as the crank turns from ``phi_from`` to ``phi_to`` (signed sweep).

    ``|BD|^2 = a^2 + |AD|^2 - 2 a |AD| cos(phi - phi_D)`` is extreme at the
    ends or where ``B`` is on the line ``AD`` (``phi = phi_D``, ``phi_D + pi``).
    Returns ``(r_min, phi_at_min, r_max, phi_at_max)``.
    """
    AD = D - A
    dist = math.hypot(*AD)
    phi_d = math.atan2(AD[1], AD[0])
    lo, hi = sorted((phi_from, phi_to))
    cands = [phi_from, phi_to]
    for base in (phi_d, phi_d + PI):
        k = math.ceil((lo - base) / (2 * PI))
        x = base + 2 * PI * k
        while x <= hi:
            cands.append(x)
            x += 2 * PI
    r = [math.sqrt(max(a * a + dist * dist - 2 * a * dist * math.cos(p - phi_d), 0.0)) for p in cands]
    i, j = int(np.argmin(r)), int(np.argmax(r))
    return r[i], cands[i], r[j], cands[j]


def _check_motion(A, D, a, b, c, phi_from, phi_to):
    """``None`` if the crank turns from ``phi_from`` to ``phi_to`` without a dead centre, else
    ``(crank angle, what)`` of the first trouble found; the minimum transmission angle and the
    crank angle where it occurs."""
    rmin, pmin, rmax, pmax = _bd_range(A, D, a, phi_from, phi_to)
    if rmax >= b + c:
        return (pmax, "coupler and rocker extended in line"), 0.0, pmax
    if rmin <= abs(b - c):
        return (pmin, "coupler and rocker folded in line"), 0.0, pmin
    g1, g2 = acute(triangle_angle(b, c, rmin)), acute(triangle_angle(b, c, rmax))
    return None, min(g1, g2), (pmin if g1 <= g2 else pmax)


def _evaluate(rows, A, D):
    """Assess the four-bar ``A B C D`` through the positions.

    Returns ``(problem, gamma_min, phis, where)``: ``problem`` a message or
    None; ``phis`` the crank angles at the positions, unwrapped along the
    chosen sense of turning; ``where`` the crank angle (rad, on the same
    unwrapped scale) of the minimum transmission angle.
    """
    B = [r[:2] for r in rows]
    C = [r[2:] for r in rows]
    a = math.dist(A, B[0])
    c = math.dist(D, C[0])
    b = math.dist(B[0], C[0])
    if a <= RIGID_TOL * b:
        return "the crank pivot A falls on the moving pivot B", 0.0, None, None
    if c <= RIGID_TOL * b:
        return "the rocker pivot D falls on the moving pivot C", 0.0, None, None
    if math.dist(A, D) <= RIGID_TOL * b:
        return "the fixed pivots A and D coincide", 0.0, None, None
    modes = [cross(D - Bi, Ci - Bi) for Bi, Ci in zip(B, C)]
    for i, m in enumerate(modes):
        if abs(m) <= TANGENCY * b * math.dist(D, B[i]):
            return (f"branch defect: in position {i + 1} the coupler and rocker are in line (a dead "
                    "centre)"), 0.0, None, None
    for i, m in enumerate(modes[1:], 2):
        if (m > 0) != (modes[0] > 0):
            return (f"branch defect: position {i} is in the other assembly mode than position 1 "
                    "(C on the other side of the line BD): the linkage cannot move from one to the "
                    "other without being taken apart"), 0.0, None, None
    ang = [math.atan2(Bi[1] - A[1], Bi[0] - A[0]) for Bi in B]
    if len(rows) == 3:
        ccw = [(x - ang[0]) % (2 * PI) for x in ang]
        sense = 1.0 if ccw[1] < ccw[2] else -1.0
        phis = [ang[0] + sense * ((x - ang[0]) * sense % (2 * PI)) for x in ang]
        trouble, g, where = _check_motion(A, D, a, b, c, phis[0], phis[2])
        if trouble is not None:
            k = 1 if (trouble[0] - phis[1]) * sense < 0 else 2
            return (f"order defect: turning from position 1 through 2 to 3 the crank meets a dead "
                    f"centre ({trouble[1]}) between positions {k} and {k + 1}, at crank angle "
                    f"{fmt_deg(trouble[0] % (2 * PI))}"), 0.0, None, None
        return None, g, phis, where
    options = []
    for sense in (1.0, -1.0):
        phis = [ang[0], ang[0] + sense * ((ang[1] - ang[0]) * sense % (2 * PI))]
        trouble, g, where = _check_motion(A, D, a, b, c, *phis)
        options.append((trouble, abs(phis[1] - phis[0]), g, phis, where))
    free = [o for o in options if o[0] is None]
    if not free:
        t = options[0][0]
        return (f"dead centre: the crank meets one ({t[1]}) turning either way between the positions "
                f"(at crank angle {fmt_deg(t[0] % (2 * PI))} turning counter-clockwise)"), \
            0.0, None, None
    best = min(free, key=lambda o: o[1])
    return None, best[2], best[3], best[4]


def coupler_positions(positions, *, pivots=None, name="coupler-positions", steps=361,
                      speed=1.0) -> Design:
    """A four-bar whose coupler ``BC`` passes through 2 or 3 given positions.

    Parameters
    ----------
    positions : sequence of 2 or 3 ``[Bx, By, Cx, Cy]``
        The coupler's moving pivots in each position (m), in the order the
        linkage is to reach them.
    pivots : ``[Ax, Ay, Dx, Dy]``, optional
        The fixed pivots, for two positions only (each on its perpendicular
        bisector to :data:`PIVOT_TOL` of the coupler length).  Without them,
        two positions get the pivots of the search described in the module
        docstring.
    name, steps, speed
        The scene's name, the sweep's steps and the crank's speed (rad/s).

    Returns
    -------
    Design
        A four-bar scene in the positions' own coordinates (the pivots are
        not moved to the origin), assembled in position 1, the driver turning
        the crank from position 1 to the last through the others;
        ``extra["crank_angles"]`` the crank angles at the positions (rad,
        unwrapped along the sweep), ``extra["pivots"]`` ``[Ax, Ay, Dx, Dy]``;
        ``gamma_min`` the minimum transmission angle between the positions.

    Raises
    ------
    SynthesisError
        Malformed positions (see :func:`read_positions`); three positions
        of a moving pivot in line; ``pivots`` with three positions or off
        the bisectors; a branch or order defect or a dead centre between
        the positions (the message names it); no defect-free pair of pivots
        found by the search.

    Examples
    --------
    A four-bar's own coupler positions give back its pivots:

    >>> from linkage_sym.synthesis.builders import fourbar
    >>> joints = [fourbar(1.0, 3.0, 3.0, 3.5, crank_deg=phi).scene["joints"] for phi in (60, 100, 140)]
    >>> d = coupler_positions([[*j[1]["at"], *j[2]["at"]] for j in joints])
    >>> [round(v, 12) + 0.0 for v in d.extra["pivots"]]
    [0.0, 0.0, 3.5, 0.0]
    >>> round(math.degrees(d.gamma_min), 9), d.gamma_min_where
    (62.720387264, 'crank angle 60° (position 1)')

    Positions the crank cannot drive through are refused, the defect named:

    >>> coupler_positions([[0, 0, 5, 0], [-1, 1, 3, 4], [-3, 1, 0, 5]])
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: positions: branch defect: in position 1 the coupler and rocker are in line (a dead centre); three positions fix the pivots, so no four-bar driven by the crank AB meets them
    """
    rows = read_positions(positions)
    steps, speed = sweep_options(steps, speed)
    name = scene_name(name)
    L = math.hypot(rows[0][2] - rows[0][0], rows[0][3] - rows[0][1])
    notes = []
    if len(rows) == 3:
        A, D, g, phis, where = _three_positions(rows, pivots)
        field = "positions"
        notes.append("three positions: the fixed pivots are the circumcentres of B1 B2 B3 and "
                     "C1 C2 C3 (a unique design)")
    elif pivots is not None:
        A, D, g, phis, where = _two_positions_with_pivots(rows, pivots, L)
        field = "pivots"
    else:
        A, D, g, phis, where = _search(rows, L)
        field = "positions"
        notes.append(f"two positions and no pivots given: A and D chosen on the perpendicular "
                     f"bisectors of B1B2 and C1C2, within {SEARCH_SPAN:g} coupler lengths of the "
                     f"chords' midpoints ({SEARCH_POINTS} x {SEARCH_POINTS} grid), as the pair "
                     "without branch or order defect with the largest minimum transmission angle "
                     f"between the positions ({fmt_deg(g)}); give pivots to choose them")
    _check_limits(rows, A, D, field)
    return _scene(rows, A, D, g, phis, where, notes, name, steps, speed)


def _three_positions(rows, pivots) -> tuple:
    """``(A, D, g, phis, where)`` of three positions: the pivots are the circumcentres of
    ``B1 B2 B3`` and ``C1 C2 C3``, refused when pivots are given too or the design has a
    defect."""
    if pivots is not None:
        raise SynthesisError("pivots", "three positions fix the pivots (the circumcentres); "
                                       "pivots are given for two positions only")
    A = circumcentre(*(r[:2] for r in rows), "A")
    D = circumcentre(*(r[2:] for r in rows), "D")
    problem, g, phis, where = _evaluate(rows, A, D)
    if problem:
        raise SynthesisError("positions", f"{problem}; three positions fix the pivots, so no "
                                          "four-bar driven by the crank AB meets them")
    return A, D, g, phis, where


def _two_positions_with_pivots(rows, pivots, L) -> tuple:
    """``(A, D, g, phis, where)`` of two positions with the pivots given (checked against
    the bisectors), refused when the design has a defect."""
    A, D = _given_pivots(rows, pivots, L)
    problem, g, phis, where = _evaluate(rows, A, D)
    if problem:
        raise SynthesisError("pivots", f"{problem}; choose other pivots on the bisectors")
    return A, D, g, phis, where


def _check_limits(rows, A, D, field):
    """Refuse a four-bar the scene format cannot hold (its limits on coordinates, spread and crank)."""
    B, C = rows[0][:2], rows[0][2:]
    a, c = math.dist(A, B), math.dist(D, C)
    reach = max(math.hypot(*A) + a, math.hypot(*D) + c)  # B and C turn about A and D
    if not reach <= MAX_LENGTH:
        raise SynthesisError(field, f"the four-bar's joints come up to {fmt_len(reach)} from the "
                             f"origin as the crank turns, beyond the scene format's "
                             f"+-{MAX_LENGTH:.0e} m on coordinates (the solver multiplies up to ten "
                             "such lengths, and every product must stay within the float64 range "
                             "1.8e308)")
    points = (A, B, C, D)
    size = max(math.dist(p, q) for p in points for q in points)
    far = max(math.hypot(*p) for p in points)
    if far > MAX_SPREAD * size:
        raise SynthesisError(field, f"the four-bar's joints lie up to {fmt_len(far)} from the "
                             f"origin, more than {MAX_SPREAD:.0e} times its size ({fmt_len(size)}, "
                             "the largest distance between two joints): float64 keeps 16 digits of "
                             "a coordinate, so fewer than 7 of the geometry would be left; move the "
                             "origin nearer the positions")
    crank_apart(field, a, size, "the crank AB")


def _given_pivots(rows, pivots, L):
    if pivots is None or not isinstance(pivots, (list, tuple)) or len(pivots) != 4:
        raise SynthesisError("pivots", f"four numbers Ax, Ay, Dx, Dy are expected, got {pivots!r}")
    p = np.array([coordinate("pivots", v) for v in pivots])
    A, D = p[:2], p[2:]
    for P, k, name in ((A, 0, "A"), (D, 2, "D")):
        r1, r2 = math.dist(P, rows[0][k:k + 2]), math.dist(P, rows[1][k:k + 2])
        if abs(r1 - r2) > PIVOT_TOL * L:
            m = "B" if name == "A" else "C"
            raise SynthesisError("pivots", f"{name} = ({P[0]:.6g}, {P[1]:.6g}) is not on the "
                                 f"perpendicular bisector of {m}1{m}2: it is {fmt_len(r1)} from "
                                 f"{m}1 and {fmt_len(r2)} from {m}2")
    return A, D


def _search(rows, L):
    """The best defect-free pivots on the bisectors (see the module docstring)."""
    lines = []
    for k in (0, 2):
        P1, P2 = rows[0][k:k + 2], rows[1][k:k + 2]
        m = 0.5 * (P1 + P2)
        t = P2 - P1
        n = np.array([-t[1], t[0]]) / math.hypot(*t)
        lines.append((m, n))
    s = np.linspace(-SEARCH_SPAN * L, SEARCH_SPAN * L, SEARCH_POINTS)
    best = None
    for sa in s:
        A = lines[0][0] + sa * lines[0][1]
        for sd in s:
            D = lines[1][0] + sd * lines[1][1]
            problem, g, phis, where = _evaluate(rows, A, D)
            if problem is None and (best is None or g > best[2]):
                best = (A, D, g, phis, where)
    if best is None:
        raise SynthesisError("positions", "no pair of pivots on the perpendicular bisectors within "
                             f"{SEARCH_SPAN:g} coupler lengths of the chords' midpoints passes "
                             "through both positions without a branch defect or a dead centre; "
                             "give pivots")
    return best


def _scene(rows, A, D, g, phis, where, notes, name, steps, speed) -> Design:
    B, C = rows[0][:2], rows[0][2:]
    a, b, c, d = math.dist(A, B), math.dist(B, C), math.dist(C, D), math.dist(A, D)
    xy = lambda p: [float(p[0]), float(p[1])]  # noqa: E731
    scene = {
        "name": name,
        "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "rocker"}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": xy(A)},
            {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": xy(B)},
            {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": xy(C)},
            {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": xy(D)},
        ],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": math.degrees(phis[0]),
                     "stop_deg": math.degrees(phis[-1]), "steps": steps, "speed": speed,
                     "acceleration": 0.0}],
        "outputs": ["kinematics"],
    }
    extra = {"crank_angles": [float(p) for p in phis], "pivots": [*xy(A), *xy(D)],
             "gamma_min_crank_angle": float(where)}
    k = min(range(len(phis)), key=lambda i: abs(phis[i] - where))
    at = (f"position {k + 1}" if abs(phis[k] - where) <= 1e-12 else
          "the crank in line with the frame AD")
    text = f"crank angle {fmt_deg(where % (2 * PI))} ({at})"
    return Design("fourbar", scene, {"crank": a, "coupler": b, "rocker": c, "ground": d},
                  tuple(notes), None, None, g, text, extra)


__all__ = ["circumcentre", "coupler_positions", "read_positions"]
