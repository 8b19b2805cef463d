"""The kinetic energy of an analysis, summed link by link from the numeric solver's velocities
(``m v_G² / 2 + I ω² / 2``), for the motion tests' energy and inertia checks."""

from __future__ import annotations

import numpy as np


def kinetic_energy(scene, analysis):
    """(N,) the mechanism's kinetic energy at each step of ``analysis``."""
    T = np.zeros(analysis.n_steps)
    for link in scene.links:
        lk = analysis.links[link.name]
        v = np.asarray(lk.com_velocity)
        T += 0.5 * link.mass * (v[:, 0] ** 2 + v[:, 1] ** 2) + 0.5 * link.inertia * lk.omega ** 2
    return T
