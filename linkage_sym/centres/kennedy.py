"""Instant centres by Kennedy's three-centre theorem: geometry only, no velocities.

The textbook chapter *Kinematic analysis of planar mechanisms* (README Sources [4], section 3-2,
eq. 3-5) finds the centres of a linkage in two steps:

1. *Primary centres* come from the joints: an ``R`` joint is the centre of
   its two links (at the pin), a ``P`` joint's centre lies at infinity normal
   to the slide, a gear mesh's (``G`` joint, rolling without slip: the
   chapter's Fig. 3-3c) is its pitch point.  A pin shared by three or more links (written, as the format
   says, as several ``R`` joints at the same point of a common link) is the
   centre of every pair of them.
2. Every other centre ``P_ij`` lies on the line through ``P_ik`` and
   ``P_kj`` for every third link ``k`` (Kennedy's, or the Kennedy-Aronhold,
   three-centre theorem).  Two such lines meet at ``P_ij``.  Which pairs can
   be reached this way is a graph question (the textbook's circle diagram):
   the links are nodes, known centres edges, and a missing edge ``ij`` is
   added once two triangles ``ikj``, ``ilj`` close on it.

This module computes only that.  Points and lines are homogeneous
coordinates (projective plane), so a centre at infinity is a point like any
other: the line through a finite centre and the point at infinity in the
direction ``u`` is the line through the centre along ``u``; two parallel
lines meet at infinity.  It reads the joints' positions and the links'
rotations of an analysis, never a velocity: the velocity method
(:mod:`linkage_sym.centres.velocity`) shares no code with it and checks it.

Numbers
-------
Coordinates are made dimensionless about the centre ``c`` of the assembly
configuration's joints, in units of the mechanism's size ``L`` (the largest
distance between two joints, the format's characteristic length), and every
homogeneous vector is scaled to unit length, so no product overflows or
underflows whatever the units of the scene.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkage_sym.model import GROUND

__all__ = ["FAR", "KennedyCentres", "kennedy_centres"]

FAR = 1e9
"""A centre farther than this many mechanism sizes from the mechanism is at infinity.

Two lines through points of the mechanism that meet so far away are parallel
to within 1e-9 rad: in float64 their meeting point is only known to about
``1e-16 * (d / L)**2`` sizes, already 100 sizes at 1e9.  Such a centre is
reported by its direction, as an exact point at infinity.
"""

DEGENERATE = 1e-13
"""Two centres closer than this (relative, in the scaled frame) span no line.

