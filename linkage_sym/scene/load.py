"""Scene files: reading one into a validated :class:`Scene`, and writing a scene back.

:func:`load_scene` reads JSON (a path) or takes an already-parsed mapping and
hands it to :func:`~linkage_sym.scene.validate.parse_scene`; :func:`dump_scene`
is its inverse, back to the file layout of ``docs/scene-format.md``.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Mapping
from typing import Any

from linkage_sym.errors import SceneError
from linkage_sym.model.scene import Driver, Effects, Joint, Link, Load, Scene
from linkage_sym.scene.validate import parse_scene

__all__ = ["dump_scene", "load_scene"]


def load_scene(source: str | os.PathLike[str] | Mapping[str, Any]) -> Scene:
    """Load and validate a scene from a JSON file or an already-parsed mapping.

    Parameters
    ----------
    source : str, os.PathLike or Mapping
        Path of a JSON scene file, or the scene itself as a mapping in the
        file layout.

    Returns
    -------
    Scene
        The validated scene, angles in radians and defaults applied.

    Raises
    ------
    SceneError
        If the file is missing, unreadable or not valid JSON (naming the file,
        and the line and column of a syntax error), or if the scene is invalid
        (listing every problem as ``"field.path: reason"``).
    TypeError
        If ``source`` is neither a path nor a mapping.

    Examples
    --------
    >>> scene = load_scene({
    ...     "name": "slider",
    ...     "links": [{"name": "block", "mass": 2.0, "com": [0.0, 0.0]}],
    ...     "joints": [{"name": "S", "type": "P", "links": ["ground", "block"],
    ...                 "at": [0.0, 0.0], "axis_deg": 0}],
    ...     "drivers": [{"joint": "S", "start": 0.0, "stop": 0.1, "steps": 11, "speed": 0.5}],
    ... })
    >>> scene.drivers[0]
    Driver(joint='S', kind='P', start=0.0, stop=0.1, steps=11, speed=0.5, acceleration=0.0, toward=None)
    >>> scene.effects, scene.outputs
    (Effects(inertia=False, gravity=None, loads=True, springs=False, friction=False), ('kinematics', 'reactions', 'driving', 'frame'))
    >>> load_scene("no/such/scene.json")
    Traceback (most recent call last):
      ...
    linkage_sym.errors.SceneError: invalid scene (1 problem):
      no/such/scene.json: no such file
    """
    if isinstance(source, Mapping):
        return parse_scene(source)
    if isinstance(source, (str, os.PathLike)):
        return parse_scene(_read_json(os.fspath(source)))
    raise TypeError(f"load_scene() takes a path or a mapping, not {type(source).__name__}")


def _read_json(path: str) -> Any:
    """The parsed contents of a JSON file; any failure is a :class:`SceneError`."""
    try:
        with open(path, encoding="utf-8-sig") as file:
            text = file.read()
    except FileNotFoundError as err:
        raise SceneError([f"{path}: no such file"]) from err
    except OSError as err:
        raise SceneError([f"{path}: cannot be read ({err.strerror or err})"]) from err
    except UnicodeDecodeError as err:
        raise SceneError([f"{path}: not UTF-8 text (byte {err.start})"]) from err
    try:
        value = json.loads(text, object_pairs_hook=_JSONObject.from_pairs)
        repeated = list(_repeated_keys(value, ""))
    except json.JSONDecodeError as err:
        raise SceneError([f"{path}: line {err.lineno}, column {err.colno}: invalid JSON: {err.msg}"]) from err
    except RecursionError as err:  # arrays or objects nested some thousand levels deep
        raise SceneError([f"{path}: invalid JSON for a scene: nested deeper than Python's JSON "
                          "reader goes (a scene nests a few levels)"]) from err
    if repeated:
        # json.loads keeps the last of repeated keys silently; a scene must not
        raise SceneError([f"{path}: {field}: given more than once" for field in repeated])
    return value


class _JSONObject(dict):
    """A JSON object that remembers the keys its text gave more than once."""

    repeated: tuple = ()

    @classmethod
    def from_pairs(cls, pairs):
        obj = cls()
        repeated = []
        for key, val in pairs:
            if key in obj and key not in repeated:
                repeated.append(key)
            obj[key] = val
        if repeated:
            obj.repeated = tuple(repeated)
        return obj


def _repeated_keys(value, where):
    """Field paths (``joints[3].at``) of every key given more than once, in file order."""
    if isinstance(value, dict):
        for key in getattr(value, "repeated", ()):
            yield f"{where}.{key}" if where else key
        for key, val in value.items():
            yield from _repeated_keys(val, f"{where}.{key}" if where else key)
    elif isinstance(value, list):
        for i, val in enumerate(value):
            yield from _repeated_keys(val, f"{where}[{i}]")


def dump_scene(scene: Scene) -> dict[str, Any]:
    """A scene in the file layout: the inverse of :func:`parse_scene`.

    Angles go back to degrees (``axis_deg``, and ``start_deg``/``stop_deg`` of
    ``R`` drivers; ``P`` drivers keep ``start``/``stop`` in metres).  Every
    default is written out, except absent optional values (``com``, a load's
    force, gravity), ``points`` and ``springs`` when there are none, and
    ``effects.springs`` when false.
    ``parse_scene(dump_scene(s)) == s`` for every scene ``s`` that
    :func:`parse_scene` produces.

    Parameters
    ----------
    scene : Scene
        The scene to write.

    Returns
    -------
    dict
        JSON-serialisable mapping (lists, not tuples).

    Examples
    --------
    >>> from linkage_sym.model import Driver, Joint, Link
    >>> scene = Scene("s", (Link("block"),),
    ...               (Joint("S", "P", ("ground", "block"), (0.0, 0.0), math.pi / 2),),
    ...               (Driver("S", "P", 0.0, 0.1, 11, 0.5),))
    >>> dump_scene(scene)["joints"]
    [{'name': 'S', 'type': 'P', 'links': ['ground', 'block'], 'at': [0.0, 0.0], 'axis_deg': 90.0}]
    """
    out = {
        "name": scene.name,
        "links": [_dump_link(link) for link in scene.links],
        "joints": [_dump_joint(joint) for joint in scene.joints],
        "drivers": [_dump_driver(driver) for driver in scene.drivers],
        "loads": [_dump_load(load) for load in scene.loads],
        "effects": _dump_effects(scene.effects),
        "outputs": list(scene.outputs),
    }
    if scene.points:  # an extension of the format: written only when used
        out["points"] = [{"name": p.name, "link": p.link, "at": list(p.at)} for p in scene.points]
    if scene.springs:  # the contract's second part: written only when used
        out["springs"] = [_dump_spring(k) for k in scene.springs]
        out["effects"]["springs"] = scene.effects.springs  # false too: true is the default then
    if scene.simulate is not None:  # the contract's second part: written only when given
        out["simulate"] = _dump_simulation(scene)
    return out


def _dump_spring(spring) -> dict[str, Any]:
    """A spring in the file layout (its free length or angle written out)."""
    out: dict[str, Any] = {"name": spring.name}
    if spring.joint is not None:
        out.update(joint=spring.joint, stiffness=spring.stiffness,
                   free_angle_deg=spring.free_angle_deg)
    else:
        out.update(links=list(spring.links), at=[list(p) for p in spring.at],
                   stiffness=spring.stiffness, free_length=spring.free_length)
    out["damping"] = spring.damping
    return out


def _dump_link(link: Link) -> dict[str, Any]:
    out: dict[str, Any] = {"name": link.name, "mass": link.mass}
    if link.com is not None:
        out["com"] = list(link.com)
    out["inertia"] = link.inertia
    return out


def _dump_joint(joint: Joint) -> dict[str, Any]:
    out: dict[str, Any] = {
        "name": joint.name,
        "type": joint.type,
        "links": list(joint.links),
        "at": list(joint.at),
    }
    if joint.axis is not None:
        out["axis_deg"] = _degrees(joint.axis)
    if joint.type == "G":  # a gear mesh (an extension of the format)
        out["carrier"] = joint.carrier
        out["radii"] = list(joint.radii)
        out["internal"] = joint.internal
        out["pressure_angle_deg"] = _degrees(joint.pressure_angle)
    elif joint.type == "cam":  # a cam contact (an extension of the format)
        out.update(_dump_cam(joint.cam))
    if joint.friction is not None:  # contract part two: written only when given
        out["friction"] = {"coefficient": joint.friction.coefficient}
        if joint.friction.radius is not None:
            out["friction"]["radius"] = joint.friction.radius
    return out


def _dump_cam(cam) -> dict[str, Any]:
    """A cam contact's ``profile`` and ``follower`` in the file layout."""
    if cam.profile == "circle":
        centre, R = cam.data
        body: Any = {"centre": list(centre), "radius": R}
    elif cam.profile == "polar":
        centre, phi, r = cam.data
        body = {"centre": list(centre), "phi_deg": [_degrees(v) for v in phi], "r": list(r)}
    else:
        (points,) = cam.data
        body = [list(p) for p in points]
    profile: dict[str, Any] = {cam.profile: body}
    if cam.pitch:
        profile["pitch"] = True
    follower: dict[str, Any] = {"kind": cam.follower}
    if cam.follower == "roller":
        follower["radius"] = cam.radius
    if cam.follower == "flat":
        follower["face_deg"] = _degrees(cam.face)
    return {"profile": profile, "follower": follower}


