"""Animations of a sweep: the frames shown, what each frame draws, the files written.

What a frame draws is read back from the figure's artists after drawing it (the pins'
circles, the arrows' offsets and vectors, the transmission arcs, the status box) and
compared with the analysis at the frame's step; the files are read back with Pillow (GIF)
or as text (HTML).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from matplotlib import animation as mpl_animation
from matplotlib.patches import Arc, Circle, Polygon
from matplotlib.quiver import Quiver
from matplotlib.text import Text
from PIL import Image

import linkage_sym
from linkage_sym.numeric.results.result import SINGULAR, UNASSEMBLABLE
from linkage_sym.plotting.animation import (
    ARROW_SHARE,
    FADED,
    AnimationError,
    animate,
    frame_steps,
)
from tests.support import scenes

DPI = 30  # small frames: the tests check what is drawn, not how it looks


@pytest.fixture(scope="module")
def crank_rocker():
    scene = linkage_sym.load_example("crank_rocker")
    return scene, linkage_sym.analyze(scene)


def non_grashof():
    """A four-bar whose crank cannot turn fully (0.03 + 0.06 > 0.05 + 0.035): the steps
    from 140 to 220 degrees cannot be assembled; with masses, loads and a traced point."""
    d, _ = scenes.fourbar(0.03, 0.05, 0.035, 0.06, steps=37, coupler_com=(0.02, 0.01),
                          name="non-Grashof four-bar")
    d["outputs"] = ["kinematics", "reactions", "driving", "frame"]
    d["effects"] = {"inertia": True, "gravity": [0.0, -9.81], "loads": True}
    d["points"] = [{"name": "P", "link": "coupler", "at": [0.03, 0.04]}]
    scene = linkage_sym.load_scene(d)
    return scene, linkage_sym.analyze(scene)


@pytest.fixture(scope="module")
def unassemblable():
    return non_grashof()


def by_gid(ax, gid, kind=object):
    found = [a for a in ax.get_children() if isinstance(a, kind) and a.get_gid() == gid]
    assert len(found) == 1, (gid, found)
    return found[0]


def test_frames_sample_the_sweep_evenly_and_never_more_than_its_steps():
    assert frame_steps(361, 5).tolist() == [0, 90, 180, 270, 360]
    steps = frame_steps(37, 37)
    assert steps.tolist() == list(range(37))  # every step, none skipped
    steps = frame_steps(100, 7)
    assert len(set(steps.tolist())) == 7 and steps[0] == 0 and steps[-1] == 99
    assert np.all(np.abs(steps - np.linspace(0, 99, 7)) <= 0.5)
    assert frame_steps(361).size == 120 and frame_steps(13).tolist() == list(range(13))
    for bad in (0, 38, -1, 2.5, True, "4"):
        with pytest.raises(AnimationError) as err:
            frame_steps(37, bad)
        assert err.value.field == "frames"
    with pytest.raises(AnimationError, match="at most|from 1 to the sweep's 37 steps"):
        frame_steps(37, 38)


@pytest.mark.parametrize("fps", [0, -1.0, math.nan, math.inf, "x", True])
def test_a_rate_that_is_not_a_positive_number_is_refused(crank_rocker, fps):
    with pytest.raises(AnimationError) as err:
        animate(*crank_rocker, frames=2, fps=fps)
    assert err.value.field == "fps"


def test_the_gif_has_exactly_the_frames_asked_for(crank_rocker, tmp_path):
    anim = animate(*crank_rocker, frames=4, fps=8, dpi=DPI)
    path = anim.save(tmp_path / "motion.gif")
    assert [p.name for p in tmp_path.iterdir()] == ["motion.gif"]  # no temporary file left
    plain = tmp_path / "plain"
    plain.write_bytes(b"")
    assert path.stat().st_mode == plain.stat().st_mode  # the permissions of any new file
    plain.unlink()
    with Image.open(path) as gif:
        assert gif.format == "GIF"
        assert gif.n_frames == 4
        assert abs(gif.info["duration"] - 125) <= 10  # 8 frames per second (GIF: in 10 ms)


def test_a_frame_draws_the_joints_and_the_path_at_its_step(crank_rocker):
    scene, analysis = crank_rocker
    anim = animate(scene, analysis, frames=7, dpi=DPI)
    assert anim.unit_scale == 1000.0  # mm
    for k in (0, 3, 6):
        step = int(anim.steps[k])
        anim.draw(k)
        for joint in scene.joints:
            pin = by_gid(anim.ax, f"joint {joint.name}", Circle)
            drawn = np.asarray(pin.center) / anim.unit_scale
            want = analysis.joints[joint.name].position[step]
            assert np.max(np.abs(drawn - want)) <= 1e-12, (k, joint.name)
        # the traced point's coupler curve, grown up to the step and no further
        trace = by_gid(anim.ax, "trace point P (on coupler)")
        xy = np.asarray(trace.get_xydata()) / anim.unit_scale
        assert len(xy) == step + 1
        assert np.max(np.abs(xy[-1] - analysis.points["P"].position[step])) <= 1e-12
    assert anim.ax.get_title().startswith(f"crank-rocker: step {anim.steps[6]} (0 to 360)")


def test_a_slider_is_drawn_at_its_joint(tmp_path):
    scene = linkage_sym.load_example("slider_crank_offset")
    analysis = linkage_sym.analyze(scene)
    anim = animate(scene, analysis, frames=5, dpi=DPI)
    anim.draw(2)
    step = int(anim.steps[2])
    sliding = [j for j in scene.joints if j.type == "P"]
    assert sliding
    for joint in sliding:
        block = by_gid(anim.ax, f"joint {joint.name}", Polygon)
        centre = np.asarray(block.get_xy())[:4].mean(axis=0) / anim.unit_scale
        assert np.max(np.abs(centre - analysis.joints[joint.name].position[step])) <= 1e-12


@pytest.mark.slow
def test_an_unassemblable_step_is_marked_with_the_last_solved_pose_faded(unassemblable):
    scene, analysis = unassemblable
    bad = np.flatnonzero(analysis.status == UNASSEMBLABLE)
    assert bad.size and bad[0] > 0 and bad[-1] < analysis.n_steps - 1  # a gap inside the sweep
    anim = animate(scene, analysis, frames=analysis.n_steps, dpi=DPI, velocity=True,
                   forces=True, transmission=True)
    for k, step in enumerate(anim.steps):
        anim.draw(k)
        notes = [t for t in anim.ax.texts if (t.get_gid() or "").startswith("status")]
        if step not in bad:
            assert notes == [], step
            continue
        (note,) = notes  # every unassemblable step has its frame, and the frame says so
        text = note.get_text().replace("\n", " ")
        assert note.get_gid() == "status unassemblable"
        assert f"step {step}: unassemblable" in text
        assert analysis.messages[step].split(":")[0] in text  # the solver's reason
        assert f"the last solved pose (step {bad[0] - 1})" in text
        pins = [a for a in anim.ax.patches if (a.get_gid() or "").startswith("joint ")]
        assert pins and all(p.get_alpha() == FADED for p in pins)
        for pin in pins:  # at the last solved step
            want = analysis.joints[pin.get_gid()[6:]].position[bad[0] - 1]
            assert np.max(np.abs(np.asarray(pin.center) / 1000.0 - want)) <= 1e-12
        # no arrows nor angles where nothing was solved
        assert not [a for a in anim.ax.get_children() if isinstance(a, (Quiver, Arc))]


def test_a_singular_step_keeps_its_pose_and_says_it_has_no_rates(crank_rocker):
    scene, analysis = crank_rocker
    status = analysis.status.copy()
    status[180] = SINGULAR
    messages = list(analysis.messages)
    messages[180] = "dyad RRR (coupler, rocker): folded"
    marked = dataclasses.replace(analysis, status=status, messages=messages)
    anim = animate(scene, marked, frames=3, dpi=DPI, velocity=True)
    anim.draw(1)
    note = by_gid(anim.ax, "status singular", Text)
    assert "step 180: singular" in note.get_text() and "folded" in note.get_text()
    pin = by_gid(anim.ax, "joint C", Circle)
    assert pin.get_alpha() == 1.0
    assert not [a for a in anim.ax.get_children() if isinstance(a, Quiver)]


def _arrow_at(quiver, point):
    """The vector of the arrow of ``quiver`` that starts at ``point`` (axis units)."""
    offsets = np.asarray(quiver.get_offsets())
    i = int(np.argmin(np.hypot(*(offsets - point).T)))
    assert np.hypot(*(offsets[i] - point)) <= 1e-9
    return np.array([quiver.U[i], quiver.V[i]])


def test_layers_draw_arrows_proportional_to_the_values(crank_rocker):
    scene, analysis = crank_rocker
    anim = animate(scene, analysis, frames=5, dpi=DPI, velocity=True, acceleration=True,
                   forces=True, transmission=True)
    k, s = 1, anim.unit_scale
    step = int(anim.steps[k])
    anim.draw(k)
    L = scene.characteristic_length()
    for layer, values, joint in (
        ("velocity", analysis.joints["C"].velocity, "C"),
        ("acceleration", analysis.points["P"].acceleration, None),
        ("reactions", analysis.forces.reactions["B"], "B"),
    ):
        quiver = by_gid(anim.ax, layer, Quiver)
        at = (analysis.joints[joint].position if joint else analysis.points["P"].position)[step]
        drawn = _arrow_at(quiver, at * s)
        want = anim.scales[layer] * values[step]
        assert np.max(np.abs(drawn - want)) <= 1e-12 * np.hypot(*want), layer
        # one scale for the whole sweep: the largest value is ARROW_SHARE sizes long
    v = np.concatenate([analysis.joints[j.name].velocity for j in scene.joints
                        if j.links[1] != "ground"] + [analysis.points["P"].velocity])
    biggest = np.nanmax(np.hypot(*v.T))
    assert abs(biggest * anim.scales["velocity"] - ARROW_SHARE * L * s) <= 1e-12 * L * s
    # the driving torque's arrow turns in proportion to the torque
    torque = analysis.forces.driving["A"][step]
    texts = [t.get_text() for t in anim.ax.texts]
    assert f"T A = {torque:.3g} N·m" in texts
    # the transmission angle's arc spans the angle
    arc = by_gid(anim.ax, "transmission C", Arc)
    span = (arc.theta2 - arc.theta1) % 360.0
    assert abs(span - math.degrees(analysis.transmission_angles["C"][step])) <= 1e-9


def test_the_centres_layer_draws_kennedys_centre_of_the_coupler(crank_rocker):
    """P13 (ground and coupler) is where the crank's line AB meets the rocker's line DC."""
    scene, analysis = crank_rocker
    anim = animate(scene, analysis, frames=9, dpi=DPI, centres=True)
    k = 5  # step 225: P13 inside the drawing
    step = int(anim.steps[k])
    anim.draw(k)
    A, B, C, D = (analysis.joints[n].position[step] for n in "ABCD")
    # A + t (B - A) = D + u (C - D)
    t, _ = np.linalg.solve(np.column_stack([B - A, D - C]), D - A)
    want = A + t * (B - A)
    marker = by_gid(anim.ax, "centre P13")
    drawn = np.asarray(marker.get_xydata())[0] / anim.unit_scale
    assert np.max(np.abs(drawn - want)) <= 1e-9 * scene.characteristic_length()
    lines = [a for a in anim.ax.lines if a.get_color() == "#d62728"]
    assert len(lines) >= 2  # the three-centre lines through P13


@pytest.mark.parametrize("layer, outputs, why", [
    ("forces", ["kinematics"], "no forces"),
    ("velocity", ["reactions", "driving"], "no velocities"),
    ("centres", ["reactions", "driving"], "need velocities"),
])
def test_a_layer_without_its_values_is_refused_by_name(layer, outputs, why):
    d, _ = scenes.fourbar(0.024, 0.06, 0.05, 0.078, steps=13)
    d["outputs"] = outputs
    d["effects"] = {"inertia": False, "gravity": None, "loads": True}
    d["loads"] = [{"link": "rocker", "torque": -0.5}]
    scene = linkage_sym.load_scene(d)
    analysis = linkage_sym.analyze(scene)
    with pytest.raises(AnimationError, match=why) as err:
        animate(scene, analysis, frames=2, **{layer: True})
    assert err.value.field == layer


def test_transmission_of_a_mechanism_without_rrr_dyad_is_refused():
    scene = linkage_sym.load_example("slider_crank_offset")
    with pytest.raises(AnimationError, match="no RRR dyad") as err:
        animate(scene, linkage_sym.analyze(scene), frames=2, transmission=True)
    assert err.value.field == "transmission"


@pytest.mark.parametrize("name", ["motion.png", "motion", "motion.gif.txt"])
def test_another_suffix_is_refused_and_nothing_written(crank_rocker, tmp_path, name):
    anim = animate(*crank_rocker, frames=2, dpi=DPI)
    with pytest.raises(AnimationError, match=r"\.gif, \.mp4 or \.html") as err:
        anim.save(tmp_path / name)
    assert err.value.field == "path"
    assert list(tmp_path.iterdir()) == []


def test_html_is_one_file_that_refers_to_nothing_outside(crank_rocker, tmp_path):
    anim = animate(*crank_rocker, frames=3, dpi=DPI, velocity=True)
    path = anim.save(tmp_path / "motion.html")
    assert [p.name for p in tmp_path.iterdir()] == ["motion.html"]
    html = path.read_text(encoding="utf-8")
    assert html.startswith("<!DOCTYPE html>")
    assert "http://" not in html and "https://" not in html
    assert "<link" not in html and "fa fa-" not in html  # no icon font fetched
    assert html.count("data:image/png;base64,") == 3  # the frames, embedded
    inline = anim._repr_html_()  # what a notebook shows
    assert "https://" not in inline and inline.count("data:image/png;base64,") == 3


def test_mp4_without_ffmpeg_is_a_clear_error(crank_rocker, tmp_path, monkeypatch):
    monkeypatch.setattr(mpl_animation.writers, "is_available", lambda name: False)
    anim = animate(*crank_rocker, frames=2, dpi=DPI)
    with pytest.raises(AnimationError, match="ffmpeg, which is not found.*a .gif or .html") as err:
        anim.save(tmp_path / "motion.mp4")
    assert err.value.field == "path"
    assert list(tmp_path.iterdir()) == []


@pytest.mark.skipif(not mpl_animation.writers.is_available("ffmpeg"),
                    reason="ffmpeg is not installed (its absence is tested above)")
def test_mp4_where_ffmpeg_is_found(crank_rocker, tmp_path):
    path = animate(*crank_rocker, frames=3, dpi=DPI).save(tmp_path / "motion.mp4")
    assert path.read_bytes()[4:8] == b"ftyp"


def test_the_api_function_of_the_package(crank_rocker, tmp_path):
    anim = linkage_sym.animate(*crank_rocker, frames=2, dpi=DPI, transmission=True)
    assert anim.layers == ("transmission",)
    with Image.open(anim.save(tmp_path / "a.gif")) as gif:
        assert gif.n_frames == 2
