"""The crank-rocker with its motor (``crank_rocker_motor``) as a multibody model of Exudyn.

Shares no code with linkage_sym: redundant coordinates (each link a ``RigidBody2D`` with
``x, y, phi`` of its centre of mass), ``RevoluteJoint2D`` constraints (index 3), gravity as a
mass-proportional load, the coupler's force at its point, the rocker's torque while the
crank's angle is within its active range, and the motor's torque on the crank from its
speed (the table interpolated linearly, its end rows held); integrated by Exudyn's implicit
generalized-alpha solver (no numerical damping: spectral radius 1) at a fixed step.

Exudyn: Gerstmayr, "Exudyn -- a C++-based Python package for flexible multibody systems",
Multibody System Dynamics 60 (2024).
"""

from __future__ import annotations

import math

import numpy as np


def crank_omega(data: dict, duration: float, step: float):
    """``(t, omega)``: the crank's angular velocity of the scene ``data`` (a
    ``crank_rocker_motor``-like dict: four R joints A-B-C-D, crank A-B driven at A with a
    torque motor, loads on the rocker (torque, optional ``active_deg``) and coupler (force at a
    point)) from its ``simulate`` start, Exudyn's forward dynamics at the fixed ``step``."""
    import exudyn as exu
    from exudyn.utilities import (MarkerBodyMass, MarkerBodyPosition, MarkerBodyRigid,
                                  NodeRigidBody2D, ObjectGround, ObjectRigidBody2D,
                                  RevoluteJoint2D, SensorNode, Force, Torque,
                                  LoadMassProportional, MarkerNodeRigid)

    links = {lk["name"]: lk for lk in data["links"]}
    at = {j["name"]: np.array(j["at"], float) for j in data["joints"]}
    sim = data["simulate"]
    start = math.radians(sim.get("start_deg", 0.0))
    if start != 0.0:
        raise ValueError("the model starts at the assembly configuration (start_deg 0)")
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(ObjectGround())
    body, node = {}, {}
    for name in ("crank", "coupler", "rocker"):
        lk = links[name]
        com = np.array(lk["com"], float)
        node[name] = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[com[0], com[1], 0.0],
                                                 initialVelocities=[0.0, 0.0, 0.0]))
        body[name] = mbs.AddObject(ObjectRigidBody2D(mass=lk["mass"],
                                                     inertia=lk["inertia"],
                                                     nodeNumber=node[name]))
    # crank's initial speed about A (rest in the examples)
    w0 = float(sim.get("start_speed", 0.0))
    if w0 != 0.0:
        raise ValueError("the model starts from rest")

    def local(name, point):
        return list(point - np.array(links[name]["com"], float)) + [0.0]

    def pin(a, b, point):
        if b == "ground":
            a, b = b, a
        if a == "ground":
            ma = mbs.AddMarker(MarkerBodyPosition(bodyNumber=ground,
                                                  localPosition=list(point) + [0.0]))
        else:
            ma = mbs.AddMarker(MarkerBodyPosition(bodyNumber=body[a], localPosition=local(a, point)))
        mb = mbs.AddMarker(MarkerBodyPosition(bodyNumber=body[b], localPosition=local(b, point)))
        mbs.AddObject(RevoluteJoint2D(markerNumbers=[ma, mb]))

    for j in data["joints"]:
        pin(j["links"][0], j["links"][1], at[j["name"]])
    g = data["effects"].get("gravity")
    if g:
        for name in body:
            m = mbs.AddMarker(MarkerBodyMass(bodyNumber=body[name]))
            mbs.AddLoad(LoadMassProportional(markerNumber=m, loadVector=[g[0], g[1], 0.0]))
    crank_node = node["crank"]

    def crank_state(mbs_):
        phi = mbs_.GetNodeOutput(crank_node, exu.OutputVariableType.Rotation)
        w = mbs_.GetNodeOutput(crank_node, exu.OutputVariableType.AngularVelocity)
        return float(np.ravel(phi)[-1]), float(np.ravel(w)[2])

    for load in data.get("loads", []):
        name = load["link"]
        if "torque" in load:
            T = float(load["torque"])
            rng = load.get("active_deg")

            def torque(mbs_, t, v, T=T, rng=rng):
                if rng is None:
                    return [0.0, 0.0, T]
                q = math.degrees(crank_state(mbs_)[0]) % 360.0
                return [0.0, 0.0, T if rng[0] <= q <= rng[1] else 0.0]

            mk = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body[name]))
            mbs.AddLoad(Torque(markerNumber=mk, loadVector=[0.0, 0.0, T],
                               loadVectorUserFunction=torque))
        if "force" in load:
            if load.get("active_deg") is not None:
                raise ValueError("a force over part of the cycle is not modelled here")
            mk = mbs.AddMarker(MarkerBodyPosition(bodyNumber=body[name],
                                                  localPosition=local(name, np.array(load["at"]))))
            mbs.AddLoad(Force(markerNumber=mk, loadVector=list(load["force"]) + [0.0]))
    table = np.array(data["drivers"][0]["motor"]["torque"], float)

    def motor(mbs_, t, v):
        return [0.0, 0.0, float(np.interp(crank_state(mbs_)[1], table[:, 0], table[:, 1]))]

    mk = mbs.AddMarker(MarkerNodeRigid(nodeNumber=crank_node))
    mbs.AddLoad(Torque(markerNumber=mk, loadVector=[0.0, 0.0, 0.0],
                       loadVectorUserFunction=motor))
    sensor = mbs.AddSensor(SensorNode(nodeNumber=crank_node, storeInternal=True,
                                      outputVariableType=exu.OutputVariableType.AngularVelocity))
    mbs.Assemble()
    settings = exu.SimulationSettings()
    n = int(round(duration / step))
    settings.timeIntegration.numberOfSteps = n
    settings.timeIntegration.endTime = duration
    settings.timeIntegration.generalizedAlpha.spectralRadius = 1.0
    settings.timeIntegration.newton.relativeTolerance = 1e-12
    settings.timeIntegration.newton.absoluteTolerance = 1e-14
    settings.timeIntegration.verboseMode = 0
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = step
    exu.SolveDynamic(mbs, settings)
    data_ = mbs.GetSensorStoredData(sensor)
    return data_[:, 0], data_[:, 3]
