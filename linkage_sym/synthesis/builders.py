"""Scenes from dimensions: the four-bar, the offset slider-crank, the rocking guide-bar.

Nobody should compute assembly coordinates by hand.  Each builder takes the
link lengths and a crank angle and returns a :class:`~linkage_sym.synthesis.common.Design`
whose ``scene`` is a valid scene of the format (``linkage_sym.load_scene``
reads it), with the lengths exact to rounding.

Frame of every scene: the crank's ground pivot ``A`` at the origin, the frame
along ``+x``; the crank angle ``crank_deg`` is measured counter-clockwise from
``+x``; one driver turns the crank a full turn from that angle.

* **four-bar** ``A B C D``: ``D = (d, 0)``; ``branch="open"`` puts ``C`` on
  the left of the directed line ``B -> D`` (above the frame when the crank is
  along ``+x``: the quadrilateral ``ABCD`` is not crossed there),
  ``"crossed"`` its mirror image in ``BD``.  The sign of
  ``(D - B) x (C - B)`` is the assembly mode, constant along a branch.
* **slider-crank**: the slider's line is ``y = offset`` (axis along ``+x``);
  ``branch="right"`` puts the slider at larger ``x`` than the crank pin,
  ``"left"`` at smaller.
* **guide-bar**: ``D = (d, 0)`` is the guide's pivot; the guide is the line
  through ``D`` and the crank pin ``B`` (the rocking guide-bar of the
  shaper of example 3-7 of the textbook chapter *Kinematic analysis of
  planar mechanisms*, Sources [4] of the README).

Examples
--------
>>> import linkage_sym
>>> d = fourbar(0.024, 0.06, 0.05, 0.078, crank_deg=90)
>>> [j["name"] for j in d.scene["joints"]]
['A', 'B', 'C', 'D']
>>> scene = linkage_sym.load_scene(d.scene)
>>> round(math.dist(scene.joint("B").at, scene.joint("C").at), 15)
0.06
"""

from __future__ import annotations

import math

from linkage_sym.structure.grashof import classify
from linkage_sym.synthesis.common import (
    COINCIDENCE,
    MAX_ANGLE_DEG,
    MAX_SPREAD,
    TANGENCY,
    Design,
    SynthesisError,
    acute,
    coordinate,
    crank_apart,
    cross,
    fmt_deg,
    fmt_len,
    half_chord,
    number,
    positive,
    scene_name,
    sweep_options,
    triangle_angle,
    within_reach,
)

BRANCHES = ("open", "crossed")
SLIDER_BRANCHES = ("right", "left")

GUIDE_CLEARANCE = 1e-12
"""A guide-bar's crank and frame distance must differ by more than this fraction
of the frame distance: equal, the block would pass through the guide's pivot ``D``."""

MAX_CRANK_DEG = MAX_ANGLE_DEG - 360.0
"""Largest magnitude of the assembly's crank angle (degrees): the driver turns a
full turn from it, and both ends must be angles the scene format holds."""


def _driver(crank_deg: float, steps: int, speed: float) -> dict:
    return {"joint": "A", "toward": "B", "start_deg": crank_deg, "stop_deg": crank_deg + 360.0,
            "steps": steps, "speed": speed, "acceleration": 0.0}


def _xy(p) -> list:
    return [float(p[0]), float(p[1])]


def _choice(name: str, value, allowed) -> str:
    if value not in allowed:
        raise SynthesisError(name, f"one of {', '.join(allowed)} is expected, got {value!r}")
    return value


def _crank_deg(value) -> float:
    """The assembly's crank angle (degrees), checked against :data:`MAX_CRANK_DEG`."""
    x = number("crank_deg", value)
    if not abs(x) <= MAX_CRANK_DEG:
        raise SynthesisError("crank_deg", f"must be within +-{MAX_CRANK_DEG:g} degrees, got {x:g}: "
                             "the driver turns a full turn from it, and the scene format holds "
                             f"angles within +-{MAX_ANGLE_DEG:.0e} degrees (float64 resolves such "
                             "an angle to 1e-10 degree; beyond, the direction it gives is lost)")
    return x


