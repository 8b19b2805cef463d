"""The plotting layer writes readable PNGs from hand-made results.

The results here are built by hand (closed-form slider-crank and four-bar
positions, finite-difference rates), not by the solver, so these tests only
depend on the plain data classes and the result container.
"""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

from linkage_sym.model import Driver, Joint, Link, Scene  # noqa: E402
from linkage_sym.numeric.results.result import (  # noqa: E402
    OK,
    SINGULAR,
    UNASSEMBLABLE,
    Analysis,
    JointKinematics,
    LinkKinematics,
)
from linkage_sym.plotting import coupler_curves, mechanism_snapshot, motion_diagrams, plot_all  # noqa: E402
from linkage_sym.plotting.style import status_runs  # noqa: E402

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
N = 37
OMEGA = 10.0


def _rot(theta, p):
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * p[0] - s * p[1], s * p[0] + c * p[1]], axis=-1)


def _rates(theta, values):
    """Time derivatives of values sampled over theta at constant crank speed OMEGA."""
    return np.gradient(values, theta, axis=0) * OMEGA


def _link(rotation, local_a, global_a, theta, com=None):
    """LinkKinematics of a link whose point local_a is at global_a (N, 2)."""
    origin = global_a - _rot(rotation, local_a)
    omega = _rates(theta, rotation)
    lk = LinkKinematics(rotation=rotation, origin=origin, omega=omega,
                        alpha=_rates(theta, omega), origin_velocity=_rates(theta, origin))
    lk.origin_acceleration = _rates(theta, lk.origin_velocity)
    if com is not None:
        lk.com = lk.point(com)
        lk.com_velocity = lk.point_velocity(com)
        lk.com_acceleration = lk.point_acceleration(com)
    return lk


def _joint(lk, at):
    return JointKinematics(lk.point(at), lk.point_velocity(at), lk.point_acceleration(at))


def _blank(analysis, step, status, keep_positions=False):
    """Mark one step as not ok, with NaN where the result contract says so."""
    analysis.status[step] = status
    analysis.messages[step] = f"test: {status}"
    for lk in analysis.links.values():
        names = ["omega", "alpha", "origin_velocity", "origin_acceleration",
                 "com_velocity", "com_acceleration"]
        if not keep_positions:
            names += ["rotation", "origin", "com"]
        for name in names:
            arr = getattr(lk, name)
            if arr is not None:
                arr[step] = np.nan
    for jk in analysis.joints.values():
        for name in ["velocity", "acceleration"] + ([] if keep_positions else ["position"]):
            getattr(jk, name)[step] = np.nan


def slider_crank():
    """Offset-free slider-crank, crank 30 mm, coupler 100 mm; steps 9 and 20 not ok."""
    r, l = 0.03, 0.10
    scene = Scene(
        name="test slider-crank",
        links=(Link("crank", 0.1, (0.015, 0.0), 1e-5), Link("rod", 0.3, (0.08, 0.0), 2e-4),
               Link("piston", 0.5, (0.13, 0.0), 1e-4)),
        joints=(Joint("A", "R", ("ground", "crank"), (0.0, 0.0)),
                Joint("B", "R", ("crank", "rod"), (r, 0.0)),
                Joint("C", "R", ("rod", "piston"), (r + l, 0.0)),
                Joint("D", "P", ("ground", "piston"), (r + l, 0.0), axis=0.0)),
        drivers=(Driver("A", "R", 0.0, 2 * math.pi, N, OMEGA, toward="B"),),
    )
    theta = np.linspace(0.0, 2 * math.pi, N)
    b = np.stack([r * np.cos(theta), r * np.sin(theta)], axis=-1)
    c = np.stack([b[:, 0] + np.sqrt(l**2 - b[:, 1] ** 2), np.zeros(N)], axis=-1)
    phi = np.arctan2(c[:, 1] - b[:, 1], c[:, 0] - b[:, 0])
    links = {
        "crank": _link(theta.copy(), (r, 0.0), b, theta, com=(0.015, 0.0)),
        "rod": _link(phi, (r, 0.0), b, theta, com=(0.08, 0.0)),
        "piston": _link(np.zeros(N), (r + l, 0.0), c, theta, com=(0.13, 0.0)),
    }
    joints = {"A": _joint(links["crank"], (0.0, 0.0)), "B": _joint(links["rod"], (r, 0.0)),
              "C": _joint(links["piston"], (r + l, 0.0)),
              "D": _joint(links["piston"], (r + l, 0.0))}
    analysis = Analysis(
        scene=scene.name, stages=("position", "velocity", "acceleration"),
        status=np.array([OK] * N, dtype=object), messages=[None] * N,
        drivers={"A": {"q": theta.copy(), "qd": np.full(N, OMEGA), "qdd": np.zeros(N)}},
        joints=joints, links=links, condition=np.ones(N), outputs=("kinematics",),
    )
    _blank(analysis, 9, UNASSEMBLABLE)
    _blank(analysis, 20, SINGULAR, keep_positions=True)
    return scene, analysis


