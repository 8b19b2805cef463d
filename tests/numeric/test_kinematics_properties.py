"""Property tests of the numeric kinematics on random assemblable mechanisms.

Hypothesis draws Grashof crank-rockers, offset slider-cranks and Watt
six-bars that assemble over the whole crank turn with a transmission angle
bounded away from 0 and 180 deg (so every step is well conditioned), in
either assembly mode, anywhere in the plane.  Properties on every step:

* all steps ok and every result finite;
* link lengths (distances between the joints of one link) constant;
* every joint and driver constraint closed (position, velocity, acceleration)
  -- same tolerances as test_kinematics_consistency;
* no branch jump: each Assur group's Jacobian-determinant sign (own FD
  Jacobian) and the dyad's relative-angle sign equal the assembly ones.

Derandomized (fixed examples, reproducible), modest ``max_examples``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from tests.support import reference_kinematics as ref  # noqa: E402
from tests.support import scenes  # noqa: E402

# every test here runs 50 random mechanisms (over 3 s each on a loaded 2-core machine)
pytestmark = pytest.mark.slow

POS_TOL = 1e-12
RATE_TOL = 1e-11
SETTINGS = settings(max_examples=50, derandomize=True, deadline=None, database=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])

length = st.floats(1.0, 4.0)
scale = st.sampled_from([1e-3, 1.0, 1e3])
sigma = st.sampled_from([1, -1])
angle = st.floats(-180.0, 180.0)
rate = st.tuples(sigma, st.floats(0.1, 20.0)).map(lambda t: t[0] * t[1])  # |w1| >= 0.1


def _crank_rocker(l2, l3, l4, f):
    """Crank length that lets the crank turn fully: |BD| in [l4 - l1, l4 + l1]
    must stay inside (|l2 - l3|, l2 + l3); f in (0, 1) of the largest such l1.
    Returns None if the proportions allow no crank or the transmission angle
    would come within ~8 deg of 0 / 180 deg."""
    l1max = min(l4 - abs(l2 - l3), l2 + l3 - l4)
    if l1max <= 0.05:
        return None
    l1 = f * l1max
    for d in (l4 - l1, l4 + l1):
        cmu = (l2 * l2 + l3 * l3 - d * d) / (2 * l2 * l3)  # cos(transmission angle)
        if abs(cmu) > 0.99:
            return None
    return l1


def _common_checks(scene, res, sigma_fn=None):
    assert np.all(res.status == "ok"), sorted(set(res.status))
    for name, jk in res.joints.items():
        for arr in (jk.position, jk.velocity, jk.acceleration):
            assert np.all(np.isfinite(arr)), f"joint {name}: non-finite results"
    for name, lk in res.links.items():
        for arr in (lk.rotation, lk.omega, lk.alpha, lk.origin):
            assert np.all(np.isfinite(arr)), f"link {name}: non-finite results"
    # link lengths: every pair of joints of one link keeps its assembly distance
    size = scene.characteristic_length()
    for link in scene.link_names:
        js = [j for j in scene.joints if link in j.links]
        for a in range(len(js)):
            for b in range(a + 1, len(js)):
                ja, jb = js[a], js[b]
                L = math.dist(ja.at, jb.at)
                pa = res.links[link].point(ja.at)
                pb = res.links[link].point(jb.at)
                dist = np.hypot(*(pa - pb).T)
                assert np.all(np.abs(dist - L) <= POS_TOL * size), (
                    f"{link}: |{ja.name}{jb.name}| drifts by {np.abs(dist - L).max():.2e}")
                # the reported joint positions agree (each is on its links[1])
                for jj, pp in ((ja, pa), (jb, pb)):
                    if jj.type == "R":
                        got = np.asarray(res.joints[jj.name].position)
                        assert np.all(np.hypot(*(got - pp).T) <= POS_TOL * size)
    fails = ref.closure_failures(scene, res, POS_TOL, RATE_TOL)
    assert not fails, "; ".join(fails[:5])
    groups, s0, signs, _ = ref.determinant_signs(scene, res)
    jump = signs != s0[None, :]
    assert not jump.any(), (
        f"branch jump: group {groups[int(np.argwhere(jump)[0][1])][0]} flips its "
        f"determinant sign at step {int(np.argwhere(jump)[0][0])}")
    if sigma_fn is not None:
        s = sigma_fn(res)
        assert np.all(s == s[0]), f"relative-angle sign flips at step {np.argmax(s != s[0])}"


def _dyad_sign(res, b, c, d):
    """sign cross(B - D, C - D) from the reported joint positions = the RRR
    dyad's determinant sign sign(sin(th2 - th3))."""
    B, C, D = (np.asarray(res.joints[n].position) for n in (b, c, d))
    return np.sign(ref._cross(B - D, C - D))


