"""Each design as a scene of its own (``--write-scenes DIR``; :class:`SceneFiles` asks
:func:`linkage_sym.design.sweep` for them).

A design's scene is the sweep's scene with its joints where the design's
assembly configuration puts them (the closed forms at the scene's driver
values with the scene's assembly-mode signs, :meth:`Model.assemble`), every
link's centre of mass, traced points and load points carried along with its
link frame (origin ``u``, x-axis toward ``v``: their coordinates in the frame
are kept, or the design's own where it varies them), ``P`` joints' slide
directions turned with the link that carries them, and the design's masses,
inertias, gravity and load values.  ``linkage_sym.analyze`` of that scene
solves the design again with the numeric solver, which is how the tests check
every metric of the sweep.
"""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from linkage_sym.model import GROUND

__all__ = ["SceneFiles", "design_scene"]


@dataclass(frozen=True)
class SceneFiles:
    """Each design's own scene written as a file, for :func:`linkage_sym.design.sweep`.

    Attributes
    ----------
    folder : str or os.PathLike
        Where each design's scene is written, as ``design_<i>.json`` (created if need
        be).  A design that cannot be assembled has none (the result's ``no_scene`` lists
        them), nor has one that breaks the scene's rules (``bad_scene``, with the rule: the
        invalid designs, and any whose scene the scene reader refuses).
    rows : sequence of int or range, optional
        Only these designs' scenes (their ``design`` numbers, rows of the table);
        default every design's.  The sweep checks them; a problem names ``rows``.

    Examples
    --------
    >>> SceneFiles("designs", rows=[0, range(10, 20)])
    SceneFiles(folder='designs', rows=[0, range(10, 20)])
    """

    folder: str | os.PathLike
    rows: Sequence | None = None


def _at(v, d):
    return float(v[d]) if np.ndim(v) else float(v)


def design_scene(model, P, X0, joints0, d: int, name: str):
    """The :class:`~linkage_sym.model.Scene` of design ``d`` of a chunk (``P``, ``X0``,
    ``joints0`` from :meth:`Model.assemble`)."""
    scene = model.scene
    frames = model.frames
    theta = {lk: float(X0[model.angle_of[lk], d]) for lk in scene.link_names}
    theta[GROUND] = 0.0
    origin = {lk: (float(joints0["origin:" + lk][0, d]), float(joints0["origin:" + lk][1, d]))
              for lk in scene.link_names}
    origin[GROUND] = (0.0, 0.0)

    def value(recipe, default):
        return _at(model.value(P, recipe, default), d)

    def local(link, at):  # coordinates in the scene's frame of ``link``
        if link == GROUND:
            return at
        fr = frames[link]
        c, s = math.cos(fr.theta0), math.sin(fr.theta0)
        dx, dy = at[0] - fr.origin[0], at[1] - fr.origin[1]
        return c * dx + s * dy, -s * dx + c * dy

    def place(link, xy):  # a point of the link frame at the design's assembly
        th, (ox, oy) = theta[link], origin[link]
        c, s = math.cos(th), math.sin(th)
        return (ox + c * xy[0] - s * xy[1], oy + s * xy[0] + c * xy[1])

    joints = []
    for j in scene.joints:
        at = (float(joints0[j.name][0, d]), float(joints0[j.name][1, d]))
        axis = j.axis
        if j.type == "P":
            a = j.links[0]
            base = 0.0 if a == GROUND else frames[a].theta0
            gamma = value(("gamma", j.name), j.axis - base)
            axis = math.atan2(math.sin(gamma + theta[a]), math.cos(gamma + theta[a]))
        kw = {}
        if j.friction is not None:  # the design's coefficient and pin radius (contract part two)
            kw["friction"] = dataclasses.replace(
                j.friction, coefficient=value(("mu", j.name), j.friction.coefficient),
                radius=(None if j.friction.radius is None
                        else value(("rpin", j.name), j.friction.radius)))
        joints.append(dataclasses.replace(j, at=at, axis=axis, **kw))
    links = []
    for lk in scene.links:
        com = lk.com
        if com is not None:
            p0, q0 = local(lk.name, com)
            com = place(lk.name, (value(("p", lk.name), p0), value(("q", lk.name), q0)))
        links.append(dataclasses.replace(lk, mass=value(("m", lk.name), lk.mass),
                                         inertia=value(("I", lk.name), lk.inertia), com=com))
    loads = []
    for i, ld in enumerate(scene.loads):
        kw = {}
        if ld.force is not None:
            kw["force"] = (value(("Fx", i), ld.force[0]), value(("Fy", i), ld.force[1]))
            x0, y0 = local(ld.link, ld.at)
            kw["at"] = place(ld.link, (value(("xi", i), x0), value(("eta", i), y0)))
        if ld.torque:
            kw["torque"] = value(("T", i), ld.torque)
        loads.append(dataclasses.replace(ld, **kw))
    effects = scene.effects
    if effects.gravity is not None:
        effects = dataclasses.replace(effects, gravity=(value(("gx",), effects.gravity[0]),
                                                        value(("gy",), effects.gravity[1])))
    points = tuple(dataclasses.replace(p, at=place(p.link, local(p.link, p.at)))
                   for p in scene.points)
    return dataclasses.replace(scene, name=name, links=tuple(links), joints=tuple(joints),
                               loads=tuple(loads), effects=effects, points=points,
                               springs=_springs(scene, value, local, place))


def _springs(scene, value, local, place) -> tuple:
    """The scene's springs with the design's values (``value(recipe, default)``), their ends
    carried along with their links (``local``, ``place``: see :func:`design_scene`)."""
    springs = []
    for k in scene.springs:
        kw = {"stiffness": value(("k", k.name), k.stiffness),
              "damping": value(("c", k.name), k.damping)}
        if k.joint is not None:
            kw["free_angle_deg"] = math.degrees(value(("theta_f", k.name), k.free_angle))
        else:
            kw["free_length"] = value(("L0", k.name), k.free_length)
            kw["at"] = tuple(
                place(link, (value(("xi_s", k.name, i), x0), value(("eta_s", k.name, i), y0)))
                for i, link in enumerate(k.links)
                for x0, y0 in (local(link, k.at[i]),))
        springs.append(dataclasses.replace(k, **kw))
    return tuple(springs)
