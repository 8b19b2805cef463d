"""Result containers of a numeric analysis: arrays over the steps of a sweep.

Every array's first axis is the step index (length ``N``).  Values of a step
whose ``status`` is not ``"ok"`` are NaN in these arrays and are *left out*
of :meth:`Analysis.to_dict` (the contract's JSON), so no NaN is ever passed
off as a result.  A ``"singular"`` step keeps its positions (the velocity
problem has no unique solution there, the position problem does).

The JSON is strict: any other value that is not finite (a NaN or an infinity
that a solver let through) is left out as well, and a ``warnings`` entry says
which; :meth:`Analysis.to_json` writes with ``allow_nan=False``.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field

import numpy as np

OK = "ok"
UNASSEMBLABLE = "unassemblable"
SINGULAR = "singular"


@dataclass
class JointKinematics:
    """Motion of a joint's point fixed on its ``links[1]``; each array (N, 2)."""

    position: np.ndarray
    velocity: np.ndarray | None = None
    acceleration: np.ndarray | None = None


@dataclass
class LinkKinematics:
    """Motion of one moving link.

    ``rotation`` is the rotation from the assembly configuration (rad,
    continuous along the sweep); ``origin`` is the global position of the point
    of the link that sits at the global origin in the assembly configuration.
    ``com*`` are ``None`` for a link without a centre of mass.
    """

    rotation: np.ndarray
    origin: np.ndarray
    omega: np.ndarray | None = None
    alpha: np.ndarray | None = None
    origin_velocity: np.ndarray | None = None
    origin_acceleration: np.ndarray | None = None
    com: np.ndarray | None = None
    com_velocity: np.ndarray | None = None
    com_acceleration: np.ndarray | None = None

    def point(self, local) -> np.ndarray:
        """Global position (N, 2) of the link point whose assembly position is ``local``."""
        c, s = np.cos(self.rotation), np.sin(self.rotation)
        x, y = local
        return self.origin + np.stack([c * x - s * y, s * x + c * y], axis=-1)

    def point_velocity(self, local) -> np.ndarray:
        """Velocity (N, 2) of the link point whose assembly position is ``local``."""
        rx, ry = _rotated(self.rotation, local)
        w = self.omega
        return self.origin_velocity + np.stack([-w * ry, w * rx], axis=-1)

    def point_acceleration(self, local) -> np.ndarray:
        """Acceleration (N, 2) of the link point whose assembly position is ``local``."""
        rx, ry = _rotated(self.rotation, local)
        w, a = self.omega, self.alpha
        return self.origin_acceleration + np.stack(
            [-a * ry - w * w * rx, a * rx - w * w * ry], axis=-1
        )


def _rotated(theta, local):
    c, s = np.cos(theta), np.sin(theta)
    x, y = local
    return c * x - s * y, s * x + c * y


@dataclass
class GroupForces:
    """How the forces of one Assur group were solved.

    Attributes
    ----------
    links : tuple of str
        The group's links.
    method : str
        ``"input"``, ``"dyad RRR"`` ... for closed forms; ``"disconnection"``
        for a class-III (or driven, or larger) group solved by Dang and Zhang's
        superposition; ``"dense"`` when a group's own equilibrium equations
        were solved as one linear system (no disconnection applies);
        ``"global"`` under the global method.
    choices : tuple of str
        For ``"disconnection"``: every disconnection choice, described.
    used : ndarray of int, shape (N,) or None
        For ``"disconnection"``: index into ``choices`` used at each step
        (-1 at steps without a solution).
    amplification : ndarray, shape (N,) or None
        For ``"disconnection"``: the cancellation factor of the
        superposition at each step (``max(|R'| + |R''X|) / max|R|``); the
        number of significant digits lost is about its base-10 logarithm.
    """

    links: tuple[str, ...]
    method: str
    choices: tuple[str, ...] = ()
    used: np.ndarray | None = None
    amplification: np.ndarray | None = None


