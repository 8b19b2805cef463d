"""What every command of the command line shares (no command here).

The :class:`OptionError` every command raises for options it cannot use,
loading a scene file, checking every output path before anything is
computed (:func:`check_outputs`), writing a file the command was asked for,
and the file stem of a scene's plots.  The commands live in the modules of
:mod:`linkage_sym.cli` (one a command), each importing from here (not from
each other).
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

__all__ = ["BROKEN_PIPE", "EXIT_STATUS", "NO_STEP_ASSEMBLED", "OPTIONS", "COMMAND_POINTERS",
           "CommandParser", "OptionError", "option_of", "option_error", "error_text",
           "command_words", "load", "check_outputs",
           "write", "emit", "stem", "driver_kinds", "closed_streams_to_devnull"]

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


class CommandParser(argparse.ArgumentParser):
    """An argument parser whose help may name what only a library knows (the metrics of
    ``sweep``): ``help_hook(parser)``, when set, fills those texts the first time help is
    formatted, so that building the parser (``--version``, another command) imports no
    library.

    Examples
    --------
    >>> p = CommandParser(prog="x", add_help=False)
    >>> p.help_hook = lambda parser: setattr(parser, "epilog", "filled")
    >>> p.format_help().strip().splitlines()[-1]
    'filled'
    """

    help_hook = None

    def format_help(self) -> str:
        hook, self.help_hook = self.help_hook, None
        if hook is not None:
            hook(self)
        return super().format_help()


class OptionError(Exception):
    """Command-line options the command cannot use; each problem starts with the option's name."""

    def __init__(self, problems):
        self.problems = [problems] if isinstance(problems, str) else list(problems)
        super().__init__("; ".join(self.problems))


SWEEP_OPTIONS = {"parameters": "--vary", "output": "--output-link", "trace": "--trace",
                 "metrics": "--metrics", "chunk_designs": "--chunk-designs", "scene": "scene",
                 "rows": "--scene-rows", "workers": "--workers", "tolerance": "--tolerance",
                 "samples": "--samples", "monte_carlo": "--monte-carlo",
                 "random_state": "--random-state", "dask": "--dask", "path": "-o/--output",
                 "backend": "--backend"}
"""The parameters of :func:`linkage_sym.design.sweep` and the attributes of its
``MonteCarlo``, ``Execution`` and ``SceneFiles`` (the ``field`` of a ``SweepError``;
``path``: the table's file) and the options of ``sweep`` that fill them, named apart
(``parameters``: ``--vary``; ``rows``, of ``SceneFiles``: ``--scene-rows``).  A field's
first word is looked up (``parameters l_AB``: the axis ``l_AB`` of ``--vary``); a field not
listed is printed as it is (``parameters['l_AB']``)."""

ANALYZE_OPTIONS = {"format": "--format", "keep": "--plots", "path": "-o/--output",
                   "method": "--method", "disconnection": "--disconnection"}
"""The arguments of :func:`linkage_sym.output.write_sweep` (the ``field`` of an
``OutputError``: ``keep`` is the whole sweep kept for the plots) and of
:func:`linkage_sym.analyze`, and the options of ``analyze`` that fill them."""

ANIMATE_OPTIONS = {"path": "-o/--output", "frames": "--frames", "fps": "--fps", **{layer: f"--layers {layer}" for layer in (
    "velocity", "acceleration", "forces", "centres", "transmission")}}
"""The parameters of :func:`linkage_sym.plotting.animation.animate` and the options of
``animate`` that fill them (``path``: the file of ``-o``; a layer: its name in ``--layers``)."""

OPTIONS = {"sweep": SWEEP_OPTIONS, "analyze": ANALYZE_OPTIONS, "animate": ANIMATE_OPTIONS}
"""Each command whose options are not its library parameters with dashes: its table."""


COMMAND_POINTERS = {
    "parameters": "`linkage-sym sweep SCENE --list` prints them with their values",
    "analyze": "`linkage-sym analyze` solves one design",
    "builders": "'linkage-sym new'",
    "disconnections": "`linkage-sym structure` lists them",
}
"""What the command line says for each of the library's pointers
(:data:`linkage_sym.errors.POINTERS`: a function to call) in a message: its command."""


