"""Bookkeeping of a run over the scene's sweep that both runtimes share (NumPy only).

The numeric plan (:mod:`linkage_sym.numeric.plan`) and the compiled symbolic
mechanism (:mod:`linkage_sym.codegen.runtime`) solve a sweep by different
methods; what a step's status means, how it is worded, and the path they both
follow are one thing, kept here:

* the scene's sweep and the stages its outputs call for;
* the solving path from the assembly configuration through the steps, and the
  unwrapping of angles along it;
* the singularity threshold of the scene format and its message;
* the statuses and messages of the steps (:func:`step_status`), the
  singularity decision on screened steps (:func:`mark_singular`);
* the result (:func:`new_analysis`) and what every run adds to it whatever
  solved it (:func:`finish`: the warnings of the run -- ``ok`` steps that
  lose digits, force superpositions that cancel, assembly-mode jumps --, the
  transmission angles, the instant centres), so a new output kind is added
  here once;
* the accuracy calibration run, made once per runtime (:class:`Calibration`).

The Newton continuation policy both runtimes use lives beside it, in
:mod:`linkage_sym.numeric.continuation`.
"""

from __future__ import annotations

import math

import numpy as np

from linkage_sym.errors import SceneError
from linkage_sym.model import GROUND, Scene
from linkage_sym.numeric.results import accuracy
from linkage_sym.numeric.results.jumps import assembly_jumps
from linkage_sym.numeric.results.passages import infinity_passages
from linkage_sym.numeric.continuation.messages import step_warnings
from linkage_sym.numeric.engine import heap
from linkage_sym.numeric.results.result import OK, SINGULAR, UNASSEMBLABLE, Analysis
from linkage_sym.numeric.forces.policy import AMPLIFICATION_LIMIT
from linkage_sym.numeric.results.transmission import transmission_angles
from linkage_sym.numeric.results.wording import steps_text

SINGULAR_COND = 1e10
"""Spec: a step is singular when the dimensionless condition number exceeds this."""
SCREEN = 1e-3
"""A group indicator below this triggers the exact condition number at that step."""
WARN_COND = 1e6
"""An ``ok`` step whose computed condition number exceeds this is named in ``Analysis.warnings``."""
MAX_ANGLE_STEP = math.radians(2.0)
"""Largest driver increment (R drivers) between two points of the solving path."""
MAX_SLIDE_STEP = 0.02
"""Largest driver increment (P drivers) along the path, as a fraction of the mechanism size."""
MAX_EXTRA_PATH = 10**6
"""Most path points a sweep may add to its steps (from the assembly configuration to the first
step, and between steps farther apart than the increments above), or ten times its steps if
that is more: beyond it the path would outgrow the sweep, and the scene is refused."""


def singular_message(cond: float) -> str:
    """The message of a ``singular`` step (both runtimes word it alike)."""
    return (
        f"singular position: condition number {cond:.3g} of the dimensionless constraint "
        f"Jacobian exceeds {SINGULAR_COND:.0e}; velocities and accelerations have no unique "
        "solution"
    )


def step_status(failed: np.ndarray, message_of) -> tuple[np.ndarray, list]:
    """Statuses and messages of the steps from the first failing group at each one.

    ``failed`` (N,) holds that group's index, -1 where every group is solved;
    ``message_of(i)`` words the failure at step ``i``.
    """
    N = len(failed)
    status = np.full(N, OK, dtype="<U13")
    bad = np.flatnonzero(failed >= 0)
    status[bad] = UNASSEMBLABLE
    messages: list = [None] * N
    for i in bad:
        messages[i] = message_of(int(i))
    return status, messages


def mark_singular(status, messages, condition, idx, cond) -> np.ndarray:
    """Record the exact condition numbers ``cond`` of the screened steps ``idx``; the
    ones above :data:`SINGULAR_COND` (or not finite) become ``singular``.  Returns them."""
    condition[idx] = cond
    sing = idx[~(cond <= SINGULAR_COND)]
    status[sing] = SINGULAR
    for i in sing:
        messages[i] = singular_message(condition[i])
    return sing


