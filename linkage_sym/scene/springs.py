"""The ``springs`` section of a scene: springs and dampers (the contract's second part).

A spring acts between two links (``links``, ``at`` -- one point on each, in
the assembly configuration -- ``stiffness``, ``free_length``, ``damping``) or
at an ``R`` joint (``joint``, ``stiffness``, ``free_angle_deg``,
``damping``); see ``docs/scene-format.md``, "Springs and dampers".
:func:`read_springs` reads the section with the checks and wording of
:class:`~linkage_sym.scene.fields.FieldReader`, every problem named by its
field; :func:`springs_effect` reads ``effects.springs``.

Examples
--------
>>> from linkage_sym import load_example
>>> from linkage_sym.scene import parse_scene
>>> from linkage_sym.scene.load import dump_scene
>>> data = dump_scene(load_example("crank_rocker"))
>>> data["springs"] = [
...     {"name": "k1", "links": ["ground", "rocker"], "at": [[0.10, 0.05], [0.07, 0.02]],
...      "stiffness": 500.0, "damping": 2.0},
...     {"name": "k2", "joint": "D", "stiffness": 1.5}]
>>> scene = parse_scene(data)
>>> k1, k2 = scene.springs
>>> round(k1.free_length, 6), k2.free_angle, scene.effects.springs
(0.042426, 0.0, True)
>>> data["springs"] = [{"name": "k1", "links": ["rocker", "rocker"], "at": [[0, 0], [1, 0]],
...                     "stiffness": -1.0}, {"name": "k1", "joint": "B", "stiffness": 1.0,
...                     "free_length": 0.1}]
>>> parse_scene(data)
Traceback (most recent call last):
  ...
linkage_sym.errors.SceneError: invalid scene (4 problems):
  springs[0].stiffness: must be a finite number >= 0, got -1.0
  springs[0].links: a spring between link 'rocker' and itself (it needs two different links)
  springs[1].name: duplicate spring name 'k1' (first at springs[0])
  springs[1].free_length: not allowed on a joint spring (only between two links)
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from linkage_sym.model.scene import GROUND, Spring
from linkage_sym.scene.fields import ANGLE, REQUIRED, did_you_mean, json_kind, show_value

__all__ = ["SPRING_KEYS", "read_springs", "springs_effect"]

LINK_SPRING_KEYS = ("links", "at", "free_length")
"""The keys of a spring between two links (besides the common ones)."""
JOINT_SPRING_KEYS = ("joint", "free_angle_deg")
"""The keys of a spring at an ``R`` joint (besides the common ones)."""
SPRING_KEYS = ("name", "stiffness", "damping", *LINK_SPRING_KEYS, *JOINT_SPRING_KEYS)
"""Every key of a ``springs`` entry."""
RULE = {"minimum": 0.0}
"""Stiffness, damping and free length: finite numbers, none negative."""


def springs_effect(r, effects: Mapping[str, Any] | None, data: Mapping[str, Any]) -> bool | None:
    """``effects.springs``: as given (a boolean), else whether the scene gives ``springs``."""
    given = "springs" in data
    if effects is None:
        return given
    return r.boolean(effects, "springs", "effects", default=given)


def read_springs(r, data: Mapping[str, Any]) -> tuple[Spring, ...]:
    """The ``springs`` of a scene mapping, checked against the reader ``r``'s links and joints.

    ``r`` is the scene reader (:mod:`linkage_sym.scene.validate`): a
    :class:`~linkage_sym.scene.fields.FieldReader` whose ``link_index`` and
    ``joints`` (``None`` where their section was not even an array) resolve the
    names.  Problems are recorded in ``r``; only springs without one are returned.
    """
    out = []
    for path, entry, name, before in r.named_entries(data, "springs", SPRING_KEYS, "spring"):
        if "joint" in entry and "links" in entry:
            r.add(path, "give either 'joint' (a spring at an R joint) or 'links' and 'at' "
                        "(a spring between two links), not both")
            continue
        stiffness = r.number(entry, "stiffness", path, **RULE)
        damping = r.number(entry, "damping", path, default=0.0, **RULE)
        if "joint" in entry:
            fields = _joint_spring(r, entry, path)
        else:
            fields = _link_spring(r, entry, path)
        if len(r.problems) == before:
            out.append(Spring(name, stiffness, damping, **fields))
    return tuple(out)


def _joint_spring(r, entry: Mapping[str, Any], path: str) -> dict:
    """The fields of a spring at an ``R`` joint (problems recorded in ``r``)."""
    r.forbid(entry, path, LINK_SPRING_KEYS, "on a joint spring (only between two links)")
    joint = r.name(entry, "joint", path)
    if joint is not None and r.joints is not None:
        info = r.joints.get(joint)
        if info is None:
            r.add(f"{path}.joint", f"unknown joint '{joint}'{did_you_mean(joint, r.joints)}")
        elif info.type is not None and info.type != "R":
            r.add(f"{path}.joint", f"a joint spring acts at an R joint; joint '{joint}' is of "
                                   f"type {info.type}")
    angle = r.number(entry, "free_angle_deg", path, default=0.0, **ANGLE)
    return {"joint": joint, "free_angle_deg": angle}


def _link_spring(r, entry: Mapping[str, Any], path: str) -> dict:
    """The fields of a spring between two links (problems recorded in ``r``)."""
    r.forbid(entry, path, ("free_angle_deg",), "on a spring between two links (only at a joint)")
    if "links" not in entry:
        r.missing(f"{path}.links", "a spring joins two links ('links' and 'at') or acts at an "
                                   "R joint ('joint')")
    pair = _pair(r, entry, path)
    at = _points(r, entry, path)
    length = None
    if at is not None:
        length = math.hypot(at[1][0] - at[0][0], at[1][1] - at[0][1])
        if length == 0.0:
            r.add(f"{path}.at", "the two points coincide in the assembly configuration: the "
                                "direction of the spring's force is not defined there")
    free = r.number(entry, "free_length", path, default=length, **RULE)
    return {"links": pair, "at": at, "free_length": free}


def _pair(r, entry: Mapping[str, Any], path: str) -> tuple[str, str] | None:
    """``links``: two names of links (``ground`` or a listed link), not the same."""
    if "links" not in entry:
        return None
    value = entry["links"]
    field = f"{path}.links"
    if not isinstance(value, (list, tuple)) or len(value) != 2 or not all(
            isinstance(v, str) and v for v in value):
        r.add(field, f"must be an array of 2 link names, got {show_value(value)}")
        return None
    ok = True
    for k, name in enumerate(value):
        if name != GROUND and r.link_index is not None and name not in r.link_index:
            known = [GROUND, *r.link_index]
            r.add(f"{field}[{k}]", f"unknown link '{name}'{did_you_mean(name, known)}")
            ok = False
    if value[0] == value[1]:
        r.add(field, f"a spring between link '{value[0]}' and itself (it needs two different links)")
        ok = False
    return (value[0], value[1]) if ok else None


def _points(r, entry: Mapping[str, Any], path: str):
    """``at``: two points, ``at[0]`` on ``links[0]``, ``at[1]`` on ``links[1]``."""
    if not r.present(entry, "at", path, REQUIRED, "one point on each link, [[x, y], [x, y]]"):
        return None
    value = entry["at"]
    if not isinstance(value, (list, tuple)) or len(value) != 2:
        got = json_kind(value) if not isinstance(value, (list, tuple)) else f"{len(value)} items"
        r.add(f"{path}.at", f"must be two points [[x, y], [x, y]] (one on each link), got {got}")
        return None
    points = [r.point({f"at[{k}]": v}, f"at[{k}]", path, position=True) for k, v in enumerate(value)]
    if points[0] is None or points[1] is None:
        return None
    return points[0], points[1]