@dataclass
class Forces:
    """Joint reactions, driver efforts and frame loads over a sweep.

    Sign conventions are those of the scene format: a joint's ``reaction`` is
    the force that its ``links[0]`` exerts on its ``links[1]`` (for a ``P``
    joint: the force normal to the slide, applied at the joint's reference
    point, with ``reaction_moments`` the couple about that point); a
    driver's effort is applied by ``links[0]`` on ``links[1]`` and is not part
    of the reaction; the frame force and moment (about the global origin) are
    what the moving links exert on the ground.  Arrays are NaN at steps whose
    status is not ``ok``.

    Attributes
    ----------
    method : str
        ``"dyad"`` (closed-form group routines, Dang and Zhang's superposition for
        complex groups) or ``"global"`` (one sparse linear system).
    reactions : dict of str to ndarray (N, 2)
    reaction_moments : dict of str to ndarray (N,)
        Zero for ``R`` joints.
    driving : dict of str to ndarray (N,)
        Torque (``R`` driver) or axial force (``P`` driver).
    frame_force : ndarray (N, 2)
    frame_moment : ndarray (N,)
    groups : list of GroupForces
        How each group was solved, in solving order.
    """

    method: str
    reactions: dict
    reaction_moments: dict
    driving: dict
    frame_force: np.ndarray
    frame_moment: np.ndarray
    groups: list = field(default_factory=list)


