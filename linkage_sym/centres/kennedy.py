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
underflows whatever the units of the scene.  The homogeneous points, the
three-centre lines and their intersections with their error estimates are
:mod:`linkage_sym.centres.kennedy_lines`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkage_sym.centres.kennedy_lines import (
    FAR,
    ROUNDING,
    intersect_best,
    relative,
    snap,
    to_global,
    unit,
)
from linkage_sym.model import GROUND

__all__ = ["FAR", "KennedyCentres", "kennedy_centres"]

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
    d = _CircleDiagram(scene, analysis)
    d.seed_joints()
    derived = d.rounds()
    d.refine(derived)
    d.settle_weakest(derived)
    return d.result()


class _CircleDiagram:
    """The circle diagram of :func:`kennedy_centres` as it is filled in: per pair of links
    ``(a, b)`` (symmetric, ground first) and step, the unit homogeneous centre ``H`` in the
    scaled frame, the finite ones ``PG`` in global coordinates, the error estimate ``E``, the
    angle ``ang`` of the lines met there, the two centres ``via`` that gave those lines, the
    weakest angle ``weak`` along the chain, whether the pair is ``known``, its ``source``, and
    the ``pinned`` pairs."""

    def __init__(self, scene, analysis):
        self.scene, self.analysis = scene, analysis
        self.names = names = (GROUND, *scene.link_names)
        self.n = n = len(names)
        self.idx = {name: i for i, name in enumerate(names)}
        self.N = N = len(analysis.status)
        pts = np.array([j.at for j in scene.joints], dtype=float)
        self.c = pts.mean(axis=0)
        self.L = scene.characteristic_length() or 1.0
        self.H = np.full((n, n, N, 3), np.nan)  # unit homogeneous centres, scaled frame, symmetric
        self.PG = np.full((n, n, N, 2), np.nan)  # the finite ones in global coordinates (m)
        self.E = np.full((n, n, N), np.nan)  # error estimate: scaled length (finite), rad (at infinity)
        self.known = np.zeros((n, n), dtype=bool)
        self.ang = np.full((n, n, N), np.nan)
        self.weak = np.full((n, n, N), np.nan)
        self.via = np.full((n, n, N, 2), -1, dtype=int)
        self.source: dict = {}
        self.pinned: set = set()
        self.steps = np.arange(N)

    def put(self, a, b, h, err, what, at=None):
        """Centre ``(a, b)`` known from a joint (``at``: its global position when finite)."""
        weak, H, PG, E, known = self.weak, self.H, self.PG, self.E, self.known
        weak[a, b] = weak[b, a] = np.where(np.all(np.isfinite(h), axis=-1), np.pi / 2, np.nan)
        H[a, b] = H[b, a] = h
        if at is not None:
            PG[a, b] = PG[b, a] = at
        E[a, b] = E[b, a] = err
        known[a, b] = known[b, a] = True
        self.source[min(a, b), max(a, b)] = what

    def finite(self, p):
        """A point's unit homogeneous coordinates (scaled frame) and their error."""
        c, L, N = self.c, self.L, self.N
        p = np.asarray(p, dtype=float)
        err = ROUNDING * (1.0 + np.linalg.norm(p, axis=-1) / L)
        return snap(np.concatenate([(p - c) / L, np.ones((N, 1))], axis=-1)), err

    def seed_joints(self):
        """The centres the joints give: pins first (a pin wins over a slide between the same
        links), gear meshes' pitch points, slides at infinity, shared pins, cam contacts."""
        scene, analysis, idx, known, N = self.scene, self.analysis, self.idx, self.known, self.N
        put, finite, pinned = self.put, self.finite, self.pinned
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
        self.seed_cams()

    def seed_cams(self):
        """A cam contact's centre: on the contact normal (Kennedy), met by a line of known
        centres."""
        scene, analysis, idx, known, N = self.scene, self.analysis, self.idx, self.known, self.N
        H, E, names, n, c, L = self.H, self.E, self.names, self.n, self.c, self.L
        for joint in scene.joints:  # a cam contact's centre: on the contact normal (Kennedy)
            if joint.type == "cam":
                a, b = idx[joint.links[0]], idx[joint.links[1]]
                N_ = np.asarray(analysis.joints[joint.name].normal, dtype=float).T  # recorded
                C = np.asarray(analysis.joints[joint.name].position, dtype=float)
                normal = np.cross(self.finite(C)[0], np.stack([N_[0], N_[1], np.zeros(N)], axis=-1))
                for k in range(n):
                    if k not in (a, b) and known[a, k] and known[b, k] and not known[a, b]:
                        other = np.cross(H[a, k], H[b, k])
                        h = snap(np.cross(other, normal))
                        sin = np.abs(unit(other)[..., 0] * unit(normal)[..., 1]
                                     - unit(other)[..., 1] * unit(normal)[..., 0])
                        err = (E[a, k] + E[b, k] + ROUNDING) / np.maximum(sin, 1e-300)
                        self.put(a, b, h, err, f"contact normal of cam {joint.name} and line "
                                 f"P{names[a]},{names[k]}-P{names[b]},{names[k]}", to_global(h, c, L))

    def chain(self, i, j, a, v):
        """Weakest angle of centre ``ij`` met at angle ``a`` by the lines via ``v`` (N, 2).

        A centre at infinity has the lines' direction, known as well as the lines
        are, however small ``a``: its own angle does not count.
        """
        H, weak, steps = self.H, self.weak, self.steps
        out = np.where(H[i, j, :, 2] == 0.0, np.pi / 2, a)
        for col in (0, 1):
            k = np.maximum(v[:, col], 0)
            for end in (i, j):
                w = weak[end, k, steps]
                out = np.where(v[:, col] >= 0, np.fmin(out, w), out)
        return out

    def lines_through(self, i, j):
        """The links ``k`` whose centres with ``i`` and with ``j`` are both known."""
        known = self.known
        return [k for k in range(self.n) if k not in (i, j) and known[i, k] and known[k, j]]

    def rounds(self) -> list:
        """Rounds of the circle diagram, each closing every pair two known lines meet on;
        the pairs derived, in order."""
        H, PG, E, ang, via, weak, known = self.H, self.PG, self.E, self.ang, self.via, self.weak, self.known
        n, c, L = self.n, self.c, self.L
        derived = []
        while True:  # rounds of the circle diagram
            found = [(i, j, self.lines_through(i, j)) for i in range(n) for j in range(i + 1, n)
                     if not known[i, j]]
            found = [f for f in found if len(f[2]) >= 2]
            if not found:
                break
            for i, j, ks in found:
                h, err, a, v = intersect_best(H, PG, E, i, j, ks, c, L)
                H[i, j] = H[j, i] = h
                PG[i, j] = PG[j, i] = to_global(h, c, L)
                E[i, j] = E[j, i] = err
                ang[i, j] = ang[j, i] = a
                via[i, j] = via[j, i] = v
                weak[i, j] = weak[j, i] = self.chain(i, j, a, v)
            for i, j, _ in found:
                known[i, j] = known[j, i] = True
                self.source[i, j] = "three-centre lines"
                derived.append((i, j))
        return derived

    def refine(self, derived):
        """Centres found in later rounds give more lines through the earlier ones (in the
        shaper the first two lines through P(crank, ram) are one line at every step):
        intersect again with every line there is, and keep, step by step, the intersection
        with the smaller error."""
        H, PG, E, ang, via = self.H, self.PG, self.E, self.ang, self.via
        n, c, L = self.n, self.c, self.L
        for _ in range(n):
            improved = False
            for i, j in derived:
                h, err, a, v = intersect_best(H, PG, E, i, j, self.lines_through(i, j), c, L)
                better = np.isfinite(err) & ~(relative(h, err) >= relative(H[i, j], E[i, j]))
                better &= ~np.isclose(err, E[i, j], rtol=1e-3, atol=0.0)  # no churn on ties
                if better.any():
                    improved = True
                    H[i, j] = H[j, i] = np.where(better[:, None], h, H[i, j])
                    PG[i, j] = PG[j, i] = np.where(better[:, None], to_global(h, c, L), PG[i, j])
                    E[i, j] = E[j, i] = np.where(better, err, E[i, j])
                    ang[i, j] = ang[j, i] = np.where(better, a, ang[i, j])
                    via[i, j] = via[j, i] = np.where(better[:, None], v, via[i, j])
            if not improved:
                break

    def settle_weakest(self, derived):
        """The weakest angles along the final chains (they may be circular)."""
        weak, ang, via = self.weak, self.ang, self.via
        for _ in range(self.n):
            before = weak.copy()
            for i, j in derived:
                weak[i, j] = weak[j, i] = self.chain(i, j, ang[i, j], via[i, j])
            if np.array_equal(before, weak, equal_nan=True):
                break

    def result(self) -> KennedyCentres:
        """Every pair's centre, as :class:`KennedyCentres` (ground first, pairs in order)."""
        names, n, H, PG = self.names, self.n, self.H, self.PG
        ang, via, weak, source, pinned = self.ang, self.via, self.weak, self.source, self.pinned
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
