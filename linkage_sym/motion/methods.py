"""The integrators ``simulate`` offers, named without importing SciPy (the command line's
help lists them before any of the motion's machinery loads)."""

__all__ = ["METHODS"]

METHODS = ("Radau", "LSODA", "BDF")
"""The stiff-capable methods of :func:`scipy.integrate.solve_ivp` offered."""
