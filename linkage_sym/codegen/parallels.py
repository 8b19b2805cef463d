"""Dyads of two slides along a compiled mechanism's solving path (NumPy only).

A dyad of two slides (``PRP``, ``RPP``) has its joint at the intersection of two lines; its
closed form divides by the cross product of their directions, which the generated function
``parallels_<group>`` gives (:meth:`~linkage_sym.codegen.compile._Builder.parallels`).  Along the
runtime's solving path (:class:`~linkage_sym.codegen.runtime.CompiledMechanism`):

* a path point where that cross product is zero to rounding (within
  :data:`~linkage_sym.numeric.kinematics.loci.PARALLEL_ULPS` units of rounding: the slides'
  directions are unit vectors) cannot be assembled: the joint is at infinity, whatever
  huge number the closed form gives there;
* a sign change of the cross product between two consecutive path points where the dyad is
  solved means the slides became parallel between them: the joint passed through infinity
  and came back from the other end of its slides.  It is a warning of the run, worded as
  the numeric solver words it (:func:`~linkage_sym.numeric.continuation.messages.parallel_note`),
  at the first step past it.
"""

from __future__ import annotations

import numpy as np

from linkage_sym.codegen.blocks import full
from linkage_sym.numeric.continuation import messages
from linkage_sym.numeric.kinematics.loci import PARALLEL_ULPS
from linkage_sym.numeric.results.passages import PassageNote

__all__ = ["two_slides"]

_TOL = PARALLEL_ULPS * float(np.finfo(float).eps)


def two_slides(cm, step, X: list, Qpath: np.ndarray, failed: np.ndarray,
               why: dict) -> list:
    """After the closed step ``step``: mark the path points where a dyad of two slides it
    solved has parallel slides as failed (its group, unless an earlier group failed there),
    each with its message in ``why`` (path point -> text, the numeric solver's wording), and
    return the notes of its joint's passages through infinity, ``(first path point past it,
    text(step))``.

    Parameters
    ----------
    cm : CompiledMechanism
        Its ``art`` (``parallels``), generated functions, parameters and scene.
    step : ClosedStep
        The step just solved.
    X : list
        The coordinates along the path (each an array over the ``K`` points, or a number).
    Qpath : ndarray
        Driver values (D, K) along the path.
    failed : ndarray
        Each path point's first failing group (-1: none); updated in place.
    why : dict
        The messages of the path points failed here; updated in place.
    """
    art = cm.art
    K = Qpath.shape[1]
    kinds = {n: cm.scene.joint(n).type for n in art.q}
    qpath = dict(zip(art.q, Qpath))
    notes = []
    CS = None
    for g, a, b, joint in art.parallels:
        group = art.group(g)
        if not set(group.cols) <= set(step.x):
            continue
        if CS is None:  # the cosines and sines of the angles solved so far, made once
            CS = tuple([None if x is None or not cm.is_angle[c] else f(x)
                        for c, x in enumerate(X)] for f in (np.cos, np.sin))
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            (cross,) = cm.call(f"parallels_{g}", X=X, Q=list(Qpath), CS=CS)
            cross = np.array(full(cross, K))
            parallel = np.abs(cross) <= _TOL
        failed[parallel & ((failed < 0) | (failed > g))] = g
        for i in np.flatnonzero(parallel & (failed == g)):
            why[int(i)] = messages.parallel_failure(group.title, (a, b))
        # the points where the dyad is solved: its coordinates numbers, its slides not parallel
        solved = np.isfinite(cross) & ~parallel
        for c in group.cols:
            solved &= np.isfinite(full(X[c], K))
        idx = np.flatnonzero(solved)
        side = cross[idx] > 0
        for k in np.flatnonzero(side[1:] != side[:-1]):
            i, j = int(idx[k]), int(idx[k + 1])
            before = messages.driver_values_text(qpath, kinds, i)
            after = messages.driver_values_text(qpath, kinds, j)
            notes.append(PassageNote(j, lambda text, before=before, after=after, group=group,
                                     a=a, b=b, joint=joint: messages.parallel_note(
                                         group.title, (a, b), joint, before, after, text), joint))
    return notes
