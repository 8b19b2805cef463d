"""``synthesize function`` and ``synthesize path`` (added to ``synthesize`` by :func:`add_kinds`).

synthesize function (--function EXPR | --table F.csv) --phi-range A0,A1 --psi-range B0,B1
        [--x-range X0,X1] [--precision-points N | --x-points X1,X2,...] [--ground D]
        [--plot ERR.png] [--error-csv ERR.csv] [-o SCENE.json]
    A four-bar generating y = f(x) by Freudenstein's equation; the structural
    error measured by the solver over the range.
synthesize path (--points PTS.json | --curve C.csv [--samples N]) [--crank-deg A1,A2,...]
        [--type four-bar|slider-crank] [--starts N] [--keep K] [--min-transmission-deg DEG]
        [--grashof-crank] [--random-state N] [-o DIR] [--csv T.csv] [--plot CURVES.png]
    Four-bars (or slider-cranks) whose coupler point passes through the points, best first.
"""

from __future__ import annotations

import csv
import json
import math
import sys


def _numbers(option, text, least=2, exact=None):
    from linkage_sym.cli.common import OptionError

    if text is None:
        return None
    try:
        values = [float(x) for x in text.split(",")]
    except ValueError:
        raise OptionError(f"{option}: comma-separated numbers expected, got {text!r}") from None
    if (exact is not None and len(values) != exact) or len(values) < least:
        raise OptionError(f"{option}: {exact or f'at least {least}'} numbers expected, got {text!r}")
    return values


def _read_csv(option, path):
    """Rows of numbers of a CSV file (a header row of words is skipped)."""
    import numpy as np  # the command's work, not its help

    from linkage_sym.cli.common import OptionError

    try:
        with open(path, encoding="utf-8", newline="") as fh:
            rows = [r for r in csv.reader(fh) if r and any(c.strip() for c in r)]
    except OSError as err:
        raise OptionError(f"{option}: cannot read {path!r}: {err.strerror}") from err
    out = []
    for k, r in enumerate(rows):
        try:
            out.append([float(c) for c in r[:2]])
        except ValueError:
            if k == 0:
                continue
            raise OptionError(f"{option}: row {k + 1} of {path!r} is not two numbers: {r}") from None
    if not out or any(len(r) != 2 for r in out):
        raise OptionError(f"{option}: {path!r} holds no rows of two numbers x, y")
    return np.array(out)


def cmd_function(args) -> int:
    """``linkage-sym synthesize function``."""
    import numpy as np  # the command's work, not its help

    from linkage_sym.cli.common import check_outputs, option_error, write
    from linkage_sym.synthesis.common import SynthesisError
    from linkage_sym.synthesis.expression import parse
    from linkage_sym.synthesis.function_gen import function_generator, structural_error, table_function

    check_outputs(files=[("-o/--output", args.output), ("--plot", args.plot),
                         ("--error-csv", args.error_csv)])
    try:
        if args.function is not None:
            f = parse(args.function)
            xr = _numbers("--x-range", args.x_range, exact=2)
            if xr is None:
                from linkage_sym.cli.common import OptionError
                raise OptionError("--x-range: the range of x is needed with --function")
        else:
            tab = _read_csv("--table", args.table)
            f = table_function(tab[:, 0], tab[:, 1])
            xr = _numbers("--x-range", args.x_range, exact=2) or [tab[0, 0], tab[-1, 0]]
        d = function_generator(f, xr, _numbers("--phi-range", args.phi_range, exact=2),
                               _numbers("--psi-range", args.psi_range, exact=2),
                               precision_points=args.precision_points, x_points=_numbers("--x-points", args.x_points, 3),
                               ground=args.ground, name=args.name, steps=args.steps,
                               speed=args.speed)
    except SynthesisError as err:
        raise option_error(err) from err
    x, err = structural_error(d, f)
    deg = np.degrees(err)
    ex = d.extra
    print(f"four-bar function generator (Freudenstein 1955), {len(ex['x_points'])} precision "
          f"points ({'exact' if len(ex['x_points']) == 3 else 'least squares'}):")
    for k, v in d.lengths.items():
        print(f"  {k:8s} {v:.9g} m")
    for note in d.notes[:1]:
        print(f"  {note}")
    print("  precision points x: " + ", ".join(f"{v:.6g}" for v in ex["x_points"]))
    bad = int(np.isnan(deg).sum())
    print(f"  structural error (solver, {len(x)} points): max |e| = {np.nanmax(np.abs(deg)):.6g}°"
          + (f"; {bad} points not solved (beyond reach or dead centre)" if bad else ""))
    if args.error_csv:
        lines = ["x,phi_deg,error_deg"] + [f"{a!r},{p!r},{e!r}" for a, p, e in
                                            zip(x, np.degrees(_phi(ex, x)), deg)]
        write(args.error_csv, "\n".join(lines) + "\n")
        print(f"wrote {args.error_csv}")
    if args.plot:
        from linkage_sym.plotting.synthesis_curves import save, structural_error_figure

        save(structural_error_figure(x, deg, ex["x_points"], f"structural error of {args.name}"),
             args.plot)
        print(f"wrote {args.plot}")
    if args.output:
        write(args.output, json.dumps(d.scene, indent=2) + "\n")
        print(f"wrote {args.output}")
    return 0


