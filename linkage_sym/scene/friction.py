"""The ``friction`` field of a joint (contract, second part: "Machine effects and motion").

An ``R`` joint's friction is ``{"coefficient": f, "radius": r}`` (the pin's
radius, m; its friction circle has radius ``f r``), a ``P`` joint's
``{"coefficient": f}``.  It acts when the scene's ``effects.friction`` is
true (default false).  Gear meshes and cam contacts carry no friction (the
field is refused on them: the force solvers have no friction model for a
higher pair).

Examples
--------
>>> from linkage_sym.scene.fields import FieldReader
>>> r = FieldReader()
>>> read_friction(r, {"friction": {"coefficient": 0.15, "radius": 0.005}}, "joints[1]", "R")
JointFriction(coefficient=0.15, radius=0.005)
>>> read_friction(r, {"friction": {"coefficient": 0.1, "radius": 0.01}}, "joints[2]", "P")
>>> r.problems
['joints[2].friction.radius: not allowed on a P joint (only an R joint has a pin radius)']
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from linkage_sym.model.scene import JointFriction
from linkage_sym.scene.fields import FieldReader

__all__ = ["FRICTION_KEYS", "read_friction"]

FRICTION_KEYS = ("coefficient", "radius")
"""The keys of a joint's ``friction`` object."""


def read_friction(reader: FieldReader, entry: Mapping[str, Any], path: str,
                  jtype: str | None) -> JointFriction | None:
    """The joint's :class:`JointFriction` (``None``: no ``friction`` key, or a problem
    recorded in ``reader`` naming the field).

    Refused: friction on a gear mesh or cam contact, a negative coefficient, a
    missing or non-positive ``radius`` on an ``R`` joint, a ``radius`` on a
    ``P`` joint, unknown keys.
    """
    if "friction" not in entry:
        return None
    where = f"{path}.friction"
    if jtype in ("G", "cam"):
        what = "a gear mesh" if jtype == "G" else "a cam contact"
        reader.add(where, f"not allowed on {what} (only R and P joints have a friction model)")
        return None
    value = entry["friction"]
    if not reader.object(value, where):
        return None
    before = len(reader.problems)
    reader.keys(value, where, FRICTION_KEYS)
    f = reader.number(value, "coefficient", where, minimum=0.0,
                      why="the friction coefficient f of the joint")
    radius = None
    if jtype == "P":
        if "radius" in value:
            reader.add(f"{where}.radius", "not allowed on a P joint (only an R joint has a pin radius)")
    elif jtype == "R":
        radius = reader.number(value, "radius", where, why="an R joint's pin radius (m)")
        if radius is not None and radius <= 0:
            reader.add(f"{where}.radius", f"must be > 0 (the pin's radius, m), got {radius:g}")
    if len(reader.problems) > before or f is None or jtype is None:
        return None
    return JointFriction(f, radius)
