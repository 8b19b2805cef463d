"""The force plots write readable PNGs from kinematics plus hand-made forces.

The force solver is not used: the kinematics come from the real solving plan,
the :class:`~linkage_sym.numeric.results.result.Forces` are built here (the shaking
force and moment from the links' inertia, the reactions and efforts made up),
with a few steps marked not ``ok`` and NaN like the result contract says.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

import linkage_sym
from linkage_sym.model import Driver, Effects, Joint, Link, Scene
from linkage_sym.numeric.plan import compile_plan
from linkage_sym.numeric.results.result import (
    OK,
    SINGULAR,
    UNASSEMBLABLE,
    Analysis,
    Forces,
    JointKinematics,
    LinkKinematics,
)
from linkage_sym.plotting import driving_effort, frame_loads, plot_all, reaction_hodographs
from linkage_sym.plotting.forces import (
    driving_effort_figure,
    frame_loads_figure,
    frame_words,
    inertia_only,
    reaction_hodographs_figure,
)

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
BAD_STEPS = {40: UNASSEMBLABLE, 41: UNASSEMBLABLE, 200: SINGULAR}


def synthetic_forces(scene: Scene, analysis: Analysis) -> Forces:
    """Forces of the right shapes: inertia-based frame loads, made-up reactions and efforts."""
    n = analysis.n_steps
    frame_force = np.zeros((n, 2))
    frame_moment = np.zeros(n)
    for link in scene.links:
        lk = analysis.links[link.name]
        if lk.com is None or lk.com_acceleration is None:
            continue
        ma = link.mass * np.asarray(lk.com_acceleration, dtype=float)
        frame_force -= ma
        com = np.asarray(lk.com, dtype=float)
        frame_moment -= (com[:, 0] * ma[:, 1] - com[:, 1] * ma[:, 0]
                         + link.inertia * np.asarray(lk.alpha))
    reactions, moments = {}, {}
    theta = np.linspace(0.0, 2 * math.pi, n)
    for k, joint in enumerate(scene.joints):
        amp = 3.0 + k
        r = np.stack([amp * np.cos(theta + k) + 1.0, 0.6 * amp * np.sin(2 * theta - k)], axis=-1)
        reactions[joint.name] = r + frame_force * (k % 2)
        moments[joint.name] = 0.05 * np.sin(theta) if joint.type == "P" else np.zeros(n)
    driving = {
        d.joint: (0.4 * np.sin(theta + k) + 0.1 * np.cos(3 * theta) + 0.05)
        * (1.0 if d.kind == "R" else 50.0)
        for k, d in enumerate(scene.drivers)
    }
    return Forces(method="dyad", reactions=reactions, reaction_moments=moments, driving=driving,
                  frame_force=frame_force, frame_moment=frame_moment)


def _mark_bad(analysis: Analysis, steps: dict) -> None:
    """Mark steps not ok and NaN every force (and rate) there."""
    for step, status in steps.items():
        analysis.status[step] = status
        analysis.messages[step] = f"test: {status}"
        f = analysis.forces
        for arr in (*f.reactions.values(), *f.reaction_moments.values(), *f.driving.values(),
                    f.frame_force, f.frame_moment):
            arr[step] = np.nan


def example(name: str = "crank_rocker", *, effects: Effects | None = None, bad=BAD_STEPS):
    """A real example's kinematics with synthetic forces attached."""
    scene = linkage_sym.load_example(name)
    if effects is not None:
        scene = replace(scene, effects=effects)
    analysis = compile_plan(scene).run()
    analysis.status = np.asarray(analysis.status, dtype=object).copy()
    analysis.forces = synthetic_forces(scene, analysis)
    analysis.p_joints = tuple(j.name for j in scene.joints if j.type == "P")
    if "forces" not in analysis.stages:
        analysis.stages = tuple(analysis.stages) + ("forces",)
    _mark_bad(analysis, {k: v for k, v in bad.items() if k < analysis.n_steps})
    return scene, analysis


