"""The sections of a mechanism's LaTeX equations, each written into a :class:`Doc`.

The symbols (a list, or a nomenclature table with units), the loop equations
(the kinematics chapter's eq. 3-8 and its projections 3-9) and gear meshes,
the explicit positions, the velocity and acceleration equations (3-28, 3-29)
and, when derived, each group's force equations and the frame loads, in the
notation of :mod:`linkage_sym.symbolic.latex_notation`.
:func:`linkage_sym.symbolic.latex.latex_document` writes them in this order.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from linkage_sym.symbolic.latex_blocks import block_matrix, rate_matrix
from linkage_sym.symbolic.latex_figures import loop_figure
from linkage_sym.symbolic.latex_radicands import position_rows
from linkage_sym.symbolic.latex_notation import (
    MAX_EQUATION,
    MAX_MATRIX,
    column,
    escape_text,
    pmatrix,
    rows_of,
)

__all__ = ["MAX_MEANING", "UNITS", "equations", "nomenclature", "scene_joint_type", "symbol_list"]

MAX_MEANING = 60
"""A symbol's meaning longer than this (characters) is set as a paragraph in the symbol table."""

UNITS = {
    "length": "m", "coordinate": "m", "angle": "rad", "mass": "kg",
    "inertia": r"kg\,m$^2$", "gravity": r"m/s$^2$",
}


def _unit_of_parameter(p) -> str:
    if p.kind == "load":
        return r"N\,m" if p.name.startswith("T_") else "N"
    return UNITS.get(p.kind, "")


def _unit_of_intermediate(sym) -> str:
    pre = sym.name.split("_", 1)[0]
    if pre in ("cphi", "sphi"):
        return "1"
    if pre in ("aGx", "aGy"):
        return r"m/s$^2$"
    if pre in ("T", "tau"):  # a spring's tension or torque
        return "N" if pre == "T" else r"N\,m"
    return "m"


def nomenclature(doc, nm, eqs) -> None:
    """Every symbol with its meaning and unit, as a ``longtable``."""
    rows = []
    for s, sd, sdd in zip(eqs.x, eqs.xd, eqs.xdd):
        if s.name.startswith("theta_"):
            link = escape_text(s.name[6:])
            rows += [(nm(s), f"angle of link {link}", "rad"),
                     (nm(sd), f"angular velocity of link {link}", "rad/s"),
                     (nm(sdd), f"angular acceleration of link {link}", r"rad/s$^2$")]
        else:
            j = escape_text(s.name[2:])
            rows += [(nm(s), f"slide of prismatic joint {j}", "m"),
                     (nm(sd), f"slide velocity of joint {j}", "m/s"),
                     (nm(sdd), f"slide acceleration of joint {j}", r"m/s$^2$")]
    for q, qd, qdd, d in zip(eqs.q, eqs.qd, eqs.qdd, eqs.scene.drivers):
        j = escape_text(d.joint)
        u = "rad" if d.kind == "R" else "m"
        rows += [(nm(q), f"driver coordinate of joint {j}", u),
                 (nm(qd), "its velocity", u + "/s"), (nm(qdd), "its acceleration", u + r"/s$^2$")]
    for ge in eqs.groups:
        if ge.sigma is not None:
            rows.append((nm(ge.sigma), f"assembly mode of group {ge.index + 1} ($\\pm 1$)", "1"))
    for j, k in zip(eqs.scene.meshes, eqs.flanks):
        rows.append((nm(k), f"flank of gear mesh {escape_text(j.name)}: sign of its tangential "
                            "force ($\\pm 1$)", "1"))
    for s in eqs.parameters:
        p = eqs.table.params[s.name]
        rows.append((nm(s), escape_text(p.meaning), _unit_of_parameter(p)))
    for s, meaning in eqs.intermediates:
        rows.append((nm(s), escape_text(meaning), _unit_of_intermediate(s)))
    if eqs.has_forces:
        for s, _, meaning in eqs.force_intermediates:
            rows.append((nm(s), escape_text(meaning), _unit_of_intermediate(s)))
        for j in eqs.scene.joints:
            jn = escape_text(j.name)
            if j.type == "G":
                a, b = (escape_text(n) for n in j.links)
                rows.append((nm(eqs.F[j.name][0]), f"tooth load of gear mesh {jn} on its line of "
                                                   f"action (gear {a} on gear {b})", "N"))
                continue
            f1, f2 = eqs.F[j.name]
            if j.type == "R":
                rows += [(nm(f1), f"force of joint {jn}'s first link on its second, x", "N"),
                         (nm(f2), "the same, y", "N")]
            else:
                rows += [(nm(f1), f"normal force of prismatic joint {jn}", "N"),
                         (nm(f2), f"couple of prismatic joint {jn}", r"N\,m")]
        for d in eqs.scene.drivers:
            rows.append((nm(eqs.E[d.joint]), f"driving effort at joint {escape_text(d.joint)}",
                         r"N\,m" if d.kind == "R" else "N"))
        for law in eqs.friction_laws:
            jn = escape_text(law.joint)
            r = law.kind == "R"
            rows.append((nm(law.friction), f"friction {'couple' if r else 'force'} of joint {jn}'s "
                         "first link on its second", r"N\,m" if r else "N"))
            rows.append((nm(law.sign), f"sign of joint {jn}'s relative motion", "1"))
            if isinstance(law.arm, sp.Symbol):
                rows.append((nm(law.arm), f"friction circle's radius of joint {jn}" if r
                             else f"friction coefficient of joint {jn}", "m" if r else "1"))
    doc.text(r"\begin{longtable}{lll}")
    doc.text(r"symbol & meaning & unit \\ \hline \endhead")
    for sym, meaning, unit in rows:
        if len(meaning) > MAX_MEANING:  # a paragraph of its own: the table keeps to the margins
            meaning = rf"\parbox[t]{{0.6\linewidth}}{{\raggedright {meaning}}}"
        doc.text(rf"${sym}$ & {meaning} & {unit} \\")
    doc.text(r"\end{longtable}")


