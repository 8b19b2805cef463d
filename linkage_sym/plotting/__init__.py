"""Plots of analysis results (Matplotlib only, no pyplot, no backend switch).

Figures are made with :class:`matplotlib.figure.Figure` and written with
``savefig``, so importing this package changes no global Matplotlib state and
works without a display.  The plotting layer only reads results
(:class:`~linkage_sym.numeric.result.Analysis`) and scenes
(:class:`~linkage_sym.model.Scene`); it solves nothing.

Functions
---------
motion_diagrams
    Position, velocity and acceleration diagrams against the driver (3 PNGs).
coupler_curves
    Joint and centre-of-mass paths with the mechanism drawn (1 PNG).
mechanism_snapshot
    Draw the mechanism at one step on a given Matplotlib axis.
"""

from linkage_sym.plotting.motion import motion_diagrams
from linkage_sym.plotting.paths import coupler_curves, mechanism_snapshot

__all__ = ["coupler_curves", "mechanism_snapshot", "motion_diagrams", "plot_all"]


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
        The motion diagrams, then ``<stem>_paths.png``.
    """
    from pathlib import Path

    from linkage_sym.plotting.style import file_stem

    written = motion_diagrams(scene, analysis, out_dir, prefix=prefix)
    written.append(coupler_curves(scene, analysis, Path(out_dir) / f"{file_stem(scene, prefix)}_paths.png"))
    return written
