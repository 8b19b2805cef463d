"""The ``linkage-sym`` command line (also ``python -m linkage_sym``).

Commands
--------
analyze SCENE.json [-o RESULT.json | -o -] [--format json|csv|npz|parquet]
        [--method dyad|global|symbolic] [--disconnection K] [--plots DIR]
        [--precision double|DIGITS] [--extremes]
    Solve the scene's sweep and write the result of the contract: kinematics,
    joint reactions, driver efforts and frame loads, as the scene asks; with
    ``--plots`` also its pictures.  The console gets a summary (statuses
    counted, peak driving efforts, the largest reaction, frame/shaking force
    and moment peaks, warnings); ``-o -`` writes the JSON to standard output
    instead.  ``--format`` (default: the file's suffix) writes the steps as
    columns instead (CSV, NumPy npz, Parquet); the sweep is solved and
    written in chunks of steps (``linkage_sym.output``), so memory does not
    grow with its length.  ``symbolic`` evaluates the SymPy-derived, lambdified equations
    (compiled once per topology and cached) instead of the numeric dyad
    solver.  The summary ends with the worst step's estimated accuracy;
    ``--precision DIGITS`` evaluates the derived equations in mpmath and
    ``--extremes`` locates the sweep's extremes (``linkage_sym.cli_accuracy``).
derive SCENE.json [--latex] [--numeric] [-o FILE]
    Derive the scene's equations with SymPy (loops, closed forms, velocity,
    acceleration and force equations) and print them as SymPy text, or with
    ``--latex`` as a LaTeX fragment in the notation of the textbook chapter
    "Kinematic analysis of planar mechanisms" (for ``\\input``
    in a document that loads amsmath).  ``--numeric`` puts the scene's
    numbers in place of the parameter symbols.
balance SCENE.json [-o BALANCE.json | -o -] [--latex [FILE.tex]] [--plots DIR]
        [--balanced-scene FILE] [--optimize FILE [--weights F,M,T] [--max-mass KG]
        [--links L1,L2]]
    Derive a hinged linkage's shaking moment in Song and Wang's (1992) mass and
    acceleration parameters, its shaking force and moment balance
    conditions, counterweights that balance the force, and the shaking
    force and moment over the sweep (from the lambdified modules).  The
    console gets a summary (the conditions, the counterweights, RMS shaking
    force and moment before and after); the JSON only with ``-o``.
    ``--latex`` writes the expressions as a LaTeX fragment (to FILE.tex, or
    beside ``-o`` with the suffix .tex);
    ``--plots`` writes the polar plot and the moment curve before and after
    balancing; ``--optimize`` writes the scene with counterweights that
    minimise a weighted sum of RMS shaking force, moment and driving effort
    (each counterweight at most its link's mass unless ``--max-mass``; a
    solver that did not converge is reported as a warning).
    The derived conditions cover hinged (R-joint only) linkages: for a scene
    with prismatic joints only ``--optimize`` (and ``--plots``) run, with
    series from the force solver.
structure SCENE.json
    Print the drivers and Assur groups in solving order, with the
    disconnection choices of class-III groups.
demo [-o DIR] [--example NAME]
    Analyse shipped examples and write motion diagrams, coupler curves,
    driving effort, joint-reaction hodographs, frame loads, and the shaking
    force and moment (the same motion with inertia as the only effect).
examples
    List the shipped example scenes.

Plot files are named after the scene's ``name`` (made safe for a path) in
every command.

Exit status (see ``EXIT_STATUS``): 0 done; 1 a write that failed although its
path was checked (disk full), or memory that ran out although the run was
estimated to fit (nothing written); 2 an invalid scene or option
(a message naming each offending field or option on standard error; nothing
is written, every output path is checked before anything is computed); 3
``analyze`` whose sweep has no step that could be assembled (the result file
is written, no plots); 141 standard output closed early (``| head``), quietly.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import sys
from pathlib import Path

import numpy as np

from linkage_sym import cli_accuracy, cli_balance, cli_centres
from linkage_sym._version import __version__
from linkage_sym.cli_common import OptionError, check_outputs as _check_outputs, load as _load
from linkage_sym.cli_common import closed_streams_to_devnull, emit, stem as _stem
from linkage_sym.errors import BalanceError, SceneError
from linkage_sym.synthesis import cli as synthesis_cli
from linkage_sym.design import cli as design_cli  # linkage-sym sweep

DEMO_EXAMPLES = ("crank_rocker", "shaper")

NO_STEP_ASSEMBLED = 3  # analyze: the result file is written, but no step could be assembled
BROKEN_PIPE = 141  # 128 + SIGPIPE, what a shell reports for `yes | head`

EXIT_STATUS = f"""\
exit status:
  0    done
  1    a file could not be written after all (e.g. disk full, or out of memory): the message
       says which; no partial file is left
  2    invalid scene or option: a message names each field or option; nothing is written
       (every output path is checked before anything is computed)
  {NO_STEP_ASSEMBLED}    analyze: no step of the sweep could be assembled; the result file is still
       written (-o), no plots
  {BROKEN_PIPE}  standard output closed early (e.g. | head): stops quietly