def symbol_list(doc, nm, eqs) -> None:
    """The symbols and their meanings, as an ``itemize`` list."""
    doc.text(r"\begin{itemize}")
    for s, sd, sdd in zip(eqs.x, eqs.xd, eqs.xdd):
        if s.name.startswith("theta_"):
            what = f"angle, angular velocity and acceleration of link {s.name[6:]}"
        else:
            what = f"slide of prismatic joint {s.name[2:]} and its rates"
        doc.text(rf"\item ${nm(s)}, {nm(sd)}, {nm(sdd)}$: {escape_text(what)}")
    for q, qd, qdd in zip(eqs.q, eqs.qd, eqs.qdd):
        doc.text(rf"\item ${nm(q)}, {nm(qd)}, {nm(qdd)}$: driver coordinate of joint "
                 f"{escape_text(q.name[2:])} and its rates")
    for ge in eqs.groups:
        if ge.sigma is not None:
            doc.text(rf"\item ${nm(ge.sigma)} = \pm 1$: assembly mode of group {ge.index + 1}")
    for s in eqs.parameters:
        p = eqs.table.params[s.name]
        doc.text(rf"\item ${nm(s)}$: {escape_text(p.meaning)} ({p.kind})")
    for s, meaning in eqs.intermediates:
        doc.text(rf"\item ${nm(s)}$: {escape_text(meaning)} (intermediate)")
    for s, _, meaning in getattr(eqs, "force_intermediates", ()):
        doc.text(rf"\item ${nm(s)}$: {escape_text(meaning)} (intermediate)")
    if eqs.has_forces:
        doc.text(
            r"\item $R_{J,x}, R_{J,y}$: force of the joint's first link on its second at "
            r"revolute joint $J$; $N_{J}$, $M_{J}$: normal force and couple of prismatic joint "
            r"$J$; $\tau_{J}$, $f_{J}$: driving torque or force at joint $J$"
        )
    if getattr(eqs, "friction_laws", None):
        doc.text(
            r"\item $M^{f}_{J}$, $F^{f}_{J}$: friction couple or force at joint $J$; $\rho_{J}$, "
            r"$\mu_{J}$: its friction circle's radius or coefficient; $\nu_{J}$: the sign of its "
            "relative motion"
        )
    doc.text(r"\end{itemize}")


def scene_joint_type(eqs, name: str) -> str:
    """The type (``R``, ``P``, ``G``) of joint ``name`` of the equations' scene."""
    return eqs.scene.joint(name).type


def equations(doc, nm, eqs, figures: bool = False) -> None:
    """Every section after the symbols: loops (with a TikZ figure of each where ``figures``),
    gear meshes, positions, velocities, accelerations and, when derived, forces."""
    _loops(doc, nm, eqs, figures)
    _meshes(doc, nm, eqs)
    _positions(doc, nm, eqs)
    _velocities(doc, nm, eqs)
    _accelerations(doc, nm, eqs)
    if eqs.has_forces:
        _forces(doc, nm, eqs)
        if eqs.friction_laws:
            _friction(doc, nm, eqs)
        _frame(doc, nm, eqs)