Such a pair of centres gives no three-centre line at that step; the centre
sought is then found from the other lines, or not at that step.
"""

ROUNDING = 8 * float(np.finfo(float).eps)
"""Error estimate of a primary centre: of a pin, relative to its distance from the
global origin (at least one mechanism size); of a slide's direction, relative to
its angle (at least 1 rad)."""

DISTINCT = 1e3
"""Two nearly parallel three-centre lines meet at infinity only if they lie this many times
their possible offsets apart; closer, they may be one line, and they meet nowhere in
particular (the intersection is not used)."""

UNCERTAIN = 1e-3
"""An intersection whose estimated error exceeds this fraction of its distance (at least one
mechanism size) is not used: the lines are too nearly one."""

@dataclass
class KennedyCentres:
    """The centres Kennedy's theorem reaches, at every step of a sweep.

    Attributes
    ----------
    links : tuple of str
        ``ground`` then the scene's links in scene order.
    pairs : tuple of (str, str)
        Every unordered pair of ``links``, ``(links[i], links[j])`` with
        ``i < j``, in the order ``(0, 1), (0, 2), ..., (1, 2), ...``.
    position : ndarray, shape (N, P, 2)
        Global position (m) of each finite centre; NaN where the centre is at
        infinity or was not reached.
    direction : ndarray, shape (N, P, 2)
        Unit direction of each centre at infinity; NaN elsewhere.
    at_infinity : ndarray of bool, shape (N, P)
    reached : ndarray of bool, shape (N, P)
        Whether the centre was found at that step (False at steps without
        positions, and where every three-centre line through it degenerates).
    angle : ndarray, shape (N, P)
        For a centre found by intersecting two three-centre lines: the angle
        (rad, in ``[0, pi/2]``) between them, the conditioning of that
        intersection; ``pi/2`` where one line is the line at infinity; NaN for
        primary centres and where not reached.
    via : ndarray of int, shape (N, P, 2)
        The two third links ``k``, ``l`` (indices into ``links``) whose
        lines ``P_ik P_kj`` and ``P_il P_lj`` gave the centre; ``-1`` for
        primary centres and where not reached.
    weakest : ndarray, shape (N, P)
        The smallest angle (rad) of every intersection the centre rests on:
        its own and those of the centres its lines pass through, and theirs;
        ``pi/2`` for primary centres, NaN where not reached.  An intersection
        of lines at the angle ``a`` magnifies the errors of the lines by
        ``1/sin a``, so a small value flags a centre known to fewer digits
        (a line through a centre that is itself a near-parallel intersection).
    source : tuple of str
        Per pair: ``"joint A"``, ``"joint S (slide)"``, ``"pin of joints C, C2"``,
        ``"three-centre lines"`` or ``"unreachable"`` (the three-centre lines
        run out: no two triangles of known centres close on the pair).
    pinned : ndarray of bool, shape (P,)
        Whether the pair's links share a pin (an ``R`` joint between them, or a
        pin shared by several links): the pin is a point of zero relative
        velocity at every step, so it is their centre even at a step where
        they are at rest relative to each other.
    """

    links: tuple
    pairs: tuple
    position: np.ndarray
    direction: np.ndarray
    at_infinity: np.ndarray
    reached: np.ndarray
    angle: np.ndarray
    via: np.ndarray
    weakest: np.ndarray
    source: tuple
    pinned: np.ndarray

    def index(self, a: str, b: str) -> int:
        """Index into :attr:`pairs` of the unordered pair ``{a, b}``.

        Examples
        --------
        >>> import linkage_sym
        >>> scene = linkage_sym.load_example("crank_rocker")
        >>> k = kennedy_centres(scene, linkage_sym.analyze(scene))
        >>> k.index("coupler", "ground"), k.pairs[1]
        (1, ('ground', 'coupler'))
        """
        i, j = self.links.index(a), self.links.index(b)
        i, j = min(i, j), max(i, j)
        n = len(self.links)
        return i * n - i * (i + 1) // 2 + (j - i - 1)


def _unit(h):
    """Homogeneous vectors (..., 3) scaled to unit length (zero vectors become NaN)."""
    norm = np.linalg.norm(h, axis=-1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        return np.where(norm > 0.0, h / norm, np.nan)


def _snap(h):
    """Unit homogeneous points with those beyond :data:`FAR` sizes set exactly at infinity."""
    h = _unit(h)
    w = np.abs(h[..., 2])
    xy = np.linalg.norm(h[..., :2], axis=-1)
    far = w * FAR <= xy
    h = np.where(far[..., None], np.concatenate([h[..., :2], np.zeros_like(h[..., 2:])], -1), h)
    return _unit(h)


def _joint_pins(scene):
    """Groups of ``R`` joints that are one pin: on a common link (or the ground) and at one
    assembly point."""
    rj = [j for j in scene.joints if j.type == "R"]
    parent = list(range(len(rj)))

    def root(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a in range(len(rj)):
        for b in range(a + 1, len(rj)):
            ja, jb = rj[a], rj[b]
            shared = (set(ja.links) & set(jb.links)) - {GROUND}
            # at one point exactly, as the format writes a shared pin: two pins apart by
            # however little are two points, whose relative centre lies on their line
            close = tuple(ja.at) == tuple(jb.at)
            # on the ground two pivots at one point are one pin as well
            if close and (shared or (GROUND in ja.links and GROUND in jb.links)):
                parent[root(a)] = root(b)
    groups = {}
    for a in range(len(rj)):
        groups.setdefault(root(a), []).append(rj[a])
    return [g for g in groups.values() if len(g) > 1]


def kennedy_centres(scene, analysis) -> KennedyCentres:
    """Every instant centre Kennedy's theorem reaches, at every step.

    Parameters
    ----------
    scene : Scene
        The mechanism (joints, their types and slide axes).
    analysis : Analysis
        Its solved sweep; only ``joints[...].position`` of the ``R`` joints
        and ``links[...].rotation`` of the guides of ``P`` joints are read.

    Returns
    -------
    KennedyCentres

    Notes
    -----
    The pairs are reached in rounds: a round adds every missing pair that
    two triangles of centres known at its start close on.  A pair no round
    reaches is ``"unreachable"``: e.g. the five-bar's (two degrees of freedom)
    secondary centres depend on the ratio of its input speeds, which geometry
    does not know.

    A centre with more than two lines through it is, at each step, the
    intersection with the smallest estimated error: each centre carries an
    error estimate (rounding of the pins, ``ROUNDING``), a line through two
    centres may be off by their errors, tilted by their sum over their
    distance, and an intersection is off by the lines' offsets there over the
    sine of their angle.  Lines through centres that coincide at that step,
    or through a centre not found at that step, are skipped; so is a meeting
    whose estimated error exceeds ``UNCERTAIN`` of its distance, and a meeting
    at infinity of two lines that are not ``DISTINCT`` (they may be one line
    for all their errors): where no pair of lines is left, the centre is not
    reached at that step rather than guessed.  Once every
    reachable pair is known, every derived centre is intersected again with
    all the lines there are (later centres give lines through earlier ones)
    until no estimate improves.

    Examples
    --------
    The four-bar's ``P13`` (ground--coupler, the textbook's numbering with the
    ground as link 1) is where lines ``AB`` and ``DC`` meet:

    >>> import numpy as np, linkage_sym
    >>> scene = linkage_sym.load_example("crank_rocker")
    >>> res = linkage_sym.analyze(scene)
    >>> k = kennedy_centres(scene, res)
    >>> len(k.pairs), k.source[:3]
    (6, ('joint A', 'three-centre lines', 'joint D'))
    >>> A, B, C, D = (res.joints[n].position[90] for n in "ABCD")
    >>> P13 = k.position[90, k.index("ground", "coupler")]
    >>> cross = lambda u, v: u[0] * v[1] - u[1] * v[0]
    >>> bool(abs(cross(B - A, P13 - A)) < 1e-15 and abs(cross(C - D, P13 - D)) < 1e-15)
    True

    A slider's centre with the ground is at infinity, normal to its slide:

    >>> s = linkage_sym.load_example("slider_crank_offset")
    >>> k = kennedy_centres(s, linkage_sym.analyze(s))
    >>> i = k.index("ground", "slider")
    >>> k.source[i], bool(k.at_infinity[0, i]), np.abs(k.direction[0, i]).round(12).tolist()
    ('joint C_guide (slide)', True, [0.0, 1.0])
    """
    names = (GROUND, *scene.link_names)
    n = len(names)
    idx = {name: i for i, name in enumerate(names)}
    N = len(analysis.status)
    pts = np.array([j.at for j in scene.joints], dtype=float)
    c = pts.mean(axis=0)
    L = scene.characteristic_length() or 1.0

    H = np.full((n, n, N, 3), np.nan)  # unit homogeneous centres, scaled frame, symmetric
    PG = np.full((n, n, N, 2), np.nan)  # the finite ones in global coordinates (m)
    E = np.full((n, n, N), np.nan)  # error estimate: scaled length (finite), rad (at infinity)
    known = np.zeros((n, n), dtype=bool)
    ang = np.full((n, n, N), np.nan)
    weak = np.full((n, n, N), np.nan)
    via = np.full((n, n, N, 2), -1, dtype=int)
    source: dict = {}
    pinned: set = set()

    def put(a, b, h, err, what, at=None):
        weak[a, b] = weak[b, a] = np.where(np.all(np.isfinite(h), axis=-1), np.pi / 2, np.nan)
        H[a, b] = H[b, a] = h
        if at is not None:
            PG[a, b] = PG[b, a] = at
        E[a, b] = E[b, a] = err
        known[a, b] = known[b, a] = True
        source[min(a, b), max(a, b)] = what

    def finite(p):
        p = np.asarray(p, dtype=float)
        err = ROUNDING * (1.0 + np.linalg.norm(p, axis=-1) / L)
        return _snap(np.concatenate([(p - c) / L, np.ones((N, 1))], axis=-1)), err

    for joint in scene.joints:  # pins first: a pin wins over a slide between the same links
        if joint.type == "R":
            a, b = idx[joint.links[0]], idx[joint.links[1]]
            if not known[a, b]:
                at = np.asarray(analysis.joints[joint.name].position, dtype=float)
                put(a, b, *finite(at), f"joint {joint.name}", at)
                pinned.add((min(a, b), max(a, b)))
    for joint in scene.joints:  # a gear mesh rolls without slip: its pitch point (Fig. 3-3c)
        if joint.type == "G":
            a, b = idx[joint.links[0]], idx[joint.links[1]]
            if not known[a, b]:
                at = np.asarray(analysis.joints[joint.name].position, dtype=float)
                put(a, b, *finite(at), f"pitch point of mesh {joint.name}", at)
    for joint in scene.joints:
        if joint.type == "P":
            a, b = idx[joint.links[0]], idx[joint.links[1]]
            if known[a, b]:
                continue
            guide = joint.links[0]
            turn = 0.0 if guide == GROUND else np.asarray(analysis.links[guide].rotation, float)
            th = joint.axis + turn + np.zeros(N)
            put(a, b, np.stack([-np.sin(th), np.cos(th), np.zeros(N)], axis=-1),
                ROUNDING * (1.0 + np.abs(th)), f"joint {joint.name} (slide)")
    for group in _joint_pins(scene):
        members = sorted({idx[x] for j in group for x in j.links})
        at = np.asarray(analysis.joints[group[0].name].position, dtype=float)
        where = finite(at)
        label = f"pin of joints {', '.join(j.name for j in group)}"
        for a in members:
            for b in members:
                if a < b and not known[a, b]:
                    put(a, b, *where, label, at)
                    pinned.add((a, b))

    for joint in scene.joints:  # a cam contact's centre: on the contact normal (Kennedy)
        if joint.type == "cam":
            a, b = idx[joint.links[0]], idx[joint.links[1]]
            N_ = np.asarray(analysis.joints[joint.name].normal, dtype=float).T  # recorded
            C = np.asarray(analysis.joints[joint.name].position, dtype=float)
            normal = np.cross(finite(C)[0], np.stack([N_[0], N_[1], np.zeros(N)], axis=-1))
            for k in range(n):
                if k not in (a, b) and known[a, k] and known[b, k] and not known[a, b]:
                    other = np.cross(H[a, k], H[b, k])
                    h = _snap(np.cross(other, normal))
                    sin = np.abs(_unit(other)[..., 0] * _unit(normal)[..., 1]
                                 - _unit(other)[..., 1] * _unit(normal)[..., 0])
                    err = (E[a, k] + E[b, k] + ROUNDING) / np.maximum(sin, 1e-300)
                    put(a, b, h, err, f"contact normal of cam {joint.name} and line "
                        f"P{names[a]},{names[k]}-P{names[b]},{names[k]}", _global(h, c, L))
    steps = np.arange(N)

    def chain(i, j, a, v):
        """Weakest angle of centre ``ij`` met at angle ``a`` by the lines via ``v`` (N, 2).

        A centre at infinity has the lines' direction, known as well as the lines
        are, however small ``a``: its own angle does not count.
        """
        out = np.where(H[i, j, :, 2] == 0.0, np.pi / 2, a)
        for col in (0, 1):
            k = np.maximum(v[:, col], 0)
            for end in (i, j):
                w = weak[end, k, steps]
                out = np.where(v[:, col] >= 0, np.fmin(out, w), out)
        return out

    def lines_through(i, j):
        return [k for k in range(n) if k not in (i, j) and known[i, k] and known[k, j]]

    derived = []
    while True:  # rounds of the circle diagram
        found = [(i, j, lines_through(i, j)) for i in range(n) for j in range(i + 1, n)
                 if not known[i, j]]
        found = [f for f in found if len(f[2]) >= 2]
        if not found:
            break
        for i, j, ks in found:
            h, err, a, v = _intersect_best(H, PG, E, i, j, ks, c, L)
            H[i, j] = H[j, i] = h
            PG[i, j] = PG[j, i] = _global(h, c, L)
            E[i, j] = E[j, i] = err
            ang[i, j] = ang[j, i] = a
            via[i, j] = via[j, i] = v
            weak[i, j] = weak[j, i] = chain(i, j, a, v)
        for i, j, _ in found:
            known[i, j] = known[j, i] = True
            source[i, j] = "three-centre lines"
            derived.append((i, j))
    # Centres found in later rounds give more lines through the earlier ones (in the shaper the
    # first two lines through P(crank, ram) are one line at every step): intersect again with
    # every line there is, and keep, step by step, the intersection with the smaller error.
    for _ in range(n):
        improved = False
        for i, j in derived:
            h, err, a, v = _intersect_best(H, PG, E, i, j, lines_through(i, j), c, L)
            better = np.isfinite(err) & ~(_relative(h, err) >= _relative(H[i, j], E[i, j]))
            better &= ~np.isclose(err, E[i, j], rtol=1e-3, atol=0.0)  # no churn on ties
            if better.any():
                improved = True
                H[i, j] = H[j, i] = np.where(better[:, None], h, H[i, j])
                PG[i, j] = PG[j, i] = np.where(better[:, None], _global(h, c, L), PG[i, j])
                E[i, j] = E[j, i] = np.where(better, err, E[i, j])
                ang[i, j] = ang[j, i] = np.where(better, a, ang[i, j])
                via[i, j] = via[j, i] = np.where(better[:, None], v, via[i, j])
        if not improved:
            break
    for _ in range(n):  # the weakest angles along the final chains (they may be circular)
        before = weak.copy()
        for i, j in derived:
            weak[i, j] = weak[j, i] = chain(i, j, ang[i, j], via[i, j])
        if np.array_equal(before, weak, equal_nan=True):
            break

    pairs, P = [], []
    for i in range(n):
        for j in range(i + 1, n):
            pairs.append((names[i], names[j]))
            P.append((i, j))
    h = np.stack([H[i, j] for i, j in P], axis=1)  # (N, P, 3)
    reached = np.all(np.isfinite(h), axis=-1)
    inf = reached & (h[..., 2] == 0.0)
    fin = reached & ~inf
    pos = np.stack([PG[i, j] for i, j in P], axis=1)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        d = h[..., :2] / np.linalg.norm(h[..., :2], axis=-1, keepdims=True)
    return KennedyCentres(
        links=names,
        pairs=tuple(pairs),
        position=np.where(fin[..., None], pos, np.nan),
        direction=np.where(inf[..., None], d, np.nan),
        at_infinity=inf,
        reached=reached,
        angle=np.stack([ang[i, j] for i, j in P], axis=1),
        via=np.stack([via[i, j] for i, j in P], axis=1),
        weakest=np.stack([weak[i, j] for i, j in P], axis=1),
        source=tuple(source.get(p, "unreachable") for p in P),
        pinned=np.array([p in pinned for p in P], dtype=bool),
    )


def _relative(h, err):
    """Error relative to a centre's distance (at least one size); angular error at infinity."""
    w = np.abs(h[..., 2])
    xy = np.linalg.norm(h[..., :2], axis=-1)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        return np.where(w > 0.0, err / np.maximum(1.0, xy / w), err)