"""


# ------------------------------------------------------------------ analyze


def _at(scene, peak) -> str:
    """``step i (A = 57°, ...)``: a peak's step with its driver values."""
    vals = []
    for name, q in peak.drivers.items():
        kind = scene.joint(name).type
        vals.append(f"{name} = {np.degrees(q):.4g}°" if kind == "R" else f"{name} = {q:.4g} m")
    return f"step {peak.step} ({', '.join(vals)})" if vals else f"step {peak.step}"


def _kinds(scene) -> dict:
    """Each driver's joint type, for :func:`~linkage_sym.output.stats.ranges_text`."""
    return {d.joint: scene.joint(d.joint).type for d in scene.drivers}


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
        lines.append(ranges_text(UNASSEMBLABLE, stats.unassemblable, _kinds(scene)))
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
    lines += [f"warning: {w}" for w in stats.warnings]
    return lines


def cmd_analyze(args) -> int:
    from linkage_sym import output
    from linkage_sym.numeric.plan import compile_plan

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
        raise OptionError(err.problems) from err
    scene = _load(args.scene)
    # the whole run's peak (two copies of the driver values, the path, a chunk or, for
    # --plots, every step), before any of it is made
    output.check_run_memory(scene, "whole" if args.plots else "chunks", method=args.method,
                            fmt=fmt if args.output else None, copies=2)
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
                raise OptionError([f"--{p}" for p in err.problems]) from err
            raise
        if args.disconnection is not None and not any(
            g.kind not in ("input", "dyad") for g in plan.decomposition.groups
        ):
            print("note: --disconnection ignored: the mechanism has no complex group", file=sys.stderr)
        sweep = output.plan_sweep(plan, args.method)
    sweep, report = cli_accuracy.prepare(scene, sweep, args)  # --precision, --extremes
    to_stdout = args.output == "-"
    try:
        stats = output.write_sweep(
            sweep, None if to_stdout else args.output, fmt,
            indent=1 if args.pretty else None, stream=sys.stdout if to_stdout else None,
            progress=True, keep=bool(args.plots))
    except output.OutputError as err:
        raise OptionError(err.problems) from err
    except (MemoryError, output.ChunkError) as err:
        what = "out of memory" if isinstance(err, MemoryError) else str(err)
        print(f"linkage-sym analyze: {what}; nothing written", file=sys.stderr)
        return 1
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


# ------------------------------------------------------------------ derive


