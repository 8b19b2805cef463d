"""Pictures of a simulated motion and of a flywheel's design.

* :func:`plot_simulation`: the driver's speed against time (the periodic turn marked, with
  its mean speed), and the torque balance: the motor's effort and the effort the mechanism
  resists with at constant speed (``E0``, the driving effort at zero acceleration) against
  time;
* :func:`plot_flywheel`: the speed over one period of the periodic motion with the refined
  flywheel (and with the energy method's estimate), the energy diagram (the work surplus
  ``dE`` of the energy method over the period, its range ``dE_max`` marked) and the torque
  balance of the energy method (the motor's effort at the mean speed against the resisting
  effort over the period).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from linkage_sym.plotting.style import ensure_dir, new_figure, save

__all__ = ["plot_flywheel", "plot_simulation"]


def _units(kind: str) -> tuple[str, str]:
    return ("rad/s", "N·m") if kind == "R" else ("m/s", "N")


def plot_simulation(scene, res, folder: Path, stem: str) -> list[Path]:
    """The speed and torque-balance pictures of a
    :class:`~linkage_sym.motion.simulate.SimulationResult`; returns the files written."""
    folder = ensure_dir(folder)
    d = scene.drivers[0]
    speed_unit, effort_unit = _units(d.kind)
    t = res.time
    qd = res.analysis.drivers[d.joint]["qd"]
    fig = new_figure(7.0, 3.6)
    ax = fig.add_subplot(1, 1, 1)
    dense = np.linspace(t[0], res.trajectory.t_end, max(4000, len(t)))
    ax.plot(dense, res.trajectory(dense)[1], color="C0", lw=1.2, label="speed (integrated)")
    ax.plot(t, qd, ".", color="C0", ms=2.5, label="samples")
    m = res.motion
    if "reason" not in m:
        ax.axvspan(m["from"], m["to"], color="C2", alpha=0.15,
                   label=f"last periodic turn: δ = {m['speed_fluctuation']:.4g}")
        ax.axhline(m["mean_speed"], color="C2", lw=0.8, ls="--",
                   label=f"mean speed {m['mean_speed']:.4g} {speed_unit}")
    ax.set_xlabel("time (s)")
    ax.set_ylabel(f"speed of driver {d.joint} ({speed_unit})")
    ax.set_title(f"{scene.name}: speed of the machine driven by its motor")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    paths = [save(fig, folder / f"{stem}_speed.png")]
    fig = new_figure(7.0, 3.6)
    ax = fig.add_subplot(1, 1, 1)
    driving = res.analysis.forces.driving[d.joint] if res.analysis.forces else res.motor
    resisting = driving - res.inertia * res.analysis.drivers[d.joint]["qdd"]
    ax.plot(t, res.motor, color="C3", lw=1.2, label="motor's effort M(ω)")
    ax.plot(t, resisting, color="C0", lw=1.0,
            label="resisting effort E0 (the driving effort at zero acceleration)")
    ax.fill_between(t, resisting, res.motor, color="C1", alpha=0.2,
                    label="J·q̈ (accelerates the machine)")
    ax.set_xlabel("time (s)")
    ax.set_ylabel(f"effort on driver {d.joint} ({effort_unit})")
    ax.set_title(f"{scene.name}: torque balance")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    paths.append(save(fig, folder / f"{stem}_torque_balance.png"))
    return paths


def plot_flywheel(scene, res, folder: Path, stem: str) -> list[Path]:
    """The speed, energy-diagram and torque-balance pictures of a
    :class:`~linkage_sym.motion.flywheel.FlywheelResult`; returns the files written."""
    folder = ensure_dir(folder)
    e = res.energy
    deg = np.degrees(e["q"])
    paths = []
    fig = new_figure(7.0, 3.6)
    ax = fig.add_subplot(1, 1, 1)
    traj = res.orbit["trajectory"]
    tt = np.linspace(traj.t[0], traj.t_end, 2000)
    y = traj(tt)
    ax.plot(np.degrees(y[0]), y[1], color="C0", lw=1.2,
            label=f"with the flywheel {res.inertia:.4g} kg·m²: δ = {res.fluctuation:.4g}")
    ax.axhline(res.mean_speed, color="C2", ls="--", lw=0.8,
               label=f"mean speed {res.mean_speed:.5g} rad/s")
    ax.set_xlabel(f"angle of driver {scene.drivers[0].joint} (degrees)")
    ax.set_ylabel("speed (rad/s)")
    ax.set_title(f"{scene.name}: periodic motion with the flywheel (δ requested "
                 f"{res.requested:g})")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    paths.append(save(fig, folder / f"{stem}_flywheel_speed.png"))
    fig = new_figure(7.0, 3.6)
    ax = fig.add_subplot(1, 1, 1)
    energy = e["energy"]
    ax.plot(deg, energy, color="C1", lw=1.4, label="work surplus ΔE(φ)")
    i, k = int(np.argmax(energy)), int(np.argmin(energy))
    ax.axhline(energy[i], color="0.5", lw=0.6)
    ax.axhline(energy[k], color="0.5", lw=0.6)
    ax.annotate("", xy=(deg[i], energy[i]), xytext=(deg[i], energy[k]),
                arrowprops={"arrowstyle": "<->", "color": "C3"})
    right = deg[i] > 0.5 * (deg[0] + deg[-1])  # the label on the side with room
    ax.text(deg[i], 0.5 * (energy[i] + energy[k]),
            f"ΔE_max = {e['delta_E_max']:.4g} J  " if right else
            f"  ΔE_max = {e['delta_E_max']:.4g} J", color="C3", va="center",
            ha="right" if right else "left")
    ax.set_xlabel(f"angle of driver {scene.drivers[0].joint} (degrees)")
    ax.set_ylabel("energy (J)")
    ax.set_title(f"{scene.name}: energy diagram at the mean speed {e['mean_speed']:.5g} rad/s")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    paths.append(save(fig, folder / f"{stem}_energy.png"))
    fig = new_figure(7.0, 3.6)
    ax = fig.add_subplot(1, 1, 1)
    ax.plot(deg, e["effort"], color="C0", lw=1.2, label="resisting effort E0(φ, ω_m)")
    ax.axhline(e["mean_effort"], color="C3", lw=1.2, label="motor's effort M(ω_m)")
    ax.fill_between(deg, e["effort"], e["mean_effort"], color="C1", alpha=0.2)
    ax.set_xlabel(f"angle of driver {scene.drivers[0].joint} (degrees)")
    ax.set_ylabel("torque (N·m)")
    ax.set_title(f"{scene.name}: torque balance over the period")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    paths.append(save(fig, folder / f"{stem}_flywheel_torque.png"))
    return paths
