"""Guide (RP) dyads in Burmester motion generation: poses of random known inverted slider-cranks
(tests.support.guide_reference: written and solved there, no synthesis code) give that linkage
back among the solutions to 1e-9 of its size; every defect-free design meets every pose as the
solver drives its scene read back from JSON; an independent random-start least-squares search on
the dyad's own equation finds nothing the method did not report; degenerate poses are refused;
known guide-sliders (a guide and a slider, the block driven) come back, and their dead centre is
found."""

import json
import math

import numpy as np
import pytest

from linkage_sym.synthesis.burmester import burmester_curves, dyads_at
from linkage_sym.synthesis.burmester_rp import guide_points
from linkage_sym.synthesis.common import SynthesisError
from linkage_sym.synthesis.defects import check_motion
from linkage_sym.synthesis.motion import motion_synthesis, table
from tests.support.guide_reference import (other_assembly, poses_of,
                                           random_inverted_slider_crank)
from tests.support.slider_reference import solve_at

POSES = [[0.0, 0.0, 0.0], [1.0, 0.2, 10.0], [1.8, 0.7, 25.0], [2.3, 1.5, 45.0], [2.5, 2.4, 70.0]]


def _known(seed, n, kind="oscillating"):
    """A random inverted slider-crank, its n poses over 210 degrees of crank, its joints and
    size (its largest distance between joints ``A``, ``B``, ``D`` at pose 1)."""
    scene = random_inverted_slider_crank(np.random.default_rng(seed), kind)
    j = {x["name"]: x for x in scene["joints"]}
    size = max(math.dist(j[a]["at"], j[b]["at"]) for a, b in ("AB", "BD", "AD"))
    return scene, poses_of(scene, n), j, size


def _same_line(axis_a, axis_b):
    """The angle between two line directions (degrees), modulo a half turn (rad)."""
    return abs(math.remainder(math.radians(axis_a - axis_b), math.pi))


def _through_poses(scene, crank_angles, poses):
    """The largest distance of the solver's coupler frame from a pose, rotation error times the
    coupler length added (``|BC|``, ``|BD|`` or a guide-slider's ``|AC|``), over that length;
    the scene read back from JSON."""
    scene = json.loads(json.dumps(scene))
    res = solve_at(scene, np.asarray(crank_angles))
    at = {j["name"]: j["at"] for j in scene["joints"]}
    slide_b = any(x["name"] == "B" and x["type"] == "P" for x in scene["joints"])
    b = math.dist(at["A"] if slide_b else at["B"], at["C"] if "C" in at else at["D"])
    P, rot = res.points["P"].position, res.links["coupler"].rotation
    turn = [math.radians(p[2] - poses[0][2]) for p in poses]
    err = [math.dist(P[k], p[:2]) + b * abs(math.remainder(rot[k] - turn[k], 2 * math.pi))
           for k, p in enumerate(poses)]
    return max(err) / b


@pytest.mark.parametrize("seed,kind", [(1, "oscillating"), (2, "rotating"), (3, "oscillating"),
                                       (4, "rotating")])
def test_five_poses_of_an_inverted_slider_crank_give_it_back(seed, kind):
    known, poses, j, size = _known(seed, 5, kind)
    guides = guide_points(poses)
    assert len(guides) == 1  # five poses: the known guide, and no other
    assert math.dist(guides[0].pivot, j["D"]["at"]) <= 1e-9 * size
    assert _same_line(math.degrees(guides[0].axis), j["D_slide"]["axis_deg"]) <= 1e-9
    result = motion_synthesis(poses)
    inverted = [d for d in result.designs if d.kind == "inverted slider-crank"]
    found = 0
    for d in inverted:
        at = {x["name"]: x for x in d.scene["joints"]}
        off = sum(math.dist(at[n]["at"], j[n]["at"]) for n in "ABD")
        found += (off <= 1e-9 * size
                  and _same_line(at["D_slide"]["axis_deg"], j["D_slide"]["axis_deg"]) <= 1e-9)
    assert found == 1
    free = [d for d in result.designs if d.check.defect_free]
    assert any(d.kind == "inverted slider-crank" for d in free)
    for d in free:
        assert _through_poses(d.scene, d.check.crank_angles, poses) <= 1e-9
    rows = table(result)
    inv = [r for r in rows if r["linkage"] == "inverted slider-crank"]
    assert len(inv) == len(inverted)
    assert all(math.isfinite(r["offset"]) and math.isnan(r["rocker"]) for r in inv)