def _size(points) -> float:
    """The largest distance between two of the points (the mechanism's size)."""
    return max(math.dist(p, q) for p in points for q in points)


def _crank_pin(a: float, crank_deg: float) -> tuple[float, float]:
    phi = math.radians(crank_deg)
    return a * math.cos(phi), a * math.sin(phi)


# ------------------------------------------------------------------ four-bar


def fourbar_gamma_min(a: float, b: float, c: float, d: float) -> tuple[float, float]:
    """Minimum transmission angle of a four-bar over a full crank turn, and the crank angle.

    The angle between coupler and rocker at ``C`` follows from the law of
    cosines in triangle ``BCD``; ``|BD|`` is monotone in the crank angle
    between 0 and 180 degrees, so its extremes -- and those of the
    transmission angle -- are at the crank angles 0 (crank over the frame,
    pointing at ``D``) and 180 degrees.  Valid for a crank that turns fully.

    Returns
    -------
    gamma_min : float
        ``min(gamma, pi - gamma)`` at the worse of the two (rad).
    crank_angle : float
        0 or pi: where it occurs.

    Examples
    --------
    >>> g, at = fourbar_gamma_min(1.0, 3.0, 3.0, 3.5)
    >>> round(math.degrees(g), 6), at
    (49.248637, 0.0)
    """
    g0 = acute(triangle_angle(b, c, abs(d - a)))
    g180 = acute(triangle_angle(b, c, d + a))
    return (g0, 0.0) if g0 <= g180 else (g180, math.pi)


def fourbar_where(crank_angle: float) -> str:
    """Words for the crank angle of a four-bar's minimum transmission angle (0 or pi)."""
    if crank_angle == 0.0:
        return "crank angle 0° (crank over the frame, pointing at D)"
    return "crank angle 180° (crank in line with the frame, pointing away from D)"


