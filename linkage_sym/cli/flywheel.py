"""``linkage-sym flywheel``: the flywheel a requested speed fluctuation needs.

::

    linkage-sym flywheel SCENE.json --fluctuation DELTA [-o FLYWHEEL.json | -o -] [--plots DIR]

prints the moment of inertia (kg m^2) to add to the driven link so that the periodic motion's
speed fluctuation is at most ``DELTA``: the textbook's energy method (the largest energy
surplus over a cycle) as a first estimate, then refined by simulation until the simulated
fluctuation is within 1 % below ``DELTA`` (:func:`linkage_sym.flywheel`); both are reported,
with the fluctuation each gives.  ``--plots`` draws the speed over the period with the
flywheel, the energy diagram and the torque balance.
"""

from __future__ import annotations

import json
import math
import sys

__all__ = ["cmd_flywheel", "register"]


def register(sub) -> None:
    """Add the ``flywheel`` command to the ``linkage-sym`` subparsers ``sub``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        What ``ArgumentParser.add_subparsers`` returned.

    Examples
    --------
    >>> import argparse
    >>> p = argparse.ArgumentParser(prog="linkage-sym")
    >>> register(p.add_subparsers(dest="command"))
    >>> a = p.parse_args(["flywheel", "s.json", "--fluctuation", "0.02"])
    >>> a.command, a.fluctuation, a.func is cmd_flywheel
    ('flywheel', 0.02, True)
    """
    c = sub.add_parser(
        "flywheel", help="the flywheel that keeps the speed fluctuation within a bound",
        description="The moment of inertia to add to the driven link so that the periodic "
        "motion's speed fluctuation (w_max - w_min) / w_m is at most DELTA: the energy "
        "method's estimate, refined by simulation.")
    c.add_argument("scene", help="scene JSON file")
    c.add_argument("--fluctuation", type=float, required=True, metavar="DELTA",
                   help="the largest coefficient of speed fluctuation, e.g. 0.02")
    c.add_argument("-o", "--output", metavar="FILE",
                   help="write the result JSON ('-' for standard output, the summary then goes "
                   "to standard error)")
    c.add_argument("--plots", metavar="DIR", help="draw the speed with the flywheel, the energy "
                   "diagram and the torque balance into this folder")
    c.set_defaults(func=cmd_flywheel)


def cmd_flywheel(args) -> int:
    """Run ``linkage-sym flywheel`` (see the module docstring); returns the exit status."""
    from linkage_sym.cli.common import OptionError, check_outputs, load, stem, write
    from linkage_sym.motion.flywheel import flywheel

    if not (math.isfinite(args.fluctuation) and 0 < args.fluctuation < 2):
        raise OptionError(f"--fluctuation: must be a number between 0 and 2 (exclusive), got "
                          f"{args.fluctuation:g}")
    check_outputs(files=[("-o/--output", args.output)], folders=[("--plots", args.plots)])
    scene = load(args.scene)
    notes = sys.stderr if args.output == "-" else sys.stdout

    def progress(inertia, delta):
        print(f"  trial: flywheel {inertia:.6g} kg m^2 -> fluctuation {delta:.6g}", file=notes,
              flush=True)

    res = flywheel(scene, args.fluctuation, progress=progress)
    e = res.energy
    lines = [
        f"flywheel for {scene.name} on link '{res.link}', speed fluctuation at most "
        f"{res.requested:g}:",
        f"  energy method: largest energy surplus {e['delta_E_max']:.6g} J at the mean speed "
        f"{e['mean_speed']:.6g} rad/s, mechanism's own J {e['mean_J']:.6g} kg m^2 -> "
        f"flywheel {res.estimate:.6g} kg m^2 (simulated fluctuation "
        f"{res.estimate_fluctuation:.6g})",
        f"  refined by simulation: flywheel {res.inertia:.6g} kg m^2 -> fluctuation "
        f"{res.fluctuation:.6g} at the mean speed {res.mean_speed:.6g} rad/s "
        f"({len(res.iterations)} simulations)",
    ]
    print("\n".join(lines), file=notes)
    text = json.dumps(res.to_dict(), indent=1, allow_nan=False) + "\n"
    if args.output == "-":
        sys.stdout.write(text)
    elif args.output:
        write(args.output, text)
        print(f"wrote {args.output}", file=notes)
    if args.plots:
        from pathlib import Path

        from linkage_sym.plotting.dynamics import plot_flywheel

        for path in plot_flywheel(scene, res, Path(args.plots), stem(scene)):
            print(f"wrote {path}", file=notes)
    return 0
