"""The ``new`` and ``synthesize`` commands of ``linkage-sym`` (registered by :func:`register`).

new fourbar --crank A --coupler B --rocker C --ground D [--crank-deg PHI]
        [--branch open|crossed] [--coupler-point U,V] -o SCENE.json
new slider-crank --crank A --coupler B [--offset E] [--crank-deg PHI] [--branch right|left] -o ...
new guide-bar --crank A --ground D [--crank-deg PHI] -o ...
    Write the scene of a linkage given by its dimensions (m): the crank's
    pivot at the origin, the frame along +x, the driver over a full turn.
synthesize crank-rocker --K K --rocker C --swing-deg PSI [--ground D | --crank A] [-o ...]
synthesize slider-crank --K K --stroke H [--offset E | --crank A] [-o ...]
synthesize guide-bar --K K --ground D [-o ...]
    Design by the stroke-time ratio K (the textbook section "Design of
    four-bar mechanisms", Sources [2] of the README): print the dimensions,
    the extreme-position angle and the minimum transmission angle with where
    it occurs; write the scene with -o.
synthesize coupler-positions --positions FILE.json [--pivots AX,AY,DX,DY] [-o ...]
    A four-bar through 2 or 3 given coupler positions ``[[Bx, By, Cx, Cy], ...]``.
synthesize motion --poses P.json [-o DIR]
    Four-bars through 4 or 5 coupler poses (Burmester theory):
    :mod:`linkage_sym.cli.synthesize_motion`.
synthesize function ... | synthesize path ...
    Function and path generation (:mod:`linkage_sym.cli.funcpath`).
synthesize equations [--latex] [-o FILE]
    The design equations, derived with SymPy, as text or a LaTeX fragment.

Every refusal names its option and exits with status 2; nothing is written.
"""

from __future__ import annotations

import argparse
import json
import sys


def _refuse(err):
    from linkage_sym.cli.common import option_error

    return option_error(err)


def _numbers(option: str, text: str | None, n: int, names: str):
    """``n`` comma-separated numbers of an option, or :class:`OptionError`."""
    from linkage_sym.cli.common import OptionError

    if text is None:
        return None
    try:
        values = [float(x) for x in text.split(",")]
    except ValueError:
        values = []
    if len(values) != n:
        raise OptionError(f"{option}: {n} comma-separated numbers {names} expected, got {text!r}")
    return values


def _emit(design, args, what: str) -> int:
    """Print the design and write its scene (``-o``); ``-o -`` writes the scene to standard output."""
    from linkage_sym.cli.common import write as _write
    from linkage_sym.synthesis.builders import describe

    to_stdout = args.output == "-"
    out = sys.stderr if to_stdout else sys.stdout
    print(what, file=out)
    for line in describe(design):
        print(f"  {line}", file=out)
    for note in design.notes:
        print(f"  note: {note}", file=out)
    text = json.dumps(design.scene, indent=2) + "\n"
    if to_stdout:
        sys.stdout.write(text)
    elif args.output:
        _write(args.output, text)
        print(f"wrote {args.output}")
    else:
        print("(the scene: -o FILE, or -o - for standard output)")
    return 0


def _sweep(args) -> dict:
    return {"name": args.name, "steps": args.steps, "speed": args.speed}


def cmd_new(args) -> int:
    """``linkage-sym new fourbar|slider-crank|guide-bar``."""
    from linkage_sym.synthesis.common import SynthesisError
    from linkage_sym.cli.common import check_outputs as _check_outputs
    from linkage_sym.synthesis import builders

    _check_outputs(files=[("-o/--output", args.output)])
    try:
        if args.kind == "fourbar":
            point = _numbers("--coupler-point", args.coupler_point, 2, "U,V")
            design = builders.fourbar(args.crank, args.coupler, args.rocker, args.ground,
                                      crank_deg=args.crank_deg, branch=args.branch,
                                      coupler_point=point, **_sweep(args))
        elif args.kind == "slider-crank":
            design = builders.slider_crank(args.crank, args.coupler, args.offset,
                                           crank_deg=args.crank_deg, branch=args.branch,
                                           **_sweep(args))
        else:
            design = builders.guide_bar(args.crank, args.ground, crank_deg=args.crank_deg,
                                        **_sweep(args))
    except SynthesisError as err:
        raise _refuse(err) from err
    return _emit(design, args, f"{args.kind} from its dimensions:")


_SOURCE = "textbook section 'Design of four-bar mechanisms' [2]"


