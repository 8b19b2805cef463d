"""Plots of analysis results (Matplotlib only, no pyplot, no backend switch).

Figures are made with :class:`matplotlib.figure.Figure` and written with
``savefig``, so importing this package changes no global Matplotlib state and
works without a display.  The plotting layer only reads results
(:class:`~linkage_sym.numeric.results.result.Analysis`) and scenes
(:class:`~linkage_sym.model.Scene`); it solves nothing.

Functions
---------
motion_diagrams
    Position, velocity and acceleration diagrams against the driver (3 PNGs).
coupler_curves
    Joint and centre-of-mass paths with the mechanism drawn (1 PNG).
mechanism_snapshot
    Draw the mechanism at one step on a given Matplotlib axis.
driving_effort
    Driver torques and forces against the driver, with RMS and peak (1 PNG).
reaction_hodographs
    Polar hodographs of the joint reactions over the cycle (1 PNG).
frame_loads
    Frame (or shaking) force hodograph and moment against the driver (1 PNG).

The animation of a sweep (GIF, MP4, HTML) is :func:`linkage_sym.plotting.animation.animate`,
imported on its own (``linkage_sym.animate``) so that the still pictures load no animation
machinery.
"""

from linkage_sym.plotting.forces import driving_effort, frame_loads, reaction_hodographs
from linkage_sym.plotting.motion import motion_diagrams
from linkage_sym.plotting.paths import coupler_curves, mechanism_snapshot

__all__ = [
    "coupler_curves",
    "driving_effort",
    "frame_loads",
    "mechanism_snapshot",
    "motion_diagrams",
    "plot_all",
    "reaction_hodographs",
]


def plot_all(scene, analysis, out_dir, prefix=None):
    """Write every plot of a sweep into ``out_dir``.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
    out_dir : str or os.PathLike
        Created if needed.
    prefix : str, optional
        File-name stem; default the scene's name.

    Returns
    -------
    list of pathlib.Path
        The motion diagrams, then ``<stem>_transmission.png`` (when the
        analysis has transmission angles: an RRR dyad), ``<stem>_paths.png``;
        when the analysis has
        forces (:attr:`Analysis.forces` is not None), then also
        ``<stem>_driving.png`` (if there are driver efforts and ``"driving"``
        is in :attr:`Analysis.outputs`), ``<stem>_reactions.png`` (if
        ``"reactions"`` is) and ``<stem>_frame.png`` (if ``"frame"`` is).
    """
    from pathlib import Path

    from linkage_sym.plotting.style import file_stem

    written = motion_diagrams(scene, analysis, out_dir, prefix=prefix)
    stem = Path(out_dir) / file_stem(scene, prefix)
    if analysis.transmission_angles:
        from linkage_sym.plotting.transmission import transmission_angles

        written.append(transmission_angles(scene, analysis, f"{stem}_transmission.png"))
    written.append(coupler_curves(scene, analysis, f"{stem}_paths.png"))
    forces = analysis.forces
    if forces is not None:
        if forces.driving and "driving" in analysis.outputs:
            written.append(driving_effort(scene, analysis, f"{stem}_driving.png"))
        if "reactions" in analysis.outputs:
            written.append(reaction_hodographs(scene, analysis, f"{stem}_reactions.png"))
        if "frame" in analysis.outputs:
            written.append(frame_loads(scene, analysis, f"{stem}_frame.png"))
    return written
