"""``linkage-sym synthesize motion``: four-bars and (inverted) slider-cranks through four or five
coupler poses (Burmester).

synthesize motion --poses P.json [--dyads N] [-o DIR] [--name NAME] [--steps N] [--speed W]
    P.json holds ``[[x, y, angle_deg], ...]`` (the coupler frame's origin, m, and
    angle, degrees).  Every four-bar from pairs of Burmester dyads, every
    slider-crank from a dyad and a coupler point whose positions lie on a line,
    every inverted slider-crank from a dyad and a fixed pivot a coupler line
    passes through in every pose, and every guide-slider from such a pivot (its
    block driven) and a coupler point on a line, is driven through the poses by
    the solver and classified; the table is printed, best first.  With -o:
    ``design-01.json`` ... (the coupler frame's origin the traced point P, the
    sweep from pose 1 to the last), ``designs.csv``, ``poses.png``
    (the best design in every pose) and ``burmester.png`` (the curves or points).
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

SHOWN = 20
"""Rows of the table printed (all are in the CSV)."""


def _read_poses(path):
    from linkage_sym.cli.common import OptionError
    from linkage_sym.synthesis.common import SynthesisError

    try:
        with open(path, encoding="utf-8") as fh:
            return json.load(fh, parse_int=float)
    except OSError as err:
        raise OptionError(f"--poses: cannot read {path!r}: {err.strerror}") from err
    except UnicodeDecodeError as err:
        raise SynthesisError("poses", f"{path!r} is not a text (UTF-8) JSON file") from None
    except json.JSONDecodeError as err:
        raise OptionError(f"--poses: {path!r} is not valid JSON: {err}") from err
    except RecursionError:
        raise SynthesisError("poses", f"{path!r} nests its arrays too deeply to be read") from None


def _cell(v) -> str:
    if isinstance(v, bool):
        return "yes" if v else "-"
    if isinstance(v, float):
        return f"{v:.4g}"
    return str(v)


def _print_table(rows) -> None:
    cols = ["design", "Ax", "Ay", "Dx", "Dy", "crank", "coupler", "rocker", "ground", "grashof",
            "branch", "circuit", "order", "dead_centre", "gamma_min_deg", "error"]
    shown = [[_cell(r[c]) for c in cols] for r in rows[:SHOWN]]
    widths = [max(len(c), *(len(s[i]) for s in shown)) for i, c in enumerate(cols)]
    print("  ".join(c.rjust(w) for c, w in zip(cols, widths)))
    for s in shown:
        print("  ".join(x.rjust(w) for x, w in zip(s, widths)))
    if len(rows) > SHOWN:
        print(f"... {len(rows) - SHOWN} more in designs.csv (-o DIR)")


def cmd_motion(args) -> int:
    """``linkage-sym synthesize motion``: print the designs' table; write them with ``-o``."""
    from linkage_sym.cli.common import check_outputs, option_error, write
    from linkage_sym.synthesis.common import SynthesisError
    from linkage_sym.synthesis.motion import motion_synthesis, table

    check_outputs(folders=[("-o/--output", args.output)] if args.output else [])
    try:
        poses = _read_poses(args.poses)
        result = motion_synthesis(poses, dyads=args.dyads, name=args.name, steps=args.steps,
                                  speed=args.speed)
    except SynthesisError as err:
        raise option_error(err) from err
    rows = table(result)
    n = len(result.poses)
    found = "Burmester point pairs" if n == 5 else "dyads sampled on the centre-point curve"
    free = sum(r["defect_free"] for r in rows)
    sliders = sum(r["linkage"] == "slider-crank" for r in rows)
    k = len(result.sliders)
    also = (f", {sliders} slider-cranks (from {k} coupler point{'s' if k > 1 else ''} on a line)"
            if result.sliders else "")
    guides = sum(r["linkage"] == "inverted slider-crank" for r in rows)
    both = sum(r["linkage"] == "guide-slider" for r in rows)
    k = len(result.guides)
    also += (f", {guides} inverted slider-cranks (from {k} fixed pivot{'s' if k > 1 else ''} on a "
             f"coupler line) and {both} guide-sliders" if result.guides else "")
    print(f"motion generation through {n} poses: {len(result.dyads)} {found}, "
          f"{len(rows) - sliders - guides - both} four-bars{also} ({free} without a defect), best "
          "first; "
          "error: "
          "the largest distance of the solver's coupler pose from a pose, in coupler lengths")
    _print_table(rows)
    if args.output:
        out = Path(args.output)
        for r, d in zip(rows, result.designs):
            write(out / f"{r['design']}.json", json.dumps(d.scene, indent=2) + "\n")
        with open(out / "designs.csv", "w", newline="", encoding="utf-8") as fh:
            w = csv.DictWriter(fh, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows({k: (v if not isinstance(v, float) or math.isfinite(v) else "")
                         for k, v in r.items()} for r in rows)
        from linkage_sym.plotting.burmester import plot_curves, plot_poses

        plot_poses(result, out / "poses.png")
        plot_curves(result, out / "burmester.png")
        print(f"wrote {len(rows)} scenes, designs.csv, poses.png and burmester.png to {out}")
    return 0


def add_motion(kinds) -> None:
    """Add ``motion`` to the ``synthesize`` command's kinds (``kinds``: its subparsers)."""
    p = kinds.add_parser("motion", help="four-bars and (inverted) slider-cranks through 4 or 5 "
                         "coupler poses (Burmester)")
    p.add_argument("--poses", required=True, metavar="P.json",
                   help="JSON list of 4 or 5 poses [x, y, angle_deg]: the coupler frame's origin "
                        "(m) and angle (deg)")
    p.add_argument("--dyads", type=int, default=12,
                   help="four poses: dyads sampled on the centre-point curve (default 12; every "
                        "ordered pair is a four-bar)")
    p.add_argument("--name", default="motion", help="the scenes' name stem (default motion)")
    p.add_argument("--steps", type=int, default=361,
                   help="steps of each scene's sweep, pose 1 to the last (default 361)")
    p.add_argument("--speed", type=float, default=1.0,
                   help="the crank's angular velocity, rad/s (default 1)")
    p.add_argument("-o", "--output", metavar="DIR",
                   help="folder for design-01.json ..., designs.csv, poses.png, burmester.png")
    p.set_defaults(func=cmd_motion)
