"""Validation of a scene mapping into the plain :mod:`linkage_sym.model` classes.

One pass over the mapping (the layout of ``docs/scene-format.md``)
collects *every* problem, each as ``"field.path: reason"``, and raises a
single :class:`~linkage_sym.errors.SceneError` listing them all.  Objects of
:mod:`linkage_sym.model.scene` are only built for entries without problems,
and a :class:`~linkage_sym.model.scene.Scene` only when there are none.

Structural checks (connectivity to the ground, then the Gruebler-Kutzbach
mobility against the number of drivers) run only when the names they rely on
are valid, so that one typo does not cascade into a page of noise.

Size: about 650 lines, the scene's sections and its structure checks, which
read each other's results (links before joints, joints before drivers, drivers
before loads); the field readers (:mod:`~linkage_sym.scene.fields`), the loads
over the cycle (:mod:`~linkage_sym.scene.schedules`) and the gear meshes
(:mod:`~linkage_sym.scene.gears`) are apart.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Mapping
from typing import Any, NamedTuple

from linkage_sym.errors import SceneError
from linkage_sym.scene.cams import CAM_KEYS, read_cam_fields
from linkage_sym.scene.gears import GEAR_KEYS, MeshFields, place_meshes, read_mesh_fields
from linkage_sym.scene.schedules import SCHEDULE_KEYS, read_schedule
from linkage_sym.scene.fields import (
    ANGLE,
    POINT_EXPECTED,
    REQUIRED,
    FieldReader,
    did_you_mean,
    json_kind,
    radians_or_none,
    show_value,
)
from linkage_sym.model.scene import (
    EXTENSION_OUTPUTS,
    GROUND,
    OUTPUTS,
    Driver,
    Effects,
    Joint,
    Link,
    Load,
    Point,
    Scene,
    TracedPoint,
)

__all__ = ["parse_scene", "value_problem", "MASS_RULE", "ANGLE_RULE"]

TOP_KEYS = ("name", "links", "joints", "drivers", "loads", "effects", "outputs", "points")
LINK_KEYS = ("name", "mass", "com", "inertia")
JOINT_KEYS = ("name", "type", "links", "at", "axis_deg", *GEAR_KEYS, *CAM_KEYS)
R_DRIVER_KEYS = ("toward", "start_deg", "stop_deg")
P_DRIVER_KEYS = ("start", "stop")
DRIVER_KEYS = ("joint", *R_DRIVER_KEYS, *P_DRIVER_KEYS, "steps", "speed", "acceleration")
LOAD_KEYS = ("link", "force", "at", "torque")
POINT_KEYS = ("name", "link", "at")
EFFECTS_KEYS = ("inertia", "gravity", "loads")
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

COINCIDENCE_TOLERANCE = 1e-9
"""Two joint points closer than this fraction of the mechanism's size coincide."""

MIN_SIZE = 1e-30
"""Smallest size (largest distance between two joints, m) of a mechanism.

Products of up to ten lengths of that size stay above float64's smallest normal
number (2.2e-308) instead of underflowing to 0.
"""

MAX_SPREAD = 1e9
"""Farthest a point may lie from the origin, in sizes of the mechanism.

A float64 keeps 16 significant digits of a coordinate: a point 1e9 sizes away
keeps 7 digits of the mechanism's geometry, and beyond it fewer.
"""

MAX_SWEEP_DEG = 360_000.0
"""Largest range ``|stop_deg - start_deg|`` of an R driver: 1000 turns.

The solver follows the mechanism in increments of at most 2 degrees, so such a
sweep is already 180 000 solving points.
"""

MAX_SLIDE = 1000.0
"""Largest ``|start|``, ``|stop|`` of a P driver, in sizes of the mechanism.

The solver follows a slide in increments of 2 % of the size (of 1 m when a single
joint gives no size), so such a sweep is already 150 000 solving points.
"""

MASS_RULE = {"minimum": 0.0}
"""The rule of a link's ``mass`` and ``inertia`` (besides every number's magnitude)."""

ANGLE_RULE = ANGLE
"""The rule of an angle in degrees (``axis_deg``, ``start_deg``, ``stop_deg``)."""


