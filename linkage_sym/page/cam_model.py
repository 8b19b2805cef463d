"""What the page of a cam mechanism solves with: the profile as data and the solving order.

The symbolic layer does not derive cam contacts, so a page of a mechanism with one solves it
with ``cams.js`` (beside this module): a JavaScript port of the numeric layer's solvers of
the groups a cam mechanism is made of -- input links (a driver on a known link), RRR
dyads (the closed form) and cam followers (:class:`~linkage_sym.numeric.kinematics.cams.CamSolver`: the contact condition
in the profile parameter, bracketed on a grid and bisected, the assembly branch kept by its
sign) -- and of its singularity screen (the pressure angle's cosine, then the condition
number of the constraint Jacobian).  :func:`cam_model` gives what the port reads besides
the scene: each profile exactly as the numeric layer evaluates it (a circle's centre and
radius; the periodic cubic splines' breakpoints and coefficients, as SciPy's
``CubicSpline`` holds them) and the groups in solving order.

A mechanism with a group of another kind (a dyad of another type, a gear, a Newton group)
besides its cam contacts is refused by name: the port covers input links, RRR dyads and cam
followers only.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> m = cam_model(load_example("cam_eccentric_rocker"))
>>> [g["kind"] for g in m["groups"]], m["cams"]["K"]["profile"]["kind"]
(['input', 'cam'], 'circle')
"""

from __future__ import annotations

from linkage_sym.errors import SceneError
from linkage_sym.model import Scene
from linkage_sym.numeric.kinematics.cam_profile import GRID, CamProfile
from linkage_sym.numeric.kinematics.cams import BISECTIONS, STRAIGHT, cam_geometry
from linkage_sym.numeric.kinematics.closed_form import ASSEMBLY_TOL
from linkage_sym.scene.load import dump_scene
from linkage_sym.structure import decompose

__all__ = ["PAGE_GROUPS", "cam_model", "cam_page_model", "profile_data"]

PAGE_GROUPS = ("input", "cam", "dyad RRR")
"""The groups ``cams.js`` solves (kind, and a dyad's type)."""


def _spline(s) -> dict:
    """A SciPy ``CubicSpline`` (a ``PPoly``) as data: breakpoints and coefficients (4, n)."""
    return {"x": s.x.tolist(), "c": s.c.tolist()}


def profile_data(p: CamProfile) -> dict:
    """The profile ``p`` (:class:`~linkage_sym.numeric.kinematics.cam_profile.CamProfile`)
    as data, as the numeric layer evaluates it.

    ``{"kind": "circle", "centre", "R"}``; ``{"kind": "polar", "centre", "phi0", "r"}``
    (``r`` the spline of the radius in ``phi - phi0``); ``{"kind": "points", "x", "y"}``
    (the splines of the coordinates in the chord-length parameter).
    """
    if p.kind == "circle":
        return {"kind": "circle", "centre": list(p.centre), "R": p.R}
    if p.kind == "polar":
        return {"kind": "polar", "centre": list(p.centre), "phi0": float(p._phi0),
                "r": _spline(p._r)}
    return {"kind": "points", "x": _spline(p._x), "y": _spline(p._y)}


def _other(joint, link: str) -> str:
    return joint.links[0] if joint.links[1] == link else joint.links[1]


def _group(scene: Scene, g) -> dict:
    if g.kind == "input":
        (link,) = g.links
        j = scene.joint(g.drivers[0])
        return {"kind": "input", "link": link, "joint": j.name, "known": _other(j, link),
                "sign": 1.0 if j.links[1] == link else -1.0}
    if g.kind == "dyad":  # RRR: links[0] carries the first external joint
        e0, ji, e1 = (scene.joint(n) for n in g.joints)
        return {"kind": "dyad", "links": list(g.links), "joints": [e0.name, ji.name, e1.name],
                "known": [_other(e0, g.links[0]), _other(e1, g.links[1])]}
    cam = next(scene.joint(n) for n in g.joints if scene.joint(n).type == "cam")
    if len(g.links) != 1 or cam.links[1] != g.links[0]:
        raise SceneError([f"joints: cam contact '{cam.name}': its follower must be a link "
                          "turning on a pivot or sliding on a slide of a link known before it, "
                          "the cam known too"])
    (link,) = g.links
    pivot = next(scene.joint(n) for n in g.joints if scene.joint(n).type != "cam")
    return {"kind": "cam", "link": link, "joint": cam.name, "pivot": pivot.name,
            "known": _other(pivot, link)}