def _friction(doc, nm, eqs) -> None:
    """The joints' friction laws (contract part two), which close the force equations."""
    doc.text(r"\paragraph{Joint friction.}")
    doc.text(
        "The frictions in the groups' right-hand sides are those of Coulomb's law: at a revolute "
        r"joint the couple $M^{f}_{J}$ about the pin, $\rho_{J} = f_{J} r_{J}$ the radius of its "
        r"friction circle; at a prismatic joint the force $F^{f}_{J}$ along the axis, $\mu_{J}$ "
        "its coefficient; each what the joint's first link exerts on its second, against the "
        r"sign $\nu_{J}$ of the second link's motion relative to the first (of its relative "
        r"acceleration where the velocity is zero; $\nu_{J} = 0$ where both are). These laws make "
        "the equations nonlinear in the reactions; the numeric methods solve them (Newton's "
        "method on each group's frictions)."
    )
    rows, keys = [], []
    for law in eqs.friction_laws:
        r = nm.sum_rows(nm(law.friction), law.law)
        rows += r
        keys += [f"friction-{law.joint}"] + [None] * (len(r) - 1)
    doc.align(rows, keys)


def _loops(doc, nm, eqs, figures: bool = False) -> None:
    """Every closed vector loop in complex form (eq. 3-8) and its projections (3-9), each
    followed by its figure where ``figures``
    (:func:`linkage_sym.symbolic.latex_figures.loop_figure`)."""
    doc.text(r"\paragraph{Loop equations.}")
    if eqs.loops:
        doc.text(
            "Each joint that closes a loop gives a closed vector loop "
            r"\cite[eq.~3-8]{linkagesym-kinematics} and its projections on the "
            "axes (its eq.~3-9):"
        )
    else:
        doc.text("The mechanism has no closed vector loop: every link is placed along a tree"
                 + (" (its gear meshes close it below)." if eqs.meshes else "."))
    for jname, v in eqs.loops:
        key = f"loop-{jname}"
        first = len(doc.labels)
        rows = [r.replace("&=", "&=", 1) for r in nm.sum_rows("0", v.complex())]
        doc.align(rows, [key] + [None] * (len(rows) - 1))
        rx, ry = nm.sum_rows("0", v.x), nm.sum_rows("0", v.y)
        doc.align(rx + ry, [key + "-x"] + [None] * (len(rx) - 1) + [key + "-y"] + [None] * (len(ry) - 1))
        if figures:
            eq_label = doc.labels[first]  # the loop's complex form: eq:<scene>:loop-<joint>
            doc.text(loop_figure(eqs, nm, jname, "fig:" + eq_label[3:], eq_label))


def _meshes(doc, nm, eqs) -> None:
    """Each gear mesh's rolling without slip."""
    if eqs.meshes:
        doc.text(r"\paragraph{Gear meshes.}")
        doc.text(
            "Each mesh rolls without slip: its pitch radii times the rotations of its gears "
            "relative to its carrier, from the assembly configuration, cancel (an external "
            "mesh) or agree (an internal one):"
        )
        rows, keys = [], []
        for jname, e in eqs.meshes:
            r = nm.sum_rows("0", e)
            rows += r
            keys += [f"mesh-{jname}"] + [None] * (len(r) - 1)
        doc.align(rows, keys)


def _positions(doc, nm, eqs) -> None:
    """The explicit positions with their named intermediates, and the groups found
    numerically."""
    doc.text(r"\paragraph{Positions.}")
    if eqs.closed_forms:
        rows, keys, named = position_rows(nm, eqs.position_steps)
        listed = ", ".join(f"${r}$ of ${s}$" for r, s in named)
        doc.text(
            "Explicit positions of the input links and dyads, in solving order "
            r"(each may use those above it; $\sigma = \pm 1$ selects the assembly mode). "
            "Each dyad first names its outer joints, the distance $d$ between them, the "
            "projection $a$ and the half-chord $h$ of its inner joint (Heron's form, accurate "
            "near a dead centre), then its inner joint and its angles"
            + (f". A square root too wide for a row has its radicand named as a row of its own "
               f"({listed}):" if named else ":")
        )
        doc.align(rows, keys)
    for ge in eqs.groups:
        if not ge.closed:
            coords = ", ".join(f"${nm(s)}$" for s in ge.x)
            links = escape_text(", ".join(ge.group.links))
            doc.text(
                f"Group {ge.index + 1} ({escape_text(ge.group.kind)}: links {links}) has no "
                f"explicit closed form: its coordinates {coords} are found numerically "
                "(Newton's method) from its loop "
                + ("and mesh " if any(scene_joint_type(eqs, j) == "G" for j in ge.group.joints) else "")
                + "equations above."
            )


