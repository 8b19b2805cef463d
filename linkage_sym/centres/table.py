"""The instant centres of a sweep as reported: Kennedy's, filled and screened by velocities.

Every unordered pair of links (the ground included) has one centre at each
step with velocities.  :func:`instant_centres` takes it from Kennedy's
construction (:mod:`linkage_sym.centres.kennedy`); a pair that construction
cannot reach is filled from the velocity fields
(:mod:`linkage_sym.centres.velocity`) and marked; a pair whose links are at
rest relative to each other at that step has no centre (every point would be
one) and is reported ``undefined``, unless they share a pin: the pin has no
relative velocity at any step, so it is their centre then too.  The result's
``instant_centres`` output (an extension of the scene format) is
:meth:`InstantCentres.records`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkage_sym.centres.kennedy import kennedy_centres
from linkage_sym.centres.velocity import velocity_centres

__all__ = ["InstantCentres", "instant_centres", "textbook_numbers"]


def textbook_numbers(links) -> dict:
    """Link numbers as in the textbook chapter's figures: the ground 1, then the links in order.

    Parameters
    ----------
    links : sequence of str
        ``ground`` first, then the moving links in scene order.

    Examples
    --------
    >>> textbook_numbers(("ground", "crank", "coupler", "rocker"))
    {'ground': 1, 'crank': 2, 'coupler': 3, 'rocker': 4}
    """
    return {name: i + 1 for i, name in enumerate(links)}


@dataclass
class InstantCentres:
    """Every pair's instant centre at every step of a sweep.

    Attributes
    ----------
    links : tuple of str
        ``ground``, then the scene's links in scene order.
    pairs : tuple of (str, str)
        ``(links[i], links[j])`` for ``i < j``: ``N (N - 1) / 2`` of them
        (eq. 3-5 of the textbook chapter *Kinematic analysis of planar mechanisms*).
    rates : ndarray of bool, shape (N,)
        Steps with velocities (``ok`` steps of a sweep whose velocity stage
        ran); only these have centres.
    position : ndarray, shape (N, P, 2)
        Finite centres (m); NaN otherwise.
    direction : ndarray, shape (N, P, 2)
        Unit direction of the centres at infinity (the sign is free: the
        larger component is made positive); NaN otherwise.
    at_infinity, undefined : ndarray of bool, shape (N, P)
    from_velocities : ndarray of bool, shape (N, P)
        Centres Kennedy's construction did not reach at that step, filled
        from the velocity fields.
    source : tuple of str
        How Kennedy's construction finds each pair (see
        :class:`~linkage_sym.centres.kennedy.KennedyCentres`).
    kennedy : KennedyCentres
        The construction itself (for its three-centre lines).
    """

    links: tuple
    pairs: tuple
    rates: np.ndarray
    position: np.ndarray
    direction: np.ndarray
    at_infinity: np.ndarray
    undefined: np.ndarray
    from_velocities: np.ndarray
    source: tuple
    kennedy: object

    def index(self, a: str, b: str) -> int:
        """Index into :attr:`pairs` of the unordered pair ``{a, b}``.

        Examples
        --------
        >>> import linkage_sym
        >>> scene = linkage_sym.load_example("crank_rocker")
        >>> ic = instant_centres(scene, linkage_sym.analyze(scene))
        >>> ic.pairs[ic.index("rocker", "crank")]
        ('crank', 'rocker')
        """
        i, j = sorted((self.links.index(a), self.links.index(b)))
        n = len(self.links)
        return i * n - i * (i + 1) // 2 + (j - i - 1)

    def label(self, k: int) -> str:
        """``P13``: pair ``k`` in the textbook's numbering (the ground is link 1).

        Examples
        --------
        >>> import linkage_sym
        >>> scene = linkage_sym.load_example("crank_rocker")
        >>> ic = instant_centres(scene, linkage_sym.analyze(scene))
        >>> ic.label(ic.index("coupler", "ground")), ic.label(ic.index("rocker", "crank"))
        ('P13', 'P24')
        """
        num = textbook_numbers(self.links)
        a, b = self.pairs[k]
        sep = "" if len(self.links) < 10 else ","
        return f"P{num[a]}{sep}{num[b]}"

    def columns(self) -> list:
        """The columns of the ``instant_centres`` records
        (:meth:`linkage_sym.numeric.results.result.Analysis.columns`).

        Per pair ``a, b`` (in the records' order): ``instant_centres.a.b.position.x``, ``.y``
        where the record has a ``position``, ``direction.x``, ``.y`` where it is ``at_infinity``
        (both ``"finite"``: NaN wherever the record has no such number), and two flags at
        every ``ok`` step, 1 or 0: ``undefined`` (the record says ``undefined``) and
        ``from_velocities`` (its ``method`` is ``"velocity"``).
        """
        rates = np.asarray(self.rates, bool)
        out = []
        for k, (a, b) in enumerate(self.pairs):
            und = self.undefined[:, k]
            flags = {"undefined": und, "from_velocities": self.from_velocities[:, k] & ~und}
            p = f"instant_centres.{a}.{b}"
            out += [(f"{p}.position.x", self.position[:, k, 0], "finite"),
                    (f"{p}.position.y", self.position[:, k, 1], "finite"),
                    (f"{p}.direction.x", self.direction[:, k, 0], "finite"),
                    (f"{p}.direction.y", self.direction[:, k, 1], "finite")]
            out += [(f"{p}.{name}", np.where(rates, f.astype(float), np.nan), "ok")
                    for name, f in flags.items()]
        return out

    def records(self, i: int) -> list:
        """The ``instant_centres`` entry of step ``i`` of the result (empty without rates).

        One record per pair, in :attr:`pairs` order: ``{"links": [a, b],
        "position": [x, y]}``, ``{"links": [a, b], "at_infinity": true,
        "direction": [ux, uy]}`` or ``{"links": [a, b], "undefined": true}``;
        a centre filled from the velocities also has ``"method": "velocity"``.

        Examples
        --------
        >>> import linkage_sym
        >>> scene = linkage_sym.load_example("slider_crank_offset")
        >>> ic = instant_centres(scene, linkage_sym.analyze(scene))
        >>> ic.records(30)[ic.index("ground", "slider")]
        {'links': ['ground', 'slider'], 'at_infinity': True, 'direction': [0.0, 1.0]}
        >>> ic.records(30)[ic.index("ground", "crank")]
        {'links': ['ground', 'crank'], 'position': [0.0, 0.0]}
        """
        if not self.rates[i]:
            return []
        out = []
        for k, (a, b) in enumerate(self.pairs):
            rec: dict = {"links": [a, b]}
            if self.undefined[i, k]:
                rec["undefined"] = True
            elif self.at_infinity[i, k]:
                rec["at_infinity"] = True
                rec["direction"] = [float(x) + 0.0 for x in self.direction[i, k]]
            else:
                rec["position"] = [float(x) + 0.0 for x in self.position[i, k]]
            if self.from_velocities[i, k] and not self.undefined[i, k]:
                rec["method"] = "velocity"
            out.append(rec)
        return out


def _canonical(u):
    """Unit directions (..., 2) with their larger component made positive (the sign is free)."""
    big = np.where(np.abs(u[..., 0]) >= np.abs(u[..., 1]), u[..., 0], u[..., 1])
    return np.where((big < 0)[..., None], -u, u)


def instant_centres(scene, analysis) -> InstantCentres:
    """The instant centres of every pair of links at every step with velocities.

    Kennedy's construction gives them (it is the default); the velocity
    method fills the pairs Kennedy cannot reach (marked), and says where two
    links are at rest relative to each other (``undefined``; two links that
    share a pin keep the pin as their centre).

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        The scene's solved sweep.

    Returns
    -------
    InstantCentres

    Examples
    --------
    A four-bar has 4 * 3 / 2 = 6 centres; the five-bar (two drivers) has 10, of
    which the 5 not at a joint come from the velocities: the three-centre
    lines run out.

    >>> import linkage_sym
    >>> scene = linkage_sym.load_example("fivebar")
    >>> ic = instant_centres(scene, linkage_sym.analyze(scene))
    >>> len(ic.pairs), int(ic.from_velocities[100].sum())
    (10, 5)
    >>> ic.records(100)[1]["method"]
    'velocity'
    """
    k = kennedy_centres(scene, analysis)
    N, P = k.at_infinity.shape
    rates = np.asarray(analysis.status == "ok") & ("velocity" in analysis.stages)
    if "velocity" in analysis.stages:
        v = velocity_centres(analysis)
        if v.pairs != k.pairs:  # both list ground first, then the links in scene order
            raise ValueError(f"the analysis' links {v.links} are not the scene's {k.links}")
        # a pin is a centre of its links at every step, at relative rest too
        undefined = v.undefined & rates[:, None] & ~k.pinned[None, :]
    else:
        v = None
        undefined = np.zeros((N, P), dtype=bool)
    fill = rates[:, None] & ~k.reached & ~undefined
    use = rates[:, None] & k.reached & ~undefined
    if v is not None:
        inf = np.where(use, k.at_infinity, fill & v.at_infinity)
        pos = np.where(use[..., None], k.position, np.where(fill[..., None], v.position, np.nan))
        u = np.where(use[..., None], k.direction, np.where(fill[..., None], v.direction, np.nan))
    else:
        inf, pos, u = use & k.at_infinity, np.where(use[..., None], k.position, np.nan), k.direction
    inf = inf & rates[:, None]
    return InstantCentres(
        links=k.links,
        pairs=k.pairs,
        rates=rates,
        position=np.where((rates[:, None] & ~inf & ~undefined)[..., None], pos, np.nan),
        direction=np.where(inf[..., None], _canonical(u), np.nan),
        at_infinity=inf,
        undefined=undefined,
        from_velocities=fill,
        source=k.source,
        kennedy=k,
    )