def four_bar():
    """The crank-rocker of the scene-format contract, drawn from closed-form positions."""
    A, B, C, D = (np.array(p) for p in ((0.0, 0.0), (0.024, 0.0), (0.066, 0.047), (0.078, 0.0)))
    scene = Scene(
        name="test crank-rocker",
        links=(Link("crank", 0.2, (0.012, 0.0), 1e-5), Link("coupler", 0.5, (0.045, 0.02), 2e-4),
               Link("rocker", 0.3, (0.07, 0.024), 6e-5)),
        joints=(Joint("A", "R", ("ground", "crank"), tuple(A)),
                Joint("B", "R", ("crank", "coupler"), tuple(B)),
                Joint("C", "R", ("coupler", "rocker"), tuple(C)),
                Joint("D", "R", ("rocker", "ground"), tuple(D))),
        drivers=(Driver("A", "R", 0.0, 2 * math.pi, N, OMEGA, toward="B"),),
    )
    theta = np.linspace(0.0, 2 * math.pi, N)
    r1, l2, l3 = np.linalg.norm(B - A), np.linalg.norm(C - B), np.linalg.norm(D - C)
    bs = np.stack([r1 * np.cos(theta), r1 * np.sin(theta)], axis=-1)
    cs = []
    prev = C
    for b in bs:  # circle-circle intersection, branch nearest the previous step
        d = np.linalg.norm(D - b)
        a = (l2**2 - l3**2 + d**2) / (2 * d)
        h = math.sqrt(max(l2**2 - a**2, 0.0))
        e = (D - b) / d
        mid = b + a * e
        cands = [mid + h * np.array([-e[1], e[0]]), mid - h * np.array([-e[1], e[0]])]
        prev = min(cands, key=lambda p: np.linalg.norm(p - prev))
        cs.append(prev)
    cs = np.array(cs)
    ang = lambda v: np.unwrap(np.arctan2(v[:, 1], v[:, 0]))  # noqa: E731
    rot2 = ang(cs - bs) - math.atan2(*(C - B)[::-1])
    rot3 = ang(cs - D) - math.atan2(*(C - D)[::-1])
    links = {
        "crank": _link(theta.copy(), tuple(B), bs, theta, com=(0.012, 0.0)),
        "coupler": _link(rot2, tuple(B), bs, theta, com=(0.045, 0.02)),
        "rocker": _link(rot3, tuple(D), np.tile(D, (N, 1)), theta, com=(0.07, 0.024)),
    }
    joints = {"A": _joint(links["crank"], tuple(A)), "B": _joint(links["coupler"], tuple(B)),
              "C": _joint(links["rocker"], tuple(C)),
              "D": JointKinematics(np.tile(D, (N, 1)), np.zeros((N, 2)), np.zeros((N, 2)))}
    analysis = Analysis(
        scene=scene.name, stages=("position", "velocity", "acceleration"),
        status=np.array([OK] * N, dtype=object), messages=[None] * N,
        drivers={"A": {"q": theta.copy(), "qd": np.full(N, OMEGA), "qdd": np.zeros(N)}},
        joints=joints, links=links, condition=np.ones(N), outputs=("kinematics",),
    )
    return scene, analysis


