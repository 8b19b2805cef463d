"""Every printed equation of ``derive --latex``, read back and evaluated with the scene's numbers,
is the numeric solver's value at a step (issue 31).

The LaTeX is read by :mod:`tests.support.latex_reader` (no SymPy, no code of the printer); the
names it meets are given numbers through the document's own symbol table (``--symbols``): a
parameter by its meaning (the scene's value of the parameter that meaning belongs to), a
coordinate, rate, driver value or force by its meaning (angle of link L, driver coordinate of
joint J, force of joint J's first link on its second, ...) from :func:`linkage_sym.analyze`,
which shares no code with the symbolic layer.  Checked at three solved steps spread over the
sweep, each within ``1e-10`` of its family's scale (``L`` for lengths, 1 rad for angles, the
largest reaction ``F`` for forces and ``F L`` for moments, the largest rate for the rates):

* **positions**: each row in solving order (the assembly modes ``sigma`` the ones that give
  the numeric configuration), every joint's coordinates and every link's angle the numeric
  ones;
* **rate matrices**: every entry of every block ``A_ij`` and of ``B`` is the numeric Jacobian of
  the position equations at the step (complex-step derivatives, exact to rounding, of
  ``Phi``, which is checked to vanish there), ``A xd = B qd`` with the numeric rates and each
  printed ``r_i`` is row ``i`` of ``A xdd`` with the numeric accelerations;
* **forces**: the centres of mass's accelerations are the numeric ones; each group's
  ``A_g F_g = b_g - C_g F_later``, solved from the last group back with the printed matrices,
  gives the numeric reactions and driving efforts; the frame's force and moment are the
  numeric ones.
"""

from __future__ import annotations

import itertools
import math
import re

import numpy as np
import pytest
import sympy as sp

import linkage_sym
from linkage_sym.examples import load_example
from linkage_sym.structure.parameters import ident, link_frames
from linkage_sym.symbolic.latex import latex_document
from tests.support import latex_reader as tex

EXAMPLES = ["crank_rocker", "slider_crank_offset", "watt_sixbar", "sixbar_class3"]
RTOL = 1e-10


