"""Where a Newton group jumps to another configuration of its assembly mode (NumPy only).

A group solved by Newton's method (a class-III triad, a driven group, any group without a
closed form) follows its assembly configuration by continuation
(:mod:`linkage_sym.numeric.continuation`).  Where the continuation reaches a limit or
singular position and a configuration of the same determinant sign exists past it, or where
the group is assembled again after steps that could not be, the group goes on in the
configuration nearest to the last solved one: the steps on both sides may be ``ok``, but the
group's links do not move continuously from one to the other -- a line drawn between them
shows a motion the mechanism never makes.  Both runtimes note such a jump as a
:class:`JumpNote` (the run's warning says it in words:
:func:`~linkage_sym.numeric.continuation.messages.note_message`); the run keeps it as an
:class:`AssemblyJump` in :attr:`Analysis.jumps
<linkage_sym.numeric.results.result.Analysis>` (:func:`assembly_jumps`), which the plots
read to break their lines there, as they do at a passage through infinity
(:mod:`linkage_sym.numeric.results.passages`).

The links that jump (:func:`~linkage_sym.numeric.results.passages.placed_from`) are the
group's, then every link of a group solved later that one of its joints (or a gear's carrier)
ties to a link already in the set: its position is computed from theirs.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, NamedTuple

from linkage_sym.model import Scene
from linkage_sym.numeric.results.passages import notes_on_steps, placed_from
from linkage_sym.structure.groups import Decomposition, decompose

__all__ = ["AssemblyJump", "JumpNote", "assembly_jumps"]


class JumpNote(NamedTuple):
    """A runtime's note of a Newton group's jump along its solving path.

    Attributes
    ----------
    point : int
        The path point reached by the jump.
    text : callable
        ``text(step words)``: the run's warning, given where a step sees it.
    group : str
        The group's label (e.g. ``"triad (class III)"``).
    links : tuple of str
        The group's links.
    limit : bool
        True when the group passed a limit or singular position, False when it is assembled
        again after path points that could not be.
    """

    point: int
    text: Callable[[str], str]
    group: str
    links: tuple
    limit: bool


@dataclass(frozen=True)
class AssemblyJump:
    """A Newton group's jump to another configuration of its assembly mode between two steps.

    Attributes
    ----------
    group : str
        The group's label, and its links in brackets, as its warning names it.
    before, after : int or None, int
        The steps on either side (``before`` is ``None`` when the jump lies between the
        assembly configuration and step 0); ``after`` is the step whose warning says it.
    links : tuple of str
        The links that jump (:func:`~linkage_sym.numeric.results.passages.placed_from`), in
        the scene's order: no point fixed on them moves continuously from ``before`` to
        ``after``.
    limit : bool
        True after a limit or singular position, False on re-entry after steps that could
        not be assembled.
    """

    group: str
    before: int | None
    after: int
    links: tuple[str, ...]
    limit: bool


def assembly_jumps(notes, step_points, scene: Scene,
                   decomposition: Decomposition | None = None) -> tuple:
    """The run's assembly-mode jumps of Newton groups, from its runtime's notes.

    Parameters
    ----------
    notes : sequence
        The runtime's notes of its solving path; the :class:`JumpNote` among them are read.
    step_points : array_like of int
        The path point of every step, increasing.
    scene : Scene
    decomposition : Decomposition, optional

    Returns
    -------
    tuple of AssemblyJump
        In the order of the notes; a jump past the last step (on no step's way) is left out,
        as its warning is.
    """
    out = []
    for note, k in notes_on_steps(notes, JumpNote, step_points):
        if decomposition is None:
            decomposition = decompose(scene)
        out.append(AssemblyJump(f"{note.group} ({', '.join(note.links)})",
                                k - 1 if k > 0 else None, k,
                                placed_from(scene, note.links, decomposition), note.limit))
    return tuple(out)
