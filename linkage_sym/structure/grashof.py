"""Grashof class of four-bar loops.

A loop of four links joined by four revolute joints is a four-bar whatever
the rest of the mechanism is.  With ``s`` and ``l`` its shortest and longest
link and ``p``, ``q`` the other two (the link lengths being the distances
between each link's two joints of the loop), Grashof's criterion says: if
``s + l < p + q`` the shortest link turns fully relative to every other;
if ``s + l > p + q`` no link turns fully relative to another; ``s + l = p + q``
is the *change point*, where the loop can fold flat and change assembly mode.
With the fixed link of the loop (the ground, when the loop contains it) this
gives the classes named in the four-bar design chapter of the textbook
(*Design of four-bar mechanisms*, Sources [2] of the README):

* ``crank-rocker``: Grashof, the shortest link is next to the fixed one (it is
  the crank);
* ``double-crank``: Grashof, the shortest link is the fixed one;
* ``double-rocker``: Grashof with the shortest link opposite the fixed one
  (that coupler turns fully, both links on the frame rock);
* ``triple-rocker``: not Grashof (no link turns fully relative to another:
  the three moving links rock);
* ``change point``: ``s + l = p + q`` within :data:`CHANGE_POINT_TOL` of
  the perimeter.

A loop without the ground (no fixed link) is ``Grashof``, ``not Grashof`` or
``change point``.  These names are the values of :attr:`GrashofClass.name`,
of the design sweep's ``grashof`` columns and of ``linkage-sym structure``'s
report (:data:`CLASS_NAMES`).

NumPy-free and SymPy-free: plain arithmetic on the scene's assembly points.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import permutations

from linkage_sym.model import GROUND, Scene

CHANGE_POINT_TOL = 1e-9
"""``|s + l - (p + q)|`` up to this fraction of the perimeter is a change point:
a scene's coordinates rarely carry more digits than that."""

CLASS_NAMES = ("crank-rocker", "double-crank", "double-rocker", "triple-rocker", "change point")
"""The classes of a loop through the ground (its fixed link), in the order of the textbook."""
LOOSE_NAMES = ("Grashof", "not Grashof", "change point")
"""The classes of a loop without the ground (no fixed link)."""


@dataclass(frozen=True)
class GrashofClass:
    """The Grashof class of one four-bar.

    Attributes
    ----------
    name : str
        ``"crank-rocker"``, ``"double-crank"``, ``"double-rocker"`` (Grashof, the
        shortest link opposite the frame), ``"triple-rocker"`` (not Grashof) or
        ``"change point"`` (:data:`CLASS_NAMES`); for a loop without the ground (no
        fixed link) ``"Grashof"``, ``"not Grashof"`` or ``"change point"``
        (:data:`LOOSE_NAMES`).
    grashof : bool or None
        ``s + l < p + q`` (True), ``>`` (False), or None at the change point.
    shortest : int
        Index (into the lengths given) of the shortest link.
    margin : float
        ``(p + q) - (s + l)``: positive for a Grashof loop.
    detail : str
        One line: the inequality with its numbers and which link turns fully.
    """

    name: str
    grashof: bool | None
    shortest: int
    margin: float
    detail: str


def classify(lengths, fixed: int | None = 0, names=None) -> GrashofClass:
    """Grashof class of a four-bar with link ``lengths`` in loop order.

    Parameters
    ----------
    lengths : sequence of 4 float
        The links in the order they follow each other round the loop.
    fixed : int or None
        Index of the fixed link (the frame); None for a loop that does not
        contain the ground (the class then says only which link turns fully).
    names : sequence of 4 str, optional
        Link names for the detail line (default ``l0`` .. ``l3``).

    Returns
    -------
    GrashofClass

    Examples
    --------
    >>> classify([0.078, 0.024, 0.0602, 0.05], fixed=0, names=["ground", "crank", "coupler", "rocker"]).name
    'crank-rocker'
    >>> classify([1.0, 3.0, 3.5, 4.0], fixed=0).name   # shortest is the frame
    'double-crank'
    >>> classify([4.0, 3.0, 1.0, 3.5], fixed=0).name   # shortest opposite the frame
    'double-rocker'
    >>> print(classify([0.078, 0.05, 0.06, 0.05], fixed=0).detail)   # not Grashof
    not Grashof: s + l = 0.05 + 0.078 = 0.128 > p + q = 0.11; no link turns fully: the three moving links rock
    >>> c = classify([14.0, 7.0, 17.0, 10.0], fixed=0)  # 7 + 17 = 10 + 14
    >>> c.name, c.grashof
    ('change point', None)
    >>> print(classify([3.0, 2.0, 1.8, 1.0], fixed=None).detail)
    not Grashof: s + l = 1 + 3 = 4 > p + q = 3.8; no link turns fully (a triple-rocker whichever link is fixed)
    """
    ls = [float(x) for x in lengths]
    if len(ls) != 4:
        raise ValueError(f"four lengths expected, got {len(ls)}")
    names = list(names) if names is not None else [f"l{i}" for i in range(4)]
    order = sorted(range(4), key=lambda i: ls[i])
    i_s, i_l = order[0], order[-1]
    s, l = ls[i_s], ls[i_l]
    p, q = (ls[i] for i in order[1:3])
    margin = (p + q) - (s + l)
    perimeter = sum(ls)
    sums = f"s + l = {s:.6g} + {l:.6g} = {s + l:.6g}"
    other = f"p + q = {p + q:.6g}"
    if abs(margin) <= CHANGE_POINT_TOL * perimeter:
        return GrashofClass("change point", None, i_s, margin,
                            f"change point: {sums} = {other} (within {CHANGE_POINT_TOL:g} of the "
                            "perimeter): the loop can fold flat and change its assembly mode")
    if margin < 0:
        if fixed is None:
            return GrashofClass("not Grashof", False, i_s, margin,
                                f"not Grashof: {sums} > {other}; no link turns fully (a "
                                "triple-rocker whichever link is fixed)")
        return GrashofClass("triple-rocker", False, i_s, margin,
                            f"not Grashof: {sums} > {other}; no link turns fully: the three "
                            "moving links rock")
    turns = f"'{names[i_s]}' (shortest) turns fully"
    if fixed is None:
        return GrashofClass("Grashof", True, i_s, margin, f"Grashof: {sums} < {other}; {turns}")
    if i_s == fixed:
        name = "double-crank"
        why = f"{turns}: both links next to it are cranks"
    elif (i_s - fixed) % 4 == 2:
        name = "double-rocker"
        why = f"{turns}, opposite the frame: both links on the frame rock"
    else:
        name = "crank-rocker"
        why = f"{turns}, next to the frame: it is the crank"
    return GrashofClass(name, True, i_s, margin, f"Grashof: {sums} < {other}; {why}")


