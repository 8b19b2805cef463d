"""``linkage-sym centres``: the instant centres of one step, as a person reads them.

::

    linkage-sym centres SCENE.json [--step K | --deg PHI] [-o FILE] [--plots DIR] [--polygons]

prints the ``N (N - 1) / 2`` instant centres of the step (eq. 3-5 of the
textbook chapter *Kinematic analysis of planar mechanisms*), numbered as the
chapter's figures number links (the ground 1, then the scene's links in
order: ``P13``), each with how it was found: at a joint, by Kennedy's
three-centre lines (which two), or from the velocities where those lines run
out; ``-o`` writes them as JSON; ``--plots`` draws the linkage with its centres
and three-centre lines, and the fixed and moving centrodes of the floating
links over the sweep.  ``--polygons`` adds the quantities of the graphical
method (each link's angular velocity and acceleration, the slip velocity,
slip acceleration and Coriolis term of each sliding pair between moving
links, the normal and tangential accelerations of each point about each
pivot of its link) to the print-out and the JSON, and with ``--plots`` draws
the velocity and acceleration polygons to scale.

The step is the sweep's step ``K`` (default: its first solved step), or with
``--deg PHI`` the mechanism solved at the driver angle ``PHI`` degrees itself
(a scene with one ``R`` driver), reached continuously from the assembly
configuration as every step is.  The table and the JSON record are those of
:mod:`linkage_sym.centres.report`.
"""

from __future__ import annotations

import dataclasses
import json
import math
import sys

__all__ = ["cmd_centres", "register"]


def register(sub) -> None:
    """Add the ``centres`` command to the ``linkage-sym`` subparsers ``sub``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        What ``ArgumentParser.add_subparsers`` returned.

    Examples
    --------
    >>> import argparse
    >>> p = argparse.ArgumentParser(prog="linkage-sym")
    >>> register(p.add_subparsers(dest="command"))
    >>> a = p.parse_args(["centres", "s.json", "--deg", "30", "--polygons"])
    >>> a.command, a.deg, a.step, a.polygons, a.func is cmd_centres
    ('centres', 30.0, None, True, True)
    """
    c = sub.add_parser(
        "centres", help="instant centres of a step, centrodes, velocity and acceleration polygons",
        description="Print the instant centres of one step (numbered as in the textbook chapter "
        "'Kinematic analysis of planar mechanisms': the ground is link 1), found by Kennedy's "
        "three-centre lines (from the velocities where those run out); optionally write them as "
        "JSON, draw them with the centrodes, and add the polygon method's quantities.")
    c.add_argument("scene", help="scene JSON file")
    at = c.add_mutually_exclusive_group()
    at.add_argument("--step", type=int, metavar="K",
                    help="step of the scene's sweep (from 0; default: the first solved step)")
    at.add_argument("--deg", type=float, metavar="PHI",
                    help="solve at this driver angle (degrees, as the scene's start_deg; a scene "
                    "with one R driver)")
    c.add_argument("-o", "--output", metavar="FILE", help="write the step's centres as JSON "
                   "('-' for standard output, the table then goes to standard error)")
    c.add_argument("--plots", metavar="DIR", help="draw the linkage with its centres and "
                   "three-centre lines, and the centrodes of the floating links (and with "
                   "--polygons the velocity and acceleration polygons)")
    c.add_argument("--polygons", action="store_true", help="add the graphical method's "
                   "quantities: slip velocity and acceleration, Coriolis terms, normal and "
                   "tangential accelerations")
    c.set_defaults(func=cmd_centres)


def _problems_at(scene, args):
    """Option problems that the scene alone shows (before solving)."""
    from linkage_sym.cli.common import OptionError
    from linkage_sym.scene.fields import ANGLE_WHY, MAX_ANGLE_DEG

    if args.deg is not None:
        if len(scene.drivers) != 1 or scene.drivers[0].kind != "R":
            have = ", ".join(f"{d.joint} ({d.kind} joint)" for d in scene.drivers)
            raise OptionError(f"--deg: needs a scene with one R driver; its drivers: {have}")
        if not math.isfinite(args.deg):
            raise OptionError(f"--deg: {args.deg} is not a finite angle")
        if abs(args.deg) > MAX_ANGLE_DEG:  # as a scene's start_deg
            raise OptionError(f"--deg: {ANGLE_WHY}, got {args.deg:g}")
    if args.step is not None and not 0 <= args.step < scene.steps:
        raise OptionError(f"--step: {args.step} is not a step of the sweep (0 to {scene.steps - 1})")