def _velocities(doc, nm, eqs) -> None:
    """``A xd = B qd`` (3-28), whole or with the matrices' entries."""
    doc.text(r"\paragraph{Velocities.}")
    doc.text(
        r"Differentiating the position equations $\Phi$ with respect to time gives "
        r"$\mathbf{A}\,\dot{\mathbf{x}} = \mathbf{B}\,\dot{\mathbf{q}}$ "
        r"\cite[eq.~3-28]{linkagesym-kinematics}, "
        r"$\mathbf{A} = \partial\Phi/\partial\mathbf{x}$, "
        r"$\mathbf{B} = -\partial\Phi/\partial\mathbf{q}$:"
    )
    A, B = pmatrix(nm, eqs.A), pmatrix(nm, eqs.B)
    col_xd, col_qd = column(nm, eqs.xd), column(nm, eqs.qd)
    whole = f"{A} {col_xd} = {B} {col_qd}"
    if A is not None and B is not None and len(whole) <= MAX_EQUATION:
        doc.equation(whole, "velocity")
    else:
        doc.equation(r"\mathbf{A}\,\dot{\mathbf{x}} = \mathbf{B}\,\dot{\mathbf{q}}", "velocity")
        doc.align([rf"\dot{{\mathbf{{x}}}} &= {col_xd}", rf"\dot{{\mathbf{{q}}}} &= {col_qd}"],
                  numbered=False)
        rows = [ge.rows for ge in eqs.groups]
        starts = np.cumsum([0] + [len(ge.x) for ge in eqs.groups])
        cols = [slice(int(a), int(b)) for a, b in zip(starts[:-1], starts[1:])]
        if A is None:
            rate_matrix(doc, nm, "A", eqs.A, rows, cols)
        else:
            doc.align([rf"\mathbf{{A}} &= {A}"], numbered=False)
        if B is None:
            rate_matrix(doc, nm, "B", eqs.B, rows, [slice(0, len(eqs.q))])
        else:
            doc.align([rf"\mathbf{{B}} &= {B}"], numbered=False)


def _accelerations(doc, nm, eqs) -> None:
    """``A xdd = r`` (3-29), the right-hand side whole or entry by entry."""
    doc.text(r"\paragraph{Accelerations.}")
    doc.text(
        r"Differentiating once more \cite[eq.~3-29]{linkagesym-kinematics}, "
        r"$\mathbf{A}\,\ddot{\mathbf{x}} = -\dot{\mathbf{A}}\,\dot{\mathbf{x}} + "
        r"\dot{\mathbf{B}}\,\dot{\mathbf{q}} + \mathbf{B}\,\ddot{\mathbf{q}}$, with the same "
        r"$\mathbf{A}$; the right-hand side is printed as one column $\mathbf{r}$:"
    )
    doc.equation(
        r"\mathbf{A}\,\ddot{\mathbf{x}} = \mathbf{r} = -\dot{\mathbf{A}}\,\dot{\mathbf{x}} "
        r"+ \dot{\mathbf{B}}\,\dot{\mathbf{q}} + \mathbf{B}\,\ddot{\mathbf{q}}",
        "acceleration",
    )
    doc.align([rf"\ddot{{\mathbf{{x}}}} &= {column(nm, eqs.xdd)}"], numbered=False)
    rhs = pmatrix(nm, eqs.acc_rhs)
    if rhs is not None and eqs.acc_rhs.rows <= MAX_MATRIX:
        doc.align([rf"\mathbf{{r}} &= {rhs}"], numbered=False)
    else:
        doc.entries(nm, r"\mathbf{r}", eqs.acc_rhs, "the right-hand side", "r")