@dataclass(frozen=True)
class FourBarLoop:
    """A loop of four links and four revolute joints in a scene.

    ``joints[i]`` joins ``links[i]`` and ``links[i + 1]``, so ``links[i]`` runs from
    ``joints[i - 1]`` to ``joints[i]``; ``lengths[i]`` is the
    distance between them in the assembly configuration.  ``links[0]`` is the
    ground when the loop contains it.
    """

    links: tuple[str, str, str, str]
    joints: tuple[str, str, str, str]
    lengths: tuple[float, float, float, float]

    def grashof(self) -> GrashofClass:
        """The loop's :class:`GrashofClass` (the ground, if in the loop, is fixed)."""
        return classify(self.lengths, 0 if self.links[0] == GROUND else None, self.links)


def four_bar_loops(scene: Scene) -> list[FourBarLoop]:
    """Every loop of four distinct links joined by four revolute joints.

    Each loop is listed once, loops through the ground first (starting with
    it), the links in the order of the scene's ``links`` where there is a
    choice.  Loops with a link of zero length (two of its joints at one
    point: a pin shared by three links) are left out: they are not
    four-bars.

    Examples
    --------
    >>> import linkage_sym
    >>> loops = four_bar_loops(linkage_sym.load_example("crank_rocker"))
    >>> [(lp.links, lp.joints) for lp in loops]
    [(('ground', 'crank', 'coupler', 'rocker'), ('A', 'B', 'C', 'D'))]
    >>> loops[0].grashof().name
    'crank-rocker'
    """
    revolute = [j for j in scene.joints if j.type == "R"]
    at = {j.name: j.at for j in scene.joints}
    links = [GROUND, *scene.link_names]
    seen, out = set(), []
    for chain in permutations(links, 4):
        if GROUND in chain and chain[0] != GROUND:
            continue  # a loop through the ground starts with it
        for joints in _joint_choices(revolute, chain):
            key = frozenset(joints)
            if key in seen or len(key) != 4:
                continue
            lengths = tuple(math.dist(at[joints[i - 1]], at[joints[i]]) for i in range(4))
            seen.add(key)
            if min(lengths) > 0.0:
                out.append(FourBarLoop(chain, joints, lengths))
    return out


def _joint_choices(revolute, chain):
    """Tuples ``(j0, j1, j2, j3)``, ``j_i`` a revolute joint of ``chain[i]`` and ``chain[i + 1]``."""
    out = [()]
    for i in range(4):
        a, b = chain[i], chain[(i + 1) % 4]
        options = [j.name for j in revolute if set(j.links) == {a, b}]
        out = [(*prev, j) for prev in out for j in options]
    return out


def grashof_lines(scene: Scene) -> list[str]:
    """The lines ``linkage-sym structure`` prints about the scene's four-bar loops.

    Examples
    --------
    >>> import linkage_sym
    >>> for line in grashof_lines(linkage_sym.load_example("crank_rocker")):
    ...     print(line)
    Four-bar loops (Grashof class, textbook section 'Design of four-bar mechanisms' [2]):
      ground D-A 0.078, crank A-B 0.024, coupler B-C 0.06303, rocker C-D 0.04851 (m): crank-rocker
         Grashof: s + l = 0.024 + 0.078 = 0.102 < p + q = 0.111539; 'crank' (shortest) turns fully, next to the frame: it is the crank
    """
    loops = four_bar_loops(scene)
    if not loops:
        return []
    lines = ["Four-bar loops (Grashof class, textbook section 'Design of four-bar mechanisms' [2]):"]
    for lp in loops:
        g = lp.grashof()
        sides = ", ".join(f"{lp.links[i]} {lp.joints[i - 1]}-{lp.joints[i]} {lp.lengths[i]:.4g}"
                          for i in range(4))
        lines.append(f"  {sides} (m): {g.name}")
        lines.append(f"     {g.detail}")
    return lines