def _plain_text(eqs) -> str:
    """The derived equations as SymPy text, section by section."""
    out = [f"# mechanism {eqs.scene.name}", "", "## coordinates"]
    out += [f"x = {eqs.x}", f"q = {eqs.q}"]
    out += ["", "## loop equations (complex form = 0)"]
    out += [f"{j}: {v.complex()} = 0" for j, v in eqs.loops]
    if eqs.meshes:
        out += ["", "## gear meshes (rolling without slip = 0)"]
        out += [f"{j}: {e} = 0" for j, e in eqs.meshes]
    out += ["", "## position equations Phi = 0"] + [f"{e} = 0" for e in eqs.Phi]
    out += ["", "## closed forms"] + [f"{s} = {e}" for s, e in eqs.closed_forms]
    out += [f"group {g.index + 1} ({g.group.kind}): solved numerically for {g.x}"
            for g in eqs.groups if not g.closed]
    out += ["", "## velocity: A xd = B qd", f"xd = {eqs.xd}", f"A = {eqs.A}", f"B = {eqs.B}"]
    out += ["", "## acceleration: A xdd = acc_rhs", f"xdd = {eqs.xdd}", f"acc_rhs = {eqs.acc_rhs}"]
    if eqs.has_forces:
        out += ["", "## forces: A_g F_g = b_g - C_g F_later"]
        for g, (A, b, C, later) in zip(eqs.groups, eqs.force_blocks):
            out += [f"group {g.index + 1}: F_g = {g.forces}", f"  A_g = {A}", f"  b_g = {b}"]
            if later:
                out += [f"  C_g = {C}", f"  F_later = {later}"]
        out += ["", "## frame force x, y and moment about the origin"] + [str(e) for e in eqs.frame]
    if eqs.parameters:
        out += ["", "## parameters"]
        out += [f"{s}: {eqs.table.params[s.name].meaning}" for s in eqs.parameters]
    return "\n".join(out) + "\n"


def cmd_derive(args) -> int:
    from linkage_sym.symbolic import derive

    if (args.standalone or args.symbols) and not args.latex:
        raise OptionError("--standalone and --symbols shape the LaTeX output: give --latex too")
    _check_outputs(files=[("-o/--output", args.output)])
    scene = _load(args.scene)
    eqs = derive(scene, symbolic=not args.numeric, forces=True)
    if args.latex:
        from linkage_sym.symbolic.latex import latex_document, standalone

        text = latex_document(eqs, symbols=args.symbols)
        if args.standalone:
            text = standalone(text, f"Equations of the mechanism {scene.name}")
    else:
        text = _plain_text(eqs)
    emit(args.output, text)
    return 0


# ------------------------------------------------------------------ the others


def cmd_structure(args) -> int:
    from linkage_sym.structure import decompose, structure_report

    scene = _load(args.scene)
    print(structure_report(scene, decompose(scene)))
    return 0


def cmd_examples(args) -> int:
    from linkage_sym.examples import example_names, example_path

    for name in example_names():
        print(f"{name:28s} {example_path(name)}")
    return 0


def cmd_demo(args) -> int:
    from linkage_sym.examples import example_names, example_path

    names = args.example or list(DEMO_EXAMPLES)
    unknown = [n for n in names if n not in example_names()]
    if unknown:
        raise OptionError(f"--example: unknown {', '.join(map(repr, unknown))}; known examples: "
                          f"{', '.join(example_names())}")
    _check_outputs(folders=[("-o/--output", args.output)])
    from linkage_sym.model import Effects
    from linkage_sym.numeric.plan import compile_plan
    from linkage_sym.numeric.results.result import UNASSEMBLABLE
    from linkage_sym.output.stats import ranges_text, step_ranges
    from linkage_sym.plotting import frame_loads, plot_all

    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    for name in names:
        scene = _load(example_path(name))
        stem = _stem(scene)
        analysis = compile_plan(scene).run()
        result = out / f"{stem}_result.json"
        result.write_text(json.dumps(analysis.to_dict()) + "\n")
        files = plot_all(scene, analysis, out)
        # the shaking force and moment: the same motion with inertia as the only effect
        shaking_scene = dataclasses.replace(
            scene,
            effects=Effects(inertia=True, gravity=None, loads=False),
            outputs=("frame",),
        )
        shaking = compile_plan(shaking_scene).run()
        files.append(frame_loads(shaking_scene, shaking, out / f"{stem}_shaking.png"))
        n_ok = int(analysis.ok.sum())
        bad = step_ranges(analysis.status == UNASSEMBLABLE,
                          {k: d["q"] for k, d in analysis.drivers.items()})
        gaps = f" ({ranges_text(UNASSEMBLABLE, bad, _kinds(scene))})" if bad.count else ""
        print(f"{name}: {n_ok}/{analysis.n_steps} steps solved{gaps}; wrote")
        print(f"  {result}")
        for f in files:
            print(f"  {f}")
        if all(j.type == "R" for j in scene.joints):
            files = cli_balance.demo_balance(scene, stem, out)
            print(f"{name}: balancing conditions and force-balancing counterweights; wrote")
            for f in files:
                print(f"  {f}")
    print(f"demo output is in {out.resolve()}")
    return 0


