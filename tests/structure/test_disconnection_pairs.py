"""A class-IV Assur group that only pairs of binary links reduce to dyads.

The mechanism
-------------
A crank (``A``, ground; ``B``, pin) drives an eight-link Assur group made of
two *quaternary* platforms ``P`` and ``Q`` coupled by two binary links
``c1`` (E1-F1) and ``c2`` (E2-F2), the closed contour P-c1-Q-c2 of four
links (class IV).  ``P`` hangs from the crank pin by ``a1`` (B-C1) and from
the ground by ``a2`` (C2-D2); ``Q`` hangs from the ground by ``b1`` (G1-H1)
and ``b2`` (G2-H2).  Every joint is a revolute: 9 moving links, 13 joints,
mobility 1.  The crank turns a full revolution, 37 steps, with a speed and
an acceleration; every link has a mass, an inertia and a centre of mass off
the line of its joints; gravity, a force on ``Q`` and a torque on ``b1``
act as well.

Why only pairs work (worked out by hand from the graph, not by the code):

* removing one binary link leaves one degree of freedom, so one
  hypothetical input: removing ``c1`` (or ``c2``) leaves ``P`` and ``Q``
  on one coupler, and whichever side the input is on, the other platform
  with its two hangers and the coupler is a triad; removing a hanger
  (``a1``, say) leaves ``P`` with one hanger, and the input either leaves
  a six-link group or makes ``Q`` known and ``P, c1, c2, a2`` a triad;
* cutting one internal joint leaves two inputs: cutting a coupler joint
  leaves that coupler dangling from one platform (never a dyad), cutting a
  hanger's platform joint forces that hanger to be one of the inputs and
  the other input again leaves a triad or a larger group (joints to the
  crank or the ground are external: never cut).

Pairs that work: (hanger of one platform, coupler), inputs the other hanger
of that platform and either hanger of the other (4 pairs x 2); both
couplers, inputs one hanger of each platform (4); pairs of hangers fail
(both hangers of one platform: the only inputs left are the other
platform's two hangers, which over-constrain it; one of each: the 4-link
group P-c1-Q-c2 is left).  That is 20 choices, each two unknowns X1, X2 from a
2x2 system, each with two RRR dyads.

What is checked, and against what
---------------------------------
* Structure: the decomposition and the 20 choices against the hand-derived
  list above; the ``structure`` command prints them.
* ``method="dyad"`` (superposition over the default pair) against
  ``method="global"`` (one sparse solve): every reaction, the driving
  torque, the frame force and moment, to 1e-9 of the sweep's largest
  magnitude of that quantity.  The two are not fully independent: the
  removed pair's reactions are split with ``global_statics.assemble``
  (``superposition._Choice._split_svd``), which the global method also
  uses.  So the results are also checked against identities that share no
  code with the library: every link's equilibrium
  (:func:`force_checks.link_residuals`), the frame force and moment from
  the momentum balance of the whole mechanism, and the power balance, all
  written here from the reported kinematics.
* Every one of the 20 choices, forced with ``compile_plan(scene,
  disconnection=k)`` and asserted to be the one used at every step, gives
  the global reactions to the same 1e-9.
* The groups' amplification is finite at every ok step.

Why 1e-9 holds: the sweep is far from singular positions (dimensionless
condition number below 1e3, asserted) and every choice's amplification
stays below ``AMPLIFICATION_LIMIT`` = 1e3 (asserted through ``used == k``),
so at most about 3 + 2 digits are lost from 1e-16.  Observed worst: 2.0e-15
(dyad vs global), 1.8e-12 (choice 13, amplification 387), 1.9e-15 (power),
7e-16 (frame), 1.9e-15 (link equilibrium).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import linkage_sym
from tests.support.force_checks import link_residuals
from linkage_sym.cli import main
from linkage_sym.numeric.plan import compile_plan
from linkage_sym.structure import decompose, disconnections

TOL = 1e-9

SCENE = {
    "name": "class4-pairs",
    "links": [
        {"name": "crank", "mass": 0.4, "com": [0.02, 0.015], "inertia": 1.0e-4},
        {"name": "a1", "mass": 1.3, "com": [0.035, 0.085], "inertia": 4.7e-3},
        {"name": "P", "mass": 1.2, "com": [0.15, 0.165], "inertia": 5.8e-3},
        {"name": "a2", "mass": 0.6, "com": [0.178, 0.047], "inertia": 1.5e-3},
        {"name": "c1", "mass": 0.45, "com": [0.27, 0.276], "inertia": 2.1e-3},
        {"name": "c2", "mass": 0.8, "com": [0.32, 0.146], "inertia": 3.4e-3},
        {"name": "Q", "mass": 0.9, "com": [0.478, 0.219], "inertia": 3.5e-3},
        {"name": "b1", "mass": 0.85, "com": [0.536, 0.209], "inertia": 2.0e-3},
        {"name": "b2", "mass": 1.0, "com": [0.49, 0.046], "inertia": 2.8e-3},
    ],
    "joints": [
        {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
        {"name": "B", "type": "R", "links": ["crank", "a1"], "at": [0.04, 0.0]},
        {"name": "C1", "type": "R", "links": ["a1", "P"], "at": [0.05, 0.18]},
        {"name": "C2", "type": "R", "links": ["P", "a2"], "at": [0.17, 0.12]},
        {"name": "D2", "type": "R", "links": ["a2", "ground"], "at": [0.20, -0.05]},
        {"name": "E1", "type": "R", "links": ["P", "c1"], "at": [0.17, 0.26]},
        {"name": "F1", "type": "R", "links": ["c1", "Q"], "at": [0.40, 0.30]},
        {"name": "E2", "type": "R", "links": ["P", "c2"], "at": [0.20, 0.17]},
        {"name": "F2", "type": "R", "links": ["c2", "Q"], "at": [0.42, 0.14]},
        {"name": "G1", "type": "R", "links": ["Q", "b1"], "at": [0.50, 0.28]},
        {"name": "H1", "type": "R", "links": ["b1", "ground"], "at": [0.60, 0.10]},
        {"name": "G2", "type": "R", "links": ["Q", "b2"], "at": [0.52, 0.12]},
        {"name": "H2", "type": "R", "links": ["b2", "ground"], "at": [0.45, -0.05]},
    ],
    "drivers": [
        {"joint": "A", "toward": "B", "start_deg": 0, "stop_deg": 360, "steps": 37,
         "speed": 12.0, "acceleration": 30.0}
    ],
    "loads": [
        {"link": "Q", "force": [15.0, -25.0], "at": [0.47, 0.25]},
        {"link": "b1", "torque": 2.0},
    ],
    "effects": {"inertia": True, "gravity": [0.0, -9.81], "loads": True},
    "outputs": ["kinematics", "reactions", "driving", "frame"],
}

GROUP = ("a1", "P", "a2", "c1", "c2", "Q", "b1", "b2")
PIVOT = {"a1": "B", "a2": "D2", "b1": "H1", "b2": "H2"}  # each hanger's joint to a known link
JOINTS_OF = {"a1": {"B", "C1"}, "a2": {"C2", "D2"}, "c1": {"E1", "F1"}, "c2": {"E2", "F2"},
             "b1": {"G1", "H1"}, "b2": {"G2", "H2"}}


def expected_choices():
    """The 20 (removed links, hypothetical inputs) derived by hand (module docstring)."""
    other = {"a1": "a2", "a2": "a1", "b1": "b2", "b2": "b1"}
    out = set()
    for c in ("c1", "c2"):
        for h in ("a1", "a2", "b1", "b2"):
            far = ("b1", "b2") if h[0] == "a" else ("a1", "a2")
            for f in far:
                out.add((frozenset({h, c}), frozenset({(other[h], PIVOT[other[h]]),
                                                       (f, PIVOT[f])})))
    for a in ("a1", "a2"):
        for b in ("b1", "b2"):
            out.add((frozenset({"c1", "c2"}), frozenset({(a, PIVOT[a]), (b, PIVOT[b])})))
    return out


# --------------------------------------------------------------------------- fixtures
@pytest.fixture(scope="module")
def scene():
    return linkage_sym.load_scene(SCENE)


@pytest.fixture(scope="module")
def group(scene):
    return decompose(scene).groups[1]


@pytest.fixture(scope="module")
def runs(scene):
    plan = compile_plan(scene)
    a = plan.run(exact_condition=True)
    g = plan.run(method="global")
    # the premise of every tolerance here: a full turn, every step solved, far from singular
    assert a.ok.all() and g.ok.all(), [m for m in a.messages if m][:3]
    assert np.nanmax(a.condition) < 1e3
    return plan, a, g


def rel_err(diff, ref):
    """Largest |diff| over the sweep divided by the largest |ref| (vectors: Euclidean norm)."""
    diff, ref = np.asarray(diff, float), np.asarray(ref, float)
    if diff.ndim == 2:
        diff, ref = np.hypot(*diff.T), np.hypot(*ref.T)
    return float(np.max(np.abs(diff)) / np.max(np.abs(ref)))


def max_errors(f, ref):
    """Worst relative error of each force quantity of ``f`` against ``ref``."""
    errs = {j: rel_err(f.reactions[j] - ref.reactions[j], ref.reactions[j]) for j in ref.reactions}
    errs["driving A"] = rel_err(f.driving["A"] - ref.driving["A"], ref.driving["A"])
    errs["frame force"] = rel_err(f.frame_force - ref.frame_force, ref.frame_force)
    errs["frame moment"] = rel_err(f.frame_moment - ref.frame_moment, ref.frame_moment)
    return errs


# --------------------------------------------------------------------------- structure
def test_one_class_iv_group_of_eight_links(scene):
    dec = decompose(scene)
    assert [(g.kind, set(g.links)) for g in dec.groups] == [
        ("input", {"crank"}), ("group", set(GROUP))]
    g = dec.groups[1]
    assert g.assur_class == 4 and g.label == "group (class IV)"
    assert set(g.external) == {"B", "D2", "H1", "H2"}
    assert set(g.internal) == {"C1", "C2", "E1", "F1", "E2", "F2", "G1", "G2"}


def test_only_pairs_of_binary_links_disconnect(scene, group):
    choices = disconnections(scene, group)
    # a single removal never appears: the pairs branch was taken, and it found them all
    assert all(len(c.removed_links) == 2 for c in choices)
    got = {(frozenset(c.removed_links), frozenset(c.inputs)) for c in choices}
    assert len(got) == len(choices) == 20
    assert got == expected_choices()
    for c in choices:
        # both removed links are binary links of the group, cut at their two joints
        assert set(c.removed_links) <= set(JOINTS_OF)
        assert set(c.removed_joints) == set().union(*(JOINTS_OF[n] for n in c.removed_links))
        assert c.unknowns == 2 and c.sliding == (False, False)
        # the rest falls apart into two RRR dyads
        assert [d.dyad_type for d in c.dyads] == ["RRR", "RRR"]
        covered = [n for d in c.dyads for n in d.links] + [n for n, _ in c.inputs]
        assert sorted(covered + list(c.removed_links)) == sorted(GROUP)
        assert c.describe().startswith(
            f"remove link '{c.removed_links[0]}', link '{c.removed_links[1]}' (joints ")


def test_structure_command_lists_the_pair_choices(tmp_path, capsys, scene, group):
    path = tmp_path / "class4.json"
    path.write_text(json.dumps(SCENE))
    assert main(["structure", str(path)]) == 0
    text = capsys.readouterr().out
    assert "group (class IV): a1, P, a2, c1, c2, Q, b1, b2;" in text
    lines = [ln.strip() for ln in text.splitlines() if ") remove link '" in ln]
    assert len(lines) == 20
    assert sum(ln.endswith("(default)") for ln in lines) == 1
    for k, (ln, c) in enumerate(zip(lines, disconnections(scene, group))):
        assert ln.startswith(f"{k}) {c.describe()}")


# --------------------------------------------------------------------------- forces
def test_dyad_method_equals_global(runs):
    plan, a, g = runs
    info = a.forces.groups[1]
    assert info.method == "disconnection" and len(info.choices) == 20
    assert (info.used == info.used[0]).all()  # the default pair, never a fallback
    for j in a.forces.reaction_moments:  # all revolutes: no reaction couple
        assert not a.forces.reaction_moments[j].any() and not g.forces.reaction_moments[j].any()
    errs = max_errors(a.forces, g.forces)
    worst = max(errs, key=errs.get)
    assert errs[worst] <= TOL, (worst, errs[worst])


@pytest.mark.slow
def test_every_pair_disconnection_gives_the_same_forces(scene, runs):
    plan, _, g = runs
    for k in range(20):
        b = compile_plan(scene, disconnection=k).run()
        assert b.ok.all()
        info = b.forces.groups[1]
        # the forced choice is used at every step (no fallback hides it)
        assert (info.used == k).all(), (k, np.nanmax(info.amplification))
        errs = max_errors(b.forces, g.forces)
        worst = max(errs, key=errs.get)
        assert errs[worst] <= TOL, (k, info.choices[k], worst, errs[worst])


def test_amplification_is_finite_on_ok_steps(runs):
    _, a, _ = runs
    amps = [grp.amplification for grp in a.forces.groups if grp.amplification is not None]
    assert len(amps) == 1
    assert np.isfinite(amps[0][a.ok]).all() and (amps[0][a.ok] >= 1.0).all()


# ----------------------------------------------------- identities that share no library code
def _load_point(a, load):
    """Position and velocity (N, 2) of a load's point, from its link's reported com motion."""
    link = next(lk for lk in SCENE["links"] if lk["name"] == load["link"])
    lk = a.links[load["link"]]
    d = np.subtract(load["at"], link["com"])
    th = lk.rotation
    r = np.stack([np.cos(th) * d[0] - np.sin(th) * d[1],
                  np.sin(th) * d[0] + np.cos(th) * d[1]], axis=-1)
    v = lk.com_velocity + lk.omega[:, None] * np.stack([-r[:, 1], r[:, 0]], axis=-1)
    return lk.com + r, v


def test_power_balance(runs):
    """Driver power = dT/dt - P_gravity - P_loads, to 1e-9 of the sum of the terms' magnitudes."""
    _, a, g = runs
    grav = np.array(SCENE["effects"]["gravity"])
    terms = []  # each (N,), signed so that their sum is dT/dt - P_gravity - P_loads
    for link in SCENE["links"]:
        lk = a.links[link["name"]]
        terms.append(link["mass"] * np.sum(lk.com_velocity * lk.com_acceleration, axis=1))
        terms.append(link["inertia"] * lk.omega * lk.alpha)
        terms.append(-link["mass"] * lk.com_velocity @ grav)
    for load in SCENE["loads"]:
        if "force" in load:
            terms.append(-_load_point(a, load)[1] @ np.array(load["force"]))
        if "torque" in load:
            terms.append(-load["torque"] * a.links[load["link"]].omega)
    rhs = np.sum(terms, axis=0)
    scale = np.sum(np.abs(terms), axis=0)
    qd = a.drivers["A"]["qd"]
    assert (qd == 12.0).all() and (a.drivers["A"]["qdd"] == 30.0).all()
    for res in (a, g):
        drive = res.forces.driving["A"] * qd
        err = np.max(np.abs(drive - rhs) / (scale + np.abs(drive)))
        assert err <= TOL, (res.forces.method, err)


