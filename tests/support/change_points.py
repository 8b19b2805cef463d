"""A change-point four-bar whose coupler end passes through the rocker's pivot, by hand.

Crank ``AB`` 3, coupler ``BC`` 1, rocker ``DC`` 1, ground ``AD`` 3 + ``gap`` (``gap`` 0: the
change point of links 3, 1, 1, 3; 0.001: a four-bar near it), the ground turned by ``PHI``
degrees and moved to ``ORIGIN``.  With ``gap`` 0, joint ``B`` (on the crank's circle of
radius 3 about ``A``) is on ``D`` (3 from ``A``) exactly when the crank points from ``A`` to
``D``: the driver's angle (from the ground's +x axis to ``AB``) is then ``PHI`` (mod 360),
and nowhere else.  Every position here is the intersection of two circles written out,
sharing no code with the package.
"""

from __future__ import annotations

import math
import re

import numpy as np

PHI = 30.0
"""Direction of the ground ``AD`` (degrees): the change point's driver value."""
ORIGIN = (1.0, -2.0)
SIGMA = 1.0
"""``C`` on the left of the line from ``B`` to ``D`` in the assembly configuration."""
ASSEMBLY = PHI + 25.0
"""The crank's angle (degrees) in the assembly configuration (``|BD| = 6 sin(12.5°) < 2``:
the coupler and the rocker reach ``B`` within 38.9 degrees of ``PHI``)."""


def points(q, gap=0.0):
    """``A``, ``B``, ``C``, ``D`` at the crank angles ``q`` (rad, array), ``C`` on the side
    ``SIGMA`` of the line from ``B`` to ``D`` (NaN where the circles do not meet)."""
    q = np.asarray(q, float)
    A = np.array(ORIGIN)
    phi = math.radians(PHI)
    D = A + (3.0 + gap) * np.array([math.cos(phi), math.sin(phi)])
    B = np.stack([A[0] + 3.0 * np.cos(q), A[1] + 3.0 * np.sin(q)], axis=-1)
    v = D - B
    d = np.hypot(v[..., 0], v[..., 1])
    with np.errstate(invalid="ignore", divide="ignore"):
        h = np.sqrt(1.0 - d * d / 4.0)  # both links 1 long: C over the midpoint of BD
        n = np.stack([-v[..., 1], v[..., 0]], axis=-1) / d[..., None]
    C = (B + D) / 2.0 + SIGMA * h[..., None] * n
    return A, B, C, D


def scene(start_deg, stop_deg, steps, gap=0.0):
    """The four-bar assembled at the crank angle :data:`ASSEMBLY`, swept by its crank."""
    A, B, C, D = points(math.radians(ASSEMBLY), gap)
    return {
        "name": "change point by hand",
        "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "rocker"}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [float(v) for v in A]},
            {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": [float(v) for v in B]},
            {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": [float(v) for v in C]},
            {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": [float(v) for v in D]},
        ],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": start_deg, "stop_deg": stop_deg,
                     "steps": steps, "speed": 1.0}],
        "outputs": ["kinematics"],
    }


WARNING = re.compile(
    r"^dyad RRR \(coupler, rocker\): joints B and D pass through one point between "
    r"A = (?P<before>-?[0-9.]+)° and A = (?P<after>-?[0-9.]+)° \(a change point: joint C can "
    r"be anywhere on one circle about them there\); at (?P<step>step \d+( \(reached from (step "
    r"\d+|the assembly configuration)\))?) the dyad keeps its assembly mode \(joint C on the "
    r"same side of the line from B to D\), so links coupler and rocker have turned a half turn \(which way is undefined\); "
    r"the other branch, where the assembly mode changes and they do not turn, is equally valid$")
"""The warning of a change point between two path points, every field but the values."""
