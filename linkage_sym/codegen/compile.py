"""Compile a mechanism's derived equations into NumPy functions (uses SymPy).

:func:`compile_mechanism` derives a scene's equations with every parameter
kept symbolic, turns each stage's outputs into one function (SymPy's
``cse`` and ``NumPyPrinter``, as ``lambdify(..., cse=True)`` would, printed
directly) and stores the functions' source and
layout in the cache (:mod:`linkage_sym.codegen.cache`), keyed on the
topology.  The next scene of the same topology -- in this process or any
later one -- loads the artifact instead of deriving again.

Every generated function has the same fixed signature, written into its
docstring::

    f(X, XD, XDD, Q, QD, QDD, FORCES, P, CX=None, SX=None)

with ``X``, ``XD``, ``XDD`` the coordinates and their rates (list of
arrays), ``Q``, ``QD``, ``QDD`` the drivers', ``FORCES`` the reactions and
efforts and ``P`` the parameters followed by the assembly-mode signs; ``CX``, ``SX``
the cosines and sines of ``X`` (the functions after the positions read
them instead of evaluating trigonometric functions again).  A
function reads only the arguments its expressions use; the others may be
``None``.  Arrays broadcast: one call evaluates a whole sweep.
"""

from __future__ import annotations

import itertools
import keyword

import sympy as sp

from linkage_sym.codegen import cache
from linkage_sym.codegen.artifact import Artifact, FrictionJoint
from linkage_sym.codegen.runtime import CompiledMechanism, load_compiled
from linkage_sym.errors import refuse_symbolic_unsupported
from linkage_sym.model import Scene
from linkage_sym.numeric.engine.run import needed_stages
from linkage_sym.symbolic.mechanism import MechanismEquations

ARGS = ("X", "XD", "XDD", "Q", "QD", "QDD", "FORCES", "P", "CX", "SX")


def _names(symbols) -> list[str]:
    return [s.name for s in symbols]


PRINTERS = ("numpy", "mpmath", "javascript")
"""What generated code evaluates with: NumPy arrays (the compiled runtime), mpmath numbers
(arbitrary precision, :mod:`linkage_sym.codegen.precision`) or JavaScript numbers (the page
that solves a mechanism in a browser, :mod:`linkage_sym.codegen.javascript`)."""

JS_RESERVED = frozenset(
    "break case catch class const continue debugger default delete do else enum export extends "
    "false finally for function if import in instanceof new null return super switch this throw "
    "true try typeof var void while with yield let static implements interface package private "
    "protected public await arguments eval Math NaN Infinity undefined".split())
"""Names a generated JavaScript function may not bind (reserved words and the globals it reads)."""


def _printer(kind="numpy"):
    # the settings lambdify uses: names from ``from numpy import *`` / ``from mpmath import *``
    settings = {"fully_qualified_modules": False, "inline": True,
                "allow_unknown_functions": True, "user_functions": {}}
    if kind == "mpmath":
        from sympy.printing.pycode import MpmathPrinter

        return MpmathPrinter(settings)
    if kind == "javascript":
        from sympy.printing.jscode import JavascriptCodePrinter

        class _StrictJavascript(JavascriptCodePrinter):
            # a function without a JavaScript form is an error, never a comment; said here
            # rather than by the ``strict`` setting, which SymPy before 1.13 does not know
            def _print_not_supported(self, expr):
                raise ValueError(f"no JavaScript form for {type(expr).__name__}: {expr}")

        return _StrictJavascript({"user_functions": {}})
    if kind != "numpy":
        raise ValueError(f"unknown printer {kind!r}: one of {', '.join(PRINTERS)}")
    from sympy.printing.numpy import NumPyPrinter

    return NumPyPrinter(settings)