def shaper():
    """Shaper of example 3-7 (l1 = 125, l3 = 600, l4 = 150 mm): a slider on a swinging guide."""
    l1, l3, l4 = 0.125, 0.600, 0.150
    th3_0, th4_0 = math.radians(65.55610), math.radians(169.93820)
    l6 = l1 * math.tan(th3_0)
    l6p = l3 * math.sin(th3_0) + l4 * math.sin(th4_0)
    A, B, C = np.array([0.0, l6]), np.array([l1, l6]), np.zeros(2)
    D = l3 * np.array([math.cos(th3_0), math.sin(th3_0)])
    E = D + l4 * np.array([math.cos(th4_0), math.sin(th4_0)])
    t = lambda p: tuple(float(v) for v in p)  # noqa: E731
    scene = Scene(
        name="test shaper",
        links=(Link("crank"), Link("block", 1.0, t(B)), Link("rocker", 5.0, t(D / 2), 0.15),
               Link("rod", 1.0, t((D + E) / 2), 2e-3), Link("ram", 10.0, t(E))),
        joints=(Joint("A", "R", ("ground", "crank"), t(A)),
                Joint("B", "R", ("crank", "block"), t(B)),
                Joint("B'", "P", ("rocker", "block"), t(B), axis=th3_0),
                Joint("C", "R", ("ground", "rocker"), t(C)),
                Joint("D", "R", ("rocker", "rod"), t(D)),
                Joint("E", "R", ("rod", "ram"), t(E)),
                Joint("F", "P", ("ground", "ram"), t(E), axis=0.0)),
        drivers=(Driver("A", "R", 0.0, 2 * math.pi, N, OMEGA, toward="B"),),
    )
    th1 = np.linspace(0.0, 2 * math.pi, N)
    bs = np.stack([l1 * np.cos(th1), l6 + l1 * np.sin(th1)], axis=-1)
    th3 = np.arctan2(bs[:, 1], bs[:, 0])
    ds = l3 * np.stack([np.cos(th3), np.sin(th3)], axis=-1)
    th4 = math.pi - np.arcsin((l6p - ds[:, 1]) / l4)
    es = ds + l4 * np.stack([np.cos(th4), np.sin(th4)], axis=-1)
    links = {
        "crank": _link(th1.copy(), t(A), np.tile(A, (N, 1)), th1),
        "block": _link(th3 - th3_0, t(B), bs, th1, com=t(B)),
        "rocker": _link(th3 - th3_0, t(C), np.zeros((N, 2)), th1, com=t(D / 2)),
        "rod": _link(th4 - th4_0, t(D), ds, th1, com=t((D + E) / 2)),
        "ram": _link(np.zeros(N), t(E), es, th1, com=t(E)),
    }
    joints = {"A": _joint(links["crank"], t(A)), "B": _joint(links["block"], t(B)),
              "B'": _joint(links["block"], t(B)), "C": _joint(links["rocker"], t(C)),
              "D": _joint(links["rod"], t(D)), "E": _joint(links["ram"], t(E)),
              "F": _joint(links["ram"], t(E))}
    analysis = Analysis(
        scene=scene.name, stages=("position", "velocity", "acceleration"),
        status=np.array([OK] * N, dtype=object), messages=[None] * N,
        drivers={"A": {"q": th1.copy(), "qd": np.full(N, OMEGA), "qdd": np.zeros(N)}},
        joints=joints, links=links, condition=np.ones(N), outputs=("kinematics",),
    )
    return scene, analysis


def _assert_png(path):
    assert path.exists()
    data = path.read_bytes()
    assert len(data) > 1000
    assert data[:8] == PNG_SIGNATURE


@pytest.mark.parametrize("make", [pytest.param(slider_crank, marks=pytest.mark.slow), four_bar,
                                  pytest.param(shaper, marks=pytest.mark.slow)])
