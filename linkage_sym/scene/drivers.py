"""The ``drivers`` section of a scene: the driven joints, their ranges and ``toward``.

:class:`DriverSection`, a part of the scene reader of
:mod:`linkage_sym.scene.validate`, reads every driver against the joints read
before it: an ``R`` driver's angles in degrees (at most :data:`MAX_SWEEP_DEG`)
and the joint ``toward`` that its angle points to, a ``P`` driver's slide in
metres (held to the mechanism's size by
:meth:`~linkage_sym.scene.checks.SceneChecks.check_size`), the steps every
driver shares.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from linkage_sym.model.scene import Driver
from linkage_sym.scene.fields import ANGLE, FieldReader, radians_or_none, did_you_mean
from linkage_sym.scene.joints import JointInfo
from linkage_sym.scene.motors import read_motor

__all__ = ["DRIVER_KEYS", "DriverSection", "MAX_SWEEP_DEG", "P_DRIVER_KEYS", "R_DRIVER_KEYS"]

R_DRIVER_KEYS = ("toward", "start_deg", "stop_deg")
P_DRIVER_KEYS = ("start", "stop")
DRIVER_KEYS = ("joint", *R_DRIVER_KEYS, *P_DRIVER_KEYS, "steps", "speed", "acceleration", "motor")

MAX_SWEEP_DEG = 360_000.0
"""Largest range ``|stop_deg - start_deg|`` of an R driver: 1000 turns.

The solver follows the mechanism in increments of at most 2 degrees, so such a
sweep is already 180 000 solving points.
"""


class DriverSection(FieldReader):
    """The ``drivers`` section, read against the reader's ``joints``; sets ``drivers_ok`` and
    ``slides`` (every valid start and stop of a ``P`` driver), and uses ``coincide``
    (:class:`~linkage_sym.scene.checks.SceneChecks`) for ``toward``."""

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
            motor = read_motor(self, entry, path, kind)
            if kind is not None and len(self.problems) == before:
                drivers.append(Driver(joint, kind, start, stop, steps, speed, acceleration, toward,
                                      *degrees, motor=motor))
        self.drivers_ok = refs_ok
        return tuple(drivers)

    def driver_range(
        self, entry: Mapping[str, Any], path: str, info: JointInfo | None
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

    def toward(self, entry: Mapping[str, Any], path: str, joint: str, info: JointInfo) -> str | None:
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