def test_frame_from_momentum_balance(runs):
    """Frame force and moment = what gravity, loads and d'Alembert terms put on the moving links.

    Sum over the moving links: m (g - a_G) and, about the origin, G x m (g - a_G) - I alpha, plus
    the loads; to 1e-9 of the sum of the terms' magnitudes.
    """
    _, a, g = runs
    grav = np.array(SCENE["effects"]["gravity"])
    forces, moments = [], []
    for link in SCENE["links"]:
        lk = a.links[link["name"]]
        f = link["mass"] * (grav - lk.com_acceleration)
        forces.append(f)
        moments.append(lk.com[:, 0] * f[:, 1] - lk.com[:, 1] * f[:, 0])
        moments.append(-link["inertia"] * lk.alpha)
    for load in SCENE["loads"]:
        if "force" in load:
            p = _load_point(a, load)[0]
            f = np.broadcast_to(np.array(load["force"], float), p.shape)
            forces.append(f)
            moments.append(p[:, 0] * f[:, 1] - p[:, 1] * f[:, 0])
        if "torque" in load:
            moments.append(np.full(a.n_steps, load["torque"]))
    F = np.sum(forces, axis=0)
    M = np.sum(moments, axis=0)
    sF = np.sum([np.hypot(*f.T) for f in forces], axis=0)
    sM = np.sum(np.abs(moments), axis=0)
    for res in (a, g):
        eF = np.max(np.hypot(*(res.forces.frame_force - F).T) / sF)
        eM = np.max(np.abs(res.forces.frame_moment - M) / sM)
        assert eF <= TOL and eM <= TOL, (res.forces.method, eF, eM)


def test_every_link_is_in_equilibrium(scene, runs):
    """Each link's force and moment balance (force_checks), to 1e-9 of its terms' magnitudes."""
    _, a, _ = runs
    for link, (rf, rm, sf, sm) in link_residuals(scene, a).items():
        assert np.max(np.hypot(*rf.T) / sf) <= TOL, (link, "force")
        assert np.max(np.abs(rm) / sm) <= TOL, (link, "moment")
