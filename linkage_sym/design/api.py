"""``linkage_sym.sweep``: evaluate many designs of one scene's topology at once."""

from __future__ import annotations

import dataclasses
import json
import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from linkage_sym.design.aliases import current_name, current_names
from linkage_sym.design.errors import SweepError
from linkage_sym.design.execute import TARGET_ENTRIES, Execution, Spec, compiled_state, run_chunks
from linkage_sym.design.metrics import DEFAULT_METRICS, MetricPlan, check_choices, refuse_meshes
from linkage_sym.design.newton_groups import DEFAULT_CHUNK as ONE_AT_A_TIME_CHUNK
from linkage_sym.design.parameters import Designs, MonteCarlo, check_names, grid
from linkage_sym.design.parameters import design_problems, read_samples, refuse_invalid
from linkage_sym.design.table import SweepResult

__all__ = ["sweep", "scene_parameters", "default_metrics"]


def _as_scene(scene):
    from linkage_sym.model import Scene

    if isinstance(scene, Scene):
        return scene
    from linkage_sym.scene import load_scene

    return load_scene(scene)


def scene_parameters(scene) -> list:
    """``(name, value, meaning)`` of every parameter a sweep may vary (what
    ``linkage-sym sweep SCENE --list`` prints).

    Examples
    --------
    >>> import linkage_sym
    >>> rows = scene_parameters(linkage_sym.load_example("crank_rocker"))
    >>> [(n, round(v, 6)) for n, v, _ in rows[2:5]]
    [('l_AB', 0.024), ('l_BC', 0.063032), ('l_CD', 0.048508)]
    """
    from linkage_sym.design.evaluate import Model
    from linkage_sym.design.parameters import parameter_list

    scene = _as_scene(scene)
    model = Model(scene, forces=_has_forces(scene))
    return parameter_list(scene, model.names, model.params)


def _has_forces(scene) -> bool:
    return any(lk.mass > 0 or lk.inertia > 0 for lk in scene.links) or bool(scene.loads)


