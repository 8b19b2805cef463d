"""The options of counterweight optimisation, checked in one place (plain Python, no SymPy).

:func:`search_options` checks what :func:`~.search.optimize_counterweights`
is asked (links, weights, bounds) and fills in the defaults of
:func:`default_bounds`; the optimiser calls it, and so does the command line
(``linkage-sym balance --optimize``) before anything is computed, so a bad
option gives the same words from both, every problem at once.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> search_options(load_example("crank_rocker"), links=["crank", "nosuch"], weights=(0, 0, 0))
Traceback (most recent call last):
  ...
linkage_sym.balancing.options.OptionsError: weights: three numbers (force, moment, driving effort) >= 0, not all 0, expected; got 0,0,0; links: 'nosuch' not among the moving links crank, coupler, rocker
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from linkage_sym.balancing.counterweight import as_scene
from linkage_sym.structure.parameters import link_frames

__all__ = ["OptionsError", "SearchOptions", "default_bounds", "search_options"]


class OptionsError(ValueError):
    """Options of :func:`~.search.optimize_counterweights` that cannot be used, all at once.

    ``problems`` holds ``(option, message)`` pairs, ``option`` the name of
    the keyword argument (``links``, ``weights``, ``max_mass``,
    ``max_radius``); the command line turns it into its flag.
    """

    def __init__(self, problems):
        self.problems = list(problems)
        super().__init__("; ".join(f"{option}: {message}" for option, message in self.problems))


@dataclass(frozen=True)
class SearchOptions:
    """Checked options of :func:`~.search.optimize_counterweights` (see :func:`search_options`)."""

    links: tuple
    weights: tuple
    max_mass: dict
    max_radius: dict


def _bad_bound(v) -> bool:
    try:
        v = float(v)
    except (TypeError, ValueError):
        return True
    return not (math.isfinite(v) and v >= 0)


def _per_link(value, links, default, what, problems) -> dict:
    """The bound ``what`` of each link in ``links``; what is wrong with it goes to ``problems``."""
    if value is None:
        return {n: float(default[n]) for n in links}
    if isinstance(value, Mapping):
        unknown = sorted(set(value) - set(links), key=str)
        if unknown:
            problems.append((what, f"links {', '.join(map(repr, unknown))} are not optimised"))
        bad = [n for n in links if n in value and _bad_bound(value[n])]
        problems += [(what, f"of {n}: a finite number >= 0 expected, got {value[n]!r}") for n in bad]
        if unknown or bad:
            return {}
        return {n: float(value.get(n, default[n])) for n in links}
    if _bad_bound(value):
        problems.append((what, f"a finite number >= 0 expected, got {value!r}"))
        return {}
    return {n: float(value) for n in links}


def search_options(scene, links=None, weights=(1.0, 1.0, 1.0), max_mass=None, max_radius=None) -> SearchOptions:
    """The options of :func:`~.search.optimize_counterweights`, checked (the parameters are its own).

    ``weights`` may be given as strings (what a user typed); every problem
    is collected before :class:`OptionsError` is raised.

    Returns
    -------
    SearchOptions
        ``links`` (default: every moving link), ``weights`` as three floats,
        ``max_mass`` and ``max_radius`` per link (defaults of
        :func:`default_bounds` where not given).

    Raises
    ------
    OptionsError
        Naming each option that is wrong, and why.
    """
    scene = as_scene(scene)
    names = list(scene.link_names if links is None else links)
    problems = []
    try:
        given = list(weights)
    except TypeError:
        given = [weights]
    try:
        w = tuple(float(x) for x in given)
    except (TypeError, ValueError):
        w = ()
    if len(w) != 3 or not all(math.isfinite(x) and x >= 0 for x in w) or not any(x > 0 for x in w):
        problems.append(("weights", "three numbers (force, moment, driving effort) >= 0, not all 0, "
                                    f"expected; got {','.join(map(str, given))}"))
    unknown = [n for n in names if n not in scene.link_names]
    if not names:
        problems.append(("links", "no link to optimise"))
    elif unknown:
        problems.append(("links", f"{', '.join(map(repr, unknown))} not among the moving links "
                                  f"{', '.join(scene.link_names)}"))
    elif len(set(names)) != len(names):
        twice = sorted({n for n in names if names.count(n) > 1}, key=names.index)
        problems.append(("links", f"{', '.join(map(repr, twice))} listed twice"))
    dm, dr = default_bounds(scene)
    valid = [n for n in dict.fromkeys(names) if n in scene.link_names]
    Mmax = _per_link(max_mass, valid, dm, "max_mass", problems)
    Rmax = _per_link(max_radius, valid, dr, "max_radius", problems)
    if problems:
        raise OptionsError(problems)
    return SearchOptions(tuple(names), w, Mmax, Rmax)


def default_bounds(scene) -> tuple[dict, dict]:
    """Default bounds of :func:`~.search.optimize_counterweights`, per moving link.

    ``max_mass``: the link's own mass, so that a counterweight at most
    doubles its link's mass and the bounds scale with the masses (ten times
    every mass, ten times every bound); a massless link gets the mean mass
    of the moving links, and 1 kg if every moving link is massless.
    ``max_radius``: twice the link's length ``|uv|`` (its frame's x-axis),
    or twice the mechanism's characteristic length (the largest distance
    between two joints) for a link whose joints all coincide.

    Examples
    --------
    >>> from linkage_sym.examples import load_example
    >>> mm, mr = default_bounds(load_example("crank_rocker"))
    >>> round(mm["crank"], 12), round(mm["rocker"], 12), round(mr["crank"], 12)
    (0.2, 0.3, 0.048)
    """
    scene = as_scene(scene)
    frames = link_frames(scene)
    masses = [link.mass for link in scene.links]
    mean = sum(masses) / len(masses) if masses else 0.0
    fallback = mean if mean > 0 else 1.0
    L = scene.characteristic_length() or 1.0
    mm, mr = {}, {}
    for link in scene.links:
        n = link.name
        fr = frames[n]
        length = 0.0 if fr.v is None else math.dist(fr.origin, scene.joint(fr.v).at)
        mm[n] = link.mass if link.mass > 0 else fallback
        mr[n] = 2.0 * (length if length > 0 else L)
    return mm, mr