def _global(h, c, L):
    """Global position (N, 2) of unit homogeneous points of the scaled frame; NaN at infinity."""
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        return np.where((h[:, 2] != 0.0)[:, None], c + L * h[:, :2] / h[:, 2:3], np.nan)


def _line(ha, pa, hb, pb, c, L):
    """The three-centre line through two centres, in the scaled frame (N, 3).

    ``(n, c0)`` with ``|n| = 1`` for the line ``n . x + c0 = 0``, ``(0, 0, 1)`` for the
    line at infinity (through two centres at infinity), NaN where the two centres
    span no line (they coincide, or one is missing).  The direction comes from the
    difference of the global positions (or is a centre's direction at infinity),
    never from a difference of shifted coordinates: two pins 1e-7 of the size apart
    give their line to rounding of their own coordinates, not 1e7 times that.
    """
    fa = np.all(np.isfinite(pa), axis=-1)
    fb = np.all(np.isfinite(pb), axis=-1)
    ia = np.all(np.isfinite(ha), axis=-1) & ~fa
    ib = np.all(np.isfinite(hb), axis=-1) & ~fb
    d = np.where((fa & fb)[:, None], pb - pa, np.where(fa[:, None], hb[:, :2], ha[:, :2]))
    span = np.linalg.norm(d, axis=-1)
    anchor = np.where(fa[:, None], pa, pb)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        nrm = np.stack([-d[:, 1], d[:, 0]], axis=-1) / span[:, None]
        c0 = -np.sum(nrm * (anchor - c), axis=-1) / L
    line = np.concatenate([nrm, c0[:, None]], axis=-1)
    finite_line = (fa & fb & (span > DEGENERATE * L)) | (fa & ib) | (ia & fb)
    apart = np.abs(ha[:, 0] * hb[:, 1] - ha[:, 1] * hb[:, 0]) > DEGENERATE
    at_inf = ia & ib & apart
    return np.where(finite_line[:, None], line,
                    np.where(at_inf[:, None], np.array([0.0, 0.0, 1.0]), np.nan))


