"""``linkage-sym analyze``: solve a scene's sweep, write the result, print a summary.

::

    linkage-sym analyze SCENE.json [-o RESULT.json | -o -] [--format json|csv|npz|parquet]
                        [--method dyad|global|symbolic] [--disconnection K] [--plots DIR]
                        [--precision double|DIGITS] [--extremes]

See :mod:`linkage_sym.cli` for what it writes; ``--precision`` and ``--extremes``
are read by :mod:`linkage_sym.cli.accuracy`.
"""

from __future__ import annotations

import argparse
import math
import sys

from linkage_sym.cli import accuracy as cli_accuracy
from linkage_sym.cli.common import EXIT_STATUS, NO_STEP_ASSEMBLED, OptionError, driver_kinds
from linkage_sym.cli.common import command_words, option_error
from linkage_sym.cli.common import check_outputs as _check_outputs, load as _load
from linkage_sym.errors import SceneError

__all__ = ["NO_STEP_ASSEMBLED", "cmd_analyze", "register", "summary"]


def _at(scene, peak) -> str:
    """``step i (A = 57°, ...)``: a peak's step with its driver values."""
    vals = []
    for name, q in peak.drivers.items():
        kind = scene.joint(name).type
        vals.append(f"{name} = {math.degrees(q):.4g}°" if kind == "R" else f"{name} = {q:.4g} m")
    return f"step {peak.step} ({', '.join(vals)})" if vals else f"step {peak.step}"



def summary(scene, analysis) -> list[str]:
    """The console summary of a sweep: statuses counted, peak efforts and loads, warnings.

    ``analysis``: an ``Analysis``, or the ``SweepStats`` of a sweep solved in
    chunks (``linkage_sym.output``).
    """
    from linkage_sym.numeric.results.result import UNASSEMBLABLE
    from linkage_sym.output import SweepStats
    from linkage_sym.output.stats import ranges_text

    stats = analysis if isinstance(analysis, SweepStats) else SweepStats.of(analysis)
    counts = {"ok": stats.counts.get("ok", 0), **stats.counts}
    lines = [f"{scene.name}: {stats.n_steps} steps: "
             + ", ".join(f"{n} {s}" for s, n in counts.items())
             + f" (stages {', '.join(stats.stages)})"]
    if stats.unassemblable.count:
        lines.append(ranges_text(UNASSEMBLABLE, stats.unassemblable, driver_kinds(scene)))
    if not stats.outputs:
        lines.append("the scene's outputs are empty: the result holds each step's status and "
                     "driver values only (the position stage ran to find which steps assemble)")
    if stats.has_forces:
        if "driving" in stats.outputs:
            for name, peak in stats.driving.items():
                if not peak:
                    continue
                what, unit = ("torque", "N·m") if scene.joint(name).type == "R" else ("force", "N")
                lines.append(f"peak driving {what} at {name}: {peak.value:.4g} {unit} at {_at(scene, peak)}")
        if "reactions" in stats.outputs and stats.reactions:
            best = None
            for name, peak in stats.reactions.items():
                if peak and (best is None or peak.value > best[1].value):
                    best = (name, peak)
            if best is not None:
                name, peak = best
                lines.append(f"largest reaction: {peak.value:.4g} N at joint {name}, {_at(scene, peak)}")
        if "frame" in stats.outputs:
            shaking = (scene.effects.inertia and scene.effects.gravity is None
                       and (not scene.effects.loads or not scene.loads))
            word = "shaking" if shaking else "frame"
            for label, peak, unit in ((f"{word} force", stats.frame_force, "N"),
                                      (f"{word} moment", stats.frame_moment, "N·m")):
                if peak:
                    lines.append(f"peak {label}: {peak.value:.4g} {unit} at {_at(scene, peak)}")
    if stats.work is not None:  # joint friction (contract part two)
        lines += _friction_lines(scene, stats.work)
    lines += [f"warning: {w}" for w in stats.warnings]
    return lines


def _friction_lines(scene, work) -> list[str]:
    """The summary's friction lines: the sweep's mean efficiency, the peak friction power."""
    eta = work.efficiency()
    if eta is None:
        line = (f"mean efficiency: none (the driver's work over the sweep's ok steps is "
                f"{work.work_in:.4g} J, not positive)")
    else:
        line = (f"mean efficiency over the sweep: {eta:.4g} (the driver's work with the friction "
                f"left out, {work.work_out:.4g} J, over its work with it, {work.work_in:.4g} J)")
    out = [line]
    if work.friction_peak:
        out.append(f"peak friction power: {work.friction_peak.value:.4g} W at "
                   f"{_at(scene, work.friction_peak)}")
    return out


def cmd_analyze(args) -> int:
    from linkage_sym import output

    fmt = _output_format(args)
    scene = _load(args.scene)
    # the whole run's peak (two copies of the driver values, the path, a chunk or, for
    # --plots, every step), before any of it is made
    output.check_run_memory(scene, "whole" if args.plots else "chunks", method=args.method,
                            fmt=fmt if args.output else None, copies=2)
    sweep = _sweep(scene, args)
    sweep, report = cli_accuracy.prepare(scene, sweep, args)  # --precision, --extremes
    to_stdout = args.output == "-"
    try:
        stats = output.write_sweep(
            sweep, None if to_stdout else args.output, fmt,
            indent=1 if args.pretty else None, stream=sys.stdout if to_stdout else None,
            progress=True, keep=bool(args.plots))
    except output.OutputError as err:
        raise option_error(err, "analyze") from err
    except (MemoryError, output.ChunkError) as err:
        what = "out of memory" if isinstance(err, MemoryError) else str(err)
        print(f"linkage-sym analyze: {what}; nothing written", file=sys.stderr)
        return 1
    notes = _print_result(scene, stats, report, args, to_stdout)
    if not stats.any_assembled:
        first = f" (step 0: {stats.first_message})" if stats.n_steps else ""
        print(f"linkage-sym: no step of the sweep could be assembled{first}"
              + ("; no plots written" if args.plots else ""), file=sys.stderr)
        return NO_STEP_ASSEMBLED
    if args.plots:
        from linkage_sym.plotting import plot_all

        written = plot_all(scene, stats.analysis, args.plots)
        print(f"wrote {len(written)} plots into {args.plots}:", file=notes)
        for path in written:
            print(f"  {path}", file=notes)
    return 0


