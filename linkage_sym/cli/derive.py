"""``linkage-sym derive``: the scene's equations derived with SymPy, as text (wrapped to the
terminal's width, :mod:`linkage_sym.symbolic.text`), LaTeX (with a TikZ figure of each vector
loop) or Markdown with MathJax math.

::

    linkage-sym derive SCENE.json [--latex [--standalone] [--symbols] [--no-figures]]
                                  [--markdown [--symbols]] [--numeric [--digits N|full]] [-o FILE]

With ``--numeric`` each number is printed correctly rounded to ``--digits`` significant digits
(:data:`linkage_sym.symbolic.numbers.DIGITS` by default; ``full``: the shortest decimal that
reads back as the scene's double), and the output says which.
"""

from __future__ import annotations

import argparse

from linkage_sym.cli.common import OptionError, check_outputs as _check_outputs, emit, load as _load

__all__ = ["cmd_derive", "register"]


def cmd_derive(args) -> int:
    from linkage_sym.symbolic import derive
    from linkage_sym.symbolic.numbers import DIGITS

    if args.latex and args.markdown:
        raise OptionError("--latex and --markdown write the same equations in two markups: "
                          "give one of them")
    if (args.standalone or args.no_figures) and not args.latex:
        raise OptionError("--standalone and --no-figures shape the LaTeX output: give --latex too")
    if args.symbols and not (args.latex or args.markdown):
        raise OptionError("--symbols adds a table of the symbols to the LaTeX or Markdown "
                          "output: give --latex or --markdown too")
    if args.digits is not None and not args.numeric:
        raise OptionError("--digits rounds the numbers that --numeric puts in place of the "
                          "parameters: give --numeric too")
    digits = DIGITS if args.digits is None else args.digits
    _check_outputs(files=[("-o/--output", args.output)])
    scene = _load(args.scene)
    eqs = derive(scene, symbolic=not args.numeric, forces=True)
    if args.latex:
        from linkage_sym.symbolic.latex import latex_document, standalone

        text = latex_document(eqs, symbols=args.symbols, figures=not args.no_figures,
                              digits=digits)
        if args.standalone:
            text = standalone(text, f"Equations of the mechanism {scene.name}")
    elif args.markdown:
        from linkage_sym.symbolic.markdown import markdown_document

        text = markdown_document(eqs, symbols=args.symbols, digits=digits)
    else:
        import shutil

        from linkage_sym.symbolic.text import plain_text

        text = plain_text(eqs, width=shutil.get_terminal_size((100, 24)).columns, digits=digits)
    emit(args.output, text)
    return 0


def _digits(text: str):
    """``--digits``: a whole number of significant digits, or ``full``."""
    from linkage_sym.symbolic.numbers import FULL, MAX_DIGITS, check_digits  # SymPy: on use

    if text == FULL:
        return FULL
    try:
        return check_digits(int(text))
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"a whole number from 1 to {MAX_DIGITS}, or '{FULL}'; got {text!r}") from None


def register(sub) -> None:
    """Add the ``derive`` command to the ``linkage-sym`` subparsers ``sub``."""
    v = sub.add_parser("derive", help="derive the scene's equations with SymPy (text, LaTeX or Markdown)")
    v.add_argument("scene", help="scene JSON file")
    v.add_argument("--latex", action="store_true", help="write a LaTeX fragment (notation of the textbook chapter 'Kinematic analysis of planar mechanisms')")
    v.add_argument("--markdown", action="store_true",
                   help="write the same equations as Markdown with MathJax math ($$ blocks), "
                   "for notebooks and documentation pages")
    v.add_argument("--numeric", action="store_true", help="the scene's numbers instead of parameter symbols")
    v.add_argument("--digits", type=_digits, metavar="N|full",
                   # the numbers of linkage_sym.symbolic.numbers (DIGITS, MAX_DIGITS, FULL; it
                   # imports SymPy, which the command line loads only when used: tested equal)
                   help="with --numeric: print each number correctly rounded to N significant "
                   "digits (1 to 17; default 6, and the output says so), or 'full': the "
                   "shortest decimal that reads back as the scene's number")
    v.add_argument("--standalone", action="store_true",
                   help="with --latex: a complete document (preamble, bibliography) instead of a fragment")
    v.add_argument("--symbols", action="store_true",
                   help="with --latex or --markdown: a table of every symbol with its meaning "
                   "and unit")
    v.add_argument("--no-figures", action="store_true",
                   help="with --latex: leave out the TikZ figure of each vector loop")
    v.add_argument("-o", "--output", help="output file (default: standard output)")
    v.set_defaults(func=cmd_derive)
