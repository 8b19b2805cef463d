"""Solving positions and rates: every group's solver, in pose coordinates (NumPy/SciPy only).

``constraints`` (joint, gear-mesh and driver equations in pose coordinates),
``cams`` (cam contacts: positions, the instantaneous replacement, records) on
``cam_profile`` (a cam's profile curve), ``joint_rows`` (a scene's rows, every
joint's and driver's), ``state`` (a link's pose and rates over the steps),
``loci`` (the circles and lines a dyad's joint lies on), ``solver`` (the
``GroupSolver`` contract every group's solver meets), ``closed_form`` (input
links and dyads), ``gears`` (a gear on its pivot, mesh forces), ``newton``
(groups by Newton's method in pose coordinates) and ``loop_closure`` (groups
of R and P joints and gear meshes -- class-III triads, the printing
mechanism's, actuator groups, gear trains -- in their links' angles and
slides), both continued along the path by :mod:`linkage_sym.numeric.continuation`.
"""