def generate(name: str, args: list, outputs: list, doc: str, printer: str = "numpy",
             companion=None):
    """Source of one generated function: common subexpressions, then NumPy code.

    Printed with SymPy's ``cse`` and ``NumPyPrinter`` directly (no editing of
    ``lambdify``'s text): ``args`` are the symbol lists of :data:`ARGS`, each
    unpacked only if the function reads one of its entries (the others may be
    ``None``); a symbol whose name is not a Python identifier is bound to a
    name of its own.  ``doc`` becomes the docstring.  ``printer``: ``"numpy"``,
    ``"mpmath"`` (rationals as quotients of ``mpf``, so no digit is lost to a float) or
    ``"javascript"`` (a JavaScript ``function`` of the same arguments and outputs, ``doc``
    its leading comment; SymPy's ``JavascriptCodePrinter``).

    ``companion``: ``(name, doc, outputs_of)``, a second function printed from the same
    common subexpressions, its outputs ``outputs_of(repl, reduced)`` (the ``cse``
    assignments and the first function's reduced outputs); then the two sources are
    returned.
    """
    js = printer == "javascript"
    printer = _printer(printer)
    outputs = [sp.sympify(e) for e in outputs]
    used = set().union(*(e.free_symbols for e in outputs)) if outputs else set()
    taken = {str(s) for s in used} | set(ARGS)
    rename = {}
    lines = []
    for arg, syms in zip(ARGS, args):
        if not any(s in used for s in syms):
            continue
        names = []
        for k, sym in enumerate(syms):
            nm = sym.name
            if (not nm.isidentifier() or keyword.iskeyword(nm) or nm in ARGS
                    or (js and (nm in JS_RESERVED or not nm.isascii()))):
                nm = f"{arg}_{k}"
                while nm in taken:
                    nm += "_"
                taken.add(nm)
                rename[sym] = sp.Symbol(nm, **sym.assumptions0)
            names.append(nm)
        lines.append(f"    [{', '.join(names)}] = {arg}")
    if rename:
        outputs = [e.xreplace(rename) for e in outputs]
    taken |= {str(s) for s in rename.values()}
    cse_names = (sp.Symbol(n) for n in (f"x{i}" for i in itertools.count()) if n not in taken)
    repl, reduced = sp.cse(outputs, symbols=cse_names)
    src = _print_function(name, lines, repl, reduced, doc, printer, js)
    if companion is None:
        return src
    name2, doc2, outputs_of = companion
    return src, _print_function(name2, lines, repl, outputs_of(repl, reduced), doc2, printer, js)


def _print_function(name, unpack, repl, reduced, doc, printer, js) -> str:
    """One function's text: the unpacking lines, the ``cse`` assignments, the outputs."""
    if js:
        return _javascript_function(name, unpack, repl, reduced, doc, printer)
    lines = list(unpack)
    for sym, e in repl:
        lines.append(f"    {sym} = {printer.doprint(e)}")
    lines.append(f"    return [{', '.join(printer.doprint(e) for e in reduced)}]")
    quoted = '    """' + doc.replace('"""', "'''").replace("\n", "\n    ") + '\n    """\n'
    sig = ", ".join(ARGS[:-2]) + ", CX=None, SX=None"
    return f"def {name}({sig}):\n" + quoted + "\n".join(lines) + "\n"


def _javascript_function(name, unpack, repl, reduced, doc, printer) -> str:
    """The JavaScript text of :func:`generate`'s function (``unpack``: its Python
    unpacking lines, the same destructuring in JavaScript)."""
    body = [f"  const {line.strip().split(' = ')[0]} = {line.strip().split(' = ')[1]};"
            for line in unpack]
    body += [f"  const {sym} = {printer.doprint(e)};" for sym, e in repl]
    body.append(f"  return [{', '.join(printer.doprint(e) for e in reduced)}];")
    comment = "\n".join(("  // " + ln).rstrip() for ln in doc.splitlines())
    sig = ", ".join(ARGS)
    return f"function {name}({sig}) {{\n{comment}\n" + "\n".join(body) + "\n}\n"


def _describe(kind: str, eqs: MechanismEquations, p_syms, outputs_desc: str) -> str:
    def listing(label, syms):
        return f"{label} = [{', '.join(_names(syms))}]"

    return "\n".join(
        [
            f"{kind} of mechanism '{eqs.scene.name}' (generated by linkage_sym from SymPy).",
            "",
            "Arguments, in this fixed order (each a list of arrays or numbers):",
            listing("X", eqs.x),
            listing("XD", eqs.xd),
            listing("XDD", eqs.xdd),
            listing("Q", eqs.q),
            listing("QD", eqs.qd),
            listing("QDD", eqs.qdd),
            listing("FORCES", getattr(eqs, "all_forces", [])),
            listing("P", p_syms),
            "CX, SX = cos and sin of every entry of X (computed once by the runtime and",
            "         shared by every function after the positions)",
            "",
            "Returns: " + outputs_desc,
        ]
    )


DIRECTIONS = ("for each coordinate: a slide's value; an angle's cosine and sine; or Y, X, "
              "cos r, sin r of an angle atan2(Y, X) + r")
"""What a closed step's directions function returns (its docstring's last line)."""


def _pattern(M) -> list:
    return [(i, j) for i in range(M.rows) for j in range(M.cols) if M[i, j] != 0]


