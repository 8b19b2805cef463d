"""Pictures of a motion simulated with several motors.

:func:`plot_several`: each driver's speed against time (its last full turn marked, with its
mean speed), and each driver's effort balance against time: its motor's effort and the
effort the mechanism resists with at zero accelerations (``E0``, the driving effort less
``(M q̈)_k``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from linkage_sym.plotting.style import ensure_dir, new_figure, save

__all__ = ["plot_several"]


def plot_several(scene, res, folder: Path, stem: str) -> list[Path]:
    """The speed and effort-balance pictures of a
    :class:`~linkage_sym.motion.multi_simulate.SeveralSimulationResult`; returns the files
    written."""
    folder = ensure_dir(folder)
    n = len(scene.drivers)
    t = res.time
    dense = np.linspace(t[0], res.trajectory.t_end, max(4000, len(t)))
    y = res.trajectory(dense)
    fig = new_figure(7.0, 2.4 * n + 0.6)
    for k, d in enumerate(scene.drivers):
        unit = "rad/s" if d.kind == "R" else "m/s"
        ax = fig.add_subplot(n, 1, k + 1)
        ax.plot(dense, y[n + k], color=f"C{k}", lw=1.2, label=f"speed of driver {d.joint}")
        ax.plot(t, res.analysis.drivers[d.joint]["qd"], ".", color=f"C{k}", ms=2.5,
                label="samples")
        turn = res.motion["drivers"][d.joint]
        if "reason" not in turn:
            ax.axvspan(turn["from"], turn["to"], color="C2", alpha=0.15,
                       label=f"last full turn: δ = {turn['speed_fluctuation']:.4g}")
            ax.axhline(turn["mean_speed"], color="C2", lw=0.8, ls="--",
                       label=f"its mean speed {turn['mean_speed']:.4g} {unit}")
        ax.set_ylabel(f"ω of {d.joint} ({unit})")
        ax.legend(loc="best", fontsize=7)
        ax.grid(alpha=0.3)
        if k == 0:
            ax.set_title(f"{scene.name}: speeds of the machine driven by its {n} motors")
    ax.set_xlabel("time (s)")
    paths = [save(fig, folder / f"{stem}_speed.png")]
    fig = new_figure(7.0, 2.4 * n + 0.6)
    qdd = np.array([res.analysis.drivers[d.joint]["qdd"] for d in scene.drivers])
    Mqdd = np.einsum("sij,js->is", res.mass_matrix, qdd)
    for k, d in enumerate(scene.drivers):
        unit = "N·m" if d.kind == "R" else "N"
        ax = fig.add_subplot(n, 1, k + 1)
        motor = res.motor[d.joint]
        driving = res.analysis.forces.driving[d.joint] if res.analysis.forces else motor
        resisting = driving - Mqdd[k]
        ax.plot(t, motor, color="C3", lw=1.2, label="motor's effort")
        ax.plot(t, resisting, color="C0", lw=1.0, label="resisting effort E0 (q̈ = 0)")
        ax.fill_between(t, resisting, motor, color="C1", alpha=0.2, label="(M·q̈) of this driver")
        ax.set_ylabel(f"effort on {d.joint} ({unit})")
        ax.legend(loc="best", fontsize=7)
        ax.grid(alpha=0.3)
        if k == 0:
            ax.set_title(f"{scene.name}: effort balance of each motor")
    ax.set_xlabel("time (s)")
    paths.append(save(fig, folder / f"{stem}_torque_balance.png"))
    return paths
