"""Rotations across gaps of unassemblable steps, every method (the scene format's rule).

The contract: ``links.*.rotation`` is continuous along the sweep, and across a gap of
unassemblable steps it continues with the value nearest to the last solved step.  A link
turned by a driver on the ground reports the driver's value ``q - q0`` at every step (so
every method gives the same number); a link driven relative to another moving link follows
the rule like any other.

The reference shares no code with the package:

* each link's direction at a step comes from the positions (``atan2`` of two of its ``R``
  joints, or its guide's direction for a link held by a ``P`` joint), and the four-bar's and
  the guide-bar's positions themselves from the closed forms of ``reference_kinematics``;
* :func:`contract_rotations` applies the rule to those directions: every sweep here starts
  at the assembly configuration (rotation 0) with steps of at most 2 degrees (the solving
  path's own increment, so the steps are the path), so "continuous", "nearest to the last
  solved step" after a gap, and a Newton group's re-entry past a limit (a jump between two
  steps) are all "nearest to the previous solved step".

Random mechanisms of every shipped linkage topology (hypothesis for the four-bar, the
guide-bar and the class-III triad, a fixed random set for the shipped examples' shapes),
driven over spans with gaps, by the dyad, global and symbolic methods; and the sweep's
``swing`` of a four-bar with a gap against the reference's.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import linkage_sym

from tests.support import reference_kinematics as ref  # noqa: E402
from tests.support import scenes  # noqa: E402

METHODS = ("dyad", "global", "symbolic")
TWO_PI = 2 * math.pi
ANGLE_TOL = 1e-9
"""Rotations against the reference (rad).  Near a limit position a dyad's angles carry
about sqrt(eps) (a tangency's square root); steps within 1e-6 of one are held to
:data:`NEAR_LIMIT_TOL` instead: a turn missed across a gap is off by 2 pi either way."""
NEAR_LIMIT_TOL = 1e-6
SETTINGS = settings(max_examples=40, derandomize=True, deadline=None, database=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


# -- the reference --------------------------------------------------------------------------

def contract_rotations(angle, solved):
    """The scene format's rule on directions known modulo a turn (rad, from the assembly
    configuration): the first solved step nearest 0 (the sweep starts at the assembly
    configuration), each later solved step nearest the previous solved one."""
    out = np.full(len(angle), np.nan)
    prev = 0.0
    for i in np.flatnonzero(solved):
        v = angle[i] - TWO_PI * round((angle[i] - prev) / TWO_PI)
        out[i] = v
        prev = v
    return out


def link_directions(scene: dict, res) -> dict:
    """Each moving link's direction (rad, from the assembly configuration, modulo a turn)
    at every step, from the joints' positions alone: two ``R`` joints of the link, or the
    direction of the link a ``P`` joint holds it to (ground: 0)."""
    joints = scene["joints"]
    pos = {j["name"]: np.asarray(res.joints[j["name"]].position, float) for j in joints}
    out = {}

    def direction(link, seen=()):
        if link == "ground":
            return np.zeros(len(res.status))
        if link in out:
            return out[link]
        rs = [j for j in joints if j["type"] == "R" and link in j["links"]]
        for a in rs:
            for b in rs:
                if math.dist(a["at"], b["at"]) > 1e-6 * size(scene):
                    d = pos[b["name"]] - pos[a["name"]]
                    v = np.arctan2(d[:, 1], d[:, 0]) - math.atan2(b["at"][1] - a["at"][1],
                                                                  b["at"][0] - a["at"][0])
                    out[link] = v
                    return v
        for j in joints:
            if j["type"] == "P" and link in j["links"]:
                other = j["links"][0] if j["links"][1] == link else j["links"][1]
                if other not in seen:
                    out[link] = direction(other, seen + (link,))
                    return out[link]
        return None

    for lk in scene["links"]:
        direction(lk["name"])
    return {k: v for k, v in out.items() if v is not None}


def size(scene: dict) -> float:
    pts = np.array([j["at"] for j in scene["joints"]], float)
    return float(np.max(np.ptp(pts, axis=0)))


def ground_drivers(scene: dict) -> dict:
    """``{link: (joint, sign)}`` of links turned by an ``R`` driver on the ground."""
    out = {}
    for d in scene["drivers"]:
        j = next(j for j in scene["joints"] if j["name"] == d["joint"])
        if j["type"] == "R" and "ground" in j["links"]:
            link = j["links"][1] if j["links"][0] == "ground" else j["links"][0]
            out[link] = (d["joint"], 1.0 if j["links"][1] == link else -1.0)
    return out


def check_rule(scene: dict, res, method: str, limit=None):
    """Every link's rotation against the reference rule (see the module docstring);
    ``limit`` (N,) marks steps near a limit position (looser tolerance there)."""
    solved = res.status != "unassemblable"
    tol = np.full(len(solved), ANGLE_TOL)
    if limit is not None:
        tol[limit] = NEAR_LIMIT_TOL
    driven = ground_drivers(scene)
    for link, ang in link_directions(scene, res).items():
        got = np.asarray(res.links[link].rotation, float)
        if link in driven:
            joint, sign = driven[link]
            q = np.asarray(res.drivers[joint]["q"], float)
            want = sign * (q - q[0])  # the sweep starts at the assembly configuration
            want[~solved] = np.nan
            # the driver's value is also the link's direction
            err = np.abs(np.angle(np.exp(1j * (got - ang))))
            assert np.all(err[solved] <= tol[solved]), (method, link, "direction")
        else:
            want = contract_rotations(ang, solved)
        scenes.assert_close(got[solved], want[solved], 0, f"{method}: {link}.rotation",
                            atol=tol[solved])


def has_gap(res) -> bool:
    """An unassemblable stretch with solved steps on both sides."""
    idx = np.flatnonzero(res.status != "unassemblable")
    return bool(len(idx) and np.any(np.diff(idx) > 1))


def start_at_assembly(scene: dict, span_deg: float, step_deg: float = 2.0) -> dict:
    """``scene`` with each ``R`` driver starting at its assembly value and turning
    ``span_deg`` in steps of ``step_deg`` (at most the solving path's 2 degrees, so the steps
    are the path), a ``P`` driver from 0 over ``span_deg`` / 360 of the size."""
    scene = json.loads(json.dumps(scene))
    steps = int(math.ceil(abs(span_deg) / step_deg)) + 1
    pos = {j["name"]: j["at"] for j in scene["joints"]}
    for d in scene["drivers"]:
        j = next(j for j in scene["joints"] if j["name"] == d["joint"])
        if j["type"] == "R":
            a, b = pos[d["joint"]], pos[d["toward"]]
            start = math.degrees(math.atan2(b[1] - a[1], b[0] - a[0]))
            d["start_deg"], d["stop_deg"] = start, start + span_deg
        else:
            d.pop("start_deg", None)
            d.pop("stop_deg", None)
            d["start"], d["stop"] = 0.0, span_deg / 360.0 * size(scene)
        d["steps"] = steps
    scene["outputs"] = ["kinematics"]
    return scene


def run_all(scene: dict) -> dict:
    sc = linkage_sym.load_scene(scene)
    return {m: linkage_sym.analyze(sc, method=m) for m in METHODS}


def run_drawn(scene: dict) -> dict:
    """:func:`run_all` of a drawn mechanism; one assembled at a dead centre, or with a
    driver's joint and the joint it points toward at one point (the triad's noise at its
    bound, -0.05, puts B on A), is refused as the format says and is not an example."""
    try:
        return run_all(scene)
    except linkage_sym.SceneError as e:
        assume("singular position" not in str(e) and "at the same point as" not in str(e))
        raise


def methods_agree(results: dict, limit=None):
    """Where two methods solved the same steps, their rotations are equal."""
    base = results["dyad"]
    for m, res in results.items():
        if not np.array_equal(res.status != "unassemblable", base.status != "unassemblable"):
            continue  # a tangency taken by one method and not the other moves the gap
        solved = base.status != "unassemblable"
        tol = np.full(len(solved), ANGLE_TOL)
        if limit is not None:
            tol[limit] = NEAR_LIMIT_TOL
        for link in base.links:
            scenes.assert_close(res.links[link].rotation[solved],
                                base.links[link].rotation[solved], 0,
                                f"{m} against dyad: {link}.rotation", atol=tol[solved])


# -- four-bars whose crank cannot turn fully: closed-form positions ------------------------

def _fourbar_case(l1, l2, l3, l4, th_deg, sigma, span, steps=None):
    """A four-bar assembled at crank angle ``th_deg`` and driven from there over ``span``
    degrees in ``steps`` (default: 1-degree steps)."""
    th = math.radians(th_deg)
    if not np.isfinite(ref.fourbar_position(l1, l2, l3, l4, th, sigma)[1]):
        return None
    scene, _ = scenes.fourbar(l1, l2, l3, l4, start_deg=th_deg, stop_deg=th_deg + span,
                              steps=steps or int(abs(span)) + 1, sigma=sigma)
    return scene


def _fourbar_reference(scene, res, l1, l2, l3, l4, sigma):
    """Closed-form joint positions, the status, and the steps near a limit position."""
    q = np.asarray(res.drivers["A"]["q"], float)
    th2, th3 = ref.fourbar_position(l1, l2, l3, l4, q, sigma)
    B = np.stack([l1 * np.cos(q), l1 * np.sin(q)], axis=1)
    C = np.stack([l4 + l3 * np.cos(th3), l3 * np.sin(th3)], axis=1)
    d = np.hypot(B[:, 0] - l4, B[:, 1])
    margin = np.minimum(d - abs(l2 - l3), l2 + l3 - d) / max(l1, l2, l3, l4)
    return B, C, margin


@pytest.mark.slow
@SETTINGS
@given(lengths=st.lists(st.floats(0.5, 4.0), min_size=4, max_size=4),
       th_deg=st.floats(-180, 180), sigma=st.sampled_from([1, -1]),
       span=st.sampled_from([-720.0, -400.0, 250.0, 400.0, 720.0]),
       coarse=st.booleans())
def test_fourbar_rotations_across_gaps(lengths, th_deg, sigma, span, coarse):
    """Random four-bars whose crank cannot turn fully, over spans with gaps, in 1-degree
    steps or 5.6-degree steps (which the solving path refines: the old code then took the
    rule from a path point between steps)."""
    l1, l2, l3, l4 = lengths
    s = sorted(lengths)
    crank_turns = (s[0] + s[3] <= s[1] + s[2]) and min(lengths) in (l1, l4)
    assume(not crank_turns)  # the crank cannot turn fully: a span over a turn has a gap
    # not a change point (s + l = p + q): there the coupler turns by half a turn between two
    # points of the solving path, and which way is undefined (a warning of the run says so:
    # tests/numeric/test_change_points.py); a 5.6-degree step then sees the other way from
    # the path (test_a_change_point_four_bar... covers the 1-degree steps)
    assume(abs(s[0] + s[3] - s[1] - s[2]) > 1e-9 * s[3])
    steps = int(abs(span) / 5.6) + 1 if coarse else None
    scene = _fourbar_case(l1, l2, l3, l4, th_deg, sigma, span, steps)
    assume(scene is not None)
    _check_fourbar(scene, run_drawn(scene), lengths, sigma)


def _check_fourbar(scene, results, lengths, sigma):
    """Statuses, positions and rotations of every method against the closed forms."""
    l1, l2, l3, l4 = lengths
    res = results["dyad"]
    B, C, margin = _fourbar_reference(scene, res, l1, l2, l3, l4, sigma)
    clear = np.abs(margin) > 1e-7  # status decided beyond rounding
    limit = np.abs(margin) < 1e-6
    for m, r in results.items():
        solved = r.status != "unassemblable"
        assert np.array_equal(solved[clear], (margin >= 0)[clear]), (m, "statuses")
        ok = solved & ~limit
        scale = max(l1, l2, l3, l4)
        scenes.assert_close(r.joints["B"].position[ok], B[ok], 1e-12, f"{m}: B", scale=scale)
        scenes.assert_close(r.joints["C"].position[ok], C[ok], 1e-9, f"{m}: C", scale=scale)
        check_rule(scene, r, m, limit)
    methods_agree(results, limit)


def test_a_change_point_four_bar_whose_coupler_end_passes_the_rocker_pivot():
    """Crank 3, coupler 1, rocker 1, ground 3 (a change point, found by hypothesis), from
    crank angle 1 degree over -720 in 1-degree steps: at 0 and -360 degrees joint B lies on
    the rocker's pivot D and the equal coupler and rocker can take any angle.  The dyad
    method reported the step at -360 degrees (where B is 4e-15 from D) singular with B 0.3 %
    of the size off the crank's circle: the half-chord's formula had lost every digit there.
    Those steps are unassemblable now ("joints B and D coincide"), or singular with their
    positions exact, and every rotation follows the rule across them; each passage is a
    warning of the run, in every method (the other branch is there too:
    tests/numeric/test_change_points.py)."""
    lengths = [3.0, 1.0, 1.0, 3.0]
    scene = _fourbar_case(*lengths, 1.0, 1, -720.0)
    results = run_all(scene)
    _check_fourbar(scene, results, lengths, 1)
    for m, r in results.items():
        for i in (1, 361):
            assert r.status[i] in ("unassemblable", "singular"), (m, i)
            if r.status[i] == "singular":
                scenes.assert_close(r.joints["B"].position[i], [3.0, 0.0], 1e-12, m, scale=3.0)
    assert "coincide" in results["dyad"].messages[361]
    for m, r in results.items():
        assert len(r.warnings) == 2 and all("pass through one point" in w for w in r.warnings), m


def test_the_issue_fourbar_rocker_comes_back_nearest():
    """The four-bar of the report (crank 2.663, coupler 1.139, rocker 1.427, ground 2.697)
    driven over 200 degrees in 37 steps: its crank turns on two arcs, and the solving path
    refines the 5.6-degree steps.  After the gap the rocker and the coupler continue nearest
    to the last solved step (the old code took the path point after it and brought the
    rocker back at -3.348 where 2.935 is nearest), in every method; the crank reports the
    driver's value."""
    scene = _fourbar_case(2.663, 1.139, 1.427, 2.697, -27.0, 1, 200.0, steps=37)
    results = run_all(scene)
    for m, r in results.items():
        assert has_gap(r)
        check_rule(scene, r, m)
        solved = np.flatnonzero(r.status != "unassemblable")
        gap = np.flatnonzero(np.diff(solved) > 1)[0]
        i, j = solved[gap], solved[gap + 1]
        for link in ("coupler", "rocker"):
            th = r.links[link].rotation
            assert abs(th[j] - th[i]) <= math.pi, (m, link, th[i], th[j])
    methods_agree(results)


