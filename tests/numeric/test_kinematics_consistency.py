"""Self-consistency of the numeric kinematics, without any closed form.

* Velocities are derivatives of positions and accelerations of velocities
  (central finite differences along a finely stepped sweep).
* Every joint and driver constraint holds at position, velocity and
  acceleration level on every shipped example and on the tests' scenes.
* Every ok step stays in the assembly mode: the sign of each Assur group's
  constraint-Jacobian determinant (own decomposition, own residuals, own
  finite-difference Jacobian, see reference_kinematics) is the one of the
  assembly configuration.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from tests.support import reference_kinematics as ref  # noqa: E402
from tests.support import scenes  # noqa: E402
from tests.support.marks import slow_cases  # noqa: E402

EPS = np.finfo(float).eps

# Closure: the contract's positions are exact solutions of the constraints up
# to rounding; 1e-12 x the mechanism's size (the brief's bound).
POS_TOL = 1e-12
# Velocity / acceleration closure: relative to the sweep's largest joint speed
# (acceleration) -- a rate is the solution of a linear system, so rounding of
# the positions (1e-16 x size) is amplified by the constraint Jacobian's
# condition (< 1e3 on the ok steps of these mechanisms): 1e-11.
RATE_TOL = 1e-11


def _examples():
    from tests.support.example_sets import lower_pair_examples

    return lower_pair_examples()  # reference_kinematics.py solves R and P joints only


def _own_scenes():
    """The tests' mechanisms (name -> scene dict), driver with acceleration."""
    out = {}
    out["fourbar"] = scenes.fourbar(0.024, 0.063, 0.048, 0.078, speed=7.0, acceleration=2.5,
                                    coupler_com=(0.03, 0.015), rotate_deg=20)[0]
    out["slider_crank"] = scenes.slider_crank(0.03, 0.1, 0.012, speed=7.0, acceleration=2.5)[0]
    out["guide_bar"] = scenes.guide_bar(0.024, 0.048, 0.078, 100.0, speed=7.0,
                                        acceleration=2.5)[0]
    out["shaper"] = scenes.shaper(speed=7.0, acceleration=2.5)
    out["watt_sixbar"] = scenes.watt_sixbar(0.02, 0.06, 0.05, 0.07, e_len=0.04, e_ang_deg=120,
                                            G=(0.12, 0.08), speed=7.0,
                                            acceleration=2.5)[0]
    return out


def _with_steps(d, start, stop, steps):
    """The scene with its sweep replaced by canonical crank angles start..stop
    (the builders' default sweep starts at canonical 0, so the scene's
    ``start_deg`` is the drawing's rotation)."""
    d = dict(d)
    dr = dict(d["drivers"][0])
    rot = dr["start_deg"]
    dr.update(start_deg=start + rot, stop_deg=stop + rot, steps=steps)
    d["drivers"] = [dr]
    return d


# ---------------------------------------------------------------------------
# finite differences
# ---------------------------------------------------------------------------