def new_analysis(scene: Scene, stages, status, messages, q, qd, qdd, joints, links, points,
                 condition, forces) -> Analysis:
    """The :class:`Analysis` of a run, whichever runtime solved it."""
    drivers = {
        k: {"q": np.asarray(q[k], float), "qd": np.asarray(qd[k], float),
            "qdd": np.asarray(qdd[k], float)}
        for k in q
    }
    return Analysis(
        scene=scene.name,
        stages=tuple(stages),
        status=status,
        messages=messages,
        drivers=drivers,
        joints=joints,
        links=links,
        condition=condition,
        outputs=tuple(scene.outputs),
        forces=forces,
        p_joints=tuple(j.name for j in scene.joints if j.type == "P"),
        points=points,
    )


def finish(res: Analysis, scene: Scene, notes, step_points, decomposition=None) -> Analysis:
    """What every run adds to its result, whichever runtime solved it.

    The warnings (assembly-mode jumps and ambiguous modes of Newton groups
    from their ``notes``, see :func:`~linkage_sym.numeric.continuation.messages.step_warnings`; then
    :func:`run_warnings`), the passages of joints through infinity among those notes
    (:func:`~linkage_sym.numeric.results.passages.infinity_passages`) and the Newton groups'
    assembly-mode jumps (:func:`~linkage_sym.numeric.results.jumps.assembly_jumps`), the transmission
    angles, and the instant centres when the scene asks for them.
    """
    res.warnings.extend(step_warnings(notes, step_points))
    res.passages = infinity_passages(notes, step_points, scene, decomposition)
    res.jumps = assembly_jumps(notes, step_points, scene, decomposition)
    if res.forces is not None:
        res.warnings.extend(res.forces.notes)
    res.warnings.extend(run_warnings(res))
    res.transmission_angles = transmission_angles(scene, res, decomposition)
    if "instant_centres" in scene.outputs:  # an extension of the format
        from linkage_sym.centres import instant_centres

        res.instant_centres = instant_centres(scene, res)
    return res


class Calibration:
    """The accuracy calibration of one runtime (see :mod:`linkage_sym.numeric.results.accuracy`).

    The ratio ``G`` of the exact condition number to a runtime's cheap
    indicator is measured once, by a run of the scene's own sweep at
    :func:`accuracy.calibration_steps` with exact condition numbers, so every
    later run -- whole or in chunks -- uses the same ``G``.  While that run is
    under way, :attr:`active` is true and the run hands its data to
    :meth:`record` instead of computing an accuracy.
    """

    def __init__(self):
        self.active = False
        self._data = None
        self._G = None

    @property
    def G(self) -> float | None:
        """The ratio once measured (``None`` before the first run)."""
        return None if self._G is None else self._G[0]

    def record(self, K, ok, indicator) -> None:
        self._data = (K, ok, indicator)

    def ratio(self, sweep, run):
        """``G``, measured on the first call by ``run(q, qd, qdd)`` at the calibration steps
        of ``sweep()``."""
        if self._G is None:
            q, qd, qdd = sweep()
            idx = accuracy.calibration_steps(len(next(iter(q.values()))))
            self.active = True
            try:
                run(*({k: np.asarray(v)[idx] for k, v in d.items()} for d in (q, qd, qdd)))
            finally:
                self.active = False
            self._G = (accuracy.calibration(*self._data),)
        return self._G[0]


def unwrap_angles(th: np.ndarray) -> np.ndarray:
    """Remove the 2 pi jumps of an angle sequence (as ``np.unwrap``, with a fast exit).

    Consecutive path points are at most a few degrees apart, so a jump of more
    than half a turn can only be a wrap of ``atan2``.  Shared by the numeric plan and the
    compiled mechanism's runtime.

    Examples
    --------
    >>> unwrap_angles(np.array([3.0, -3.0, -2.9])).round(4).tolist()
    [3.0, 3.2832, 3.3832]
    """
    d = np.diff(th)
    jump = np.abs(d) > math.pi
    if not jump.any():
        return th
    k = np.zeros_like(th)
    k[1:] = np.cumsum(np.where(jump, np.round(d / (2 * math.pi)), 0.0))
    return th - 2 * math.pi * k


