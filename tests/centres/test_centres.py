"""Instant centres: Kennedy's construction against the velocity method, and closed forms.

The two methods of :mod:`linkage_sym.centres` share no code (import-linter
contracts in pyproject.toml): Kennedy's reads the joints' positions and the
guides' rotations only, the velocity method the links' rates.  Checked here:

* on every shipped example and on hypothesis-random four-bars, slider-cranks,
  guide-bars and Watt six-bars, every centre both methods give:

  - finite centres agree to ``1e-9 L max(1, (d / 100 L)^2) + 1e-13 (L + d)
    w_max / |w_i - w_j|`` (``L`` the mechanism's size, ``d`` the centre's
    distance from the middle of the mechanism, ``w_max`` the largest angular
    velocity at the step).  Up to 100 sizes away and for links whose
    angular velocities differ by a fair share of ``w_max`` that is 1e-9 of the
    size.  Farther, the intersection of two lines through the mechanism moves
    by about ``1e-16 (d / L)^2`` sizes for a rounding-level tilt of either
    line; and the velocity method's centre ``J dv / dw`` moves by about
    ``1e-15 (L + d) w_max / |dw|`` for rates rounded to 1e-15 of ``w_max``:
    the two terms allow for these with a margin of 100;
  - centres at infinity point the same way to ``1e-9 + 1e-13 V / |dv|`` rad
    (``dv`` the two links' relative velocity at the middle of the mechanism,
    ``V`` the step's speed scale: the velocity method's direction is normal
    to ``dv``); a centre one method puts at infinity and the other more than
    1e6 sizes away likewise, to 1e-6 rad;
  - compared where both are well conditioned: every intersection Kennedy's
    centre rests on meets at more than 1e-6 rad (``KennedyCentres.weakest``)
    and the two links' angular velocities (for centres at infinity: their
    velocities) differ by more than 1e-6 of the largest one (the velocity
    method divides by that difference).  At least
    95 % (examples) or 90 % (random mechanisms) of the centres are compared;

* the solver's velocities rebuilt from the centres with the ground:
  ``v = w J (p - P_0k)`` for every joint of every link whose centre lies
  within 1e4 sizes, to 1e-9 of the step's largest speed; a link whose centre
  is at infinity translates (its ``w`` below 1e-9 of the largest, every
  velocity normal to the centre's direction);
* ``N (N - 1) / 2`` centres at every step (eq. 3-5 of the textbook chapter
  *Kinematic analysis of planar mechanisms*); a four-bar's ``P13`` on lines
  AB and CD;
* the centrodes of an antiparallelogram's coupler against their closed form:
  ellipses ``|PA| + |PD| = a`` (fixed) and ``|PB| + |PC| = a`` (moving, in the
  coupler's frame) when the crossing links ``a`` are the longer, hyperbolas
  ``||PA| - |PD|| = a`` otherwise (the isosceles-trapezoid symmetry of the
  antiparallelogram: ``P`` is as far from ``A`` as from ``C``, and from ``D``
  as from ``B``).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st

import linkage_sym
from linkage_sym.centres import (
    centrodes,
    floating_links,
    instant_centres,
    kennedy_centres,
    velocity_centres,
)
from linkage_sym.examples import example_names

from tests.support import reference_kinematics as ref  # noqa: E402
from tests.support import scenes  # noqa: E402
from tests.support.marks import slow_cases  # noqa: E402

POS = 1e-9
VEL_ROUNDING = 1e-13
DIR = 1e-9
WEAK = 1e-6
FAR_FINITE = 1e6
REBUILD = 1e-9
SETTINGS = settings(max_examples=60, derandomize=True, deadline=None, database=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


def _cross(u, v):
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def check_methods_agree(scene, res, share=0.95):
    """Kennedy's centres against the velocity method's, with the tolerances of the module doc."""
    k = kennedy_centres(scene, res)
    v = velocity_centres(res)
    assert k.pairs == v.pairs
    n = len(k.links)
    assert len(k.pairs) == n * (n - 1) // 2
    L = scene.characteristic_length()
    ok = res.status == "ok"
    mid = np.mean([res.joints[j.name].position for j in scene.joints], axis=0)  # (N, 2)
    wmax = np.max([np.abs(lk.omega) for lk in res.links.values()], axis=0)
    usable = ok[:, None] & k.reached & ~v.undefined
    cond = usable & (k.weakest > WEAK) & (np.abs(v.relative_omega) > WEAK * wmax[:, None])
    both_inf = cond & k.at_infinity & v.at_infinity
    both_fin = cond & ~k.at_infinity & ~v.at_infinity
    d = np.hypot(*np.moveaxis(np.where(k.at_infinity[..., None], v.position, k.position)
                              - mid[:, None, :], -1, 0)) / L
    err = np.hypot(*np.moveaxis(k.position - v.position, -1, 0)) / L
    with np.errstate(divide="ignore"):
        ill = wmax[:, None] / np.abs(v.relative_omega)  # the velocity method's 1/conditioning
    tol = POS * np.maximum(1.0, (d / 100.0) ** 2) + VEL_ROUNDING * (1.0 + d) * ill
    bad = both_fin & ~(err <= tol)
    assert not bad.any(), _worst(k, bad, err / tol, "finite centres differ")
    # pairs whose relative rotation vanishes (sliding pairs, translations): directions.  The
    # velocity method's is normal to the relative velocity dv, known to ~1e-15 of the speed
    vel = {"ground": np.zeros_like(mid)}
    for name, lk in res.links.items():
        r = mid - lk.origin
        vel[name] = lk.origin_velocity + lk.omega[:, None] * np.stack([-r[:, 1], r[:, 0]], -1)
    dv = np.stack([np.hypot(*(vel[b] - vel[a]).T) for a, b in k.pairs], axis=1)
    speed = np.max([np.hypot(*x.T) for x in vel.values()], axis=0) + wmax * L
    with np.errstate(divide="ignore"):
        dtol = DIR + VEL_ROUNDING * speed[:, None] / dv
    par = usable & k.at_infinity & v.at_infinity & (dv > WEAK * speed[:, None])
    derr = np.abs(_cross(k.direction, v.direction))
    bad = par & ~(derr <= dtol)
    assert not bad.any(), _worst(k, bad, derr / dtol, "directions at infinity differ")
    # one method at infinity, the other very far: the direction from the mechanism
    for inf_dir, far_pos in ((k.direction, v.position), (v.direction, k.position)):
        mixed = usable & np.all(np.isfinite(inf_dir), -1) & np.all(np.isfinite(far_pos), -1)
        if mixed.any():
            r = far_pos - mid[:, None, :]
            dist = np.hypot(*np.moveaxis(r, -1, 0))
            assert np.all(dist[mixed] > FAR_FINITE * L), "a finite centre near, the other at infinity"
            with np.errstate(invalid="ignore"):
                e = np.abs(_cross(inf_dir, r / dist[..., None]))
            assert np.all(e[mixed] <= 1e-6), "a far centre off the direction of infinity"
    compared = both_fin | both_inf | par
    assert compared.sum() >= share * usable.sum(), (
        f"only {compared.sum()} of {usable.sum()} centres compared")
    return k, v


def _worst(k, bad, ratio, what):
    i = np.nanargmax(np.where(bad, ratio, np.nan))
    s, p = np.unravel_index(i, bad.shape)
    return f"{what}: {int(bad.sum())} of them; worst at step {s}, pair {k.pairs[p]}: {ratio[s, p]:.3g} x tol"


def check_rebuilt_velocities(scene, res):
    """Every joint's velocity from its link's centre with the ground: ``v = w J (p - P_0k)``."""
    ic = instant_centres(scene, res)
    ok = res.status == "ok"
    L = scene.characteristic_length()
    speed = np.max([np.hypot(*np.moveaxis(jk.velocity, -1, 0)) for jk in res.joints.values()], axis=0)
    wmax = np.max([np.abs(lk.omega) for lk in res.links.values()], axis=0)
    checked = 0
    for link in scene.link_names:
        kidx = ic.index("ground", link)
        P = ic.position[:, kidx]
        w = np.asarray(res.links[link].omega)
        finite = ok & np.all(np.isfinite(P), -1)
        for j in scene.joints:
            if link not in j.links:
                continue
            if j.type == "P" and j.links[1] != link:
                continue  # the slider's reference point is not fixed on the guide
            lk = res.links[link]
            local = j.at
            p = lk.point(local)
            vel = lk.point_velocity(local)
            r = p - P
            far = np.hypot(*r.T) > 1e4 * L
            rebuilt = w[:, None] * np.stack([-r[:, 1], r[:, 0]], -1)
            err = np.hypot(*(rebuilt - vel).T)
            use = finite & ~far & ~ic.undefined[:, kidx]
            assert np.all(err[use] <= REBUILD * speed[use]), (link, j.name, float(np.max(err[use] / speed[use])))
            checked += int(use.sum())
            inf = ok & ic.at_infinity[:, kidx]
            if inf.any():
                u = ic.direction[:, kidx]
                assert np.all(np.abs(w[inf]) <= REBUILD * wmax[inf])
                along = np.abs(np.sum(vel * u, -1))
                assert np.all(along[inf] <= REBUILD * speed[inf]), (link, j.name)
                checked += int(inf.sum())
    assert checked > 0


# ------------------------------------------------------------------ shipped examples


# the Watt, Stephenson and Song-Wang six-bars, the printing mechanisms and the flywheel shaper in
# the default run only (the class-3 six-bar, the shaper and the rest in the fast lane too)
CENTRES_SLOW = {
    "printing_mechanism", "printing_mechanism_stroke", "shaper_flywheel", "stephenson_sixbar",
    "watt_sixbar", "song_wang_sixbar"}


@pytest.mark.parametrize("name", slow_cases(example_names(), CENTRES_SLOW))
def test_examples_kennedy_against_velocities(name):
    scene = linkage_sym.load_example(name)
    res = linkage_sym.analyze(scene)
    check_methods_agree(scene, res)
    check_rebuilt_velocities(scene, res)


@pytest.mark.parametrize("name", slow_cases(example_names(), CENTRES_SLOW))
def test_count_on_every_step(name):
    """N(N-1)/2 records at every step with velocities (eq. 3-5), one per unordered pair."""
    scene = linkage_sym.load_example(name)
    res = linkage_sym.analyze(scene)
    ic = instant_centres(scene, res)
    n = len(scene.links) + 1
    for i in range(res.n_steps):
        recs = ic.records(i)
        if res.status[i] != "ok":
            assert recs == []
            continue
        assert len(recs) == n * (n - 1) // 2
        assert len({frozenset(r["links"]) for r in recs}) == len(recs)
        for r in recs:
            assert sum(k in r for k in ("position", "direction", "undefined")) == 1, r


@pytest.mark.slow
def test_reachability_of_the_examples():
    """The five-bar's secondary centres (two degrees of freedom) are filled from the
    velocities; every 1-DOF example's are Kennedy's at every step but two of the shaper's:
    at 90 and 270 deg the guide bar is vertical, the connecting link turns at ~1e-9 of the
    crank's rate, and every pair of lines left through P(crank, connecting_link) and
    P(crank, ram) is one line but for rounding (checked: refused, not guessed)."""
    for name in example_names():
        scene = linkage_sym.load_example(name)
        res = linkage_sym.analyze(scene)
        k = kennedy_centres(scene, res)
        unreachable = [p for p, s in zip(k.pairs, k.source) if s == "unreachable"]
        missed = ~k.reached & (res.status == "ok")[:, None]
        if name in ("fivebar", "fivebar_motors"):  # one mechanism: with and without motors
            assert len(unreachable) == 5
            continue
        assert unreachable == [], name
        if name in ("shaper", "shaper_flywheel"):  # one mechanism, one sweep
            steps, pairs = np.nonzero(missed)
            assert set(steps) == {90, 270}
            assert {k.pairs[p] for p in pairs} == {("crank", "connecting_link"), ("crank", "ram")}
        else:
            assert not missed.any(), name


def test_compound_pin_of_the_song_wang_sixbar():
    """Links 3 and 4 of Song and Wang's six-bar share link 2's pin C (joints C and C2):
    their centre is that pin, at every step."""
    scene = linkage_sym.load_example("song_wang_sixbar")
    res = linkage_sym.analyze(scene)
    k = kennedy_centres(scene, res)
    i = k.index("3", "4")
    assert k.source[i] == "pin of joints C, C2"
    assert np.array_equal(k.position[:, i], res.joints["C"].position)


# ------------------------------------------------------------------ random mechanisms

length = st.floats(1.0, 4.0)
scale = st.sampled_from([1e-3, 1.0, 1e3])
sigma = st.sampled_from([1, -1])
angle = st.floats(-180.0, 180.0)
rate = st.tuples(sigma, st.floats(0.1, 20.0)).map(lambda t: t[0] * t[1])


def _crank_rocker(l2, l3, l4, f):
    """The crank length of a crank-rocker with these links, well away from dead centres
    (as tests/numeric/test_kinematics_properties.py draws them)."""
    l1max = min(l4 - abs(l2 - l3), l2 + l3 - l4)
    if l1max <= 0.05:
        return None
    l1 = f * l1max
    for d in (l4 - l1, l4 + l1):
        if abs((l2 * l2 + l3 * l3 - d * d) / (2 * l2 * l3)) > 0.99:
            return None
    return l1


@pytest.mark.slow
@SETTINGS
@given(l2=length, l3=length, l4=length, f=st.floats(0.1, 0.9), sg=sigma, start=angle,
       rot=angle, sc=scale, w=rate)
def test_random_fourbars(l2, l3, l4, f, sg, start, rot, sc, w):
    l1 = _crank_rocker(l2, l3, l4, f)
    assume(l1 is not None)
    d, pl = scenes.fourbar(l1 * sc, l2 * sc, l3 * sc, l4 * sc, start_deg=start,
                           stop_deg=start + 360, steps=73, speed=w, sigma=sg, rotate_deg=rot,
                           origin=(0.3 * sc, -0.7 * sc))
    scene, res = scenes.run(d)
    check_methods_agree(scene, res, share=0.9)
    check_rebuilt_velocities(scene, res)
    # P13 (ground-coupler) lies on lines AB and DC; P24 (crank-rocker) on AD and BC
    k = kennedy_centres(scene, res)
    A, B, C, D = (res.joints[n].position for n in "ABCD")
    for pair, lines in ((("ground", "coupler"), ((A, B), (D, C))),
                        (("crank", "rocker"), ((A, D), (B, C)))):
        P = k.position[:, k.index(*pair)]
        fin = np.all(np.isfinite(P), -1)
        scale_p = np.maximum(scene.characteristic_length(), np.hypot(*P.T))
        for a, b in lines:
            dist = np.abs(_cross(b - a, P - a)) / np.hypot(*(b - a).T)
            assert np.all(dist[fin] <= 1e-12 * scale_p[fin]), pair


@pytest.mark.slow
@SETTINGS
@given(l1=st.floats(0.5, 2.0), r=st.floats(1.5, 5.0), ef=st.floats(-0.8, 0.8), sg=sigma,
       start=angle, rot=angle, sc=scale, w=rate)
def test_random_slider_cranks(l1, r, ef, sg, start, rot, sc, w):
    l2 = r * l1
    d, _ = scenes.slider_crank(l1 * sc, l2 * sc, ef * (l2 - l1) * sc, start_deg=start,
                               stop_deg=start + 360, steps=73, speed=w, sigma=sg,
                               rotate_deg=rot, origin=(-1.1 * sc, 0.4 * sc))
    scene, res = scenes.run(d)
    check_methods_agree(scene, res, share=0.9)
    check_rebuilt_velocities(scene, res)
    ic = instant_centres(scene, res)
    k = ic.index("ground", "slider")
    u = ic.direction[:, k]
    axis = np.array([math.cos(math.radians(rot)), math.sin(math.radians(rot))])
    moving = ~ic.undefined[:, k]  # the slider stops at its dead centres
    assert np.all(ic.at_infinity[moving, k])
    assert np.all(np.abs(u[moving] @ axis) <= 1e-15)  # at infinity normal to the slide


@pytest.mark.slow
@SETTINGS
@given(l4=length, f=st.floats(0.1, 0.8), g=st.floats(0.05, 0.9), gamma=st.floats(20.0, 160.0),
       sg=sigma, start=angle, rot=angle, sc=scale, w=rate)
def test_random_guide_bars(l4, f, g, gamma, sg, start, rot, sc, w):
    """The guide-bar of the textbook chapter's example 3-1 with random proportions: the
    block stays off the arm's foot (l3 |sin gamma| < |DB|), so the crank turns fully."""
    l1 = f * l4
    l3 = g * (l4 - l1) / abs(math.sin(math.radians(gamma)))
    d, _, _ = scenes.guide_bar(l1 * sc, l3 * sc, l4 * sc, gamma, start_deg=start,
                               stop_deg=start + 360, steps=73, speed=w, sigma=sg,
                               rotate_deg=rot, origin=(0.2 * sc, 0.5 * sc))
    scene, res = scenes.run(d)
    assume(bool(np.all(res.status == "ok")))
    check_methods_agree(scene, res, share=0.9)
    check_rebuilt_velocities(scene, res)


