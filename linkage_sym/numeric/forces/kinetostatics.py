"""Kinetostatics: joint reactions, driver efforts and frame loads of a solved motion.

:class:`ForcePlan` is compiled once per mechanism (one force routine per
Assur group) and evaluated over the steps whose kinematics are ``ok``.

Methods
-------
``"dyad"`` (default)
    From the last group back to the drivers, each group's reactions from
    its own equilibrium: closed forms for input links and dyads
    (:mod:`~linkage_sym.numeric.forces.statics`), Dang and Zhang's disconnection and
    superposition for class-III and other complex groups
    (:mod:`~linkage_sym.numeric.forces.superposition`); the reactions of a solved
    group are then loads on the links it hangs from.
``"global"``
    Every link's equilibrium in one sparse system
    (:mod:`~linkage_sym.numeric.forces.global_statics`), the check of the former.

Gear meshes
-----------
A gear on its pivot is solved in closed form (:class:`~linkage_sym.numeric.kinematics.gears.GearForces`),
a group of several links with meshes as one dense system.  A mesh's force
lies on the line of action of the flank the tangential force presses on
(:mod:`~linkage_sym.numeric.kinematics.gears`); the flank is not known before the
solve, so a scene with meshes is solved with every flank +1, then again
with the flanks the tangential forces show, until no tooth load is negative
(two solves unless the flank of one mesh changes another's tangential force).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from linkage_sym.model import GROUND, Scene
from linkage_sym.numeric.kinematics.gears import GearForces, pulling_note
from linkage_sym.numeric.forces import friction as fr
from linkage_sym.numeric.forces.global_friction import solve_global_friction
from linkage_sym.numeric.forces.global_statics import frame_wrench, solve_dense, solve_global
from linkage_sym.numeric.forces.loads import applied_wrenches
from linkage_sym.numeric.forces.springs import record_keys, spring_values
from linkage_sym.numeric.forces.policy import check_method
from linkage_sym.numeric.results.result import SELF_LOCKING, Forces, GroupForces
from linkage_sym.numeric.results.wording import steps_text
from linkage_sym.numeric.forces.statics import DyadForces, Geometry, InputForces, push
from linkage_sym.numeric.forces.superposition import SuperpositionForces
from linkage_sym.structure.disconnection import usable_disconnections
from linkage_sym.structure import Decomposition, Group



@dataclass
class GroupSolution:
    """What a force routine returns for its group over ``K`` steps."""

    reactions: dict
    """joint -> ``(fx, fy, m)``: the reaction the joint's ``links[0]`` exerts on ``links[1]``."""
    efforts: dict
    """driven joint -> driving force or torque."""
    used: np.ndarray | None = None
    """(K,) index of the disconnection used at each step (superposition only)."""
    amplification: np.ndarray | None = None
    """(K,) cancellation of the superposition (superposition only)."""


class ForceRoutine(Protocol):
    """The force routine of one Assur group, as :class:`ForcePlan` calls it."""

    method: str
    """How the group is solved, as reported in ``GroupForces.method``."""
    choices: tuple
    """The disconnections tried (superposition only; else empty)."""

    def solve(self, W, geo: Geometry, L: float, K: int) -> GroupSolution:
        """Reactions and efforts from the applied wrenches ``W`` over ``K`` steps."""


class _InputRoutine:
    choices = ()
    method = "input"

    def __init__(self, scene: Scene, g: Group):
        (dname,) = g.drivers
        self.routine = InputForces(scene, g.links[0], dname)

    def solve(self, W, geo, L, K) -> GroupSolution:
        r, e = self.routine.solve(W, geo)
        name = self.routine.joint.name
        return GroupSolution({name: r}, {name: e})


class _DyadRoutine:
    choices = ()

    def __init__(self, scene: Scene, g: Group):
        self.routine = DyadForces(scene, g)
        self.method = f"dyad {g.dyad_type}"

    def solve(self, W, geo, L, K) -> GroupSolution:
        return GroupSolution(self.routine.solve(W, geo), {})


class _SuperpositionRoutine:
    method = "disconnection"

    def __init__(self, scene: Scene, g: Group, choices, preferred):
        self.routine = SuperpositionForces(scene, g, choices, preferred)
        self.choices = tuple(d.describe() for d in self.routine.choices)

    def solve(self, W, geo, L, K) -> GroupSolution:
        res, eff, used, amp = self.routine.solve(W, geo, L, K)
        return GroupSolution(res, eff, used, amp)


