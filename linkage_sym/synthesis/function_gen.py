"""Function generation: a four-bar whose output angle ``psi`` follows ``y = f(x)``.

Freudenstein's equation (F. Freudenstein, "Approximate synthesis of four-bar
linkages", Trans. ASME 77, 1955) relates the crank angle ``phi`` and the
rocker angle ``psi`` of a four-bar::

    K1 cos(phi) - K2 cos(psi) + K3 = cos(phi - psi)

Here both angles are measured counter-clockwise from ``+x``, the crank's pivot
``A`` at the origin and the rocker's pivot ``D`` at ``(d, 0)``; the loop
``a e^(i phi) + b e^(i theta) = d + c e^(i psi)`` gives ``K1 = -d/c``,
``K2 = -d/a``, ``K3 = (a^2 - b^2 + c^2 + d^2) / (2 a c)``.  A negative ``a``
(or ``c``) is a link of length ``|a|`` pointing the other way: its angle in the
scene is ``phi + 180°``.

The function is mapped linearly onto the angles: ``x`` over ``[x0, x1]`` to
``phi`` over the input range, ``y = f(x)`` over ``[f(x0), f(x1)]`` to ``psi``
over the output range.  Three precision points (Chebyshev spacing over
``[x0, x1]`` by default) give ``K`` by a linear solve, met exactly; more give the
least-squares ``K`` of the equation's residuals.  The structural error -- the
output angle the linkage makes minus the one asked for -- is measured by the
solver (:func:`structural_error`), not by the equation.

NumPy only, and the solver (``linkage_sym.compile_plan``) for the error.

Examples
--------
>>> import numpy as np
>>> d = function_generator(np.log10, (1.0, 10.0), (30.0, 120.0), (240.0, 330.0))
>>> [round(v, 6) for v in d.extra["K"]]
[0.503066, -0.494628, -1.04604]
"""

from __future__ import annotations

import math

import numpy as np

from linkage_sym.synthesis.common import (
    TANGENCY,
    Design,
    SynthesisError,
    fmt_len,
    number,
    positive,
    scene_name,
    sweep_options,
)

__all__ = ["chebyshev", "function_generator", "structural_error", "table_function"]


def chebyshev(x0: float, x1: float, n: int) -> np.ndarray:
    """Chebyshev spacing of ``n`` precision points over ``[x0, x1]``.

    Examples
    --------
    >>> [round(float(v), 6) for v in chebyshev(0.0, 1.0, 3)]
    [0.066987, 0.5, 0.933013]
    """
    j = np.arange(1, n + 1)
    return 0.5 * (x0 + x1) - 0.5 * (x1 - x0) * np.cos((2 * j - 1) * math.pi / (2 * n))


def table_function(x, y):
    """``f`` interpolating a table ``y(x)`` linearly (``x`` strictly increasing).

    Raises
    ------
    SynthesisError
        Fewer than 2 rows, numbers that are not finite, ``x`` not increasing.
    """
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    if x.ndim != 1 or x.shape != y.shape or len(x) < 2:
        raise SynthesisError("table", "at least 2 rows of two numbers x, y are expected")
    if not (np.isfinite(x).all() and np.isfinite(y).all()):
        raise SynthesisError("table", "every x and y must be a finite number")
    if not (np.diff(x) > 0).all():
        raise SynthesisError("table", "x must increase strictly from row to row")
    return lambda t: np.interp(np.asarray(t, dtype=float), x, y)


def _range(name, pair):
    lo, hi = (number(name, v) for v in pair)
    if lo == hi:
        raise SynthesisError(name, f"the range's ends must differ, got {lo:g} twice")
    return lo, hi


def _mapping(f, x_range, phi_range, psi_range):
    """``(phi(x), psi(x))`` in radians, and ``f``'s values at the ends."""
    x0, x1 = x_range
    y0, y1 = (float(f(np.array([v]))[0]) for v in (x0, x1))
    if not (math.isfinite(y0) and math.isfinite(y1)) or y0 == y1:
        raise SynthesisError("function", f"f(x0) = {y0:g} and f(x1) = {y1:g} must be finite and "
                             "differ: the output range is mapped onto [f(x0), f(x1)]")
    p0, p1 = (math.radians(v) for v in phi_range)
    s0, s1 = (math.radians(v) for v in psi_range)

    def phi(x):
        return p0 + (np.asarray(x, dtype=float) - x0) / (x1 - x0) * (p1 - p0)

    def psi(x):
        return s0 + (f(x) - y0) / (y1 - y0) * (s1 - s0)

    return phi, psi