def test_motion_diagrams_write_three_pngs(tmp_path, make):
    scene, analysis = make()
    out = tmp_path / "nested" / "dir"
    paths = motion_diagrams(scene, analysis, out)
    assert [p.name for p in paths] == [
        f"{scene.name.replace(' ', '_')}_{k}.png"
        for k in ("positions", "velocities", "accelerations")
    ]
    for p in paths:
        _assert_png(p)


@pytest.mark.slow
def test_prefix_names_the_files(tmp_path):
    scene, analysis = slider_crank()
    paths = motion_diagrams(scene, analysis, tmp_path, prefix="run1")
    assert {p.name for p in paths} == {"run1_positions.png", "run1_velocities.png",
                                       "run1_accelerations.png"}
    assert all(p.parent == tmp_path for p in paths)


def test_a_stage_that_did_not_run_is_not_drawn(tmp_path):
    scene, analysis = slider_crank()
    analysis.stages = ("position",)
    paths = motion_diagrams(scene, analysis, tmp_path)
    assert [p.name.rsplit("_", 1)[1] for p in paths] == ["positions.png"]


@pytest.mark.parametrize("make", [slider_crank, four_bar,
                                  pytest.param(shaper, marks=pytest.mark.slow)])
def test_coupler_curves_write_one_png(tmp_path, make):
    scene, analysis = make()
    out = tmp_path / "sub" / "paths.png"
    assert coupler_curves(scene, analysis, out) == out
    _assert_png(out)


@pytest.mark.slow
def test_nan_gaps_and_all_bad_steps_do_not_raise(tmp_path):
    scene, analysis = slider_crank()
    assert np.isnan(analysis.links["rod"].rotation[9])
    assert np.isnan(analysis.links["rod"].omega[20])
    assert np.isfinite(analysis.links["rod"].rotation[20])
    for p in plot_all(scene, analysis, tmp_path / "gaps"):
        _assert_png(p)
    for step in range(N):  # nothing solved at all
        _blank(analysis, step, UNASSEMBLABLE)
    for p in plot_all(scene, analysis, tmp_path / "nothing"):
        _assert_png(p)


def test_snapshot_of_an_unsolved_step_draws_nothing():
    from matplotlib.figure import Figure

    scene, analysis = slider_crank()
    ax = Figure().subplots()
    assert mechanism_snapshot(scene, analysis, 9, ax) == []
    assert mechanism_snapshot(scene, analysis, 20, ax)  # singular: positions known
    assert mechanism_snapshot(scene, analysis, None, ax)  # assembly configuration


def test_a_prismatic_driver_puts_metres_on_the_x_axis():
    """Metres, as the result files have them (the axis was in mm for a scene under 1 m)."""
    from dataclasses import replace

    from linkage_sym.plotting.motion import driver_axis, motion_figure

    scene, analysis = slider_crank()
    scene = replace(scene, drivers=(Driver("D", "P", 0.0, -0.06, N, 1.0),))
    q = np.linspace(0.0, -0.06, N)
    analysis.drivers = {"D": {"q": q.copy(), "qd": np.ones(N), "qdd": np.zeros(N)}}
    x, label, unit = driver_axis(scene, analysis)
    assert unit == "m" and "(m)" in label
    assert np.array_equal(x, q)
    fig = motion_figure(scene, analysis, "velocity")
    assert fig.axes[-1].get_xlabel() == label


@pytest.mark.parametrize("quantity,unit", [("position", "m"), ("velocity", "m/s"),
                                           ("acceleration", "m/s²")])
def test_slider_panels_are_in_the_units_of_the_result_files(quantity, unit):
    """The slider panel of each motion diagram is in m, m/s, m/s², as the result files (it was
    in mm, mm/s, mm/s² for a scene under 1 m).  Reference: the ram's point E read off the
    hand-made result, along the slide (axis 0: its x component)."""
    from linkage_sym.plotting.motion import motion_figure

    scene, analysis = shaper()
    (ax,) = [a for a in motion_figure(scene, analysis, quantity).axes
             if a.get_ylabel().startswith("slider")]
    assert ax.get_ylabel().endswith(f"({unit})")
    (line,) = [ln for ln in ax.get_lines() if ln.get_label().startswith(("s:", "v:", "a:"))]
    jk = analysis.joints["F"]
    want = {"position": jk.position[:, 0] - scene.joint("F").at[0],
            "velocity": jk.velocity[:, 0], "acceleration": jk.acceleration[:, 0]}[quantity]
    scale = float(np.max(np.abs(want)))
    assert np.max(np.abs(line.get_ydata() - want)) <= 1e-12 * scale


