"""The JavaScript backend of the evaluator: a mechanism solved in a browser (uses SymPy).

The page of :mod:`linkage_sym.page` solves a mechanism with the functions the derivation
prints (:func:`~linkage_sym.codegen.compile.build_artifact` with ``printer="javascript"``:
the same stages, the same layout as the NumPy runtime's, printed by SymPy's
``JavascriptCodePrinter`` after ``cse``) and a walk over the artifact's steps written in
JavaScript (``evaluator.js`` beside this module, package data, and ``evaluator_rates.js``:
the rate problems, the points by level and the force blocks, the hooks of
:class:`~linkage_sym.codegen.evaluator.Evaluator`): the closed steps with the
assembly-mode signs the NumPy runtime chooses, the Newton steps by the continuation policy
of :mod:`linkage_sym.numeric.continuation` (whose constants are this module's
:data:`CONSTANTS`, read from the Python modules that define them), the statuses, and the
parameters' recipes that read the joints' positions (:mod:`linkage_sym.structure.recipes`).

:func:`mechanism_script` is what a page inlines: the constants, the generated functions, the
evaluator and the mechanism's model (its joints, drivers, links, loads and traced points, and
the artifact's records the walk reads), as one script that needs no library and no network.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> text = mechanism_script(load_example("crank_rocker"))
>>> "function positions_0(X, XD, XDD, Q, QD, QDD, FORCES, P, CX, SX)" in text
True
"""

from __future__ import annotations

import dataclasses
import json
import math
from importlib import resources

from linkage_sym.codegen import cache
from linkage_sym.codegen.artifact import Artifact
from linkage_sym.codegen.compile import _Builder
from linkage_sym.codegen.runtime import ASSEMBLY_MATCH, SCREEN
from linkage_sym.errors import SYMBOLIC_LACKS, SceneError
from linkage_sym.model import Scene
from linkage_sym.numeric.continuation import roots
from linkage_sym.numeric.forces.loads import ACTIVE_END
from linkage_sym.numeric.engine.run import MAX_ANGLE_STEP, MAX_SLIDE_STEP, SINGULAR_COND
from linkage_sym.numeric.kinematics.loci import PARALLEL_ULPS, TANGENT_ULPS
from linkage_sym.numeric.results.transmission import rrr_dyads
from linkage_sym.scene.load import dump_scene
from linkage_sym.structure.parameters import driver_q0, ident, link_frames

__all__ = ["CONSTANTS", "FORCE_OUTPUTS", "PAGE_FUNCTIONS", "POSITION_POINTS", "POSITION_RECIPES",
           "evaluator_source", "mechanism_model", "mechanism_script", "page_artifact",
           "page_scene", "forces_left_out"]

CONSTANTS = {
    "TOL": roots.TOL, "MAX_ITER": roots.MAX_ITER, "STALL_ITER": roots.STALL_ITER,
    "POLISH_FLOOR": roots.POLISH_FLOOR, "MAX_POLISH": roots.MAX_POLISH,
    "MAX_CORRECTION": roots.MAX_CORRECTION, "MIN_FRACTION": roots.MIN_FRACTION,
    "SAME_ROOT": roots.SAME_ROOT, "TURNED_SEEDS": roots.TURNED_SEEDS,
    "SEARCH_ITER": roots.SEARCH_ITER, "SEARCH_STEP": roots.SEARCH_STEP,
    "SCREEN": SCREEN, "SINGULAR_COND": SINGULAR_COND, "ASSEMBLY_MATCH": ASSEMBLY_MATCH,
    "MAX_ANGLE_STEP": MAX_ANGLE_STEP, "MAX_SLIDE_STEP": MAX_SLIDE_STEP,
    "TANGENT_ULPS": TANGENT_ULPS, "EPS": float(2.0 ** -52), "ACTIVE_END": ACTIVE_END,
}
"""The evaluator's constants, each the Python runtime's own (``CONST`` in the script)."""

POSITION_POINTS = "position_points"
"""A function the page's artifact adds: the first rows of ``points`` (the joints' positions,
then the link frames' origins, as its layout places them), all a step of the sweep needs:
the whole ``points`` (velocities, accelerations, the force blocks) only for the layers."""

PAGE_FUNCTIONS = ("positions_", "newton_", "parallels_", "rates", "accelerations", "points",
                  POSITION_POINTS)
"""The generated functions a page calls (by name or prefix): the positions' steps, ``A``'s
entries and ``B qd`` (the singularity screen, the velocities), the accelerations'
right-hand side and the points (joints, frame origins, centres of mass by level, the force
blocks' entries); the cross products of the slides of dyads of two slides (parallel slides
cannot be assembled: :mod:`linkage_sym.codegen.parallels`)."""