class _GearRoutine:
    """A gear on its pivot: the tooth load and the pivot's reaction in closed form."""

    choices = ()
    method = "gear"

    def __init__(self, scene: Scene, g: Group):
        self.routine = GearForces(scene, g)

    def solve(self, W, geo, L, K) -> GroupSolution:
        return GroupSolution(self.routine.solve(W, geo, L, K), {})


class _DenseRoutine:
    """A group no disconnection reduces to dyads: its own equilibrium as one linear system."""

    choices = ()
    method = "dense"

    def __init__(self, scene: Scene, g: Group):
        self.scene, self.group = scene, g

    def solve(self, W, geo, L, K) -> GroupSolution:
        g = self.group
        res, eff = solve_dense(
            self.scene, list(g.links), list(g.joints), list(g.drivers), geo, W, L, K
        )
        return GroupSolution(res, eff)


class ForcePlan:
    """Force routines of every group of a decomposition, compiled once.

    Parameters
    ----------
    scene : Scene
    decomposition : Decomposition
    L : float
        Characteristic length (moment rows and unknowns are scaled by it).
    disconnection : int or dict, optional
        Disconnection to prefer for complex groups: one index for every such
        group, or ``{group index: choice index}``; default
        :func:`~linkage_sym.numeric.forces.superposition.default_choice`.
    """

    def __init__(self, scene: Scene, decomposition: Decomposition, L: float, disconnection=None):
        self.scene = scene
        self.decomposition = decomposition
        self.L = L
        self.routines: list[ForceRoutine] = []
        for gi, g in enumerate(decomposition.groups):
            if g.kind == "input":
                self.routines.append(_InputRoutine(scene, g))
            elif g.kind == "dyad":
                self.routines.append(_DyadRoutine(scene, g))
            elif g.kind == "gear" and len(g.links) == 1:
                self.routines.append(_GearRoutine(scene, g))
            elif g.kind in ("gear", "cam"):  # a cam: one unknown along the contact normal
                self.routines.append(_DenseRoutine(scene, g))
            else:
                choices = usable_disconnections(scene, g)
                pref = disconnection.get(gi) if isinstance(disconnection, dict) else disconnection
                if choices:
                    self.routines.append(_SuperpositionRoutine(scene, g, choices, pref))
                else:
                    self.routines.append(_DenseRoutine(scene, g))

    def run(self, S, ok, method="dyad", q=None) -> Forces:
        """Forces at the steps where ``ok`` is true (NaN elsewhere).

        Parameters
        ----------
        S : dict of LinkState
            Solved link states over all N steps.
        ok : ndarray of bool, shape (N,)
        method : {"dyad", "global"}
        q : dict of ndarray, optional
            Driver values over the N steps, for loads that vary over the cycle.
        """
        check_method(method)
        scene = self.scene
        N = len(ok)
        idx = None if ok.all() else np.flatnonzero(ok)
        K = N if idx is None else len(idx)
        Sk = S if idx is None else {n: (st.take(idx) if n != GROUND else st) for n, st in S.items()}
        qk = None if q is None else {k: np.asarray(v, float) if idx is None else np.asarray(v, float)[idx]
                                     for k, v in q.items()}
        flank: dict = {}
        pulling: dict = {}  # mesh -> steps of the last solve whose tooth load pulls
        solves = 1 + 2 * len(scene.meshes)
        friction = bool(fr.active_joints(scene)) and K > 0
        for _ in range(solves):
            geo = Geometry(scene, Sk, flank)
            fset = fr.FrictionSet(scene, Sk, geo, K) if friction else None
            reactions, efforts, frame, groups, fric = self._solve(Sk, geo, qk, method, K, idx, N, fset)
            wrong, pulling = {}, {}
            for m in scene.meshes:  # the tooth load must press, not pull: else the other flank
                ux, uy = geo.line_of_action(m.name)
                fx, fy, _ = reactions[m.name]
                neg = fx * ux + fy * uy < 0
                if np.any(neg):
                    wrong[m.name] = np.where(neg, -flank.get(m.name, 1.0), flank.get(m.name, 1.0))
                    pulling[m.name] = np.flatnonzero(np.broadcast_to(neg, (K,)))
            if not wrong:
                break
            flank = {**flank, **wrong}
        notes = pulling_notes(scene, geo, reactions, idx) if scene.cams else []
        for name, bad in pulling.items():  # never settled: said, not hidden
            steps = bad if idx is None else idx[bad]
            notes.append(pulling_note(name, steps, solves))
        values = spring_values(scene, Sk)
        springs = {k.name: dict(zip(record_keys(k), (_spread(x, idx, N) for x in values[k.name])))
                   for k in scene.active_springs}
        out_r, out_m = {}, {}
        for j in scene.joints:
            fx, fy, m = reactions[j.name]
            out_r[j.name] = np.stack([_spread(fx, idx, N), _spread(fy, idx, N)], axis=-1)
            out_m[j.name] = _spread(m, idx, N)
        out = Forces(
            method=method,
            reactions=out_r,
            reaction_moments=out_m,
            driving={d.joint: _spread(efforts[d.joint], idx, N) for d in scene.drivers},
            frame_force=np.stack([_spread(frame[0], idx, N), _spread(frame[1], idx, N)], axis=-1),
            frame_moment=_spread(frame[2], idx, N),
            groups=groups,
            notes=notes,
            springs=springs,
        )
        if scene.effects.friction:  # contract part two: friction's results, self-locking steps
            ideal = self._solve(Sk, geo, qk, method, K, idx, N, None)[1] if friction else efforts
            _friction_results(out, scene, fset, fric, ideal, efforts, idx, N)
        return out

    def _solve(self, Sk, geo, qk, method, K, idx, N, fset=None):
        """Reactions, efforts, frame wrench and group records at the ``K`` solved steps, and
        with friction (``fset``) ``(mu, locked, lockers)`` (see
        :func:`~linkage_sym.numeric.forces.friction.solve_group`), else ``None``."""
        scene = self.scene
        W = applied_wrenches(scene, Sk, q=qk)
        groups = []
        fric = None
        if K == 0:
            reactions = {j.name: (np.zeros(0),) * 3 for j in scene.joints}
            efforts = {d.joint: np.zeros(0) for d in scene.drivers}
            frame = (np.zeros(0), np.zeros(0), np.zeros(0))
            # the group records as a run with solved steps has them (a chunk of a sweep
            # whose steps all fail has the same groups and choices as the others)
            for g, routine in zip(self.decomposition.groups, self.routines):
                info = GroupForces(g.links, "global" if method == "global" else routine.method)
                if method != "global" and routine.choices:
                    info.choices = routine.choices
                    info.used = np.full(N, -1, int)
                    info.amplification = np.full(N, np.nan)
                groups.append(info)
        elif method == "global":
            if fset is None:
                reactions, efforts = solve_global(scene, geo, W, self.L, K)
                frame = frame_wrench(scene, geo, reactions, efforts)
            else:
                reactions, efforts, mu, locked, lockers = solve_global_friction(
                    scene, geo, W, self.L, K, fset)
                folded = {n: fr.fold(scene.joint(n), r, mu.get(n), geo) for n, r in reactions.items()}
                frame = frame_wrench(scene, geo, folded, efforts)
                fric = (mu, locked, lockers)
            if scene.active_springs:  # a spring anchored on the ground pulls on the frame too
                g = W[GROUND]
                frame = (frame[0] + g.fx, frame[1] + g.fy, frame[2] + g.m)
            groups = [GroupForces(g.links, "global") for g in self.decomposition.groups]
        else:
            reactions, efforts = {}, {}
            mu, locked, lockers = {}, np.zeros(K, bool), {}
            for g, routine in zip(reversed(self.decomposition.groups), reversed(self.routines)):
                sol = routine.solve(W, geo, self.L, K)
                res, eff = sol.reactions, sol.efforts
                if fset is not None:
                    res, eff, m_g, lk, who = fr.solve_group(
                        _linear(routine, geo, self.L, K), (res, eff), scene,
                        g.joints, W, geo, fset, locked)
                    mu.update(m_g)
                    locked = locked | lk
                    for i, names in who.items():
                        lockers.setdefault(i, []).extend(names)
                info = GroupForces(g.links, routine.method)
                if sol.used is not None:
                    info.choices = routine.choices
                    info.used = _spread(sol.used, idx, N, -1, int)
                    info.amplification = _spread(sol.amplification, idx, N, np.nan)
                groups.append(info)
                reactions.update(res)
                efforts.update(eff)
                inside = set(g.links)
                for name in g.external:
                    j = scene.joint(name)
                    r = res[name] if fset is None else fr.fold(j, res[name], mu.get(name), geo)
                    push(W, j, geo, r, eff.get(name), only=W.keys() - inside)
            groups.reverse()
            w = W[GROUND]
            frame = (w.fx, w.fy, w.m)
            if fset is not None:
                fric = (mu, locked, lockers)
        return reactions, efforts, frame, groups, fric


