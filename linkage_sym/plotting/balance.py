"""Balancing plots (moved to :mod:`linkage_sym.plotting.balance_force`, whose names are
importable from here)."""

from linkage_sym.plotting.balance_force import (  # noqa: F401 - the names documented here
    SMALL_RATIO,
    ZERO_ABS,
    ZERO_REL,
    shaking_force_polar,
    shaking_force_polar_figure,
    shaking_moment_curve,
    shaking_moment_figure,
)
