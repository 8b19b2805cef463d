"""A self-contained page that solves a mechanism in the browser (``linkage-sym view``).

:func:`page_html` writes one HTML file with everything inline -- its style, its script, the
functions the symbolic layer prints in JavaScript and the evaluator that walks them
(:mod:`linkage_sym.codegen.javascript`) -- and nothing fetched: no network, no font, no
image.  The page draws the links, joints and traced paths on a canvas; plays the sweep
(play / pause, a slider over the driver's range, a speed); lets a joint's assembly position
be dragged or typed, or a length typed, and re-derives the parameters and re-solves the
whole sweep at once, the assembly modes chosen from the new assembly configuration as the
scene format says; shows each step's status; and downloads the edited scene as a scene
file.  Its layers (``layers.js``, ``centres.js``), each behind a checkbox and off when the
page opens, draw the joints' and traced points' velocities and accelerations, the joint
reactions and driving efforts (arrows with one scale over the sweep, written on the page),
the instant centres with the three-centre lines of Kennedy's construction, and the RRR
dyads' transmission angles; a layer the scene has no values for (no mass, inertia or load:
no forces; no RRR dyad) is disabled, its reason shown.  Its warnings panel (``warnings.js``,
:mod:`linkage_sym.page.warnings`) opens with those of the Python run the page was built from,
when its caller gives one, and after each change lists what the page's evaluator finds (steps
that cannot be assembled or are singular, a joint passing through infinity), the run's
other warnings greyed as from the scene as built.  For tests and scripts it defines
``window.linkageSym``:

- ``solve(q)``: the mechanism at the driver values ``q`` (a number for one driver, a list
  in the drivers' order or ``{joint: value}``; rad for an ``R`` driver, m for a ``P`` one,
  as a result file gives them), reached continuously from the assembly configuration:
  ``{status, message, joints: {name: [x, y]}, points: {name: [x, y]}}``;
- ``moveJoint(name, x, y)``: what a drag does (every joint at the same point moves with
  it); returns ``{error, counts}`` (the sweep's statuses counted);
- ``scene()``: the current scene in the format's JSON (what ``linkage-sym analyze`` reads);
- ``warnings()``: the panel: ``{shown: [{text, origin, recomputed, stale}], page, built,
  changed}`` (``origin`` ``"python"`` or ``"page"``; ``page`` the texts the page's evaluator
  finds now, ``built`` the run's or null, ``changed`` whether the scene differs from it);
- ``layers(q)``: the layers' values at ``q`` (the drivers at the scene's speeds and
  accelerations): ``{status, velocities: {joints, points}, accelerations: {joints, points},
  reactions: {joint: [fx, fy]}, reaction_moments, driving: {joint: effort}, centres:
  {"a,b": record}, lines, transmission_deg: {inner joint: degrees}}`` (``reactions`` and
  ``driving`` null without forces; a centre's record as the result file's
  ``instant_centres``); ``setLayer(name, on)``, ``layersAvailable()``, ``layerScales()``.

A mechanism with cam contacts, which the symbolic layer does not derive, is solved instead by
``cams.js`` (inlined after the evaluator): a port of the numeric layer's input-link, RRR
dyad and cam-follower solvers reading :func:`~linkage_sym.page.cam_model.cam_page_model` (each
profile as data); the page draws the profile and the follower's roller or face.  Gear
meshes are the symbolic layer's.  :mod:`linkage_sym.page.gallery` writes the pages of the
shipped examples and a gallery linking them (the demo does).

Examples
--------
>>> from linkage_sym.examples import load_example
>>> html = page_html(load_example("crank_rocker"))
>>> html.startswith("<!DOCTYPE html>"), "http://" in html or "https://" in html
(True, False)
"""

from __future__ import annotations

import json
import math
from importlib import resources

from linkage_sym.centres import kennedy_lines, velocity
from linkage_sym.codegen.javascript import CONSTANTS, evaluator_source, mechanism_script
from linkage_sym.model import Scene
from linkage_sym.page.cam_model import cam_page_model
from linkage_sym.page.warnings import built_warnings

__all__ = ["cam_script", "layer_constants", "page_html"]


def _read(name: str) -> str:
    return resources.files("linkage_sym.page").joinpath(name).read_text("utf-8")


def _json(value) -> str:
    # JSON inside a <script>: no "</" (it would end the script element)
    return json.dumps(value, allow_nan=False).replace("</", "<\\/")


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def cam_script(scene: Scene) -> str:
    """The script before ``cams.js`` on the page of a cam mechanism: ``CONST``, the evaluator
    (its linear algebra, solving path and errors), no generated function and ``MODEL``
    (:func:`~linkage_sym.page.cam_model.cam_page_model`)."""
    consts = {k: (v if math.isfinite(v) else None) for k, v in CONSTANTS.items()}
    return "\n".join([f"const CONST = {_json(consts)};", evaluator_source(),
                      "const GENERATED = {};", f"const MODEL = {_json(cam_page_model(scene))};"])


def layer_constants() -> str:
    """``LAYER_CONST``: the constants of the instant centres' construction the page's
    ``centres.js`` uses, each read from the Python module that defines it."""
    consts = {"FAR": kennedy_lines.FAR, "DEGENERATE": kennedy_lines.DEGENERATE,
              "ROUNDING": kennedy_lines.ROUNDING, "DISTINCT": kennedy_lines.DISTINCT,
              "UNCERTAIN": kennedy_lines.UNCERTAIN, "REST": velocity.REST,
              "VELOCITY_FAR": velocity.FAR}
    return f"const LAYER_CONST = {json.dumps(consts)};"


def page_html(scene: Scene, analysis=None) -> str:
    """The page of ``scene`` (one HTML document, everything inline).

    ``analysis``: a Python run of ``scene`` (:func:`linkage_sym.analyze`; the command line's
    ``view`` makes one), whose warnings the page's warnings panel opens with
    (:func:`~linkage_sym.page.warnings.built_warnings`); without it the panel opens with what
    the page's own evaluator finds.  The page itself runs no Python solver.

    Raises
    ------
    SceneError
        A mechanism with cam contacts and a group the page's port of the solvers does not
        solve (a dyad other than RRR, a gear, a Newton group), naming it.
    """
    built = None if analysis is None else built_warnings(analysis)
    layers = [layer_constants(), _read("centres.js"), _read("layers.js"),
              f"const BUILT = {_json(built)};", _read("warnings.js")]
    if scene.cams:  # the symbolic layer derives no cam contact: cams.js ports the solvers
        script = "\n".join([cam_script(scene), _read("cams.js"), *layers, _read("page.js")])
    else:
        script = "\n".join([mechanism_script(scene), *layers, _read("page.js")])
    if "</script" in script.lower():  # pragma: no cover - nothing generated writes it
        raise ValueError("the page's script may not contain '</script'")
    out = _read("page.html")
    for key, value in (("%%TITLE%%", _escape(f"{scene.name} - linkage_sym")),
                       ("%%STYLE%%", _read("page.css")), ("%%SCRIPT%%", script)):
        out = out.replace(key, value, 1)
    return out
