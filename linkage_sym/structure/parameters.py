"""Link frames and the named parameters of a scene (no SymPy here).

Every quantity that sizes a mechanism has a name made from the scene's names,
a meaning, and a *recipe* that reads its value off the scene's assembly
configuration.  The symbolic layer turns names into SymPy symbols; a
compiled model loaded from the cache reads the values of another scene of
the same topology through the same recipes, without SymPy.

==================  ===================================================
``l_<u><P>``        distance from a link's frame origin ``u`` to its point ``P``
``beta_<u><P>``     angle of ``u -> P`` from the link's x-axis ``u -> v``
``x_<J>, y_<J>``    coordinates of a point ``J`` of the ground
``gamma_<J>``       slide direction of ``P`` joint ``J`` from the x-axis of ``links[0]``
``theta0_<link>``   angle of the link's x-axis ``u -> v`` in the assembly configuration
``delta_<J><T>``    angle of a driver's ``J -> toward`` from the x-axis of its link
``m_<link>``        mass; ``xG_<link>, yG_<link>``: centre of mass in the link frame
``I_<link>``        moment of inertia about the centre of mass
``g_x, g_y``        gravity
``F_<i>x, F_<i>y``  force of load ``i`` (global components) at ``xi_<i>, eta_<i>``
``T_<i>``           torque of load ``i``
``r_<J><g>``        pitch radius of gear ``g`` of mesh ``J``
``phi_<J>``         pressure angle of mesh ``J``
``epsilon_<J>``     angle of the line of centres of mesh ``J`` (gear ``a`` toward gear
                    ``b``) from the x-axis of its carrier
``mu_<J>``          friction coefficient of joint ``J``; ``rpin_<J>``: an ``R`` joint's
                    pin radius (registered by the compiled runtime where friction acts)
==================  ===================================================

Link frames (as Song and Wang 1992 define them, in the notation of the
kinematics textbook chapter): a moving link's frame has
its origin at the link's first joint ``u`` in scene order and its x-axis
toward its second joint ``v`` (the first one at a different point); a link
whose joints all sit at one point keeps the global x direction of the
assembly configuration.  The ground's frame is the global frame.  Only lower
pairs (``R``, ``P``) place a frame: a gear mesh's pitch point or a cam's
contact is not a point of the gears or the cam (it stays on the line of
centres while they turn).

Examples
--------
>>> from linkage_sym.examples import load_example
>>> table = ParameterTable(load_example("crank_rocker"))
>>> table.point("coupler", "C")  # C is the frame's v point: its angle is 0
('l_BC', None)
>>> round(table.value("l_BC"), 6)
0.063032
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from linkage_sym.model import GROUND, Scene
from linkage_sym.structure.recipes import Recipe

COINCIDENT = 1e-12
"""Relative distance (to the mechanism size) below which two points coincide."""
LOWER_PAIRS = ("R", "P")
"""The joint types whose point is a point of both links (they place link frames)."""


@dataclass(frozen=True)
class LinkFrame:
    """Frame of one moving link: origin joint ``u``, x-axis toward ``v``."""

    link: str
    u: str
    v: str | None
    origin: tuple[float, float]
    theta0: float


@dataclass(frozen=True)
class Parameter:
    """A named quantity: its recipe (how to read it off a scene), value and meaning."""

    name: str
    recipe: tuple
    value: float
    meaning: str
    kind: str  # length, angle, coordinate, mass, inertia, gravity, load


def ident(n: str) -> str:
    """A scene name made safe for a symbol name."""
    out = "".join(ch if ch.isalnum() or ch == "_" else "_" for ch in n)
    return out if out and not out[0].isdigit() else "_" + out


def _pair(a: str, b: str) -> str:
    a, b = ident(a), ident(b)
    return a + b if len(a) == 1 and len(b) == 1 else f"{a}_{b}"


def link_frames(scene: Scene) -> dict[str, LinkFrame]:
    """Frame of every moving link (see the module docstring)."""
    L = scene.characteristic_length() or 1.0
    out = {}
    for link in scene.link_names:
        js = [j for j in scene.joints if link in j.links and j.type in LOWER_PAIRS]
        u = js[0]
        v = next((j for j in js[1:] if math.dist(j.at, u.at) > COINCIDENT * L), None)
        th = 0.0 if v is None else math.atan2(v.at[1] - u.at[1], v.at[0] - u.at[0])
        out[link] = LinkFrame(link, u.name, None if v is None else v.name, tuple(u.at), th)
    return out


def driver_q0(scene: Scene) -> dict[str, float]:
    """Each driver's value in the assembly configuration (an ``R`` driver's
    representative nearest its start, as the scene format says)."""
    out = {}
    for d in scene.drivers:
        if d.kind == "R":
            j, t = scene.joint(d.joint), scene.joint(d.toward)
            phi = math.atan2(t.at[1] - j.at[1], t.at[0] - j.at[0])
            out[d.joint] = phi + 2 * math.pi * round((d.start - phi) / (2 * math.pi))
        else:
            out[d.joint] = 0.0
    return out


class ParameterTable:
    """The parameters of one scene, registered on first use in a stable order."""

    def __init__(self, scene: Scene):
        self.scene = scene
        self.frames = link_frames(scene)
        self.L = scene.characteristic_length() or 1.0
        self.params: dict[str, Parameter] = {}
        self._by_recipe: dict[tuple, str] = {}

    # -- registration ----------------------------------------------------------
    def _register(self, name: str, recipe: tuple, meaning: str, kind: str) -> str:
        got = self._by_recipe.get(recipe)
        if got is not None:
            return got
        while name in self.params:  # the same name for another quantity
            name += "_"
        self.params[name] = Parameter(name, recipe, evaluate(self.scene, recipe), meaning, kind)
        self._by_recipe[recipe] = name
        return name

    def value(self, name: str) -> float:
        return self.params[name].value

    # -- geometry ----------------------------------------------------------------
    def coincides_with_origin(self, link: str, at) -> bool:
        fr = self.frames[link]
        return math.dist(at, fr.origin) <= COINCIDENT * self.L

    def point(self, link: str, point: str):
        """Names ``(l, beta)`` placing joint ``point`` on ``link``.

        ``None`` when the point is the frame origin ``u``; ``beta`` is ``None``
        for the frame's ``v`` point (its angle is 0 by definition).
        """
        at = self.scene.joint(point).at
        if self.coincides_with_origin(link, at):
            return None
        fr = self.frames[link]
        pair = _pair(fr.u, point)
        l = self._register(
            f"l_{pair}", ("l", link, point),
            f"distance from joint {fr.u} to {point} on link {link}", "length",
        )
        if point == fr.v:
            return l, None
        b = self._register(
            f"beta_{pair}", ("beta", link, point),
            f"angle of {fr.u}->{point} from the x-axis {fr.u}->{fr.v} of link {link}", "angle",
        )
        return l, b

    def ground_point(self, point: str):
        n = ident(point)
        return (
            self._register(f"x_{n}", ("x", point), f"x of point {point} of the ground", "coordinate"),
            self._register(f"y_{n}", ("y", point), f"y of point {point} of the ground", "coordinate"),
        )

    def theta0(self, link: str):
        """Name of the assembly angle of ``link``'s x-axis (``None`` for the ground)."""
        if link == GROUND:
            return None
        return self._register(
            f"theta0_{ident(link)}", ("theta0", link),
            f"angle of the x-axis of link {link} in the assembly configuration", "angle",
        )

    def gamma(self, joint: str):
        a = self.scene.joint(joint).links[0]
        return self._register(
            f"gamma_{ident(joint)}", ("gamma", joint),
            f"slide direction of joint {joint} from the x-axis of link {a}", "angle",
        )

    def delta(self, joint: str, toward: str):
        return self._register(
            f"delta_{_pair(joint, toward)}", ("delta", joint, toward),
            f"angle of {joint}->{toward} from the x-axis of the link carrying {toward}", "angle",
        )

    def mass(self, link: str):
        n = ident(link)
        return (
            self._register(f"m_{n}", ("m", link), f"mass of link {link}", "mass"),
            self._register(f"I_{n}", ("I", link), f"moment of inertia of link {link} about its centre of mass", "inertia"),
        )

    def com(self, link: str):
        n = ident(link)
        return (
            self._register(f"xG_{n}", ("p", link), f"centre of mass of link {link}: x in the link frame", "length"),
            self._register(f"yG_{n}", ("q", link), f"centre of mass of link {link}: y in the link frame", "length"),
        )

    def gravity(self):
        return (
            self._register("g_x", ("gx",), "gravity, x component", "gravity"),
            self._register("g_y", ("gy",), "gravity, y component", "gravity"),
        )

    def load(self, i: int):
        """Names of load ``i``'s force, its point (link frame) and torque, as present."""
        ld = self.scene.loads[i]
        k = i + 1
        out = {}
        if ld.force is not None:
            out["force"] = (
                self._register(f"F_{k}x", ("Fx", i), f"load {k} on {ld.link}: force x", "load"),
                self._register(f"F_{k}y", ("Fy", i), f"load {k} on {ld.link}: force y", "load"),
            )
            out["at"] = (
                self._register(f"xi_{k}", ("xi", i), f"load {k}: point x in the frame of {ld.link}", "length"),
                self._register(f"eta_{k}", ("eta", i), f"load {k}: point y in the frame of {ld.link}", "length"),
            )
        if ld.torque:
            out["torque"] = self._register(f"T_{k}", ("T", i), f"load {k} on {ld.link}: torque", "load")
        return out

    def spring(self, name: str):
        """Names of spring ``name``'s parameters: ``{"k", "c" (a damped spring's: ``None``
        without damping), and "L0", "ends" (each end's point in its link's frame) between
        two links, or "theta_f" at a joint}``."""
        k = next(k for k in self.scene.springs if k.name == name)
        n = ident(name)
        out = {
            "k": self._register(f"k_{n}", ("k", name), f"stiffness of spring {name}", "stiffness"),
            "c": None if k.damping == 0.0 else self._register(
                f"c_{n}", ("c", name), f"damping of spring {name}", "damping"),
        }
        if k.joint is not None:
            out["theta_f"] = self._register(f"theta_f_{n}", ("theta_f", name),
                                            f"free angle of spring {name}", "angle")
            return out
        out["L0"] = self._register(f"L0_{n}", ("L0", name), f"free length of spring {name}", "length")
        out["ends"] = tuple(
            (self._register(f"xi_{n}_{i}", ("xi_s", name, i),
                            f"spring {name}: end {i} x in the frame of {link}", kind),
             self._register(f"eta_{n}_{i}", ("eta_s", name, i),
                            f"spring {name}: end {i} y in the frame of {link}", kind))
            for i, link in enumerate(k.links)
            for kind in ("coordinate" if link == GROUND else "length",))
        return out

    def friction(self, joint: str):
        """Names of joint ``joint``'s friction (``joints[i].friction``): ``(mu, rpin)``, its
        coefficient ``mu_<J>`` and an ``R`` joint's pin radius ``rpin_<J>`` (``None`` for a
        ``P`` joint)."""
        j = self.scene.joint(joint)
        n = ident(joint)
        mu = self._register(f"mu_{n}", ("mu", joint), f"friction coefficient of joint {joint}",
                            "friction")
        if j.type != "R":
            return mu, None
        return mu, self._register(f"rpin_{n}", ("rpin", joint),
                                  f"pin radius of joint {joint} (its friction circle: mu r)",
                                  "length")

    def mesh(self, joint: str):
        """Names ``(r_a, r_b, phi, epsilon)`` of gear mesh ``joint`` (see the module docstring)."""
        j = self.scene.joint(joint)
        a, b = j.links
        return (
            self._register(f"r_{_pair(joint, a)}", ("radius", joint, 0),
                           f"pitch radius of gear {a} in mesh {joint}", "length"),
            self._register(f"r_{_pair(joint, b)}", ("radius", joint, 1),
                           f"pitch radius of gear {b} in mesh {joint}", "length"),
            self._register(f"phi_{ident(joint)}", ("phi", joint),
                           f"pressure angle of mesh {joint}", "angle"),
            self._register(f"epsilon_{ident(joint)}", ("epsilon", joint),
                           f"angle of the line of centres {a}->{b} of mesh {joint} from the "
                           f"x-axis of its carrier {j.carrier}", "angle"),
        )


def evaluate(scene: Scene, recipe: tuple, frames=None) -> float:
    """The value of the parameter described by ``recipe`` in ``scene`` (binary64; any
    number type: :meth:`linkage_sym.structure.recipes.Recipe.value`)."""
    frames = link_frames(scene) if frames is None else frames
    return Recipe.of(recipe).value(scene, frames)
