"""The ``linkage-sym`` command line (also ``python -m linkage_sym``).

One module a command (``linkage_sym.cli.analyze`` with its ``.accuracy`` options,
``.derive``, ``.structure``, ``.demo`` with ``examples``, ``.synthesize`` with ``new``,
``.balance``, ``.centres``, ``.sweep``, ``.animate``, ``.view``), each with its ``register`` and ``cmd_*``,
reading options and printing; what they compute is the library's.  What they share
is in :mod:`linkage_sym.cli.common`, with the one mapping of the library's parameter
names to options.  This module builds the parser and runs the command; no command's
imports run until the command does, so ``--version`` and ``--help`` load no library
(``sweep --help`` only the metric names).

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
    ``--extremes`` locates the sweep's extremes (``linkage_sym.cli.accuracy``).
derive SCENE.json [--latex [--no-figures] | --markdown] [--numeric [--digits N|full]] [-o FILE]
    Derive the scene's equations with SymPy (loops, closed forms, velocity,
    acceleration and force equations) and print them as SymPy text (the positions as
    named steps, every line within the terminal's width), or with
    ``--latex`` as a LaTeX fragment in the notation of the textbook chapter
    "Kinematic analysis of planar mechanisms" (for ``\\input``
    in a document that loads amsmath; a TikZ figure of each vector loop
    unless ``--no-figures``), or with ``--markdown`` as Markdown with
    MathJax math.  ``--numeric`` puts the scene's numbers in place of the
    parameter symbols, each correctly rounded to ``--digits`` significant digits
    (default 6, said in the output; ``full``: the exact double's shortest decimal).
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
animate SCENE.json -o motion.gif|.mp4|.html [--frames N] [--fps F]
        [--layers velocity,acceleration,forces,centres,transmission]
        [--method dyad|global|symbolic]
    Solve the sweep and write the mechanism moving: the links, the paths
    growing, the layers asked for; a frame of a step that is not ``ok`` says
    so.  GIF by Pillow, MP4 by ffmpeg where it is found, HTML as one
    self-contained file.
view SCENE.json -o PAGE.html
    Write one self-contained HTML page (no network) that solves the mechanism in the
    browser with the equations the symbolic layer prints in JavaScript: play the sweep,
    drag a joint or type a length and the whole sweep is solved again, download the
    edited scene (``linkage_sym.page``).

simulate SCENE.json [-o RESULT.json | -o -] [--method LSODA|Radau|BDF] [--plots DIR]
    Integrate the motion of the machine driven by its motor (``drivers[i].motor``) from
    the scene's ``simulate`` section and write the steps at the sampled times, analysed
    as ``analyze`` analyses a step, with the periodic motion's mean speed and speed
    fluctuation; a progress bar follows long runs.
flywheel SCENE.json --fluctuation DELTA [-o FLYWHEEL.json | -o -] [--plots DIR]
    The moment of inertia to add to the driven link for a speed fluctuation of at most
    DELTA: the energy method's estimate, refined by simulation; both reported.

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

import os
import sys
from argparse import RawDescriptionHelpFormatter
from importlib import import_module

from linkage_sym._version import __version__
from linkage_sym.cli.common import BROKEN_PIPE, EXIT_STATUS, NO_STEP_ASSEMBLED, OptionError
from linkage_sym.cli.common import CommandParser, closed_streams_to_devnull, error_text
from linkage_sym.errors import BalanceError, SceneError

__all__ = ["BROKEN_PIPE", "EXIT_STATUS", "NO_STEP_ASSEMBLED", "build_parser", "main"]

# the command modules, in the order of the help's list
COMMANDS = ("analyze", "derive", "structure", "demo", "synthesize", "balance", "centres", "sweep",
            "animate", "view", "simulate", "flywheel")


def build_parser() -> CommandParser:
    """The ``linkage-sym`` parser: each command module's ``register`` adds its command."""
    p = CommandParser(
        prog="linkage-sym",
        description="Symbolic-numeric analysis of planar linkages.",
        epilog=EXIT_STATUS,
        formatter_class=RawDescriptionHelpFormatter,
    )
    p.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = p.add_subparsers(dest="command", required=True)
    for name in COMMANDS:
        import_module(f"linkage_sym.cli.{name}").register(sub)
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
        print(f"linkage-sym: {error_text(err, args.command)}", file=sys.stderr)
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