def command_words(text: str) -> str:
    """A library message with each of its pointers (:data:`linkage_sym.errors.POINTERS`)
    replaced by the command that does the same (:data:`COMMAND_POINTERS`).

    Examples
    --------
    >>> from linkage_sym.errors import POINTERS
    >>> command_words(f"unknown parameter 'l_XY' ({POINTERS['parameters']})")
    "unknown parameter 'l_XY' (`linkage-sym sweep SCENE --list` prints them with their values)"
    """
    from linkage_sym.errors import POINTERS

    for key, said in COMMAND_POINTERS.items():
        text = text.replace(POINTERS[key], said)
    return text


def option_of(field: str, command: str | None = None) -> str:
    """The option that fills the library's parameter ``field``: the command's table in
    :data:`OPTIONS`, else ``--`` and the field with dashes for underscores, an index kept
    after it.  The one place that maps what the library names to what a user types.

    Examples
    --------
    >>> option_of("swing_deg"), option_of("positions[1][2]"), option_of("max_mass")
    ('--swing-deg', '--positions [1][2]', '--max-mass')
    >>> option_of("parameters", "sweep"), option_of("parameters l_AB", "sweep")
    ('--vary', '--vary l_AB')
    >>> option_of("path", "sweep"), option_of("parameters['l_AB']", "sweep")
    ('-o/--output', "parameters['l_AB']")
    """
    if command in OPTIONS:
        table = OPTIONS[command]
        base, space, rest = field.partition(" ")
        return table[base] + space + rest if base in table else field
    base, _, index = field.partition("[")
    opt = "--" + base.replace("_", "-")
    return f"{opt} [{index}" if index else opt


def option_error(err, command: str | None = None) -> OptionError:
    """A library error about a command's parameters as the :class:`OptionError` that names
    the options: ``err.field`` and ``err.reason`` (``SweepError``, ``SynthesisError``,
    ``OutputError``, whose ``field`` may be None: the reason alone), or ``err.problems`` of
    ``(field, reason)`` (the balancing's ``OptionsError``).

    Examples
    --------
    >>> from linkage_sym.design.errors import SweepError
    >>> option_error(SweepError("parameters", "no parameter to vary"), "sweep").problems
    ['--vary: no parameter to vary']
    >>> from linkage_sym.output import OutputError
    >>> option_error(OutputError("not enough memory: ...", field="keep"), "analyze").problems
    ['--plots: not enough memory: ...']
    """
    if hasattr(err, "field"):
        if err.field is None:
            return OptionError(command_words(err.reason))
        return OptionError(f"{option_of(err.field, command)}: {command_words(err.reason)}")
    return OptionError([f"{option_of(field, command)}: {command_words(why)}"
                        for field, why in err.problems])


NUMERIC_METHOD_COMMANDS = frozenset({"analyze", "animate"})
"""The commands whose ``--method`` picks the dyad or the global method: a refusal of the
symbolic method by any other command names ``linkage-sym analyze``'s option instead."""


def error_text(err, command: str | None = None) -> str:
    """What the command line prints of a library error it does not turn into an
    :class:`OptionError` (an invalid scene, a balancing that cannot be met): its text, the
    parameter it names (``BalanceError.field``, ``SymbolicUnsupportedError.field``) given as
    the option.

    Examples
    --------
    >>> from linkage_sym.errors import BalanceError
    >>> error_text(BalanceError("no step could be assembled", field="optimize"), "balance")
    'cannot balance: --optimize: no step could be assembled'
    >>> from linkage_sym.errors import SymbolicUnsupportedError
    >>> error_text(SymbolicUnsupportedError([(1, "K", "cam")]), "analyze")[-50:]
    '; the numeric methods do (--method dyad or global)'
    >>> error_text(SymbolicUnsupportedError([(1, "K", "cam")]), "derive")[-56:]
    'methods do (linkage-sym analyze --method dyad or global)'
    """
    from linkage_sym.errors import BalanceError, SceneError, SymbolicUnsupportedError

    if isinstance(err, SymbolicUnsupportedError):  # the choice of method: analyze's option
        choice = f"{option_of(err.field)} dyad or global"
        if command not in NUMERIC_METHOD_COMMANDS:  # this command has no such option
            choice = f"linkage-sym analyze {choice}"
        return str(SceneError(err.problems_naming(choice)))
    field = getattr(err, "field", None) if isinstance(err, BalanceError) else None
    if field is None:
        return command_words(str(err))
    return f"cannot balance: {option_of(field, command)}: {command_words(err.reason)}"


