"""The continuation's messages, worded alike by both runtimes (NumPy only).

A path point the policy could not solve (:func:`failure_message`), a point
reached without a continuous path (:func:`note_message`), the driver values
they name (:func:`driver_values_text`), and the run's warnings of those jumps
at the steps that see them (:func:`step_warnings`); and the jump of a dyad of two slides
whose joint passes through infinity between two path points (:func:`parallel_note`), which
both runtimes find by their own means, and the failure where they are parallel
(:func:`parallel_failure`); and an RRR dyad's change point between two path points
(:func:`change_point_note`).
"""

from __future__ import annotations


import numpy as np

from linkage_sym.numeric.results import wording


def failure_message(label: str, links, failure, where) -> str:
    """The message of a path point the continuation could not solve (both runtimes).

    ``where(t)`` words the driver values a fraction ``t`` of the way from the
    previous path point to this one (e.g. ``"A = 123.45 deg"``).
    """
    head = f"{label} ({', '.join(links)})"
    kind, detail = failure
    if kind == "limit":
        return (
            f"{head}: reaches a limit or singular position at {where(detail)} and no solution "
            "in the assembly mode exists past it: the group cannot be assembled here"
        )
    if kind == "other_mode":
        return (
            f"{head}: the only solution(s) found ({detail}) are in the other assembly mode "
            "(determinant sign of the group's Jacobian); not accepted"
        )
    return f"{head}: Newton on the group's loop equations finds no solution: the group cannot be assembled here"


def note_message(label: str, links, note, step_text: str, where) -> str:
    """The warning of a point reached without a continuous path (both runtimes)."""
    _, limit, n_same = note
    head = f"{label} ({', '.join(links)})"
    how = (
        f"passes a limit or singular position at {where(limit)}"
        if limit is not None
        else "re-enters after steps that cannot be assembled"
    )
    text = (
        f"{head} {how}; at {step_text} it continues in the assembly mode (determinant sign), "
        "nearest to the last solved configuration"
    )
    if n_same > 1:
        text += f": the assembly mode is ambiguous there ({n_same} solutions with that sign)"
    return text


def parallel_note(head: str, slides, joint: str, before: str, after: str,
                  step_text: str) -> str:
    """The warning of a dyad of two slides (``PRP``, ``RPP``) whose slides become parallel
    between two solved path points, where the driver values are ``before`` and ``after``
    (:func:`driver_values_text`): the intersection of the slides, ``joint``, passes through
    infinity and comes back from the other end of the slides (both runtimes).

    Examples
    --------
    >>> parallel_note("dyad PRP (rod, block)", ("A_slide", "C_guide"), "C", "A = 1°",
    ...               "A = -1°", "step 5 (reached from step 4)")[:79]
    'dyad PRP (rod, block): the slides of joints A_slide and C_guide become parallel'
    """
    return (
        f"{head}: the slides of joints {slides[0]} and {slides[1]} become parallel between "
        f"{before} and {after}: joint {joint} passes through infinity there; at {step_text} "
        "it is on the far side of its slides"
    )


def change_point_note(head: str, outer, inner: str, links, before: str, after: str,
                      step_text: str) -> str:
    """The warning of an RRR dyad whose outer joints pass through one point between two
    solved path points, where the driver values are ``before`` and ``after``
    (:func:`driver_values_text`): a change point, where the dyad may keep its assembly mode
    or change it; the closed form keeps it (both runtimes,
    :mod:`~linkage_sym.numeric.continuation.change_points`).

    Examples
    --------
    >>> change_point_note("dyad RRR (coupler, rocker)", ("B", "D"), "C", ("coupler", "rocker"),
    ...                   "A = 1°", "A = -1°", "step 5 (reached from step 4)")[:73]
    'dyad RRR (coupler, rocker): joints B and D pass through one point between'
    """
    return (
        f"{head}: joints {outer[0]} and {outer[1]} pass through one point between {before} "
        f"and {after} (a change point: joint {inner} can be anywhere on one circle about "
        f"them there); at {step_text} the dyad keeps its assembly mode (joint {inner} on the "
        f"same side of the line from {outer[0]} to {outer[1]}), so links {links[0]} and "
        f"{links[1]} have turned a half turn (which way is undefined); the other branch, "
        "where the assembly mode changes and they do not turn, is equally valid"
    )


def parallel_failure(head: str, slides) -> str:
    """The message of a path point where a dyad of two slides has them parallel (its joint
    at infinity: unassemblable), both runtimes."""
    return f"{head}: the slides of joints {slides[0]} and {slides[1]} are parallel"


def driver_values_text(q: dict, kinds: dict, i: int, t: float | None = None) -> str:
    """Driver values at path point ``i`` (or a fraction ``t`` of the way from ``i - 1``), worded.

    ``q`` maps each driven joint to its values along the path, ``kinds`` to
    ``"R"`` (an angle, printed in degrees) or ``"P"`` (a slide, in metres).
    """
    at = {name: float(v[i]) if t is None or i == 0 else float(v[i - 1] + t * (v[i] - v[i - 1]))
          for name, v in q.items()}
    return wording.driver_values_text(at, kinds)


def step_warnings(notes, step_points) -> list[str]:
    """Warnings of the Newton groups' jumps (a limit passed, a re-entry after a gap).

    ``notes`` are ``(path point, text(step))`` pairs; ``step_points`` the path
    point of every step, increasing.  A jump between two steps is reported at
    the step after it.
    """
    out = []
    step_points = np.asarray(step_points)
    for p, text, *_ in notes:  # a passage's note also names its joint
        k = int(np.searchsorted(step_points, p))
        if k >= len(step_points):
            continue  # on the way to the first step only: no step sees it
        where = f"step {k}" if step_points[k] == p else f"step {k} (reached from step {k - 1})"
        if k == 0 and step_points[0] != p:
            where = "step 0 (reached from the assembly configuration)"
        out.append(text(where))
    return out