def cmd_synthesize(args) -> int:
    """``linkage-sym synthesize crank-rocker|slider-crank|guide-bar|coupler-positions|equations``."""
    from linkage_sym.synthesis.common import SynthesisError
    from linkage_sym.cli.common import check_outputs as _check_outputs

    _check_outputs(files=[("-o/--output", args.output)])
    if args.kind == "equations":
        return _equations(args)
    from linkage_sym.synthesis import kratio, positions

    try:
        if args.kind == "crank-rocker":
            design = kratio.crank_rocker(args.K, args.rocker, args.swing_deg, ground=args.ground,
                                         crank=args.crank, **_sweep(args))
            what = f"crank-rocker by the stroke-time ratio K ({_SOURCE}):"
        elif args.kind == "slider-crank":
            design = kratio.slider_crank(args.K, args.stroke, offset=args.offset, crank=args.crank,
                                         **_sweep(args))
            what = f"offset slider-crank by the stroke-time ratio K ({_SOURCE}):"
        elif args.kind == "guide-bar":
            design = kratio.guide_bar(args.K, args.ground, **_sweep(args))
            what = f"guide-bar by the stroke-time ratio K ({_SOURCE}):"
        else:
            rows = _read_positions(args.positions)
            pivots = _numbers("--pivots", args.pivots, 4, "AX,AY,DX,DY")
            design = positions.coupler_positions(rows, pivots=pivots, **_sweep(args))
            n = len(rows)
            what = f"four-bar through {n} coupler positions ({_SOURCE}):"
    except SynthesisError as err:
        raise _refuse(err) from err
    if args.kind == "coupler-positions":
        angles = ", ".join(f"{x * 57.29577951308232:.6g}°" for x in design.extra["crank_angles"])
        p = design.extra["pivots"]
        design = _add_note(design, f"fixed pivots A = ({p[0]:.6g}, {p[1]:.6g}), D = ({p[2]:.6g}, "
                                   f"{p[3]:.6g}); crank angles at the positions {angles}")
    return _emit(design, args, what)


def _add_note(design, note):
    import dataclasses

    return dataclasses.replace(design, notes=(*design.notes, note))


def _read_positions(path):
    """The parsed JSON of the ``--positions`` file; every failure names the option.

    Integers are read as floats (``parse_int``), as the positions are: an
    integer of more than 4300 digits would otherwise stop ``json`` itself
    (Python's limit on converting such strings), and one beyond float64's range
    becomes ``inf``, refused with the position that holds it.
    """
    from linkage_sym.synthesis.common import SynthesisError
    from linkage_sym.cli.common import OptionError

    try:
        with open(path, encoding="utf-8") as fh:
            return json.load(fh, parse_int=float)
    except OSError as err:
        raise OptionError(f"--positions: cannot read {path!r}: {err.strerror}") from err
    except UnicodeDecodeError as err:
        raise SynthesisError("positions", f"{path!r} is not a text (UTF-8) JSON file: byte "
                                          f"{err.object[err.start]:#04x} at position {err.start}") from None
    except json.JSONDecodeError as err:
        raise OptionError(f"--positions: {path!r} is not valid JSON: {err}") from err
    except RecursionError:
        raise SynthesisError("positions", f"{path!r} nests its arrays too deeply to be read (positions "
                                          "are a list of 2 or 3 lists of 4 numbers)") from None


def _equations(args) -> int:
    from linkage_sym.cli.common import emit
    from linkage_sym.synthesis.equations import latex_document, plain_text

    text = latex_document() if args.latex else plain_text()
    emit(args.output, text)
    return 0


def _sweep_options(p) -> None:
    p.add_argument("--name", help="the scene's name (default: the linkage's kind)")
    p.add_argument("--steps", type=int, default=361, help="steps of the sweep (default 361)")
    p.add_argument("--speed", type=float, default=1.0,
                   help="the crank's angular velocity, rad/s (default 1)")


def _output(p, required=False) -> None:
    p.add_argument("-o", "--output", metavar="SCENE.json", required=required,
                   help="scene file to write ('-' for standard output)")