@dataclass
class Analysis:
    """Everything one run of a solving plan computed.

    Attributes
    ----------
    scene : str
        Name of the scene.
    stages : tuple of str
        The stages that actually ran, in order (``position``, ``velocity``,
        ``acceleration``, ``forces``).
    status : ndarray of str, shape (N,)
        ``"ok"``, ``"unassemblable"`` or ``"singular"``.
    messages : list of (str or None)
        Why a step is not ``ok``; ``None`` for ``ok`` steps.
    drivers : dict
        ``{joint: {"q": (N,), "qd": (N,), "qdd": (N,)}}``.  For the scene's
        own sweep these arrays are read-only and shared by every run of a
        plan.
    joints, links : dict
        :class:`JointKinematics` / :class:`LinkKinematics` by name.  Their
        arrays are views of one block per run: a run's arrays share no
        memory with another run's.
    condition : ndarray, shape (N,)
        Exact dimensionless condition number of the full constraint
        Jacobian (lengths divided by the mechanism's size) at the steps
        where it was computed: where a group's cheap indicator fell below
        ``linkage_sym.numeric.plan.SCREEN``, or at every step with
        ``Plan.run(exact_condition=True)``.  NaN at the other steps (well
        conditioned by their indicators) and at unassemblable steps.
    outputs : tuple of str
        The outputs the scene asked for.
    warnings : list of str
        What no step's status says (see ``linkage_sym.numeric.plan.run_warnings``):
        ``ok`` steps whose computed condition number exceeds 1e6, and force
        superpositions that cancel with every disconnection.  Written to the
        JSON as ``warnings`` and printed by the command line.
    forces : Forces or None
        Reactions, efforts and frame loads when the ``forces`` stage ran.
    p_joints : tuple of str
        Names of the prismatic joints (their reactions carry a moment).
    points : dict
        :class:`JointKinematics` of the scene's traced points (its
        ``points``, an extension of the format), by name.
    instant_centres : InstantCentres or None
        Every pair's instant centre at every step, when the scene lists the
        ``instant_centres`` output (an extension of the format; see
        :mod:`linkage_sym.centres`); written to each ``ok`` step's record.
    """

    scene: str
    stages: tuple[str, ...]
    status: np.ndarray
    messages: list
    drivers: dict
    joints: dict
    links: dict
    condition: np.ndarray
    outputs: tuple[str, ...]
    warnings: list = field(default_factory=list)
    forces: Forces | None = None
    p_joints: tuple[str, ...] = ()
    points: dict = field(default_factory=dict)
    instant_centres: object = None

    @property
    def ok(self) -> np.ndarray:
        """Boolean mask of the steps whose status is ``ok``."""
        return self.status == OK

    @property
    def n_steps(self) -> int:
        return len(self.status)

    def to_dict(self) -> dict:
        """The result in the JSON layout of the scene-format contract."""
        steps = []
        want_kin = "kinematics" in self.outputs
        has_vel = "velocity" in self.stages
        has_acc = "acceleration" in self.stages
        forces = self.forces
        p_joints = set(self.p_joints)

        def motion(k: JointKinematics, i: int, rates: bool) -> dict:
            """A joint's or traced point's record at step ``i``."""
            rec = {"position": _vec(k.position[i])}
            if rates and has_vel:
                rec["velocity"] = _vec(k.velocity[i])
            if rates and has_acc:
                rec["acceleration"] = _vec(k.acceleration[i])
            return rec

        dropped: list[str] = []  # fields left out because they are not finite
        centres = self.instant_centres if "instant_centres" in self.outputs else None
        for i in range(self.n_steps):
            st = str(self.status[i])
            step: dict = {"status": st}
            if self.messages[i] is not None:
                step["message"] = self.messages[i]
            step["drivers"] = {
                name: {k: float(v[i]) for k, v in d.items()} for name, d in self.drivers.items()
            }
            positions = st in (OK, SINGULAR)
            rates = st == OK
            if want_kin and positions:
                joints = {name: motion(jk, i, rates) for name, jk in self.joints.items()}
                links = {}
                for name, lk in self.links.items():
                    rec = {"rotation": float(lk.rotation[i])}
                    if rates and has_vel:
                        rec["omega"] = float(lk.omega[i])
                    if rates and has_acc:
                        rec["alpha"] = float(lk.alpha[i])
                    if lk.com is not None:
                        rec["com"] = _vec(lk.com[i])
                        if rates and has_vel:
                            rec["com_velocity"] = _vec(lk.com_velocity[i])
                        if rates and has_acc:
                            rec["com_acceleration"] = _vec(lk.com_acceleration[i])
                    links[name] = rec
                step["joints"] = joints
                step["links"] = links
                if self.points:
                    step["points"] = {name: motion(pk, i, rates) for name, pk in self.points.items()}
            if forces is not None and rates:
                if "reactions" in self.outputs:
                    joints = step.setdefault("joints", {})
                    for name, r in forces.reactions.items():
                        rec = joints.setdefault(name, {})
                        rec["reaction"] = _vec(r[i])
                        if name in p_joints:
                            rec["reaction_moment"] = float(forces.reaction_moments[name][i])
                if "driving" in self.outputs:
                    step["driving"] = {k: float(v[i]) for k, v in forces.driving.items()}
                if "frame" in self.outputs:
                    step["frame"] = {
                        "force": _vec(forces.frame_force[i]),
                        "moment": float(forces.frame_moment[i]),
                    }
            if rates and centres is not None:  # extension: every pair's instant centre
                step["instant_centres"] = centres.records(i)
            steps.append(_finite_only(step, f"steps[{i}]", dropped))
        out = {"scene": self.scene, "stages": list(self.stages), "steps": steps}
        if forces is not None:
            out["force_method"] = forces.method
            out["groups"] = [
                {
                    "links": list(g.links),
                    "method": g.method,
                    **(
                        {
                            "choices": list(g.choices),
                            "steps_per_choice": {
                                g.choices[k]: int((g.used == k).sum())
                                for k in range(len(g.choices))
                                if (g.used == k).any()
                            },
                        }
                        if g.used is not None
                        else {}
                    ),
                }
                for g in forces.groups
            ]
        warnings = list(self.warnings)
        if dropped:
            shown = ", ".join(dropped[:3]) + (f" and {len(dropped) - 3} more" if len(dropped) > 3 else "")
            warnings.append(
                f"{len(dropped)} computed value{'s are' if len(dropped) != 1 else ' is'} not finite "
                f"(NaN or infinite) and left out of the result: {shown}"
            )
        if warnings:
            out["warnings"] = warnings
        return out

    def to_json(self, **kwargs) -> str:
        """:meth:`to_dict` as strict JSON text (never ``NaN`` nor ``Infinity``).

        ``kwargs`` go to :func:`json.dumps` (e.g. ``indent``); ``allow_nan`` is
        always ``False``, so a non-finite number is an error, never written.
        """
        return json.dumps(self.to_dict(), **{**kwargs, "allow_nan": False})


def _vec(v) -> list:
    return [float(v[0]), float(v[1])]


_LEFT_OUT = object()
"""What :func:`_finite_only` returns for a value that is left out."""


def _finite_only(value, path: str, dropped: list):
    """``value`` (a step record) without its non-finite numbers; their paths go to ``dropped``.

    A vector ``[x, y]`` with a non-finite component is left out whole; a record
    keeps its other fields.
    """
    if isinstance(value, float):
        if math.isfinite(value):
            return value
        dropped.append(path)
        return _LEFT_OUT
    if isinstance(value, dict):
        out = {}
        for key, item in value.items():
            kept = _finite_only(item, f"{path}.{key}", dropped)
            if kept is not _LEFT_OUT:
                out[key] = kept
        return out
    if isinstance(value, list):
        if all(isinstance(x, float) and math.isfinite(x) for x in value):
            return value
        if all(isinstance(x, (float, int)) for x in value):  # a vector: whole or not at all
            dropped.append(path)
            return _LEFT_OUT
        return [x for x in (_finite_only(x, f"{path}[{k}]", dropped) for k, x in enumerate(value))
                if x is not _LEFT_OUT]
    return value
