"""The ``linkage-sym`` command line (also ``python -m linkage_sym``).

Commands
--------
analyze SCENE.json -o RESULT.json [--method dyad|global|symbolic] [--disconnection K]
        [--plots DIR]
    Solve the scene's sweep and write the result of the contract: kinematics,
    joint reactions, driver efforts and frame loads, as the scene asks; with
    ``--plots`` also its pictures.
    ``symbolic`` evaluates the SymPy-derived, lambdified equations (compiled
    once per topology and cached) instead of the numeric dyad solver.
derive SCENE.json [--latex] [--numeric] [-o FILE]
    Derive the scene's equations with SymPy (loops, closed forms, velocity,
    acceleration and force equations) and print them as SymPy text, or with
    ``--latex`` as a LaTeX fragment in seed 003's notation (for ``\\input``
    in a document that loads amsmath).  ``--numeric`` puts the scene's
    numbers in place of the parameter symbols.
balance SCENE.json -o BALANCE.json [--latex] [--plots DIR] [--balanced-scene FILE]
        [--optimize FILE [--weights F,M,T] [--max-mass KG] [--links L1,L2]]
    Derive a hinged linkage's shaking moment in seed 002's mass and
    acceleration parameters, its shaking force and moment balance
    conditions, counterweights that balance the force, and the shaking
    force and moment over the sweep (from the lambdified modules);
    ``--plots`` writes the polar plot and the moment curve before and after
    balancing; ``--optimize`` writes the scene with counterweights that
    minimise a weighted sum of RMS shaking force, moment and driving effort.
    A scene with prismatic joints has no module: it is refused, unless
    ``--optimize`` is given, which then runs alone (series from the force
    solver).
structure SCENE.json
    Print the drivers and Assur groups in solving order, with the
    disconnection choices of class-III groups.
demo [-o DIR] [--example NAME]
    Analyse shipped examples and write motion diagrams, coupler curves,
    driving effort, joint-reaction hodographs, frame loads, and the shaking
    force and moment (the same motion with inertia as the only effect).
examples
    List the shipped example scenes.

An invalid scene exits with status 2, a message naming each offending field
on standard error, and writes nothing.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
from pathlib import Path

from linkage_sym.errors import BalanceError, SceneError

DEMO_EXAMPLES = ("crank_rocker", "shaper")


def _load(path):
    from linkage_sym.scene import load_scene

    return load_scene(path)


def _write(path, text: str) -> None:
    """Write a file the command was asked for, creating its folder if needed."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)


def cmd_analyze(args) -> int:
    from linkage_sym.numeric.plan import compile_plan

    scene = _load(args.scene)
    if args.method == "symbolic":
        from linkage_sym.codegen.compile import compile_mechanism

        if args.disconnection is not None:
            print("note: --disconnection ignored by the symbolic method", file=sys.stderr)
        analysis = compile_mechanism(scene).run()
    else:
        plan = compile_plan(scene, args.disconnection)
        if args.disconnection is not None and not any(
            g.kind not in ("input", "dyad") for g in plan.decomposition.groups
        ):
            print("note: --disconnection ignored: the mechanism has no complex group", file=sys.stderr)
        analysis = plan.run(method=args.method)
    result = analysis.to_dict()
    for w in result.get("warnings", []):
        print(f"warning: {w}", file=sys.stderr)
    text = json.dumps(result, indent=1 if args.pretty else None)
    if args.output in (None, "-"):
        print(text)
    else:
        _write(args.output, text + "\n")
        n_bad = sum(s["status"] != "ok" for s in result["steps"])
        print(
            f"wrote {args.output}: {len(result['steps'])} steps, stages {', '.join(result['stages'])}"
            + (f", {n_bad} steps not ok (see their 'message')" if n_bad else "")
        )
    if args.plots:
        from linkage_sym.plotting import plot_all

        written = plot_all(scene, analysis, args.plots)
        # the JSON may be on standard output: the list of pictures goes beside it
        to = sys.stderr if args.output in (None, "-") else sys.stdout
        print(f"wrote {len(written)} plots into {args.plots}:", file=to)
        for path in written:
            print(f"  {path}", file=to)
    return 0


