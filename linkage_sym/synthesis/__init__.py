"""Synthesis: linkages from what the designer wants, as verified scenes.

* :mod:`~linkage_sym.synthesis.builders` -- scenes from dimensions: the
  four-bar, the offset slider-crank, the rocking guide-bar
  (``linkage-sym new``).

The methods are those of the textbook section *Design of four-bar mechanisms*
(Sources [2] of the README).  Every design is a plain scene dict that
``linkage_sym.load_scene`` reads; the tests analyse each with the solver.
"""

from linkage_sym.synthesis.builders import fourbar, guide_bar, slider_crank
from linkage_sym.synthesis.common import Design, SynthesisError

__all__ = ["Design", "SynthesisError", "fourbar", "guide_bar", "slider_crank"]