# -- guide-bars (a block sliding on a turning guide): closed-form positions ---------------

@pytest.mark.slow
@SETTINGS
@given(l1=st.floats(0.5, 3.0), l3=st.floats(0.2, 3.0), l4=st.floats(0.5, 3.0),
       gamma=st.floats(20.0, 160.0), th_deg=st.floats(-180, 180), sigma=st.sampled_from([1, -1]),
       span=st.sampled_from([-720.0, 400.0, 720.0]))
def test_guide_bar_rotations_across_gaps(l1, l3, l4, gamma, th_deg, sigma, span):
    th = math.radians(th_deg)
    r0 = ref.guide_bar(l1, l3, l4, math.radians(gamma), th, 0.0, 0.0, sigma)
    assume(np.isfinite(r0["th3"]))
    scene, _, _ = scenes.guide_bar(l1, l3, l4, gamma, start_deg=th_deg, stop_deg=th_deg + span,
                                   steps=int(abs(span)) + 1, sigma=sigma)
    results = run_drawn(scene)
    res = results["dyad"]
    assume(has_gap(res))
    q = np.asarray(res.drivers["A"]["q"], float)
    rr = ref.guide_bar(l1, l3, l4, math.radians(gamma), q, np.ones_like(q), 0.0, sigma)
    d = np.hypot(l1 * np.cos(q) - l4, l1 * np.sin(q))
    margin = (d - l3 * abs(math.sin(math.radians(gamma)))) / max(l1, l3, l4)
    limit = np.abs(margin) < 1e-6
    guide0 = float(r0["th3"])
    for m, r in results.items():
        solved = r.status != "unassemblable"
        check_rule(scene, r, m, limit)
        ok = solved & ~limit
        # the guide's direction by the closed form, modulo a turn
        err = np.angle(np.exp(1j * (r.links["guide"].rotation - (rr["th3"] - guide0))))
        assert np.all(np.abs(err[ok]) <= 1e-9), m
    methods_agree(results, limit)


