"""Plain data classes for a scene (see ``docs/scene-format.md``).

Nothing here computes: these classes are what :func:`linkage_sym.scene.load_scene`
produces after validation, and what every solver reads.  Angles are stored in
radians (the file's ``*_deg`` keys are converted on loading), everything else in
SI units, points as ``(x, y)`` tuples in the global frame of the assembly
configuration.

Link frames
-----------
Every link's local frame coincides with the global frame in the assembly
configuration.  A point fixed on a link therefore has, as local coordinates,
the global coordinates it has in the assembly configuration, and a link's
rotation angle is its rotation *from* the assembly configuration.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

GROUND = "ground"
"""Name of the fixed link; never listed in ``Scene.links``."""

OUTPUTS = ("kinematics", "reactions", "driving", "frame")
"""The contract's outputs, in the order results list them; a scene's default."""

EXTENSION_OUTPUTS = ("instant_centres",)
"""Outputs linkage_sym adds to the contract's (an extension of the format): a scene
may list them, none is a default.  ``instant_centres``: every pair's instant centre
at each step with velocities (see :mod:`linkage_sym.centres`)."""

STAGES = ("position", "velocity", "acceleration", "forces")
"""Every computation stage, in the order they run."""

Point = tuple[float, float]


@dataclass(frozen=True)
class Link:
    """A rigid moving link.

    ``com`` is ``None`` only for a massless link; ``inertia`` is the moment of
    inertia about the centre of mass.
    """

    name: str
    mass: float = 0.0
    com: Point | None = None
    inertia: float = 0.0


@dataclass(frozen=True)
class CamSpec:
    """A cam contact's profile and follower, as read (see ``docs/scene-format.md``).

    ``profile`` is ``"circle"`` (``data = (centre, R)``), ``"polar"``
    (``data = (centre, phi, r)``, ``phi`` in radians) or ``"points"``
    (``data = (points,)``), in the cam link's frame; ``pitch`` says the curve
    is the roller centre's path relative to the cam (the pitch curve), not
    the working profile.  ``follower`` is ``"roller"``, ``"knife"`` or
    ``"flat"``; ``radius`` the roller's (0 otherwise); ``face`` the flat
    face's direction (radians, on the follower) or ``None``.
    """

    profile: str
    data: tuple
    follower: str
    radius: float = 0.0
    face: float | None = None
    pitch: bool = False


@dataclass(frozen=True)
class JointFriction:
    """Coulomb friction of an ``R`` or ``P`` joint (``joints[i].friction``, contract part two).

    ``coefficient`` is the friction coefficient f (>= 0); ``radius`` the pin's
    radius (m) of an ``R`` joint, whose friction circle has radius
    ``f * radius``, and ``None`` for a ``P`` joint.
    """

    coefficient: float
    radius: float | None = None

    @property
    def arm(self) -> float:
        """The friction circle's radius (``R``, m) or the coefficient itself (``P``)."""
        return self.coefficient * (1.0 if self.radius is None else self.radius)


@dataclass(frozen=True)
class Joint:
    """A lower pair between ``links[0]`` and ``links[1]``, or a gear mesh.

    For a ``P`` joint ``axis`` is the slide direction in radians, fixed on
    ``links[0]``; ``at`` is the reference point, fixed on ``links[1]``.
    ``axis`` is ``None`` for an ``R`` joint.

    A ``G`` joint (gear mesh, an extension of the format: a higher pair) joins
    two gears ``links[0]`` and ``links[1]`` turning on pivots (``R`` joints)
    of the ``carrier`` link, with pitch radii ``radii``; they roll without
    slip, ``ra (theta_a - theta_c) = -+ rb (theta_b - theta_c)`` (minus for an
    external mesh, plus for an ``internal`` one, whose larger gear is the
    ring).  ``at`` is the pitch point in the assembly configuration, fixed on
    the carrier; ``pressure_angle`` (radians) tilts the line of action from
    the common tangent.  ``pivots`` names the ``R`` joint each gear turns on:
    one joining it to the carrier, or one joining it to a link to which the
    carrier is pinned at the same point (a sun coaxial with its arm on the
    ground).  These fields are ``None``/``False`` for R and P joints.

    A ``cam`` joint (cam contact, an extension of the format: a higher pair)
    keeps a follower element on link ``links[1]`` in contact with the profile
    of the cam ``links[0]`` (``cam``, a :class:`CamSpec`); ``at`` is the
    follower's element point in the assembly configuration (roller centre,
    knife point, or a point of a flat face), fixed on the follower.

    ``friction`` (a :class:`JointFriction`, ``R`` and ``P`` joints only) is
    the joint's Coulomb friction, which acts when the scene's
    ``effects.friction`` is true.
    """

    name: str
    type: str  # "R", "P", "G" or "cam"
    links: tuple[str, str]
    at: Point
    axis: float | None = None
    carrier: str | None = None
    radii: tuple[float, float] | None = None
    internal: bool = False
    pressure_angle: float | None = None
    pivots: tuple[str, str] | None = None
    cam: CamSpec | None = None
    friction: JointFriction | None = None

    @property
    def moves_with(self) -> str:
        """The link ``at`` is fixed on: ``links[1]``, or a mesh's carrier."""
        return self.carrier if self.type == "G" else self.links[1]