def fourbar(crank, coupler, rocker, ground, *, crank_deg=0.0, branch="open", coupler_point=None,
            name="fourbar", steps=361, speed=1.0) -> Design:
    """A four-bar ``A B C D`` from its link lengths (m).

    Parameters
    ----------
    crank, coupler, rocker, ground : float
        Lengths ``AB``, ``BC``, ``CD``, ``AD`` (m), each > 0.
    crank_deg : float
        Crank angle of the assembly configuration, from ``+x`` (degrees);
        the driver turns a full turn from it.
    branch : {"open", "crossed"}
        Assembly mode (see the module docstring).
    coupler_point : (float, float), optional
        A traced point ``P`` of the coupler, ``(u, v)`` in the coupler's
        frame: origin ``B``, ``u`` along ``B -> C``, ``v`` to its left (m).
    name : str
        The scene's name.
    steps : int
        Steps of the sweep (>= 2).
    speed : float
        The crank's angular velocity (rad/s) at every step.

    Returns
    -------
    Design
        ``lengths`` ``crank``, ``coupler``, ``rocker``, ``ground``; ``notes``
        say when the crank cannot turn fully (the Grashof class), and for a
        crank-rocker ``K``, ``theta`` and ``gamma_min`` are set.

    Raises
    ------
    SynthesisError
        A length that is not > 0, lengths that close no loop (the longest
        not shorter than the sum of the others), an unknown branch, or a
        crank angle at
        which the four-bar cannot be assembled (``|BD|`` outside
        ``[|b - c|, b + c]``) or sits at a dead centre (coupler and rocker
        in line: the assembly mode is not defined there), or puts the crank
        pin ``B`` within :data:`~linkage_sym.synthesis.common.COINCIDENCE`
        of the linkage's size from ``D`` (the direction ``B -> D``, which
        places ``C``, is lost in rounding there).

    Examples
    --------
    >>> d = fourbar(1.0, 3.0, 3.0, 3.5, crank_deg=90.0)
    >>> d.scene["joints"][2]["at"]       # C
    [2.4051681333969688, 2.79308846688939]
    >>> d.notes[0]
    "Grashof class: crank-rocker (Grashof: s + l = 1 + 3.5 = 4.5 < p + q = 6; 'crank' (shortest) turns fully, next to the frame: it is the crank)"
    >>> fourbar(1.0, 1.0, 1.0, 2.5, crank_deg=180.0)
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: crank_deg: at 180° the four-bar cannot be assembled: |BD| = 3.5 m is more than coupler + rocker = 2 m (Grashof class: triple-rocker: the crank turns over part of a turn only)
    """
    a, b, c, d = (positive(n, v) for n, v in
                  (("crank", crank), ("coupler", coupler), ("rocker", rocker), ("ground", ground)))
    phi_deg = _crank_deg(crank_deg)
    branch = _choice("branch", branch, BRANCHES)
    point = None if coupler_point is None else _pair("coupler_point", coupler_point)
    steps, speed = sweep_options(steps, speed)
    name = scene_name(name)
    # C stays within the rocker of D, the point P within |P - B| of B, as the crank turns
    within_reach("ground" if d >= c else "rocker", d + c, "ground + rocker")
    if point is not None:
        within_reach("coupler_point", a + math.hypot(*point), "crank + |P - B|")
    longest = max(a, b, c, d)
    if 2 * longest >= a + b + c + d:
        raise SynthesisError("crank", f"no four-bar has these lengths: the longest, "
                             f"{fmt_len(longest)}, is not shorter than the sum of the other three, "
                             f"{fmt_len(a + b + c + d - longest)}")
    g = classify([d, a, b, c], fixed=0, names=["ground", "crank", "coupler", "rocker"])
    full = g.name == "double-crank" or (g.name == "crank-rocker" and g.shortest == 1)
    bx, by, cx, cy = _fourbar_assembly(a, b, c, d, phi_deg, branch, g.name, full)
    size = _size([(0.0, 0.0), (bx, by), (cx, cy), (d, 0.0)])
    crank_apart("crank", a, size, "the crank")
    scene = _fourbar_scene(name, (bx, by), (cx, cy), d, _driver(phi_deg, steps, speed))
    if point is not None:
        scene["points"] = [{"name": "P", "link": "coupler",
                            "at": _coupler_point(point, bx, by, cx, cy, b, size)}]
    notes, extra, K, theta, gmin, where_min = _fourbar_class(a, b, c, d, g, full)
    return Design("fourbar", scene, {"crank": a, "coupler": b, "rocker": c, "ground": d},
                  tuple(notes), K, theta, gmin, where_min, extra)


def _fourbar_assembly(a, b, c, d, phi_deg, branch, g_name, full) -> tuple:
    """``(bx, by, cx, cy)``: the pins ``B`` and ``C`` at the crank angle, refused where the
    four-bar cannot be assembled, sits at a dead centre or has ``B`` on ``D`` (``g_name``, ``full``: its
    Grashof class and whether the crank turns fully, for the refusal)."""
    bx, by = _crank_pin(a, phi_deg)
    r = math.hypot(d - bx, by)
    where = f"at {phi_deg:g}° the four-bar cannot be assembled"
    turns = "" if full else (f" (Grashof class: {g_name}: the crank turns over part of a turn "
                             "only)")
    if r > b + c:
        raise SynthesisError("crank_deg", f"{where}: |BD| = {fmt_len(r)} is more than coupler + "
                                          f"rocker = {fmt_len(b + c)}{turns}")
    if r < abs(b - c):
        raise SynthesisError("crank_deg", f"{where}: |BD| = {fmt_len(r)} is less than |coupler - "
                                          f"rocker| = {fmt_len(abs(b - c))}{turns}")
    if not r > COINCIDENCE * max(a, b, c, d):
        raise SynthesisError("crank_deg", f"at {phi_deg:g}° the crank pin B is {fmt_len(r)} from "
                             f"the rocker pivot D, within {COINCIDENCE:.0e} of the linkage's size, "
                             "where the scene format takes them for one point: the direction B -> D"
                             ", which places C, is lost in the coordinates' rounding (a singular "
                             f"assembly: crank {fmt_len(a)} and ground {fmt_len(d)} bring B onto D, "
                             "coupler and rocker fold onto each other); choose another crank angle")
    h = half_chord(r, b, c)
    if not h > TANGENCY * min(b, c):
        raise SynthesisError("crank_deg", f"at {phi_deg:g}° the coupler and rocker are in line (a "
                                          "dead-centre position): the assembly mode is not defined "
                                          "there; choose another crank angle")
    ux, uy = (d - bx) / r, (0.0 - by) / r
    x = 0.5 * ((b - c) * ((b + c) / r) + r)  # b - c exact when close; no r * r to underflow
    sign = 1.0 if branch == "open" else -1.0
    cx, cy = bx + x * ux - sign * h * uy, by + x * uy + sign * h * ux
    return bx, by, cx, cy


