"""The former names of design parameters, still accepted with a warning.

A link's centre of mass in its frame was named ``p_<link>, q_<link>`` until the
symbols were given one meaning each: ``q`` names a driver coordinate (``q_A``), so
the centre of mass is now ``xG_<link>, yG_<link>`` (printed ``x^G, y^G`` in the
derived equations).  A sweep given a former name reads it as the current one and
warns (:class:`FutureWarning`), so that no user's sweep breaks silently; its table's
column carries the current name.

Examples
--------
>>> import warnings
>>> from linkage_sym.examples import load_example
>>> scene = load_example("crank_rocker")
>>> with warnings.catch_warnings(record=True) as caught:
...     warnings.simplefilter("always")
...     current_name("p_coupler", scene), current_name("l_AB", scene)
('xG_coupler', 'l_AB')
>>> str(caught[0].message)
"the design parameter 'p_coupler' is now named 'xG_coupler' (the centre of mass of link coupler in its frame); the former name will be refused in a later version"
"""

from __future__ import annotations

import warnings

from linkage_sym.design.parameters import Designs
from linkage_sym.structure.parameters import ident

__all__ = ["FORMER_PREFIXES", "current_name", "current_names"]

FORMER_PREFIXES = {"p": "xG", "q": "yG"}
"""A former prefix of a link's parameter and the current one."""


def current_name(name: str, scene) -> str:
    """``name``, or the current name of a former one (with a :class:`FutureWarning`).

    Parameters
    ----------
    name : str
        A design parameter's name as the user gave it.
    scene : Scene
        The swept scene: ``p_<link>``/``q_<link>`` are former names only where
        ``<link>`` is one of its links.

    Returns
    -------
    str
        The name the sweep uses.
    """
    pre, sep, rest = name.partition("_")
    if not sep or pre not in FORMER_PREFIXES:
        return name
    link = next((lk for lk in scene.link_names if ident(lk) == rest), None)
    if link is None:
        return name
    new = f"{FORMER_PREFIXES[pre]}_{rest}"
    warnings.warn(f"the design parameter {name!r} is now named {new!r} (the centre of mass "
                  f"of link {link} in its frame); the former name will be refused in a later "
                  "version", FutureWarning, stacklevel=3)
    return new


def current_names(designs: Designs, scene) -> Designs:
    """``designs`` with every former name replaced by the current one (:func:`current_name`).

    Parameters
    ----------
    designs : Designs
        The designs as given.
    scene : Scene
        The swept scene.

    Returns
    -------
    Designs
        The same designs (the same object when no name changes).
    """
    new = {n: current_name(n, scene) for n in designs.names}
    if all(k == v for k, v in new.items()):
        return designs
    axes = tuple((new[n], v) for n, v in designs.axes)
    return Designs(tuple(new[n] for n in designs.names), designs.values, designs.kind, axes)
