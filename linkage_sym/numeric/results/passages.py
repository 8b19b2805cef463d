"""Where a joint passes through infinity between two steps of a sweep (NumPy only).

A dyad of two slides (``PRP``, ``RPP``) has its joint at the intersection of the slides'
lines.  When the slides become parallel between two solved path points the joint runs off
to infinity along them and comes back from the other end: the steps on both sides are
``ok`` (exact solutions), but nothing joins them -- a line drawn from one to the other
shows a motion the mechanism never makes.  Both runtimes find such a passage by their own
means and note it as a :class:`PassageNote` (the run's warning says it in words:
:func:`~linkage_sym.numeric.continuation.messages.parallel_note`); the run keeps it as an
:class:`InfinityPassage` in :attr:`Analysis.passages
<linkage_sym.numeric.results.result.Analysis>` (:func:`infinity_passages`), which the
plots read to break their lines there.

Which links the passage carries off (:func:`far_links`) is read from the structure, not
from the numbers: the dyad's links placed at the joint (both links of a ``PRP`` dyad; the
link of an ``RPP`` dyad that is not pinned to a known link), then every link of a group
solved later that is joined to one of them -- its position is computed from theirs, so it
has no continuous path across the passage either.  Every point fixed on those links (the
far joint, its coincident joints, traced points, centres of mass) has its path broken there.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, NamedTuple

import numpy as np

from linkage_sym.model import GROUND, Scene
from linkage_sym.structure.groups import Decomposition, decompose

__all__ = ["InfinityPassage", "PassageNote", "far_links", "infinity_passages", "notes_on_steps",
           "placed_from"]


class PassageNote(NamedTuple):
    """A runtime's note of a passage through infinity along its solving path.

    Attributes
    ----------
    point : int
        The first solved path point past the passage.
    text : callable
        ``text(step words)``: the run's warning, given where a step sees it (as every
        note of :func:`~linkage_sym.numeric.continuation.messages.step_warnings`).
    joint : str
        The dyad's joint at the intersection of its slides (the one at infinity).
    """

    point: int
    text: Callable[[str], str]
    joint: str


@dataclass(frozen=True)
class InfinityPassage:
    """A joint's passage through infinity between two steps of a run.

    Attributes
    ----------
    joint : str
        The joint at the intersection of a dyad's two slides.
    before, after : int or None, int
        The steps on either side: the passage lies between them (``before`` is ``None``
        when it lies between the assembly configuration and step 0).  As the run's warning
        says, ``after`` is the first step past it; a step between them that the dyad could
        not solve (its slides parallel there) is not ``ok``.
    links : tuple of str
        The links carried through infinity with the joint (:func:`far_links`), in the
        scene's order: no point fixed on them moves continuously from ``before`` to ``after``.
    """

    joint: str
    before: int | None
    after: int
    links: tuple[str, ...]


def placed_from(scene: Scene, links, decomposition: Decomposition | None = None) -> tuple:
    """``links`` and every link of a group solved after theirs that one of its joints (or a
    gear's carrier) ties to a link already in the set, in the order of
    :attr:`Scene.link_names`.

    Examples
    --------
    >>> import linkage_sym
    >>> scene = linkage_sym.load_scene({
    ...     "name": "four-bar", "links": [{"name": "crank"}, {"name": "coupler"},
    ...                                   {"name": "rocker"}],
    ...     "joints": [
    ...         {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0, 0]},
    ...         {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": [0, 0.1]},
    ...         {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": [0.3, 0.2]},
    ...         {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": [0.3, 0]}],
    ...     "drivers": [{"joint": "A", "toward": "B", "start_deg": 90, "stop_deg": 100,
    ...                  "steps": 3, "speed": 1.0}]})
    >>> placed_from(scene, ["crank"]), placed_from(scene, ["rocker"])
    (('crank', 'coupler', 'rocker'), ('rocker',))
    """
    dec = decomposition if decomposition is not None else decompose(scene)
    out = set(links)
    first = min((i for i, g in enumerate(dec.groups) if out & set(g.links)), default=None)
    if first is not None:
        for g in dec.groups[first + 1:]:
            ties = set()
            for name in g.joints:
                j = scene.joint(name)
                ties |= set(j.links) | ({j.carrier} if j.carrier else set())
            if (ties - set(g.links) - {GROUND}) & out:
                out |= set(g.links)
    return tuple(n for n in scene.link_names if n in out)


def far_links(scene: Scene, joint: str, decomposition: Decomposition | None = None) -> tuple:
    """The links a dyad of two slides carries through infinity with its joint ``joint``.

    The dyad's links that its joint places (those without an outer ``R`` joint to a known
    link: both of a ``PRP`` dyad, the second of an ``RPP`` dyad), then every link of a group
    solved after it that one of its joints (or a gear's carrier) ties to a link already in
    the set.

    Parameters
    ----------
    scene : Scene
    joint : str
        The inner joint of a ``PRP`` dyad, or the middle one of an ``RPP`` dyad.
    decomposition : Decomposition, optional
        The scene's, if already at hand.

    Returns
    -------
    tuple of str
        In the order of :attr:`Scene.link_names`.

    Examples
    --------
    A guide turning about the origin, a rod sliding through it, pinned at ``C`` to a block
    sliding on the line ``y = 0.05``: a ``PRP`` dyad (rod, block), which carries both off.

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
    >>> far_links(scene, "C")
    ('rod', 'block')
    """
    dec = decomposition if decomposition is not None else decompose(scene)
    dyad = next(g for g in dec.groups if g.kind == "dyad" and joint in g.joints)
    pinned = {link for name in dyad.external if scene.joint(name).type == "R"
              for link in scene.joint(name).links if link in dyad.links}
    return placed_from(scene, set(dyad.links) - pinned, dec)


def infinity_passages(notes, step_points, scene: Scene,
                      decomposition: Decomposition | None = None) -> tuple:
    """The run's passages through infinity, from its runtime's notes.

    Parameters
    ----------
    notes : sequence
        The runtime's notes of its solving path; the :class:`PassageNote` among them are read.
    step_points : array_like of int
        The path point of every step, increasing.
    scene : Scene
    decomposition : Decomposition, optional

    Returns
    -------
    tuple of InfinityPassage
        In the order of the notes; a passage past the last step (on no step's way) is left
        out, as its warning is.
    """
    out = []
    for note, k in notes_on_steps(notes, PassageNote, step_points):
        if decomposition is None:
            decomposition = decompose(scene)
        out.append(InfinityPassage(note.joint, k - 1 if k > 0 else None, k,
                                   far_links(scene, note.joint, decomposition)))
    return tuple(out)


def notes_on_steps(notes, kind: type, step_points):
    """Each of a runtime's ``notes`` of the type ``kind`` with the step on whose way from the
    step before it lies, ``(note, k)``: the first step at or after the note's path point
    (``0``: on the way from the assembly configuration); a note past the last step is left
    out, as its warning is.

    Examples
    --------
    >>> notes = [PassageNote(3, "a", "C"), "other", PassageNote(9, "b", "C")]
    >>> [(n.text, k) for n, k in notes_on_steps(notes, PassageNote, [0, 2, 4, 6])]
    [('a', 2)]
    """
    step_points = np.asarray(step_points)
    for note in notes:
        if isinstance(note, kind):
            k = int(np.searchsorted(step_points, note.point))
            if k < len(step_points):
                yield note, k