def cmd_centres(args) -> int:
    """Run ``linkage-sym centres`` (see the module docstring); returns the exit status.

    Examples
    --------
    >>> import contextlib, io
    >>> from linkage_sym.cli import main
    >>> from linkage_sym.examples import example_path
    >>> out = io.StringIO()
    >>> with contextlib.redirect_stdout(out):
    ...     status = main(["centres", str(example_path("crank_rocker")), "--step", "30"])
    >>> status, out.getvalue().splitlines()[3]
    (0, '  P13  ground-coupler  (73.092, 42.2) mm  three-centre lines P12-P23 and P14-P34')
    """
    import numpy as np

    from linkage_sym.centres import instant_centres, polygon_quantities
    from linkage_sym.centres.report import centres_report, step_record
    from linkage_sym.cli.common import OptionError, check_outputs as _check_outputs, load as _load, write as _write
    from linkage_sym.numeric.plan import compile_plan

    _check_outputs(files=[("-o/--output", args.output)], folders=[("--plots", args.plots)])
    scene = _load(args.scene)
    _problems_at(scene, args)
    scene = dataclasses.replace(scene, outputs=("kinematics",))  # velocities and accelerations
    from linkage_sym.output import check_run_memory

    # the whole sweep and its centres at every step, before any of it is made
    check_run_memory(dataclasses.replace(scene, outputs=("kinematics", "instant_centres")))
    plan = compile_plan(scene)
    sweep = plan.run()
    if args.deg is not None:
        d = scene.drivers[0]
        one = lambda v: {d.joint: np.array([float(v)])}  # noqa: E731
        analysis = plan.run(q=one(math.radians(args.deg)), qd=one(d.speed), qdd=one(d.acceleration))
        i = 0
        where = f"--deg {args.deg:g}"
    else:
        analysis = sweep
        ok = np.flatnonzero(sweep.status == "ok")
        if args.step is None and ok.size == 0:
            raise OptionError("--step: no step of the sweep could be solved with velocities "
                              f"(step 0: {sweep.messages[0]})")
        i = int(ok[0]) if args.step is None else args.step
        where = f"--step {i}"
    if str(analysis.status[i]) != "ok":
        raise OptionError(f"{where.split()[0]}: {where} is {analysis.status[i]}: "
                          f"{analysis.messages[i]}; no velocities there")
    centres = instant_centres(scene, analysis)
    pq = polygon_quantities(scene, analysis, i) if args.polygons else None
    lines = centres_report(scene, analysis, centres, i, pq)
    if args.deg is not None:
        lines[0] = lines[0].replace(f"at step {i} ", "", 1)
    out = step_record(scene, analysis, centres, i, pq, None if args.deg is not None else i)
    notes = sys.stdout
    if args.output == "-":
        sys.stdout.write(json.dumps(out, indent=1, allow_nan=False) + "\n")
        notes = sys.stderr
        print("\n".join(lines), file=notes)
    else:
        print("\n".join(lines))
        if args.output:
            _write(args.output, json.dumps(out, indent=1, allow_nan=False) + "\n")
            print(f"wrote {args.output}")
    if args.plots:
        _plots(args, scene, sweep, analysis, centres, i, pq, notes)
    return 0


def _plots(args, scene, sweep, analysis, centres, i, pq, notes) -> None:
    """Write the centres' figure, the centrodes' (when a link floats) and the polygons'
    (with --polygons) into the --plots folder; say so on ``notes``."""
    from pathlib import Path

    from linkage_sym.centres import centrodes, floating_links, instant_centres
    from linkage_sym.plotting.centres import centres_figure, centrodes_figure, polygons_figure
    from linkage_sym.plotting.style import file_stem

    stem = Path(args.plots) / file_stem(scene, None)
    written = [centres_figure(scene, analysis, centres, i, f"{stem}_centres.png")]
    floating = floating_links(scene)
    if floating:
        crv = centrodes(scene, sweep, instant_centres(scene, sweep), floating)
        written.append(centrodes_figure(scene, analysis, centres, i, crv,
                                        f"{stem}_centrodes.png"))
    else:
        print("no centrodes drawn: no floating link (every link is pivoted or slides on "
              "the ground)", file=notes)
    if pq is not None:
        written.append(polygons_figure(scene, pq, f"{stem}_polygons.png"))
    print(f"wrote {len(written)} plots into {args.plots}:", file=notes)
    for path in written:
        print(f"  {path}", file=notes)