def _phi(ex, x):
    import numpy as np  # the command's work, not its help

    (x0, x1), (p0, p1) = ex["x_range"], ex["phi_range"]
    return np.radians(p0 + (x - x0) / (x1 - x0) * (p1 - p0))


def _targets(args):
    from linkage_sym.cli.common import OptionError

    if args.points is not None:
        try:
            with open(args.points, encoding="utf-8") as fh:
                return json.load(fh, parse_int=float)
        except OSError as err:
            raise OptionError(f"--points: cannot read {args.points!r}: {err.strerror}") from err
        except json.JSONDecodeError as err:
            raise OptionError(f"--points: {args.points!r} is not valid JSON: {err}") from err
    from linkage_sym.synthesis.path_gen import resample

    return resample(_read_csv("--curve", args.curve), args.samples).tolist()


TABLE_HEAD = ("design", "error_m", "error_per_coupler", "min_transmission_deg", "grashof",
              "crank_turns_fully", "defects", "exact")


def _rows(designs):
    return [(f"design-{k + 1:02d}", d.check.error, d.check.error / d.check.coupler,
             d.check.gamma_min_deg, d.check.grashof, d.check.full_turn, d.check.defects or "none",
             d.exact) for k, d in enumerate(designs)]


def cmd_path(args) -> int:
    """``linkage-sym synthesize path``."""
    from pathlib import Path

    from linkage_sym.cli.common import check_outputs, option_error, write
    from linkage_sym.synthesis.common import SynthesisError
    from linkage_sym.synthesis.path_gen import read_targets, synthesize_path

    check_outputs(files=[("--csv", args.csv), ("--plot", args.plot)],
                  folders=[("-o/--output", args.output)] if args.output else [])
    try:
        T = read_targets(_targets(args))
        designs = synthesize_path(T, _numbers("--crank-deg", args.crank_deg, 3), starts=args.starts,
                                  keep=args.keep, min_transmission_deg=args.min_transmission_deg,
                                  full_turn=args.grashof_crank, random_state=args.random_state,
                                  name=args.name, steps=args.steps, linkage=args.type)
    except SynthesisError as err:
        raise option_error(err) from err
    how = "exact (three points)" if len(T) == 3 else "optimisation"
    if args.type == "slider-crank":
        how = ("exact" if designs and designs[0].exact else "best fit") + (
            " (three points)" if len(T) == 3 else " (optimisation)")
    print(f"{'' if args.type == 'four-bar' else args.type + ' '}path generation through "
          f"{len(T)} points, {how}: {len(designs)} designs without a defect (solver-checked)")
    print("  " + "  ".join(f"{h:>12s}" for h in TABLE_HEAD[:5]))
    for r in _rows(designs):
        print(f"  {r[0]:>12s}  {r[1]:12.4g}  {r[2]:12.4g}  {r[3]:12.2f}  {r[4]:>12s}")
    if not designs:
        print("  none meets the constraints: more starts, a smaller minimum transmission angle, "
              "or no full-turn requirement", file=sys.stderr)
    if args.csv:
        lines = [",".join(TABLE_HEAD)] + [",".join(repr(v) if isinstance(v, float) else str(v)
                                                   for v in r) for r in _rows(designs)]
        write(args.csv, "\n".join(lines) + "\n")
        print(f"wrote {args.csv}")
    if args.output:
        folder = Path(args.output)
        folder.mkdir(parents=True, exist_ok=True)
        for k, d in enumerate(designs):
            write(folder / f"design-{k + 1:02d}.json", json.dumps(d.scene, indent=2) + "\n")
        print(f"wrote {len(designs)} scenes to {args.output}")
    if args.plot:
        _plot(args.plot, T, designs)
    return 0 if designs else 1