def _assembly(a, b, c, d, phi, sign):
    """Pins ``B``, ``C`` at crank angle ``phi`` with assembly-mode ``sign`` (signed ``a``, ``c``)."""
    B = np.array([a * math.cos(phi), a * math.sin(phi)])
    D = np.array([d, 0.0])
    r = float(np.hypot(*(D - B)))
    cc = abs(c)
    h2 = b * b - ((b * b - cc * cc + r * r) / (2 * r)) ** 2
    if not h2 > (TANGENCY * min(b, cc)) ** 2:
        return None
    u = (D - B) / r
    x = (b * b - cc * cc + r * r) / (2 * r)
    h = math.sqrt(h2)
    C = B + x * u + sign * h * np.array([-u[1], u[0]])
    return B, C


def _mode(B, C, D) -> float:
    return float(np.sign((D[0] - B[0]) * (C[1] - B[1]) - (D[1] - B[1]) * (C[0] - B[0])))


def function_generator(f, x_range, phi_range_deg, psi_range_deg, *, precision_points=3, x_points=None,
                       ground=1.0, name="function-generator", steps=181, speed=1.0) -> Design:
    """A four-bar generating ``y = f(x)``: the rocker angle against the crank angle.

    Parameters
    ----------
    f : callable
        ``f(x)`` on a float array (:func:`~linkage_sym.synthesis.expression.parse`,
        :func:`table_function`).
    x_range : (float, float)
        ``x0, x1``.
    phi_range_deg, psi_range_deg : (float, float)
        The crank's and the rocker's angles (degrees from ``+x``) at ``x0`` and ``x1``.
    precision_points : int
        Precision points, Chebyshev-spaced (3: exact; more: least squares).
    x_points : sequence of float, optional
        The precision points' ``x`` instead (at least 3).
    ground : float
        The frame ``AD`` (m): the design's scale.
    name, steps, speed
        The scene's name, the sweep's steps over the input range, the crank's speed (rad/s).

    Returns
    -------
    Design
        ``lengths`` crank, coupler, rocker, ground; ``extra``: ``K`` (K1, K2,
        K3), ``x_points``, ``phi``, ``psi`` (rad) of the precision points,
        ``equation_residual`` (largest at the points), ``phi_range``, ``psi_offset``
        (the rocker's scene angle minus ``psi``: 0 or pi).

    Raises
    ------
    SynthesisError
        A malformed range or point, a singular system, lengths that close
        no loop, precision points in two assembly modes (a branch defect) or
        a crank angle of the range where the linkage cannot be assembled.
    """
    x_range = _range("x_range", x_range)
    phi_range = _range("phi_range", phi_range_deg)
    psi_range = _range("psi_range", psi_range_deg)
    d = positive("ground", ground)
    steps, speed = sweep_options(steps, speed)
    name = scene_name(name)
    if x_points is None:
        if not isinstance(precision_points, int) or precision_points < 3:
            raise SynthesisError("precision_points", f"at least 3, got {precision_points!r}")
        xs = chebyshev(*x_range, precision_points)
    else:
        xs = np.array([number("x_points", v) for v in x_points])
        if len(xs) < 3 or len(set(xs.tolist())) != len(xs):
            raise SynthesisError("x_points", "at least 3 distinct precision points are expected")
    phi, psi = _mapping(f, x_range, phi_range, psi_range)
    P, S = phi(xs), psi(xs)
    if not np.isfinite(S).all():
        raise SynthesisError("function", "f is not finite at every precision point")
    M = np.column_stack([np.cos(P), -np.cos(S), np.ones_like(P)])
    rhs = np.cos(P - S)
    if np.linalg.cond(M) > 1e12:
        raise SynthesisError("x_points", "the precision points give a singular system (angles too "
                             "close, or ranges that make the equations dependent)")
    K = np.linalg.solve(M, rhs) if len(xs) == 3 else np.linalg.lstsq(M, rhs, rcond=None)[0]
    if K[0] == 0.0 or K[1] == 0.0:
        raise SynthesisError("function", "K1 or K2 is zero: the rocker or crank would be infinite")
    c, a = -d / K[0], -d / K[1]
    b2 = a * a + c * c + d * d - 2 * a * c * K[2]
    if not b2 > 0:
        raise SynthesisError("function", f"no coupler length: b^2 = {b2:.6g} (K3 = {K[2]:.6g})")
    b = math.sqrt(b2)
    # each precision point's configuration: C from the asked-for psi; its assembly mode
    D = np.array([d, 0.0])
    modes = []
    for p, s in zip(P, S):
        B = np.array([a * math.cos(p), a * math.sin(p)])
        C = D + c * np.array([math.cos(s), math.sin(s)])
        modes.append(_mode(B, C, D))
    if len(set(modes)) != 1 or modes[0] == 0:
        raise SynthesisError("x_points", "the precision points lie in different assembly modes "
                             "(a branch defect): choose other ranges or points")
    start = math.radians(phi_range[0])
    conf = _assembly(a, b, c, d, start, modes[0])
    if conf is None:
        raise SynthesisError("phi_range", f"at the input range's start ({phi_range[0]:g}°) the "
                             "four-bar cannot be assembled (or sits at a dead centre)")
    scene = _scene(name, conf, d, a, phi_range, steps, speed)
    residual = float(np.max(np.abs(M @ K - rhs)))
    notes = (f"Freudenstein K1 = {K[0]:.9g}, K2 = {K[1]:.9g}, K3 = {K[2]:.9g}",
             f"crank {fmt_len(abs(a))}, coupler {fmt_len(b)}, rocker {fmt_len(abs(c))}, ground "
             f"{fmt_len(d)}")
    extra = {"K": tuple(float(k) for k in K), "x_points": xs, "phi": P, "psi": S,
             "equation_residual": residual, "phi_range": phi_range, "psi_range": psi_range,
             "x_range": x_range, "crank_offset": 0.0 if a > 0 else math.pi,
             "psi_offset": 0.0 if c > 0 else math.pi}
    return Design("fourbar", scene, {"crank": float(abs(a)), "coupler": b, "rocker": float(abs(c)),
                                     "ground": d},
                  notes, extra=extra)


