"""A hinged linkage as the balancing derivations see it: pins, link frames, symbols.

Names (the issue's and Song and Wang's (1992) notation, ``<link>`` the link's name):

=========================  ==================================================
``m_<link>``               mass
``a_<link>``               length ``|uv|`` between the frame's joints
``xG_<link>, yG_<link>``   centre of mass in the link frame (origin ``u``,
                           x-axis toward ``v``): Song and Wang's ``p, q``
``k_<link>``               radius of gyration about the centre of mass
``xi_<link>_<P>``,         a third pin ``P`` of the link in its frame
``eta_<link>_<P>``
``x_<P>, y_<P>``           coordinates of pin ``P``
``xdd_<P>, ydd_<P>``       its acceleration
``phidd_<link>``           angular acceleration of the link
=========================  ==================================================

Frames are those of :func:`linkage_sym.structure.parameters.link_frames`:
``u`` is the link's first joint in scene order, ``v`` its second (the first
one at a different point).  A *pin* is a point shared by links: the joints
that sit at one point of a common link (Song and Wang's pin C of links 2, 3 and 4,
written as two joints) are one pin, named after the first of them.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> model = BalanceModel(load_example("crank_rocker"))
>>> [(f.link, f.u, f.v) for f in model.frames.values()]
[('crank', 'A', 'B'), ('coupler', 'B', 'C'), ('rocker', 'C', 'D')]
>>> sorted(model.ground_pins), model.origin_pins
(['A', 'D'], ('A',))
>>> round(model.values()["a_coupler"], 6)
0.063032
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import sympy as sp

from linkage_sym.errors import SceneError
from linkage_sym.model import GROUND, Scene
from linkage_sym.structure.parameters import COINCIDENT, link_frames


def tag(name: str) -> str:
    """A scene name as it appears inside a symbol name (``m_<tag>``)."""
    return "".join(ch if ch.isalnum() or ch == "_" else "_" for ch in name)


JOINT_KINDS = {"P": "prismatic joint", "G": "gear mesh", "cam": "cam contact"}
"""What each joint type other than a hinge (``R``) is called in a message."""

KINDS = {t: f"a {kind}" for t, kind in JOINT_KINDS.items()}


def non_hinged(scene: Scene) -> list:
    """``(index, joint)`` of every joint of ``scene`` that is not a hinge (an ``R`` joint), in
    scene order: what the derived balancing conditions do not cover.

    Examples
    --------
    >>> from linkage_sym.examples import load_example
    >>> non_hinged(load_example("crank_rocker"))
    []
    >>> [(i, j.name, JOINT_KINDS[j.type]) for i, j in non_hinged(load_example("slider_crank_offset"))]
    [(3, 'C_guide', 'prismatic joint')]
    """
    return [(i, j) for i, j in enumerate(scene.joints) if j.type != "R"]


def require_hinged(scene: Scene, what: str) -> None:
    """Refuse a scene with joints other than hinges (prismatic joints, gear meshes, cam
    contacts), naming each of them."""
    bad = [
        f"joints[{i}] '{j.name}': {KINDS.get(j.type, j.type)}; {what} covers hinged (R-joint) "
        "linkages only"
        for i, j in non_hinged(scene)
    ]
    if bad:
        raise SceneError(bad)


@dataclass(frozen=True)
class Pin:
    """A point shared by links: one or more coincident joints."""

    name: str
    joints: tuple
    links: tuple
    at: tuple
    ground: bool
    at_origin: bool


class BalanceModel:
    """Pins, frames and symbols of a hinged linkage.

    Parameters
    ----------
    scene : Scene
        A scene whose joints are all revolute.

    Raises
    ------
    SceneError
        When a joint is prismatic (named with its index), or a link has no
        second joint at another point (it has no frame x-axis).
    """

    def __init__(self, scene: Scene):
        require_hinged(scene, "the mass/acceleration-parameter method (Song and Wang 1992)")
        self.scene = scene
        self.frames = link_frames(scene)
        bad = [
            f"links '{f.link}': all its joints sit at one point, so it has no frame x-axis"
            for f in self.frames.values()
            if f.v is None
        ]
        bad += [
            f"links[{i}].inertia: {L.inertia} with zero mass; the module writes the inertia "
            "as m k^2, so a massless link cannot carry one"
            for i, L in enumerate(scene.links)
            if L.mass == 0 and L.inertia > 0
        ]
        if bad:
            raise SceneError(bad)
        self.L = scene.characteristic_length() or 1.0
        self._make_pins()
        self.links = scene.link_names
        self._symbols: dict[str, sp.Symbol] = {}
        self.meanings: dict[str, str] = {}

    # -- pins ----------------------------------------------------------------
    def _make_pins(self) -> None:
        scene = self.scene
        parent = {j.name: j.name for j in scene.joints}

        def find(x):
            while parent[x] != x:
                parent[x] = parent[parent[x]]
                x = parent[x]
            return x

        joints = list(scene.joints)
        for i, a in enumerate(joints):
            for b in joints[i + 1 :]:
                if set(a.links) & set(b.links) and math.dist(a.at, b.at) <= COINCIDENT * self.L:
                    ra, rb = find(a.name), find(b.name)
                    if ra != rb:  # keep the earlier joint as the pin's name
                        first = min(ra, rb, key=lambda n: [j.name for j in joints].index(n))
                        parent[ra] = parent[rb] = first
        groups: dict[str, list] = {}
        for j in joints:
            groups.setdefault(find(j.name), []).append(j)
        self.pins: dict[str, Pin] = {}
        self.pin_of: dict[str, str] = {}
        for name, js in groups.items():
            links = []
            for j in js:
                for link in j.links:
                    if link not in links:
                        links.append(link)
            at = js[0].at
            ground = GROUND in links
            origin = ground and math.hypot(*at) <= COINCIDENT * self.L
            self.pins[name] = Pin(name, tuple(j.name for j in js), tuple(links), tuple(at), ground, origin)
            for j in js:
                self.pin_of[j.name] = name
        self.ground_pins = tuple(p for p in self.pins if self.pins[p].ground)
        self.origin_pins = tuple(p for p in self.pins if self.pins[p].at_origin)
        self.moving_pins = tuple(p for p in self.pins if not self.pins[p].ground)

    def link_pins(self, link: str) -> list:
        """The pins of ``link``: ``u``'s and ``v``'s first, then the others in scene order."""
        fr = self.frames[link]
        u, v = self.pin_of[fr.u], self.pin_of[fr.v]
        out = [u, v]
        for j in self.scene.joints:
            if link in j.links and self.pin_of[j.name] not in out:
                out.append(self.pin_of[j.name])
        return out

    def uv(self, link: str) -> tuple:
        fr = self.frames[link]
        return self.pin_of[fr.u], self.pin_of[fr.v]

    # -- symbols -------------------------------------------------------------
    def sym(self, name: str, meaning: str, **assumptions) -> sp.Symbol:
        s = self._symbols.get(name)
        if s is None:
            s = self._symbols[name] = sp.Symbol(name, **assumptions)
            self.meanings[name] = meaning
        return s

    def link_symbols(self, link: str) -> tuple:
        """``(m, a, p, q, k)`` of ``link``."""
        t = tag(link)
        u, v = self.uv(link)
        return (
            self.sym(f"m_{t}", f"mass of link {link}", positive=True),
            self.sym(f"a_{t}", f"length of link {link}, from joint {u} to joint {v}", positive=True),
            self.sym(f"xG_{t}", f"centre of mass of link {link}: coordinate along {u}->{v}", real=True),
            self.sym(f"yG_{t}", f"centre of mass of link {link}: coordinate normal to {u}->{v}", real=True),
            self.sym(f"k_{t}", f"radius of gyration of link {link} about its centre of mass", nonnegative=True),
        )

    def local_point(self, link: str, pin: str) -> sp.Expr:
        """Position of ``pin`` in ``link``'s frame, as a complex number."""
        u, v = self.uv(link)
        if pin == u:
            return sp.Integer(0)
        a = self.link_symbols(link)[1]
        if pin == v:
            return a
        t, n = tag(link), tag(pin)
        xi = self.sym(f"xi_{t}_{n}", f"pin {pin} on link {link}: coordinate along {u}->{v}", real=True)
        eta = self.sym(f"eta_{t}_{n}", f"pin {pin} on link {link}: coordinate normal to {u}->{v}", real=True)
        return xi + sp.I * eta

    def pin_symbols(self, pin: str) -> tuple:
        """``(x, y, x'', y'')`` of ``pin``: zeros where the pin is fixed / at the origin."""
        P = self.pins[pin]
        n = tag(pin)
        if P.at_origin:
            x = y = sp.Integer(0)
        else:
            x = self.sym(f"x_{n}", f"x of pin {pin}", real=True)
            y = self.sym(f"y_{n}", f"y of pin {pin}", real=True)
        if P.ground:
            ax = ay = sp.Integer(0)
        else:
            ax = self.sym(f"xdd_{n}", f"x acceleration of pin {pin}", real=True)
            ay = self.sym(f"ydd_{n}", f"y acceleration of pin {pin}", real=True)
        return x, y, ax, ay

    def phidd(self, link: str) -> sp.Symbol:
        return self.sym(f"phidd_{tag(link)}", f"angular acceleration of link {link}", real=True)

    # -- values --------------------------------------------------------------
    def substitution(self) -> dict:
        """``{symbol: value}`` for every registered symbol the scene gives a value."""
        values = self.values()
        return {s: values[n] for n, s in self._symbols.items() if n in values}

    def values(self) -> dict:
        """Value of every link and local-point parameter, read off the scene."""
        out = {}
        for link in self.links:
            L = self.scene.link(link)
            fr = self.frames[link]
            u, v = self.uv(link)
            ux, uy = self.pins[u].at
            c, s = math.cos(fr.theta0), math.sin(fr.theta0)

            def local(pt):
                dx, dy = pt[0] - ux, pt[1] - uy
                return c * dx + s * dy, -s * dx + c * dy

            t = tag(link)
            out[f"m_{t}"] = L.mass
            out[f"a_{t}"] = math.dist(self.pins[u].at, self.pins[v].at)
            p, q = local(L.com) if L.com is not None else (0.0, 0.0)
            out[f"xG_{t}"], out[f"yG_{t}"] = p, q
            out[f"k_{t}"] = math.sqrt(L.inertia / L.mass) if L.mass > 0 else 0.0
            for pin in self.link_pins(link)[2:]:
                xi, eta = local(self.pins[pin].at)
                out[f"xi_{t}_{tag(pin)}"], out[f"eta_{t}_{tag(pin)}"] = xi, eta
        for pin in self.ground_pins:
            out[f"x_{tag(pin)}"], out[f"y_{tag(pin)}"] = self.pins[pin].at
        return out