def _forces(doc, nm, eqs) -> None:
    """The centres of mass's accelerations, then each group's force equations."""
    doc.text(r"\paragraph{Forces.}")
    doc.text(
        "Each group's links in equilibrium with their loads and d'Alembert inertia "
        r"forces give $\mathbf{A}_g \mathbf{F}_g = \mathbf{b}_g - \mathbf{C}_g "
        r"\mathbf{F}_{\mathrm{later}}$, solved from the last group back "
        r"($\mathbf{F}_{\mathrm{later}}$: the reactions and efforts of the groups solved after it)."
    )
    if eqs.force_intermediates:
        doc.text(
            r"The d'Alembert forces use the accelerations $a^{G}$ of the centres of mass, "
            "from the positions and rates above:" if not eqs.spring_efforts else
            r"The d'Alembert forces use the accelerations $a^{G}$ of the centres of mass, "
            r"and the springs and dampers pull with the tensions $T$ along their lengths $L$ "
            r"(each named once from its components $\Delta x, \Delta y$, as a dyad's $d$; a "
            r"joint spring: the torque $\tau$ on its joint's second link), from the positions "
            r"and rates above:"
        )
        rows, keys = [], []
        for sym, e, _ in eqs.force_intermediates:
            r = nm.sum_rows(nm(sym), e)
            rows += r
            keys += [f"acc-{sym.name}"] + [None] * (len(r) - 1)
        doc.align(rows, keys)
    for ge, block in zip(eqs.groups, eqs.readable_force_blocks):
        _force_group(doc, nm, ge, block)


def _force_group(doc, nm, ge, block) -> None:
    """Group ``ge``'s ``A_g F_g = b_g - C_g F_later``, whole or with named matrices."""
    Ag, bg, Cg, later = block
    g = ge.index + 1
    links = escape_text(", ".join(ge.group.links))
    doc.text(rf"\subparagraph{{Group {g}}} ({escape_text(ge.group.kind)}: links {links}).")
    a = pmatrix(nm, Ag)
    wide_a = a or block_matrix(nm, Ag)  # whole, a source line a row, when the rows fit a line
    b = pmatrix(nm, bg)
    c = pmatrix(nm, Cg) if later else None
    wide_c = (c or block_matrix(nm, Cg)) if later else None
    F = column(nm, ge.forces)
    Fl = column(nm, later) if later else None
    small = a is not None and b is not None and (not later or c is not None)
    rhs = None if not small else b + (f" - {c} {Fl}" if later else "")
    if small and len(f"{a} {F} = {rhs}") <= MAX_EQUATION:
        doc.equation(f"{a} {F} = {rhs}", f"forces-{g}")
    else:
        rhs = rf"\mathbf{{b}}_{{{g}}}" + (
            rf" - \mathbf{{C}}_{{{g}}} \mathbf{{F}}_{{>{g}}}" if later else "")
        doc.equation(rf"\mathbf{{A}}_{{{g}}} \mathbf{{F}}_{{{g}}} = {rhs}", f"forces-{g}")
        rows = rows_of(nm, rf"\mathbf{{F}}_{{{g}}}", ge.forces)
        if later:
            rows += rows_of(nm, rf"\mathbf{{F}}_{{>{g}}}", later)
        doc.align(rows, numbered=False)
        for name, M, m_tex, what, entry in (
            (rf"\mathbf{{A}}_{{{g}}}", Ag, wide_a, "the matrix", f"A^{{({g})}}"),
            (rf"\mathbf{{b}}_{{{g}}}", bg, b, "the column", f"b^{{({g})}}"),
            (rf"\mathbf{{C}}_{{{g}}}", Cg, wide_c, "the matrix", f"C^{{({g})}}"),
        ):
            if name.startswith(r"\mathbf{C}") and not later:
                continue
            if m_tex is not None:
                doc.align([f"{name} &= {m_tex}"], numbered=False)
            elif M.is_zero_matrix:
                doc.text(f"${name} = 0$.")
            else:
                doc.entries(nm, name, M, what, entry)


def _frame(doc, nm, eqs) -> None:
    """The force and moment the moving links put on the frame."""
    doc.text(
        "The frame (ground) carries the force and the moment about the origin "
        "that the moving links put on it:"
    )
    rows, keys = [], []
    for lhs, e, k in zip(
        (r"F^{\mathrm{fr}}_{x}", r"F^{\mathrm{fr}}_{y}", r"M^{\mathrm{fr}}"),
        eqs.readable_frame,
        ("frame-x", "frame-y", "frame-moment"),
    ):
        r = nm.sum_rows(lhs, e)
        rows += r
        keys += [k] + [None] * (len(r) - 1)
    doc.align(rows, keys)