def _scene(name, conf, d, a, phi_range, steps, speed) -> dict:
    B, C = conf
    shift = 0.0 if a > 0 else 180.0
    drv = {"joint": "A", "toward": "B", "start_deg": phi_range[0] + shift,
           "stop_deg": phi_range[1] + shift, "steps": steps, "speed": speed, "acceleration": 0.0}
    joints = [
        {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
        {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": [float(B[0]), float(B[1])]},
        {"name": "C", "type": "R", "links": ["coupler", "rocker"], "at": [float(C[0]), float(C[1])]},
        {"name": "D", "type": "R", "links": ["rocker", "ground"], "at": [d, 0.0]},
    ]
    return {"name": name, "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "rocker"}],
            "joints": joints, "drivers": [drv], "outputs": ["kinematics"]}


def structural_error(design, f, n=361):
    """The structural error over the input range, measured by the solver.

    The scene is analysed by ``linkage_sym.compile_plan`` at ``n`` crank
    angles over the range; the rocker's angle is read from the solved joints
    ``C`` and ``D`` (not from the design equation) and compared with the
    angle ``f`` asks for.

    Returns
    -------
    x, error : ndarray
        ``x`` over its range and the error (rad); NaN where the solver
        reports a step it could not solve.
    """
    import linkage_sym

    ex = design.extra
    phi, psi = _mapping(f, ex["x_range"], ex["phi_range"], ex["psi_range"])
    x = np.linspace(*ex["x_range"], n)
    plan = linkage_sym.compile_plan(linkage_sym.load_scene(design.scene))
    q = phi(x) + ex["crank_offset"]
    res = plan.run(q={"A": q}, qd={"A": np.ones(n)}, qdd={"A": np.zeros(n)})
    C, D = res.joints["C"].position, res.joints["D"].position
    got = np.arctan2(C[:, 1] - D[:, 1], C[:, 0] - D[:, 0]) - ex["psi_offset"]
    err = np.angle(np.exp(1j * (got - psi(x))))
    err[res.status != "ok"] = np.nan
    return x, err