def _output_format(args) -> str:
    """The result file's format, with -o, --format and --pretty checked together."""
    from linkage_sym import output

    _check_outputs(files=[("-o/--output", args.output)], folders=[("--plots", args.plots)],
                   replaced=True)
    try:
        fmt = output.output_format(args.output, args.format)
        problems = []
        if args.format is not None and args.output is None:
            problems.append("--format: needs -o FILE (without -o only the summary is printed)")
        if args.output == "-" and fmt in ("npz", "parquet"):
            problems.append(f"--format {fmt}: a binary file; give -o FILE, not standard output")
        if args.pretty and fmt != "json":
            problems.append(f"--pretty: indents JSON only, not {fmt}")
        if problems:
            raise OptionError(problems)
        if fmt == "parquet" and args.output is not None:
            output.require_pyarrow()
    except output.OutputError as err:
        raise option_error(err, "analyze") from err
    return fmt


def _sweep(scene, args):
    """The sweep to write, by the method asked for (--method, --disconnection)."""
    from linkage_sym import output
    from linkage_sym.numeric.plan import compile_plan

    if args.method == "symbolic":
        from linkage_sym.codegen.compile import compile_mechanism

        if args.disconnection is not None:
            print("note: --disconnection ignored by the symbolic method", file=sys.stderr)
        sweep = output.compiled_sweep(compile_mechanism(scene))
    else:
        try:
            plan = compile_plan(scene, args.disconnection)
        except SceneError as err:
            if args.disconnection is not None and all(
                    p.startswith("disconnection:") for p in err.problems):
                raise OptionError([f"--{command_words(p)}" for p in err.problems]) from err
            raise
        if args.disconnection is not None and not any(
            g.kind not in ("input", "dyad") for g in plan.decomposition.groups
        ):
            print("note: --disconnection ignored: the mechanism has no complex group", file=sys.stderr)
        sweep = output.plan_sweep(plan, args.method)
    return sweep


def _print_result(scene, stats, report, args, to_stdout: bool):
    """The warnings and summary: on standard error when the result goes to standard output,
    else on standard output; returns that stream (for the plots' notes)."""
    if to_stdout:  # the result for a pipe; what a person reads goes to standard error
        for w in stats.warnings:
            print(f"warning: {w}", file=sys.stderr)
        for line in report.lines():
            print(line, file=sys.stderr)
        notes = sys.stderr
    else:
        if args.output:
            print(f"wrote {args.output}")
        print("\n".join(summary(scene, stats) + report.lines()))
        if not args.output:
            print("(the result JSON: -o FILE, or -o - for standard output)")
        notes = sys.stdout
    return notes


def register(sub) -> None:
    """Add the ``analyze`` command to the ``linkage-sym`` subparsers ``sub``."""
    a = sub.add_parser(
        "analyze", help="solve a scene's sweep and write the result JSON",
        description="Solve a scene's sweep; write the result JSON (-o FILE, or -o - for "
        "standard output) and print a summary: statuses counted, peak driving efforts, the "
        "largest reaction, frame (shaking) force and moment peaks, warnings.",
        epilog=EXIT_STATUS, formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    a.add_argument("scene", help="scene JSON file")
    a.add_argument("-o", "--output", metavar="FILE",
                   help="result file (JSON unless --format or its suffix says otherwise); '-' "
                   "writes it to standard output (and the summary is left out); default: the "
                   "summary only")
    a.add_argument("--pretty", action="store_true", help="indent the JSON")
    a.add_argument(
        "--format", choices=("json", "csv", "npz", "parquet"), default=None,
        help="result file format (default: from the -o file's suffix, .csv .npz .parquet, "
        "else json): json is the contract's layout; csv one row per step with a column per "
        "number (joints.B.position.x ...); npz one array per column; parquet through pyarrow "
        "(pip install 'linkage_sym[parquet]'). Any length of sweep is solved and written "
        "in chunks of steps, in bounded memory",
    )
    a.add_argument(
        "--method",
        choices=("dyad", "global", "symbolic"),
        default="dyad",
        help="numeric solver with forces group by group (dyad, default) or as one sparse "
        "system (global); or the lambdified SymPy equations (symbolic)",
    )
    a.add_argument(
        "--disconnection",
        type=int,
        metavar="K",
        help="disconnection (Dang and Zhang's method) to use for complex groups (index in the list "
        "`linkage-sym structure` prints, from 0; default: the best-suited one)",
    )
    a.add_argument(
        "--plots",
        metavar="DIR",
        help="also write the sweep's pictures into DIR (motion diagrams, paths and coupler "
        "curves; driving effort, reaction hodographs and frame loads when forces ran); none "
        f"when no step could be assembled (exit {NO_STEP_ASSEMBLED})",
    )
    cli_accuracy.add_analyze_options(a)  # --precision, --extremes
    a.set_defaults(func=cmd_analyze)
