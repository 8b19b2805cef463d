"""Decomposition of a mechanism into driven links and Assur groups.

A mechanism is solved group by group: each group is a minimal set of
still-unknown links whose constraint equations (2 per joint, 1 per driver),
written against links already known, are exactly as many as its unknowns
(3 per link).  Searching subsets by increasing size finds, in order, the
driven input links (1 link, a joint and a driver), the dyads (2 links,
3 joints), the class-III triads (4 links, 6 joints) and any larger or driven
group, without a catalogue of shapes.

A gear mesh (``G`` joint, an extension of the format) is a higher pair: one
equation, linking the angles of its two gears and their carrier.  Groups
containing meshes close by the same count (``3 n = 2 p + h`` for ``n``
links, ``p`` lower pairs and ``h`` higher pairs: meshes and cam contacts): a gear turning on a pivot of a
known carrier and meshing with a known gear is a one-link group (kind
``"gear"``), a planet with its carrier driven through the sun a two-link one.

A subset with *more* equations than unknowns is an over-constrained
sub-chain; a mechanism for which no subset closes is under-determined
somewhere even if its overall mobility matches its drivers.  Both are
reported as :class:`~linkage_sym.errors.SceneError`.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

from linkage_sym.errors import SceneError
from linkage_sym.model import GROUND, Scene

MAX_GROUP_SIZE = 8
"""Largest group searched for; larger Assur groups are refused."""

DYAD_TYPES = ("RRR", "RRP", "RPR", "PRP", "RPP")


@dataclass(frozen=True)
class Group:
    """One step of the solving order.

    Attributes
    ----------
    links : tuple of str
        The links this group determines (for a dyad of type ``XYZ``, ordered
        so that ``links[0]`` carries the first external joint).
    joints : tuple of str
        Every joint whose equations belong to the group.
    external : tuple of str
        Joints connecting the group to links solved before it (for a dyad:
        first and last letter of its type, in that order).
    internal : tuple of str
        Joints between two links of the group.
    drivers : tuple of str
        Names of the driven joints whose driver equation belongs to the group.
    kind : str
        ``"input"`` (one link set by a driver), ``"dyad"``, ``"triad"``
        (class-III group of a ternary link and three binary links),
        ``"driven"`` (a group containing a relative driver, e.g. an actuator),
        ``"gear"`` (a group containing a gear mesh: one gear on its pivot, or
        several links, e.g. a planet and its carrier), ``"cam"`` (a follower
        on its pivot or slide touching a known cam) or ``"group"`` (any
        other Assur group, solved by Newton).
    assur_class : int or None
        2 for dyads, 3 for triads, the size of the largest closed contour of
        internal joints for larger groups; ``None`` for input links.
    dyad_type : str or None
        ``RRR``, ``RRP``, ``RPR``, ``PRP`` or ``RPP`` for a dyad.
    """

    links: tuple[str, ...]
    joints: tuple[str, ...]
    external: tuple[str, ...]
    internal: tuple[str, ...]
    drivers: tuple[str, ...]
    kind: str
    assur_class: int | None = None
    dyad_type: str | None = None

    @property
    def label(self) -> str:
        """Short human-readable name, e.g. ``"dyad RRP"``, ``"triad (class III)"``, ``"group (class IV)"``."""
        if self.kind == "dyad":
            return f"dyad {self.dyad_type}"
        if self.kind == "triad":
            return "triad (class III)"
        if self.kind == "input":
            return "input link"
        if self.kind == "driven":
            return "driven group"
        if self.kind == "gear":
            return "gear" if len(self.links) == 1 else "gear group"
        if self.kind == "cam":
            return "cam follower" if len(self.links) == 1 else "cam group"
        roman = {4: "IV", 5: "V", 6: "VI", 7: "VII", 8: "VIII"}
        return f"group (class {roman.get(self.assur_class, self.assur_class)})"


@dataclass(frozen=True)
class Decomposition:
    """Drivers and Assur groups of a scene, in solving order."""

    groups: tuple[Group, ...]
    mobility: int

    def group_of(self, link: str) -> Group:
        """The group that determines ``link``."""
        for g in self.groups:
            if link in g.links:
                return g
        raise KeyError(link)


@dataclass(frozen=True)
class Constraint:
    """One constraint of the structure: a joint (2 equations), a driver or a gear mesh (1),
    as :func:`search_groups` takes them (also for the disconnection's virtual mechanism,
    :mod:`linkage_sym.structure.disconnection`).

    A mesh's ``links`` are its two gears and its carrier.
    """

    name: str
    is_driver: bool
    links: tuple[str, ...]
    is_mesh: bool = False

    @property
    def equations(self) -> int:
        return 1 if self.is_driver or self.is_mesh else 2


def _items(scene: Scene, drivers=None) -> list[Constraint]:
    items = [
        Constraint(j.name, False, (*j.links, j.carrier), True) if j.type == "G"
        else Constraint(j.name, False, j.links, True) if j.type == "cam"
        else Constraint(j.name, False, j.links)
        for j in scene.joints
    ]
    for d in scene.drivers if drivers is None else drivers:
        items.append(Constraint(d, True, scene.joint(d).links))
    return items


def mobility(scene: Scene) -> int:
    """Grübler–Kutzbach mobility ``3 (n - 1) - 2 j - h`` of a planar linkage.

    ``j`` lower pairs (R, P) and ``h`` higher pairs (gear meshes, cam contacts).

    Examples
    --------
    >>> from linkage_sym.model import Scene, Link, Joint, Driver
    >>> j = [Joint("A", "R", ("ground", "c"), (0, 0)), Joint("B", "R", ("c", "k"), (1, 0)),
    ...      Joint("C", "R", ("k", "r"), (2, 1)), Joint("D", "R", ("r", "ground"), (3, 0))]
    >>> mobility(Scene("4bar", (Link("c"), Link("k"), Link("r")), tuple(j), ()))
    1
    """
    h = sum(j.type in ("G", "cam") for j in scene.joints)
    return 3 * len(scene.links) - 2 * (len(scene.joints) - h) - h


def search_groups(scene: Scene, items: list[Constraint], known: set[str], order: list[str]):
    """Generator of (links, items) groups in solving order; raises on failure.

    On failure (a sub-chain with more equations than unknowns, or none that
    closes) the :class:`SceneError` names every over-constrained and every
    under-constrained part of the links still unknown (see :func:`_parts`).
    """
    remaining = [n for n in order if n not in known]
    pending = list(items)
    while remaining:
        found = over = None
        for size in range(1, min(len(remaining), MAX_GROUP_SIZE) + 1):
            for subset in combinations(remaining, size):
                s = set(subset)
                mine = [
                    it
                    for it in pending
                    if set(it.links) <= s | known and set(it.links) & s
                ]
                neq = sum(it.equations for it in mine)
                if neq > 3 * size:
                    over = subset
                    break
                if neq == 3 * size:
                    found = (subset, mine)
                    break
            if found or over:
                break
        if found is None:
            raise SceneError(_refusal(remaining, pending, known, over))
        subset, mine = found
        yield subset, mine
        known |= set(subset)
        remaining = [n for n in remaining if n not in known]
        pending = [it for it in pending if it not in mine]


def _refusal(remaining: list[str], pending: list[Constraint], known: set[str], over) -> list[str]:
    """The problems of links ``remaining`` that no group determines.

    ``over`` is the over-constrained sub-chain the search met, if any.  Both
    kinds of part are named: when Gruebler's count matches, a part with too
    many equations goes with another with too few.
    """
    over_links, under_links = _parts(remaining, pending)
    if not over_links and over is not None:
        over_links = list(over)

    def count(links, touching):
        s = set(links)
        mine = [
            it for it in pending
            if set(it.links) & s and (touching or set(it.links) <= s | known)
        ]
        return sum(it.equations for it in mine), 3 * len(links)

    problems = []
    if over_links:
        neq, unknowns = count(over_links, touching=False)
        problems.append(
            f"structure: {_links(over_links)} over-constrained "
            f"({neq} constraint equations for {unknowns} unknowns)"
        )
    if under_links:
        neq, unknowns = count(under_links, touching=True)
        both = (
            " (the mechanism is over-constrained in one part and under-constrained in another, "
            "which the Gruebler-Kutzbach count cannot see)"
            if over_links
            else ""
        )
        problems.append(
            f"structure: {_links(under_links)} under-constrained "
            f"({neq} constraint equations for {unknowns} unknowns): the drivers do not "
            f"determine their positions{both}"
        )
    if not problems:  # no part stands out: a group larger than the search
        problems.append(
            "structure: links "
            + ", ".join(remaining)
            + " cannot be determined from the drivers (no sub-chain of up to "
            f"{MAX_GROUP_SIZE} links closes)"
        )
    return problems


def _links(names: list[str]) -> str:
    """``link a is`` or ``links a, b are``, for messages."""
    return f"link {names[0]} is" if len(names) == 1 else f"links {', '.join(names)} are"


def _parts(remaining: list[str], pending: list[Constraint]) -> tuple[list[str], list[str]]:
    """Links of the over- and of the under-constrained part among ``remaining``.

    The coarse Dulmage-Mendelsohn decomposition of the structural incidence of
    the pending equations (2 per joint, 1 per driver) on the unknowns (3 per
    link, each equation involving every unknown of its links): with a maximum
    matching of equations to unknowns, the over-constrained part is what
    alternating paths reach from the unmatched equations, the under-constrained
    part what they reach from the unmatched unknowns.  Both are independent of
    the matching chosen.
    """
    cols = [(n, k) for n in remaining for k in range(3)]
    col_of = {c: i for i, c in enumerate(cols)}
    rows: list[list[int]] = []
    for it in pending:
        adj = [col_of[n, k] for n in it.links if n in remaining for k in range(3)]
        if adj:
            rows.extend([adj] * it.equations)
    row_adj: list[list[int]] = [[] for _ in cols]  # rows of each column
    for r, adj in enumerate(rows):
        for c in adj:
            row_adj[c].append(r)
    match_col: list[int | None] = [None] * len(cols)  # the row matched to each column
    match_row: list[int | None] = [None] * len(rows)

    def augment(r, seen):
        for c in rows[r]:
            if c not in seen:
                seen.add(c)
                if match_col[c] is None or augment(match_col[c], seen):
                    match_col[c], match_row[r] = r, c
                    return True
        return False

    for r in range(len(rows)):
        augment(r, set())
    over_cols: set[int] = set()
    stack = [r for r in range(len(rows)) if match_row[r] is None]
    seen_rows = set(stack)
    while stack:
        for c in rows[stack.pop()]:
            if c not in over_cols:
                over_cols.add(c)
                r = match_col[c]
                if r is not None and r not in seen_rows:
                    seen_rows.add(r)
                    stack.append(r)
    under_cols = {c for c in range(len(cols)) if match_col[c] is None}
    stack = list(under_cols)
    while stack:
        for r in row_adj[stack.pop()]:
            c = match_row[r]
            if c is not None and c not in under_cols:
                under_cols.add(c)
                stack.append(c)

    def links(found):
        names = {cols[c][0] for c in found}
        return [n for n in remaining if n in names]

    return links(over_cols), links(under_cols)


def classify_group(scene: Scene, links: tuple[str, ...], mine: list[Constraint]) -> Group:
    """The :class:`Group` of ``links`` solved by the constraints ``mine`` (a group found by
    :func:`search_groups`): its kind (input, dyad, triad, gear, cam ...), class and
    internal and external joints."""
    s = set(links)
    joints = [it for it in mine if not it.is_driver]
    drivers = tuple(it.name for it in mine if it.is_driver)
    internal = [j for j in joints if set(j.links) <= s]
    external = [j for j in joints if not set(j.links) <= s]
    jtype = {j.name: j.type for j in scene.joints}
    if drivers and len(links) == 1:
        kind, cls, dtype = "input", None, None
    elif any(jtype[j.name] == "G" for j in joints):
        kind, cls, dtype = "gear", None, None
    elif any(jtype[j.name] == "cam" for j in joints):
        kind, cls, dtype = "cam", None, None
    elif drivers:
        kind, cls, dtype = "driven", None, None
    elif len(links) == 2 and len(external) == 2 and len(internal) == 1:
        # order the links so that the type reads ext0-int-ext1 canonically
        b0, b1 = links
        e0 = next(j for j in external if b0 in j.links)
        e1 = next(j for j in external if b1 in j.links)
        t = jtype[e0.name] + jtype[internal[0].name] + jtype[e1.name]
        if t not in DYAD_TYPES:
            b0, b1, e0, e1, t = b1, b0, e1, e0, t[::-1]
        if t not in DYAD_TYPES:
            raise SceneError(
                [f"structure: dyad {b0}, {b1} of type {t} has no unique position"]
            )
        return Group(
            links=(b0, b1),
            joints=(e0.name, internal[0].name, e1.name),
            external=(e0.name, e1.name),
            internal=(internal[0].name,),
            drivers=(),
            kind="dyad",
            assur_class=2,
            dyad_type=t,
        )
    else:
        cls = _assur_class(links, internal)
        deg = {n: sum(n in j.links for j in internal) for n in links}
        if len(links) == 4 and cls == 3 and sorted(deg.values()) == [1, 1, 1, 3]:
            kind = "triad"
        else:
            kind = "group"
        dtype = None
    return Group(
        links=tuple(links),
        joints=tuple(j.name for j in joints),
        external=tuple(j.name for j in external),
        internal=tuple(j.name for j in internal),
        drivers=drivers,
        kind=kind,
        assur_class=cls,
        dyad_type=dtype,
    )


def _assur_class(links, internal) -> int:
    """Largest closed contour of internal joints (a ternary link counts as 3)."""
    deg = {n: 0 for n in links}
    adj: dict[str, list[str]] = {n: [] for n in links}
    for j in internal:
        a, b = j.links
        deg[a] += 1
        deg[b] += 1
        adj[a].append(b)
        adj[b].append(a)
    best = max(deg.values())
    # longest simple cycle in the link graph (groups are small: brute force)
    def walk(start, node, seen):
        nonlocal best
        for nxt in adj[node]:
            if nxt == start and len(seen) >= 3:
                best = max(best, len(seen))
            elif nxt not in seen:
                walk(start, nxt, seen | {nxt})

    for n in links:
        walk(n, n, {n})
    return max(best, 2)


def decompose(scene: Scene) -> Decomposition:
    """Split a scene into input links and Assur groups, in solving order.

    Raises
    ------
    SceneError
        If a sub-chain is over-constrained or the mechanism cannot be solved
        group by group from its drivers.

    Examples
    --------
    >>> from linkage_sym.model import Scene, Link, Joint, Driver
    >>> j = (Joint("A", "R", ("ground", "crank"), (0, 0)),
    ...      Joint("B", "R", ("crank", "coupler"), (1, 0)),
    ...      Joint("C", "R", ("coupler", "rocker"), (2, 1)),
    ...      Joint("D", "R", ("rocker", "ground"), (3, 0)))
    >>> d = (Driver("A", "R", 0.0, 6.28, 10, 1.0, toward="B"),)
    >>> dec = decompose(Scene("4bar", (Link("crank"), Link("coupler"), Link("rocker")), j, d))
    >>> [(g.label, g.links) for g in dec.groups]
    [('input link', ('crank',)), ('dyad RRR', ('coupler', 'rocker'))]
    """
    order = list(scene.link_names)
    items = _items(scene, [d.joint for d in scene.drivers])
    groups = tuple(
        classify_group(scene, links, mine)
        for links, mine in search_groups(scene, items, {GROUND}, order)
    )
    return Decomposition(groups=groups, mobility=mobility(scene))