def _dump_driver(driver: Driver) -> dict[str, Any]:
    out: dict[str, Any] = {"joint": driver.joint}
    if driver.kind == "R":
        out["toward"] = driver.toward
        out["start_deg"] = _given_degrees(driver.start_deg, driver.start)
        out["stop_deg"] = _given_degrees(driver.stop_deg, driver.stop)
    else:
        out["start"] = driver.start
        out["stop"] = driver.stop
    out["steps"] = driver.steps
    out["speed"] = driver.speed
    out["acceleration"] = driver.acceleration
    if driver.motor is not None:  # the contract's second part: written only when given
        m = driver.motor
        value: Any = (m.efforts[0] if len(m.speeds) == 1 and m.speeds[0] == 0.0
                      else [[v, e] for v, e in zip(m.speeds, m.efforts)])
        out["motor"] = {m.kind: value}
    return out


def _dump_simulation(scene: Scene) -> dict[str, Any]:
    """The ``simulate`` section in the file layout (the start in the driver's units)."""
    sim = scene.simulate
    out: dict[str, Any] = {"duration": sim.duration}
    if isinstance(sim.start, tuple):  # several drivers: lists over them, null for the other kind
        out["start_deg"] = [_degrees(v) if d.kind == "R" else None
                            for d, v in zip(scene.drivers, sim.start)]
        out["start"] = [v if d.kind == "P" else None for d, v in zip(scene.drivers, sim.start)]
        for key in ("start_deg", "start"):
            if all(v is None for v in out[key]):
                del out[key]
        out["start_speed"] = list(sim.start_speed)
        out["samples"] = sim.samples
        return out
    if scene.drivers and scene.drivers[0].kind == "R":
        out["start_deg"] = _degrees(sim.start)
    else:
        out["start"] = sim.start
    out["start_speed"] = sim.start_speed
    out["samples"] = sim.samples
    return out