def test_status_runs_split_by_status():
    status = [OK, UNASSEMBLABLE, UNASSEMBLABLE, SINGULAR, OK, UNASSEMBLABLE]
    assert status_runs(status) == [(UNASSEMBLABLE, 1, 2), (SINGULAR, 3, 3), (UNASSEMBLABLE, 5, 5)]


@pytest.mark.slow
def test_plotting_changes_no_global_matplotlib_state():
    """Importing and plotting neither imports pyplot nor switches the backend."""
    code = (
        "import sys, tempfile;"
        "import tests.plotting.test_plotting as t, linkage_sym.plotting as lp;"
        "s, a = t.slider_crank();"
        "lp.plot_all(s, a, tempfile.mkdtemp());"
        "assert 'matplotlib.pyplot' not in sys.modules, 'pyplot imported';"
        "assert 'sympy' not in sys.modules, 'sympy imported'"
    )
    import pathlib

    root = pathlib.Path(__file__).resolve().parents[2]
    subprocess.run([sys.executable, "-c", code], check=True, cwd=root)


def test_transmission_minimum_is_marked_where_it_is_read():
    """The crank-rocker's gamma at C peaks at 132 deg at 180 deg of the crank, which is 48.2 deg
    from folding: the mark (and its label) sit at min(gamma, 180 - gamma) = 48.2 deg there, not
    on gamma's maximum.  Reference: the angle between C->B and C->D from the joints' positions."""
    import linkage_sym
    from linkage_sym.plotting.transmission import transmission_figure

    scene = linkage_sym.load_example("crank_rocker")
    res = linkage_sym.analyze(scene)
    B, C, D = (np.asarray(res.joints[j].position, dtype=float) for j in "BCD")
    u, v = B - C, D - C
    gamma = np.degrees(np.arctan2(np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]),
                                  np.sum(u * v, axis=1)))
    dev = np.minimum(gamma, 180.0 - gamma)
    k = int(np.argmin(dev))
    assert gamma[k] > 90.0  # the case of the report: read off the reflected value
    ax = transmission_figure(scene, res).axes[0]
    marks = [ln for ln in ax.get_lines() if ln.get_marker() == "o"]
    assert len(marks) == 1
    (mx,), (my,) = marks[0].get_data()
    assert mx == pytest.approx(np.degrees(res.drivers["A"]["q"][k]), rel=1e-12)
    assert my == pytest.approx(dev[k], rel=1e-9)
    texts = [t for t in ax.texts if t.get_text().endswith("°")]
    assert [t.get_text() for t in texts] == [f"{dev[k]:.3g}°"]
    assert texts[0].xy == pytest.approx((mx, my), rel=1e-12)


def _luminance(rgb):
    """WCAG 2 relative luminance of an sRGB colour (components 0..1)."""
    c = np.asarray(rgb[:3], dtype=float)
    c = np.where(c <= 0.03928, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return float(0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2])