FORCE_OUTPUTS = ("reactions", "driving")
"""The outputs a page's artifact adds for a scene with masses, inertias or loads (the
layer of reactions and driving efforts)."""

POSITION_RECIPES = ("l", "beta", "x", "y", "theta0", "gamma", "delta", "p", "q", "epsilon",
                    "xi", "eta")
"""The recipe tags that read the joints' assembly positions: re-derived in the page after
a drag (``RECIPES`` of ``evaluator.js``); the others are the scene's numbers."""


def evaluator_source() -> str:
    """The text of ``evaluator.js`` (the walk, Newton's continuation, the recipes), then
    ``evaluator_rates.js`` (the rate problems, the points by level, the forces)."""
    folder = resources.files("linkage_sym.codegen")
    return "\n".join(folder.joinpath(name).read_text("utf-8")
                     for name in ("evaluator.js", "evaluator_rates.js"))


def page_scene(scene: Scene) -> Scene:
    """``scene`` with the outputs its page's layers need: ``kinematics`` (velocities and
    accelerations), and the reactions and driving efforts where the scene has something
    they act on (a link's mass or inertia, a load); the same scene where it lists them.

    Examples
    --------
    >>> from linkage_sym.examples import load_example
    >>> s = load_example("crank_rocker")
    >>> page_scene(s) is s
    True
    """
    if forces_left_out(scene) is not None:  # the page derives the kinematics alone
        outputs = tuple(o for o in scene.outputs if o not in (*FORCE_OUTPUTS, "frame"))
        outputs += () if "kinematics" in outputs else ("kinematics",)
        effects = dataclasses.replace(scene.effects, springs=False, friction=False)
        return dataclasses.replace(scene, outputs=outputs, effects=effects)
    want = ["kinematics"]
    if scene.loads or any(lk.mass > 0 or lk.inertia > 0 for lk in scene.links):
        want += FORCE_OUTPUTS
    missing = [o for o in want if o not in scene.outputs]
    if not missing:
        return scene
    return dataclasses.replace(scene, outputs=tuple(scene.outputs) + tuple(missing))


def forces_left_out(scene: Scene) -> str | None:
    """Why a page of ``scene`` leaves its forces out, or None: the compiled symbolic layer
    does not solve joint friction (the contract's second part; its springs and dampers it
    derives), so such a page solves and draws the kinematics, and its force layer says why
    it is off.

    Examples
    --------
    >>> from linkage_sym.examples import load_example
    >>> forces_left_out(load_example("crank_rocker")) is None
    True
    >>> forces_left_out(load_example("crank_rocker_spring")) is None
    True
    >>> forces_left_out(load_example("slider_crank_press_friction"))
    "the page's equations leave the joints' friction out (the numeric methods solve it)"
    """
    if scene.effects.friction and any(
            j.friction is not None and j.friction.coefficient > 0 for j in scene.joints):
        return "the page's equations leave the joints' friction out (the numeric methods solve it)"
    return None


def page_artifact(scene: Scene) -> Artifact:
    """``scene``'s artifact with JavaScript sources, derived with the outputs the page's
    layers need (:func:`page_scene`): from the compiled-mechanism cache
    (:mod:`linkage_sym.codegen.cache`, under a key of its own printer), else derived and
    stored there, so a page of a topology already seen needs no SymPy derivation.

    Raises
    ------
    SceneError
        A scene the symbolic layer does not derive (a cam contact), naming the joint.
    """
    problems = [
        f"joints[{i}]: a page solves the mechanism with the symbolic layer's equations, which "
        f"do not support {SYMBOLIC_LACKS[j.type]} yet (joint '{j.name}' is of type {j.type}); "
        "the numeric solvers analyse it"
        for i, j in enumerate(scene.joints) if j.type in SYMBOLIC_LACKS]
    if problems:
        raise SceneError(problems)
    page = page_scene(scene)
    sig = {**cache.signature(page), "printer": "javascript"}  # one topology: one artifact
    key = cache.key_of(sig)
    got = cache.load_artifact(key)
    if got is not None:
        return got
    # the derivation's own builder, to print one more function from its equations
    builder = _Builder(page, "javascript")
    art = builder.artifact(key, sig)
    eqs = builder.eqs
    outs = [e for j in scene.joints for e in eqs.joint_kin[j.name][0]]
    outs += [e for n in scene.link_names for e in eqs.origin_kin[n][0]]
    builder.add(POSITION_POINTS, outs, "the joints' positions, then the frame origins' "
                "(the first rows of points: its layout)", True)
    art.functions[POSITION_POINTS] = builder.funcs[POSITION_POINTS]
    cache.store_artifact(key, art)
    return art