@pytest.mark.slow
@SETTINGS
@given(l2=length, l3=length, l4=length, f=st.floats(0.1, 0.9), sg=sigma, sg2=sigma,
       e_len=st.floats(0.3, 1.5), e_ang=st.floats(30.0, 330.0), gx=st.floats(-3.0, 6.0),
       gy=st.floats(-4.0, 4.0), spread=st.floats(0.1, 0.8), reach=st.floats(0.1, 0.5),
       start=angle, w=rate)
@example(l2=1.0, l3=1.0, l4=1.0, f=0.5, sg=1, sg2=1, e_len=1.0, e_ang=30.0, gx=1e-7, gy=0.0,
         spread=0.5, reach=0.5, start=0.0, w=1.0)
@example(l2=1.0, l3=1.0, l4=1.0, f=0.5, sg=1, sg2=-1, e_len=1.0, e_ang=30.0, gx=0.0,
         gy=5.506717292648199e-07, spread=0.5, reach=0.5, start=0.0, w=1.0)
@example(l2=1.0, l3=1.0, l4=1.0, f=0.5, sg=1, sg2=1, e_len=1.0, e_ang=30.0, gx=0.0, gy=1e-10,
         spread=0.5, reach=0.5, start=0.0, w=1.0)
def test_random_watt_sixbars(l2, l3, l4, f, sg, sg2, e_len, e_ang, gx, gy, spread, reach,
                             start, w):
    """The examples: G 1e-7, 5.5e-7 and 1e-10 of the size from A.  In the first, at some steps the
    three-centre lines through P(crank, link6) are all one line (the x-axis) but for rounding;
    their "meeting" far away on it once fed garbage to every centre built on it: nearly
    parallel lines now meet at infinity only when they are well apart, and a meeting known to
    worse than 1e-3 is not used.  In the second, the line through A and G took its direction
    from shifted coordinates, 1e7 times their rounding: lines now take it from the centres'
    own coordinates.  The third (G 1e-10 from A) was taken for one pin with A, within the
    validator's coincidence tolerance: only pins at exactly one point are one pin now.  G near
    D is left out: links 5 and 6 then hardly move relative to the
    rocker, and the velocity method has nothing to divide by."""
    l1 = _crank_rocker(l2, l3, l4, f)
    assume(l1 is not None)
    assume(math.hypot(gx - l4, gy) > 0.05)
    e = e_len * l3
    th = np.linspace(0, 2 * np.pi, 721)
    _, th3 = ref.fourbar_position(l1, l2, l3, l4, th, sg)
    ang = th3 + math.radians(e_ang)
    dist = np.hypot(l4 + e * np.cos(ang) - gx, e * np.sin(ang) - gy)
    assume(dist.min() > 0.3 * dist.max())
    l5, l6 = scenes.watt_dyad_lengths(l1, l2, l3, l4, e, e_ang, (gx, gy), sg, spread, reach)
    d, _ = scenes.watt_sixbar(l1, l2, l3, l4, e_len=e, e_ang_deg=e_ang, G=(gx, gy), l5=l5, l6=l6,
                              sigma=sg, sigma2=sg2, start_deg=start, stop_deg=start + 360,
                              steps=73, speed=w)
    scene, res = scenes.run(d)
    assume(bool(np.all(res.status == "ok")))
    check_methods_agree(scene, res, share=0.9)
    check_rebuilt_velocities(scene, res)