INERTIA_ONLY = Effects(inertia=True, gravity=None, loads=False)


def _assert_png(path):
    from matplotlib.image import imread

    assert path.exists() and path.stat().st_size > 1000
    assert path.read_bytes()[:8] == PNG_SIGNATURE
    img = imread(path)
    assert img.ndim == 3 and img.shape[0] > 300 and img.shape[1] > 300
    rgb = img[..., :3].reshape(-1, 3)
    assert np.ptp(rgb, axis=0).max() > 0.5, "blank single-colour image"
    assert len(np.unique(rgb.round(2), axis=0)) > 20


def _texts(fig) -> str:
    """Every title, label, legend entry and text of a figure, lower-cased."""
    parts = [fig._suptitle.get_text() if fig._suptitle else ""]
    for ax in fig.axes:
        parts += [ax.get_title(), ax.get_xlabel(), ax.get_ylabel()]
        parts += [t.get_text() for t in ax.texts]
        leg = ax.get_legend()
        if leg is not None:
            parts += [t.get_text() for t in leg.get_texts()]
    for leg in fig.legends:
        parts += [t.get_text() for t in leg.get_texts()]
    return "\n".join(parts).lower()


# ------------------------------------------------------------------ files written


@pytest.mark.slow
def test_each_function_writes_a_readable_png(tmp_path):
    scene, analysis = example()
    out = tmp_path / "a" / "b"
    assert driving_effort(scene, analysis, out / "d.png") == out / "d.png"
    assert reaction_hodographs(scene, analysis, out / "r.png") == out / "r.png"
    assert frame_loads(scene, analysis, str(out / "f.png")) == out / "f.png"
    for name in ("d.png", "r.png", "f.png"):
        _assert_png(out / name)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["shaper", "hydraulic_boom", "fivebar", "sixbar_class3"])
def test_other_examples_plot(tmp_path, name):
    scene, analysis = example(name)
    for fn in (driving_effort, reaction_hodographs, frame_loads):
        _assert_png(fn(scene, analysis, tmp_path / f"{fn.__name__}.png"))


@pytest.mark.slow
def test_plot_all_adds_force_files_only_with_forces(tmp_path):
    scene, analysis = example()
    with_forces = plot_all(scene, analysis, tmp_path / "with")
    names = [p.name for p in with_forces]
    assert names == [f"crank-rocker_{k}.png" for k in
                     ("positions", "velocities", "accelerations", "transmission", "paths",
                      "driving", "reactions", "frame")]
    for p in with_forces[-3:]:
        _assert_png(p)

    analysis.forces = None
    names = [p.name for p in plot_all(scene, analysis, tmp_path / "without", prefix="k")]
    assert names == [f"k_{k}.png" for k in ("positions", "velocities", "accelerations",
                                            "transmission", "paths")]


@pytest.mark.slow
def test_plot_all_follows_the_outputs(tmp_path):
    scene, analysis = example()
    analysis.outputs = ("kinematics", "frame")
    names = [p.name.rsplit("_", 1)[1] for p in plot_all(scene, analysis, tmp_path / "a")]
    assert names[-2:] == ["paths.png", "frame.png"]
    analysis.outputs = ("kinematics", "driving", "reactions")
    analysis.forces.driving = {}
    names = [p.name.rsplit("_", 1)[1] for p in plot_all(scene, analysis, tmp_path / "b")]
    assert names[-2:] == ["paths.png", "reactions.png"]


# ------------------------------------------------------------------ what is drawn


@pytest.mark.slow
def test_shaking_words_only_under_inertia_alone():
    scene, analysis = example()  # inertia + gravity + loads
    assert not inertia_only(scene)
    assert frame_words(scene) == ("frame force", "frame moment")
    text = _texts(frame_loads_figure(scene, analysis))
    assert "frame force" in text and "frame moment" in text and "shaking" not in text

    scene, analysis = example(effects=INERTIA_ONLY)
    assert inertia_only(scene)
    text = _texts(frame_loads_figure(scene, analysis))
    assert "shaking force" in text and "shaking moment" in text and "frame force" not in text