def _linear(routine, geo, L, K):
    """A group routine as ``W -> (reactions, efforts)``: the linear solve the friction's
    Newton calls (:func:`~linkage_sym.numeric.forces.friction.solve_group`)."""
    def solve(W):
        sol = routine.solve(W, geo, L, K)
        return sol.reactions, sol.efforts
    return solve


def _friction_results(out: Forces, scene, fset, fric, ideal, efforts, idx, N) -> None:
    """Fill the friction's fields of ``out`` over the ``N`` steps (see :class:`Forces`), its
    notes (joints without a direction of friction), and NaN at the self-locking steps."""
    K = N if idx is None else len(idx)
    mu, locked, lockers = fric if fric is not None else ({}, np.zeros(K, bool), {})
    per_joint = {}
    for j in scene.joints:
        if j.friction is not None:
            m = mu.get(j.name)
            per_joint[j.name] = _spread(np.zeros(K) if m is None else m, idx, N)
    power = fset.power(mu) if fset is not None else np.zeros(K)
    locked_n = _spread(locked, idx, N, False, bool)
    messages = {}
    for i, names in lockers.items():
        step = int(i if idx is None else idx[i])
        messages[step] = (
            f"{SELF_LOCKING}: no finite driving effort moves the mechanism as prescribed: the "
            f"friction at joint(s) {', '.join(dict.fromkeys(names))} grows with the effort "
            "faster than the effort can move it")
    eff = None
    if len(scene.drivers) == 1:
        (d,) = scene.drivers
        e, e0 = np.asarray(efforts[d.joint], float), np.asarray(ideal[d.joint], float)
        with np.errstate(divide="ignore", invalid="ignore"):
            eta = np.where((e != 0) & (e0 != 0) & (np.sign(e) == np.sign(e0)), e0 / e, np.nan)
        eff = _spread(eta, idx, N)
    out.friction, out.friction_power, out.efficiency = per_joint, _spread(power, idx, N), eff
    out.driving_ideal = {k: _spread(v, idx, N) for k, v in ideal.items()}
    out.locked, out.lock_messages = locked_n, messages
    if fset is not None:
        out.notes += fset.notes(idx)
    if locked_n.any():  # nothing is reported at a self-locking step but its status
        arrays = [*out.reactions.values(), *out.reaction_moments.values(), *out.driving.values(),
                  out.frame_force, out.frame_moment, *per_joint.values(), out.friction_power,
                  *out.driving_ideal.values(), *([eff] if eff is not None else [])]
        for a in arrays:
            a[locked_n] = np.nan