def _fourbar_class(a, b, c, d, g, full) -> tuple:
    """``(notes, extra, K, theta, gmin, where_min)`` of a four-bar of Grashof class ``g``:
    a crank-rocker's ratio, swing and minimum transmission angle, a double-crank's angle, or
    the note that the crank cannot turn fully."""
    notes = [f"Grashof class: {g.name} ({g.detail})"]
    extra = {}
    K = theta = gmin = where_min = None
    if g.name == "crank-rocker" and full:
        gmin, at = fourbar_gamma_min(a, b, c, d)
        where_min = fourbar_where(at)
        theta = fourbar_extreme_angle(a, b, c, d)
        K = (math.pi + theta) / (math.pi - theta)
        extra["swing"] = fourbar_swing(a, b, c, d)
    elif g.name == "double-crank":
        gmin, at = fourbar_gamma_min(a, b, c, d)
        where_min = fourbar_where(at)
    else:
        if g.name == "crank-rocker":
            notes.append("the rocker CD is this loop's crank: driven at A, the linkage rocks")
        notes.append("the crank cannot make the full turn the driver asks for: the steps beyond "
                     "its reach are reported unassemblable")
    return notes, extra, K, theta, gmin, where_min


def _slider_crank_class(a, b, e, full) -> tuple:
    """``(notes, extra, K, theta, gmin, where)`` of a slider-crank: its ratio, stroke and
    minimum transmission angle when the crank turns fully, else the note that it cannot."""
    notes, extra = [], {}
    K = theta = gmin = where = None
    if full:
        theta = slider_crank_extreme_angle(a, b, e)
        K = (math.pi + theta) / (math.pi - theta)
        extra["stroke"] = slider_crank_stroke(a, b, e)
        gmin = math.acos((a + abs(e)) / b)
        where = slider_crank_where(e)
    else:
        notes.append(f"the crank cannot make a full turn (crank + |offset| = {fmt_len(a + abs(e))} "
                     f"> rod = {fmt_len(b)}): the steps beyond its reach are reported unassemblable")
    return notes, extra, K, theta, gmin, where


def _coupler_point(point, bx, by, cx, cy, b, size) -> list:
    """The traced point ``(u, v)`` of the coupler ``B C`` (length ``b``) at its assembly
    position, refused beyond :data:`MAX_SPREAD` sizes from the crank pivot."""
    u, v = point
    ex, ey = (cx - bx) / b, (cy - by) / b
    at = _xy((bx + u * ex - v * ey, by + u * ey + v * ex))
    if math.hypot(*at) > MAX_SPREAD * size:
        raise SynthesisError("coupler_point", f"P is {fmt_len(math.hypot(*at))} from the crank "
                             f"pivot A, more than {MAX_SPREAD:.0e} times the linkage's size "
                             f"({fmt_len(size)}, the largest distance between two joints): "
                             "float64 keeps 16 digits of a coordinate, so fewer than 7 of the "
                             "linkage's geometry would be left")
    return at


