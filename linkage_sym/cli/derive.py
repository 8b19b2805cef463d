"""``linkage-sym derive``: the scene's equations derived with SymPy, as text or LaTeX.

::

    linkage-sym derive SCENE.json [--latex [--standalone] [--symbols]] [--numeric] [-o FILE]
"""

from __future__ import annotations

from linkage_sym.cli.common import OptionError, check_outputs as _check_outputs, emit, load as _load

__all__ = ["cmd_derive", "register"]


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
        if eqs.friction_laws:  # contract part two: the laws that close the force equations
            out += ["", "## joint friction (rho_J = f r: the friction circle's radius; mu_J: the "
                    "coefficient; nu_J: the sign of the joint's relative motion)"]
            out += [f"{law.friction} = {law.law}" for law in eqs.friction_laws]
        if eqs.spring_efforts:  # contract part two: known loads of the coordinates and rates
            out += ["", "## springs and dampers (T_k: a spring's tension; tau_k: a joint spring's "
                    "torque on its joint's links[1])"]
            out += [f"{sym} = {e}" for _, sym, e, _, _ in eqs.spring_efforts]
        out += ["", "## frame force x, y and moment about the origin"]
        out += [str(e) for e in eqs.readable_frame]
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



def register(sub) -> None:
    """Add the ``derive`` command to the ``linkage-sym`` subparsers ``sub``."""
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