# ------------------------------------------------------------------ centrodes


def antiparallelogram(a, b, theta_deg=50.0):
    """Crossed four-bar A-B-C-D: ground AD = coupler BC = b, cranks AB = DC = a (crossing)."""
    A, D = np.array([0.0, 0.0]), np.array([b, 0.0])
    th = math.radians(theta_deg)
    B = a * np.array([math.cos(th), math.sin(th)])
    dist = np.hypot(*(D - B))
    ex = (D - B) / dist
    x = (b * b - a * a + dist * dist) / (2 * dist)
    h = math.sqrt(b * b - x * x)
    ey = np.array([-ex[1], ex[0]])
    parallelogram = B + D - A
    C = max((B + x * ex + h * ey, B + x * ex - h * ey), key=lambda c: np.hypot(*(c - parallelogram)))
    xy = lambda p: [float(p[0]), float(p[1])]  # noqa: E731
    scene = {
        "name": "antiparallelogram",
        "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "rocker"}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": xy(A)},
            {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": xy(B)},
            {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": xy(C)},
            {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": xy(D)},
        ],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": 20, "stop_deg": 160, "steps": 141,
                     "speed": 3.0}],
        "outputs": ["kinematics", "instant_centres"],
    }
    return scene, A, B, C, D


@pytest.mark.parametrize("a, b, kind", [(0.1, 0.06, "ellipse"), (0.06, 0.1, "hyperbola")])
def test_antiparallelogram_centrodes(a, b, kind):
    """Fixed centrode: the conic with foci A, D; moving: the same conic with foci B, C in
    the coupler's frame (its assembly configuration); major axis a in both."""
    d, A, B, C, D = antiparallelogram(a, b)
    scene, res = scenes.run(d)
    assert np.all(res.status == "ok")
    ic = instant_centres(scene, res)
    assert floating_links(scene) == ("coupler",)
    c = centrodes(scene, res, ic)["coupler"]
    for pts, f1, f2 in ((c.fixed, A, D), (c.moving, B, C)):
        fin = np.all(np.isfinite(pts), -1)
        assert fin.sum() > 100
        r1, r2 = np.hypot(*(pts - f1).T), np.hypot(*(pts - f2).T)
        value = r1 + r2 if kind == "ellipse" else np.abs(r1 - r2)
        tol = 1e-12 * np.maximum(1.0, np.hypot(*pts.T) / b)
        assert np.all(np.abs(value[fin] - a) <= tol[fin] * 10 * a)


def test_moving_centrode_touches_the_fixed_one():
    """At every step the moving centrode, carried by the coupler, passes through the
    instant centre: the rolling contact."""
    scene = linkage_sym.load_example("crank_rocker")
    res = linkage_sym.analyze(scene)
    c = centrodes(scene, res, instant_centres(scene, res))["coupler"]
    L = scene.characteristic_length()
    for i in range(0, res.n_steps, 10):
        if np.all(np.isfinite(c.fixed[i])):
            assert np.hypot(*(c.moving_at(res, i)[i] - c.fixed[i])) <= 1e-12 * max(
                L, float(np.hypot(*c.fixed[i])))