def value_problem(field: str, value: float, rule: Mapping[str, Any] | None = None) -> str | None:
    """The problem the scene reader reports for the number ``value`` at ``field``, or ``None``.

    The reader's own check (:meth:`FieldReader.number`), for a value that comes from
    elsewhere than a scene file -- a design of a sweep, say -- to be held to the rules
    of the field it would fill: every number finite and within
    :data:`~linkage_sym.scene.fields.MAX_MAGNITUDE`, and ``rule``'s own
    (:data:`MASS_RULE`, :data:`ANGLE_RULE`; default none besides).

    Examples
    --------
    >>> value_problem("links[1].mass", -1.0)
    >>> value_problem("links[1].mass", -1.0, MASS_RULE)
    'links[1].mass: must be a finite number >= 0, got -1.0'
    >>> value_problem("loads[0].torque", 0.5) is None
    True
    """
    reader = FieldReader()
    path, _, key = field.rpartition(".")
    reader.number({key: float(value)}, key, path, **(rule or {}))
    return reader.problems[0] if reader.problems else None


def parse_scene(data: Mapping[str, Any]) -> Scene:
    """Validate a parsed scene mapping and build the :class:`Scene` it describes.

    Angles given in degrees (``axis_deg``, ``start_deg``, ``stop_deg``) are
    stored in radians, numbers as floats, points as ``(x, y)`` tuples, and
    defaults are applied.

    Parameters
    ----------
    data : Mapping
        A scene in the file layout, e.g. the result of :func:`json.load`.

    Returns
    -------
    Scene
        The validated scene.

    Raises
    ------
    SceneError
        Listing every problem found, each as ``"field.path: reason"``.

    Examples
    --------
    A slider on a vertical guide, driven along it:

    >>> data = {
    ...     "name": "slider",
    ...     "links": [{"name": "block", "mass": 1, "com": [0, 0]}],
    ...     "joints": [{"name": "S", "type": "P", "links": ["ground", "block"],
    ...                 "at": [0, 0], "axis_deg": 90}],
    ...     "drivers": [{"joint": "S", "start": 0, "stop": 0.1, "steps": 11, "speed": 1}],
    ... }
    >>> scene = parse_scene(data)
    >>> scene.joints[0].axis == math.pi / 2, scene.drivers[0].kind, scene.links[0].mass
    (True, 'P', 1.0)

    Every problem is reported at once:

    >>> parse_scene(dict(data, name="", drivers=[
    ...     {"joint": "S", "start": 0, "stop": 0.1, "steps": 0, "spead": 1}]))
    Traceback (most recent call last):
      ...
    linkage_sym.errors.SceneError: invalid scene (4 problems):
      name: must be a non-empty string, got ""
      drivers[0].spead: unknown key (did you mean 'speed'?)
      drivers[0].steps: must be an integer >= 1, got 0
      drivers[0].speed: required key is missing
    """
    return _SceneReader().read(data)


class _JointInfo(NamedTuple):
    """What later sections need to know of a joint; ``None`` marks an invalid field."""

    index: int
    type: str | None
    links: tuple[str, str] | None
    at: Point | None


