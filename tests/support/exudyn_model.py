"""A scene of ``R`` and ``P`` joints driven by one torque motor, as a multibody model of Exudyn.

Shares no code with linkage_sym: redundant coordinates (each moving link a ``RigidBody2D``
with ``x, y, phi`` of its centre of mass), ``RevoluteJoint2D`` and ``PrismaticJoint2D``
constraints (index 3), gravity as a mass-proportional load, the loads at their points (a
force's ``active_deg`` window and a torque's followed by the driven link's own rotation,
modulo the period, ends included), and the motor's torque on the driven link from its speed
(the table interpolated linearly, its end rows held), and springs between two links as
spring-dampers between their two points (tension ``k (L - L0) + c dL/dt``, ``free_length``
defaulting to the points' distance as given); integrated by Exudyn's implicit
generalized-alpha solver (no numerical damping: spectral radius 1) at a fixed step.
What the scene format says is read from it directly: a ``P`` joint's axis is fixed on
``links[0]`` at ``axis_deg`` in the assembly configuration, ``links[1]`` slides along it.

Exudyn: Gerstmayr, "Exudyn -- a C++-based Python package for flexible multibody systems",
Multibody System Dynamics 60 (2024).
"""

from __future__ import annotations

import math

import numpy as np


def _window(rng, period=360.0):
    """Whether a driver angle (degrees from the scene's zero) is in ``rng`` (ends included,
    modulo the period); ``None``: always."""
    if rng is None:
        return lambda q: True
    lo, hi = float(rng[0]), float(rng[1])
    return lambda q: any(lo <= q % period + k * period <= hi for k in (0, 1))


