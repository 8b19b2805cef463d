"""What the callers of the force layer read without loading it: the force methods and the
superposition's cancellation limit.

A run without forces (``Plan.run`` of a kinematics-only scene, the command line's
``analyze`` of one) checks the force method asked for and words its warnings with the
limit; both live here, with no import, so that such a run loads none of the force
routines (:mod:`~linkage_sym.numeric.forces.kinetostatics` and the modules it uses), a
part of the command line's start-up (issue 28).  Those modules import them from here.
"""

from __future__ import annotations

__all__ = ["AMPLIFICATION_LIMIT", "METHODS", "check_method"]

METHODS = ("dyad", "global")
"""The force methods of :mod:`~linkage_sym.numeric.forces.kinetostatics`."""

AMPLIFICATION_LIMIT = 1e3
"""Above this cancellation factor (3 digits lost) another disconnection is tried."""


def check_method(method) -> None:
    """Refuse a force method that does not exist, naming the field.

    Parameters
    ----------
    method : str
        One of :data:`METHODS`.

    Raises
    ------
    ValueError
        Any other value.

    Examples
    --------
    >>> check_method("global")
    >>> check_method("fast")
    Traceback (most recent call last):
    ...
    ValueError: method: unknown force method 'fast' (use one of dyad, global)
    """
    if method not in METHODS:
        raise ValueError(
            f"method: unknown force method {method!r} (use one of {', '.join(METHODS)})"
        )
