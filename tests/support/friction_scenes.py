"""Scenes with joint friction shared by the friction tests of every method (contract part
two, issue 29): a shipped example with friction put in every ``R`` and ``P`` joint, and an
inclined slider that self-locks at the friction angle's closed form."""

from __future__ import annotations

import math

from linkage_sym.examples import example_dict

__all__ = ["inclined_slider", "with_friction"]


def with_friction(name):
    """Shipped example ``name`` with friction in every R and P joint (coefficients 0.10,
    0.11, ... in joint order; pins of radius 1 cm)."""
    d = example_dict(name)
    d["effects"]["friction"] = True
    for k, j in enumerate(d["joints"]):
        if j.get("type", "R") == "R":
            j["friction"] = {"coefficient": 0.1 + 0.01 * k, "radius": 0.01}
        elif j["type"] == "P":
            j["friction"] = {"coefficient": 0.1 + 0.01 * k}
    return d


def inclined_slider(f, start_deg=4.0, stop_deg=40.0, steps=181):
    """A block on a vertical guide (friction ``f``), pushed up through a massless rod by a
    pusher sliding horizontally towards the guide (driven).  The rod's angle above the
    horizontal, theta, runs from ``start_deg`` to about ``stop_deg``."""
    l = 0.1
    xb0 = l * math.cos(math.radians(start_deg))
    yc0 = l * math.sin(math.radians(start_deg))
    travel = xb0 - l * math.cos(math.radians(stop_deg))
    return {
        "name": "inclined-slider",
        "links": [{"name": "pusher"}, {"name": "rod"},
                  {"name": "block", "mass": 2.0, "com": [0.0, yc0]}],
        "joints": [
            {"name": "A", "type": "P", "links": ["ground", "pusher"], "at": [xb0, 0.0],
             "axis_deg": 180},
            {"name": "B", "type": "R", "links": ["pusher", "rod"], "at": [xb0, 0.0]},
            {"name": "C", "type": "R", "links": ["rod", "block"], "at": [0.0, yc0]},
            {"name": "C_guide", "type": "P", "links": ["ground", "block"], "at": [0.0, yc0],
             "axis_deg": 90, "friction": {"coefficient": f}},
        ],
        "drivers": [{"joint": "A", "start": 0.0, "stop": travel, "steps": steps, "speed": 0.5}],
        "effects": {"inertia": False, "gravity": [0.0, -9.81], "loads": True, "friction": True},
        "outputs": ["kinematics", "reactions", "driving"],
    }


def assert_zero_friction_is_frictionless(a, b):
    """The forces ``a`` of a scene whose every friction coefficient is 0 against the forces
    ``b`` of the same scene without friction: the same numbers exactly, no friction and no
    friction power, an efficiency of 1 wherever it has a value (all but at most 4 steps)."""
    import numpy as np

    for j in a.reactions:
        assert np.array_equal(a.reactions[j], b.reactions[j])
        assert np.array_equal(a.reaction_moments[j], b.reaction_moments[j])
        assert np.array_equal(a.friction[j], np.zeros(len(a.friction[j])))
    assert np.array_equal(a.driving["A"], b.driving["A"])
    assert np.array_equal(a.frame_force, b.frame_force)
    assert np.array_equal(a.frame_moment, b.frame_moment)
    assert np.array_equal(a.friction_power, np.zeros(len(a.friction_power)))
    ok = np.isfinite(a.efficiency)
    assert np.all(a.efficiency[ok] == 1.0) and ok.sum() >= len(ok) - 4