def build_artifact(scene: Scene, printer: str = "numpy", key: str | None = None,
                   signature: dict | None = None) -> Artifact:
    """Derive ``scene`` with symbolic parameters and generate its functions.

    ``printer="mpmath"`` prints the same functions for mpmath numbers (one step at a
    time, any precision) instead of NumPy arrays; ``printer="javascript"`` as JavaScript
    functions (one step at a time, in a browser: :mod:`linkage_sym.codegen.javascript`).  ``key`` and ``signature``: the
    cache's, recorded in the artifact.
    """
    return _Builder(scene, printer).artifact(key, signature)


class _Builder:
    """One derivation printed stage by stage: the position steps, the rates, the points
    and force blocks (each a method), into the records of an :class:`Artifact`."""

    def __init__(self, scene: Scene, printer: str):
        self.scene, self.printer = scene, printer
        self.stages = needed_stages(scene)
        self.forces = "forces" in self.stages
        # joint friction (contract part two): its terms derived (where it acts and forces are
        # asked for), its laws solved at run time (codegen.friction)
        self.eqs = eqs = MechanismEquations(scene, symbolic=True, forces=self.forces,
                                            friction=True)
        laws = eqs.friction_laws
        arms = [[eqs.sym(n) for n in eqs.table.friction(law.joint) if n is not None]
                for law in laws]  # each joint's coefficient (and pin radius) in P
        self.p_syms = eqs.parameters + eqs.sigmas + eqs.flanks
        self.F = (eqs.all_forces + [law.friction for law in laws]) if self.forces else []
        self.friction = [FrictionJoint(law.joint, law.kind, self.F.index(law.friction),
                                       self.p_syms.index(a[0]),
                                       self.p_syms.index(a[1]) if len(a) > 1 else None)
                         for law, a in zip(laws, arms)]
        cx = [sp.Symbol("cos_" + s.name, real=True) for s in eqs.x]
        sx = [sp.Symbol("sin_" + s.name, real=True) for s in eqs.x]
        self.args = [eqs.x, eqs.xd, eqs.xdd, eqs.q, eqs.qd, eqs.qdd, self.F, self.p_syms, cx, sx]
        self.trig = {}
        for s, c, si in zip(eqs.x, cx, sx):
            if s.name.startswith("theta_"):
                self.trig[sp.cos(s)] = c
                self.trig[sp.sin(s)] = si
        self.angles = {s for s in eqs.x if s.name.startswith("theta_")}
        self.xi = {s: i for i, s in enumerate(eqs.x)}
        self.funcs: dict = {}

    def shared_trig(self, e):
        """``e`` with the sines and cosines of the link angles as inputs."""
        angles = self.angles
        e = e.replace(
            lambda n: isinstance(n, (sp.sin, sp.cos)) and bool(n.args[0].free_symbols & angles),
            lambda n: sp.expand_trig(n),
        )
        return e.xreplace(self.trig)

    def add(self, name, outputs, what, share=False):
        if share:
            outputs = [self.shared_trig(sp.sympify(e)) for e in outputs]
        self.funcs[name] = generate(name, self.args, outputs,
                                    _describe(name, self.eqs, self.p_syms, what), self.printer)

    def positions(self):
        """The position steps (closed-form segments between groups that need a numeric
        root) and the groups' records."""
        eqs, xi = self.eqs, self.xi
        steps, groups, segment = [], [], []
        defs = dict(eqs.closed_forms)

        def flush():
            if not segment:
                return
            name = f"positions_{len(steps)}"
            nested: dict = {}
            for s, e in eqs.closed_forms:
                if s in segment:
                    nested[s] = e.xreplace(nested)
            exprs = [nested[s] for s in segment]
            dname, forms = f"directions_{len(steps)}", []
            self.funcs[name], self.funcs[dname] = generate(
                name, self.args, exprs, _describe(name, self.eqs, self.p_syms,
                                                  "[" + ", ".join(_names(segment)) + "]"),
                self.printer, (dname, _describe(dname, self.eqs, self.p_syms, DIRECTIONS),
                               lambda repl, reduced: self.directions(segment, repl, reduced,
                                                                     forms)))
            steps.append({"kind": "closed", "function": name, "x": [xi[s] for s in segment],
                          "directions": dname, "forms": forms})
            segment.clear()

        for ge in eqs.groups:
            cols = [xi[s] for s in ge.x]
            if ge.closed:
                segment.extend(s for s in ge.x if s in defs)
            else:
                flush()
                name = f"newton_{ge.index}"
                rows = eqs.Phi[ge.rows, :]
                Jg = eqs.A[ge.rows, cols]
                self.add(name, list(rows) + list(Jg), f"residual ({rows.rows}) then jacobian (row-major)")
                steps.append({"kind": "newton", "function": name, "group": ge.index, "x": cols})
            groups.append({
                "index": ge.index, "links": list(ge.group.links), "label": ge.group.label,
                "closed": ge.closed, "cols": cols, "rows": [ge.rows.start, ge.rows.stop],
                "sigma": (None if ge.sigma is None
                          else len(eqs.parameters) + eqs.sigmas.index(ge.sigma)),
            })
        flush()
        return steps, groups

    def directions(self, segment, repl, reduced, forms) -> list:
        """The outputs of a closed step's directions function (its coordinates without the
        angles' arctangents, for a design sweep that needs only the angles' cosines and
        sines), from the positions function's common subexpressions ``repl`` and reduced
        outputs: a slide's value; an angle ``atan2(Y, X) + r`` (``Y``, ``X`` depending on
        the drivers) as ``Y, X, cos r, sin r`` -- the very arguments the positions
        function gives ``arctan2``; any other angle as its cosine and sine.  Appends each
        coordinate's form to ``forms`` (:class:`~linkage_sym.codegen.artifact.ClosedStep`)."""
        defs = dict(repl)
        deps: dict = {}  # a cse symbol -> the arguments' symbols it depends on
        for sym, e in repl:
            deps[sym] = set().union(*(deps.get(f, {f}) for f in e.free_symbols))
        drivers = set(self.eqs.q)

        def on_drivers(e):
            return any(deps.get(f, {f}) & drivers for f in e.free_symbols)

        outs = []
        for s, e in zip(segment, reduced):
            if s not in self.angles:
                outs.append(e)
                forms.append("value")
                continue
            head = None
            for t in sp.Add.make_args(e):
                at = defs.get(t, t)  # an arctangent the cse named
                if isinstance(at, sp.atan2) and on_drivers(at):
                    head = (t, at)
                    break
            if head is None:
                outs += [sp.cos(e), sp.sin(e)]
                forms.append("unit")
            else:
                r = e - head[0]
                outs += [head[1].args[0], head[1].args[1], sp.cos(r), sp.sin(r)]
                forms.append("atan2")
        return outs

    def parallels(self) -> list:
        """Each dyad of two slides (``PRP``, ``RPP``) as ``[group, slide joint, slide joint,
        joint at their intersection]``, with its function ``parallels_<group>`` giving the
        cross product of its slides' directions (the closed form's denominator: zero where
        the slides are parallel, its sign the side of infinity the joint is on) from the
        cosines and sines of the angles (``CX``, ``SX``: what a design sweep has); an empty
        list for a mechanism without such a dyad."""
        for g, _, _, den in self.eqs.two_slides:
            self.add(f"parallels_{g}", [den], "cross product of the directions of the dyad's "
                     "two slides (its closed form's denominator)", True)
        return [[g, a, b, joint] for g, (a, b), joint, _ in self.eqs.two_slides]

    def rates(self):
        """``A``'s non-zero entries and ``B qd``; the accelerations' right-hand side."""
        eqs = self.eqs
        pattern = _pattern(eqs.A)
        Bqd = eqs.B * sp.Matrix(eqs.qd)
        self.add("rates", [eqs.A[i, j] for i, j in pattern] + list(Bqd),
                 "nonzero entries of A, then B qd", True)
        if "acceleration" in self.stages:
            self.add("accelerations", list(eqs.acc_rhs), "right-hand side of A xdd = rhs", True)
        return pattern

    def points(self):
        """The points function (joints, frame origins, centres of mass by level, slide
        units, lines of action, the force blocks' entries) and its layout; the frame
        function and the force blocks' records."""
        eqs, scene, stages = self.eqs, self.scene, self.stages
        outs, layout = [], {}

        def put(key, values):
            layout[key] = [len(outs), len(outs) + len(values)]
            outs.extend(values)

        levels = [0] + ([1] if "velocity" in stages else []) + ([2] if "acceleration" in stages else [])
        for lev in levels:
            for j in scene.joints:
                put(f"joint:{j.name}:{lev}", eqs.joint_kin[j.name][lev])
            for n in scene.link_names:
                put(f"origin:{n}:{lev}", eqs.origin_kin[n][lev])
            for n, kin in eqs.com_kin.items():
                put(f"com:{n}:{lev}", kin[lev])
        for j in scene.joints:
            if j.type == "P":
                put(f"slide:{j.name}", list(eqs.slide_unit(j.name)))
            elif j.type == "G":  # the line of action, with the flank an input
                put(f"mesh:{j.name}", list(eqs.line_of_action(j)))
        force_layout = []
        if self.forces:
            fi = {s: i for i, s in enumerate(self.F)}
            mus = [self.F[f.force] for f in self.friction]
            for ge, (Ag, bg, Cg, later) in zip(eqs.groups, eqs.force_blocks):
                if mus:  # the frictions as known forces: b_g - C_g F_later - Cf_g mu
                    Cg, later = Cg.row_join(-bg.jacobian(mus)), list(later) + mus
                    bg = bg.xreplace({m: 0 for m in mus})
                pa, pc = _pattern(Ag), _pattern(Cg)
                k = ge.index
                put(f"A:{k}", [Ag[i, j] for i, j in pa])
                put(f"b:{k}", list(bg))
                put(f"C:{k}", [Cg[i, j] for i, j in pc])
                force_layout.append({"unknowns": [fi[s] for s in ge.forces], "A": pa,
                                     "C": [(i, fi[later[j]]) for i, j in pc]})
            for f in self.friction:  # the relative rates that give each friction its sign
                put(f"frate:{f.joint}", friction_rates(eqs, f))
            for name, _, effort, _, value in eqs.spring_efforts:  # each spring's record
                put(f"spring:{name}", [value, effort])
            self.add("frame", list(eqs.frame), "frame force x, y and moment about the origin", True)
        self.add("points", outs, "joint, origin and centre-of-mass kinematics, slide units, force blocks",
                 True)
        return layout, force_layout

    def artifact(self, key, signature) -> Artifact:
        eqs, scene = self.eqs, self.scene
        steps, groups = self.positions()
        pattern = self.rates()
        parallels = self.parallels()
        layout, force_layout = self.points()
        table = eqs.table
        return Artifact.from_dict({
            "scene": scene.name,
            "stages": list(self.stages),
            "x": _names(eqs.x),
            "q": [d.joint for d in scene.drivers],
            "params": [[s.name, list(_jsonable(table.params[s.name].recipe))] for s in eqs.parameters],
            "sigmas": len(eqs.sigmas),
            "flanks": [j.name for j in scene.meshes],
            "steps": steps,
            "groups": groups,
            "rows_length": eqs.row_is_length,
            # rows and columns of lengths, for the dimensionless condition number
            "cols_length": [s.name.startswith("s_") for s in eqs.x],
            "pattern": pattern,
            "layout": layout,
            "forces": force_layout,
            "force_names": _names(self.F),
            "functions": self.funcs,
            "friction": [f.to_dict() for f in self.friction],
            "parallels": parallels,
            "key": key,
            "signature": signature,
        })