def _fd_check(x, v, q, qd, ok, what, extra=None, vscale=0.0):
    """Central differences of x along the sweep vs v (= dx/dt).

    ``(x[i+1] - x[i-1]) / (2h) * qd`` has the truncation error
    ``h^2/6 * x'''(xi) * qd`` (O(h^2)); x''' is bounded by the third differences
    of x over the five neighbouring intervals, with a factor 2 of safety, and
    rounding adds ``8 eps max|x| / h`` plus ``64 eps vscale`` (the rounding of a
    rate that is zero in exact arithmetic, e.g. a fixed joint's, is relative to
    the mechanism's rates ``vscale``).  ``extra`` is added to the derivative
    (the qdd term of an acceleration).  The bound must itself be small
    (< 1e-4 of the largest rate) for the check to mean something."""
    x = np.asarray(x, dtype=float).reshape(len(q), -1)
    v = np.asarray(v, dtype=float).reshape(len(q), -1)
    h = q[1] - q[0]
    assert np.allclose(np.diff(q), h, rtol=1e-9, atol=0)
    fd = (x[2:] - x[:-2]) / (2 * h) * qd
    if extra is not None:
        fd = fd + np.asarray(extra, dtype=float).reshape(len(q), -1)[1:-1]
    d3 = np.abs(x[3:] - 3 * x[2:-1] + 3 * x[1:-2] - x[:-3]) / abs(h) ** 3  # at i + 1.5
    n = len(q)
    bound = np.empty((n - 2, x.shape[1]))
    for i in range(1, n - 1):
        lo, hi = max(0, i - 3), min(len(d3), i + 2)
        bound[i - 1] = 2 * h * h / 6 * abs(qd) * d3[lo:hi].max(0)
    bound += 8 * EPS * np.abs(x).max() * abs(qd) / abs(h) + 64 * EPS * vscale
    use = ok[2:] & ok[1:-1] & ok[:-2]
    vmax = max(np.abs(v[1:-1][use]).max(), vscale)
    # (a fixed point: vmax = vscale = 0, the bound is rounding only)
    assert vmax == 0 or bound[use].max() <= 1e-4 * vmax, (
        f"{what}: finite-difference bound {bound[use].max():.2e} too loose vs {vmax:.2e}")
    err = np.abs(fd - v[1:-1])
    bad = use[:, None] & (err > bound)
    assert not bad.any(), (
        f"{what}: |FD - solver| {err[bad].max():.3e} exceeds the O(h^2) bound "
        f"at steps {np.nonzero(bad.any(1))[0][:5] + 1}")
    return float(err[use].max() / vmax) if vmax > 0 else 0.0


@pytest.mark.parametrize("name", ["fourbar", "slider_crank", "guide_bar", "shaper",
                                  "watt_sixbar"])
def test_rates_are_derivatives_of_positions(name):
    """Velocities = central FD of positions, accelerations = central FD of
    velocities (+ v qdd/qd), for every joint, link rotation and centre of
    mass; sweep over 60 deg in 0.05 deg steps (h = 8.7e-4 rad)."""
    d = _with_steps(_own_scenes()[name], 20.0, 80.0, 1201)
    scene, res = scenes.run(d)
    ok = res.ok
    assert ok.all(), set(res.status)
    dname = scene.drivers[0].joint
    q = np.asarray(res.drivers[dname]["q"], dtype=float)
    qd = float(res.drivers[dname]["qd"][0])
    qdd = float(res.drivers[dname]["qdd"][0])
    worst = 0.0
    vj = max(np.abs(jk.velocity).max() for jk in res.joints.values())
    aj = max(np.abs(jk.acceleration).max() for jk in res.joints.values())
    wl = max(np.abs(lk.omega).max() for lk in res.links.values())
    al = max(np.abs(lk.alpha).max() for lk in res.links.values())
    for jn, jk in res.joints.items():
        worst = max(worst, _fd_check(jk.position, jk.velocity, q, qd, ok, f"joint {jn} velocity",
                                     vscale=vj))
        worst = max(worst, _fd_check(jk.velocity, jk.acceleration, q, qd, ok,
                                     f"joint {jn} acceleration", extra=jk.velocity / qd * qdd,
                                     vscale=aj))
    for ln, lk in res.links.items():
        worst = max(worst, _fd_check(lk.rotation, lk.omega, q, qd, ok, f"link {ln} omega",
                                     vscale=wl))
        worst = max(worst, _fd_check(lk.omega, lk.alpha, q, qd, ok, f"link {ln} alpha",
                                     extra=lk.omega / qd * qdd, vscale=al))
        if lk.com is not None:
            worst = max(worst, _fd_check(lk.com, lk.com_velocity, q, qd, ok, f"{ln} com vel",
                                         vscale=vj))
            worst = max(worst, _fd_check(lk.com_velocity, lk.com_acceleration, q, qd, ok,
                                         f"{ln} com acc", extra=lk.com_velocity / qd * qdd,
                                         vscale=aj))
    # O(h^2) with h = 8.7e-4: the observed relative error is ~1e-7, far below 1e-5
    assert worst < 1e-5


# ---------------------------------------------------------------------------
# closure on every shipped example and the tests' scenes
# ---------------------------------------------------------------------------


def _closure(scene, res):
    return ref.closure_failures(scene, res, POS_TOL, RATE_TOL)


