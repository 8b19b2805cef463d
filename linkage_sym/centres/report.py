"""The instant centres of one step as a person reads them: the table ``linkage-sym centres``
prints, and the step's record it writes as JSON.

Centres are numbered as the textbook chapter *Kinematic analysis of planar
mechanisms* numbers links (the ground 1, then the scene's links in order:
``P13``), each with how it was found: at a joint, by Kennedy's three-centre
lines (which two), or from the velocities where those lines run out.  With
the :class:`~linkage_sym.centres.polygons.Polygons` of the step, the
graphical method's quantities follow (eqs. 3-1 to 3-4).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["ROUNDING", "centres_report", "step_record"]

ROUNDING = 1e-12
"""Printed numbers below this fraction of their scale (the mechanism's size, the
step's largest speed or acceleration) are rounding: they print as 0."""


def _unit(scene):
    return ("mm", 1000.0) if scene.characteristic_length() < 1.0 else ("m", 1.0)


def _xy(v, scale=1.0, digits=5, tiny=0.0):
    """``(x, y)`` with ``digits`` significant digits; components below ``tiny`` print as 0."""
    x, y = (0.0 if abs(c) <= tiny else float(c) * scale + 0.0 for c in v[:2])
    return f"({x:.{digits}g}, {y:.{digits}g})"


def _where(scene, analysis, i) -> str:
    """``A = 60°`` for each driver at step ``i``."""
    out = []
    for name, d in analysis.drivers.items():
        q = float(d["q"][i])
        kind = scene.joint(name).type
        out.append(f"{name} = {math.degrees(q):.6g}°" if kind == "R" else f"{name} = {q:.6g} m")
    return ", ".join(out)


def centres_report(scene, analysis, centres, i, polygons=None) -> list:
    """The printed table of step ``i``: one line per centre, then the polygon quantities.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
    centres : InstantCentres
    i : int
        Step index into ``analysis``.
    polygons : Polygons, optional

    Returns
    -------
    list of str

    Examples
    --------
    >>> import linkage_sym
    >>> from linkage_sym.centres import instant_centres
    >>> scene = linkage_sym.load_example("crank_rocker")
    >>> res = linkage_sym.analyze(scene)
    >>> lines = centres_report(scene, res, instant_centres(scene, res), 30)
    >>> print("\\n".join(lines[:4]))
    crank-rocker: 6 = 4·3/2 instant centres at step 30 (A = 30°)
    links: 1 ground, 2 crank, 3 coupler, 4 rocker (numbered as in the textbook chapter's figures)
      P12  ground-crank    (0, 0) mm  at joint A
      P13  ground-coupler  (73.092, 42.2) mm  three-centre lines P12-P23 and P14-P34
    """
    unit, scale = _unit(scene)
    L = scene.characteristic_length() or 1.0
    names = centres.links
    n = len(names)
    num = {name: k + 1 for k, name in enumerate(names)}
    lines = [f"{scene.name}: {n * (n - 1) // 2} = {n}·{n - 1}/2 instant centres at step {i}"
             + (f" ({_where(scene, analysis, i)})" if analysis.drivers else ""),
             "links: " + ", ".join(f"{num[x]} {x}" for x in names)
             + " (numbered as in the textbook chapter's figures)"]
    width = max(len(f"{a}-{b}") for a, b in centres.pairs)
    k_all = centres.kennedy
    for k, (a, b) in enumerate(centres.pairs):
        label = centres.label(k)
        head = f"  {label:<4} {a + '-' + b:<{width}}  "
        src = centres.source[k]
        if centres.undefined[i, k]:
            lines.append(head + "undefined: the two links are at rest relative to each other")
            continue
        if centres.at_infinity[i, k]:
            what = f"at infinity, direction {_xy(centres.direction[i, k], digits=6, tiny=ROUNDING)}"
        else:
            what = _xy(centres.position[i, k], scale, tiny=ROUNDING * L) + f" {unit}"
        if centres.from_velocities[i, k]:
            how = "from the velocities (no two three-centre lines reach it)"
        elif src.startswith(("joint", "pin", "pitch point")):  # a mesh's: its pitch point
            how = ("normal to the slide of joint " + src[6:-8] if src.endswith("(slide)")
                   else "at " + src)
        else:
            ia, ib = names.index(a), names.index(b)
            via = [int(t) for t in k_all.via[i, k] if t >= 0]
            pair = lambda x, y: centres.label(centres.index(names[x], names[y]))  # noqa: E731
            how = "three-centre lines " + " and ".join(f"{pair(ia, t)}-{pair(t, ib)}" for t in via)
        lines.append(head + what + "  " + how)
    if polygons is not None:
        lines += _polygon_lines(scene, polygons, num)
    return lines


def _polygon_lines(scene, pq, num) -> list:
    """The graphical method's quantities, as the textbook chapter writes them (eqs. 3-1 to 3-4)."""
    vmax = max([float(np.hypot(*p.velocity)) for p in pq.points] + [0.0])
    amax = max([float(np.hypot(*p.acceleration)) for p in pq.points] + [0.0])
    wmax = max([abs(w) for w in pq.omega.values()] + [0.0])
    almax = max([abs(a) for a in pq.alpha.values()] + [0.0])

    def v(x):
        return _xy(x, tiny=ROUNDING * vmax)

    def a(x):
        return _xy(x, tiny=ROUNDING * amax)

    def num_(x, top):
        return 0.0 if abs(x) <= ROUNDING * top else x

    out = ["angular velocity and acceleration of each link:"]
    for name in scene.link_names:
        out.append(f"  {num[name]} {name}: ω = {num_(pq.omega[name], wmax):.6g} rad/s, "
                   f"α = {num_(pq.alpha[name], almax):.6g} rad/s²")
    if pq.sliding:
        out.append("sliding pairs between moving links (v_slider = v_guide + v_rel; "
                   "a_slider = a_guide + a_k + a_rel, a_k = 2ω×v_rel):")
    for s in pq.sliding:
        b_s, b_g = f"{s.point}{num[s.slider]}", f"{s.point}{num[s.guide]}"
        out.append(f"  {s.joint}: {s.slider} on {s.guide}; {b_s} relative to {b_g}:")
        out.append(f"    v_rel = {num_(s.speed, vmax):.6g} m/s along the slide "
                   f"{_xy(s.axis, digits=4, tiny=ROUNDING)}, vector {v(s.velocity)} m/s")
        out.append(f"    a_rel = {num_(s.rate, amax):.6g} m/s² along the slide, "
                   f"vector {a(s.acceleration)} m/s²")
        out.append(f"    Coriolis a_k = 2ω({s.guide})×v_rel = {a(s.coriolis)} m/s², "
                   f"|a_k| = {num_(float(np.hypot(*s.coriolis)), amax):.6g} m/s²")
    out.append("each point relative to each pivot of its link (v = ω×r, a_n = -ω²r, a_t = α×r):")
    for r in pq.relative:
        out.append(f"  {r.link}: {r.point} about {r.about}: v = {v(r.velocity)} m/s, "
                   f"a_n = {a(r.normal)} (|{num_(float(np.hypot(*r.normal)), amax):.5g}|), "
                   f"a_t = {a(r.tangential)} (|{num_(float(np.hypot(*r.tangential)), amax):.5g}|) m/s²")
    return out


def step_record(scene, analysis, centres, i, polygons=None, step=None) -> dict:
    """The JSON record of step ``i``: the scene, the step (``step``; None for a step solved
    on its own), the driver values, the textbook numbering, the centres and, with
    ``polygons``, the graphical method's quantities.

    Examples
    --------
    >>> import linkage_sym
    >>> from linkage_sym.centres import instant_centres
    >>> scene = linkage_sym.load_example("crank_rocker")
    >>> res = linkage_sym.analyze(scene)
    >>> rec = step_record(scene, res, instant_centres(scene, res), 30, step=30)
    >>> rec["step"], rec["numbering"]
    (30, {'ground': 1, 'crank': 2, 'coupler': 3, 'rocker': 4})
    """
    out = {"scene": scene.name, "step": step,
           "drivers": {k: {x: float(v[x][i]) for x in ("q", "qd", "qdd")}
                       for k, v in analysis.drivers.items()},
           "numbering": {name: k + 1 for k, name in enumerate(centres.links)},
           "instant_centres": centres.records(i)}
    if polygons is not None:
        out["polygons"] = polygons.to_dict()
        out["polygons"].pop("step")
    return out
