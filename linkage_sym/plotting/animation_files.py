"""The files an animation is written to, and what its arguments may be (Matplotlib only).

:mod:`linkage_sym.plotting.animation` draws the frames; this module checks the arguments that
decide what is drawn and written (the frames, the rate, the file's kind) and makes the HTML
player one self-contained file.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
from matplotlib import animation as mpl_animation

__all__ = ["DEFAULT_FRAMES", "EMBED_LIMIT_MB", "SUFFIXES", "AnimationError", "check_fps", "frame_steps",
           "html_page", "output_kind", "positive", "require_ffmpeg", "self_contained"]

DEFAULT_FRAMES = 120
"""Frames of an animation whose count is not given (every step of a shorter sweep)."""


SUFFIXES = {".gif": "GIF (Pillow)", ".mp4": "MP4 (ffmpeg)", ".html": "HTML (one self-contained file)"}
"""The files an animation is written to, by suffix."""

EMBED_LIMIT_MB = 1000.0
"""Size (MB) up to which an HTML animation embeds every frame (Matplotlib's default, 20 MB,
would drop the frames past it)."""

class AnimationError(ValueError):
    """An animation that cannot be made or written as asked: ``field`` names the
    argument (``frames``, ``fps``, ``path``, or a layer: ``forces`` ...), ``reason`` says why.

    Examples
    --------
    >>> str(AnimationError("frames", "at most the sweep's 37 steps, got 40"))
    "frames: at most the sweep's 37 steps, got 40"
    """

    def __init__(self, field: str, reason: str):
        self.field = field
        self.reason = reason
        super().__init__(f"{field}: {reason}")


def frame_steps(n_steps: int, frames: int | None = None) -> np.ndarray:
    """The steps shown by ``frames`` frames: the sweep sampled evenly, first and last step
    included.

    Parameters
    ----------
    n_steps : int
        Steps of the sweep.
    frames : int, optional
        Frames wanted, 1 to ``n_steps``; default ``min(n_steps, DEFAULT_FRAMES)``.

    Returns
    -------
    ndarray of int, shape (frames,)
        Increasing, all different (a spacing of at least one step rounds to distinct steps).

    Raises
    ------
    AnimationError
        ``frames`` not a whole number from 1 to ``n_steps``.

    Examples
    --------
    >>> frame_steps(361, 5).tolist(), frame_steps(4).tolist(), frame_steps(37, 1).tolist()
    ([0, 90, 180, 270, 360], [0, 1, 2, 3], [0])
    """
    if n_steps < 1:
        raise AnimationError("frames", "the analysis has no step to show")
    if frames is None:
        frames = min(n_steps, DEFAULT_FRAMES)
    if isinstance(frames, bool) or not isinstance(frames, (int, np.integer)):
        raise AnimationError("frames", f"a whole number of frames is expected, got {frames!r}")
    if not 1 <= frames <= n_steps:
        raise AnimationError("frames", f"from 1 to the sweep's {n_steps} steps (one frame a "
                             f"step at most), got {frames}")
    if frames == 1:
        return np.zeros(1, dtype=int)
    return np.rint(np.linspace(0.0, n_steps - 1, int(frames))).astype(int)


def positive(field: str, value, what: str) -> float:
    """``value`` as a positive finite float, else :class:`AnimationError` naming ``field``."""
    if not isinstance(value, bool):
        try:
            number = float(value)
        except (TypeError, ValueError):
            number = math.nan
        if math.isfinite(number) and number > 0.0:
            return number
    raise AnimationError(field, f"a positive number of {what} is expected, got {value!r}")


def check_fps(fps) -> float:
    """``fps`` as a positive finite float, else :class:`AnimationError` (field ``fps``).

    Examples
    --------
    >>> check_fps(12), check_fps("2.5")
    (12.0, 2.5)
    """
    return positive("fps", fps, "frames per second")


def output_kind(path) -> str:
    """``"gif"``, ``"mp4"`` or ``"html"`` from ``path``'s suffix (any case).

    Raises
    ------
    AnimationError
        Another suffix (field ``path``).

    Examples
    --------
    >>> output_kind("motion.GIF"), output_kind("a/b.html")
    ('gif', 'html')
    >>> output_kind("motion.png")
    Traceback (most recent call last):
    ...
    linkage_sym.plotting.animation_files.AnimationError: path: 'motion.png': an animation is written as .gif, .mp4 or .html, not '.png'
    """
    suffix = Path(path).suffix.lower()
    if suffix not in SUFFIXES:
        given = f"{suffix!r}" if suffix else "a name without a suffix"
        raise AnimationError("path", f"{str(path)!r}: an animation is written as .gif, .mp4 "
                             f"or .html, not {given}")
    return suffix[1:]


def require_ffmpeg() -> None:
    """Raise :class:`AnimationError` (field ``path``) if Matplotlib finds no ffmpeg for MP4."""
    if not mpl_animation.writers.is_available("ffmpeg"):
        raise AnimationError("path", "an MP4 file is written by ffmpeg, which is not found "
                             "(not on the PATH, nor set in Matplotlib's animation.ffmpeg_path); "
                             "a .gif or .html file needs nothing more")


ICONS = {"fa fa-minus": "\u2212", "fa fa-fast-backward": "|\u25c0\u25c0",
         "fa fa-step-backward": "|\u25c0", "fa fa-play fa-flip-horizontal": "\u25c0",
         "fa fa-pause": "||", "fa fa-play": "\u25b6", "fa fa-step-forward": "\u25b6|",
         "fa fa-fast-forward": "\u25b6\u25b6|", "fa fa-plus": "+"}
"""The player's buttons as characters (triangles of the Geometric Shapes block, which common
fonts have), for the icon font Matplotlib's player fetches."""


def self_contained(html: str) -> str:
    """Matplotlib's player (:meth:`~matplotlib.animation.Animation.to_jshtml`) without its one
    outside reference: the stylesheet of an icon font (Font Awesome, from a CDN) is left out and
    the buttons' icons are written as characters (:data:`ICONS`).

    Examples
    --------
    >>> self_contained('<link rel="stylesheet"\\nhref="https://x/fa.css">'
    ...                '<button><i class="fa fa-play"></i></button>')
    '<button>\u25b6</button>'
    """
    html = re.sub(r"<link\b[^>]*\bhref\s*=\s*[\"']?https?://[^>]*>", "", html)
    return re.sub(r'<i class="(fa [^"]*)"></i>', lambda m: ICONS.get(m.group(1), "?"), html)


def html_page(title: str, body: str) -> str:
    """One HTML document around the player (no reference outside the file)."""
    from html import escape

    return (f"<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            f"<title>{escape(title)}</title>\n</head>\n<body>\n{body}\n</body>\n</html>\n")
