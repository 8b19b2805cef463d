"""A scene's constraint rows: every joint's and driver's, of every kind.

The rows themselves are in :mod:`linkage_sym.numeric.kinematics.constraints`
(revolute and prismatic joints, gear meshes, drivers) and
:mod:`linkage_sym.numeric.kinematics.cams` (a cam contact's instantaneous
replacement); this module picks each joint's.
"""

from __future__ import annotations

from typing import NamedTuple

from linkage_sym.model import Scene
from linkage_sym.numeric.kinematics.constraints import Constraint, GMesh, PDriver, PJoint, RDriver, RJoint


class JointRows(NamedTuple):
    """The constraint rows of one joint: its own, and its driver's if it is driven."""

    joint: Constraint
    driver: Constraint | None = None

    @property
    def rows(self) -> list[Constraint]:
        return [self.joint] if self.driver is None else [self.joint, self.driver]


def scene_constraints(scene: Scene, phi0: dict[str, float]) -> dict[str, JointRows]:
    """Constraints of every joint and driver, keyed by joint name.

    A driven joint has its joint rows and its driver row (:class:`JointRows`).
    ``phi0`` gives, for each R driver, the angle of its ``toward`` vector in
    the assembly configuration.
    """
    driven = {d.joint: d for d in scene.drivers}
    out: dict[str, JointRows] = {}
    for j in scene.joints:
        a, b = j.links
        if j.type == "G":
            out[j.name] = JointRows(GMesh(a, b, j.carrier, j.radii, j.internal))
            continue
        if j.type == "cam":  # the contact's replacement rows (the cam module: scenes with cams)
            from linkage_sym.numeric.kinematics.cams import CamContact

            out[j.name] = JointRows(CamContact(j, scene.characteristic_length() or 1.0))
            continue
        row: Constraint = RJoint(a, b, j.at) if j.type == "R" else PJoint(a, b, j.axis)
        driver: Constraint | None = None
        if j.name in driven:
            if j.type == "R":
                driver = RDriver(a, b, phi0[j.name], j.name)
            else:
                driver = PDriver(a, b, j.axis, j.name)
        out[j.name] = JointRows(row, driver)
    return out
