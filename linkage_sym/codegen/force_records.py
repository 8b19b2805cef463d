"""The compiled runtime's forces as a result's records (NumPy only: no SymPy here).

:func:`force_records` turns the forces :class:`~linkage_sym.codegen.runtime.CompiledMechanism`
solved at its steps with rates (the generated force blocks, with the joints' friction
where it acts: :mod:`linkage_sym.codegen.friction`) into the
:class:`~linkage_sym.numeric.results.result.Forces` every method returns: the joints'
reactions, the drivers' efforts, the frame, the springs' records and, with
``effects.friction``, the friction's fields (each joint's friction, the power it
dissipates, the efficiency, the self-locking steps and their messages), filled as the
numeric methods fill them.
"""

from __future__ import annotations

import numpy as np

from linkage_sym.codegen.blocks import full
from linkage_sym.codegen.friction import NumpyOps, lock_message, no_direction_note
from linkage_sym.numeric.forces.springs import record_keys
from linkage_sym.numeric.results.result import Forces, GroupForces
from linkage_sym.structure.parameters import ident

__all__ = ["force_records"]


def force_records(cm, pts, solved, XkD, CS, sel, ok_idx, N, notes, P) -> Forces:
    """The :class:`Forces` of a run of ``cm`` over ``N`` steps.

    ``solved``: ``(F, friction, ideal)``, the forces at the steps ``ok_idx`` (the entries
    ``sel`` of the ``points`` outputs ``pts``), the friction's
    :class:`~linkage_sym.codegen.friction.FrictionSolution` (``None`` where no friction
    acts) and the forces with the friction left out; ``XkD``: the coordinates and their
    rates there; ``P``: the parameters of the frame function (the flanks settled on)."""
    art = cm.art
    Fv, fric, ideal = solved
    Xk, XD = XkD  # the coordinates and their rates (a damper's pull on the frame)
    Kk = len(ok_idx)
    fx, fy, mz = (
        np.broadcast_to(np.asarray(v, float), (Kk,))
        for v in cm.call("frame", P, X=list(Xk[:, sel]), XD=[v[sel] for v in XD], F=list(Fv),
                         CS=(list(CS[0][:, sel]), list(CS[1][:, sel])))
    )

    def spread(v):
        out = np.full(N, np.nan)
        out[ok_idx] = v
        return out

    joint_forces, efforts = cm.reactions(
        cm.scene, Fv, lambda key: [v[sel] for v in art.rows(pts, key)], np.zeros(Kk))
    reactions, moments = {}, {}
    for name, (rx, ry, mm) in joint_forces.items():
        reactions[name] = np.stack([spread(rx), spread(ry)], axis=-1)
        moments[name] = spread(mm)
    driving = {name: spread(v) for name, v in efforts.items()}
    springs = {k.name: dict(zip(record_keys(k), (spread(full(v, len(sel))[sel])
                                                   for v in art.rows(pts, f"spring:{k.name}"))))
               for k in cm.scene.active_springs}
    out = Forces(
        method="symbolic",
        reactions=reactions,
        reaction_moments=moments,
        driving=driving,
        frame_force=np.stack([spread(fx), spread(fy)], axis=-1),
        frame_moment=spread(mz),
        groups=[GroupForces(tuple(g.links), "symbolic") for g in art.groups],
        notes=notes,
        springs=springs,
    )
    if cm.scene.effects.friction:  # contract part two
        _friction_fields(out, cm, fric, Fv if ideal is None else ideal, spread, ok_idx, N)
    return out


def _friction_fields(out: Forces, cm, fric, ideal, spread, ok_idx, N) -> None:
    """The friction's fields of ``out`` (as the numeric methods fill them): each joint with
    a ``friction`` field its friction (0 where it does not act), the power, with one driver
    the efficiency, the self-locking steps with their messages (NaN there), the notes on
    joints without a direction of friction."""
    scene, K = cm.scene, len(ok_idx)
    mu = {} if fric is None else fric.mu
    per_joint = {j.name: spread(np.zeros(K) if mu.get(j.name) is None else mu[j.name])
                 for j in scene.joints if j.friction is not None}
    power = np.zeros(K) if fric is None else fric.power(NumpyOps)
    locked = np.zeros(N, bool)
    messages = {}
    if fric is not None:
        locked[ok_idx] = fric.locked
        messages = {int(ok_idx[i]): lock_message(names) for i, names in fric.lockers.items()}
        for name, has in fric.direction.items():
            bad = np.flatnonzero(~np.broadcast_to(has, (K,)))
            if len(bad):
                out.notes.append(no_direction_note(name, ok_idx[bad]))
    fidx = cm.art.force_index()
    ideal_e = {d.joint: spread(ideal[fidx[("tau_" if d.kind == "R" else "f_") + ident(d.joint)]])
               for d in scene.drivers}
    eff = None
    if len(scene.drivers) == 1:
        (d,) = scene.drivers
        e, e0 = out.driving[d.joint], ideal_e[d.joint]
        with np.errstate(divide="ignore", invalid="ignore"):
            eff = np.where((e != 0) & (e0 != 0) & (np.sign(e) == np.sign(e0)), e0 / e, np.nan)
    out.friction, out.friction_power, out.efficiency = per_joint, spread(power), eff
    out.driving_ideal, out.locked, out.lock_messages = ideal_e, locked, messages
    if locked.any():  # nothing is reported at a self-locking step but its status
        for a in [*out.reactions.values(), *out.reaction_moments.values(), *out.driving.values(),
                  out.frame_force, out.frame_moment, *per_joint.values(), out.friction_power,
                  *ideal_e.values(), *([eff] if eff is not None else [])]:
            a[locked] = np.nan