def cam_model(scene: Scene) -> dict:
    """What ``cams.js`` reads besides the scene (JSON-ready): the groups and the profiles.

    Returns
    -------
    dict
        ``groups`` (solving order: ``{"kind": "input", "link", "joint", "known", "sign"}``,
        ``{"kind": "cam", "link", "joint", "pivot", "known"}`` or ``{"kind": "dyad", "links",
        "joints", "known"}``, an RRR dyad's joints external, internal, external), ``cams`` (per contact: the
        cam and follower links, the follower's kind, the roller's radius, ``pitch``, the
        radius ``rho`` of the curve the element point keeps from the profile, the flat
        face's direction ``face`` (rad) and its normal ``m0`` pointing away from the cam,
        and :func:`profile_data`), ``cam_constants`` (the numeric layer's ``GRID``,
        ``BISECTIONS`` and ``STRAIGHT``; ``closed_form.ASSEMBLY_TOL``).

    Raises
    ------
    SceneError
        A group the port does not solve (named), or a follower that is not one link.
    """
    groups = []
    for g in decompose(scene).groups:
        kind = g.kind if g.kind != "dyad" else f"dyad {g.dyad_type}"
        if kind not in PAGE_GROUPS:
            raise SceneError([
                f"joints: a page of a mechanism with cam contacts solves input links, cam "
                f"followers and RRR dyads only; its {kind} group of link(s) {', '.join(g.links)} "
                f"(joints {', '.join(g.joints)}) is not supported yet; the numeric solvers "
                "analyse it"])
        groups.append(_group(scene, g))
    cams = {}
    for j in scene.cams:
        geo = cam_geometry(j)
        cams[j.name] = {
            "cam": j.links[0], "follower": j.links[1], "kind": geo.kind, "radius": geo.radius,
            "pitch": bool(geo.pitch), "rho": geo.rho,
            "face": None if j.cam.face is None else float(j.cam.face),
            "m0": None if geo.m0 is None else [float(v) for v in geo.m0],
            "profile": profile_data(geo.profile)}
    return {"groups": groups, "cams": cams,
            "cam_constants": {"GRID": GRID, "BISECTIONS": BISECTIONS, "STRAIGHT": STRAIGHT,
                              "ASSEMBLY_TOL": ASSEMBLY_TOL}}


def cam_page_model(scene: Scene) -> dict:
    """``MODEL`` of a cam mechanism's page (JSON-ready): :func:`cam_model` with what the
    page draws and edits -- the joints (type, links, assembly position, a ``P`` joint's
    axis), the drivers (values in rad or m), the links' centres of mass, the traced points
    and the scene in the file layout (:func:`~linkage_sym.scene.load.dump_scene`), the keys
    :func:`linkage_sym.codegen.javascript.mechanism_model` gives them."""
    joints = {}
    for j in scene.joints:
        rec = {"type": j.type, "links": list(j.links), "at": list(j.at)}
        if j.axis is not None:
            rec["axis"] = j.axis
        joints[j.name] = rec
    return {
        "name": scene.name,
        "order": [j.name for j in scene.joints],
        "joints": joints,
        "drivers": [{"joint": d.joint, "kind": d.kind, "toward": d.toward, "start": d.start,
                     "stop": d.stop, "steps": d.steps} for d in scene.drivers],
        "links": {lk.name: {"com": None if lk.com is None else list(lk.com)}
                  for lk in scene.links},
        "points": [{"name": p.name, "link": p.link, "at": list(p.at)} for p in scene.points],
        "scene": dump_scene(scene),
        **cam_model(scene),
    }
