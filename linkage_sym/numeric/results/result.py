"""Result containers of a numeric analysis: arrays over the steps of a sweep.

Every array's first axis is the step index (length ``N``).  Values of a step
whose ``status`` is not ``"ok"`` are NaN in these arrays and are *left out*
of :meth:`Analysis.to_dict` (the contract's JSON), so no NaN is ever passed
off as a result.  A ``"singular"`` step keeps its positions (the velocity
problem has no unique solution there, the position problem does).

The JSON is strict: any other value that is not finite is left out as well,
and a ``warnings`` entry says which (:mod:`~linkage_sym.numeric.results.strict_json`).

Size: about 600 lines, of which the JSON layout of the scene format (one
record per step, every field named) is most: it is the contract, kept in one
place beside the classes it writes.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field

import numpy as np

from linkage_sym.numeric.results.efficiency import mean_efficiency_record, run_work
from linkage_sym.numeric.results.records import RecordBlock
from linkage_sym.numeric.results.strict_json import LEFT_OUT, LeftOut, finite_only

OK = "ok"
UNASSEMBLABLE = "unassemblable"
SINGULAR = "singular"
SELF_LOCKING = "self-locking"
"""Contract part two: a step at which no finite driving effort moves the mechanism against
its joints' friction (:mod:`linkage_sym.numeric.forces.friction`)."""