@pytest.mark.parametrize("effects, shaking", [
    (Effects(inertia=True, gravity=None, loads=True), False),  # the example has loads
    (Effects(inertia=True, gravity=(0.0, -9.81), loads=False), False),
    (Effects(inertia=False, gravity=None, loads=False), False),
    (INERTIA_ONLY, True),
])
def test_inertia_only_rule(effects, shaking):
    scene = replace(linkage_sym.load_example("crank_rocker"), effects=effects)
    assert inertia_only(scene) is shaking
    assert inertia_only(replace(scene, loads=())) is (effects.inertia and effects.gravity is None)


@pytest.mark.slow
def test_hodographs_are_polar_one_per_joint_in_scene_order():
    scene, analysis = example()
    fig = reaction_hodographs_figure(scene, analysis)
    polar = [ax for ax in fig.axes if ax.name == "polar"]
    assert len(polar) == len(scene.joints) == len(fig.axes)
    for ax, joint in zip(polar, scene.joints):
        title = ax.get_title()
        assert title.startswith(f"{joint.name}: {joint.links[0]} on {joint.links[1]}")
        peak = np.nanmax(np.hypot(*analysis.forces.reactions[joint.name].T))
        assert "peak" in title and "N" in title
        assert ax.get_ylim()[1] >= peak
    fig = reaction_hodographs_figure(scene, analysis, joints=["C", "A"])
    assert [ax.get_title().split(":")[0] for ax in fig.axes] == ["C", "A"]
    with pytest.raises(ValueError, match="Z"):
        reaction_hodographs_figure(scene, analysis, joints=["Z"])


def test_frame_figure_has_a_polar_and_a_cartesian_panel():
    scene, analysis = example()
    fig = frame_loads_figure(scene, analysis)
    assert [ax.name for ax in fig.axes] == ["polar", "rectilinear"]
    assert "(deg" in fig.axes[1].get_xlabel()
    assert "(N·m)" in fig.axes[1].get_ylabel()


def test_driving_effort_labels_units_rms_and_peak():
    scene, analysis = example()
    fig = driving_effort_figure(scene, analysis)
    assert len(fig.axes) == 1
    ax = fig.axes[0]
    assert "(N·m)" in ax.get_ylabel() and "(deg" in ax.get_xlabel()
    text = _texts(fig)
    assert "rms" in text and "peak" in text and scene.name in text
    t = analysis.forces.driving["A"]
    rms = float(np.sqrt(np.nanmean(t[:-1] ** 2)))  # 0 to 360 deg: the repeated end point once
    assert f"rms {rms:.3g} n·m" in text
    assert any(np.allclose(line.get_ydata(), 0.0) for line in ax.get_lines())  # zero line


def test_torques_and_forces_get_separate_panels():
    scene, analysis = example("fivebar")
    d2 = scene.drivers[1]
    # make the second driver a prismatic one (its effort then is a force in N)
    joints = tuple(replace(j, type="P", axis=0.0) if j.name == d2.joint else j
                   for j in scene.joints)
    scene = replace(scene, joints=joints, drivers=(scene.drivers[0], replace(d2, kind="P")))
    fig = driving_effort_figure(scene, analysis)
    assert [ax.get_ylabel().rsplit("(", 1)[1] for ax in fig.axes] == ["N·m)", "N)"]


def test_a_prismatic_driver_effort_is_a_force():
    scene, analysis = example("hydraulic_boom")
    fig = driving_effort_figure(scene, analysis)
    assert len(fig.axes) == 1 and fig.axes[0].get_ylabel().endswith("(N)")


# ------------------------------------------------------------------------ robustness


def test_nan_steps_break_the_curves():
    scene, analysis = example()
    fig = frame_loads_figure(scene, analysis)
    moment_line = fig.axes[1].get_lines()[0]
    assert np.isnan(moment_line.get_ydata()[40]) and np.isnan(moment_line.get_ydata()[200])
    # shaded bands for the bad runs (status labels written on the axis)
    assert {UNASSEMBLABLE, SINGULAR} <= {t.get_text() for t in fig.axes[1].texts}