def ground_driven(scene: Scene) -> dict:
    """Links whose rotation is a driver's value: ``{link: (joint, sign)}``.

    A link turned by an ``R`` driver mounted on the ground reports that driver's value,
    ``sign (q - q0)`` (``sign`` +1 when the link is the joint's ``links[1]``), at every
    step, across gaps too: it is never shifted by the gap rule of
    :func:`nearest_across_gaps`, and every method gives the same number.  A link driven
    relative to another moving link follows the gap rule like any other link (its
    driver's value is in ``drivers``; the relation between the two rotations then holds
    modulo a whole turn).
    """
    out = {}
    for d in scene.drivers:
        j = scene.joint(d.joint)
        if j.type != "R" or GROUND not in j.links or j.links[0] == j.links[1]:
            continue
        link = j.links[1] if j.links[0] == GROUND else j.links[0]
        out[link] = (d.joint, 1.0 if j.links[1] == link else -1.0)
    return out


def interrupted(valid_path: np.ndarray, out, solved: np.ndarray) -> np.ndarray:
    """Where the solving path was interrupted since the last solved step.

    ``valid_path`` (..., K): path points where every group is solved; ``out``: the path
    index of each step (an index array or a slice); ``solved`` (..., N): steps with a
    position (``ok`` or ``singular``).  True at a solved step when some point of the path
    between the previous solved step and it (itself included) has no position: a gap of
    unassemblable steps, or one the path crosses between two steps.  False at the first
    solved step (the path from the assembly configuration is unwrapped as it goes).
    """
    bad = np.cumsum(~np.asarray(valid_path, bool), axis=-1)
    at = np.asarray(bad[..., out])  # invalid path points up to each step
    N = at.shape[-1]
    idx = np.where(solved, np.arange(N), -1)
    last = np.maximum.accumulate(idx, axis=-1)
    prev = np.full_like(last, -1)
    prev[..., 1:] = last[..., :-1]
    before = np.take_along_axis(at, np.maximum(prev, 0), axis=-1)
    return solved & (prev >= 0) & (at > before)


def nearest_across_gaps(th: np.ndarray, solved: np.ndarray, broken: np.ndarray) -> np.ndarray:
    """Rotations at the steps with the scene format's rule across gaps applied.

    Each stretch of steps that starts where the path was interrupted (``broken``, see
    :func:`interrupted`) is shifted by whole turns so that its first rotation is the value
    nearest to the last solved step before the gap; the shift carries on to the later
    steps, so each stretch stays continuous.  ``th`` (..., N), NaN where not ``solved``.
    Returns ``th`` itself when nothing moves.

    Examples
    --------
    >>> th = np.array([2.613, np.nan, 5.995, 6.1])
    >>> solved = np.isfinite(th)
    >>> out = nearest_across_gaps(th, solved, np.array([False, False, True, False]))
    >>> [round(float(v), 3) for v in out[[0, 2, 3]]]
    [2.613, -0.288, -0.183]
    """
    if not np.any(broken):
        return th
    N = th.shape[-1]
    idx = np.where(solved, np.arange(N), -1)
    last = np.maximum.accumulate(idx, axis=-1)
    prev = np.zeros_like(last)
    prev[..., 1:] = np.maximum(last[..., :-1], 0)
    with np.errstate(invalid="ignore"):
        d = th - np.take_along_axis(th, prev, axis=-1)
        turns = np.where(broken, np.round(d / (2 * math.pi)), 0.0)
    turns = np.cumsum(turns, axis=-1)
    if not turns.any():
        return th
    return th - 2 * math.pi * turns