@pytest.mark.slow  # the four-pose designs (a dozen dyads' pairs) take 3-5 s each
@pytest.mark.parametrize("seed,kind", [(5, "oscillating"), (6, "rotating")])
def test_four_poses_guide_through_the_known_pivot_and_designs_through_them(seed, kind):
    from scipy.optimize import minimize_scalar

    known, poses, j, size = _known(seed, 4, kind)
    guides = guide_points(poses)
    assert len(guides) == 1  # the circle-point curve's one real point at infinity
    assert math.dist(guides[0].pivot, j["D"]["at"]) <= 1e-9 * size
    # the four poses' one-parameter family of fixed pivots, the centre-point curve, passes
    # through the known pivot where its circle point runs off to infinity
    D = np.array(j["D"]["at"])
    curves = burmester_curves(poses, 3600)
    gap = np.linalg.norm(curves.centre - D, axis=2)
    branch, i = np.unravel_index(np.nanargmin(gap), gap.shape)
    assert gap[branch, i] <= 1e-3 * size
    assert np.linalg.norm(curves.circle[branch, i] - D) >= 100 * size

    def centre_gap(t):
        return min(np.linalg.norm(np.array(d.centre) - D) for d in dyads_at(poses, t)
                   if d is not None)

    t = curves.beta2[i]
    closest = minimize_scalar(centre_gap, bracket=(t - 2e-3, t, t + 2e-3), tol=1e-14)
    assert closest.fun <= 1e-5 * size
    result = motion_synthesis(poses)
    free = [d for d in result.designs if d.kind == "inverted slider-crank" and d.check.defect_free]
    assert free
    for d in free:
        assert _through_poses(d.scene, d.check.crank_angles, poses) <= 1e-9


def _search(poses, starts, rng):
    """Random-start least squares on the guide dyad's own equations -- the pivot ``G``'s
    distance from the coupler line ``{x : Im(x e^{-i psi}) = h}`` (coupler frame) zero in every
    pose -- in ``(Gx, Gy, psi, h)``: the distinct solutions within 20 spreads of pose 1 and the
    smallest residual reached (both in spreads)."""
    from scipy.optimize import least_squares

    P = np.array(poses, dtype=float)
    Z, R = P[:, 0] + 1j * P[:, 1], np.exp(1j * np.radians(P[:, 2]))
    spread = float(np.max(np.abs(Z - Z[0])))

    def f(x):
        g = (complex(x[0], x[1]) - Z) / R  # G in the coupler frame of each pose
        return (g * np.exp(-1j * x[2])).imag - x[3]

    found, best = [], math.inf
    for _ in range(starts):
        x0 = np.concatenate([Z[0].real + spread * rng.uniform(-3, 3, 1),
                             Z[0].imag + spread * rng.uniform(-3, 3, 1),
                             rng.uniform(-math.pi, math.pi, 1), spread * rng.uniform(-3, 3, 1)])
        sol = least_squares(f, x0, xtol=1e-15, ftol=1e-15, gtol=1e-15, method="lm")
        res = float(np.max(np.abs(sol.fun))) / spread
        G = complex(sol.x[0], sol.x[1])
        if abs(G - Z[0]) > 20 * spread:
            continue
        best = min(best, res)
        if res <= 1e-10 and all(abs(G - o) > 1e-6 * spread for o in found):
            found.append(G)
    return found, best, spread


@pytest.mark.parametrize("seed,n", [(7, 4), (8, 4), (9, 5), (10, 0)])
def test_random_start_search_finds_no_guide_the_method_missed(seed, n):
    if n:  # poses of a known inverted slider-crank
        _, poses, _, _ = _known(seed, n)
    else:  # four random poses
        rng = np.random.default_rng(seed)
        poses = [[*rng.uniform(-1.0, 1.0, 2), rng.uniform(-60.0, 60.0)] for _ in range(4)]
    reported = [complex(*g.pivot) for g in guide_points(poses)]
    assert len(reported) == 1  # four poses: one; five of a linkage with a guide: that one
    found, _, spread = _search(poses, 60, np.random.default_rng(seed))
    assert found
    for G in found:
        assert min(abs(G - r) for r in reported) <= 1e-6 * spread
    for r in reported:  # and the search, over its starts, reaches every reported one
        assert min(abs(G - r) for G in found) <= 1e-6 * spread


def test_five_general_poses_have_no_guide_dyad():
    _, best, _ = _search(POSES, 60, np.random.default_rng(0))
    assert best > 1e-6
    assert guide_points(POSES) == []


