"""One block of an analysis's steps as Python lists, and the parts of a step's JSON record.

:meth:`linkage_sym.numeric.results.result.Analysis.step_records` writes the
records one block of steps at a time: :class:`RecordBlock` turns the block's
arrays into lists once (``tolist``), then fills each step's kinematic part
(joints, links, traced points, transmission angles) and force part
(reactions, driving efforts, frame loads) as the step's status allows.

Examples
--------
>>> import linkage_sym
>>> res = linkage_sym.analyze(linkage_sym.load_example("crank_rocker"))
>>> blk = RecordBlock(res, 0, 2)
>>> step = {}
>>> blk.kinematics(step, 1, rates=True)
>>> sorted(step), sorted(step["links"]["crank"])
(['joints', 'links', 'points', 'transmission_angles'], ['alpha', 'com', 'com_acceleration', 'com_velocity', 'omega', 'rotation'])
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["RecordBlock"]


def _motion(lists, i: int, rates: bool, has_vel: bool, has_acc: bool) -> dict:
    """A joint's or traced point's record at step ``i`` (of the block)."""
    pos, vel, acc, pressure = lists
    rec = {"position": pos[i]}
    if pressure is not None:  # a cam contact's (an extension)
        rec["pressure_angle"] = pressure[i]
    if rates and has_vel:
        rec["velocity"] = vel[i]
    if rates and has_acc:
        rec["acceleration"] = acc[i]
    return rec


class RecordBlock:
    """Steps ``a`` to ``b`` of an analysis ``res`` as lists, ready to be written step by step.

    Parameters
    ----------
    res : Analysis
    a, b : int
        The block's first step and the step after its last.
    """

    def __init__(self, res, a: int, b: int):
        self.outputs = res.outputs
        self.want_kin = "kinematics" in res.outputs
        self.has_vel = has_vel = "velocity" in res.stages
        self.has_acc = has_acc = "acceleration" in res.stages
        self.forces = forces = res.forces
        p_joints = set(res.p_joints)
        self.has_points = bool(res.points)

        def rows(v):
            return None if v is None else v[a:b].tolist()

        def motion_lists(k):
            return (rows(k.position), rows(k.velocity) if has_vel else None,
                    rows(k.acceleration) if has_acc else None,
                    rows(getattr(k, "pressure_angle", None)))

        self.status = res.status[a:b].tolist()
        self.messages = res.messages[a:b]
        self.drivers = {name: {k: np.asarray(v, dtype=float)[a:b].tolist() for k, v in d.items()}
                        for name, d in res.drivers.items()}
        if self.want_kin:
            self.joints = {name: motion_lists(jk) for name, jk in res.joints.items()}
            self.points = {name: motion_lists(pk) for name, pk in res.points.items()}
            self.angles = {name: rows(v) for name, v in res.transmission_angles.items()}
            self.links = {
                name: (rows(lk.rotation), rows(lk.omega) if has_vel else None,
                       rows(lk.alpha) if has_acc else None, rows(lk.com),
                       rows(lk.com_velocity) if has_vel else None,
                       rows(lk.com_acceleration) if has_acc else None)
                for name, lk in res.links.items()
            }
        if forces is not None:
            self.reactions = {
                name: (rows(r), rows(forces.reaction_moments[name]) if name in p_joints else None)
                for name, r in forces.reactions.items()} if "reactions" in res.outputs else {}
            self.driving = {k: rows(v) for k, v in forces.driving.items()}
            self.frame_force, self.frame_moment = rows(forces.frame_force), rows(forces.frame_moment)
            self.springs = {name: {k: rows(v) for k, v in rec.items()}
                            for name, rec in forces.springs.items()}
            self.friction = None  # contract part two: with effects.friction and reactions
            if forces.friction is not None and "reactions" in res.outputs:
                self.friction = {name: (rows(v), "friction_force" if name in p_joints
                                        else "friction_moment")
                                 for name, v in forces.friction.items()}
                self.friction_power = rows(forces.friction_power)
                self.efficiency = None if forces.efficiency is None else rows(forces.efficiency)
        # extension: each ok step's estimated relative accuracy (numeric.results.accuracy)
        self.accuracy = {k: rows(v) for k, v in res.accuracy.items()} if res.accuracy else None
        self.centres = res.instant_centres if "instant_centres" in res.outputs else None

    def kinematics(self, step: dict, i: int, rates: bool) -> None:
        """Step ``i``'s joints, links, traced points and transmission angles into ``step``
        (``rates``: with velocities and accelerations)."""
        has_vel, has_acc = self.has_vel, self.has_acc
        step["joints"] = {name: _motion(lists, i, rates, has_vel, has_acc)
                          for name, lists in self.joints.items()}
        out_links = {}
        for name, (rot, om, al, com, comv, coma) in self.links.items():
            rec = {"rotation": rot[i]}
            if rates and has_vel:
                rec["omega"] = om[i]
            if rates and has_acc:
                rec["alpha"] = al[i]
            if com is not None:
                rec["com"] = com[i]
                if rates and has_vel:
                    rec["com_velocity"] = comv[i]
                if rates and has_acc:
                    rec["com_acceleration"] = coma[i]
            out_links[name] = rec
        step["links"] = out_links
        if self.has_points:
            step["points"] = {name: _motion(lists, i, rates, has_vel, has_acc)
                              for name, lists in self.points.items()}
        if self.angles:  # extension: the RRR dyads' transmission angles, by inner joint
            step["transmission_angles"] = {name: v[i] for name, v in self.angles.items()}

    def force_parts(self, step: dict, i: int) -> None:
        """Step ``i``'s reactions (into its joints), driving efforts, frame loads and springs."""
        if "reactions" in self.outputs:
            out_joints = step.setdefault("joints", {})
            for name, (r, m) in self.reactions.items():
                rec = out_joints.setdefault(name, {})
                rec["reaction"] = r[i]
                if m is not None:
                    rec["reaction_moment"] = m[i]
        if "driving" in self.outputs:
            step["driving"] = {k: v[i] for k, v in self.driving.items()}
        if "frame" in self.outputs:
            step["frame"] = {"force": self.frame_force[i], "moment": self.frame_moment[i]}
        if self.springs:  # the contract's second part: each spring's length and force
            step["springs"] = {name: {k: v[i] for k, v in rec.items()}
                               for name, rec in self.springs.items()}
        if self.friction is not None:
            for name, (v, key) in self.friction.items():
                step["joints"].setdefault(name, {})[key] = v[i]
            step["friction_power"] = self.friction_power[i]
            eta = None if self.efficiency is None else self.efficiency[i]
            if eta is not None and math.isfinite(eta):  # only where it is defined
                step["efficiency"] = eta