def register(sub) -> None:
    """Add the ``new`` and ``synthesize`` commands to the subparsers ``sub`` of ``linkage-sym``."""
    fmt = argparse.RawDescriptionHelpFormatter
    new = sub.add_parser("new", help="write the scene of a four-bar, slider-crank or guide-bar "
                         "from its dimensions", description="Write a valid scene from link lengths "
                         "(m): the crank's pivot A at the origin, the frame along +x, the driver on "
                         "A over a full turn from --crank-deg.", formatter_class=fmt)
    kinds = new.add_subparsers(dest="kind", required=True, metavar="KIND")
    f = kinds.add_parser("fourbar", help="four-bar A B C D (crank, coupler, rocker, ground)")
    f.add_argument("--crank", type=float, required=True, help="AB (m)")
    f.add_argument("--coupler", type=float, required=True, help="BC (m)")
    f.add_argument("--rocker", type=float, required=True, help="CD (m)")
    f.add_argument("--ground", type=float, required=True, help="AD (m); D = (AD, 0)")
    f.add_argument("--branch", choices=("open", "crossed"), default="open",
                   help="assembly mode: open puts C left of the line B->D (default), crossed its "
                   "mirror image")
    f.add_argument("--coupler-point", metavar="U,V",
                   help="a traced coupler point P: U along B->C, V to its left, from B (m)")
    s = kinds.add_parser("slider-crank", help="offset slider-crank (crank, connecting rod, offset)")
    s.add_argument("--crank", type=float, required=True, help="AB (m)")
    s.add_argument("--coupler", type=float, required=True, help="the connecting rod BC (m)")
    s.add_argument("--offset", type=float, default=0.0, help="the slider's line is y = E (m; "
                   "default 0)")
    s.add_argument("--branch", choices=("right", "left"), default="right",
                   help="slider at larger (right, default) or smaller x than the crank pin")
    g = kinds.add_parser("guide-bar", help="guide-bar: crank AB, block on B sliding along the "
                         "guide through D")
    g.add_argument("--crank", type=float, required=True, help="AB (m)")
    g.add_argument("--ground", type=float, required=True, help="AD (m); D = (AD, 0)")
    for p, default in ((f, "fourbar"), (s, "slider-crank"), (g, "guide-bar")):
        p.add_argument("--crank-deg", type=float, default=0.0,
                       help="crank angle of the assembly configuration from +x (deg, default 0)")
        _sweep_options(p)
        p.set_defaults(name=default)
        _output(p, required=True)
        p.set_defaults(func=cmd_new)

    syn = sub.add_parser("synthesize", help="design a linkage by the stroke-time ratio K or by "
                         "coupler positions", description="Design a linkage from a requirement "
                         f"({_SOURCE}); print its dimensions, the extreme-position angle and the "
                         "minimum transmission angle, and write its scene with -o.",
                         formatter_class=fmt)
    kinds = syn.add_subparsers(dest="kind", required=True, metavar="KIND")
    cr = kinds.add_parser("crank-rocker", help="crank-rocker from K, rocker length and swing")
    cr.add_argument("--K", type=float, required=True, help="stroke-time ratio (> 1)")
    cr.add_argument("--rocker", type=float, required=True, help="rocker length CD (m)")
    cr.add_argument("--swing-deg", type=float, required=True, help="rocker swing ψ (deg, 0..180)")
    one = cr.add_mutually_exclusive_group()
    one.add_argument("--ground", type=float, help="frame length AD (m)")
    one.add_argument("--crank", type=float, help="crank length AB (m)")
    sc = kinds.add_parser("slider-crank", help="offset slider-crank from K and the stroke")
    sc.add_argument("--K", type=float, required=True, help="stroke-time ratio (1 < K < 3)")
    sc.add_argument("--stroke", type=float, required=True, help="the slider's stroke H (m)")
    one = sc.add_mutually_exclusive_group()
    one.add_argument("--offset", type=float, help="offset e (m, not 0; the slider's line is y = e)")
    one.add_argument("--crank", type=float, help="crank length AB (m)")
    gb = kinds.add_parser("guide-bar", help="rocking guide-bar from K and the frame distance")
    gb.add_argument("--K", type=float, required=True, help="stroke-time ratio (> 1)")
    gb.add_argument("--ground", type=float, required=True, help="frame distance AD (m)")
    cp = kinds.add_parser("coupler-positions", help="four-bar through 2 or 3 coupler positions")
    cp.add_argument("--positions", required=True, metavar="FILE.json",
                    help="JSON list of 2 or 3 positions [Bx, By, Cx, Cy] (m)")
    cp.add_argument("--pivots", metavar="AX,AY,DX,DY",
                    help="the fixed pivots, for two positions (each on its perpendicular bisector)")
    for p, default in ((cr, "crank-rocker"), (sc, "slider-crank"), (gb, "guide-bar"),
                       (cp, "coupler-positions")):
        _sweep_options(p)
        p.set_defaults(name=default)
        _output(p)
        p.set_defaults(func=cmd_synthesize)
    from linkage_sym.cli.funcpath import add_kinds

    add_kinds(kinds, _sweep_options)
    eq = kinds.add_parser("equations", help="the design equations (SymPy), as text or LaTeX")
    eq.add_argument("--latex", action="store_true", help="a LaTeX fragment (needs amsmath)")
    eq.add_argument("-o", "--output", metavar="FILE", help="output file (default: standard output)")
    eq.set_defaults(func=cmd_synthesize)
    from linkage_sym.cli.synthesize_motion import add_motion

    add_motion(kinds)
