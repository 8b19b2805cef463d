"""The integrators ``simulate`` offers, named without importing SciPy (the command line's
help lists them before any of the motion's machinery loads)."""

__all__ = ["METHODS", "check_solver"]

METHODS = ("Radau", "LSODA", "BDF")
"""The stiff-capable methods of :func:`scipy.integrate.solve_ivp` offered."""


def check_solver(method: str, rtol: float, most: float) -> None:
    """Refuse a ``method`` not in :data:`METHODS` or a relative tolerance ``rtol`` outside
    ``(0, most]``, naming the argument.

    Examples
    --------
    >>> check_solver("LSODA", 1e-10, 1e-10)
    >>> check_solver("RK45", 1e-10, 1e-10)
    Traceback (most recent call last):
    ...
    ValueError: method: one of Radau, LSODA, BDF, got 'RK45'
    """
    if method not in METHODS:
        raise ValueError(f"method: one of {', '.join(METHODS)}, got {method!r}")
    if not 0 < rtol <= most:
        raise ValueError(f"rtol: must be in (0, {most:g}], got {rtol!r}")