def test_degenerate_poses_are_refused_with_the_field_named():
    translated = [[0.0, 0.0, 30.0], [1.0, 0.2, 30.0], [1.8, 0.7, 30.0], [2.3, 1.5, 30.0]]
    with pytest.raises(SynthesisError) as err:
        guide_points(translated)
    assert err.value.field == "poses"
    assert "the coupler does not turn between the poses" in err.value.reason
    # rotations about (1, 2): the coupler frame's origin on a circle about it
    about = [[1.0 + math.cos(math.radians(t)), 2.0 + math.sin(math.radians(t)), t]
             for t in (0.0, 20.0, 50.0, 90.0, 130.0)]
    with pytest.raises(SynthesisError) as err:
        guide_points(about)
    assert err.value.field == "poses"
    assert "rotations about one point (1, 2) only" in err.value.reason
    with pytest.raises(SynthesisError) as err:
        motion_synthesis(about)
    assert err.value.field == "poses"


def _targets(scene, deg, turn=0.0):
    """The traced point and the coupler's rotation (plus ``turn``) at crank angles ``deg``."""
    res = solve_at(scene, np.radians(deg))
    return (res.points["P"].position.tolist(),
            (np.asarray(res.links["coupler"].rotation) + turn).tolist())


def test_checker_finds_a_branch_on_the_other_circuit_and_90_degrees_without_offset():
    known = random_inverted_slider_crank(np.random.default_rng(11), "oscillating")
    other, turn = other_assembly(known)
    deg = known["drivers"][0]["start_deg"] + np.array([0.0, 50.0, 100.0, 150.0, 200.0])
    P, rot = _targets(known, deg)
    P2, rot2 = _targets(other, deg, turn)
    # poses 1 and 2 in the assembled mode, 3 to 5 in the other: a branch (and circuit) defect
    c = check_motion(known, deg, point="P", targets=P[:2] + P2[2:], rotations=rot[:2] + rot2[2:])
    assert (c.branch, c.circuit, c.missed, c.dead_centre) == (True, True, (), False)
    assert c.grashof == "oscillating-guide" and c.full_turn
    c = check_motion(known, deg, point="P", targets=P, rotations=rot)
    assert c.defect_free and max(c.errors) <= 1e-9 * c.coupler
    # a coupler line through the crank pin: the pin's force on the guide is along the velocity
    # of the guide's point under it at every crank angle
    centred = random_inverted_slider_crank(np.random.default_rng(12), "rotating", offset=0.0)
    deg = centred["drivers"][0]["start_deg"] + np.array([0.0, 90.0, 180.0, 270.0])
    P, rot = _targets(centred, deg)
    c = check_motion(centred, deg, point="P", targets=P, rotations=rot)
    assert c.grashof == "rotating-guide" and c.defect_free
    assert abs(c.gamma_min - math.pi / 2) <= 1e-9


@pytest.mark.parametrize("seed", [13, 14])
def test_guide_slider_poses_give_it_back_and_a_dead_centre_between_poses_is_found(seed):
    from tests.support.guide_reference import random_guide_slider

    known = random_guide_slider(np.random.default_rng(seed))
    j = {x["name"]: x for x in known["joints"]}
    size = math.dist(j["A"]["at"], j["C"]["at"])
    poses = poses_of(known, 5, span_deg=50.0)
    result = motion_synthesis(poses)
    both = [d for d in result.designs if d.kind == "guide-slider"]
    assert len(both) == 1  # one guide and one slider
    d = both[0]
    at = {x["name"]: x for x in d.scene["joints"]}
    assert math.dist(at["A"]["at"], j["A"]["at"]) <= 1e-9 * size
    assert math.dist(at["C"]["at"], j["C"]["at"]) <= 1e-9 * size
    assert _same_line(at["B"]["axis_deg"], j["B"]["axis_deg"]) <= 1e-9
    assert _same_line(at["C_guide"]["axis_deg"], j["C_guide"]["axis_deg"]) <= 1e-9
    assert d.check.defect_free and d.check.grashof == "guide-slider"
    assert _through_poses(d.scene, d.check.crank_angles, poses) <= 1e-9
    # the coupler's line, 60-120 degrees from the guide in pose 1, turning 160 degrees runs
    # parallel to it between two poses: the block cannot drive the slider through there
    poses = poses_of(known, 5, span_deg=160.0)
    both = [d for d in motion_synthesis(poses).designs if d.kind == "guide-slider"]
    assert len(both) == 1 and both[0].check.dead_centre and not both[0].check.defect_free
