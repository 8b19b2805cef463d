"""What four-bar and slider-crank path generation share for three targets exactly: the
crank's rotations drawn between the targets, and the standard-form dyad through them
(:mod:`linkage_sym.synthesis.path_gen`, :mod:`linkage_sym.synthesis.path_slider`).  NumPy only.
"""

from __future__ import annotations

import numpy as np

__all__ = ["crank_turns", "dyad_through"]


def crank_turns(betas, rng, draws: int) -> np.ndarray:
    """The crank's rotations from the first target to the second and third, ``(draws, 2)``
    (rad): ``betas`` repeated, or, for None, drawn (one sense per draw, within a turn).

    Examples
    --------
    >>> crank_turns([0.5, 1.0], None, 2).tolist()
    [[0.5, 1.0], [0.5, 1.0]]
    """
    if betas is None:
        sense = rng.choice([-1.0, 1.0], draws)[:, None]
        return np.sort(rng.uniform(0.1, 2 * np.pi - 0.1, (draws, 2)), axis=1) * sense
    return np.broadcast_to(np.asarray(betas, dtype=float), (draws, 2))


def dyad_through(delta, rot_fixed, rot_free):
    """``W, Z`` of ``W (e^(i r) - 1) + Z (e^(i s) - 1) = delta_j`` (j = 2, 3), Cramer's rule
    (NaN where the two rotations' determinant vanishes)."""
    a2, a3 = np.exp(1j * rot_fixed[:, 0]) - 1, np.exp(1j * rot_fixed[:, 1]) - 1
    b2, b3 = np.exp(1j * rot_free[:, 0]) - 1, np.exp(1j * rot_free[:, 1]) - 1
    det = a2 * b3 - a3 * b2
    with np.errstate(divide="ignore", invalid="ignore"):
        return (delta[0] * b3 - delta[1] * b2) / det, (a2 * delta[1] - a3 * delta[0]) / det