def mechanism_model(scene: Scene, art: Artifact) -> dict:
    """What the page's evaluator reads besides the generated functions (JSON-ready).

    The joints (type, links, assembly position, a ``P`` joint's axis, a mesh's carrier and
    pivots), the drivers (values in rad or m), the links' centres of mass, the loads'
    points and factors over the cycle, the RRR dyads (inner joint, external joints: the
    transmission angles), the traced points, the link frames' joints, the parameters (recipe and the
    scene's value), the artifact's records and the scene in the file layout
    (:func:`~linkage_sym.scene.load.dump_scene`).
    """
    frames = link_frames(scene)
    joints = {}
    for j in scene.joints:
        rec = {"type": j.type, "links": list(j.links), "at": list(j.at)}
        if j.axis is not None:
            rec["axis"] = j.axis
        if j.type == "G":
            rec["carrier"] = j.carrier
            rec["pivots"] = [p.name for p in scene.gear_pivots(j)]
        joints[j.name] = rec
    drivers = [{"joint": d.joint, "kind": d.kind, "toward": d.toward, "start": d.start,
                "stop": d.stop, "steps": d.steps, "speed": float(d.speed),
                "acceleration": float(d.acceleration)} for d in scene.drivers]
    return {
        "name": scene.name,
        "order": [j.name for j in scene.joints],
        "link_names": list(scene.link_names),
        "joints": joints,
        "drivers": drivers,
        "q0": [driver_q0(scene)[d.joint] for d in scene.drivers],
        "links": {lk.name: {"com": None if lk.com is None else list(lk.com)} for lk in scene.links},
        "ident": {n: ident(n) for n in (*scene.link_names, *(j.name for j in scene.joints))},
        "loads": [_load(ld) for ld in scene.loads],
        "dyads": [list(d) for d in rrr_dyads(scene)],
        "points": [{"name": p.name, "link": p.link, "at": list(p.at)} for p in scene.points],
        "frames": {n: [f.u, f.v] for n, f in frames.items()},
        "params": [{"name": p.name, "recipe": list(p.recipe.key),
                    "value": float(p.recipe.value(scene, frames))} for p in art.params],
        "sigmas": art.sigmas,
        "flanks": len(art.flanks),
        "forces_left_out": forces_left_out(scene),
        "scene": dump_scene(scene),
        "artifact": {
            "x": list(art.x), "q": list(art.q), "sigmas": art.sigmas,
            "params": [p.name for p in art.params],
            "steps": [s.to_dict() for s in art.steps],
            "groups": [g.to_dict() for g in art.groups],
            "rows_length": list(art.rows_length), "cols_length": list(art.cols_length),
            "pattern": [list(p) for p in art.pattern],
            "layout": {k: list(v) for k, v in art.layout.items()},
            "force_names": list(art.force_names),
            "stages": list(art.stages),
            "forces": [f.to_dict() for f in art.forces],
            "flanks": list(art.flanks),
            "load_entries": {str(k): v for k, v in art.load_entries().items()},
            # the dyads of two slides, where the mechanism has one (other pages unchanged)
            **({"parallels": [list(p) for p in art.parallels],
                "parallel_tol": PARALLEL_ULPS * float(2.0 ** -52)} if art.parallels else {}),
        },
    }


def _load(ld) -> dict:
    """A load as the page reads it: its link and point, and how it varies over the cycle
    (:func:`~linkage_sym.numeric.forces.loads.load_factor`)."""
    return {"link": ld.link, "at": None if ld.at is None else list(ld.at),
            "driver": ld.driver, "period": ld.period,
            "table": None if ld.table is None else [list(ld.table.q), list(ld.table.scale)],
            "active": None if ld.active is None else list(ld.active)}


def _json(value) -> str:
    # JSON inside a <script>: no "</" (it would end the script element)
    return json.dumps(value, allow_nan=False).replace("</", "<\\/")


def mechanism_script(scene: Scene, art: Artifact | None = None) -> str:
    """One script: ``CONST``, ``GENERATED`` (the page's generated functions), the evaluator
    (``LinkageEvaluator``) and ``MODEL`` (:func:`mechanism_model`)."""
    art = page_artifact(scene) if art is None else art
    funcs = [src for name, src in art.functions.items()
             if name.startswith(PAGE_FUNCTIONS[:3]) or name in PAGE_FUNCTIONS[3:]]
    names = [name for name in art.functions
             if name.startswith(PAGE_FUNCTIONS[:3]) or name in PAGE_FUNCTIONS[3:]]
    consts = {k: (v if math.isfinite(v) else None) for k, v in CONSTANTS.items()}
    return "\n".join([
        f"const CONST = {_json(consts)};",
        evaluator_source(),
        "// the functions generated by linkage_sym from SymPy (JavaScript printer, cse)",
        *funcs,
        f"const GENERATED = {{{', '.join(f'{n}: {n}' for n in names)}}};",
        f"const MODEL = {_json(mechanism_model(scene, art))};",
    ])