# -- class-III triads (a Newton group) --------------------------------------------------

@pytest.mark.slow
@settings(max_examples=5, derandomize=True, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(noise=st.lists(st.floats(-0.05, 0.05), min_size=12, max_size=12),
       span=st.sampled_from([-720.0, 720.0]))
def test_class3_triad_rotations_across_gaps(noise, span):
    P = {k: (v[0] + noise[2 * i], v[1] + noise[2 * i + 1])
         for i, (k, v) in enumerate(scenes.TRIAD_BASE.items())}
    scene = start_at_assembly(scenes.triad_scene(P), span)
    results = run_drawn(scene)
    assume(has_gap(results["dyad"]))
    for m, r in results.items():
        check_rule(scene, r, m, _near_limits(r))
    methods_agree(results, _near_limits(results["dyad"]))


def _near_limits(res):
    """Steps next to a gap or flagged ill-conditioned (sqrt(eps) positions there)."""
    solved = res.status != "unassemblable"
    edge = np.zeros(len(solved), bool)
    edge[:-1] |= solved[:-1] & ~solved[1:]
    edge[1:] |= solved[1:] & ~solved[:-1]
    with np.errstate(invalid="ignore"):
        return edge | (res.condition > 1e6) | (res.status == "singular")


# -- the shipped linkages' topologies with their joints moved ----------------------------

SHIPPED = ["crank_rocker", "slider_crank_offset", "shaper", "guide_bar_quick_return",
           "watt_sixbar", "stephenson_sixbar", "song_wang_sixbar", "sixbar_class3",
           "printing_mechanism", "fivebar", "hydraulic_boom", "engine_four_stroke"]


def _moved(name: str, rng) -> dict:
    raw = _raw_example(name)
    L = size(raw)
    for j in raw["joints"]:
        j["at"] = [float(v + rng.normal(0.0, 0.12 * L)) for v in j["at"]]
    raw.pop("loads", None)
    raw.pop("load_tables", None)
    raw["effects"] = {"inertia": False, "gravity": [0.0, 0.0], "loads": False}
    return raw


def _raw_example(name: str) -> dict:
    import importlib.resources

    text = (importlib.resources.files("linkage_sym.examples") / f"{name}.json").read_text()
    return json.loads(text)


@pytest.mark.slow
@pytest.mark.parametrize("name", SHIPPED)
def test_shipped_topologies_rotations_across_gaps(name):
    """Each shipped linkage's topology with its joints moved at random (a fixed random
    set) until two of them have gaps over two turns of the driver, every method."""
    rng = np.random.default_rng(sum(map(ord, name)))
    found = 0
    for _ in range(60):
        raw = _moved(name, rng)
        scene = start_at_assembly(raw, float(rng.choice([-720.0, 720.0])))
        try:
            results = run_all(scene)
        except linkage_sym.SceneError:  # e.g. assembled at a singular position
            continue
        if not has_gap(results["dyad"]):
            continue
        found += 1
        for m, r in results.items():
            check_rule(scene, r, m, _near_limits(r))
        methods_agree(results, _near_limits(results["dyad"]))
        if found == 2:
            break
    assert found >= 1, f"{name}: no moved design with a gap in 60 draws"


# -- a driven link's rotation is its driver's value, in every method ---------------------

def test_driven_crank_reports_the_drivers_value_after_a_gap():
    """The crank of a four-bar driven over two turns with gaps: ``q - q0`` at every solved
    step, far from the nearest value after a gap, the same in every method."""
    scene = _fourbar_case(2.663, 1.139, 1.427, 2.697, 30.0, 1, 720.0)
    for m, r in run_all(scene).items():
        solved = r.status != "unassemblable"
        assert has_gap(r)
        q = r.drivers["A"]["q"]
        np.testing.assert_allclose(r.links["crank"].rotation[solved], (q - q[0])[solved],
                                   rtol=0, atol=1e-12, err_msg=m)


# -- the sweep's swing of a four-bar with a gap ----------------------------------------

@pytest.mark.slow
def test_sweep_swing_with_a_gap_is_the_rockers_own():
    """The design sweep's ``swing`` of the report's four-bar (two arcs of the crank, 37 steps
    over 200 degrees) is the largest minus the smallest rotation by the rule: at the steps,
    and between two consecutive solved steps along the closed form sampled at 1e-4 degree of
    the crank (the sweep locates limit positions between samples), to 1e-6 degree.  The old
    sweep unwrapped across the gap from a path point: 11.5 degrees off."""
    l1, l2, l3, l4 = 2.663, 1.139, 1.427, 2.697
    scene = _fourbar_case(l1, l2, l3, l4, -27.0, 1, 200.0, steps=37)
    res = linkage_sym.analyze(linkage_sym.load_scene(scene))
    assert has_gap(res)
    solved = res.status != "unassemblable"
    at_steps = contract_rotations(link_directions(scene, res)["rocker"], solved)
    q = res.drivers["A"]["q"]
    th3_0 = ref.fourbar_position(l1, l2, l3, l4, q[0], 1)[1]
    values = list(at_steps[solved])
    idx = np.flatnonzero(solved)
    for i, k in zip(idx[:-1], idx[1:]):
        if k != i + 1:
            continue
        fine = np.linspace(q[i], q[k], 200001)
        th3 = np.unwrap(ref.fourbar_position(l1, l2, l3, l4, fine, 1)[1] - th3_0)
        values += list(th3 - th3[0] + at_steps[i])
    want_swing = math.degrees(max(values) - min(values))
    table = linkage_sym.sweep(scene, {"l_AB": [l1]}, metrics=["swing"])
    got = float(table.columns["swing_deg"][0])
    assert abs(got - want_swing) <= 1e-6, (got, want_swing)


# -- the centres do not depend on whole turns --------------------------------------------

def test_instant_centres_do_not_depend_on_whole_turns():
    """Instant centres read rotations only through their directions (the guides of ``P``
    joints): a run whose rotations are shifted by whole turns has the same centres, to the
    rounding of cos and sin of the shifted angles, which a far centre amplifies (1e-9
    relative, 1e-12 of the size absolute), and the same flags."""
    from linkage_sym.centres import instant_centres

    scene_d = _fourbar_case(2.663, 1.139, 1.427, 2.697, 30.0, 1, -200.0)
    scene_d["outputs"] = ["kinematics", "instant_centres"]
    for name, build in (("four-bar", scene_d),
                        ("guide-bar", scenes.guide_bar(1.0, 0.4, 0.7, 60.0, start_deg=40.0,
                                                       stop_deg=400.0, steps=361)[0])):
        build["outputs"] = ["kinematics", "instant_centres"]
        sc = linkage_sym.load_scene(build)
        res = linkage_sym.analyze(sc)
        base = instant_centres(sc, res)
        for link in res.links.values():
            link.rotation[...] = link.rotation + TWO_PI * 3
        shifted = instant_centres(sc, res)
        for flag in ("rates", "at_infinity", "undefined", "from_velocities"):
            assert np.array_equal(getattr(base, flag), getattr(shifted, flag)), (name, flag)
        for fld in ("position", "direction"):
            a, b = getattr(base, fld), getattr(shifted, fld)
            assert np.array_equal(np.isnan(a), np.isnan(b)), (name, fld)
            np.testing.assert_allclose(b, a, rtol=1e-9, atol=1e-12 * max(1.0, size(build)),
                                       err_msg=f"{name}: {fld}")
