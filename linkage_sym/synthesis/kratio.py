"""Synthesis by the stroke-time ratio ``K`` (moved to
:mod:`linkage_sym.synthesis.kratio_rocker`, whose names are importable from here)."""

from linkage_sym.synthesis.kratio_rocker import (  # noqa: F401 - the names documented here
    ALPHA_TOL,
    GRID,
    K_RTOL,
    crank_rocker,
    extreme_position_angle,
    guide_bar,
    scene_K,
    slider_crank,
)