def _fourbar_scene(name, B, C, d, driver) -> dict:
    """The four-bar's scene: pivots ``A`` at the origin and ``D`` at ``(d, 0)``, pins ``B``
    and ``C``, the crank driven by ``driver``, kinematics out."""
    joints = [
        {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
        {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": _xy(B)},
        {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": _xy(C)},
        {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": [d, 0.0]},
    ]
    return {"name": name,
            "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "rocker"}],
            "joints": joints, "drivers": [driver], "outputs": ["kinematics"]}


def _pair(name: str, value) -> tuple[float, float]:
    try:
        u, v = value
    except (TypeError, ValueError):
        raise SynthesisError(name, f"two numbers U,V are expected, got {value!r}") from None
    return coordinate(name, u), coordinate(name, v)


def fourbar_extreme_angle(a: float, b: float, c: float, d: float) -> float:
    """Extreme-position angle ``theta`` of a crank-rocker (rad): the angle ``C1 A C2``.

    At the rocker's extreme positions crank and coupler are in line:
    ``AC1 = b + a`` (extended), ``AC2 = b - a`` (overlapping); the law of
    cosines in triangles ``A C1 D`` and ``A C2 D`` gives their angles at
    ``A``; ``C1`` and ``C2`` lie on one side of ``AD`` (one assembly mode), so
    ``theta`` is the difference.

    Examples
    --------
    >>> round(math.degrees(fourbar_extreme_angle(1.0, 3.0, 3.0, 3.5)), 9)
    12.243914224
    """
    return abs(triangle_angle(b + a, d, c) - triangle_angle(b - a, d, c))


def fourbar_swing(a: float, b: float, c: float, d: float) -> float:
    """Swing angle ``psi`` of a crank-rocker's rocker (rad): the angle ``C1 D C2``.

    Examples
    --------
    >>> round(math.degrees(fourbar_swing(1.0, 3.0, 3.0, 3.5)), 9)
    40.750543782
    """
    return abs(triangle_angle(c, d, b + a) - triangle_angle(c, d, b - a))


# ------------------------------------------------------------------ slider-crank


def slider_crank(crank, coupler, offset=0.0, *, crank_deg=0.0, branch="right", name="slider-crank",
                 steps=361, speed=1.0) -> Design:
    """An (offset) slider-crank ``A B C`` from its crank, connecting rod and offset (m).

    Parameters
    ----------
    crank, coupler : float
        Lengths ``AB`` and ``BC`` (m), each > 0.
    offset : float
        The slider's line is ``y = offset`` (m; either sign).
    crank_deg : float
        Crank angle of the assembly configuration (degrees from ``+x``).
    branch : {"right", "left"}
        Slider at larger (``right``) or smaller ``x`` than the crank pin.
    name, steps, speed
        As for :func:`fourbar`.

    Returns
    -------
    Design
        Links ``crank``, ``coupler``, ``slider``; joints ``A``, ``B``, ``C``
        and the slide ``C_guide`` (P, ground-slider, axis 0°).

    Raises
    ------
    SynthesisError
        A length that is not > 0, or a crank angle at which the rod cannot
        reach the slider's line, or reaches it perpendicularly (a dead
        centre).

    Examples
    --------
    >>> d = slider_crank(0.05, 0.2, 0.02, crank_deg=90.0)
    >>> d.scene["joints"][2]["at"]
    [0.1977371993328519, 0.02]
    >>> round(d.extra["stroke"], 12), round(math.degrees(d.theta), 9)
    (0.100538028414, 3.073689925)
    >>> slider_crank(0.05, 0.1, 0.2, crank_deg=-90.0)
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: crank_deg: at -90° the connecting rod (0.1 m) cannot reach the slider's line: it is 0.25 m from the crank pin (the crank turns over part of a turn only: crank + |offset| = 0.25 m > rod = 0.1 m)
    """
    a, b = positive("crank", crank), positive("coupler", coupler)
    e = coordinate("offset", offset)
    phi_deg = _crank_deg(crank_deg)
    branch = _choice("branch", branch, SLIDER_BRANCHES)
    steps, speed = sweep_options(steps, speed)
    name = scene_name(name)
    within_reach("coupler" if b >= a else "crank", a + b, "crank + connecting rod")
    bx, by = _crank_pin(a, phi_deg)
    dy = abs(e - by)
    full = b > a + abs(e)
    part = ("" if full else f" (the crank turns over part of a turn only: crank + |offset| = "
                            f"{fmt_len(a + abs(e))} > rod = {fmt_len(b)})")
    if dy > b:
        raise SynthesisError("crank_deg", f"at {phi_deg:g}° the connecting rod ({fmt_len(b)}) cannot "
                                          f"reach the slider's line: it is {fmt_len(dy)} from the "
                                          f"crank pin{part}")
    h = math.sqrt((b - dy) * (b + dy))
    if not h > TANGENCY * b:
        raise SynthesisError("crank_deg", f"at {phi_deg:g}° the connecting rod is perpendicular to "
                                          "the slider's line (a dead-centre position): the assembly "
                                          "mode is not defined there; choose another crank angle")
    cx = bx + (h if branch == "right" else -h)
    crank_apart("crank", a, _size([(0.0, 0.0), (bx, by), (cx, e)]), "the crank")
    joints = [
        {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
        {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": _xy((bx, by))},
        {"name": "C", "type": "R", "links": ["coupler", "slider"], "at": [cx, e]},
        {"name": "C_guide", "type": "P", "links": ["ground", "slider"], "at": [cx, e],
         "axis_deg": 0.0},
    ]
    scene = {"name": name, "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "slider"}],
             "joints": joints, "drivers": [_driver(phi_deg, steps, speed)],
             "outputs": ["kinematics"]}
    notes, extra, K, theta, gmin, where = _slider_crank_class(a, b, e, full)
    return Design("slider-crank", scene, {"crank": a, "coupler": b, "offset": e}, tuple(notes),
                  K, theta, gmin, where, extra)


def slider_crank_where(e: float) -> str:
    """Words for the crank angle of a slider-crank's minimum transmission angle."""
    deg = 270 if e > 0 else 90
    side = "below" if e > 0 else "above"
    if e == 0:
        return "crank angles 90° and 270° (crank perpendicular to the slider's line)"
    return (f"crank angle {deg}° (crank perpendicular to the slider's line, pointing away from "
            f"it, {side} A)")


def slider_crank_stroke(a: float, b: float, e: float) -> float:
    """Stroke ``H`` of a slider-crank whose crank turns fully (m).

    The slider's extreme positions are where crank and rod are in line, at
    ``b + a`` and ``b - a`` from ``A``; their distances along the line differ by
    ``H = sqrt((b + a)^2 - e^2) - sqrt((b - a)^2 - e^2)``.

    Examples
    --------
    >>> round(slider_crank_stroke(0.05, 0.2, 0.0), 15)
    0.1
    """
    return math.sqrt((b + a + e) * (b + a - e)) - math.sqrt((b - a + e) * (b - a - e))


def slider_crank_extreme_angle(a: float, b: float, e: float) -> float:
    """Extreme-position angle of a slider-crank (rad): ``asin(e/(b - a)) - asin(e/(b + a))``.

    Examples
    --------
    >>> slider_crank_extreme_angle(0.05, 0.2, 0.0)
    0.0
    """
    e = abs(e)
    return math.asin(e / (b - a)) - math.asin(e / (b + a))


# ------------------------------------------------------------------ guide-bar


def guide_bar(crank, ground, *, crank_deg=0.0, name="guide-bar", steps=361, speed=1.0) -> Design:
    """A guide-bar ``A B D`` from its crank ``AB`` and frame distance ``AD`` (m).

    The block (link ``slider``) turns on the crank pin ``B`` and slides along
    the guide (link ``rocker``), a line through the guide's pivot ``D``.
    With ``crank < ground`` the guide rocks (the quick-return guide-bar); with
    ``crank > ground`` it turns fully (a note says so).

    Parameters
    ----------
    crank, ground : float
        ``AB`` and ``AD`` (m), each > 0, not equal (the block would pass
        through ``D``, where the guide's direction is undefined).
    crank_deg, name, steps, speed
        As for :func:`fourbar`.

    Returns
    -------
    Design
        Links ``crank``, ``slider`` (the block), ``rocker`` (the guide);
        joints ``A``, ``B``, ``B_slide`` (P, rocker-slider, along ``D -> B``),
        ``D``.

    Examples
    --------
    >>> d = guide_bar(0.03, 0.06, crank_deg=90.0)
    >>> d.scene["joints"][2]["axis_deg"]
    153.434948822922
    >>> round(math.degrees(d.theta), 9), d.gamma_min_where
    (60.0, 'every crank angle (the block presses on the guide perpendicular to it)')
    >>> guide_bar(0.05, 0.05)
    Traceback (most recent call last):
    ...
    linkage_sym.synthesis.common.SynthesisError: crank: equals ground (0.05 m): the block would pass through the guide's pivot D, where the guide's direction is undefined
    """
    a, d = positive("crank", crank), positive("ground", ground)
    phi_deg = _crank_deg(crank_deg)
    steps, speed = sweep_options(steps, speed)
    name = scene_name(name)
    if abs(a - d) <= GUIDE_CLEARANCE * d:
        raise SynthesisError("crank", f"equals ground ({fmt_len(d)}): the block would pass through "
                                      "the guide's pivot D, where the guide's direction is undefined")
    bx, by = _crank_pin(a, phi_deg)
    crank_apart("crank", a, _size([(0.0, 0.0), (bx, by), (d, 0.0)]), "the crank")
    axis = math.degrees(math.atan2(by, bx - d))
    joints = [
        {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
        {"name": "B", "type": "R", "links": ["crank", "slider"], "at": _xy((bx, by))},
        {"name": "B_slide", "type": "P", "links": ["rocker", "slider"], "at": _xy((bx, by)),
         "axis_deg": axis},
        {"name": "D", "type": "R", "links": ["ground", "rocker"], "at": [d, 0.0]},
    ]
    scene = {"name": name, "links": [{"name": "crank"}, {"name": "slider"}, {"name": "rocker"}],
             "joints": joints, "drivers": [_driver(phi_deg, steps, speed)],
             "outputs": ["kinematics"]}
    notes, extra = [], {}
    K = theta = None
    if a < d:
        theta = 2.0 * math.asin(a / d)
        K = (math.pi + theta) / (math.pi - theta)
        extra["swing"] = theta
    else:
        notes.append("crank > ground: the guide turns fully (a rotating guide-bar), it does not rock")
    return Design("guide-bar", scene, {"crank": a, "ground": d}, tuple(notes), K, theta,
                  math.pi / 2, GUIDE_BAR_WHERE, extra)


GUIDE_BAR_WHERE = "every crank angle (the block presses on the guide perpendicular to it)"
"""The guide-bar's transmission angle is 90° at every position: the block's
force on the guide is normal to the guide, and so is the velocity of the
guide's point under the block."""


def describe(design: Design) -> list[str]:
    """Lines for a person: the dimensions, K and theta, the minimum transmission angle.

    Examples
    --------
    >>> for line in describe(guide_bar(0.03, 0.06)):
    ...     print(line)
    guide-bar: crank 0.03 m, ground 0.06 m
    stroke-time ratio K = 2, extreme-position angle θ = 60°, guide swing ψ = 60°
    minimum transmission angle 90° at every crank angle (the block presses on the guide perpendicular to it)
    """
    dims = ", ".join(f"{k} {fmt_len(v)}" for k, v in design.lengths.items())
    lines = [f"{design.kind}: {dims}"]
    if design.K is not None:
        text = f"stroke-time ratio K = {design.K:.6g}, extreme-position angle θ = {fmt_deg(design.theta)}"
        if "swing" in design.extra:
            what = "guide swing" if design.kind == "guide-bar" else "rocker swing"
            text += f", {what} ψ = {fmt_deg(design.extra['swing'])}"
        if "stroke" in design.extra:
            text += f", stroke H = {fmt_len(design.extra['stroke'])}"
        lines.append(text)
    if design.gamma_min is not None:
        lines.append(f"minimum transmission angle {fmt_deg(design.gamma_min)} at {design.gamma_min_where}")
    return lines


__all__ = ["BRANCHES", "SLIDER_BRANCHES", "describe", "fourbar", "guide_bar", "slider_crank",
           "cross"]
