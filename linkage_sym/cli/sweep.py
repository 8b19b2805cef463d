"""``linkage-sym sweep``: many designs of one scene (registered by :func:`register`).

::

    linkage-sym sweep SCENE.json --list
    linkage-sym sweep SCENE.json (--vary NAME=LO:HI:N ... | --samples FILE.csv |
                                  --monte-carlo N --tolerance NAME=SIGMA ... [--random-state K])
                      [--metrics LIST] [--output-link LINK] [--trace POINT]
                      [-o OUT.parquet|OUT.csv|-] [--workers N] [--dask ADDRESS|local]
                      [--plots DIR] [--write-scenes DIR [--scene-rows LIST]]
                      [--chunk-designs N] [--backend numpy|numba]

Options are checked (and output paths tested) before anything is computed; a
problem is one line naming the option, exit status 2.
"""

from __future__ import annotations

import math
import sys

from linkage_sym.cli.common import OptionError, check_outputs, load, option_error

__all__ = ["register", "cmd_sweep"]


def register(sub) -> None:
    """Add the ``sweep`` command to the ``linkage-sym`` sub-parsers."""
    import argparse

    p = sub.add_parser(
        "sweep", help="evaluate many designs of a scene: a grid, samples or a Monte Carlo spread",
        description="Evaluate many designs of one scene: its named parameters (--list prints "
        "them) varied over a grid (--vary), read from a CSV file (--samples) or drawn about "
        "their values (--monte-carlo with --tolerance). One row per design: its parameters and "
        "the metrics. Each design is assembled at the scene's driver values in the scene's "
        "assembly mode; one that cannot be is marked (assemblable 0, its metrics empty). "
        "Every design is held to the rules of the scene fields its parameters fill (a mass or "
        "inertia >= 0, every number within 1e30 SI units, an angle within 1e6 degrees) and its "
        "lengths l_* must be > 0: a design that breaks one is not solved, the table's 'invalid' "
        "column gives the rule (its metrics empty), the summary counts the designs by rule, and "
        "--write-scenes writes no scene for it (nor for any design whose scene the scene reader "
        "refuses); when no design is valid (a --vary axis none of whose values is, say) the "
        "option is refused, naming the parameter. "
        "Scenes whose groups all have closed forms are evaluated many designs per call; "
        "groups without one (class-III triads, actuator groups) make the designs run one at "
        "a time, each by the numeric plan of its own scene.",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("scene", help="scene JSON file")
    p.add_argument("--list", action="store_true",
                   help="print the scene's parameters with their values and meanings, and stop")
    p.add_argument("--vary", action="append", metavar="NAME=LO:HI:N",
                   help="a grid axis: N values from LO to HI (or NAME=V1,V2,...); repeat for "
                   "more axes, the grid is their product")
    p.add_argument("--samples", metavar="FILE.csv",
                   help="designs from a CSV file: a header of parameter names, a row per design")
    p.add_argument("--monte-carlo", type=int, metavar="N",
                   help="N designs with the --tolerance parameters drawn from normal "
                   "distributions about the scene's values")
    p.add_argument("--tolerance", action="append", metavar="NAME=SIGMA",
                   help="standard deviation of a parameter for --monte-carlo (repeatable)")
    p.add_argument("--random-state", type=int, default=0, metavar="K",
                   help="state of the random generator of --monte-carlo (default 0): the same "
                   "K gives the same designs")
    p.add_argument("--metrics", metavar="LIST")  # its help: _metrics_help
    p.add_argument("--output-link", metavar="LINK",
                   help="the link whose limit positions give K and swing (default: the last "
                   "link pivoted on the ground that is not driven)")
    p.add_argument("--trace", action="append", metavar="POINT",
                   help="traced point of the path metric (repeatable; default all)")
    p.add_argument("-o", "--output", metavar="FILE",
                   help="the table: .parquet (pyarrow) or .csv; '-' writes CSV to standard "
                   "output; default: a summary only")
    p.add_argument("--workers", type=int, metavar="N",
                   help="local processes (default: this one); starting them costs about a "
                   "second, so below 5e6 designs x steps (about 14,000 four-bars of 361 steps) "
                   "one process is faster, and the sweep prints a note saying so")
    p.add_argument("--dask", metavar="ADDRESS",
                   help="send the chunks to a dask.distributed scheduler at ADDRESS; 'local' "
                   "starts a LocalCluster (of --workers processes), which pays only from 2.5e7 "
                   "designs x steps (about 70,000 four-bars of 361 steps; below, a note says "
                   "so); pip install 'linkage_sym[sweep]'")
    p.add_argument("--plots", metavar="DIR",
                   help="a map of each metric over the first two varied parameters (a grid), "
                   "or a histogram per metric (Monte Carlo, samples)")
    p.add_argument("--write-scenes", metavar="DIR",
                   help="write each design's own scene into DIR (design_<i>.json), to analyse it "
                   "alone; with --scene-rows only some")
    p.add_argument("--scene-rows", metavar="LIST",
                   help="the designs whose scenes --write-scenes writes: design numbers (the "
                   "table's 'design' column) and ranges, comma-separated: 0,5,17 or 10:20 (10 to "
                   "19, as Python slices) or :100 (the first 100); default every design")
    p.add_argument("--chunk-designs", type=int, metavar="N", help="designs per chunk")
    p.add_argument("--backend", choices=("numpy", "numba"), default="numpy",
                   help="numpy (default): arrays over designs x steps; numba: the generated "
                   "closed forms compiled, one loop over designs x steps (metrics assemblable, "
                   "grashof, K, min_transmission_deg of scenes of dyads; compiling takes a few "
                   "seconds once per run); pip install 'linkage_sym[numba]'")
    p.set_defaults(func=cmd_sweep)
    p.help_hook = _metrics_help


def _metrics_help(p) -> None:
    """The help's texts that name the metrics, filled when help is shown: building the
    parser imports nothing of the design package, the help only its list of names."""
    from linkage_sym.design.names import DEFAULT_METRICS, METRICS

    p.epilog = "metrics: " + ", ".join(METRICS) + " (definitions: linkage_sym.design.metrics)"
    for action in p._actions:
        if "--metrics" in action.option_strings:
            action.help = ("comma-separated metrics (default: those of "
                           f"{','.join(DEFAULT_METRICS)} the scene has)")


def cmd_sweep(args) -> int:
    from linkage_sym.design.errors import SweepError

    try:
        return _sweep(args)
    except SweepError as err:
        raise option_error(err, "sweep") from err


def _sweep(args) -> int:
    from linkage_sym.design.api import sweep
    from linkage_sym.design.execute import Execution
    from linkage_sym.design.parameters import MonteCarlo, parse_axis, parse_tolerance
    from linkage_sym.design.scenes import SceneFiles
    from linkage_sym.design.table import table_format
    from linkage_sym.output import check_run_memory

    if args.list:
        return _list_parameters(args.scene)
    if args.tolerance and args.monte_carlo is None:
        raise OptionError("--tolerance: used only with --monte-carlo N")
    given = [o for o, v in (("--vary", args.vary), ("--samples", args.samples),
                            ("--monte-carlo", args.monte_carlo)) if v is not None]
    if len(given) != 1:
        raise OptionError("--vary: give exactly one of --vary, --samples or --monte-carlo"
                          + (f" (got {', '.join(given)})" if given else " (or --list)"))
    check_outputs(files=[("-o/--output", args.output)],
                  folders=[("--plots", args.plots), ("--write-scenes", args.write_scenes)])
    if args.output not in (None, "-"):
        table_format(args.output)
    rows = None
    if args.scene_rows is not None:
        if args.write_scenes is None:
            raise OptionError("--scene-rows: used only with --write-scenes DIR")
        rows = parse_rows(args.scene_rows)
    if args.dask is not None:  # the extra's check, before the work
        _require_dask()
    if args.output not in (None, "-") and table_format(args.output) == "parquet":
        _require_pyarrow()
    scene = load(args.scene)
    check_run_memory(scene, "path", copies=4)  # the model, and a design along its path
    axes = _by_name(args.vary, parse_axis, "--vary")
    tol = _by_name(args.tolerance, parse_tolerance, "--tolerance")
    metrics = None
    if args.metrics:
        metrics = [m.strip() for m in args.metrics.split(",") if m.strip()]
    if args.monte_carlo is not None:
        designs = MonteCarlo(args.monte_carlo, tol, args.random_state)
    else:
        designs = axes if args.vary is not None else args.samples
    res = sweep(scene, designs, metrics, output=args.output_link, trace=args.trace,
                scenes=None if args.write_scenes is None else SceneFiles(args.write_scenes, rows),
                execution=Execution(args.workers, args.dask, args.chunk_designs, progress=True,
                                    backend=args.backend))
    out = sys.stdout if args.output != "-" else sys.stderr
    if args.output == "-":
        sys.stdout.write(res.to_csv())
    elif args.output:
        res.write(args.output)
    written = ([args.output] if args.output not in (None, "-") else [])
    if args.plots:
        from linkage_sym.design.plots import sweep_plots

        written += sweep_plots(res, args.plots, scene=scene)  # the unit of an effort
    for line in summary(res, scene):
        print(line, file=out)
    note = parallel_note(len(res), scene.steps, args.workers, args.dask)
    if note:
        print(note, file=out)
    if args.write_scenes:
        _print_scenes_written(res, args.write_scenes, out)
    for w in written:
        print(f"wrote {w}", file=out)
    return 0


def _list_parameters(path) -> int:
    """``--list``: the scene's parameters with their values and meanings."""
    from linkage_sym.design.api import scene_parameters
    from linkage_sym.output import check_run_memory

    scene = load(path)
    check_run_memory(scene, "none", copies=4)  # the model: the sweep and its path
    rows = scene_parameters(scene)
    w = max(len(n) for n, _, _ in rows)
    print(f"parameters of {scene.name!r} (SI units, angles in rad):")
    for n, v, meaning in rows:
        print(f"  {n:<{w}}  {v:< 14.8g}  {meaning}")
    return 0


def _print_scenes_written(res, folder, out) -> None:
    """``--write-scenes``: how many scenes were written, and which designs have none, why."""
    print(f"wrote {len(res.files)} design scene(s) into {folder}", file=out)
    if res.no_scene:
        shown = ", ".join(str(i) for i in res.no_scene[:10])
        more = f" and {len(res.no_scene) - 10} more" if len(res.no_scene) > 10 else ""
        print(f"  no scene for design(s) {shown}{more}: not assembled at the scene's driver "
              "values", file=out)
    if res.bad_scene:
        shown = ", ".join(str(i) for i, _ in res.bad_scene[:10])
        n = len(res.bad_scene)
        more = f" and {n - 10} more" if n > 10 else ""
        print(f"  no scene for design(s) {shown}{more}: the scene's rules refuse them "
              f"(design {res.bad_scene[0][0]}: {res.bad_scene[0][1]})", file=out)


def _by_name(texts, parse, option: str):
    """``{name: value}`` of an option given once per parameter (``parse`` reads one
    ``NAME=...``), ``None`` when it is not given; a name given twice is refused."""
    if not texts:
        return None
    out = {}
    for text in texts:
        name, value = parse(text)
        if name in out:
            raise OptionError(f"{option}: {name!r} given twice")
        out[name] = value
    return out


def parse_rows(text: str) -> list:
    """``--scene-rows``: design numbers and ranges ``A:B`` (A to B - 1; ``:B`` from 0),
    comma-separated; a range stays a ``range`` until the designs it names are checked
    (``0:99999999999999`` names more designs than any sweep has).

    Examples
    --------
    >>> parse_rows("0,5,17"), parse_rows(":3"), parse_rows("10:12,4")
    ([0, 5, 17], [range(0, 3)], [range(10, 12), 4])
    """
    out = []
    for part in text.split(","):
        part = part.strip()
        a, sep, b = part.partition(":")
        try:
            if sep:
                lo, hi = int(a) if a.strip() else 0, int(b)
                if hi <= lo:
                    raise OptionError(f"--scene-rows: {part!r}: an empty range (A:B is A to B - 1)")
                out.append(range(lo, hi))
            else:
                out.append(int(part))
        except ValueError:
            raise OptionError(f"--scene-rows: {part!r}: design numbers (0,5,17) or ranges (10:20, "
                              ":100) are expected") from None
    return out


def _require_dask():
    try:
        import dask.distributed  # noqa: F401
    except ImportError:
        raise OptionError("--dask: needs dask's distributed scheduler, which is not installed: "
                          "pip install 'linkage_sym[sweep]'") from None


def _require_pyarrow():
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        raise OptionError("-o/--output: a Parquet file needs pyarrow, which is not installed: "
                          "pip install 'linkage_sym[sweep]'") from None


def metric_unit(column: str, scene=None) -> str:
    """The unit a metric column's values are in (``""`` for a ratio or a count).

    Examples
    --------
    >>> import linkage_sym
    >>> scene = linkage_sym.load_example("slider_crank_offset")
    >>> [metric_unit(c, scene) for c in ("peak_driving_A", "peak_reaction_B", "K", "swing_deg")]
    ['N·m', 'N', '', '°']
    """
    kinds = {j.name: j.type for j in scene.joints} if scene is not None else {}
    for m in ("peak_driving_", "rms_driving_"):
        if column.startswith(m):
            joint = column[len(m):]
            return "N" if kinds.get(joint) == "P" else ("N·m" if joint in kinds else "N or N·m")
    if column.startswith("peak_reaction_") or column == "rms_shaking_force":
        return "N"
    if column == "rms_shaking_moment":
        return "N·m"
    if column.endswith("_deg"):
        return "°"
    if column.startswith("path_"):
        return "m"
    return ""


def summary(res, scene=None) -> list[str]:
    """What ``sweep`` prints: the designs, how many assemble, each metric's range (with its
    unit: efforts in N·m or N by their driver's joint, given the ``scene``)."""
    import numpy as np

    n = len(res)
    how = {"grid": "grid " + " x ".join(f"{k} {len(v)}" for k, v in res.axes),
           "monte-carlo": "Monte Carlo", "samples": "samples"}[res.kind]
    lines = [f"sweep of {res.scene!r}: {n} design(s) ({how})"]
    if res.one_at_a_time:
        lines.append(f"  one design at a time: the {', '.join(res.one_at_a_time)} of {res.scene!r} "
                     "has no closed form, so each design is solved by the numeric plan of its "
                     "own scene (Newton continuation from its assembly configuration)")
    if "invalid" in res.columns:
        bad = res["invalid"][res["invalid"] != ""]
        lines.append(f"  invalid by the scene's rules, not solved (their metrics empty): {len(bad)}")
        # counted by the broken rule, the value left out
        kinds, counts = np.unique([b.rpartition(", got ")[0] or b for b in bad],
                                  return_counts=True)
        for k, m in sorted(zip(kinds, counts), key=lambda t: -t[1]):
            lines.append(f"    {k}: {m}")
    if "assemblable" in res.columns:
        a = res["assemblable"]
        lines.append(f"  assembled at the scene's driver values: {int((a > 0).sum())}; every step "
                     f"ok: {int((a == 1).sum())}")
    paths = [c for c in res.metrics if c.startswith("path_")]
    for c in res.metrics:
        if c.startswith("path_") or c == "assemblable":
            continue
        v = res[c]
        if v.dtype.kind in "US":
            kinds, counts = np.unique(v[v != ""], return_counts=True)
            if not len(kinds):
                lines.append(f"  {c}: " + ("none: K has a value for every design" if c == "K_note"
                                           else "empty for every design"))
                continue
            lines.append(f"  {c}: " + ", ".join(f"{k} {m}" for k, m in zip(kinds, counts)))
            continue
        fin = v[np.isfinite(v)]
        if not len(fin):
            lines.append(f"  {c}: no value")
            continue
        i_lo, i_hi = int(np.nanargmin(np.where(np.isfinite(v), v, np.nan))), int(np.nanargmax(np.where(np.isfinite(v), v, np.nan)))
        extra = f" ({n - len(fin)} without a value)" if len(fin) < n else ""
        u = metric_unit(c, scene)
        u = "" if not u else (u if u == "°" else " " + u)
        lines.append(f"  {c}: {_g(fin.min())}{u} (design {i_lo}) .. {_g(fin.max())}{u} (design "
                     f"{i_hi}), mean {_g(fin.mean())}{u}{extra}")
    if paths:
        lines.append(f"  path: {len(paths) // 2} coordinates per point in the table")
    return lines


PARALLEL_MIN_ENTRIES = {"workers": 5_000_000, "dask": 25_000_000}
"""Designs x steps below which ``--workers N`` (N > 1) and ``--dask local`` cost more than
they save, and the command says so.  Measured on the shipped crank_rocker sweep (grids of
``l_AB`` x ``l_BC``, 361 steps) on a 2-core machine: the work is about 0.145 ms of CPU per
design (14.7 s for 102,400), starting the two worker processes about 1.1 s of CPU (each
imports NumPy and loads the compiled mechanism), a LocalCluster of two about 7.3 s
(scheduler, nannies, workers).  Halving the work pays for the start from about 15,000
designs (5.4e6 design-steps) with --workers 2 and 70,000 (2.5e7) with --dask local when both
cores are free: below, the processes cannot pay whatever the load.  Measured in wall time on
that machine while other jobs kept it busy (load 8 to 9), one process was faster up to
102,400 designs (65 s against 83 s with --workers 2, 150 s with --dask local) and --workers 2
faster at 409,600 (328 s against 395 s): busy cores move the crossover up, never down."""


def parallel_note(n_designs: int, steps: int, workers, dask) -> str:
    """The note ``sweep`` prints when its processes cost more than they save (see
    :data:`PARALLEL_MIN_ENTRIES`), or ``""``.

    Examples
    --------
    >>> parallel_note(100, 361, 2, None)[:60]
    'note: 100 designs x 361 steps = 36100 design-steps, fewer th'
    >>> parallel_note(100, 361, None, None), parallel_note(10**6, 361, 2, None)
    ('', '')
    """
    if dask == "local":
        size = f"of {workers} processes" if workers else "of a process per core"
        what, key = f"a dask LocalCluster {size}", "dask"
        option = "--dask local"
    elif dask is None and workers is not None and workers > 1:
        what, key, option = f"{workers} worker processes", "workers", f"--workers {workers}"
    else:
        return ""
    entries = n_designs * steps
    limit = PARALLEL_MIN_ENTRIES[key]
    if entries >= limit:
        return ""
    mant, exp = f"{limit:e}".split("e")
    return (f"note: {n_designs} designs x {steps} steps = {entries} design-steps, fewer than "
            f"{float(mant):g}e{int(exp)}: starting {what} costs more than it saves, and one process (without "
            f"{option}) is faster at this size")


def _g(x: float) -> str:
    return f"{x:.6g}" if math.isfinite(x) else "nan"
