"""Unassemblable steps of every closed-form dyad are reported per step, never a crash."""

import json

import numpy as np

import linkage_sym


def slider_crank(crank, rod, offset):
    return {
        "name": "slider",
        "links": [{"name": "crank"}, {"name": "rod"}, {"name": "slider"}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
            {"name": "B", "type": "R", "links": ["crank", "rod"], "at": [crank, 0.0]},
            {"name": "C", "type": "R", "links": ["rod", "slider"],
             "at": [crank + (rod**2 - offset**2) ** 0.5, offset]},
            {"name": "G", "type": "P", "links": ["ground", "slider"],
             "at": [crank + (rod**2 - offset**2) ** 0.5, offset], "axis_deg": 0.0},
        ],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": 0, "stop_deg": 360,
                     "steps": 73, "speed": 2.0}],
        "outputs": ["kinematics"],
    }


def test_rrp_rod_too_short_for_the_offset():
    # rod 1.0, offset 0.8, crank 0.5: near 270 deg the crank pin is 1.3 below the slide
    r = linkage_sym.analyze(linkage_sym.load_scene(slider_crank(0.5, 1.0, 0.8)))
    bad = r.status == "unassemblable"
    q = np.degrees(r.drivers["A"]["q"])
    # independent: the pin B is reachable iff its distance to the slide line <= rod
    reach = np.abs(0.8 - 0.5 * np.sin(np.radians(q))) <= 1.0
    assert np.array_equal(bad, ~reach)
    assert bad.any() and (~bad).any()
    for i in np.flatnonzero(bad):
        assert "dyad RRP (rod, slider)" in r.messages[i]
    steps = json.loads(json.dumps(r.to_dict(), allow_nan=False))["steps"]
    assert all("joints" not in s for s, b in zip(steps, bad) if b)
