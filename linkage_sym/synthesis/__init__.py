"""Synthesis: linkages from what the designer wants, as verified scenes.

* :mod:`~linkage_sym.synthesis.builders` -- scenes from dimensions: the
  four-bar, the offset slider-crank, the rocking guide-bar
  (``linkage-sym new``);
* :mod:`~linkage_sym.synthesis.kratio` -- design by the stroke-time ratio
  ``K`` with the auxiliary circle: crank-rocker (``kratio_rocker``),
  slider-crank and guide-bar (``kratio_slider``), what they share
  (``kratio_common``) and the check of the ``K`` a scene holds
  (``kratio_check``)
  (``linkage-sym synthesize crank-rocker|slider-crank|guide-bar``);
* :mod:`~linkage_sym.synthesis.positions` -- design by two or three coupler
  positions (``linkage-sym synthesize coupler-positions``);
* :mod:`~linkage_sym.synthesis.motion` -- motion generation through four
  or five coupler poses by Burmester theory (:mod:`~linkage_sym.synthesis.burmester`;
  slider and guide dyads, pivots at infinity, in ``burmester_slider`` and ``burmester_rp``),
  every candidate driven through the poses by the solver and classified
  (:mod:`~linkage_sym.synthesis.defects`: branch, order and dead-centre
  defects, Grashof class, minimum transmission angle)
  (``linkage-sym synthesize motion``);
* :mod:`~linkage_sym.synthesis.function_gen` -- function generation by
  Freudenstein's equation, the function parsed safely by
  :mod:`~linkage_sym.synthesis.expression` (``linkage-sym synthesize function``);
* :mod:`~linkage_sym.synthesis.path_gen` -- path generation: three points
  exactly, more by many starts solved at once and least squares; its closed
  forms in :mod:`~linkage_sym.synthesis.path_model`, the solver's check of each
  design in :mod:`~linkage_sym.synthesis.path_check` (``linkage-sym synthesize path``);
* :mod:`~linkage_sym.synthesis.equations` -- the design equations derived
  with SymPy, as text or LaTeX (``linkage-sym synthesize equations``); the
  only module here that imports SymPy (import contract in ``pyproject.toml``).

The methods are those of the textbook section *Design of four-bar mechanisms*
(Sources [2] of the README).  Every design is a plain scene dict that
``linkage_sym.load_scene`` reads; the tests analyse each with the solver.

Examples
--------
>>> from linkage_sym.synthesis import crank_rocker
>>> d = crank_rocker(K=1.5, rocker=0.075, swing_deg=45.0, ground=0.1)
>>> round(d.lengths["crank"], 6), round(d.lengths["coupler"], 6)
(0.025224, 0.050989)
"""

from linkage_sym.synthesis.builders import fourbar, guide_bar, slider_crank
from linkage_sym.synthesis.common import Design, SynthesisError
from linkage_sym.synthesis.kratio import crank_rocker, extreme_position_angle
from linkage_sym.synthesis.kratio import guide_bar as guide_bar_by_K
from linkage_sym.synthesis.kratio import slider_crank as slider_crank_by_K
from linkage_sym.synthesis.positions import coupler_positions


def motion_synthesis(poses, **options):
    """Four-bars and (inverted) slider-cranks whose coupler frame passes through 4 or 5 poses
    ``[x, y, angle_deg]``.

    See :func:`linkage_sym.synthesis.motion.motion_synthesis` (loaded on call:
    its solver checks need SciPy).
    """
    from linkage_sym.synthesis.motion import motion_synthesis as _motion

    return _motion(poses, **options)


__all__ = [
    "Design",
    "SynthesisError",
    "coupler_positions",
    "crank_rocker",
    "extreme_position_angle",
    "fourbar",
    "motion_synthesis",
    "guide_bar",
    "guide_bar_by_K",
    "slider_crank",
    "slider_crank_by_K",
]
