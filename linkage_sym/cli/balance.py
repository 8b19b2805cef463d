"""``linkage-sym balance``: Song and Wang's (1992) balancing conditions of a hinged linkage.

::

    linkage-sym balance SCENE.json [-o FILE | -o -] [--pretty] [--latex [FILE.tex]]
                        [--plots DIR] [--balanced-scene FILE] [--optimize FILE
                        [--weights F,M,T] [--max-mass KG] [--links L1,L2]]

derives the shaking force and moment balance conditions (hinged, R-joint only
linkages), the force-balancing counterweights and, with ``--optimize``,
counterweights optimised on the force solver's shaking force and moment (also
for linkages with sliders).  The console gets a summary (:func:`summary`:
the conditions, the counterweights, RMS shaking force and moment before and
after); the JSON document only with ``-o FILE`` (``-o -``: standard output,
then without the summary), assembled by
:func:`linkage_sym.balancing.report.balance_document`; this module reads the
options, writes the files and draws the plots.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

from linkage_sym.cli.common import OptionError, check_outputs, load, option_error, write
from linkage_sym.cli.common import stem as file_stem
from linkage_sym.errors import BalanceError

__all__ = ["cmd_balance", "register", "summary"]


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
        raise option_error(err) from err


def _latex_path(args) -> str | None:
    """The ``.tex`` file of ``--latex``: the file given, else beside ``-o FILE`` (None: not asked)."""
    if args.latex is None:
        return None
    if args.latex is not True:
        return args.latex
    if args.output in (None, "-"):
        raise OptionError("--latex: give its file (--latex FILE.tex), or -o FILE to write it "
                          "beside the JSON (FILE with the suffix .tex)")
    return str(Path(args.output).with_suffix(".tex"))


def _rms(values) -> float:
    """RMS over the steps that have a value (NaN where a step is not ok)."""
    import numpy as np

    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    return math.sqrt(float(np.mean(v * v))) if v.size else math.nan


def _weights(cws) -> str:
    return "; ".join(f"{c['link']} {c['mass']:.4g} kg at ({c['at'][0]:.4g}, {c['at'][1]:.4g}) m"
                     for c in cws) or "none"


def summary(report, series) -> list[str]:
    """The console summary of ``balance``: conditions, counterweights, RMS before and after.

    ``report`` and ``series``: those of a
    :class:`~linkage_sym.balancing.report.BalanceDocument`.
    """
    import numpy as np

    lines = [f"{report['scene']}: shaking force and moment balance (Song and Wang 1992)"]
    if report.get("conditions_derived", True):
        lines.append("force balance conditions (each = 0):")
        lines += [f"  {n}: {e}" for n, e in report["force_balance"]["conditions"].items()]
        lines.append("moment balance conditions (each = 0):")
        for expr, reason in zip(report["moment_balance_conditions"],
                                report["moment_balance_reasons"]):
            name, _, why = reason.partition(": ")
            lines.append(f"  {name}: {why}" if expr == name else f"  {name}: {expr}; {why}")
        cws = report["counterweights"]
        if isinstance(cws, dict):
            lines.append(f"no counterweights balance the force: {cws['error']}")
        else:
            lines.append(f"counterweights balancing the force: {_weights(cws)}")
    else:
        lines.append(f"conditions not derived: {report['reasons']['conditions']}")
    if "optimized" in report:
        opt = report["optimized"]
        lines.append(f"optimised counterweights: {_weights(opt['counterweights'])}")
    for what, unit, values in (
            ("force", "N", lambda s: np.hypot(s.force[:, 0], s.force[:, 1])),
            ("moment", "N·m", lambda s: s.moment)):
        lines.append(f"RMS shaking {what}: " + ", ".join(
            f"{_rms(values(s)):.4g} {unit} {s.label}" for s in series))
    notes = report.get("optimized", {}).get("notes", [])
    lines += [f"warning: optimisation: {n}" for n in notes]
    return lines


def _write_balance(scene, args, doc, files) -> int:
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
        written.append(str(shaking_force_polar(doc.series, out / f"{stem}_shaking_force_polar.png",
                                               title=scene.name, driver_kind=kind)))
        written.append(str(shaking_moment_curve(doc.series, out / f"{stem}_shaking_moment.png",
                                                title=scene.name, driver_kind=kind)))
    text = json.dumps(doc.report, indent=2 if args.pretty else None) + "\n"
    lines = summary(doc.report, doc.series)
    if args.output == "-":  # the JSON for a pipe; what a person reads goes to standard error
        sys.stdout.write(text)
        for w in written:
            print(f"wrote {w}", file=sys.stderr)
        for line in lines:
            if line.startswith("warning: "):
                print(line, file=sys.stderr)
        return 0
    if args.output is not None:
        write(args.output, text)
        written.insert(0, args.output)
    for w in written:
        print(f"wrote {w}")
    print("\n".join(lines))
    if args.output is None:
        print("(the balance JSON: -o FILE, or -o - for standard output)")
    return 0


def cmd_balance(args) -> int:
    latex = _latex_path(args)
    check_outputs(
        files=[("-o/--output", args.output), ("--balanced-scene", args.balanced_scene),
               ("--optimize", args.optimize), ("--latex", latex)],
        folders=[("--plots", args.plots)],
    )
    scene = load(args.scene)
    from linkage_sym.output import check_run_memory

    check_run_memory(scene)  # a whole run of the sweep, before any of it is made
    options = _optimize_options(scene, args)
    from linkage_sym.balancing.pins import JOINT_KINDS, non_hinged

    sliding = [f"{j.name} ({JOINT_KINDS.get(j.type, j.type)})" for _, j in non_hinged(scene)]
    if sliding and not args.optimize:
        raise OptionError(
            f"the derived balancing conditions cover hinged (R-joint only) linkages; "
            f"{scene.name!r} has other joints: {', '.join(sliding)}: use --optimize FILE "
            "for counterweights optimised on the force solver's shaking force and moment")
    for flag, given in (("--latex", latex), ("--balanced-scene", args.balanced_scene)):
        if sliding and given:
            raise OptionError(
                f"{flag}: needs the derived balance conditions, which cover hinged (R-joint) "
                f"linkages only; with other joints ({', '.join(sliding)}) only --optimize "
                "(and --plots) run")
    from linkage_sym.balancing.report import balance_document

    doc = balance_document(scene, latex=latex is not None, optimize=options)
    files = []
    if latex is not None:
        from linkage_sym.balancing.report import latex_fragment

        files.append((latex, latex_fragment(doc.report)))
    if args.balanced_scene:
        if doc.balanced_scene is None:
            raise BalanceError(doc.report["counterweights"]["error"])
        files.append((args.balanced_scene, json.dumps(doc.balanced_scene, indent=2) + "\n"))
    if args.optimize:
        files.append((args.optimize, json.dumps(doc.optimized_scene, indent=2) + "\n"))
    return _write_balance(scene, args, doc, files)


def register(sub) -> None:
    """Add the ``balance`` command to the command line's subparsers."""
    b = sub.add_parser(
        "balance", help="derive balancing conditions of a hinged linkage (Song and Wang 1992)",
        description="Derive the shaking force and moment balance conditions of a hinged "
        "(R-joint only) linkage and counterweights that balance its shaking force; with "
        "prismatic joints only --optimize (and --plots) run.  Prints a summary: the conditions, "
        "the counterweights, RMS shaking force and moment as given, force-balanced and "
        "optimised; the whole document as JSON only with -o.")
    b.add_argument("scene", help="scene JSON file (R joints only, unless --optimize)")
    b.add_argument("-o", "--output", metavar="FILE",
                   help="balance JSON file; '-' writes it to standard output (and the summary "
                   "is left out); default: the summary only")
    b.add_argument("--pretty", action="store_true", help="indent the JSON")
    b.add_argument("--latex", nargs="?", const=True, default=None, metavar="FILE.tex",
                   help="write the derived expressions (mass and acceleration parameters, "
                   "shaking moment, balance conditions) as a LaTeX fragment (amsmath) to "
                   "FILE.tex; without FILE beside -o FILE, with the suffix .tex; the JSON "
                   "also holds them, under 'latex'")
    b.add_argument("--plots", metavar="DIR", help="write the shaking force polar plot and moment curve, before and after")
    b.add_argument("--balanced-scene", metavar="FILE", help="write the scene with force-balancing counterweights")
    b.add_argument("--optimize", metavar="FILE",
                   help="write the scene with optimised counterweights (also for linkages with "
                   "sliders); a solver that did not converge is reported as a warning")
    b.add_argument("--weights", default=None, metavar="F,M,T",
                   help="with --optimize: weights of RMS shaking force, moment, driving effort (default 1,1,1)")
    b.add_argument("--max-mass", type=float, default=None, metavar="KG",
                   help="with --optimize: bound on each counterweight's mass (kg); default: "
                   "the mass of the counterweight's own link (a massless link: the mean mass "
                   "of the moving links, 1 kg if all are massless)")
    b.add_argument("--links", default=None, metavar="L1,L2",
                   help="with --optimize: links that get a counterweight (default: every moving link)")
    b.set_defaults(func=cmd_balance)