class _SceneReader(FieldReader):
    """Reads one scene mapping, collecting every problem on the way.

    ``link_index`` and ``joints`` are ``None`` when their section is not even
    an array, in which case references to them are not resolved.
    """

    def __init__(self) -> None:
        super().__init__()
        self.link_index: dict[str, int] | None = None
        self.links_ok = False
        self.joints: dict[str, _JointInfo] | None = None
        self.joints_ok = False
        self.drivers_ok = False
        self.slides: list[tuple[str, float]] = []  # every valid start/stop of a P driver
        self.joint_points: list[Point | None] = []  # every joint's `at`, None if invalid

    # -- sections ----------------------------------------------------------

    def read(self, data: Any) -> Scene:
        if not isinstance(data, Mapping):
            raise SceneError([f"scene: must be an object, got {json_kind(data)}"])
        self.keys(data, "", TOP_KEYS)
        name = self.name(data, "name", "")
        links = self.read_links(data)
        joints = self.read_joints(data)
        drivers = self.read_drivers(data)
        loads = self.read_loads(data, drivers)
        effects = self.read_effects(data)
        outputs = self.read_outputs(data)
        points = self.read_points(data)
        self.check_size()
        if self.links_ok and self.joints_ok and self.check_connected() and self.drivers_ok:
            self.check_mobility(len(data["drivers"]))
        if self.problems:
            raise SceneError(self.problems)
        assert name is not None and effects is not None and outputs is not None
        return Scene(name, links, joints, drivers, loads, effects, outputs, points)

    def read_links(self, data: Mapping[str, Any]) -> tuple[Link, ...]:
        entries = self.array(data, "links", "")
        if entries is None:
            return ()
        self.link_index = {}
        names_ok = True
        links = []
        for i, entry in enumerate(entries):
            path = f"links[{i}]"
            before = len(self.problems)
            if not self.object(entry, path):
                names_ok = False
                continue
            self.keys(entry, path, LINK_KEYS)
            name = self.name(entry, "name", path)
            if name == GROUND:
                self.add(f"{path}.name", f"'{GROUND}' is the fixed link and is never listed in links")
            elif name in self.link_index:
                first = self.link_index[name]
                self.add(f"{path}.name", f"duplicate link name '{name}' (first at links[{first}])")
            elif name is not None:
                self.link_index[name] = i
            names_ok = names_ok and name is not None and self.link_index.get(name) == i
            mass = self.number(entry, "mass", path, default=0.0, **MASS_RULE)
            com = self.point(entry, "com", path, default=None, position=True)
            if mass is not None and mass > 0 and "com" not in entry:
                self.missing(f"{path}.com", "a link with mass > 0 must give its centre of mass")
            inertia = self.number(entry, "inertia", path, default=0.0, **MASS_RULE)
            if len(self.problems) == before:
                links.append(Link(name, mass, com, inertia))
        self.links_ok = names_ok
        return tuple(links)

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
                axis = radians_or_none(self.number(entry, "axis_deg", path, why=why, **ANGLE_RULE))
            elif jtype == "R" and "axis_deg" in entry:
                self.add(f"{path}.axis_deg", "not allowed on an R joint (only a P joint has an axis)")
            if name is not None and name not in self.joints:
                self.joints[name] = _JointInfo(i, jtype, pair, at)
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
                joints.append(Joint(name, jtype, pair, at, axis))
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

    def read_drivers(self, data: Mapping[str, Any]) -> tuple[Driver, ...]:
        entries = self.array(data, "drivers", "")
        if entries is None:
            return ()
        if not entries:
            self.add("drivers", "must list at least one driver")
        driven: dict[str, int] = {}
        refs_ok = bool(entries)
        shared_steps: tuple[int, int] | None = None  # (steps, index of the driver giving it)
        drivers = []
        for i, entry in enumerate(entries):
            path = f"drivers[{i}]"
            before = len(self.problems)
            if not self.object(entry, path):
                refs_ok = False
                continue
            self.keys(entry, path, DRIVER_KEYS)
            joint = self.name(entry, "joint", path)
            info = None
            if joint is not None and self.joints is not None:
                info = self.joints.get(joint)
                if info is None:
                    self.add(f"{path}.joint", f"unknown joint '{joint}'{did_you_mean(joint, self.joints)}")
                elif info.type == "G":
                    self.add(f"{path}.joint", f"joint '{joint}' is a gear mesh; drive a gear's "
                             "pivot (an R joint) instead")
                    info = None
                elif info.type == "cam":
                    self.add(f"{path}.joint", f"joint '{joint}' is a cam contact; drive the cam's "
                             "pivot (an R joint) instead")
                    info = None
                elif joint in driven:
                    first = driven[joint]
                    self.add(f"{path}.joint", f"joint '{joint}' already has a driver (drivers[{first}])")
                else:
                    driven[joint] = i
            refs_ok = refs_ok and driven.get(joint) == i
            steps = self.integer(entry, "steps", path, minimum=1)
            if steps is not None and shared_steps is None:
                shared_steps = (steps, i)
            elif steps is not None and shared_steps is not None and steps != shared_steps[0]:
                self.add(
                    f"{path}.steps",
                    f"every driver must have the same steps: drivers[{shared_steps[1]}] has "
                    f"{shared_steps[0]}, got {steps}",
                )
            speed = self.number(entry, "speed", path)
            acceleration = self.number(entry, "acceleration", path, default=0.0)
            kind = None if info is None else info.type
            start, stop, toward, degrees = self.driver_range(entry, path, info)
            if kind is not None and len(self.problems) == before:
                drivers.append(Driver(joint, kind, start, stop, steps, speed, acceleration, toward,
                                      *degrees))
        self.drivers_ok = refs_ok
        return tuple(drivers)

    def driver_range(
        self, entry: Mapping[str, Any], path: str, info: _JointInfo | None
    ) -> tuple[float | None, float | None, str | None, tuple]:
        """``start``, ``stop`` (radians or metres) and ``toward`` of a driver on joint ``info``,
        and an ``R`` driver's ``(start_deg, stop_deg)`` as given (``()`` for the others)."""
        kind = None if info is None else info.type
        joint = entry.get("joint")
        if kind == "R":
            where = f"on a driver of R joint '{joint}'"
            self.forbid(entry, path, P_DRIVER_KEYS, f"{where} (give start_deg/stop_deg in degrees)")
            why = f"a driver of R joint '{joint}' needs it"
            assert info is not None
            toward = self.toward(entry, path, joint, info)
            start = self.number(entry, "start_deg", path, why=why, **ANGLE)
            stop = self.number(entry, "stop_deg", path, why=why, **ANGLE)
            if start is not None and stop is not None and abs(stop - start) > MAX_SWEEP_DEG:
                self.add(
                    f"{path}.stop_deg",
                    f"the sweep from start_deg {start:g} to stop_deg {stop:g} covers "
                    f"{abs(stop - start) / 360:.0f} turns; at most {MAX_SWEEP_DEG / 360:.0f} "
                    f"({MAX_SWEEP_DEG:.0f} degrees) are allowed: the solver follows the mechanism "
                    "in increments of at most 2 degrees",
                )
            return radians_or_none(start), radians_or_none(stop), toward, (start, stop)
        if kind == "P":
            where = f"on a driver of P joint '{joint}'"
            self.forbid(entry, path, ("toward",), where)
            self.forbid(entry, path, ("start_deg", "stop_deg"), f"{where} (give start/stop in metres)")
            why = f"a driver of P joint '{joint}' needs it"
            start = self.number(entry, "start", path, why=why)
            stop = self.number(entry, "stop", path, why=why)
            for key, value in (("start", start), ("stop", stop)):
                if value is not None:
                    self.slides.append((f"{path}.{key}", value))
            return start, stop, None, ()
        # The kind is unknown (a problem already reported): check only what is given.
        if "toward" in entry:
            self.name(entry, "toward", path)
        for key in (*R_DRIVER_KEYS[1:], *P_DRIVER_KEYS):
            self.number(entry, key, path, default=None)
        return None, None, None, ()

    def read_loads(self, data: Mapping[str, Any], drivers=()) -> tuple[Load, ...]:
        if "loads" not in data:
            return ()
        entries = self.array(data, "loads", "")
        if entries is None:
            return ()
        loads = []
        for i, entry in enumerate(entries):
            path = f"loads[{i}]"
            before = len(self.problems)
            if not self.object(entry, path):
                continue
            self.keys(entry, path, LOAD_KEYS + SCHEDULE_KEYS)
            link = self.name(entry, "link", path)
            if link == GROUND:
                self.add(f"{path}.link", f"loads act on moving links, not on '{GROUND}'")
            elif link is not None and self.link_index is not None and link not in self.link_index:
                self.add(f"{path}.link", f"unknown link '{link}'{did_you_mean(link, self.link_index)}")
            force = self.point(entry, "force", path, default=None)
            at = self.point(entry, "at", path, default=None, position=True)
            torque = self.number(entry, "torque", path, default=0.0)
            if "force" in entry and "at" not in entry:
                self.missing(f"{path}.at", "a force needs the point where it acts")
            elif "at" in entry and "force" not in entry:
                self.missing(f"{path}.force", "an 'at' point is given")
            elif "force" not in entry and "torque" not in entry:
                self.add(path, "a load needs a 'force' (with 'at') or a 'torque'")
            schedule = read_schedule(self, entry, path, drivers)
            # no schedule without a problem of its own: the drivers it follows were refused
            if len(self.problems) == before and schedule is not None:
                table, active, driver, period = schedule
                loads.append(Load(link, force, at, torque, table, active, driver, period))
        return tuple(loads)

    def read_points(self, data: Mapping[str, Any]) -> tuple[TracedPoint, ...]:
        """``points`` (an extension of the format): named points fixed on moving links."""
        if "points" not in data:
            return ()
        entries = self.array(data, "points", "")
        if entries is None:
            return ()
        seen: dict[str, int] = {}
        points = []
        for i, entry in enumerate(entries):
            path = f"points[{i}]"
            before = len(self.problems)
            if not self.object(entry, path):
                continue
            self.keys(entry, path, POINT_KEYS)
            name = self.name(entry, "name", path)
            if name in seen:
                self.add(f"{path}.name", f"duplicate point name '{name}' (first at points[{seen[name]}])")
            elif name is not None and self.joints is not None and name in self.joints:
                first = self.joints[name].index
                self.add(f"{path}.name", f"'{name}' already names joints[{first}]; a point needs its own name")
            elif name is not None:
                seen[name] = i
            link = self.name(entry, "link", path)
            if link == GROUND:
                self.add(f"{path}.link", f"a point on '{GROUND}' does not move; points trace moving links")
            elif link is not None and self.link_index is not None and link not in self.link_index:
                self.add(f"{path}.link", f"unknown link '{link}'{did_you_mean(link, self.link_index)}")
            at = self.point(entry, "at", path, position=True)
            if len(self.problems) == before:
                points.append(TracedPoint(name, link, at))
        return tuple(points)

    def read_effects(self, data: Mapping[str, Any]) -> Effects | None:
        if "effects" not in data:
            return Effects()
        effects = data["effects"]
        if not self.object(effects, "effects"):
            return None
        self.keys(effects, "effects", EFFECTS_KEYS)
        inertia = self.boolean(effects, "inertia", "effects", default=False)
        loads = self.boolean(effects, "loads", "effects", default=True)
        gravity = effects.get("gravity")
        if gravity is None or gravity is False:
            gravity = None
        else:
            gravity = self.point(effects, "gravity", "effects", expected=f"false, null or {POINT_EXPECTED}")
        return Effects(inertia, gravity, loads)

    def read_outputs(self, data: Mapping[str, Any]) -> tuple[str, ...] | None:
        if "outputs" not in data:
            return OUTPUTS
        entries = self.array(data, "outputs", "")
        if entries is None:
            return None
        seen: dict[str, int] = {}
        known = OUTPUTS + EXTENSION_OUTPUTS  # the contract's and linkage_sym's extensions
        for i, entry in enumerate(entries):
            path = f"outputs[{i}]"
            expected = f"one of {', '.join(known)}"
            if not isinstance(entry, str):
                self.add(path, f"must be {expected}, got {show_value(entry)}")
            elif entry not in known:
                self.add(path, f"unknown output '{entry}'{did_you_mean(entry, known)}; expected {expected}")
            elif entry in seen:
                self.add(path, f"output '{entry}' is listed twice (also outputs[{seen[entry]}])")
            else:
                seen[entry] = i
        return tuple(entries)

    # -- cross-field checks ------------------------------------------------

    def toward(self, entry: Mapping[str, Any], path: str, joint: str, info: _JointInfo) -> str | None:
        """The ``toward`` joint of a driver on R joint ``joint``, checked against it."""
        toward = self.name(entry, "toward", path, why=f"a driver of R joint '{joint}' needs it")
        if toward is None or self.joints is None:
            return toward
        field = f"{path}.toward"
        other = self.joints.get(toward)
        if other is None:
            self.add(field, f"unknown joint '{toward}'{did_you_mean(toward, self.joints)}")
            return toward
        if toward == joint:
            self.add(field, f"must name a joint other than the driven joint '{joint}'")
            return toward
        if other.type == "G":  # the gear's radius to the mesh's pitch point in the assembly
            if info.links is not None and other.links is not None and info.links[1] not in other.links:
                self.add(field, f"gear mesh '{toward}' does not mesh link '{info.links[1]}' "
                         f"(links[1] of the driven joint '{joint}')")
            return toward
        if other.type == "cam":  # the follower's element point in the assembly: a direction
            if info.links is not None and other.links is not None and info.links[1] not in other.links:
                self.add(field, f"cam contact '{toward}' does not join link '{info.links[1]}' "
                         f"(links[1] of the driven joint '{joint}')")
            return toward
        if info.links is not None and other.links is not None:
            driven_link = info.links[1]
            if driven_link not in other.links:
                self.add(
                    field,
                    f"joint '{toward}' is not on link '{driven_link}' "
                    f"(links[1] of the driven joint '{joint}')",
                )
            elif other.type == "P" and other.links[0] == driven_link:
                self.add(
                    field,
                    f"P joint '{toward}' slides along link '{driven_link}': its point is fixed on "
                    f"'{other.links[1]}', not on '{driven_link}'",
                )
        if info.at is not None and other.at is not None and self.coincide(info.at, other.at):
            self.add(field, f"joint '{toward}' is at the same point as the driven joint '{joint}'")
        return toward

    def coincide(self, a: Point, b: Point) -> bool:
        """Whether two points are the same, relative to the size of the mechanism."""
        assert self.joints is not None
        points = [j.at for j in self.joints.values() if j.at is not None]
        size = max((math.dist(p, q) for p in points for q in points), default=0.0)
        # joints all at one point are reported once, by check_size
        return size > 0 and math.dist(a, b) <= COINCIDENCE_TOLERANCE * size

    def check_size(self) -> None:
        """The mechanism's size, and every point and slide against it.

        The size is the largest distance between two joints (the length the
        solver divides lengths by); it is checked only when every joint's
        point is valid.
        """
        if not self.joint_points or None in self.joint_points:
            return
        points = self.joint_points
        size = max(math.dist(p, q) for p in points for q in points)
        if len(points) >= 2 and size == 0:
            x, y = points[0]
            self.add(
                "joints",
                f"all {len(points)} joints are at the same point [{x:g}, {y:g}]: the mechanism "
                "has no size (the largest distance between two joints, by which the solver makes "
                "lengths dimensionless, is 0)",
            )
            return
        if 0 < size < MIN_SIZE:
            self.add(
                "joints",
                f"the mechanism's size (the largest distance between two joints) is {size:.3g} m, "
                f"below {MIN_SIZE:.0e} m: the solver squares and multiplies lengths, and such "
                "products would underflow float64 (smallest normal number 2.2e-308)",
            )
            return
        if size > 0:
            for field, point in self.positions:
                distance = math.hypot(*point)
                if distance > MAX_SPREAD * size:
                    self.add(
                        field,
                        f"is {distance:.3g} m from the origin, more than {MAX_SPREAD:.0e} times "
                        f"the mechanism's size ({size:.3g} m, the largest distance between two "
                        "joints): float64 keeps 16 digits of a coordinate, so fewer than 7 of the "
                        "mechanism's geometry would be left",
                    )
        scale = size if size > 0 else 1.0
        for field, value in self.slides:
            if abs(value) > MAX_SLIDE * scale:
                self.add(
                    field,
                    f"must be within +-{MAX_SLIDE * scale:.3g} m, {MAX_SLIDE:.0f} times the "
                    f"mechanism's size ({scale:.3g} m): the solver follows a slide in increments "
                    f"of 2% of the size, got {value:g}",
                )

    def check_connected(self) -> bool:
        """Report links in no joint or not connected to the ground; ``True`` if none."""
        assert self.link_index is not None and self.joints is not None
        neighbours: dict[str, set[str]] = {GROUND: set(), **{name: set() for name in self.link_index}}
        for info in self.joints.values():
            assert info.links is not None
            a, b = info.links
            neighbours[a].add(b)
            neighbours[b].add(a)
        reached = {GROUND}
        queue = deque([GROUND])
        while queue:
            for other in neighbours[queue.popleft()] - reached:
                reached.add(other)
                queue.append(other)
        ok = True
        for name, i in self.link_index.items():
            if not neighbours[name]:
                self.add(f"links[{i}]", f"link '{name}' appears in no joint")
                ok = False
            elif name not in reached:
                self.add(f"links[{i}]", f"link '{name}' is not connected to the ground")
                ok = False
        return ok

    def check_mobility(self, n_drivers: int) -> None:
        """Gruebler-Kutzbach: the mobility must equal the number of drivers."""
        assert self.link_index is not None and self.joints is not None
        n_links = len(self.link_index)
        n_meshes = sum(j.type in ("G", "cam") for j in self.joints.values())
        n_joints = len(self.joints) - n_meshes
        mobility = 3 * n_links - 2 * n_joints - n_meshes
        if mobility != n_drivers:
            higher = f" - {n_meshes}" if n_meshes else ""
            n_cams = sum(j.type == "cam" for j in self.joints.values())
            kinds = [f"{n} {what}" for n, what in ((n_meshes - n_cams, "gear meshes"),
                                                   (n_cams, "cam contacts")) if n]
            meshes = f", {' and '.join(kinds)} (higher pairs)" if n_meshes else ""
            self.add(
                "drivers",
                f"{n_drivers} driver{'s' if n_drivers != 1 else ''} given but the mobility is "
                f"M = 3*{n_links} - 2*{n_joints}{higher} = {mobility} (Gruebler-Kutzbach, {n_links} "
                f"moving links, {n_joints} joints{meshes}); the number of drivers must equal M",
            )

    # -- field readers: report a problem and return None when invalid ------

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
