"""Synthesis: linkages from what the designer wants, as verified scenes.

* :mod:`~linkage_sym.synthesis.builders` -- scenes from dimensions: the
  four-bar, the offset slider-crank, the rocking guide-bar
  (``linkage-sym new``);
* :mod:`~linkage_sym.synthesis.kratio` -- design by the stroke-time ratio
  ``K`` with the auxiliary circle: crank-rocker, slider-crank, guide-bar
  (``linkage-sym synthesize crank-rocker|slider-crank|guide-bar``).

The methods are those of the textbook section *Design of four-bar mechanisms*
(Sources [2] of the README).  Every design is a plain scene dict that
``linkage_sym.load_scene`` reads; the tests analyse each with the solver.
"""

from linkage_sym.synthesis.builders import fourbar, guide_bar, slider_crank
from linkage_sym.synthesis.common import Design, SynthesisError
from linkage_sym.synthesis.kratio import crank_rocker, extreme_position_angle
from linkage_sym.synthesis.kratio import guide_bar as guide_bar_by_K
from linkage_sym.synthesis.kratio import slider_crank as slider_crank_by_K

__all__ = ["Design", "SynthesisError", "crank_rocker", "extreme_position_angle", "fourbar",
           "guide_bar", "guide_bar_by_K", "slider_crank", "slider_crank_by_K"]