@SETTINGS
@given(l2=length, l3=length, l4=length, f=st.floats(0.1, 0.9), sg=sigma, start=angle,
       rot=angle, sc=scale, w=rate, a=st.floats(-50, 50))
def test_random_grashof_crank_rockers(l2, l3, l4, f, sg, start, rot, sc, w, a):
    l1 = _crank_rocker(l2, l3, l4, f)
    assume(l1 is not None)
    d, pl = scenes.fourbar(l1 * sc, l2 * sc, l3 * sc, l4 * sc, start_deg=start,
                           stop_deg=start + 360, steps=73, speed=w, acceleration=a, sigma=sg,
                           rotate_deg=rot, origin=(0.3 * sc, -0.7 * sc))
    scene, res = scenes.run(d)
    _common_checks(scene, res, lambda r: _dyad_sign(r, "B", "C", "D"))
    assert np.all(_dyad_sign(res, "B", "C", "D") == sg)


@SETTINGS
@given(l1=st.floats(0.5, 2.0), r=st.floats(1.5, 5.0), ef=st.floats(-0.8, 0.8), sg=sigma,
       start=angle, rot=angle, sc=scale, w=rate, a=st.floats(-50, 50))
def test_random_slider_cranks(l1, r, ef, sg, start, rot, sc, w, a):
    """Offset |e| <= 0.8 (l2 - l1): the rod never reaches the perpendicular of
    the slide, the crank turns fully."""
    l2 = r * l1
    e = ef * (l2 - l1)
    d, pl = scenes.slider_crank(l1 * sc, l2 * sc, e * sc, start_deg=start, stop_deg=start + 360,
                                steps=73, speed=w, acceleration=a, sigma=sg, rotate_deg=rot,
                                origin=(-1.1 * sc, 0.4 * sc))
    scene, res = scenes.run(d)

    def rod_sign(res):
        # sign of cos(th2) in the canonical frame: the slider ahead of the pin
        B, C = (np.asarray(res.joints[n].position) for n in ("B", "C"))
        axis = np.array([math.cos(math.radians(rot)), math.sin(math.radians(rot))])
        return np.sign((C - B) @ axis)

    _common_checks(scene, res, rod_sign)
    assert np.all(rod_sign(res) == sg)


@SETTINGS
@given(l2=length, l3=length, l4=length, f=st.floats(0.1, 0.9), sg=sigma, sg2=sigma,
       e_len=st.floats(0.3, 1.5), e_ang=st.floats(30.0, 330.0), gx=st.floats(-3.0, 6.0),
       gy=st.floats(-4.0, 4.0), spread=st.floats(0.1, 0.8), reach=st.floats(0.1, 0.5),
       start=angle, w=rate)
def test_random_watt_sixbars(l2, l3, l4, f, sg, sg2, e_len, e_ang, gx, gy, spread, reach,
                             start, w):
    """Crank-rocker whose ternary rocker drives a second RRR dyad to a ground
    pivot G; the dyad's lengths keep |EG| inside (|l5 - l6|, l5 + l6) with margin
    (scenes.watt_dyad_lengths) and E never comes near G."""
    l1 = _crank_rocker(l2, l3, l4, f)
    assume(l1 is not None)
    e = e_len * l3
    th = np.linspace(0, 2 * np.pi, 721)
    _, th3 = ref.fourbar_position(l1, l2, l3, l4, th, sg)
    ang = th3 + math.radians(e_ang)
    dist = np.hypot(l4 + e * np.cos(ang) - gx, e * np.sin(ang) - gy)
    assume(dist.min() > 0.3 * dist.max())
    # canonical start 0 so that watt_dyad_lengths (over a full turn) applies
    l5, l6 = scenes.watt_dyad_lengths(l1, l2, l3, l4, e, e_ang, (gx, gy), sg, spread, reach)
    d, pts = scenes.watt_sixbar(l1, l2, l3, l4, e_len=e, e_ang_deg=e_ang, G=(gx, gy), l5=l5,
                                l6=l6, sigma=sg, sigma2=sg2, start_deg=start,
                                stop_deg=start + 360, steps=73, speed=w, acceleration=1.0)
    scene, res = scenes.run(d)

    def signs(res):
        s1 = _dyad_sign(res, "B", "C", "D")
        s2 = _dyad_sign(res, "E", "F", "G")
        return s1 * 2 + s2

    _common_checks(scene, res, signs)
    assert np.all(_dyad_sign(res, "B", "C", "D") == sg)
