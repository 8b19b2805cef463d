"""The JSON written by ``linkage-sym balance SCENE.json -o BALANCE.json``.

Keys (expressions are SymPy strings that :func:`sympy.sympify` reads back;
a *condition* is an expression that must equal zero):

``symbols``                    every symbol used, with its meaning
``link_frames``                ``{link: {"u": joint, "v": joint}}``
``parameters``                 the scene's value of every link parameter
``mass_parameters``            ``{"M_AB_1": expression in m, a, p, q, k}``
``acceleration_parameters``    ``{"D_AB_4": expression in pin coordinates and accelerations}``
``shaking_moment``             ``assembled`` (eq. 12 form), ``vanishing`` (eq. 10),
                               ``merged`` (eq. 11), ``regrouped`` (eq. 17 form),
                               ``force_balanced`` (eq. 18 form), ``pin_residuals``
``force_balance``              ``independent``/``dependent`` links, conditions by name
``force_balance_conditions``   list of conditions
``moment_balance_conditions``  list of conditions; ``moment_balance_reasons`` says why each
``counterweights``             counterweights satisfying the force conditions (or why none)
``series``                     shaking force and moment at every step, from the modules
``series_balanced``            the same with the counterweights
``optimized``, ``series_optimized``  with ``--optimize``: the optimised
                               counterweights and the force solver's series of the new scene
``seconds``                    derivation times
``latex``                      with ``--latex``: the same expressions as LaTeX

For a linkage with prismatic joints no condition is derived; with
``--optimize`` the JSON has ``scene``, ``conditions_derived`` (false),
``reasons``, ``optimized``, ``series`` and ``series_optimized`` (both from
the force solver) and ``series_source``.

:func:`balance_document` builds all of it (and the scene files and series
the command line writes next to it); :func:`balance_report` is its part for
the derived conditions.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from linkage_sym.balancing.conditions import Balance, derive_balance
from linkage_sym.balancing.options import SearchOptions
from linkage_sym.balancing.pins import require_hinged
from linkage_sym.balancing.series import ModuleFunctions, kinematics, module_series, solver_series
from linkage_sym.errors import BalanceError, SceneError
from linkage_sym.model import Scene


def latex_names(symbols) -> dict:
    """LaTeX for the balancing symbols: ``M_{AB1}``, ``\\ddot{x}_{B}``, ``\\ddot{\\varphi}_{2}``,
    the centre of mass ``x^{G}_{2}, y^{G}_{2}`` (as ``linkage-sym derive --latex`` prints it)."""
    out = {}
    for s in symbols:
        n = s.name
        head, _, rest = n.partition("_")
        if head in ("M", "D") and rest:
            out[s] = f"{head}_{{{rest.replace('_', '')}}}"
        elif head in ("xdd", "ydd"):
            out[s] = rf"\ddot{{{head[0]}}}_{{{rest}}}"
        elif head == "phidd":
            out[s] = rf"\ddot{{\varphi}}_{{{rest}}}"
        elif head in ("xG", "yG") and rest:
            sub = rest.replace("_", r"\_")
            out[s] = f"{head[0]}^{{G}}_{{{sub}}}"
        elif head in ("xi", "eta"):
            out[s] = rf"\{head}_{{{rest.replace('_', ',')}}}"
        elif rest:
            sub = rest.replace("_", r"\_")
            out[s] = f"{head}_{{{sub}}}"
    return out


def _s(e) -> str:
    return sp.sstr(e)


def _latex(e, names) -> str:
    return sp.latex(e, symbol_names=names)


def _meanings(model, sm) -> dict:
    """Every symbol's meaning: the model's, the shaking moment's, then those the links'
    angular accelerations add."""
    meanings = dict(model.meanings)
    meanings.update(sm.symbol_meanings())
    for link in model.links:
        model.phidd(link)
    meanings.update({k: v for k, v in model.meanings.items() if k not in meanings})
    return meanings


def balance_report(scene: Scene, balance: Balance | None = None, latex: bool = False,
                   counterweights: bool = True) -> tuple:
    """Everything ``linkage-sym balance`` writes (see the module docstring).

    Returns ``(report, series)``: the JSON-ready dict and the
    :class:`~.series.BalanceSeries` before (and, when counterweights balance
    the force, after) balancing, for the plots.
    """
    from linkage_sym.balancing.counterweight import with_counterweights
    from linkage_sym.balancing.force_counterweights import force_balancing_counterweights
    from linkage_sym.scene import load_scene

    b = balance or derive_balance(scene)
    model, sm, fb = b.model, b.moment, b.force
    meanings = _meanings(model, sm)
    out = {
        "scene": scene.name,
        "symbols": dict(sorted(meanings.items())),
        "link_frames": {l: {"u": f.u, "v": f.v} for l, f in model.frames.items()},
        "pins": {P: list(pin.joints) for P, pin in model.pins.items()},
        "parameters": model.values(),
        "mass_parameters": {n: _s(e) for n, e in sm.mass_parameters.items()},
        "acceleration_parameters": {D.name: _s(D.expr) for _, D in sm.terms},
        "shaking_moment": {
            "assembled": _s(sm.expression),
            "vanishing": list(sm.vanishing),
            "merged": {k: list(v) for k, v in sm.merged},
            "regrouped": _s(sm.regrouped_expression()),
            "force_balanced": _s(b.remaining),
            "pin_residuals": {P: _s(r) for P, r in b.pin_residuals.items()},
        },
        "force_balance": {
            "independent": list(fb.independent),
            "dependent": list(fb.dependent),
            "conditions": {c.name: _s(c.expr) for c in fb.conditions},
        },
        "force_balance_conditions": [_s(c.expr) for c in fb.conditions],
        "moment_balance_conditions": [_s(c.expr) for c in b.moment_conditions],
        "moment_balance_reasons": [f"{c.name}: {c.reason}" for c in b.moment_conditions],
        "constant_speed_links": list(b.constant_speed_links),
        "seconds": {k: round(v, 4) for k, v in b.seconds.items()},
    }
    functions = ModuleFunctions(sm)
    analysis = kinematics(scene)
    before = module_series(scene, sm, functions, analysis, label="as given")
    out["series"] = before.to_dict()
    series = [before]
    if counterweights:
        try:
            cws = force_balancing_counterweights(scene, b)
        except BalanceError as err:
            out["counterweights"] = {"error": str(err)}
        else:
            balanced = with_counterweights(scene, cws)
            after = module_series(load_scene(balanced), sm, functions, analysis, label="force-balanced")
            out["counterweights"] = [{"link": c.link, "mass": c.mass, "at": list(c.at)} for c in cws]
            out["balanced_scene"] = balanced
            out["series_balanced"] = after.to_dict()
            series.append(after)
    if latex:
        syms = set()
        for e in [sm.expression, b.remaining, sm.regrouped_expression(), *sm.mass_parameters.values(),
                  *(D.expr for _, D in sm.terms), *fb.expressions(), *(c.expr for c in b.moment_conditions)]:
            syms |= sp.sympify(e).free_symbols
        names = latex_names(syms)
        out["latex"] = {
            "mass_parameters": {n: _latex(e, names) for n, e in sm.mass_parameters.items()},
            "acceleration_parameters": {D.name: _latex(D.expr, names) for _, D in sm.terms},
            "shaking_moment": {
                "assembled": _latex(sm.expression, names),
                "regrouped": _latex(sm.regrouped_expression(), names),
                "force_balanced": _latex(b.remaining, names),
            },
            "force_balance_conditions": [_latex(c.expr, names) + " = 0" for c in fb.conditions],
            "moment_balance_conditions": [_latex(c.expr, names) + " = 0" for c in b.moment_conditions],
        }
    return out, series


def latex_fragment(report: dict) -> str:
    """The LaTeX of a balance report (built with ``latex=True``) as a fragment for a document
    that loads amsmath: mass and acceleration parameters, the shaking moment, and the force
    and moment balance conditions, one ``align*`` each.

    Examples
    --------
    >>> tex = latex_fragment({"scene": "demo", "latex": {
    ...     "mass_parameters": {"M_AB_1": "m"}, "acceleration_parameters": {},
    ...     "shaking_moment": {"assembled": "x", "regrouped": "x", "force_balanced": "y"},
    ...     "force_balance_conditions": ["m = 0"], "moment_balance_conditions": []}})
    >>> print(tex.splitlines()[4])
    M_{AB1} &= m
    """
    tex = report["latex"]

    def name(n: str) -> str:
        sym = sp.Symbol(n)
        return latex_names([sym]).get(sym) or sp.latex(sym)

    def condition(c: str) -> str:
        lhs, _, rhs = c.rpartition(" = ")
        return f"{lhs} &= {rhs}"

    scene = " ".join(str(report["scene"]).split())
    out = [f"% Shaking force and moment balance of the mechanism {scene} "
           "(Song and Wang 1992): a fragment for a document that loads amsmath", ""]
    blocks = [
        ("Mass parameters (Song and Wang 1992, eq.~6)",
         [f"{name(n)} &= {e}" for n, e in tex["mass_parameters"].items()]),
        ("Acceleration parameters (Song and Wang 1992, eq.~7)",
         [f"{name(n)} &= {e}" for n, e in tex["acceleration_parameters"].items()]),
        ("Shaking moment: assembled, regrouped, and what force balance leaves",
         [f"M_{{\\mathrm{{sh}}}} &= {tex['shaking_moment'][k]}"
          for k in ("assembled", "regrouped", "force_balanced")]),
        ("Force balance conditions", [condition(c) for c in tex["force_balance_conditions"]]),
        ("Moment balance conditions", [condition(c) for c in tex["moment_balance_conditions"]]),
    ]
    for title, rows in blocks:
        if not rows:
            continue
        out += [f"\\paragraph{{{title}}}", "\\begin{align*}", " \\\\\n".join(rows),
                "\\end{align*}", ""]
    return "\n".join(out)


@dataclass
class BalanceDocument:
    """What ``linkage-sym balance`` writes (see :func:`balance_document`).

    Attributes
    ----------
    report : dict
        The JSON (module docstring).
    series : list of BalanceSeries
        Shaking force and moment as given, then force-balanced (when
        counterweights could balance the force), then optimised (when asked),
        for the plots.
    balanced_scene : dict or None
        The scene with the force-balancing counterweights; ``None`` when none
        balance the force (``report["counterweights"]["error"]`` says why) or
        for a linkage with prismatic joints.
    optimized_scene : dict or None
        The scene with the optimised counterweights, when asked.
    """

    report: dict
    series: list
    balanced_scene: dict | None = None
    optimized_scene: dict | None = None


def balance_document(scene: Scene, latex: bool = False, optimize: SearchOptions | None = None) -> BalanceDocument:
    """Everything ``linkage-sym balance`` writes, built in one place.

    Parameters
    ----------
    scene : Scene
    latex : bool
        Add the expressions as LaTeX (hinged linkages only).
    optimize : SearchOptions, optional
        Also optimise counterweights with these options
        (:func:`~.options.search_options`).  A linkage with prismatic joints
        needs them: its conditions are not derived, and its series come from
        the force solver.

    Raises
    ------
    SceneError
        For prismatic joints without ``optimize``, or with ``latex``.
    BalanceError
        When the optimiser refuses the scene (no step whose status is ``ok``).
    """
    if all(j.type == "R" for j in scene.joints):
        report, series = balance_report(scene, latex=latex)
        doc = BalanceDocument(report, series, report.get("balanced_scene"))
        if optimize is not None:
            report["optimized"], after, doc.optimized_scene = _optimized(scene, optimize)
            report["series_optimized"] = after.to_dict()
            doc.series = [*series, after]
        return doc
    try:
        require_hinged(scene, "the mass/acceleration-parameter module (Song and Wang 1992)")
    except SceneError as err:
        if optimize is None or latex:
            raise
        why = "; ".join(err.problems)
    before = solver_series(scene, label="as given")
    section, after, optimized = _optimized(scene, optimize)
    report = {
        "scene": scene.name,
        "conditions_derived": False,
        "reasons": {"conditions": why},
        "optimized": section,
        "series": before.to_dict(),
        "series_optimized": after.to_dict(),
        "series_source": "numeric force solver, inertia only (no module: prismatic joints)",
    }
    return BalanceDocument(report, [before, after], None, optimized)


def _optimized(scene: Scene, options: SearchOptions) -> tuple:
    """The ``optimized`` section, the force solver's series of the optimised scene, and that scene."""
    from linkage_sym.balancing.search import optimize_counterweights
    from linkage_sym.scene import load_scene

    try:
        res = optimize_counterweights(scene, links=options.links, weights=options.weights,
                                      max_mass=options.max_mass, max_radius=options.max_radius)
    except ValueError as err:  # what the optimiser refuses (e.g. no ok step)
        raise BalanceError(str(err), field="optimize") from err
    after = solver_series(load_scene(res.scene), label="optimised")
    section = {
        "weights": list(options.weights), "links": list(options.links),
        "objective_start": res.objective_start, "objective": res.objective,
        "rms_start": res.rms_start, "rms_final": res.rms_final, "message": res.message,
        "notes": list(res.notes), "max_mass": dict(res.max_mass),
        "counterweights": [{"link": c.link, "mass": c.mass, "at": list(c.at)} for c in res.counterweights],
    }
    return section, after, res.scene