def driver_speed(data: dict, duration: float, step: float, newton=(1e-12, 1e-14)):
    """``(t, omega)``: the driven link's angular velocity of the scene ``data`` (a dict of the
    scene format: ``R`` and ``P`` joints, one ``R`` driver at a ground pivot with a torque
    ``motor``, ``simulate`` from rest at the assembly configuration) by Exudyn's forward
    dynamics at the fixed ``step``; ``newton``: the relative and absolute tolerances of its
    Newton iteration at each step (loads of hundreds of newtons need an absolute one above
    1e-14: its residual is in newtons)."""
    import exudyn as exu
    from exudyn.utilities import (Force, LoadMassProportional, MarkerBodyMass,
                                  MarkerBodyPosition, MarkerBodyRigid, NodeRigidBody2D,
                                  ObjectConnectorSpringDamper, ObjectGround,
                                  ObjectJointPrismatic2D, ObjectRigidBody2D, RevoluteJoint2D,
                                  SensorNode, Torque)

    links = {lk["name"]: lk for lk in data["links"]}
    joints = {j["name"]: j for j in data["joints"]}
    sim = data["simulate"]
    (drv,) = data["drivers"]
    pivot = joints[drv["joint"]]
    driven = next(n for n in pivot["links"] if n != "ground")
    toward = np.array(joints[drv["toward"]]["at"], float) - np.array(pivot["at"], float)
    q0 = math.degrees(math.atan2(toward[1], toward[0]))
    if abs(float(sim.get("start_deg", 0.0)) - drv.get("start_deg", 0.0)) > 1e-12 or \
            abs((q0 - drv.get("start_deg", 0.0) + 180.0) % 360.0 - 180.0) > 1e-9:
        raise ValueError("the model starts at the assembly configuration (start_deg there)")
    if float(sim.get("start_speed", 0.0)) != 0.0:
        raise ValueError("the model starts from rest")
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(ObjectGround())
    body, node = {"ground": ground}, {}
    for name, lk in links.items():
        com = np.array(lk["com"], float)
        node[name] = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[com[0], com[1], 0.0],
                                                 initialVelocities=[0.0, 0.0, 0.0]))
        body[name] = mbs.AddObject(ObjectRigidBody2D(mass=lk["mass"], inertia=lk["inertia"],
                                                     nodeNumber=node[name]))

    def local(name, point):
        com = np.zeros(2) if name == "ground" else np.array(links[name]["com"], float)
        return list(np.asarray(point, float) - com) + [0.0]

    for j in data["joints"]:
        a, b = j["links"]
        if j.get("type", "R") == "R":
            ma = mbs.AddMarker(MarkerBodyPosition(bodyNumber=body[a], localPosition=local(a, j["at"])))
            mb = mbs.AddMarker(MarkerBodyPosition(bodyNumber=body[b], localPosition=local(b, j["at"])))
            mbs.AddObject(RevoluteJoint2D(markerNumbers=[ma, mb]))
        elif j["type"] == "P":
            u = math.radians(j["axis_deg"])
            ma = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body[a], localPosition=local(a, j["at"])))
            mb = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body[b], localPosition=local(b, j["at"])))
            mbs.AddObject(ObjectJointPrismatic2D(
                markerNumbers=[ma, mb], axisMarker0=[math.cos(u), math.sin(u), 0.0],
                normalMarker1=[-math.sin(u), math.cos(u), 0.0]))
        else:
            raise ValueError(f"joint type {j['type']} is not modelled here")
    if data.get("effects", {}).get("springs", bool(data.get("springs"))):
        for spring in data.get("springs", []):
            if "joint" in spring:
                raise ValueError("a spring at a joint (torsion) is not modelled here")
            (a, b), (pa, pb) = spring["links"], spring["at"]
            ends = [mbs.AddMarker(MarkerBodyPosition(bodyNumber=body[n], localPosition=local(n, p)))
                    for n, p in ((a, pa), (b, pb))]
            free = spring.get("free_length", math.dist(pa, pb))
            mbs.AddObject(ObjectConnectorSpringDamper(
                markerNumbers=ends, referenceLength=float(free), stiffness=float(spring["stiffness"]),
                damping=float(spring.get("damping", 0.0))))
    g = data.get("effects", {}).get("gravity")
    if g:
        for name in links:
            m = mbs.AddMarker(MarkerBodyMass(bodyNumber=body[name]))
            mbs.AddLoad(LoadMassProportional(markerNumber=m, loadVector=[g[0], g[1], 0.0]))
    driven_node = node[driven]

    def driver_state(mbs_):
        phi = mbs_.GetNodeOutput(driven_node, exu.OutputVariableType.Rotation)
        w = mbs_.GetNodeOutput(driven_node, exu.OutputVariableType.AngularVelocity)
        return q0 + math.degrees(float(np.ravel(phi)[-1])), float(np.ravel(w)[2])

    for load in data.get("loads", []):
        name = load["link"]
        if "table" in load:
            raise ValueError("a load table is not modelled here")
        on = _window(load.get("active_deg"), float(load.get("period_deg", 360.0)))
        if load.get("torque"):
            T = float(load["torque"])

            def torque(mbs_, t, v, T=T, on=on):
                return [0.0, 0.0, T if on(driver_state(mbs_)[0]) else 0.0]

            mk = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body[name]))
            mbs.AddLoad(Torque(markerNumber=mk, loadVector=[0.0, 0.0, T],
                               loadVectorUserFunction=torque))
        if load.get("force") is not None:
            F = [float(load["force"][0]), float(load["force"][1]), 0.0]

            def force(mbs_, t, v, F=F, on=on):
                return F if on(driver_state(mbs_)[0]) else [0.0, 0.0, 0.0]

            mk = mbs.AddMarker(MarkerBodyPosition(bodyNumber=body[name],
                                                  localPosition=local(name, load["at"])))
            mbs.AddLoad(Force(markerNumber=mk, loadVector=F, loadVectorUserFunction=force))
    table = np.array(drv["motor"]["torque"], float)

    def motor(mbs_, t, v):
        return [0.0, 0.0, float(np.interp(driver_state(mbs_)[1], table[:, 0], table[:, 1]))]

    mk = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body[driven]))
    mbs.AddLoad(Torque(markerNumber=mk, loadVector=[0.0, 0.0, 0.0], loadVectorUserFunction=motor))
    sensor = mbs.AddSensor(SensorNode(nodeNumber=driven_node, storeInternal=True,
                                      outputVariableType=exu.OutputVariableType.AngularVelocity))
    mbs.Assemble()
    settings = exu.SimulationSettings()
    settings.timeIntegration.numberOfSteps = int(round(duration / step))
    settings.timeIntegration.endTime = duration
    settings.timeIntegration.generalizedAlpha.spectralRadius = 1.0
    settings.timeIntegration.newton.relativeTolerance = newton[0]
    settings.timeIntegration.newton.absoluteTolerance = newton[1]
    settings.timeIntegration.verboseMode = 0
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = step
    exu.SolveDynamic(mbs, settings)
    out = mbs.GetSensorStoredData(sensor)
    return out[:, 0], out[:, 3]