def closed_streams_to_devnull() -> None:
    """Give a command started with standard output or error closed (``>&-``, ``2>&-``) a
    stream that discards what it writes, so that every command runs as with ``>/dev/null``.

    Python sets ``sys.stdout`` (``sys.stderr``) to None then, and the first write of any
    command raised AttributeError.  The closed descriptor is pointed at the null device too,
    so that no file a command opens can take its number (and a child process's output).
    Called once, by :func:`linkage_sym.cli.main`, before any command runs.
    """
    for fd, name in ((1, "stdout"), (2, "stderr")):
        if getattr(sys, name) is not None:
            continue
        try:
            os.fstat(fd)
        except OSError:  # closed: the null device takes its number
            null = os.open(os.devnull, os.O_WRONLY)
            if null != fd:
                os.dup2(null, fd)
                os.close(null)
            stream = open(fd, "w", closefd=False, errors="backslashreplace")
        else:  # open but not given to Python (a windowed interpreter): leave it alone
            stream = open(os.devnull, "w", errors="backslashreplace")
        setattr(sys, name, stream)


def load(path):
    from linkage_sym.scene import load_scene

    return load_scene(path)


def _first_existing(path: Path) -> Path:
    """``path`` or its nearest ancestor that exists (what a ``mkdir -p`` would start from)."""
    p = path.absolute()
    while not p.exists() and p != p.parent:
        p = p.parent
    return p


def _creatable(option: str, given: str, folder: Path) -> str | None:
    """Why ``folder`` cannot be created or written into, or None."""
    base = _first_existing(folder)
    if not base.is_dir():
        return f"{option}: {given!r}: {str(base)!r} is a file, not a folder"
    if not os.access(base, os.W_OK | os.X_OK):
        return f"{option}: {given!r}: cannot write in {str(base)!r}"
    return None


def check_outputs(files=(), folders=(), replaced: bool = False) -> None:
    """Refuse, before anything is computed or written, output paths that cannot be written.

    ``files``: ``(option, path)`` of files (``None`` = not asked; ``"-"`` = standard
    output); ``folders``: ``(option, path)`` of folders, created if needed;
    ``replaced``: the files are written under a temporary name that then replaces the
    one named (``analyze``), so a device or a named pipe there is refused rather than
    replaced (the other commands write through the path).
    An empty path is refused for files and folders alike (``Path("")`` is the current
    folder, where plots and scenes would have been written unasked).
    Raises :class:`OptionError` naming each option.
    """
    problems, seen = [], {}
    for option, given in files:
        if given is None or given == "-":
            continue
        if given == "":
            problems.append(f"{option}: an empty path; a file name is expected")
            continue
        p = Path(given)
        if p.is_dir():
            problems.append(f"{option}: {given!r} is a folder; a file name is expected")
            continue
        if replaced and p.exists() and not p.is_file():  # a device, a named pipe, a socket
            problems.append(f"{option}: {given!r} is not a regular file (a device, pipe or "
                            "socket): results are written to a new file that replaces the "
                            "one named; give a file name, or -o - and redirect standard output")
            continue
        if p.exists() and not os.access(p, os.W_OK):
            problems.append(f"{option}: {given!r} is not writable")
            continue
        why = _creatable(option, given, p.parent)
        if why:
            problems.append(why)
            continue
        key = os.path.normcase(os.path.abspath(p))
        if key in seen:
            problems.append(f"{option}: {given!r} is also the file of {seen[key]}")
        seen.setdefault(key, option)
    for option, given in folders:
        if given is None:
            continue
        if given == "":
            problems.append(f"{option}: an empty path; a folder name is expected")
            continue
        p = Path(given)
        if p.exists() and not p.is_dir():
            problems.append(f"{option}: {given!r} is a file; a folder is expected")
        elif p.is_dir() and not os.access(p, os.W_OK | os.X_OK):
            problems.append(f"{option}: cannot write in {given!r}")
        elif not p.exists():
            why = _creatable(option, given, p)
            if why:
                problems.append(why)
    if problems:
        raise OptionError(problems)


def write(path, text: str) -> None:
    """Write a file the command was asked for, creating its folder if needed."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)


def emit(output, text: str) -> None:
    """A command's text to standard output (``output`` None or ``"-"``) or to the file
    ``output``, which is then named on standard output."""
    if output in (None, "-"):
        sys.stdout.write(text)
    else:
        write(output, text)
        print(f"wrote {output}")


def driver_kinds(scene) -> dict:
    """Each driver's joint type, for :func:`~linkage_sym.output.stats.ranges_text`."""
    return {d.joint: scene.joint(d.joint).type for d in scene.drivers}


def stem(scene) -> str:
    """The scene's name made safe for a file name: the stem of every plot file."""
    from linkage_sym.plotting.style import file_stem

    return file_stem(scene, None)