@pytest.mark.parametrize("name", slow_cases(_examples(), {"shaper_flywheel", "watt_sixbar", "fivebar_motors"}))
def test_closure_on_shipped_examples(name):
    """Every R joint's two points coincide, every P joint keeps its links
    parallel with the reference point on the axis line, the reported joint
    motion is links[1]'s, and every driver's coordinate (and its rates) is
    the prescribed one -- at every step that has positions (ok, singular)
    resp. rates (ok)."""
    import linkage_sym

    scene = linkage_sym.load_example(name)
    res = linkage_sym.analyze(scene)
    for d in scene.drivers:
        q = np.asarray(res.drivers[d.joint]["q"], dtype=float)
        assert np.allclose(q, np.linspace(d.start, d.stop, d.steps), rtol=0, atol=1e-14 * max(
            1.0, abs(d.start), abs(d.stop))), f"driver {d.joint}: q is not the scene's sweep"
        assert np.all(np.asarray(res.drivers[d.joint]["qd"]) == d.speed)
        assert np.all(np.asarray(res.drivers[d.joint]["qdd"]) == d.acceleration)
    fails = _closure(scene, res)
    assert not fails, f"example {name}: " + "; ".join(fails[:8])
    json.dumps(res.to_dict(), allow_nan=False)  # the contract's JSON never carries NaN


@pytest.mark.parametrize("name", ["fourbar", "slider_crank", "guide_bar", "shaper",
                                  "watt_sixbar"])
def test_closure_on_test_scenes(name):
    scene, res = scenes.run(_own_scenes()[name])
    assert res.ok.all()
    fails = _closure(scene, res)
    assert not fails, f"{name}: " + "; ".join(fails[:8])


# ---------------------------------------------------------------------------
# assembly mode: determinant sign per Assur group
# ---------------------------------------------------------------------------


def _check_signs(scene, res, what):
    groups, s0, signs, conds = ref.determinant_signs(scene, res)
    assert np.all(s0 != 0), f"{what}: singular assembly configuration?"
    ok = res.ok
    bad = ok[:, None] & (signs != s0[None, :])
    if bad.any():
        i, k = np.argwhere(bad)[0]
        raise AssertionError(
            f"{what}: group {groups[k][0]} left its assembly mode at step {i} "
            f"(q = {[float(res.drivers[d.joint]['q'][i]) for d in scene.drivers]}, "
            f"{int(bad.sum())} step(s) in all; cond there {conds[i, k]:.2e})")


@pytest.mark.parametrize("name", slow_cases(_examples(), {
    "printing_mechanism", "printing_mechanism_stroke", "shaper_flywheel", "watt_sixbar",
    "stephenson_sixbar", "song_wang_sixbar"}))
def test_assembly_mode_kept_on_shipped_examples(name):
    """For every ok step, each Assur group's constraint-Jacobian determinant
    (own FD Jacobian) has the sign it has in the assembly configuration."""
    import linkage_sym

    scene = linkage_sym.load_example(name)
    res = linkage_sym.analyze(scene)
    _check_signs(scene, res, f"example {name}")


@pytest.mark.parametrize("name", ["fourbar", "slider_crank", "guide_bar", "shaper",
                                  "watt_sixbar"])
@pytest.mark.parametrize("sigma", [1, -1])
def test_assembly_mode_kept_on_test_scenes(name, sigma):
    """Both assembly modes of the first dyad of each test mechanism."""
    kw = dict(speed=7.0, acceleration=2.5, steps=121)
    if name == "fourbar":
        d = scenes.fourbar(0.024, 0.063, 0.048, 0.078, sigma=sigma, **kw)[0]
    elif name == "slider_crank":
        d = scenes.slider_crank(0.03, 0.1, 0.012, sigma=sigma, **kw)[0]
    elif name == "guide_bar":
        d = scenes.guide_bar(0.024, 0.048, 0.078, 100.0, sigma=sigma, **kw)[0]
    elif name == "shaper":
        d = scenes.shaper(sigma4=sigma, **kw)
    else:
        d = scenes.watt_sixbar(0.02, 0.06, 0.05, 0.07, e_len=0.04, e_ang_deg=120,
                               G=(0.12, 0.08), sigma=sigma, sigma2=-sigma,
                               **kw)[0]
    scene, res = scenes.run(d)
    assert res.ok.all(), set(res.status)
    _check_signs(scene, res, name)