@dataclass(frozen=True)
class Motor:
    """A driver's motor: its effort as a function of the driver's speed.

    ``speeds`` (rad/s for an ``R`` driver, m/s for a ``P`` one) strictly
    increasing and ``efforts`` (N m or N) of the same length: the effort is
    interpolated linearly between two rows and the end rows' effort is held
    beyond them.  A constant effort has one row (its speed 0).  ``kind`` is the
    scene's key, ``"torque"`` (an ``R`` driver) or ``"force"`` (a ``P`` one).
    """

    kind: str
    speeds: tuple[float, ...]
    efforts: tuple[float, ...]


@dataclass(frozen=True)
class Simulation:
    """The ``simulate`` section: integrate the motion from ``start`` (radians or
    metres, the driver's coordinate) at ``start_speed`` over ``duration`` seconds,
    reporting ``samples`` equally spaced times.  With several drivers (several motors)
    ``start`` and ``start_speed`` are tuples with one entry per driver, in the order of
    the scene's drivers."""

    duration: float
    start: float | tuple[float, ...]
    start_speed: float | tuple[float, ...]
    samples: int


@dataclass(frozen=True)
class Driver:
    """A prescribed relative coordinate of one joint.

    ``start`` and ``stop`` are in radians for an ``R`` joint (the angle of the
    vector from the joint to ``toward``, measured from the x-axis of the joint's
    ``links[0]``) and in metres for a ``P`` joint (displacement along the axis,
    zero in the assembly configuration).  ``speed`` and ``acceleration`` hold
    at every step of the sweep.

    ``start_deg`` and ``stop_deg`` keep an ``R`` driver's numbers as the scene
    gave them (degrees; ``None`` for a driver built in radians): the radians are
    their rounding, and an arbitrary-precision run converts the degrees itself
    (:mod:`linkage_sym.codegen.precision`).  They count only while
    ``math.radians(start_deg) == start`` (likewise ``stop``); they take no part in
    comparisons.

    ``motor`` (a :class:`Motor`, or ``None``) drives the joint when the
    machine's motion is simulated (``simulate``); ``analyze`` does not read it.
    """

    joint: str
    kind: str  # "R" or "P": the type of the driven joint
    start: float
    stop: float
    steps: int
    speed: float
    acceleration: float = 0.0
    toward: str | None = None
    start_deg: float | None = field(default=None, repr=False, compare=False)
    stop_deg: float | None = field(default=None, repr=False, compare=False)
    motor: Motor | None = field(default=None, repr=False)


@dataclass(frozen=True)
class LoadTable:
    """A load's factor against one driver's value (an extension of the format).

    ``q`` in radians for an ``R`` driver, metres for a ``P`` driver, strictly
    increasing; the factor between two values is interpolated linearly.  For
    an ``R`` driver the table repeats with the load's ``period``; a ``P``
    driver's table covers its sweep.
    """

    q: tuple[float, ...]
    scale: tuple[float, ...]


@dataclass(frozen=True)
class Load:
    """An external load on one link: a force at a point and/or a torque.

    A load acts with the given force and torque at every step, unless it
    varies over the cycle (an extension of the format): ``table`` scales it
    by a factor of one driver's value, ``active`` limits it to a range
    ``(from, to)`` of that driver's value (radians or metres), and ``driver``
    names that driver's joint.  For an ``R`` driver both repeat with
    ``period`` (radians: one turn unless given, two for a four-stroke engine's
    cycle); for a ``P`` driver ``period`` is ``None``.
    """

    link: str
    force: Point | None = None
    at: Point | None = None
    torque: float = 0.0
    table: LoadTable | None = None
    active: tuple[float, float] | None = None
    driver: str | None = None
    period: float | None = None


