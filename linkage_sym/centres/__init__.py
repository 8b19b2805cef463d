"""Instant centres, centrodes and the quantities of the graphical method (NumPy only).

The textbook chapter *Kinematic analysis of planar mechanisms* (README Sources [4], section 3-2)
teaches velocity analysis by instant centres (eq. 3-5: ``N (N - 1) / 2`` of
them; Kennedy's three-centre theorem) and by velocity and acceleration
polygons with their relative and Coriolis terms.  This package computes them
from a solved sweep (:func:`linkage_sym.analyze`):

:func:`instant_centres`
    Every pair's centre at every step, by Kennedy's construction
    (:mod:`~linkage_sym.centres.kennedy`, its homogeneous points and
    three-centre lines :mod:`~linkage_sym.centres.kennedy_lines`), with the
    pairs it cannot reach
    filled from the velocity fields (:mod:`~linkage_sym.centres.velocity`,
    which shares no code with it and checks it in the tests).
:func:`centrodes`
    Fixed and moving centrodes of the floating links.
:func:`polygon_quantities`
    Absolute, relative (normal, tangential), slip and Coriolis terms of one step.

A scene that lists ``"instant_centres"`` in its ``outputs`` (an extension of
the format) gets the centres in its result, step by step.
"""

from linkage_sym.centres.centrodes import Centrode, centrodes, floating_links
from linkage_sym.centres.kennedy import KennedyCentres, kennedy_centres
from linkage_sym.centres.polygons import Polygons, polygon_quantities
from linkage_sym.centres.table import InstantCentres, instant_centres, textbook_numbers
from linkage_sym.centres.velocity import VelocityCentres, velocity_centres

__all__ = [
    "Centrode",
    "InstantCentres",
    "KennedyCentres",
    "Polygons",
    "VelocityCentres",
    "centrodes",
    "floating_links",
    "instant_centres",
    "kennedy_centres",
    "polygon_quantities",
    "textbook_numbers",
    "velocity_centres",
]
