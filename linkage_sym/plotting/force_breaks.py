"""Where a force curve must not join two steps: a passage through infinity upstream of it.

A joint carried through infinity between two steps (:attr:`Analysis.passages
<linkage_sym.numeric.results.result.Analysis>`) moves unboundedly fast near the passage: the
velocity ratio of the links carried off to the driver is unbounded there, and so are the
loads they need (by virtual work, the driving effort times the driver's rate equals the
power of the loads on those links).  Across the passage the forces jump from one large value
to another of the other sign: a line joining the two steps would draw a force that no
position of the mechanism has.

Which force curves that breaks is read from the structure, as the links carried off are
(:func:`~linkage_sym.numeric.results.passages.far_links`): the kinetostatics solves the
groups in reverse solving order, each group's reactions from its own loads and those the
groups solved after it put on it through their outer joints.  So the loads of the links
carried off reach every group they are joined to through an outer joint, and back from
there to the driver and the ground (:func:`loaded_links`).  The reaction of a joint held by
a group of those links breaks (:func:`reaction_gaps`), the driving effort of a driver of one
(:func:`effort_gaps`) and the frame's force and moment when a joint to the ground breaks
(:func:`frame_gaps`).  A group whose links none of them is joined to (a branch of its own)
keeps its curves, the joints it pins to a loaded link included.
"""

from __future__ import annotations

from linkage_sym.model import GROUND
from linkage_sym.plotting.breaks import breaks_of
from linkage_sym.structure.groups import decompose

__all__ = ["effort_gaps", "frame_gaps", "loaded_links", "reaction_gaps"]


def loaded_links(scene, links, decomposition=None) -> frozenset:
    """The links whose loads (their reactions' share) include those of ``links``: ``links``,
    and every link of a group solved before one of theirs that an outer joint (or a gear's
    carrier) of that group ties it to, transitively (the ground left out).

    Parameters
    ----------
    scene : Scene
    links : iterable of str
        The links carried through infinity.
    decomposition : Decomposition, optional

    Returns
    -------
    frozenset of str

    Examples
    --------
    The guide-slider of :func:`~linkage_sym.numeric.results.passages.far_links`: the rod
    slides through the guide, whose reactions therefore carry the rod's loads.

    >>> import linkage_sym
    >>> scene = linkage_sym.load_scene({
    ...     "name": "guide-slider",
    ...     "links": [{"name": "guide"}, {"name": "rod"}, {"name": "block"}],
    ...     "joints": [
    ...         {"name": "A", "type": "R", "links": ["ground", "guide"], "at": [0, 0]},
    ...         {"name": "A_slide", "type": "P", "links": ["rod", "guide"], "at": [0.02, 0.02],
    ...          "axis_deg": 45},
    ...         {"name": "C", "type": "R", "links": ["rod", "block"], "at": [0.05, 0.05]},
    ...         {"name": "C_guide", "type": "P", "links": ["ground", "block"],
    ...          "at": [0.05, 0.05], "axis_deg": 0}],
    ...     "drivers": [{"joint": "A", "toward": "A_slide", "start_deg": 45, "stop_deg": -45,
    ...                  "steps": 10, "speed": 1.0}]})
    >>> sorted(loaded_links(scene, ["rod", "block"]))
    ['block', 'guide', 'rod']
    """
    dec = decomposition if decomposition is not None else decompose(scene)
    out = set(links) - {GROUND}
    for g in reversed(dec.groups):
        if not out & set(g.links):
            continue
        out |= set(g.links)
        for name in g.external:
            j = scene.joint(name)
            out |= (set(j.links) | ({j.carrier} if j.carrier else set())) - {GROUND}
    return frozenset(out)


def _owner(dec, joint: str):
    """The group whose equations hold ``joint`` (its reaction is solved with that group's
    balance), ``None`` when no group does."""
    return next((g for g in dec.groups if joint in g.joints or joint in g.drivers), None)


def _gaps(analysis, scene, joints) -> tuple:
    """The steps before each passage or Newton group's jump (step 0 on) whose links' loads
    reach the group of one of ``joints`` (a joint of no group: every one), as
    :class:`~linkage_sym.plotting.breaks.Gap`."""
    records = (*analysis.passages, *getattr(analysis, "jumps", ()))
    if not any(r.before is not None for r in records):
        return ()
    dec = decompose(scene)
    owners = [_owner(dec, j) for j in joints]

    def touches(links):
        loaded = loaded_links(scene, links, dec)
        return any(g is None or loaded & set(g.links) for g in owners)

    return breaks_of(analysis, touches)


def reaction_gaps(analysis, scene, joint: str) -> tuple:
    """The steps after which the reaction of ``joint`` breaks: a passage carries off links
    whose loads reach the group that holds it (:func:`loaded_links`)."""
    return _gaps(analysis, scene, [joint])


def effort_gaps(analysis, scene, joint: str) -> tuple:
    """The steps after which the driving effort of the driven ``joint`` breaks."""
    return _gaps(analysis, scene, [joint])


def frame_gaps(analysis, scene) -> tuple:
    """The steps after which the frame force and moment break: a passage whose loads reach
    a joint to the ground."""
    return _gaps(analysis, scene, [j.name for j in scene.joints if GROUND in j.links])
