"""Synthesis by the stroke-time ratio ``K``: crank-rocker, offset slider-crank, guide-bar.

The textbook section *Design of four-bar mechanisms* (Sources [2] of the
README; "design by a given stroke-time ratio", Fig. 2-65) designs a linkage
with quick return from ``K``, the ratio of the slower stroke's time to the
faster's.  The crank turns through ``pi + theta`` in one stroke and
``pi - theta`` in the other, so (eq. 2-2)::

    theta = pi (K - 1) / (K + 1)        (180 deg (K - 1)/(K + 1))

the *extreme-position angle*: the angle at the crank pivot ``A`` between the
lines to the output's two extreme positions ``C1`` (crank and coupler
extended, ``AC1 = b + a``) and ``C2`` (overlapping, ``AC2 = b - a``).

**Auxiliary circle.**  Every point that sees the chord ``C1 C2`` under the
angle ``theta`` lies on one of two arcs of radius ``R = |C1C2| / (2 sin theta)``
through ``C1`` and ``C2``, mirror images in the chord's line (the section draws
the one on the side away from the rocker's pivot ``D``; the other one, on
``D``'s side, gives valid crank-rockers too).  With ``alpha`` the angle
``A C1 C2``, the law of sines gives ``AC1 = 2R sin(theta + alpha)`` and
``AC2 = 2R sin(alpha)``, hence the crank ``a = (AC1 - AC2)/2 =
2R sin(theta/2) cos(alpha + theta/2)`` and the coupler ``b = (AC1 + AC2)/2``.
Each arc's two halves (either side of the chord's perpendicular bisector,
which passes through ``D``) are mirror images giving the same linkage, so
``alpha`` runs over ``(0, (pi - theta)/2)`` on each arc.

**The forbidden arc.**  At the extreme positions the dyad ``B C D`` has its
assembly mode given by the side of line ``AD`` that ``C1`` (or ``C2``) lies on;
both extremes are reached in one assembly mode only if ``C1`` and ``C2`` lie on
one side of ``AD``.  A pivot ``A`` between the lines ``D C1`` and ``D C2`` (the
double wedge they form at ``D``) puts them on opposite sides: it is refused.
On its boundary ``A``, ``D`` and an extreme position are in line and the
transmission angle there is 0.  Elsewhere the triangle inequalities of
``A C1 D`` and ``A C2 D`` are exactly Grashof's conditions with the crank
shortest: every admissible pivot gives a crank-rocker whose rocker swings
through ``psi`` with the ratio ``K``.

**Which requests have a solution.**  The line ``D C1`` meets the arc away
from ``D`` (besides ``C1``) only if ``theta + psi/2 < 90`` degrees, and that
arc's admissible part ends there; the arc on ``D``'s side has an admissible
part exactly when ``theta < 90 + psi/2`` degrees.  So a crank-rocker with
swing ``psi`` exists for ``theta < 90 + psi/2`` degrees (tested against the
side-of-line criterion itself); larger ``K`` is refused.

**One more condition.**  The section notes the infinitely many solutions
until one more is given: the ground length ``AD`` (the circle of radius ``d``
about ``D`` meets each arc at most once per half), the crank length (``alpha``
in closed form above), or -- when neither is given -- the largest minimum
transmission angle, found over the admissible arcs (a grid of
:data:`GRID` points per interval, then golden-section search to
:data:`ALPHA_TOL` in ``alpha``).

**Slider-crank** (stroke ``H``): the chord is the stroke on the slider's
line; the foot of ``A`` on that line must lie outside the stroke (else the
two extremes are in different assembly modes), which needs ``theta < 90``
degrees and an offset ``0 < e < H cot(theta)``; then ``e = AC1 sin(alpha)``,
``alpha`` over ``(0, pi/2 - theta)``, and the minimum transmission angle is
``acos((a + e)/b)``.

**Guide-bar** (frame ``d``): at the extremes the guide is tangent to the
crank circle, so the guide's swing equals ``theta`` and ``a = d sin(theta/2)``;
its transmission angle is 90 degrees throughout.

**Modules.**  :mod:`~linkage_sym.synthesis.kratio_common` (``theta`` of
``K``, the bounds of the scene format, the search along the arcs),
:mod:`~linkage_sym.synthesis.kratio_rocker` (the crank-rocker),
:mod:`~linkage_sym.synthesis.kratio_slider` (the slider-crank and the
guide-bar) and :mod:`~linkage_sym.synthesis.kratio_check` (:func:`scene_K`,
the ratio a design's scene holds, checked to :data:`K_RTOL`); their public
names are importable from here.

NumPy only (import contract in ``pyproject.toml``); the same relations
derived with SymPy are in :mod:`linkage_sym.synthesis.equations`.
"""

from linkage_sym.synthesis.kratio_check import K_RTOL, scene_K
from linkage_sym.synthesis.kratio_common import ALPHA_TOL, GRID, extreme_position_angle
from linkage_sym.synthesis.kratio_rocker import crank_rocker
from linkage_sym.synthesis.kratio_slider import guide_bar, slider_crank

__all__ = ["ALPHA_TOL", "GRID", "K_RTOL", "crank_rocker", "extreme_position_angle", "guide_bar",
           "scene_K", "slider_crank"]