def friction_rates(eqs, f) -> list:
    """The ``points`` outputs ``"frate:<joint>"`` of friction joint ``f``: for every moving
    link in scene order, its angular velocity and acceleration (an ``R`` joint), or the
    velocity and acceleration ``vx, vy, ax, ay`` of its point at the joint (a ``P``
    joint): the relative motion and the sizes it is compared with
    (:mod:`linkage_sym.codegen.friction`)."""
    out = []
    p = eqs.joint_kin[f.joint][0]
    for n in eqs.scene.link_names:
        c = eqs.x.index(eqs.th[n])
        w, al = eqs.xd[c], eqs.xdd[c]
        if f.kind == "R":
            out += [w, al]
            continue
        o, vo, ao = eqs.origin_kin[n]
        rx, ry = p[0] - o[0], p[1] - o[1]
        out += [vo[0] - w * ry, vo[1] + w * rx,
                ao[0] - al * ry - w * w * rx, ao[1] + al * rx - w * w * ry]
    return out


def _jsonable(recipe):
    return [list(v) if isinstance(v, tuple) else v for v in recipe]


def compile_mechanism(scene: Scene, use_cache: bool = True) -> CompiledMechanism:
    """The compiled mechanism of ``scene``: from the cache, or derived and generated.

    Examples
    --------
    >>> from linkage_sym.examples import load_example
    >>> cm = compile_mechanism(load_example("crank_rocker"))
    >>> result = cm.run()
    >>> round(float(result.forces.driving["A"][0]), 4)  # as the numeric solver
    -0.0755
    """
    refuse_symbolic_unsupported(scene, friction_derived=True)  # friction: solved at run time
    if use_cache:
        got = load_compiled(scene)
        if got is not None:
            return got
    sig = cache.signature(scene)
    key = cache.key_of(sig)
    art = build_artifact(scene, key=key, signature=sig)
    if use_cache:
        cache.store_artifact(key, art)
    return CompiledMechanism(art, scene)
