"""The ``joints`` section of a scene: each joint's type, links, point and axis.

:class:`JointSection`, a part of the scene reader of
:mod:`linkage_sym.scene.validate`, reads every joint -- revolute ``R``,
prismatic ``P``, and the extensions' gear mesh ``G`` (its fields and pitch
point: :mod:`~linkage_sym.scene.gears`) and cam contact ``cam``
(:mod:`~linkage_sym.scene.cams`) -- and keeps what later sections need to know
of it (:class:`JointInfo`).

Examples
--------
>>> print(joint_type_problem("pin"))
must be "R" (revolute), "P" (prismatic), "G" (gear mesh) or "cam" (cam contact), got "pin" (did you mean "R"?)
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, NamedTuple

from linkage_sym.model.scene import GROUND, Joint, Point
from linkage_sym.scene.cams import CAM_KEYS, read_cam_fields
from linkage_sym.scene.fields import ANGLE, REQUIRED, FieldReader, radians_or_none, show_value, did_you_mean
from linkage_sym.scene.friction import read_friction
from linkage_sym.scene.gears import GEAR_KEYS, MeshFields, place_meshes, read_mesh_fields

__all__ = ["JOINT_KEYS", "JOINT_TYPES", "JOINT_TYPE_NAMES", "JOINT_TYPE_SYNONYMS", "JointInfo",
           "JointSection", "joint_type_problem"]

JOINT_KEYS = ("name", "type", "links", "at", "axis_deg", *GEAR_KEYS, *CAM_KEYS, "friction")
JOINT_TYPES = ("R", "P", "G", "cam")
JOINT_TYPE_NAMES = {"R": "revolute", "P": "prismatic", "G": "gear mesh", "cam": "cam contact"}
"""What each joint type is (the format's ``R`` and ``P``, the extensions' ``G`` and ``cam``)."""
JOINT_TYPE_SYNONYMS = {
    "R": ("r", "revolute", "pin", "pinned", "hinge", "hinged", "rotary", "rotational", "turning"),
    "P": ("p", "prismatic", "slider", "sliding", "slide", "slot"),
    "G": ("g", "gear", "gears", "mesh", "gear mesh", "gear_mesh"),
    "cam": ("cam contact", "cam_contact", "cam joint"),
}
"""Words read as a joint type's name (compared lower-case): the error suggests the type."""


class JointInfo(NamedTuple):
    """What later sections need to know of a joint; ``None`` marks an invalid field."""

    index: int
    type: str | None
    links: tuple[str, str] | None
    at: Point | None