@pytest.mark.parametrize("make", [slider_crank, "wide"])
def test_the_label_of_a_band_of_unsolved_steps_is_legible(make):
    """The written status of a band (``unassemblable``) was 7 pt grey 0.35 on the band's grey
    0.82, under the grid lines (contrast 3.3:1).  It is now at least 8 pt, at least 7:1 against
    what is behind it (WCAG's enhanced contrast) and above the grid."""
    from matplotlib.colors import to_rgba

    from linkage_sym.plotting.motion import motion_figure

    scene, analysis = slider_crank()
    if make == "wide":  # a band a third of the sweep wide
        for step in range(10, 22):
            _blank(analysis, step, UNASSEMBLABLE)
    ax = motion_figure(scene, analysis, "position").axes[0]
    labels = [t for t in ax.texts if t.get_text() in (UNASSEMBLABLE, SINGULAR)]
    assert {t.get_text() for t in labels} == ({UNASSEMBLABLE, SINGULAR} if make != "wide"
                                              else {UNASSEMBLABLE})
    grid_z = max(g.get_zorder() for g in ax.xaxis.get_gridlines())
    for t in labels:
        box = t.get_bbox_patch()
        behind = box.get_facecolor() if box is not None else to_rgba("0.82")
        hi, lo = sorted((_luminance(to_rgba(t.get_color())), _luminance(behind)), reverse=True)
        assert (hi + 0.05) / (lo + 0.05) >= 7.0, t.get_text()
        assert t.get_fontsize() >= 8.0
        assert t.get_zorder() > grid_z


def _patch(ax, gid):
    (found,) = [p for p in list(ax.patches) + list(ax.lines) if p.get_gid() == gid]
    return found


@pytest.mark.parametrize("step", [None, 0, 17, 40, 72])
def test_a_cam_is_drawn_as_its_profile_turning_with_it(step):
    """The eccentric cam of problem 3-8 was a bar from its pivot A to the contact K.  It is
    its circle (centre (0, 15) mm on the cam, radius 25 mm), turned with the cam: every drawn
    point is 25 mm from where the result's rotation of the cam carries the centre (1e-9
    relative: the points are on the circle up to rounding), and no bar joins A and K."""
    from matplotlib.figure import Figure

    import linkage_sym

    scene = linkage_sym.load_example("cam_eccentric_rocker")
    res = linkage_sym.analyze(scene)
    ax = Figure().subplots()
    mechanism_snapshot(scene, res, step, ax, unit_scale=1000.0)
    th = 0.0 if step is None else float(res.links["cam"].rotation[step])
    centre = np.array([-math.sin(th), math.cos(th)]) * 15.0  # A is the origin
    ring = _patch(ax, "cam profile K").get_xy()
    assert len(ring) > 100
    dist = np.hypot(*(ring - centre).T)
    assert np.max(np.abs(dist - 25.0)) <= 1e-9 * 25.0
    A, K = np.zeros(2), np.asarray(scene.joint("K").at) * 1000.0
    if step is not None:
        K = np.asarray(res.links["follower"].point(scene.joint("K").at)[step]) * 1000.0
    for line in ax.lines:
        xy = np.asarray(line.get_xydata())
        if len(xy) == 2:
            ends = sorted((tuple(np.round(xy[0], 6)), tuple(np.round(xy[1], 6))))
            assert ends != sorted((tuple(np.round(A, 6)), tuple(np.round(K, 6))))


@pytest.mark.parametrize("step", [None, 30, 90, 150])
def test_a_roller_touches_the_drawn_working_profile(step):
    """The cycloidal cam's pitch curve (``"pitch": true``) and its roller (10 mm): the roller
    is drawn at the follower's point, and the drawn working profile, turned with the cam,
    touches it: its nearest point is a roller's radius from the roller's centre (1e-4
    relative: the profile is drawn as 720 chords, which stray from the curve by about
    r (pi/720)^2 / 2 = 6e-7 m)."""
    from matplotlib.figure import Figure

    import linkage_sym

    scene = linkage_sym.load_example("cam_cycloidal_roller")
    res = linkage_sym.analyze(scene)
    ax = Figure().subplots()
    mechanism_snapshot(scene, res, step, ax, unit_scale=1000.0)
    at = scene.joint("K").at
    centre = np.asarray(at if step is None else res.links["follower"].point(at)[step]) * 1000
    roller = _patch(ax, "cam follower K")
    assert roller.get_center() == pytest.approx(tuple(centre), rel=1e-12)
    assert roller.get_radius() == pytest.approx(10.0, rel=1e-12)
    ring = _patch(ax, "cam profile K").get_xy()
    assert np.min(np.hypot(*(ring - centre).T)) == pytest.approx(10.0, rel=1e-4)