def mark_self_locking(status, messages, ok, forces: Forces) -> None:
    """Give the steps at which the friction locks the mechanism the status ``self-locking``
    and their message, and leave them out of ``ok``."""
    if forces is None or forces.locked is None:
        return
    for i, text in forces.lock_messages.items():
        if ok[i]:
            status[i] = SELF_LOCKING
            messages[i] = text
            ok[i] = False


def _spread(values, idx, N, fill=np.nan, dtype=float):
    """Values at the solved steps placed into an (N,) array (``fill`` elsewhere)."""
    out = np.full(N, fill, dtype=dtype)
    if idx is None:
        out[:] = values
    else:
        out[idx] = values
    return out


def pulling_notes(scene, geo, reactions, idx):
    """Warnings for the steps where a cam contact's force would pull (a cam only pushes)."""
    notes = []
    for j in scene.cams:
        nx, ny = geo.contact_normal(j.name)
        fx, fy, _ = reactions[j.name]
        Fn = np.atleast_1d(fx * nx + fy * ny)
        bad = np.flatnonzero(Fn < 0)
        if len(bad):
            steps = bad if idx is None else idx[bad]
            notes.append(
                f"cam contact {j.name}: the follower loses contact at {len(steps)} step(s) (steps "
                f"{steps_text(steps, len(steps))}): the contact force computed there pulls "
                f"(down to {Fn.min():.4g} N) and a cam can only push -- a spring or a heavier "
                "load must keep the follower on the profile; the forces reported there are not "
                "ones the contact can carry")
    return notes