class JointSection(FieldReader):
    """The ``joints`` section, read into the reader's ``joints`` (name to :class:`JointInfo`),
    ``joints_ok`` and ``joint_points``; the joints' links are resolved against its
    ``link_index`` (the ``links`` section, read before)."""

    def read_joints(self, data: Mapping[str, Any]) -> tuple[Joint, ...]:
        entries = self.array(data, "joints", "")
        if entries is None:
            return ()
        self.joints = {}
        structure_ok = True
        joints: list[Joint | None] = []
        meshes: list[MeshFields] = []  # gear meshes: placed once every pivot is read
        for i, entry in enumerate(entries):
            path = f"joints[{i}]"
            before = len(self.problems)
            if not self.object(entry, path):
                structure_ok = False
                continue
            self.keys(entry, path, JOINT_KEYS)
            name = self.name(entry, "name", path)
            if name in self.joints:
                first = self.joints[name].index
                self.add(f"{path}.name", f"duplicate joint name '{name}' (first at joints[{first}])")
                structure_ok = False
            jtype = self.joint_type(entry, path)
            pair = self.joint_links(entry, path)
            gear = cam = None
            if jtype != "cam":
                self.forbid(entry, path, CAM_KEYS, f"on a {jtype or 'non-cam'} joint (only a cam contact)")
            if jtype == "G":  # a gear mesh: 'at' is its pitch point, computed when left out
                at = self.point(entry, "at", path, default=None)
                names = self.link_index
                gear = read_mesh_fields(self, entry, path, pair, names)
            else:
                at = self.point(entry, "at", path, position=True)
                self.joint_points.append(at)
                self.forbid(entry, path, GEAR_KEYS, f"on a {jtype or 'non-G'} joint (only a gear mesh, type G)")
                if jtype == "cam":  # a cam contact: 'at' is the follower's element point
                    if pair is not None and GROUND == pair[1]:
                        self.add(f"{path}.links[1]", "the follower of a cam contact must be a moving link")
                    cam = read_cam_fields(self, entry, path, at)
            axis = None
            if jtype in ("G", "cam") and "axis_deg" in entry:
                what = "a gear mesh" if jtype == "G" else "a cam contact"
                self.add(f"{path}.axis_deg", f"not allowed on {what} (only a P joint has an axis)")
            elif jtype == "P":
                why = "a P joint gives its slide direction"
                axis = radians_or_none(self.number(entry, "axis_deg", path, why=why, **ANGLE))
            elif jtype == "R" and "axis_deg" in entry:
                self.add(f"{path}.axis_deg", "not allowed on an R joint (only a P joint has an axis)")
            friction = read_friction(self, entry, path, jtype)  # contract part two
            if name is not None and name not in self.joints:
                self.joints[name] = JointInfo(i, jtype, pair, at)
            structure_ok = structure_ok and None not in (name, jtype, pair)
            if gear is not None and None not in gear:
                # a mesh is placed between its two gears: not without them (a scene whose
                # links are missing has no pair, and that problem is reported already)
                if len(self.problems) == before and pair is not None:
                    meshes.append(MeshFields(i, name, pair, at, *gear))
                    joints.append(None)
            elif len(self.problems) == before and cam is not None:
                joints.append(Joint(name, jtype, pair, at, cam=cam))
            elif len(self.problems) == before:
                joints.append(Joint(name, jtype, pair, at, axis, friction=friction))
        if meshes:
            placed = place_meshes(self, meshes, [j for j in joints if j is not None])
            for k, m in enumerate(meshes):
                if m.index in placed:
                    self.joint_points.append(placed[m.index].at)
                    self.joints[m.name] = self.joints[m.name]._replace(at=placed[m.index].at)
            order = iter(m.index for m in meshes)
            joints = [placed.get(next(order)) if j is None else j for j in joints]
            if len(placed) < len(meshes):
                self.joint_points.append(None)  # a mesh without its pitch point: no size check
        self.joints_ok = structure_ok
        return tuple(j for j in joints if j is not None)

    def joint_type(self, entry: Mapping[str, Any], path: str) -> str | None:
        if not self.present(entry, "type", path, REQUIRED, ""):
            return None
        value = entry["type"]
        if isinstance(value, str) and value in JOINT_TYPES:
            return value
        self.add(f"{path}.type", joint_type_problem(value))
        return None

    def joint_links(self, entry: Mapping[str, Any], path: str) -> tuple[str, str] | None:
        """The two link names of a joint, resolved against the links section."""
        if not self.present(entry, "links", path, REQUIRED, ""):
            return None
        value = entry["links"]
        field = f"{path}.links"
        if not isinstance(value, (list, tuple)) or len(value) != 2:
            self.add(field, f"must be an array of 2 link names, got {show_value(value)}")
            return None
        ok = True
        for i, name in enumerate(value):
            if not isinstance(name, str) or not name:
                self.add(f"{field}[{i}]", f"must be a non-empty link name, got {show_value(name)}")
                ok = False
            elif self.link_index is None:
                ok = False  # links section unusable: cannot resolve
            elif name != GROUND and name not in self.link_index:
                choices = [GROUND, *self.link_index]
                self.add(f"{field}[{i}]", f"unknown link '{name}'{did_you_mean(name, choices)}")
                ok = False
        if ok and value[0] == value[1]:
            self.add(field, f"both ends are link '{value[0]}'; a joint connects two different links")
            ok = False
        return (value[0], value[1]) if ok else None


def joint_type_problem(value: Any) -> str:
    """The reason a joint's ``type`` is refused: every accepted type named, and the one an
    obvious synonym means.

    Examples
    --------
    >>> print(joint_type_problem("revolute"))
    must be "R" (revolute), "P" (prismatic), "G" (gear mesh) or "cam" (cam contact), got "revolute" (did you mean "R"?)
    >>> joint_type_problem(3).endswith("got 3")
    True
    """
    kinds = [f'"{t}" ({JOINT_TYPE_NAMES[t]})' for t in JOINT_TYPES]
    out = f"must be {', '.join(kinds[:-1])} or {kinds[-1]}, got {show_value(value)}"
    if isinstance(value, str):
        word = " ".join(value.strip().lower().replace("-", " ").split())
        meant = next((t for t, words in JOINT_TYPE_SYNONYMS.items()
                      if word in words or word.replace(" ", "_") in words or word == t.lower()), None)
        if meant is not None:
            out += f' (did you mean "{meant}"?)'
    return out
