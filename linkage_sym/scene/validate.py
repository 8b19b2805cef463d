"""Validation of a scene mapping into the plain :mod:`linkage_sym.model` classes.

One pass over the mapping (the layout of ``docs/scene-format.md``)
collects *every* problem, each as ``"field.path: reason"``, and raises a
single :class:`~linkage_sym.errors.SceneError` listing them all.  Objects of
:mod:`linkage_sym.model.scene` are only built for entries without problems,
and a :class:`~linkage_sym.model.scene.Scene` only when there are none.

Structural checks (connectivity to the ground, then the Gruebler-Kutzbach
mobility against the number of drivers) run only when the names they rely on
are valid, so that one typo does not cascade into a page of noise.

The sections read each other's results (links before joints, joints before
drivers, drivers before loads), so one reader holds them all; it is built of
parts, each a module: the joints (:mod:`~linkage_sym.scene.joints`), the
drivers (:mod:`~linkage_sym.scene.drivers`) and the checks across sections
(:mod:`~linkage_sym.scene.checks`); this module reads the links, loads,
points, effects and outputs.  The field readers
(:mod:`~linkage_sym.scene.fields`), the loads over the cycle
(:mod:`~linkage_sym.scene.schedules`), the gear meshes
(:mod:`~linkage_sym.scene.gears`), the cam contacts
(:mod:`~linkage_sym.scene.cams`) and the springs (:mod:`~linkage_sym.scene.springs`)
are apart too.  The public names of the
joints, drivers and checks modules are importable from here.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from linkage_sym.errors import SceneError
from linkage_sym.model.scene import (
    EXTENSION_OUTPUTS,
    GROUND,
    OUTPUTS,
    Effects,
    Link,
    Load,
    Point,
    Scene,
    TracedPoint,
)
# the names of the joints, drivers and checks: importable from here, as before the split
from linkage_sym.scene.checks import (  # noqa: F401
    COINCIDENCE_TOLERANCE,
    MAX_SLIDE,
    MAX_SPREAD,
    MIN_SIZE,
    SceneChecks,
)
from linkage_sym.scene.drivers import (  # noqa: F401
    DRIVER_KEYS,
    MAX_SWEEP_DEG,
    P_DRIVER_KEYS,
    R_DRIVER_KEYS,
    DriverSection,
)
from linkage_sym.scene.fields import ANGLE, POINT_EXPECTED, FieldReader, json_kind, show_value, did_you_mean
from linkage_sym.scene.joints import (  # noqa: F401
    JOINT_KEYS,
    JOINT_TYPE_NAMES,
    JOINT_TYPE_SYNONYMS,
    JOINT_TYPES,
    JointSection,
    JointInfo,
    joint_type_problem,
)
from linkage_sym.scene.motors import read_simulation
from linkage_sym.scene.schedules import SCHEDULE_KEYS, read_schedule
from linkage_sym.scene.springs import read_springs, springs_effect

__all__ = ["parse_scene", "value_problem", "MASS_RULE", "ANGLE_RULE"]

TOP_KEYS = ("name", "links", "joints", "drivers", "loads", "effects", "outputs", "points", "springs",
            "simulate")
LINK_KEYS = ("name", "mass", "com", "inertia")
LOAD_KEYS = ("link", "force", "at", "torque")
POINT_KEYS = ("name", "link", "at")
EFFECTS_KEYS = ("inertia", "gravity", "loads", "springs", "friction")

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
    >>> import math
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


class _SceneReader(JointSection, DriverSection, SceneChecks):
    """Reads one scene mapping, collecting every problem on the way.

    ``link_index`` and ``joints`` are ``None`` when their section is not even
    an array, in which case references to them are not resolved.
    """

    def __init__(self) -> None:
        super().__init__()
        self.link_index: dict[str, int] | None = None
        self.links_ok = False
        self.joints: dict[str, JointInfo] | None = None
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
        springs = read_springs(self, data)  # the contract's springs and dampers
        n_drivers = len(data["drivers"]) if isinstance(data.get("drivers"), list) else 0
        simulate = read_simulation(self, data, drivers, n_drivers)
        self.check_size()
        if self.links_ok and self.joints_ok and self.check_connected() and self.drivers_ok:
            self.check_mobility(len(data["drivers"]))
        if self.problems:
            raise SceneError(self.problems)
        assert name is not None and effects is not None and outputs is not None
        return Scene(name, links, joints, drivers, loads, effects, outputs, points, springs,
                     simulate)

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
        taken = None if self.joints is None else {
            joint: f"joints[{info.index}]" for joint, info in self.joints.items()}
        points = []
        for path, entry, name, before in self.named_entries(data, "points", POINT_KEYS, "point",
                                                            taken=taken):
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
            return Effects(springs=springs_effect(self, None, data))
        effects = data["effects"]
        if not self.object(effects, "effects"):
            return None
        self.keys(effects, "effects", EFFECTS_KEYS)
        inertia = self.boolean(effects, "inertia", "effects", default=False)
        loads = self.boolean(effects, "loads", "effects", default=True)
        friction = self.boolean(effects, "friction", "effects", default=False)
        gravity = effects.get("gravity")
        if gravity is None or gravity is False:
            gravity = None
        else:
            gravity = self.point(effects, "gravity", "effects", expected=f"false, null or {POINT_EXPECTED}")
        return Effects(inertia, gravity, loads, springs=springs_effect(self, effects, data),
                       friction=bool(friction))

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