@dataclass
class JointKinematics:
    """Motion of a joint's point fixed on its ``links[1]``; each array (N, 2).

    For a cam contact (an extension of the format) ``position`` is the contact
    point, ``velocity`` and ``acceleration`` those of the follower's material
    point there, ``pressure_angle`` (N,) the pressure angle in radians and
    ``normal`` (N, 2) the unit contact normal from the cam towards the follower
    (not written to the JSON); both are ``None`` for every other joint.
    """

    position: np.ndarray
    velocity: np.ndarray | None = None
    acceleration: np.ndarray | None = None
    pressure_angle: np.ndarray | None = None
    normal: np.ndarray | None = None


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
    notes : list of str
        What the force solve could not settle (a gear mesh whose tooth load pulls
        with either flank), added to the run's warnings.
    springs : dict of str to dict of str to ndarray (N,)
        Each acting spring's ``{"length", "force"}`` (between two links: the
        tension) or ``{"angle", "torque"}`` (at a joint), by name (the
        contract's ``springs``; :mod:`linkage_sym.numeric.forces.springs`);
        empty without springs.
    """

    method: str
    reactions: dict
    reaction_moments: dict
    driving: dict
    frame_force: np.ndarray
    frame_moment: np.ndarray
    groups: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    """What the force solve could not settle, worded for the run's warnings."""
    springs: dict = field(default_factory=dict)
    friction: dict | None = None
    """With ``effects.friction``: joint -> (N,) friction (contract part two) of every joint
    with a ``friction`` field, what ``links[0]`` exerts on ``links[1]``: the couple about
    an ``R`` joint's pin (N·m), the force along a ``P`` joint's axis (N)."""
    friction_power: np.ndarray | None = None
    """(N,) the power the friction dissipates (W, >= 0)."""
    efficiency: np.ndarray | None = None
    """(N,) with one driver: its effort without friction over its effort with it, where
    both are non-zero and of one sign (NaN elsewhere)."""
    driving_ideal: dict | None = None
    """Driven joint -> (N,) its effort with the friction left out."""
    locked: np.ndarray | None = None
    """(N,) bool: the steps at which the friction locks the mechanism (status
    ``self-locking``)."""
    lock_messages: dict = field(default_factory=dict)
    """Step -> the message of a self-locking step."""


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
        ``linkage_sym.numeric.engine.run.SCREEN``, or at every step with
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
    transmission_angles : dict
        The transmission angle (rad, 0..pi) of every RRR dyad at every step,
        by its inner joint (an extension of the format, written with the
        kinematics; see :mod:`linkage_sym.numeric.results.transmission`), NaN where a
        step has no positions.
    accuracy : dict or None
        Estimated relative accuracy of each ``ok`` step (an extension of the
        format): ``{"position", "velocity", "acceleration", "forces"}`` (those
        of the stages that ran), arrays (N,), NaN at the other steps; bounds
        from the condition numbers (see :mod:`linkage_sym.numeric.results.accuracy`).
    extremes : dict or None
        The sweep's located extremes (``analyze --extremes``; an extension of
        the format, see :mod:`linkage_sym.numeric.extremes`), written after
        ``warnings`` as ``"extremes"``.
    instant_centres : InstantCentres or None
        Every pair's instant centre at every step, when the scene lists the
        ``instant_centres`` output (an extension of the format; see
        :mod:`linkage_sym.centres`); written to each ``ok`` step's record.
    passages : tuple of InfinityPassage
        Where a dyad of two slides carries its joint through infinity between two steps
        (:mod:`linkage_sym.numeric.results.passages`): the joint, the steps on either side
        and the links carried off, for the plots to break their lines there.  Each has its
        warning in ``warnings``; not written to the JSON (the warning is).
    jumps : tuple of AssemblyJump
        Where a group solved by Newton's method goes on in another configuration of its
        assembly mode between two steps (:mod:`linkage_sym.numeric.results.jumps`): the
        group, the steps on either side and the links that jump, for the plots to break
        their lines there.  Each has its warning in ``warnings``; not written to the JSON.
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
    transmission_angles: dict = field(default_factory=dict)
    accuracy: dict | None = None
    extremes: dict | None = None
    instant_centres: object = None
    passages: tuple = ()
    jumps: tuple = ()

    @property
    def ok(self) -> np.ndarray:
        """Boolean mask of the steps whose status is ``ok``."""
        return self.status == OK

    @property
    def n_steps(self) -> int:
        return len(self.status)

    # -- serialisation ---------------------------------------------------------
    # The contract's JSON is built from three parts so that a long sweep can be
    # written step by step, in chunks (``linkage_sym.output``): the head
    # (``scene``, ``stages``), the step records, and the tail (``force_method``,
    # ``groups``, ``warnings``).  ``to_dict`` joins them for a whole run.

    def head(self) -> dict:
        """The keys of the result before ``steps``: ``scene`` and ``stages``."""
        return {"scene": self.scene, "stages": list(self.stages)}

    def step_records(self, start: int = 0, stop: int | None = None, number_from: int | None = None,
                     dropped: "LeftOut | None" = None):
        """The JSON records of steps ``start`` to ``stop`` (a generator of dicts).

        Values that are not finite are left out (see :func:`~linkage_sym.numeric.results.strict_json.finite_only`) and
        named in ``dropped`` as ``steps[k]...``, ``k`` counted from
        ``number_from`` (default ``start``: the step's own index; a chunk of a
        longer sweep passes its offset in that sweep).  The arrays are turned
        into Python numbers one block of steps at a time (``tolist``), so the
        records of a long run cost no more memory than one block's.
        """
        stop = self.n_steps if stop is None else stop
        number_from = start if number_from is None else number_from
        dropped = LeftOut() if dropped is None else dropped
        for a in range(start, stop, _RECORD_BLOCK):
            b = min(stop, a + _RECORD_BLOCK)
            yield from self._records(a, b, number_from + (a - start), dropped)

    def _records(self, a: int, b: int, number_from: int, dropped: "LeftOut"):
        """Step records of steps ``a`` to ``b`` (see :meth:`step_records`)."""
        blk = RecordBlock(self, a, b)
        status, messages, drivers = blk.status, blk.messages, blk.drivers
        # only these records can hold a value of a column to leave out; keys of a record
        # that no column covers are checked at every step
        suspect = self.not_finite(a, b)
        cols = self.columns()
        covered = {"status", "message", *(n.split(".", 1)[0] for n, _, _ in cols)}
        # a record whose values are there only where finite (instant centres) is checked
        # at every step, as one without columns
        covered -= {n.split(".", 1)[0] for n, _, when in cols if when == "finite"}
        for i in range(b - a):
            st = str(status[i])
            step: dict = {"status": st}
            if messages[i] is not None:
                step["message"] = messages[i]
            step["drivers"] = {
                name: {k: v[i] for k, v in d.items()} for name, d in drivers.items()
            }
            positions = st in (OK, SINGULAR)
            rates = st == OK
            if blk.want_kin and positions:
                blk.kinematics(step, i, rates)
            if blk.forces is not None and rates:
                blk.force_parts(step, i)
            if rates and blk.accuracy is not None:
                step["accuracy"] = {k: v[i] for k, v in blk.accuracy.items()}
            if rates and blk.centres is not None:  # extension: every pair's instant centre
                step["instant_centres"] = blk.centres.records(a + i)
            if suspect[i]:
                yield finite_only(step, f"steps[{number_from + i}]", dropped)
                continue
            for key in [k for k in step if k not in covered]:
                kept = finite_only(step[key], f"steps[{number_from + i}].{key}", dropped)
                if kept is LEFT_OUT:
                    del step[key]
                else:
                    step[key] = kept
            yield step

    def not_finite(self, start: int = 0, stop: int | None = None) -> np.ndarray:
        """Which of steps ``start`` to ``stop`` have a value in their JSON record that is
        not finite (and is left out of it): bool array of ``stop - start``.

        A value is in a step's record where its column's ``when`` (see
        :meth:`columns`) holds at the step's status.
        """
        stop = self.n_steps if stop is None else stop
        st = self.status[start:stop]
        present = {"positions": (st == OK) | (st == SINGULAR), "ok": st == OK}
        out = np.zeros(stop - start, bool)
        for name, v, when in self.columns():
            if name in ("status", "message") or when == "finite":
                continue
            bad = ~np.isfinite(v[start:stop])
            out |= bad if when == "always" else bad & present[when]
        return out

    def group_records(self, steps_per_choice: list | None = None) -> list | None:
        """The ``groups`` entry (``None`` when forces did not run).

        ``steps_per_choice``: for each group, the number of steps each choice was
        used at (a list per group, ``None`` for groups without choices); default
        this run's own counts.  A sweep written in chunks passes the sums.
        """
        if self.forces is None:
            return None
        if steps_per_choice is None:
            steps_per_choice = self.choice_counts()
        return [
            {
                "links": list(g.links),
                "method": g.method,
                **(
                    {
                        "choices": list(g.choices),
                        "steps_per_choice": {
                            g.choices[k]: int(n) for k, n in enumerate(counts) if n > 0
                        },
                    }
                    if counts is not None
                    else {}
                ),
            }
            for g, counts in zip(self.forces.groups, steps_per_choice)
        ]

    def choice_counts(self, start: int = 0, stop: int | None = None) -> list:
        """For each force group, the steps (``start`` to ``stop``) each choice was used at."""
        if self.forces is None:
            return []
        return [
            None if g.used is None
            else [int((g.used[start:stop] == k).sum()) for k in range(len(g.choices))]
            for g in self.forces.groups
        ]

    def tail(self, warnings: list | None = None, dropped: "LeftOut | None" = None,
             steps_per_choice: list | None = None, work: tuple | None = None) -> dict:
        """The keys of the result after ``steps``: ``force_method``, ``groups``,
        ``mean_efficiency``, ``warnings``.

        ``warnings`` default this run's; a note on the values left out
        (``dropped``) is added to them.  ``work``: the sweep's ``(work_in, work_out)``
        with joint friction and one driver (:mod:`linkage_sym.numeric.results.efficiency`).
        """
        out = {}
        if self.forces is not None:
            out["force_method"] = self.forces.method
            out["groups"] = self.group_records(steps_per_choice)
        if work is not None:  # extension: the sweep's mean efficiency (contract part two)
            out["mean_efficiency"] = mean_efficiency_record(*work)
        warnings = list(self.warnings if warnings is None else warnings)
        if dropped is not None and dropped.count:
            warnings.append(dropped.warning())
        if warnings:
            out["warnings"] = warnings
        if self.extremes is not None:  # extension: analyze --extremes
            out["extremes"] = self.extremes
        return out

    def to_dict(self) -> dict:
        """The result in the JSON layout of the scene-format contract."""
        dropped = LeftOut()
        steps = list(self.step_records(dropped=dropped))
        return {**self.head(), "steps": steps, **self.tail(dropped=dropped, work=run_work(self))}

    def to_json(self, **kwargs) -> str:
        """:meth:`to_dict` as strict JSON text (never ``NaN`` nor ``Infinity``).

        ``kwargs`` go to :func:`json.dumps` (e.g. ``indent``); ``allow_nan`` is
        always ``False``, so a non-finite number is an error, never written.
        """
        return json.dumps(self.to_dict(), **{**kwargs, "allow_nan": False})

    def columns(self) -> list:
        """The step records flattened into columns: ``[(name, values, when), ...]``.

        One column per number of a step's JSON record, named by its path with
        the vector components as ``x``/``y`` (``joints.B.position.x``,
        ``links.coupler.omega``, ``frame.moment``), in the order of the
        record: ``status`` (strings), ``message`` (a list of str or None),
        ``drivers.*``, ``joints.*`` (motion, then ``reaction``,
        ``reaction_moment``), ``links.*``, ``points.*``, ``driving.*``,
        ``frame.*``, ``springs.*``, ``accuracy.*``.  Numeric columns are (N,) float arrays (views of the
        result, NaN where the JSON leaves the value out because it was not
        computed).  ``when`` says at which steps the JSON holds the value:
        ``"always"``, ``"positions"`` (``ok`` and ``singular`` steps),
        ``"ok"``, or ``"finite"`` (wherever the value is finite: an instant
        centre's position or direction, of which a record has one or neither;
        ``instant_centres.a.b.*`` last, see
        :meth:`linkage_sym.centres.table.InstantCentres.columns`).  The same
        columns exist whatever the steps' statuses, so every chunk of a sweep
        has them.
        """
        want_kin = "kinematics" in self.outputs
        has_vel = "velocity" in self.stages
        has_acc = "acceleration" in self.stages
        forces = self.forces
        out = [("status", self.status, "always"), ("message", self.messages, "always")]
        for name, d in self.drivers.items():
            out += [(f"drivers.{name}.{k}", np.asarray(v, dtype=float), "always") for k, v in d.items()]

        vec = _xy_columns

        def motion(prefix, k):
            cols = vec(f"{prefix}.position", k.position, "positions")
            if getattr(k, "pressure_angle", None) is not None:  # a cam contact's
                cols.append((f"{prefix}.pressure_angle", k.pressure_angle, "positions"))
            if has_vel:
                cols += vec(f"{prefix}.velocity", k.velocity)
            if has_acc:
                cols += vec(f"{prefix}.acceleration", k.acceleration)
            return cols

        reactions = forces is not None and "reactions" in self.outputs
        # the joints in the order of the JSON's records: with motion first, then reactions only
        joint_names = list(self.joints) if want_kin else []
        if reactions:
            joint_names += [n for n in forces.reactions if n not in joint_names]
        for name in joint_names:
            if want_kin and name in self.joints:
                out += motion(f"joints.{name}", self.joints[name])
            if reactions and name in forces.reactions:
                out += vec(f"joints.{name}.reaction", forces.reactions[name])
                if name in self.p_joints:
                    out.append((f"joints.{name}.reaction_moment", forces.reaction_moments[name], "ok"))
                if forces.friction is not None and name in forces.friction:  # contract part two
                    key = "friction_force" if name in self.p_joints else "friction_moment"
                    out.append((f"joints.{name}.{key}", forces.friction[name], "ok"))
        if want_kin:
            for name, lk in self.links.items():
                out += _link_columns(name, lk, has_vel, has_acc)
            for name, pk in self.points.items():
                out += motion(f"points.{name}", pk)
            out += [(f"transmission_angles.{name}", v, "positions")
                    for name, v in self.transmission_angles.items()]
        if forces is not None:
            if "driving" in self.outputs:
                out += [(f"driving.{k}", v, "ok") for k, v in forces.driving.items()]
            if "frame" in self.outputs:
                out += vec("frame.force", forces.frame_force)
                out.append(("frame.moment", forces.frame_moment, "ok"))
            for name, rec in forces.springs.items():  # the contract's second part
                out += [(f"springs.{name}.{k}", v, "ok") for k, v in rec.items()]
            if reactions and forces.friction is not None:  # contract part two
                out.append(("friction_power", forces.friction_power, "ok"))
                if forces.efficiency is not None:
                    out.append(("efficiency", forces.efficiency, "finite"))
        if self.accuracy:  # extension: each ok step's estimated relative accuracy
            out += [(f"accuracy.{k}", v, "ok") for k, v in self.accuracy.items()]
        centres = self.instant_centres if "instant_centres" in self.outputs else None
        if centres is not None:  # extension: every pair's instant centre, at the ok steps
            out += centres.columns()
        return out


_RECORD_BLOCK = 1024
"""Steps whose arrays :meth:`Analysis.step_records` turns into Python numbers at once."""


def _xy_columns(prefix, v, when="ok") -> list:
    """The columns ``<prefix>.x`` and ``<prefix>.y`` of an (N, 2) array (see
    :meth:`Analysis.columns`)."""
    return [(f"{prefix}.x", v[:, 0], when), (f"{prefix}.y", v[:, 1], when)]


def _link_columns(name, lk, has_vel: bool, has_acc: bool) -> list:
    """A link's columns: rotation and its rates, centre of mass and its rates (see
    :meth:`Analysis.columns`)."""
    out = [(f"links.{name}.rotation", lk.rotation, "positions")]
    if has_vel:
        out.append((f"links.{name}.omega", lk.omega, "ok"))
    if has_acc:
        out.append((f"links.{name}.alpha", lk.alpha, "ok"))
    if lk.com is not None:
        out += _xy_columns(f"links.{name}.com", lk.com, "positions")
        if has_vel:
            out += _xy_columns(f"links.{name}.com_velocity", lk.com_velocity)
        if has_acc:
            out += _xy_columns(f"links.{name}.com_acceleration", lk.com_acceleration)
    return out