def solving_path(scene: Scene, names, q0: dict, L: float, Q: np.ndarray):
    """Driver values along the solving path (see the module docstring).

    Parameters
    ----------
    names : list of str
        The driven joints, in the order of the rows of ``Q``.
    q0 : dict
        Each driver's value in the assembly configuration.
    L : float
        Size of the mechanism (a slide's largest increment is a fraction of it).
    Q : ndarray (D, N)
        The steps' driver values.

    Returns
    -------
    P : ndarray (D, K)
        The assembly configuration, intermediate points up to the first step,
        then the steps, refined where consecutive steps are far apart.
    out : ndarray (N,)
        The path index of each step.
    n_ref : int
        Path intervals between consecutive steps (1: the steps are contiguous).
    """
    q0 = np.array([q0[n] for n in names])
    lim = np.array(
        [MAX_ANGLE_STEP if scene.joint(n).type == "R" else MAX_SLIDE_STEP * L for n in names]
    )
    N = Q.shape[1]
    with np.errstate(over="ignore", invalid="ignore"):
        to_first = np.abs(Q[:, 0] - q0) / lim
        apart = np.max(np.abs(np.diff(Q, axis=1)) / lim[:, None], axis=1) if N > 1 else 0 * lim
    extra = to_first + (N - 1) * np.maximum(apart - 1.0, 0.0)
    if not np.all(extra <= max(MAX_EXTRA_PATH, 10 * N)):
        k = int(np.argmax(np.where(np.isfinite(extra), extra, np.inf)))
        i = [d.joint for d in scene.drivers].index(names[k])
        unit = "°" if scene.joint(names[k]).type == "R" else " m"
        scale = math.degrees(1.0) if unit == "°" else 1.0
        raise SceneError([
            f"drivers[{i}]: the solving path from the assembly configuration "
            f"({q0[k] * scale:.6g}{unit}) to the first step ({Q[k, 0] * scale:.6g}{unit}) and "
            f"on through the steps, at most {lim[k] * scale:.3g}{unit} a point, would add "
            f"{extra[k]:.3g} points to the {N} step{'s' if N != 1 else ''} (at most "
            f"{max(MAX_EXTRA_PATH, 10 * N)}); "
            "start the sweep nearer the assembly configuration or give more steps"])
    n_pre = max(1, int(math.ceil(np.max(to_first))))
    pre = q0[:, None] + (Q[:, :1] - q0[:, None]) * (np.arange(n_pre) / n_pre)[None, :]
    n_ref = max(1, int(math.ceil(np.max(apart)))) if N > 1 else 1
    if n_ref > 1:
        f = np.arange(n_ref) / n_ref
        seg = Q[:, :-1, None] + np.diff(Q, axis=1)[:, :, None] * f
        body = np.concatenate([seg.reshape(len(names), -1), Q[:, -1:]], axis=1)
    else:
        body = Q
    return np.concatenate([pre, body], axis=1), n_pre + np.arange(N) * n_ref, n_ref


def path_size(scene: Scene) -> tuple[int, int]:
    """``(points, n_ref)`` of the solving path of the scene's own sweep
    (:func:`solving_path`) at most, from the drivers' fields alone: nothing allocated, so
    that a run's memory can be estimated before its arrays are made.

    Examples
    --------
    >>> import linkage_sym
    >>> path_size(linkage_sym.load_example("crank_rocker"))  # 361 steps 1 degree apart
    (362, 1)
    """
    from linkage_sym.structure.parameters import driver_q0

    N = scene.drivers[0].steps
    q0 = driver_q0(scene)
    L = scene.characteristic_length() or 1.0
    to_first, apart = [0.0], [0.0]
    for d in scene.drivers:
        lim = MAX_ANGLE_STEP if scene.joint(d.joint).type == "R" else MAX_SLIDE_STEP * L
        to_first.append(abs(d.start - q0[d.joint]) / lim)
        if N > 1:
            apart.append(abs(d.stop - d.start) / (N - 1) / lim)
    # an upper bound: the steps' increments computed from their values differ from the
    # nominal one in the last bits, and one just above the largest increment doubles n_ref
    n_pre = max(1, math.ceil(max(to_first) * (1 + 1e-9)))
    n_ref = max(1, math.ceil(max(apart) * (1 + 1e-9))) if N > 1 else 1
    return n_pre + (N - 1) * n_ref + 1, n_ref


