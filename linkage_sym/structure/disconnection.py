"""Disconnection choices for class-III (and higher) Assur groups (Dang and Zhang,
"A simplified method for the force analysis of complex planar multi-bar mechanisms").

Dang Zuqi and Zhang Qixian turn a complex group into a *virtual pure-dyad
mechanism*: remove one binary link (one degree of freedom gained) or one
joint (two gained), declare as many links that touch a known link to be
*hypothetical input links*, and the rest of the group must then fall apart
into dyads.  This module lists every such choice for a group; the force
solver (kinetostatics) uses one of them, and all must give the same
reactions.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

from linkage_sym.errors import SceneError
from linkage_sym.model import GROUND, Scene
from linkage_sym.structure.groups import Constraint, Group, classify_group, search_groups


@dataclass(frozen=True)
class Disconnection:
    """One way of turning a complex group into a pure-dyad mechanism.

    Attributes
    ----------
    removed_links : tuple of str
        Binary links taken out (their joints are cut).
    removed_joints : tuple of str
        Joints cut (those of the removed links, or the one joint removed).
    inputs : tuple of (str, str)
        Hypothetical input links and the joint (to a known link) about which
        each turns, or along which it slides.
    dyads : tuple of Group
        The dyads of the virtual mechanism, in solving order.
    sliding : tuple of bool
        For each input, whether it slides (its joint is prismatic): the
        unknown is then found from a force balance along the guide
        (Dang and Zhang eqs. 8-9) instead of a moment balance (eqs. 4-6).
    """

    removed_links: tuple[str, ...]
    removed_joints: tuple[str, ...]
    inputs: tuple[tuple[str, str], ...]
    dyads: tuple[Group, ...]
    sliding: tuple[bool, ...]

    @property
    def unknowns(self) -> int:
        """Number of unknown reaction components (``X`` or ``X1, X2``)."""
        return len(self.inputs)

    def describe(self) -> str:
        """One line, e.g. ``remove link 'b3' (joints F, G); input 'b1' turning about A -> dyad RRR (t, b2)``."""
        if self.removed_links:
            what = ", ".join(f"link '{n}'" for n in self.removed_links)
            what += f" (joints {', '.join(self.removed_joints)})"
        else:
            what = f"joint {', '.join(self.removed_joints)}"
        ins = "; ".join(
            f"input '{link}' {'sliding along' if s else 'turning about'} {joint}"
            for (link, joint), s in zip(self.inputs, self.sliding)
        )
        chain = " -> ".join(f"{g.label} ({', '.join(g.links)})" for g in self.dyads)
        return f"remove {what}; {ins}" + (f" -> {chain}" if chain else " (no dyad left)")


def _binary_links(group: Group, joint_links: dict[str, tuple[str, str]]) -> list[str]:
    return [
        n for n in group.links if sum(n in joint_links[j] for j in group.joints) == 2
    ]


def disconnections(scene: Scene, group: Group) -> list[Disconnection]:
    """Every disconnection of ``group`` that leaves a pure-dyad mechanism.

    Removing one binary link or one internal joint is tried first; pairs of
    binary links only when neither works (Dang and Zhang, Fig. 2).

    Examples
    --------
    For a triad, each of the three binary links can be removed, and each of
    the two others then drives a dyad: six choices; cutting one of the three
    internal joints adds three more.
    """
    if group.kind in ("input", "dyad"):
        return []
    jl = {j.name: j.links for j in scene.joints}
    jtype = {j.name: j.type for j in scene.joints}
    inside = set(group.links)
    known = (set(scene.link_names) - inside) | {GROUND}
    binaries = _binary_links(group, jl)

    def attempts():
        for b in binaries:
            yield (b,), tuple(j for j in group.joints if b in jl[j])
        for j in group.internal:
            yield (), (j,)

    found = list(_choices(scene, group, jl, jtype, known, attempts()))
    if not found:
        pairs = (
            ((a, b), tuple(j for j in group.joints if a in jl[j] or b in jl[j]))
            for a, b in combinations(binaries, 2)
        )
        found = list(_choices(scene, group, jl, jtype, known, pairs))
    return found


def _choices(scene, group, jl, jtype, known, attempts):
    for removed_links, cut in attempts:
        links = [n for n in group.links if n not in removed_links]
        joints = [j for j in group.joints if j not in cut]
        dof = 3 * len(links) - 2 * len(joints)
        if dof < 1:
            continue
        # candidate hypothetical inputs: a remaining link with a joint to a known link
        ext = {
            n: [j for j in joints if n in jl[j] and set(jl[j]) - {n} <= known]
            for n in links
        }
        cands = [(n, j) for n in links for j in ext[n]]
        for chosen in combinations(cands, dof):
            if len({n for n, _ in chosen}) < dof:
                continue
            items = [Constraint(j, False, jl[j]) for j in joints]
            items += [Constraint(j, True, jl[j]) for _, j in chosen]
            try:
                groups = [
                    classify_group(scene, ls, mine)
                    for ls, mine in search_groups(scene, items, set(known), links)
                ]
            except SceneError:
                continue
            dyads = [g for g in groups if g.kind == "dyad"]
            inputs = [g for g in groups if g.kind == "input"]
            if len(dyads) + len(inputs) != len(groups) or len(inputs) != dof:
                continue
            yield Disconnection(
                removed_links=tuple(removed_links),
                removed_joints=tuple(cut),
                inputs=tuple(chosen),
                dyads=tuple(dyads),
                sliding=tuple(jtype[j] == "P" for _, j in chosen),
            )


def usable_disconnections(scene: Scene, group: Group) -> list[Disconnection]:
    """The disconnections of ``group`` the force solver can use.

    A driven joint inside the group must be cut (its effort is then one of
    the cut joint's unknowns, as Dang and Zhang do with an actuator).
    """
    out = []
    for d in disconnections(scene, group):
        if all(j in d.removed_joints for j in group.drivers):
            out.append(d)
    return out


def default_choice(choices: list[Disconnection]) -> int:
    """Index of the disconnection used by default.

    Fewest unknowns first (one run less), then hypothetical inputs that
    turn rather than slide (Dang and Zhang advise binary, turning inputs), then
    the structure's listing order.
    """
    keys = [(d.unknowns, sum(d.sliding), i) for i, d in enumerate(choices)]
    return min(keys)[2]
