"""``linkage-sym simulate``: the motion of a machine driven by its motor.

::

    linkage-sym simulate SCENE.json [-o RESULT.json | -o -] [--method LSODA|Radau|BDF]
                         [--plots DIR]

integrates the scene's equation of motion (its ``simulate`` section, its drivers' ``motor``;
:func:`linkage_sym.simulate`) and writes the result of the contract: the steps at the sampled
times, each analysed as ``analyze`` analyses a step, the ``integrator`` and the periodic
``motion``.  The console gets a summary (how the motion ended, the speed reached, the periodic
regime or why there is none, the integration's cost); a progress bar follows long runs on a
terminal.  ``--plots`` draws the speed against time and the torque balance.
"""

from __future__ import annotations

import sys

__all__ = ["cmd_simulate", "register", "several_summary", "summary"]


def register(sub) -> None:
    """Add the ``simulate`` command to the ``linkage-sym`` subparsers ``sub``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        What ``ArgumentParser.add_subparsers`` returned.

    Examples
    --------
    >>> import argparse
    >>> p = argparse.ArgumentParser(prog="linkage-sym")
    >>> register(p.add_subparsers(dest="command"))
    >>> a = p.parse_args(["simulate", "s.json", "-o", "r.json"])
    >>> a.command, a.output, a.method, a.func is cmd_simulate
    ('simulate', 'r.json', 'LSODA', True)
    """
    from linkage_sym.motion.methods import METHODS

    c = sub.add_parser(
        "simulate", help="integrate the motion of the machine driven by its motor",
        description="Integrate the equation of motion of the scene's mechanism driven by its "
        "motor (drivers[i].motor) from the scene's simulate section, and write the steps at "
        "the sampled times analysed as analyze analyses a step, with the periodic motion's "
        "mean speed and speed fluctuation.")
    c.add_argument("scene", help="scene JSON file")
    c.add_argument("-o", "--output", metavar="FILE",
                   help="write the result JSON ('-' for standard output, the summary then goes "
                   "to standard error)")
    c.add_argument("--method", choices=("LSODA",) + tuple(m for m in METHODS if m != "LSODA"),
                   default="LSODA", help="the stiff-capable SciPy solver (default LSODA)")
    c.add_argument("--plots", metavar="DIR", help="draw the speed against time and the torque "
                   "balance into this folder")
    c.set_defaults(func=cmd_simulate)


def summary(scene, res) -> list[str]:
    """The console's lines for a :class:`~linkage_sym.motion.simulate.SimulationResult` (or,
    several drivers, a :class:`~linkage_sym.motion.multi_simulate.SeveralSimulationResult`)."""
    if len(scene.drivers) > 1:
        return several_summary(scene, res)
    d = scene.drivers[0]
    unit = "rad/s" if d.kind == "R" else "m/s"
    qd = res.analysis.drivers[d.joint]["qd"]
    traj = res.trajectory
    lines = [f"simulated {scene.name}: {len(res.time)} samples over {res.time[-1]:.6g} s "
             f"({traj.method}, rtol {traj.rtol:g}: {traj.steps} steps, {traj.evaluations} "
             "evaluations of the equation)"]
    if res.message:
        lines.append(f"  ended early: {res.message}")
    lines.append(f"  driver {d.joint}: speed {qd[0]:.6g} -> {qd[-1]:.6g} {unit}, "
                 f"largest {max(qd.max(), -qd.min()):.6g} {unit}")
    m = res.motion
    if "reason" in m:
        lines.append(f"  no periodic motion: {m['reason']}")
    else:
        lines.append(f"  periodic: period {m['period']:.6g} s, mean speed {m['mean_speed']:.6g} "
                     f"{unit}, speed fluctuation {m['speed_fluctuation']:.6g} "
                     f"(from {m['min_speed']:.6g} to {m['max_speed']:.6g} {unit})")
    lines.append(f"  the solver's effort at the integrated states equals the motor's to "
                 f"{res.effort_error:.1e} (relative)")
    return lines


def several_summary(scene, res) -> list[str]:
    """The console's lines for several drivers: each driver's speed and last full turn."""
    traj = res.trajectory
    lines = [f"simulated {scene.name}: {len(res.time)} samples over {res.time[-1]:.6g} s, "
             f"{len(scene.drivers)} motors ({traj.method}, rtol {traj.rtol:g}: {traj.steps} "
             f"steps, {traj.evaluations} evaluations of the equations)"]
    if res.message:
        lines.append(f"  ended early: {res.message}")
    for d in scene.drivers:
        unit = "rad/s" if d.kind == "R" else "m/s"
        qd = res.analysis.drivers[d.joint]["qd"]
        turn = res.motion["drivers"][d.joint]
        last = (f"last full turn: period {turn['period']:.6g} s, mean speed "
                f"{turn['mean_speed']:.6g} {unit}, speed fluctuation "
                f"{turn['speed_fluctuation']:.6g}" if "reason" not in turn else turn["reason"])
        lines.append(f"  driver {d.joint}: speed {qd[0]:.6g} -> {qd[-1]:.6g} {unit}, largest "
                     f"{max(qd.max(), -qd.min()):.6g} {unit}; {last}")
    lines.append("  no periodic regime sought: several drivers")
    lines.append(f"  the solver's efforts at the integrated states equal the motors' to "
                 f"{res.effort_error:.1e} (relative)")
    return lines


def cmd_simulate(args) -> int:
    """Run ``linkage-sym simulate`` (see the module docstring); returns the exit status."""
    from linkage_sym.cli.common import check_outputs, load, stem, write
    from linkage_sym.motion.simulate import simulate
    from linkage_sym.output import progress_bar

    check_outputs(files=[("-o/--output", args.output)], folders=[("--plots", args.plots)])
    scene = load(args.scene)
    duration = scene.simulate.duration if scene.simulate is not None else 0.0
    bar = progress_bar(1000, True, unit="‰ of the time")
    done = [0]

    def progress(t):
        if bar is not None and duration > 0:
            k = int(1000 * min(t / duration, 1.0))
            bar.update(k - done[0])
            done[0] = k

    try:
        res = simulate(scene, method=args.method, progress=progress)
    finally:
        if bar is not None:
            bar.close()
    notes = sys.stderr if args.output == "-" else sys.stdout
    print("\n".join(summary(scene, res)), file=notes)
    text = res.to_json(indent=1) + "\n"
    if args.output == "-":
        sys.stdout.write(text)
    elif args.output:
        write(args.output, text)
        print(f"wrote {args.output}", file=notes)
    if args.plots:
        from pathlib import Path

        if len(scene.drivers) > 1:
            from linkage_sym.plotting.dynamics_several import plot_several as plot_simulation
        else:
            from linkage_sym.plotting.dynamics import plot_simulation

        for path in plot_simulation(scene, res, Path(args.plots), stem(scene)):
            print(f"wrote {path}", file=notes)
    return 0