def _plain_text(eqs) -> str:
    """The derived equations as SymPy text, section by section."""
    out = [f"# mechanism {eqs.scene.name}", "", "## coordinates"]
    out += [f"x = {eqs.x}", f"q = {eqs.q}"]
    out += ["", "## loop equations (complex form = 0)"]
    out += [f"{j}: {v.complex()} = 0" for j, v in eqs.loops]
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

    scene = _load(args.scene)
    eqs = derive(scene, symbolic=not args.numeric, forces=True)
    if args.latex:
        from linkage_sym.symbolic.latex import latex_document

        text = latex_document(eqs)
    else:
        text = _plain_text(eqs)
    if args.output in (None, "-"):
        sys.stdout.write(text)
    else:
        _write(args.output, text)
        print(f"wrote {args.output}")
    return 0


def _optimize_options(scene, args) -> tuple:
    """``(weights, links)`` of ``--optimize``, checked before anything is computed or written."""
    try:
        weights = tuple(float(w) for w in args.weights.split(","))
    except ValueError:
        weights = ()
    problems = []
    if len(weights) != 3 or not all(w >= 0 for w in weights) or not any(w > 0 for w in weights):
        problems.append(f"--weights: three numbers F,M,T >= 0, not all 0, expected; got {args.weights!r}")
    links = None
    if args.links:
        links = [n.strip() for n in args.links.split(",")]
        bad = [n for n in links if n not in scene.link_names]
        if bad:
            problems.append(f"--links: {', '.join(map(repr, bad))} not among the moving links "
                            f"{', '.join(scene.link_names)}")
        elif len(set(links)) != len(links):
            problems.append(f"--links: a link is listed twice in {args.links!r}")
    if args.max_mass is not None and not args.max_mass >= 0:
        problems.append(f"--max-mass: a mass >= 0 expected, got {args.max_mass!r}")
    if problems:
        raise SceneError(problems)
    return weights, links


def _optimize(scene, args, weights, links) -> tuple:
    """Run ``--optimize``: the JSON section, and the optimised scene's shaking series (solver)."""
    from linkage_sym.balancing.optimize import optimize_counterweights
    from linkage_sym.balancing.series import solver_series

    try:
        res = optimize_counterweights(scene, links=links, weights=weights, max_mass=args.max_mass)
    except ValueError as err:  # what the optimiser refuses (e.g. no ok step): a clear exit 2
        raise BalanceError(f"--optimize: {err}") from err
    _write(args.optimize, json.dumps(res.scene, indent=2) + "\n")
    after = solver_series(_load_dict(res.scene), label="optimised")
    section = {
        "weights": list(weights), "links": list(links or scene.link_names),
        "objective_start": res.objective_start, "objective": res.objective,
        "rms_start": res.rms_start, "rms_final": res.rms_final, "message": res.message,
        "counterweights": [{"link": c.link, "mass": c.mass, "at": list(c.at)} for c in res.counterweights],
    }
    return section, after


def _load_dict(d):
    from linkage_sym.scene import load_scene

    return load_scene(d)


