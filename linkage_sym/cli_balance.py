"""``linkage-sym balance``: Song and Wang's (1992) balancing conditions of a hinged linkage.

::

    linkage-sym balance SCENE.json [-o FILE] [--pretty] [--latex] [--plots DIR]
                        [--balanced-scene FILE] [--optimize FILE [--weights F,M,T]
                        [--max-mass KG] [--links L1,L2]]

derives the shaking force and moment balance conditions (hinged, R-joint only
linkages), the force-balancing counterweights and, with ``--optimize``,
counterweights optimised on the force solver's shaking force and moment (also
for linkages with sliders).  The document is assembled by
:func:`linkage_sym.balancing.report.balance_document`; this module reads the
options, writes the files and draws the plots.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from linkage_sym.cli_common import OptionError, check_outputs, load, write
from linkage_sym.cli_common import stem as file_stem
from linkage_sym.errors import BalanceError

__all__ = ["cmd_balance", "demo_balance", "register"]


def _optimize_options(scene, args):
    """The checked options of ``--optimize`` (``None`` without it), before anything is computed or written."""
    if not args.optimize:
        given = [o for o, v in (("--weights", args.weights), ("--max-mass", args.max_mass),
                                ("--links", args.links)) if v is not None]
        if given:
            raise OptionError([f"{o}: used only with --optimize FILE" for o in given])
        return None
    from linkage_sym.balancing.options import OptionsError, search_options

    try:
        return search_options(
            scene,
            links=None if args.links is None else [n.strip() for n in args.links.split(",")],
            weights=(1.0, 1.0, 1.0) if args.weights is None else args.weights.split(","),
            max_mass=args.max_mass,
        )
    except OptionsError as err:
        raise OptionError([f"--{option.replace('_', '-')}: {why}" for option, why in err.problems]) from err


def _write_balance(scene, args, report, series, files) -> int:
    """Write everything ``balance`` computed: the scene files, the plots, the report."""
    written = []
    for path, text in files:
        write(path, text)
        written.append(path)
    if args.plots:
        from linkage_sym.plotting.balance import shaking_force_polar, shaking_moment_curve

        out = Path(args.plots)
        out.mkdir(parents=True, exist_ok=True)
        stem = file_stem(scene)
        kind = scene.joint(scene.drivers[0].joint).type
        written.append(str(shaking_force_polar(series, out / f"{stem}_shaking_force_polar.png",
                                               title=scene.name, driver_kind=kind)))
        written.append(str(shaking_moment_curve(series, out / f"{stem}_shaking_moment.png",
                                                title=scene.name, driver_kind=kind)))
    text = json.dumps(report, indent=2 if args.pretty else None)
    if args.output in (None, "-"):
        sys.stdout.write(text + "\n")
    else:
        write(args.output, text + "\n")
        written.insert(0, args.output)
    for w in written:
        print(f"wrote {w}", file=sys.stderr if args.output in (None, "-") else sys.stdout)
    return 0


def cmd_balance(args) -> int:
    check_outputs(
        files=[("-o/--output", args.output), ("--balanced-scene", args.balanced_scene),
               ("--optimize", args.optimize)],
        folders=[("--plots", args.plots)],
    )
    scene = load(args.scene)
    from linkage_sym.output import check_run_memory

    check_run_memory(scene)  # a whole run of the sweep, before any of it is made
    options = _optimize_options(scene, args)
    kinds = {"P": "prismatic joint", "G": "gear mesh", "cam": "cam contact"}
    sliding = [f"{j.name} ({kinds.get(j.type, j.type)})" for j in scene.joints if j.type != "R"]
    if sliding and not args.optimize:
        raise OptionError(
            f"the derived balancing conditions cover hinged (R-joint only) linkages; "
            f"{scene.name!r} has other joints: {', '.join(sliding)}: use --optimize FILE "
            "for counterweights optimised on the force solver's shaking force and moment")
    for flag, given in (("--latex", args.latex), ("--balanced-scene", args.balanced_scene)):
        if sliding and given:
            raise OptionError(
                f"{flag}: needs the derived balance conditions, which cover hinged (R-joint) "
                f"linkages only; with other joints ({', '.join(sliding)}) only --optimize "
                "(and --plots) run")
    from linkage_sym.balancing.report import balance_document

    doc = balance_document(scene, latex=args.latex, optimize=options)
    files = []
    if args.balanced_scene:
        if doc.balanced_scene is None:
            raise BalanceError(doc.report["counterweights"]["error"])
        files.append((args.balanced_scene, json.dumps(doc.balanced_scene, indent=2) + "\n"))
    if args.optimize:
        files.append((args.optimize, json.dumps(doc.optimized_scene, indent=2) + "\n"))
    return _write_balance(scene, args, doc.report, doc.series, files)


def demo_balance(scene, stem, out) -> list:
    """Song and Wang's (1992) balancing of a hinged example: JSON and before/after plots."""
    from linkage_sym.balancing.report import balance_document
    from linkage_sym.plotting.balance import shaking_force_polar, shaking_moment_curve

    doc = balance_document(scene)
    path = out / f"{stem}_balance.json"
    path.write_text(json.dumps(doc.report) + "\n")
    return [
        path,
        shaking_force_polar(doc.series, out / f"{stem}_balance_force_polar.png", title=scene.name),
        shaking_moment_curve(doc.series, out / f"{stem}_balance_moment.png", title=scene.name),
    ]




def register(sub) -> None:
    """Add the ``balance`` command to the command line's subparsers."""
    b = sub.add_parser(
        "balance", help="derive balancing conditions of a hinged linkage (Song and Wang 1992)",
        description="Derive the shaking force and moment balance conditions of a hinged "
        "(R-joint only) linkage; with prismatic joints only --optimize (and --plots) run.")
    b.add_argument("scene", help="scene JSON file (R joints only, unless --optimize)")
    b.add_argument("-o", "--output", help="balance JSON file (default: standard output)")
    b.add_argument("--pretty", action="store_true", help="indent the JSON")
    b.add_argument("--latex", action="store_true", help="add the expressions as LaTeX")
    b.add_argument("--plots", metavar="DIR", help="write the shaking force polar plot and moment curve, before and after")
    b.add_argument("--balanced-scene", metavar="FILE", help="write the scene with force-balancing counterweights")
    b.add_argument("--optimize", metavar="FILE",
                   help="write the scene with optimised counterweights (also for linkages with sliders)")
    b.add_argument("--weights", default=None, metavar="F,M,T",
                   help="with --optimize: weights of RMS shaking force, moment, driving effort (default 1,1,1)")
    b.add_argument("--max-mass", type=float, default=None, metavar="KG",
                   help="with --optimize: bound on each counterweight's mass (kg)")
    b.add_argument("--links", default=None, metavar="L1,L2",
                   help="with --optimize: links that get a counterweight (default: every moving link)")
    b.set_defaults(func=cmd_balance)
