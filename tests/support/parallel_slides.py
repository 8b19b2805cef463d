"""Dyads of two slides (PRP, RPP) whose slides may become parallel, with the intersection of
the two lines written here as the reference (no solver code).

``guide_slider(steps, start, stop)``: a guide turning about the origin (driver ``A``), a
rod sliding through it on the line through the origin at the guide's angle ``q``, the rod
pinned (``C``) to a block sliding on the horizontal line ``y = H``: a PRP dyad (rod,
block) whose joint ``C`` is at ``(H / tan q, H)``, at infinity where ``q = 0`` (the rod's
line parallel to the block's).

``pinned_rod(axis_deg)``: an RPP dyad: a guide turning about the origin, a block sliding
along it, a rod pinned to the ground at ``E`` and sliding through the block along a line at
``axis_deg`` to the guide (in the assembly configuration): the rod, the block and the guide
turn together, so the angle between the two slides never changes.
"""

from __future__ import annotations

import math

H = 0.05
"""Height of the block's slide."""


def guide_slider(steps: int, start: float = 30.0, stop: float = -30.0) -> dict:
    """The PRP scene (the lead's ``gs10``/``gs11`` with ``steps`` steps)."""
    q0 = math.radians(start)
    c = [H / math.tan(q0), H]
    a = [0.02 * math.cos(q0), 0.02 * math.sin(q0)]
    return {
        "name": "guide-slider",
        "links": [
            {"name": "guide", "mass": 0.1, "com": [0.0, 0.0], "inertia": 0.0001},
            {"name": "rod", "mass": 0.2, "com": [c[0] / 2, c[1] / 2], "inertia": 0.001},
            {"name": "block", "mass": 0.3, "com": c, "inertia": 0.0001},
        ],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "guide"], "at": [0.0, 0.0]},
            {"name": "A_slide", "type": "P", "links": ["rod", "guide"], "at": a,
             "axis_deg": start},
            {"name": "C", "type": "R", "links": ["rod", "block"], "at": c},
            {"name": "C_guide", "type": "P", "links": ["ground", "block"], "at": c,
             "axis_deg": 0.0},
        ],
        "drivers": [{"joint": "A", "toward": "A_slide", "start_deg": start, "stop_deg": stop,
                     "steps": steps, "speed": 1.0, "acceleration": 0.0}],
        "outputs": ["kinematics"],
    }


def joint_c(q):
    """Reference position of ``C`` in :func:`guide_slider` at guide angles ``q`` (rad):
    the intersection of the line through the origin at angle ``q`` with ``y = H``."""
    return H * math.cos(q) / math.sin(q), H


def pinned_rod(axis_deg: float, steps: int = 13) -> dict:
    """The RPP scene: guide at the origin (driver ``A``, from 20 to 80 degrees), block
    sliding along the guide (``B_guide``), rod pinned to the ground at ``E = (0.3, 0)`` and
    sliding through the block (``B_rod``, at ``axis_deg`` in the assembly configuration)."""
    q0 = math.radians(20.0)
    b = [0.2 * math.cos(q0), 0.2 * math.sin(q0)]
    return {
        "name": "pinned-rod",
        "links": [{"name": "guide"}, {"name": "block"}, {"name": "rod"}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "guide"], "at": [0.0, 0.0]},
            {"name": "B_guide", "type": "P", "links": ["block", "guide"], "at": b,
             "axis_deg": 20.0},
            {"name": "B_rod", "type": "P", "links": ["rod", "block"], "at": b,
             "axis_deg": axis_deg},
            {"name": "E", "type": "R", "links": ["ground", "rod"], "at": [0.3, 0.0]},
        ],
        "drivers": [{"joint": "A", "toward": "B_guide", "start_deg": 20, "stop_deg": 80,
                     "steps": steps, "speed": 1.0}],
        "outputs": ["kinematics"],
    }