# ------------------------------------------------------------------ parser and main


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="linkage-sym",
        description="Symbolic-numeric analysis of planar linkages.",
        epilog=EXIT_STATUS,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = p.add_subparsers(dest="command", required=True)
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
    v = sub.add_parser("derive", help="derive the scene's equations with SymPy (text or LaTeX)")
    v.add_argument("scene", help="scene JSON file")
    v.add_argument("--latex", action="store_true", help="write a LaTeX fragment (notation of the textbook chapter 'Kinematic analysis of planar mechanisms')")
    v.add_argument("--numeric", action="store_true", help="the scene's numbers instead of parameter symbols")
    v.add_argument("--standalone", action="store_true",
                   help="with --latex: a complete document (preamble, bibliography) instead of a fragment")
    v.add_argument("--symbols", action="store_true",
                   help="with --latex: a table of every symbol with its meaning and unit")
    v.add_argument("-o", "--output", help="output file (default: standard output)")
    v.set_defaults(func=cmd_derive)
    s = sub.add_parser("structure", help="print drivers and Assur groups in solving order")
    s.add_argument("scene", help="scene JSON file")
    s.set_defaults(func=cmd_structure)
    d = sub.add_parser("demo", help="analyse shipped examples and write plots")
    d.add_argument("-o", "--output", default="demo_out", metavar="DIR", help="output folder (default demo_out)")
    d.add_argument(
        "--example", action="append", metavar="NAME",
        help=f"example to run (repeatable; default {', '.join(DEMO_EXAMPLES)}; "
        "`linkage-sym examples` lists them)",
    )
    d.set_defaults(func=cmd_demo)
    e = sub.add_parser("examples", help="list the shipped example scenes")
    e.set_defaults(func=cmd_examples)
    synthesis_cli.register(sub)
    cli_balance.register(sub)
    cli_centres.register(sub)
    design_cli.register(sub)  # linkage-sym sweep
    return p


def _run(argv) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except OptionError as err:
        for problem in err.problems:
            print(f"linkage-sym {args.command}: {problem}", file=sys.stderr)
        return 2
    except (SceneError, BalanceError) as err:
        print(f"linkage-sym: {err}", file=sys.stderr)
        return 2
    except BrokenPipeError:
        raise
    except OSError as err:  # a write that failed although its path was checked (disk full ...)
        print(f"linkage-sym {args.command}: {err}", file=sys.stderr)
        return 1


def _stdout_to_devnull() -> None:
    """Point file descriptor 1 at /dev/null so that the interpreter's last flush cannot fail."""
    try:
        fd = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):  # a replaced stdout (tests): nothing to do
        return
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, fd)
    os.close(devnull)


def main(argv=None) -> int:
    """Run the command line; returns the exit status (see ``EXIT_STATUS``)."""
    closed_streams_to_devnull()  # started with >&- (sys.stdout None): output discarded
    for stream in (sys.stdout, sys.stderr):  # an ASCII-only terminal: ° and · escaped, not fatal
        if hasattr(stream, "reconfigure"):
            stream.reconfigure(errors="backslashreplace")
    try:
        code = _run(argv)
        sys.stdout.flush()  # a closed pipe shows here, not at interpreter exit
        return code
    except BrokenPipeError:  # `| head`: the reader has all it wants; stop as Unix tools do
        _stdout_to_devnull()
        return BROKEN_PIPE
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