def scene_sweep(scene: Scene):
    """Driver values ``(q, qd, qdd)`` of a scene's sweep: dicts of (N,) arrays.

    Raises
    ------
    SceneError
        If the sweep's driver values alone would not fit in the memory this process can
        still take (:func:`heap.available_memory`), naming the drivers' ``steps``.
    """
    steps = scene.drivers[0].steps if scene.drivers else 0
    need = 3 * 8 * steps * len(scene.drivers)  # q, qd, qdd: the path and results take more
    # (the probe reads /proc: asked only where the answer could be no)
    available = heap.available_memory() if need > 2**28 else None
    if available is not None and need > available:
        raise SceneError([
            f"drivers[0].steps: {steps} steps do not fit in memory: the sweep's driver values "
            f"alone take {heap.gib(need)}, and this process can take {heap.gib(available)} "
            "more; give fewer steps (or split the sweep into several scenes)"])
    q, qd, qdd = {}, {}, {}
    for d in scene.drivers:
        q[d.joint] = np.linspace(d.start, d.stop, d.steps)
        qd[d.joint] = np.full(d.steps, float(d.speed))
        qdd[d.joint] = np.full(d.steps, float(d.acceleration))
    return q, qd, qdd


def needed_stages(scene: Scene) -> tuple[str, ...]:
    """The stages a scene's outputs and effects call for, in order.

    Kinematics output needs positions, velocities and accelerations (so does
    the ``instant_centres`` extension: velocities, and accelerations for the
    polygons); forces need velocities and accelerations only when inertia acts
    on a link with mass, a spring with damping acts (its force follows its
    rate of extension), or a joint's friction acts (its direction follows them).
    """
    outs = set(scene.outputs)
    forces = bool(outs & {"reactions", "driving", "frame"})
    inertia = scene.effects.inertia and any(
        link.mass > 0 or link.inertia > 0 for link in scene.links
    )
    damping = any(k.damping != 0.0 for k in scene.active_springs)
    # joint friction's direction follows the joints' relative velocities and accelerations
    friction = scene.effects.friction and any(
        j.friction is not None and j.friction.coefficient > 0 for j in scene.joints)
    stages = ["position"]
    if "kinematics" in outs or "instant_centres" in outs or (forces and (inertia or damping or friction)):
        stages += ["velocity", "acceleration"]
    if forces:
        stages.append("forces")
    return tuple(stages)


def ill_conditioned_warning(count: int, first, worst: float, worst_step: int) -> str:
    """The wording of ``ok`` steps above :data:`WARN_COND` (one run, or a sweep's chunks)."""
    return (
        f"{count} ok step(s) have a condition number above {WARN_COND:.0e} (steps "
        f"{steps_text(first, count)}; largest {worst:.3g} at step {worst_step}): their "
        f"velocities and accelerations carry about {np.log10(worst):.0f} "
        "fewer significant digits than their positions"
    )


def cancelling_warning(links, count: int, first, worst: float, worst_step: int) -> str:
    """The wording of a group whose force superposition cancels at ``ok`` steps."""
    return (
        f"group ({', '.join(links)}): the superposition cancels at {count} "
        f"step(s) (steps {steps_text(first, count)}; amplification up to "
        f"{worst:.3g} at step {worst_step}) with every disconnection: "
        f"its reactions lose about {np.log10(worst):.0f} digits there"
    )


def run_warnings(res: Analysis) -> list[str]:
    """What a caller must know that no step's status says: ``ok`` steps that lose digits.

    * ``ok`` steps whose computed condition number exceeds :data:`WARN_COND`
      (near a dead centre or a limit position): rates there carry about
      ``log10(cond)`` fewer significant digits than positions.
    * Groups whose force superposition still cancels beyond
      ``AMPLIFICATION_LIMIT`` with the best disconnection available.
    """
    out = []
    ok = res.status == OK
    with np.errstate(invalid="ignore"):
        ill = np.flatnonzero(ok & (res.condition > WARN_COND))
    if len(ill):
        worst = int(ill[np.argmax(res.condition[ill])])
        out.append(ill_conditioned_warning(len(ill), ill, res.condition[worst], worst))
    if res.forces is not None:
        for g in res.forces.groups:
            if g.amplification is None:
                continue
            with np.errstate(invalid="ignore"):
                bad = np.flatnonzero(ok & (g.amplification > AMPLIFICATION_LIMIT))
            if len(bad):
                worst = int(bad[np.argmax(g.amplification[bad])])
                out.append(cancelling_warning(g.links, len(bad), bad, g.amplification[worst], worst))
    return out
