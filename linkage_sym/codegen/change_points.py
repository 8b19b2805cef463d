"""Change points of RRR dyads along a compiled mechanism's solving path (NumPy only).

An RRR dyad whose links are equally long can have its outer joints at one point, a change
point; where that happens between two path points every step is solved, and the run warns
of it, as the numeric solver does (:mod:`linkage_sym.numeric.continuation.change_points`: the
screen, the minimisation and the wording both runtimes share).  The positions are the
runtime's own (:class:`~linkage_sym.codegen.runtime.CompiledMechanism`):

* the vector between the outer joints comes from the dyad's two angles, ``R(phi0) (J - E0) -
  R(phi1) (J - E1)`` with ``J``, ``E0``, ``E1`` the joints' points in the assembly
  configuration and ``phi`` the links' rotations from it: where the dyad is solved, its
  inner joint is at both links' ends, so that is the vector from one outer joint to the
  other;
* at driver values between two path points the closed forms of the position steps up to the
  dyad's are called again (each a function of the driver values and the coordinates before
  it); a dyad after a group without a closed form (solved by continuation from the assembly
  configuration) is not minimised between path points, only path points where its outer
  joints coincide are found.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from linkage_sym.codegen.artifact import ClosedStep
from linkage_sym.codegen.blocks import full
from linkage_sym.numeric.continuation.change_points import change_point_notes
from linkage_sym.numeric.kinematics.closed_form import coincide_tolerance

__all__ = ["MeetingDyad", "meeting_dyads", "notes"]


@dataclass(frozen=True)
class MeetingDyad:
    """An RRR dyad whose links are equally long (to rounding), as the runtime solves it.

    ``group``: its index among the artifact's groups; ``cols``: the columns of its links'
    angles; ``theta0``: their values in the assembly
    configuration; ``arms``: the vectors from each outer joint to the inner joint there;
    ``steps``: the position steps up to its own (``None`` when one has no closed form);
    ``tol``: the outer joints' coincidence distance; ``names``: the wording's
    ``(head, outer joints, inner joint, links)``.
    """

    group: int
    cols: tuple
    theta0: tuple
    arms: tuple
    steps: tuple | None
    tol: float
    names: tuple

    def outer(self, X: list, K: int) -> tuple:
        """``(ex, ey)``, the vector from one outer joint to the other at the ``K`` points of
        the coordinates ``X`` (NaN where the dyad is not solved)."""
        e = []
        for c, th0, (ax, ay) in zip(self.cols, self.theta0, self.arms):
            phi = full(X[c], K) - th0
            cs, sn = np.cos(phi), np.sin(phi)
            e.append((cs * ax - sn * ay, sn * ax + cs * ay))
        return e[0][0] - e[1][0], e[0][1] - e[1][1]


def meeting_dyads(cm, decomposition) -> list:
    """The RRR dyads of the compiled mechanism ``cm`` (its ``art``, ``scene``,
    ``angle_of``, ``frames``) whose links are equally long: a :class:`MeetingDyad` each."""
    scene, art = cm.scene, cm.art
    out = []
    for g in decomposition.groups:
        if g.kind != "dyad" or g.dyad_type != "RRR":
            continue
        e0, ji, e1 = (scene.joint(n) for n in g.joints)
        tol = coincide_tolerance(scene, e0.at, ji.at, e1.at)
        if abs(math.dist(ji.at, e0.at) - math.dist(ji.at, e1.at)) > tol:
            continue
        cols = tuple(cm.angle_of[n] for n in g.links)
        steps = []
        for step in art.steps:
            if not isinstance(step, ClosedStep):
                steps = None
                break
            steps.append(step)
            if set(cols) <= set(step.x):
                break
        index = next(a.index for a in art.groups if tuple(a.links) == tuple(g.links))
        out.append(MeetingDyad(
            index, cols, tuple(cm.frames[n].theta0 for n in g.links),
            tuple((ji.at[0] - e.at[0], ji.at[1] - e.at[1]) for e in (e0, e1)),
            None if steps is None else tuple(steps), tol,
            (f"{g.label} ({', '.join(g.links)})", (e0.name, e1.name), ji.name, g.links)))
    return out


def notes(cm, X: list, Qpath: np.ndarray, failed: np.ndarray) -> list:
    """The notes of the change points of ``cm.meeting`` (:func:`meeting_dyads`) between the
    path points of the coordinates ``X`` solved along ``Qpath`` (D, K), ``failed`` the first
    failing group at each point: ``(first path point past it, text(step))`` pairs."""
    K = Qpath.shape[1]
    q = dict(zip(cm.art.q, Qpath))
    kinds = {n: cm.scene.joint(n).type for n in cm.art.q}
    out = []
    for dyad in cm.meeting:
        e = dyad.outer(X, K)
        solved = np.isfinite(e[0]) & np.isfinite(e[1])

        def evaluate(qs, dyad=dyad):
            Q = [np.asarray(qs[n], float) for n in cm.art.q]
            Xs = [None] * cm.m
            for step in dyad.steps:
                for c, v in zip(step.x, cm.call(step.function, X=Xs, Q=Q)):
                    Xs[c] = v
            return dyad.outer(Xs, len(Q[0]))

        out += change_point_notes(e, solved, failed == dyad.group, dyad.tol, q, kinds,
                                  None if dyad.steps is None else evaluate, dyad.names)
    return out