def _dump_load(load: Load) -> dict[str, Any]:
    out: dict[str, Any] = {"link": load.link}
    if load.force is not None:
        out["force"] = list(load.force)
    if load.at is not None:
        out["at"] = list(load.at)
    if load.torque != 0.0 or load.force is None:
        out["torque"] = load.torque
    if load.driver is not None:  # a load over the cycle (an extension of the format)
        out["driver"] = load.driver
        R = load.period is not None
        unit = _degrees if R else float  # degrees that read back to the same radians
        if R and load.period != 2 * math.pi:
            out["period_deg"] = _degrees(load.period)
        if load.table is not None:
            out["table"] = {"q_deg" if R else "q": [unit(v) for v in load.table.q],
                            "scale": list(load.table.scale)}
        if load.active is not None:
            out["active_deg" if R else "active"] = [unit(v) for v in load.active]
    return out


def _dump_effects(effects: Effects) -> dict[str, Any]:
    out: dict[str, Any] = {"inertia": effects.inertia}
    if effects.gravity is not None:
        out["gravity"] = list(effects.gravity)
    out["loads"] = effects.loads
    if effects.springs:  # the contract's second part: written only when they act
        out["springs"] = True
    if effects.friction:  # contract part two: written only when true (its default is false)
        out["friction"] = True
    return out


def _given_degrees(degrees: float | None, angle: float) -> float:
    """The degrees a scene gave for ``angle`` (kept on its driver) while they still convert to
    it, else :func:`_degrees`: a scene written and read back has the same driver numbers."""
    if degrees is not None and math.radians(degrees) == angle:
        return degrees
    return _degrees(angle)


def _degrees(angle: float) -> float:
    """Degrees that :func:`math.radians` turns back into exactly ``angle``.

    ``math.radians(math.degrees(a)) == a`` does not always hold, so this picks,
    among the values near ``math.degrees(angle)``, the shortest decimal that
    converts back exactly (``360.0`` rather than ``359.99999999999994``).  For an
    angle no degree value converts to, it returns ``math.degrees(angle)``.
    """
    approx = math.degrees(angle)
    if not math.isfinite(approx):
        return approx
    for digits in range(18):
        candidate = round(approx, digits)
        if math.radians(candidate) == angle:
            return candidate
    below = above = approx
    for _ in range(8):
        below = math.nextafter(below, -math.inf)
        above = math.nextafter(above, math.inf)
        for candidate in (below, above):
            if math.radians(candidate) == angle:
                return candidate
    return approx