def _plot(path, T, designs):
    from linkage_sym.plotting.synthesis_curves import coupler_curves_figure, save
    from linkage_sym.synthesis.path_check import curves

    rows = []
    for k, d in enumerate(designs[:6]):
        full, motion, joints = curves(d.scene, d.thetas)
        rows.append((f"design-{k + 1:02d} (error {d.check.error:.2g} m)", full, motion, joints))
    save(coupler_curves_figure(T, rows, f"coupler curves through {len(T)} targets"), path)
    print(f"wrote {path}")


def add_kinds(kinds, sweep_options) -> None:
    """Add ``function`` and ``path`` to the ``synthesize`` command's subparsers ``kinds``."""
    fn = kinds.add_parser("function", help="four-bar generating y = f(x) (Freudenstein)")
    src = fn.add_mutually_exclusive_group(required=True)
    src.add_argument("--function", help="f as an expression of x (numbers, + - * / **, pi, e, "
                     "sin cos tan exp log log10 sqrt ...), e.g. 'log10(x)'")
    src.add_argument("--table", metavar="F.csv", help="f as a table of rows x, y (interpolated)")
    fn.add_argument("--x-range", metavar="X0,X1", help="range of x (default with --table: the table's)")
    fn.add_argument("--phi-range", metavar="A0,A1", required=True,
                    help="crank angles at x0 and x1 (deg from +x)")
    fn.add_argument("--psi-range", metavar="B0,B1", required=True,
                    help="rocker angles at f(x0) and f(x1) (deg from +x)")
    fn.add_argument("--precision-points", type=int, default=3,
                    help="Chebyshev-spaced points (3 exact, more least squares; default 3)")
    fn.add_argument("--x-points", metavar="X1,X2,...", help="the precision points' x instead")
    fn.add_argument("--ground", type=float, default=1.0, help="frame AD (m, default 1)")
    fn.add_argument("--plot", metavar="ERR.png", help="plot of the structural error")
    fn.add_argument("--error-csv", metavar="ERR.csv", help="the structural error as CSV")
    fn.add_argument("-o", "--output", metavar="SCENE.json", help="scene file to write")
    sweep_options(fn)
    fn.set_defaults(name="function-generator", func=cmd_function)
    pa = kinds.add_parser("path", help="four-bars (or slider-cranks) whose coupler point passes "
                          "through points")
    src = pa.add_mutually_exclusive_group(required=True)
    src.add_argument("--points", metavar="PTS.json", help="JSON list of points [x, y] (m)")
    src.add_argument("--curve", metavar="C.csv", help="a drawn curve, rows x, y (resampled)")
    pa.add_argument("--samples", type=int, default=8, help="points taken along --curve (default 8)")
    pa.add_argument("--crank-deg", metavar="A1,A2,...", help="the crank's angle at each point "
                    "(deg; only differences count): prescribed timing")
    pa.add_argument("--type", choices=("four-bar", "slider-crank"), default="four-bar",
                    help="the linkage: four-bar (default) or slider-crank (offset and guide "
                    "direction free)")
    pa.add_argument("--starts", type=int, default=4000, help="random linkages (default 4000)")
    pa.add_argument("--keep", type=int, default=5, help="designs kept at most (default 5)")
    pa.add_argument("--min-transmission-deg", type=float, default=20.0,
                    help="smallest transmission angle between the points (deg, default 20)")
    pa.add_argument("--grashof-crank", action="store_true", help="a crank that turns fully only")
    pa.add_argument("--random-state", type=int, default=0, help="the random generator's state")
    pa.add_argument("-o", "--output", metavar="DIR", help="folder for design-01.json ...")
    pa.add_argument("--csv", metavar="T.csv", help="the table of designs as CSV")
    pa.add_argument("--plot", metavar="CURVES.png", help="the coupler curves through the targets")
    sweep_options(pa)
    pa.set_defaults(name="path-generator", func=cmd_path)
