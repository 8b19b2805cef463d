"""The four-bar with a coupler point in closed form, vectorized: what path synthesis moves.

A design is ``(Ax, Ay, Dx, Dy, a, b, c, u, v)`` and an assembly mode
``sigma = +-1``: the crank ``A B`` (length ``a``) at the angle ``theta`` from
``+x``, the coupler ``B C`` (``b``), the rocker ``D C`` (``c``), the coupler
point ``P = B + u e + v e_perp`` with ``e`` the unit vector ``B -> C``;
``C`` lies to the left of ``B -> D`` for ``sigma = +1`` (the sign of
``(D - B) x (C - B)``, constant along a branch).

This is the synthesis's own model (the local method's residuals and the exact
solutions' screen); every reported design is checked by the solver
(:mod:`linkage_sym.synthesis.path_check`).  NumPy only.
"""

from __future__ import annotations

import numpy as np

NPAR = 9
"""``Ax, Ay, Dx, Dy, a, b, c, u, v``."""

LENGTHS = (4, 5, 6)
"""The positive lengths among the parameters: crank ``a``, coupler ``b``, rocker ``c``."""

KIND = "four-bar"


def short(z) -> np.ndarray:
    """The shorter of coupler and rocker: the scale of the closed forms' reach test."""
    return np.minimum(z[..., 5], z[..., 6])


def pins(z, theta, sigma):
    """``B, C, P`` (complex) and the squared half-chord ``h2`` at crank angles ``theta``.

    ``z``: parameters (..., 9) broadcast against ``theta`` (..., k); where the
    linkage cannot be assembled (``h2 < 0``) the chord is taken as 0.

    Examples
    --------
    >>> z = np.array([0, 0, 3.5, 0, 1, 3, 3, 1, 1.0])
    >>> B, C, P, h2 = pins(z[None, :], np.array([[0.0]]), 1.0)
    >>> complex(np.round(C[0, 0], 6)), bool(h2[0, 0] > 0)
    ((2.25+2.727178j), True)
    """
    z = np.asarray(z, dtype=float)
    col = [z[..., i, None] for i in range(NPAR)]
    Ax, Ay, Dx, Dy, a, b, c, u, v = col
    A, D = Ax + 1j * Ay, Dx + 1j * Dy
    B = A + a * np.exp(1j * theta)
    r = D - B
    R = np.abs(r)
    with np.errstate(divide="ignore", invalid="ignore"):
        x = (b * b - c * c + R * R) / (2 * R)
        h2 = b * b - x * x
        e_r = r / R
    h = np.sqrt(np.maximum(h2, 0.0))
    sigma = np.asarray(sigma, dtype=float)
    sigma = sigma[..., None] if sigma.ndim else sigma
    C = B + (x + 1j * sigma * h) * e_r
    e = (C - B) / b
    P = B + (u + 1j * v) * e
    return B, C, P, h2


def transmission(z, theta, sigma):
    """The transmission angle at ``C`` (rad, 0..pi/2 as ``min(g, pi - g)``) at ``theta``."""
    B, C, _, _ = pins(z, theta, sigma)
    D = z[..., 2, None] + 1j * z[..., 3, None]
    u, w = B - C, D - C
    cosg = (u.real * w.real + u.imag * w.imag) / (np.abs(u) * np.abs(w))
    g = np.arccos(np.clip(cosg, -1.0, 1.0))
    return np.minimum(g, np.pi - g)


def mode(z, theta):
    """The assembly mode (sign of ``(D - B) x (C - B)``) of the configuration ``pins`` gives."""
    B, C, _, _ = pins(z, theta, 1.0)
    D = z[..., 2, None] + 1j * z[..., 3, None]
    return np.sign(((D - B).conjugate() * (C - B)).imag)


def grashof_crank(z) -> np.ndarray:
    """Whether the crank ``a`` turns fully (Grashof: ``s + l <= p + q`` with ``a`` shortest)."""
    d = np.hypot(z[..., 2] - z[..., 0], z[..., 3] - z[..., 1])
    L = np.stack([z[..., 4], z[..., 5], z[..., 6], d])
    s, l_ = L.min(axis=0), L.max(axis=0)
    return (s + l_ < L.sum(axis=0) - s - l_) & (z[..., 4] <= s)