@pytest.mark.slow
def test_all_nan_does_not_raise(tmp_path):
    scene, analysis = example()
    _mark_bad(analysis, {k: UNASSEMBLABLE for k in range(analysis.n_steps)})
    assert not analysis.ok.any()
    for p in (driving_effort(scene, analysis, tmp_path / "d.png"),
              reaction_hodographs(scene, analysis, tmp_path / "r.png"),
              frame_loads(scene, analysis, tmp_path / "f.png")):
        assert p.exists() and p.stat().st_size > 1000
    assert "no solved step" in _texts(frame_loads_figure(scene, analysis))
    assert "no solved step" in _texts(driving_effort_figure(scene, analysis))


def test_no_forces_is_an_error_not_a_crash():
    scene, analysis = example()
    analysis.forces = None
    with pytest.raises(ValueError, match="forces"):
        driving_effort_figure(scene, analysis)


def _chain(n_links: int):
    """A scene of ``n_links`` links in a row, one R joint per link (kinematics made up)."""
    N = 25
    links = tuple(Link(f"l{i}", 1.0, (0.1 * i + 0.05, 0.0), 1e-3) for i in range(n_links))
    names = ["ground"] + [lk.name for lk in links]
    joints = tuple(Joint(f"J{i}", "R", (names[i], names[i + 1]), (0.1 * i, 0.0))
                   for i in range(n_links))
    scene = Scene("chain", links, joints, (Driver("J0", "R", 0.0, 2 * math.pi, N, 1.0),),
                  effects=INERTIA_ONLY)
    th = np.linspace(0.0, 2 * math.pi, N)
    zeros = np.zeros((N, 2))
    lks = {lk.name: LinkKinematics(th.copy(), zeros.copy(), np.ones(N), np.zeros(N),
                                   zeros.copy(), zeros.copy(), zeros.copy(), zeros.copy(),
                                   np.stack([np.cos(th), np.sin(th)], axis=-1) * (i + 1))
           for i, lk in enumerate(links)}
    jks = {j.name: JointKinematics(zeros.copy(), zeros.copy(), zeros.copy()) for j in joints}
    analysis = Analysis(scene="chain", stages=("position", "velocity", "acceleration", "forces"),
                        status=np.array([OK] * N, dtype=object), messages=[None] * N,
                        drivers={"J0": {"q": th.copy(), "qd": np.ones(N), "qdd": np.zeros(N)}},
                        joints=jks, links=lks, condition=np.ones(N),
                        outputs=("kinematics", "reactions", "driving", "frame"))
    analysis.forces = synthetic_forces(scene, analysis)
    _mark_bad(analysis, {3: UNASSEMBLABLE})
    return scene, analysis


@pytest.mark.slow
@pytest.mark.parametrize("n", [1, 5, 12])
def test_one_to_twelve_joints_lay_out(tmp_path, n):
    scene, analysis = _chain(n)
    fig = reaction_hodographs_figure(scene, analysis)
    assert len(fig.axes) == n and all(ax.name == "polar" for ax in fig.axes)
    w, h = fig.get_size_inches()
    assert w <= 14 and h <= 12
    _assert_png(reaction_hodographs(scene, analysis, tmp_path / "r.png"))
    assert "shaking" in _texts(frame_loads_figure(scene, analysis))


@pytest.mark.slow
def test_plotting_forces_needs_no_pyplot():
    import subprocess
    import sys
    from pathlib import Path

    code = (
        "import sys, tempfile;"
        "import tests.plotting.test_plotting_forces as t, linkage_sym.plotting as lp;"
        "s, a = t.example();"
        "lp.plot_all(s, a, tempfile.mkdtemp());"
        "assert 'matplotlib.pyplot' not in sys.modules, 'pyplot imported'"
    )
    subprocess.run([sys.executable, "-c", code], check=True,
                   cwd=Path(__file__).resolve().parents[2])