def _balance_sliding(scene, args) -> int:
    """``balance --optimize`` for a scene with prismatic joints: no module, optimisation only."""
    from linkage_sym.balancing.model import require_hinged
    from linkage_sym.balancing.series import solver_series

    for flag, given in (("--latex", args.latex), ("--balanced-scene", args.balanced_scene)):
        if given:
            print(f"linkage-sym: {flag} needs the derived balance conditions, which cover hinged "
                  "(R-joint) linkages only; with prismatic joints only --optimize (and --plots) "
                  "run", file=sys.stderr)
            return 2
    try:
        require_hinged(scene, "the mass/acceleration-parameter module (seed 002)")
    except SceneError as err:
        why = "; ".join(err.problems)
    else:  # not reached: called for scenes with a P joint
        raise AssertionError("_balance_sliding called for a hinged scene")
    options = _optimize_options(scene, args)
    before = solver_series(scene, label="as given")
    section, after = _optimize(scene, args, *options)
    report = {
        "scene": scene.name,
        "conditions_derived": False,
        "reasons": {"conditions": why},
        "optimized": section,
        "series": before.to_dict(),
        "series_optimized": after.to_dict(),
        "series_source": "numeric force solver, inertia only (no module: prismatic joints)",
    }
    return _write_balance(scene, args, report, [before, after], [args.optimize])


def _write_balance(scene, args, report, series, written) -> int:
    if args.plots:
        from linkage_sym.plotting.balance import shaking_force_polar, shaking_moment_curve

        out = Path(args.plots)
        out.mkdir(parents=True, exist_ok=True)
        stem = Path(args.scene).stem
        kind = scene.joint(scene.drivers[0].joint).type
        written.append(str(shaking_force_polar(series, out / f"{stem}_shaking_force_polar.png",
                                               title=scene.name, driver_kind=kind)))
        written.append(str(shaking_moment_curve(series, out / f"{stem}_shaking_moment.png",
                                                title=scene.name, driver_kind=kind)))
    text = json.dumps(report, indent=2 if args.pretty else None)
    if args.output in (None, "-"):
        sys.stdout.write(text + "\n")
    else:
        _write(args.output, text + "\n")
        written.insert(0, args.output)
    for w in written:
        print(f"wrote {w}", file=sys.stderr if args.output in (None, "-") else sys.stdout)
    return 0


def cmd_balance(args) -> int:
    from linkage_sym.balancing.report import balance_report

    scene = _load(args.scene)
    if args.optimize and any(j.type == "P" for j in scene.joints):
        return _balance_sliding(scene, args)
    options = _optimize_options(scene, args) if args.optimize else None
    report, series = balance_report(scene, latex=args.latex)
    written = []
    if args.balanced_scene:
        if "balanced_scene" not in report:
            print(f"linkage-sym: {report['counterweights']['error']}", file=sys.stderr)
            return 2
        _write(args.balanced_scene, json.dumps(report["balanced_scene"], indent=2) + "\n")
        written.append(args.balanced_scene)
    if args.optimize:
        report["optimized"], after = _optimize(scene, args, *options)
        report["series_optimized"] = after.to_dict()
        series = [*series, after]
        written.append(args.optimize)
    return _write_balance(scene, args, report, series, written)


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
    from linkage_sym.examples import example_path
    from linkage_sym.model import Effects
    from linkage_sym.numeric.plan import compile_plan
    from linkage_sym.plotting import frame_loads, plot_all

    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    names = args.example or list(DEMO_EXAMPLES)
    for name in names:
        scene = _load(example_path(name))
        analysis = compile_plan(scene).run()
        (out / f"{name}_result.json").write_text(json.dumps(analysis.to_dict()) + "\n")
        files = plot_all(scene, analysis, out, prefix=name)
        # the shaking force and moment: the same motion with inertia as the only effect
        shaking_scene = dataclasses.replace(
            scene,
            effects=Effects(inertia=True, gravity=None, loads=False),
            outputs=("frame",),
        )
        shaking = compile_plan(shaking_scene).run()
        files.append(frame_loads(shaking_scene, shaking, out / f"{name}_shaking.png"))
        n_ok = int(analysis.ok.sum())
        print(f"{name}: {n_ok}/{analysis.n_steps} steps solved; wrote")
        print(f"  {out / (name + '_result.json')}")
        for f in files:
            print(f"  {f}")
        if all(j.type == "R" for j in scene.joints):
            files = _demo_balance(scene, name, out)
            print(f"{name}: balancing conditions and force-balancing counterweights; wrote")
            for f in files:
                print(f"  {f}")
    print(f"demo output is in {out.resolve()}")
    return 0