class Case:
    """One example: its scene, equations, document, numeric result and symbol table."""

    def __init__(self, name, derive=None, document=None):
        """``derive``, ``document``: keywords of :func:`linkage_sym.derive` and of
        ``latex_document`` beyond the defaults (the numeric mode's, for instance)."""
        self.scene = load_example(name)
        self.eqs = linkage_sym.derive(self.scene, forces=True, **(derive or {}))
        self.doc = latex_document(self.eqs, symbols=True, **(document or {}))
        self.res = linkage_sym.analyze(self.scene)
        self.parts = tex.sections(self.doc)
        table = _symbol_table(self.doc)
        self.table = [(sym, meaning) for sym, meaning, _ in table]
        self.units = {sym: unit for sym, _, unit in table}
        ok = np.flatnonzero(self.res.status == "ok")
        self.steps = ok[[len(ok) // 7, len(ok) // 2, (5 * len(ok)) // 6]]
        pos = [j.position for j in self.res.joints.values()]
        self.L = max(self.scene.characteristic_length(), float(np.nanmax(np.abs(pos))))
        self.F = float(np.nanmax([np.nanmax(np.hypot(*r.T)) for r in self.res.forces.reactions.values()]))


@pytest.fixture(scope="module", params=EXAMPLES)
def case(request):
    return Case(request.param)


def _meaning(text: str) -> str:
    m = re.fullmatch(r"\\parbox\[t\]\{[^}]*\}\{\\raggedright (.*)\}", text.strip())
    text = m.group(1) if m else text.strip()
    for escaped, plain in ((r"\_", "_"), (r"\ensuremath{\to}", "->"), (r"\ensuremath{<}", "<"),
                           (r"\ensuremath{>}", ">")):
        text = text.replace(escaped, plain)
    return text


def _symbol_table(doc: str) -> list[tuple[str, str]]:
    """``[(LaTeX symbol, meaning), ...]`` of the document's symbol table, in its order."""
    body = re.search(r"\\begin\{longtable\}\{lll\}\n(.*?)\\end\{longtable\}", doc, re.S).group(1)
    out = []
    for row in body.splitlines()[1:]:
        sym, meaning, unit = (c.strip() for c in row.rstrip("\\ ").split(" & "))
        out.append((sym.strip("$"), _meaning(meaning), unit))
    return out


def _slide_direction(case, jname, i, values):
    """The unit vector of ``P`` joint ``jname``'s slide at step ``i``, global."""
    J = case.scene.joint(jname)
    gamma = values[f"gamma_{ident(jname)}"]
    frames = link_frames(case.scene)
    turn = 0.0 if J.links[0] == "ground" else (frames[J.links[0]].theta0
                                              + float(case.res.links[J.links[0]].rotation[i]))
    return math.cos(gamma + turn), math.sin(gamma + turn)


def _numbers(case, i):
    """``{LaTeX name: number}`` of every parameter, coordinate, rate and driver value at step
    ``i``, and ``{LaTeX name: number}`` of the numeric forces (by the table's meanings)."""
    eqs, res, scene = case.eqs, case.res, case.scene
    by_meaning = {eqs.table.params[s.name].meaning: v for s, v in eqs.parameter_values().items()}
    by_name = {s.name: float(v) for s, v in eqs.parameter_values().items()}
    frames = link_frames(scene)
    values, forces, previous = {}, {}, None
    for sym, meaning in case.table:
        m = re.fullmatch(r"(angle|angular velocity|angular acceleration) of link (.+)", meaning)
        d = re.fullmatch(r"driver coordinate of joint (.+)", meaning)
        s = re.fullmatch(r"slide(?: of prismatic joint| velocity of joint| acceleration of joint) (.+)", meaning)
        r = re.fullmatch(r"force of joint (.+)'s first link on its second, x", meaning)
        if meaning in by_meaning:
            values[sym] = float(by_meaning[meaning])
        elif m:
            lk = res.links[m.group(2)]
            values[sym] = float({"angle": frames[m.group(2)].theta0 + lk.rotation[i],
                                 "angular velocity": lk.omega[i],
                                 "angular acceleration": lk.alpha[i]}[m.group(1)])
        elif d:
            previous = res.drivers[d.group(1)]
            values[sym] = float(previous["q"][i])
        elif meaning in ("its velocity", "its acceleration"):
            values[sym] = float(previous["qd" if meaning == "its velocity" else "qdd"][i])
        elif s:
            values[sym] = _slide(case, s.group(1), i, meaning.split()[1])
        elif r:
            previous = res.forces.reactions[r.group(1)][i]
            forces[sym] = float(previous[0])
        elif meaning == "the same, y":
            forces[sym] = float(previous[1])
        elif meaning.startswith("normal force of prismatic joint "):
            J = meaning.rsplit(" ", 1)[1]
            ux, uy = _slide_direction(case, J, i, by_name)
            rx, ry = res.forces.reactions[J][i]
            forces[sym] = float(-uy * rx + ux * ry)
        elif meaning.startswith("couple of prismatic joint "):
            forces[sym] = float(res.forces.reaction_moments[meaning.rsplit(" ", 1)[1]][i])
        elif meaning.startswith("driving effort at joint "):
            forces[sym] = float(res.forces.driving[meaning.rsplit(" ", 1)[1]][i])
    return values, forces


def _slide(case, jname, i, which):
    """The slide of ``P`` joint ``jname`` (0 in the assembly configuration) or its rates,
    from the numeric joint's motion relative to the guide's link ``links[0]``."""
    J = case.scene.joint(jname)
    joint = case.res.joints[jname]
    if J.links[0] != "ground":
        pytest.skip("a moving guide: none among the examples read here")
    u = _slide_direction(case, jname, i, {s.name: float(v) for s, v in case.eqs.parameter_values().items()})
    if which == "of":
        return float(np.dot(joint.position[i] - np.asarray(J.at, float), u))
    return float(np.dot(joint.velocity[i] if which == "velocity" else joint.acceleration[i], u))


def _rows(part: str) -> list[tuple[str, str]]:
    """Every ``lhs &= rhs`` row of the math blocks of a section, in order."""
    out = []
    for env, block in re.findall(r"\\begin\{(align\*?|equation)\}(.*?)\\end\{\1\}", part, re.S):
        if env.startswith("align"):
            out += tex.rows(block)
    return out


def _positions(case, values, rows, sigmas):
    """Read the position rows with the assembly modes ``sigmas``; the worst difference from
    the numeric joints and angles (over ``L`` and 1 rad) and the values, intermediates added."""
    v = dict(values, **sigmas)
    coords = {sym: meaning for sym, meaning in case.table}
    worst = 0.0
    for lhs, rhs in rows:
        got = tex.value(rhs, v)
        if math.isnan(got):
            return math.inf, v
        meaning = coords.get(lhs, "")
        j = re.fullmatch(r"([xy])-coordinate of joint (.+)", meaning)
        if lhs in values:  # a coordinate: the numeric angle, up to whole turns
            d = (got - values[lhs] + math.pi) % (2 * math.pi) - math.pi
            worst = max(worst, abs(d))
        elif j:
            want = case.res.joints[j.group(2)].position[case.step]["xy".index(j.group(1))]
            worst = max(worst, abs(got - want) / case.L)
        if lhs not in values:
            v[lhs] = got
    return worst, v


def _read_positions(case, values):
    """The values with the position rows' intermediates, for the assembly modes that give the
    numeric configuration; fails unless some do, within ``RTOL``."""
    rows = _rows(case.parts["Positions"])
    sigmas = [sym for sym, meaning in case.table if meaning.startswith("assembly mode of group")]
    best = (math.inf, None)
    for signs in itertools.product((1.0, -1.0), repeat=len(sigmas)):
        best = min(best, _positions(case, values, rows, dict(zip(sigmas, signs))),
                   key=lambda t: t[0])
    assert best[0] <= RTOL, (case.scene.name, case.step, best[0])
    return best[1], len(rows)


@pytest.mark.slow
def test_the_printed_positions_are_the_numeric_ones(case):
    for i in case.steps:
        case.step = i
        values, _ = _numbers(case, i)
        _, n = _read_positions(case, values)
        assert n >= 1  # the class-III six-bar's triad is found numerically: its crank only


_LISTED = re.compile(r"The nonzero entries \$(.+?)_\{i(j?)\}\$ of the (?:matrix|column|right-hand "
                     r"side|block) \$(.+?)\$ \(\$(\d+)(?: \\times (\d+))?\$")


def _matrix(part, defs, name, values):
    """The matrix ``name`` of a section, evaluated: written whole (a ``pmatrix``), by blocks
    (a ``pmatrix`` of named blocks and zero blocks ``\\mathbf{0}``) or entry by entry (its
    nonzero entries listed, its size in the sentence before them)."""
    if name not in defs:
        for prefix, two, listed, n, m in _LISTED.findall(part):
            if listed == name:
                out = np.zeros((int(n), int(m) if two else 1))
                for (i, j), _ in np.ndenumerate(out):
                    key = f"{prefix}_{{{i + 1},{j + 1}}}" if two else f"{prefix}_{{{i + 1}}}"
                    if key in defs:
                        out[i, j] = tex.value(defs[key], values)
                return out
        raise AssertionError(f"{name} is not printed")
    cells = tex.matrix(defs[name])
    if not any(c.startswith(r"\mathbf{") for row in cells for c in row):
        return np.array([[tex.value(c, values) for c in row] for row in cells])
    blocks = [[None if c == r"\mathbf{0}" else _matrix(part, defs, c, values) for c in row]
              for row in cells]
    heights = [next(b.shape[0] for b in row if b is not None) for row in blocks]
    widths = [next(row[k].shape[1] for row in blocks if row[k] is not None)
              for k in range(len(blocks[0]))]
    return np.block([[b if b is not None else np.zeros((h, w)) for b, w in zip(row, widths)]
                     for row, h in zip(blocks, heights)])


def _vector(defs, name, values):
    """The entries of the column ``name`` (a ``pmatrix`` of names) as numbers."""
    return np.array([tex.value(row[0], values) for row in tex.matrix(defs[name])])


def _phi_jacobians(case, i):
    """``(Phi, dPhi/dx, -dPhi/dq)`` at step ``i`` of the numeric result: complex-step
    derivatives (step 1e-30), exact to rounding."""
    eqs = case.eqs
    frames = link_frames(case.scene)
    by_name = {s.name: float(v) for s, v in eqs.parameter_values().items()}
    x = []
    for s in eqs.x:
        if s.name.startswith("theta_"):
            link = next(n for n in case.scene.link_names if f"theta_{ident(n)}" == s.name)
            x.append(frames[link].theta0 + float(case.res.links[link].rotation[i]))
        else:
            jn = next(j.name for j in case.scene.joints if f"s_{ident(j.name)}" == s.name)
            x.append(_slide(case, jn, i, "of"))
    q = [float(case.res.drivers[d.joint]["q"][i]) for d in case.scene.drivers]
    params = list(eqs.parameter_values())
    f = sp.lambdify([eqs.x, eqs.q, params], list(eqs.Phi), "numpy")
    pv = [by_name[s.name] for s in params]

    def jac(vec, at):
        cols = []
        for k in range(len(vec)):
            z = np.array(vec, complex)
            z[k] += 1e-30j
            cols.append(np.imag(np.array(at(z), complex)) / 1e-30)
        return np.array(cols).T

    phi = np.array(f(x, q, pv), float)
    return phi, jac(x, lambda z: f(list(z), q, pv)), -jac(q, lambda z: f(x, list(z), pv))


@pytest.mark.slow
def test_the_printed_rate_matrices_are_the_numeric_jacobian(case):
    vel, acc = case.parts["Velocities"], case.parts["Accelerations"]
    dv, da = dict(_rows(vel)), dict(_rows(acc))
    for i in case.steps:
        case.step = i
        values, _ = _numbers(case, i)
        phi, A_ref, B_ref = _phi_jacobians(case, i)
        assert np.all(np.abs(phi) <= RTOL * case.L), phi
        A = _matrix(vel, dv, r"\mathbf{A}", values)
        B = _matrix(vel, dv, r"\mathbf{B}", values)
        scale = np.maximum(np.abs(A_ref).max(axis=1, keepdims=True), 1e-300)
        assert A.shape == A_ref.shape and np.all(np.abs(A - A_ref) <= RTOL * scale)
        assert B.shape == B_ref.shape and np.all(np.abs(B - B_ref) <= RTOL * np.maximum(scale, 1))
        xd, qd = _vector(dv, r"\dot{\mathbf{x}}", values), _vector(dv, r"\dot{\mathbf{q}}", values)
        terms = np.abs(A) @ np.abs(xd) + np.abs(B) @ np.abs(qd)
        assert np.all(np.abs(A @ xd - B @ qd) <= RTOL * terms.max())
        xdd = _vector(da, r"\ddot{\mathbf{x}}", values)
        r = _matrix(acc, da, r"\mathbf{r}", values)[:, 0]
        family = np.abs(A).sum(axis=1) * (np.abs(xdd).max() + np.abs(xd).max() ** 2)
        assert np.all(np.abs(A @ xdd - r) <= RTOL * family.max()), (A @ xdd - r) / family.max()


def _tuple(text: str) -> list[str]:
    """The names of ``(a, b, c)^{\\mathsf{T}}``."""
    m = re.fullmatch(r"\((.*)\)\^\{\\mathsf\{T\}\}", text.replace(r"\qquad", "").strip())
    return [n.strip() for n in m.group(1).split(", ")]


def _read_forces(case, i, values, forces):
    """Solve the printed groups from the last back; ``{name: value}`` of every force, the
    worst difference from the numeric ones over their scale (the centres of mass's
    accelerations over their largest, forces over ``F``, moments over ``F L``) and the values
    with the accelerations added."""
    part = case.parts["Forces"]
    head, *groups = re.split(r"\\subparagraph\{Group \d+\}", part)
    v = dict(values)
    meanings = dict(case.table)
    worst = 0.0
    for lhs, rhs in _rows(head):  # the centres of mass's accelerations
        v[lhs] = tex.value(rhs, v)
        m = re.fullmatch(r"acceleration of the centre of mass of link (.+), ([xy])", meanings[lhs])
        acc = case.res.links[m.group(1)].com_acceleration
        worst = max(worst, abs(v[lhs] - acc[i]["xy".index(m.group(2))]) / np.nanmax(np.abs(acc)))
    solved = {}
    for k in range(len(groups), 0, -1):
        body = groups[k - 1]
        defs = dict(_rows(body))
        names = _tuple(defs[rf"\mathbf{{F}}_{{{k}}}"])
        A = _matrix(body, defs, rf"\mathbf{{A}}_{{{k}}}", v)
        rhs = _matrix(body, defs, rf"\mathbf{{b}}_{{{k}}}", v)[:, 0]
        later = defs.get(rf"\mathbf{{F}}_{{>{k}}}")
        if later is not None:
            C = _matrix(body, defs, rf"\mathbf{{C}}_{{{k}}}", v)
            rhs = rhs - C @ np.array([solved[n] for n in _tuple(later)])
        solved.update(zip(names, np.linalg.solve(A, rhs)))
    for n, got in solved.items():
        scale = case.F * (case.L if case.units[n] == r"N\,m" else 1.0)
        worst = max(worst, abs(got - forces[n]) / scale)
    return solved, worst, v


@pytest.mark.slow
def test_the_printed_force_equations_give_the_numeric_reactions_and_efforts(case):
    for i in case.steps:
        case.step = i
        values, forces = _numbers(case, i)
        values, _ = _read_positions(case, values)
        solved, worst, v = _read_forces(case, i, values, forces)
        assert set(solved) == set(forces) and worst <= RTOL, (case.scene.name, i, worst)
        frame = dict(_rows(case.parts["Forces"].rsplit(r"\subparagraph", 1)[1]))
        v.update(solved)
        fx, fy, M = (tex.value(frame[k], v) for k in (r"F^{\mathrm{fr}}_{x}", r"F^{\mathrm{fr}}_{y}",
                                                      r"M^{\mathrm{fr}}"))
        np.testing.assert_allclose([fx, fy], case.res.forces.frame_force[i], rtol=0,
                                   atol=RTOL * case.F)
        assert abs(M - case.res.forces.frame_moment[i]) <= RTOL * case.F * case.L


@pytest.mark.slow
def test_a_wrong_number_is_seen(case):
    """The check can fail: a length 1e-6 off moves a position or a force beyond 1e-10."""
    i = case.steps[0]
    case.step = i
    values, forces = _numbers(case, i)
    length = next(sym for sym, meaning in case.table if meaning.startswith("distance from joint"))
    values[length] *= 1 + 1e-6
    rows = _rows(case.parts["Positions"])
    sigmas = [sym for sym, meaning in case.table if meaning.startswith("assembly mode of group")]
    worst = min(_positions(case, values, rows, dict(zip(sigmas, signs)))[0]
                for signs in itertools.product((1.0, -1.0), repeat=len(sigmas)))
    if worst <= RTOL:  # the length is not in a closed-form row: the forces see it
        _, worst, _ = _read_forces(case, i, values, forces)
    assert worst > RTOL