@dataclass(frozen=True)
class TracedPoint:
    """A named point fixed on a moving link, whose motion the result reports.

    An extension of the scene format (``points``): a coupler point, a tool
    tip, any point of interest.  ``at`` is its position in the assembly
    configuration (so its local coordinates on ``link``).
    """

    name: str
    link: str
    at: Point


@dataclass(frozen=True)
class Spring:
    """A spring and damper (the contract's ``springs``; see ``docs/scene-format.md``).

    Between two links (``links``, ``at`` given): ``at[0]`` fixed on
    ``links[0]``, ``at[1]`` on ``links[1]`` (assembly configuration); the
    tension ``stiffness (L - free_length) + damping dL/dt`` pulls the two
    points together when positive.  ``free_length`` is the assembly distance
    when the scene does not give it (the reader fills it in).

    At an ``R`` joint (``joint`` given, ``links``, ``at`` and ``free_length``
    ``None``): the torque on the joint's ``links[1]`` is
    ``-stiffness (theta - free_angle) - damping omega``, ``theta`` the
    rotation of ``links[1]`` relative to ``links[0]`` from the assembly
    configuration.  ``free_angle_deg`` keeps the scene's degrees;
    :attr:`free_angle` is its radians.
    """

    name: str
    stiffness: float
    damping: float = 0.0
    links: tuple[str, str] | None = None
    at: tuple[Point, Point] | None = None
    free_length: float | None = None
    joint: str | None = None
    free_angle_deg: float = 0.0

    @property
    def free_angle(self) -> float:
        """``free_angle_deg`` in radians."""
        return math.radians(self.free_angle_deg)


@dataclass(frozen=True)
class Effects:
    """Which physical effects a scene asks to simulate.

    ``springs``: the scene's springs act (default false here; the scene reader
    makes it true when a scene gives ``springs`` without saying otherwise).
    ``friction``: the joints' Coulomb friction (default false).
    """

    inertia: bool = False
    gravity: Point | None = None
    loads: bool = True
    springs: bool = False
    friction: bool = False


@dataclass(frozen=True)
class Scene:
    """A validated scene: the mechanism, its drivers, loads, effects and outputs."""

    name: str
    links: tuple[Link, ...]
    joints: tuple[Joint, ...]
    drivers: tuple[Driver, ...]
    loads: tuple[Load, ...] = ()
    effects: Effects = field(default_factory=Effects)
    outputs: tuple[str, ...] = OUTPUTS
    points: tuple[TracedPoint, ...] = ()
    springs: tuple[Spring, ...] = ()
    simulate: Simulation | None = None

    @property
    def active_springs(self) -> tuple[Spring, ...]:
        """The springs that act: the scene's, when ``effects.springs`` says so."""
        return self.springs if self.effects.springs else ()

    @property
    def link_names(self) -> tuple[str, ...]:
        """Names of the moving links, in scene order."""
        return tuple(link.name for link in self.links)

    def link(self, name: str) -> Link:
        """The moving link called ``name``."""
        for link in self.links:
            if link.name == name:
                return link
        raise KeyError(name)

    def joint(self, name: str) -> Joint:
        """The joint called ``name``."""
        for joint in self.joints:
            if joint.name == name:
                return joint
        raise KeyError(name)

    @property
    def meshes(self) -> tuple[Joint, ...]:
        """The gear meshes (``G`` joints), in scene order."""
        return tuple(j for j in self.joints if j.type == "G")

    @property
    def cams(self) -> tuple[Joint, ...]:
        """The cam contacts (``cam`` joints), in scene order."""
        return tuple(j for j in self.joints if j.type == "cam")

    def gear_pivots(self, mesh: Joint) -> tuple[Joint, Joint]:
        """The ``R`` joints on which a mesh's two gears turn (see :class:`Joint`)."""
        a, b = mesh.pivots  # type: ignore[misc]
        return self.joint(a), self.joint(b)

    @property
    def steps(self) -> int:
        """Number of steps of the sweep (shared by every driver)."""
        return self.drivers[0].steps

    def characteristic_length(self) -> float:
        """Largest distance between two joints of the assembly configuration.

        Used to make lengths dimensionless (singularity test of the spec).
        """
        pts = [j.at for j in self.joints]
        best = 0.0
        for i, (xi, yi) in enumerate(pts):
            for xj, yj in pts[i + 1 :]:
                best = max(best, ((xi - xj) ** 2 + (yi - yj) ** 2) ** 0.5)
        return best