def _demo_balance(scene, name, out) -> list:
    """Seed 002's balancing of a hinged example: JSON and before/after plots."""
    from linkage_sym.balancing.report import balance_report
    from linkage_sym.plotting.balance import shaking_force_polar, shaking_moment_curve

    report, series = balance_report(scene)
    path = out / f"{name}_balance.json"
    path.write_text(json.dumps(report) + "\n")
    return [
        path,
        shaking_force_polar(series, out / f"{name}_balance_force_polar.png", title=scene.name),
        shaking_moment_curve(series, out / f"{name}_balance_moment.png", title=scene.name),
    ]


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="linkage-sym",
        description="Symbolic-numeric analysis of planar linkages.",
    )
    sub = p.add_subparsers(dest="command", required=True)
    a = sub.add_parser("analyze", help="solve a scene's sweep and write the result JSON")
    a.add_argument("scene", help="scene JSON file")
    a.add_argument("-o", "--output", help="result JSON file (default: standard output)")
    a.add_argument("--pretty", action="store_true", help="indent the JSON")
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
        help="seed-000 disconnection to use for complex groups (index in the list "
        "`linkage-sym structure` prints, from 0; default: the best-suited one)",
    )
    a.add_argument(
        "--plots",
        metavar="DIR",
        help="also write the sweep's pictures into DIR (motion diagrams, paths and coupler "
        "curves; driving effort, reaction hodographs and frame loads when forces ran)",
    )
    a.set_defaults(func=cmd_analyze)
    v = sub.add_parser("derive", help="derive the scene's equations with SymPy (text or LaTeX)")
    v.add_argument("scene", help="scene JSON file")
    v.add_argument("--latex", action="store_true", help="write a LaTeX fragment (seed 003 notation)")
    v.add_argument("--numeric", action="store_true", help="the scene's numbers instead of parameter symbols")
    v.add_argument("-o", "--output", help="output file (default: standard output)")
    v.set_defaults(func=cmd_derive)
    b = sub.add_parser("balance", help="derive balancing conditions of a hinged linkage (seed 002)")
    b.add_argument("scene", help="scene JSON file (R joints only)")
    b.add_argument("-o", "--output", help="balance JSON file (default: standard output)")
    b.add_argument("--pretty", action="store_true", help="indent the JSON")
    b.add_argument("--latex", action="store_true", help="add the expressions as LaTeX")
    b.add_argument("--plots", metavar="DIR", help="write the shaking force polar plot and moment curve, before and after")
    b.add_argument("--balanced-scene", metavar="FILE", help="write the scene with force-balancing counterweights")
    b.add_argument("--optimize", metavar="FILE", help="write the scene with optimised counterweights")
    b.add_argument("--weights", default="1,1,1", help="weights of RMS shaking force, moment, driving effort (default 1,1,1)")
    b.add_argument("--max-mass", type=float, default=None, help="bound on each counterweight's mass (kg)")
    b.add_argument("--links", default=None, metavar="L1,L2",
                   help="links that get a counterweight in --optimize (default: every moving link)")
    b.set_defaults(func=cmd_balance)
    s = sub.add_parser("structure", help="print drivers and Assur groups in solving order")
    s.add_argument("scene", help="scene JSON file")
    s.set_defaults(func=cmd_structure)
    d = sub.add_parser("demo", help="analyse shipped examples and write plots")
    d.add_argument("-o", "--output", default="demo_out", help="output folder (default demo_out)")
    d.add_argument(
        "--example", action="append", help=f"example to run (repeatable; default {', '.join(DEMO_EXAMPLES)})"
    )
    d.set_defaults(func=cmd_demo)
    e = sub.add_parser("examples", help="list the shipped example scenes")
    e.set_defaults(func=cmd_examples)
    return p


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except (SceneError, BalanceError) as err:
        print(f"linkage-sym: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