def sweep(scene, parameters, metrics=None, *, output=None, trace=None, scenes=None,
          execution=None) -> SweepResult:
    """Evaluate many designs of a scene: a grid, samples or a Monte Carlo spread.

    Every design is the scene with some named parameters (the symbolic layer's
    names, :mod:`linkage_sym.structure.parameters`; :func:`scene_parameters`
    lists them) set to other values, assembled at the scene's driver values in
    the scene's assembly mode, and solved over the scene's sweep by the
    compiled mechanism's functions, many designs per call
    (:mod:`linkage_sym.design.evaluate`).  A scene with groups without a closed
    form (class-III triads, actuator groups) has its designs solved one at a
    time, each by the numeric plan of its own scene
    (:mod:`linkage_sym.design.newton_groups`; the result's ``one_at_a_time``
    names those groups).

    Parameters
    ----------
    scene : Scene, dict or path
    parameters : mapping of str to sequence, Designs, MonteCarlo, or path
        The designs: a mapping is a grid, the product of these axes of values (the
        first varies slowest); :class:`~linkage_sym.design.parameters.Designs` are
        given designs (:func:`~linkage_sym.design.parameters.grid`,
        :func:`~linkage_sym.design.parameters.read_samples`); a
        :class:`~linkage_sym.design.parameters.MonteCarlo` is a spread drawn about the
        scene's values; a path (``str`` or ``os.PathLike``) is a CSV file of designs
        (a header of parameter names).
    metrics : sequence of str, optional
        Default: those of :data:`~linkage_sym.design.metrics.DEFAULT_METRICS` the scene
        has (``assemblable``, ``grashof``, ``K``, ``swing``, ``min_transmission_deg``).
        From :data:`linkage_sym.design.metrics.METRICS` (their definitions are
        in that module): ``assemblable``, ``grashof``, ``K``, ``swing``,
        ``min_transmission_deg``, ``peak_driving``, ``rms_driving``,
        ``peak_reaction``, ``rms_shaking_force``, ``rms_shaking_moment``, ``path``.
    output : str, optional
        The link of the metrics ``K`` and ``swing`` (default: the last link pivoted on
        the ground that is not driven).
    trace : str or sequence of str, optional
        The traced points of the metric ``path`` (default: all the scene's).
    scenes : SceneFiles, optional
        Write each design's own scene too (:class:`~linkage_sym.design.scenes.SceneFiles`:
        a folder, and optionally only some designs'); default none.
    execution : Execution, optional
        Where the chunks run (:class:`~linkage_sym.design.execute.Execution`: local
        processes, Dask, the designs per chunk, a progress bar); default in this
        process, without a progress bar.

    Every design is checked by the scene's rules
    (:func:`~linkage_sym.design.parameters.design_problems`: each varied parameter held
    to the rule of the scene field it fills, a length > 0): one that breaks a rule is
    not solved and gets no scene, and the table gains an ``invalid`` column giving the
    rule (empty for the valid designs), its metrics empty.

    Returns
    -------
    SweepResult
        One row per design: ``design``, the parameters, ``invalid`` (only when a design
        is), the metric columns.

    Raises
    ------
    SweepError
        Input it cannot use, naming the argument or attribute (an unknown parameter lists
        the valid ones); designs none of which is valid (naming a grid axis none of whose
        values is, with the rule).

    Examples
    --------
    >>> import linkage_sym
    >>> from linkage_sym.design import Execution, MonteCarlo
    >>> scene = linkage_sym.load_example("crank_rocker")
    >>> res = linkage_sym.sweep(scene, {"l_AB": [0.02, 0.024], "l_BC": [0.06, 0.065]},
    ...                         ["grashof", "K", "min_transmission_deg"])
    >>> list(res.columns)
    ['design', 'l_AB', 'l_BC', 'grashof', 'K', 'K_note', 'min_transmission_deg']
    >>> res["grashof"].tolist()
    ['crank-rocker', 'crank-rocker', 'crank-rocker', 'crank-rocker']
    >>> [round(float(k), 4) for k in res["K"]]
    [1.0503, 1.0071, 1.0945, 1.0082]
    >>> spread = linkage_sym.sweep(scene, MonteCarlo(4, {"l_AB": 5e-5}, random_state=1), ["K"],
    ...                            execution=Execution(chunk_designs=2))
    >>> spread.kind, len(spread), bool(abs(spread["l_AB"] - 0.024).max() < 5e-4)
    ('monte-carlo', 4, True)
    """
    scene = _as_scene(scene)
    execution = Execution() if execution is None else execution
    refuse_meshes(scene)
    designs = _designs(scene, parameters)
    check_choices(scene, output, trace)
    defaulted = metrics is None
    if metrics is None:
        metrics = default_metrics(scene, output)
    metrics = [metrics] if isinstance(metrics, str) else list(metrics)
    plan = MetricPlan(scene, metrics, output, trace)
    backend = _backend(execution.backend, plan.metrics if defaulted else ())
    spec = Spec(scene, tuple(designs.names), tuple(plan.metrics), plan.output,
                None if trace is None else tuple([trace] if isinstance(trace, str) else trace),
                backend=backend)
    model, _ = compiled_state(spec)
    if scenes is not None or any(n not in model.names for n in designs.names):
        # a mass, inertia or load is a parameter of the force blocks only
        spec = dataclasses.replace(spec, forces=True)
        model, _ = compiled_state(spec)
    field_name = _FIELD_OF_KIND[designs.kind]
    check_names(designs, model.names, field_name)
    recipes = {model.names[i]: r for r, i in model.recipes.items()}
    problems = design_problems(scene, designs, recipes)
    refuse_invalid(scene, designs, recipes, problems, field_name)
    valid = problems == ""
    workers, chunk_designs = execution.workers, execution.chunk_designs
    if workers is not None:
        if not isinstance(workers, int) or isinstance(workers, bool) or workers < 1:
            raise SweepError("workers", f"at least 1 process, got {workers!r}")
    if chunk_designs is None:
        chunk_designs = (ONE_AT_A_TIME_CHUNK if model.one_at_a_time
                         else max(1, getattr(model, "chunk_entries", TARGET_ENTRIES)
                                  // model.path.shape[1]))
    elif not isinstance(chunk_designs, int) or chunk_designs < 1:
        raise SweepError("chunk_designs", f"at least 1 design, got {chunk_designs!r}")
    files, no_scene, bad_scene = [], [], []
    if scenes is not None:
        rows = None if scenes.rows is None else _rows(scenes.rows, len(designs))
        files, no_scene, bad_scene = _write_scenes(model, designs, Path(scenes.folder),
                                                   chunk_designs, rows, problems)
    # an invalid design is not solved: its metrics are left blank
    parts = run_chunks(spec, designs.values[valid], chunk_designs, workers, execution.dask,
                       execution.progress)
    columns = {"design": np.arange(len(designs))}
    for k, n in enumerate(designs.names):
        columns[n] = designs.values[:, k].copy()
    if not valid.all():
        columns["invalid"] = problems
    mcols = list(parts[0])
    for c in mcols:
        solved = np.concatenate([p[c] for p in parts])
        columns[c] = np.full(len(designs), "" if solved.dtype.kind in "US" else np.nan,
                             dtype=solved.dtype)
        columns[c][valid] = solved
    return SweepResult(columns, tuple(designs.names), tuple(mcols), designs.kind, designs.axes,
                       scene.name, files, tuple(model.newton_groups), tuple(no_scene),
                       tuple(bad_scene))


_FIELD_OF_KIND = {"grid": "parameters", "samples": "samples", "monte-carlo": "tolerance"}
"""The argument a problem of the designs' names is laid to, by the kind of designs: a grid's
axes, a CSV file's header, a Monte Carlo spread's ``tolerance``."""


def default_metrics(scene, output=None) -> list:
    """The metrics of :data:`DEFAULT_METRICS` that apply to ``scene``."""
    out = []
    for m in DEFAULT_METRICS:
        try:
            MetricPlan(scene, [m], output)
        except SweepError:
            continue
        out.append(m)
    return out


def _designs(scene, parameters) -> Designs:
    """The designs ``parameters`` stands for (see :func:`sweep`), former parameter names
    read as the current ones (:mod:`linkage_sym.design.aliases`)."""
    if isinstance(parameters, Designs):
        return current_names(parameters, scene)
    if isinstance(parameters, Mapping):
        return current_names(grid(parameters), scene)
    if isinstance(parameters, (str, os.PathLike)):
        return current_names(read_samples(parameters), scene)
    if not isinstance(parameters, MonteCarlo):
        raise SweepError("parameters", "a mapping of names to values (a grid), Designs, "
                                       "MonteCarlo or the path of a CSV file is expected, got "
                                       f"{type(parameters).__name__}")
    model, _ = compiled_state(Spec(scene, (), ("assemblable",), forces=True))
    base = {n: v for n, v in zip(model.names, model.params)}
    if isinstance(parameters.tolerance, Mapping):
        tolerance = {current_name(n, scene): v for n, v in parameters.tolerance.items()}
        parameters = dataclasses.replace(parameters, tolerance=tolerance)
    for n in (parameters.tolerance or {}):
        if n not in base or n.startswith("theta0_"):
            check_names(Designs((n,), np.zeros((1, 1)), "monte-carlo"), model.names, "tolerance")
    return parameters.designs(base)


def _backend(backend, defaults=()) -> str:
    """The backend's name, checked (numba's, that numba is installed, and that it computes
    the default metrics ``defaults`` when no metric was named), before any work."""
    from linkage_sym.design.numba_sweep import BACKENDS, SUPPORTED, require_numba

    if backend not in BACKENDS:
        raise SweepError("backend", f"unknown backend {backend!r}; the backends are "
                                    f"{', '.join(BACKENDS)}")
    if backend == "numba":
        require_numba()
        other = [m for m in defaults if m not in SUPPORTED]
        if other:
            raise SweepError("backend", f"the numba backend computes {', '.join(SUPPORTED)}; "
                                        f"not {', '.join(other)}, which the default metrics "
                                        "include: name the metrics, or use the NumPy backend")
    return backend


def _rows(rows, n: int) -> np.ndarray:
    """The design numbers ``rows`` (numbers, or ``range`` objects) checked against the ``n``
    designs, sorted, once each."""
    out = []
    for r in rows:
        if isinstance(r, range):  # checked by its ends before it is listed
            if len(r) and not (0 <= r[0] < n and 0 <= r[-1] < n):
                first = r[0] if not 0 <= r[0] < n else max(r[0], n)
                raise SweepError("rows", f"no design {first}: the designs are 0 to {n - 1}")
            out.extend(r)
            continue
        try:
            v = int(r)
        except (TypeError, ValueError):
            raise SweepError("rows", f"design numbers are expected, got {rows!r}") from None
        if isinstance(r, bool) or not 0 <= v < n:
            raise SweepError("rows", f"no design {r!r}: the designs are 0 to {n - 1}")
        out.append(v)
    if not out:
        raise SweepError("rows", "no design named")
    return np.unique(np.array(out, dtype=int))


def _write_scenes(model, designs, folder: Path, size: int, rows=None, problems=None):
    """Write the scenes of the designs ``rows`` (default all); the files, the designs that
    cannot be assembled (no scene), and ``(design, problem)`` of those whose scene breaks
    the scene's rules (``problems``, from :func:`design_problems`, or the scene reader's
    own check of the scene before it is written): none of these is written."""
    from linkage_sym.design.scenes import design_scene
    from linkage_sym.errors import SceneError
    from linkage_sym.scene.load import dump_scene
    from linkage_sym.scene.validate import parse_scene

    folder.mkdir(parents=True, exist_ok=True)
    files, missing, bad = [], [], []
    width = max(1, len(str(len(designs) - 1)))
    rows = np.arange(len(designs)) if rows is None else rows
    if problems is not None:
        bad = [(int(i), str(problems[i])) for i in rows if problems[i]]
        rows = np.array([i for i in rows if not problems[i]], dtype=int)
    for a in range(0, len(rows), size):
        which = rows[a:a + size]
        vals = designs.values[which]
        P = model.design_params(designs.names, vals)
        P, X0, ok, joints0, _ = model.assemble(P, len(vals))
        for d, i in enumerate(which.tolist()):
            if not ok[d]:
                missing.append(i)
                continue
            sc = design_scene(model, P, X0, joints0, d, f"{model.scene.name}-design-{i}")
            data = dump_scene(sc)
            try:  # the reader's whole check: no scene is written that analyze would refuse
                parse_scene(data)
            except SceneError as err:
                bad.append((i, err.problems[0]))
                continue
            path = folder / f"design_{i:0{width}d}.json"
            path.write_text(json.dumps(data, indent=1) + "\n")
            files.append(str(path))
    bad.sort()
    return files, missing, bad