def _line_error(pa, ea, pb, eb):
    """How far a three-centre line through centres at ``pa``, ``pb`` (scaled frame) may be off.

    ``pa``, ``pb`` are NaN for a centre at infinity, whose ``e`` is then the error of
    its direction (rad).  Returns ``(q, e0, slope, at_inf)``: the line may be displaced
    by ``e0 + slope * |X - q|`` at a point ``X``; ``at_inf`` marks the line at infinity
    (both centres at infinity), for which ``slope`` is the directions' error.
    """
    fa = np.all(np.isfinite(pa), axis=-1)
    fb = np.all(np.isfinite(pb), axis=-1)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        span = np.linalg.norm(pa - pb, axis=-1)
        slope_ff = (ea + eb) / span
    q = np.where(fa[..., None], pa, pb)
    e0 = np.where(fa & fb, np.maximum(ea, eb), np.where(fa, ea, eb))
    slope = np.where(fa & fb, slope_ff, np.where(fa, eb, np.where(fb, ea, np.maximum(ea, eb))))
    return q, e0, slope, ~fa & ~fb


def _intersect_best(H, PG, E, i, j, ks, c, L):
    """Centre ``P_ij`` from the best pair of three-centre lines through it.

    For every step, of the lines ``P_ik P_kj`` (``k`` in ``ks``) the pair whose
    intersection has the smallest estimated error (relative to its distance)
    is used: the error of each line, propagated from the error estimates of
    its two centres, divided by the sine of the angle between the lines.

    Returns
    -------
    h : ndarray (N, 3)
        Unit homogeneous centre, scaled frame (NaN where no pair of lines meets).
    err : ndarray (N,)
        Its error estimate: scaled length, or rad for a centre at infinity.
    angle : ndarray (N,)
        Angle between the two lines used (rad, ``pi/2`` with the line at infinity).
    via : ndarray of int (N, 2)
        Their third links ``k``, ``l``.
    """
    lines = np.stack([_line(H[i, k], PG[i, k], H[k, j], PG[k, j], c, L) for k in ks])
    model = [_line_error((PG[i, k] - c) / L, E[i, k], (PG[k, j] - c) / L, E[k, j]) for k in ks]
    K, N = lines.shape[:2]
    best_r = np.full(N, np.inf)
    best = np.full((N, 3), np.nan)
    best_err = np.full(N, np.nan)
    best_angle = np.full(N, np.nan)
    best_via = np.full((N, 2), -1, dtype=int)
    for a in range(K):
        for b in range(a + 1, K):
            la, lb = lines[a], lines[b]
            qa, ea, sa, ia = model[a]
            qb, eb, sb, ib = model[b]
            meet = np.cross(la, lb)
            # one line twice (or a line through a centre missing at that step) meets nothing
            valid = np.linalg.norm(meet, axis=-1) > DEGENERATE  # False for NaN too
            h = _snap(meet)
            with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
                sin = np.abs(la[:, 0] * lb[:, 1] - la[:, 1] * lb[:, 0]) / (
                    np.linalg.norm(la[:, :2], axis=-1) * np.linalg.norm(lb[:, :2], axis=-1))
                sin = np.minimum(np.where(ia | ib, 1.0, sin), 1.0)
                X = h[:, :2] / h[:, 2:3]
                off = (ea + sa * np.linalg.norm(X - qa, axis=-1)
                       + eb + sb * np.linalg.norm(X - qb, axis=-1))
                err = np.where(h[:, 2] != 0.0, off / sin,
                               np.where(ia, sb, np.where(ib, sa, np.maximum(sa, sb))))
                # Nearly parallel lines meet far away (at infinity after the snap) only if they
                # are two lines: apart, near the mechanism, by much more than either may be off
                # there.  Lines that one may be for all their errors meet anywhere.
                na = np.linalg.norm(la[:, :2], axis=-1)
                nb = np.linalg.norm(lb[:, :2], axis=-1)
                same_sense = np.sign(np.sum(la[:, :2] * lb[:, :2], axis=-1))
                apart = np.abs(la[:, 2] / na - same_sense * lb[:, 2] / nb)
                slack = (ea + sa * np.linalg.norm(qa, axis=-1) + eb + sb * np.linalg.norm(qb, axis=-1))
                two_lines = ia | ib | (apart > DISTINCT * slack)
            rel = _relative(h, err)
            valid &= np.where(h[:, 2] == 0.0, two_lines, rel <= UNCERTAIN)
            r = np.where(valid, rel, np.inf)
            better = r < best_r
            if not better.any():
                continue
            best_r = np.where(better, r, best_r)
            best = np.where(better[:, None], h, best)
            best_err = np.where(better, err, best_err)
            best_angle = np.where(better, np.arcsin(sin), best_angle)
            best_via = np.where(better[:, None], [ks[a], ks[b]], best_via)
    ok = np.isfinite(best_r)
    return (np.where(ok[:, None], best, np.nan), np.where(ok, best_err, np.nan),
            np.where(ok, best_angle, np.nan), np.where(ok[:, None], best_via, -1))

