"""Result files of any length (linkage_sym.output): chunks, formats, memory, partial files.

Checked against independent methods:

* the JSON against a frozen copy of the contract writer as it was before
  results were streamed (``_contract_dict``, below): byte for byte;
* CSV, npz and Parquet columns against the JSON's records, read back with the
  standard library's ``csv``, ``numpy.load`` and ``pyarrow.parquet``;
* a sweep solved in chunks against the same sweep solved at once (values to
  1e-12 of each quantity's largest magnitude, statuses and messages equal);
* merged warnings against ``run_warnings`` of the whole run;
* the memory estimate against tracemalloc's measured peak.
"""

from __future__ import annotations

import copy
import csv
import dataclasses
import json
import math
import sys
import tracemalloc

import numpy as np
import pytest

import linkage_sym
from linkage_sym import output
from linkage_sym.cli import main
from linkage_sym.examples import example_dict, example_names
from linkage_sym.numeric.plan import compile_plan
from linkage_sym.numeric.engine.run import run_warnings
from linkage_sym.numeric.results.result import Analysis

from tests.support import scenes  # the tests' scene builders (tests/support/scenes.py)
from tests.support.marks import slow_cases

REL = 1e-12
"""Chunked vs whole: tolerance relative to the largest magnitude of the quantity."""
NEWTON = ("hydraulic_boom", "printing_mechanism", "printing_mechanism_stroke", "sixbar_class3")


# -- an independent writer: the contract's JSON as written before streaming -----------------------

def _vec(v):
    return [float(v[0]), float(v[1])]


def _finite(value, path, dropped):
    if isinstance(value, float):
        if math.isfinite(value):
            return value
        dropped.append(path)
        return _finite
    if isinstance(value, dict):
        out = {}
        for k, v in value.items():
            kept = _finite(v, f"{path}.{k}", dropped)
            if kept is not _finite:
                out[k] = kept
        return out
    if isinstance(value, list):
        if all(isinstance(x, float) and math.isfinite(x) for x in value):
            return value
        dropped.append(path)
        return _finite
    return value


def _contract_dict(self) -> dict:
    """``Analysis.to_dict`` as of commit 6d0b3fd (one step at a time, element by element)."""
    steps = []
    want_kin = "kinematics" in self.outputs
    has_vel, has_acc = "velocity" in self.stages, "acceleration" in self.stages
    forces = self.forces

    def motion(k, i, rates):
        rec = {"position": _vec(k.position[i])}
        if rates and has_vel:
            rec["velocity"] = _vec(k.velocity[i])
        if rates and has_acc:
            rec["acceleration"] = _vec(k.acceleration[i])
        return rec

    dropped = []
    for i in range(self.n_steps):
        st = str(self.status[i])
        step = {"status": st}
        if self.messages[i] is not None:
            step["message"] = self.messages[i]
        step["drivers"] = {n: {k: float(v[i]) for k, v in d.items()} for n, d in self.drivers.items()}
        positions, rates = st in ("ok", "singular"), st == "ok"
        if want_kin and positions:
            step["joints"] = {n: motion(jk, i, rates) for n, jk in self.joints.items()}
            links = {}
            for n, lk in self.links.items():
                rec = {"rotation": float(lk.rotation[i])}
                if rates and has_vel:
                    rec["omega"] = float(lk.omega[i])
                if rates and has_acc:
                    rec["alpha"] = float(lk.alpha[i])
                if lk.com is not None:
                    rec["com"] = _vec(lk.com[i])
                    if rates and has_vel:
                        rec["com_velocity"] = _vec(lk.com_velocity[i])
                    if rates and has_acc:
                        rec["com_acceleration"] = _vec(lk.com_acceleration[i])
                links[n] = rec
            step["links"] = links
            if self.points:
                step["points"] = {n: motion(pk, i, rates) for n, pk in self.points.items()}
        if forces is not None and rates:
            if "reactions" in self.outputs:
                joints = step.setdefault("joints", {})
                for n, r in forces.reactions.items():
                    rec = joints.setdefault(n, {})
                    rec["reaction"] = _vec(r[i])
                    if n in self.p_joints:
                        rec["reaction_moment"] = float(forces.reaction_moments[n][i])
            if "driving" in self.outputs:
                step["driving"] = {k: float(v[i]) for k, v in forces.driving.items()}
            if "frame" in self.outputs:
                step["frame"] = {"force": _vec(forces.frame_force[i]),
                                 "moment": float(forces.frame_moment[i])}
        steps.append(_finite(step, f"steps[{i}]", dropped))
    out = {"scene": self.scene, "stages": list(self.stages), "steps": steps}
    if forces is not None:
        out["force_method"] = forces.method
        out["groups"] = [
            {"links": list(g.links), "method": g.method,
             **({"choices": list(g.choices),
                 "steps_per_choice": {g.choices[k]: int((g.used == k).sum())
                                      for k in range(len(g.choices)) if (g.used == k).any()}}
                if g.used is not None else {})}
            for g in forces.groups]
    warnings = list(self.warnings)
    if dropped:
        shown = ", ".join(dropped[:3]) + (f" and {len(dropped) - 3} more" if len(dropped) > 3 else "")
        warnings.append(f"{len(dropped)} computed value{'s are' if len(dropped) != 1 else ' is'} "
                        f"not finite (NaN or infinite) and left out of the result: {shown}")
    if warnings:
        out["warnings"] = warnings
    return out


FROZEN_STEP_KEYS = ("status", "message", "drivers", "joints", "links", "points", "driving", "frame")
FROZEN_KEYS = ("scene", "stages", "steps", "force_method", "groups", "warnings")


def _without_newer_keys(result: dict) -> dict:
    """A result without the keys extensions added after the frozen writer (if any)."""
    out = {k: v for k, v in result.items() if k in FROZEN_KEYS}
    out["steps"] = [{k: v for k, v in st.items() if k in FROZEN_STEP_KEYS} for st in result["steps"]]
    # a cam contact's pressure angle (an extension) and a joint's friction (the contract's
    # second part) in its joint record
    newer = ("pressure_angle", "friction_moment", "friction_force")
    for st in out["steps"]:
        if "joints" in st:
            st["joints"] = {n: {k: v for k, v in rec.items() if k not in newer}
                            for n, rec in st["joints"].items()}
    return out


def _text(result: dict, indent=None) -> str:
    return json.dumps(result, indent=indent) + "\n"


def assert_contract_bytes(text: str, whole: Analysis, indent, what=""):
    """``text`` is what the in-memory writer writes for the whole run, byte for byte, and that
    is what the frozen writer wrote, byte for byte (up to the keys of newer extensions)."""
    result = whole.to_dict()
    assert text == _text(result, indent), what
    assert _text(_without_newer_keys(result), indent) == _text(_contract_dict(whole), indent), what


# -- scenes ----------------------------------------------------------------------------------------

def _with_steps(d, steps):
    d = copy.deepcopy(d)
    for drv in d["drivers"]:
        drv["steps"] = steps
    return d


def _slider_with_gap():
    """An offset slider-crank whose rod cannot reach the slide near 270 deg (a gap), with a P
    joint's reaction moment, masses and a traced point: every kind of column."""
    crank, rod, offset = 0.5, 1.0, 0.8
    cx = crank + (rod**2 - offset**2) ** 0.5
    return {
        "name": "slider with a gap",
        "links": [{"name": "crank", "mass": 1.0, "com": [0.25, 0.0], "inertia": 0.01},
                  {"name": "rod", "mass": 2.0, "com": [0.5, 0.4], "inertia": 0.1},
                  {"name": "slider", "mass": 1.5, "com": [cx, offset], "inertia": 0.01}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
            {"name": "B", "type": "R", "links": ["crank", "rod"], "at": [crank, 0.0]},
            {"name": "C", "type": "R", "links": ["rod", "slider"], "at": [cx, offset]},
            {"name": "G", "type": "P", "links": ["ground", "slider"], "at": [cx, offset],
             "axis_deg": 0.0},
        ],
        "points": [{"name": "M", "link": "rod", "at": [0.6, 0.5]}],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": 0, "stop_deg": 720,
                     "steps": 145, "speed": 2.0, "acceleration": 0.5}],
        "effects": {"inertia": True, "gravity": [0.0, -9.81], "loads": False},
        "outputs": ["kinematics", "reactions", "driving", "frame"],
    }


_triad_jump = scenes.triad_jump


def _ill_conditioned_fourbar():
    """An ok step near a limit (condition ~4e8) at step 60: a condition-number warning."""
    d, _ = scenes.fourbar(1.0, math.sqrt(3.0) - 0.8, 0.8, 2.0, start_deg=0, stop_deg=120,
                          steps=121, speed=10.0, acceleration=3.0, assembly_deg=10.0)
    return d


def _write(tmp_path, d):
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(d))
    return path


# -- helpers ---------------------------------------------------------------------------------------

def _field(name):
    """A column's quantity (its scale is shared): ``position``, ``omega``, ``driving``, ..."""
    parts = name.split(".")
    if parts[0] == "instant_centres":  # a centre may lie far beyond the joints
        return "instant_centres." + (parts[-2] if parts[-1] in ("x", "y") else parts[-1])
    if parts[0] in ("driving", "frame"):
        return ".".join(parts[:2]) if parts[0] == "frame" else "driving"
    return parts[-2] if parts[-1] in ("x", "y") else parts[-1]


def _scales(columns):
    out = {}
    for name, v, _ in columns:
        if name in ("status", "message"):
            continue
        a = np.abs(np.asarray(v, float))
        m = float(a[np.isfinite(a)].max(initial=0.0))
        out[_field(name)] = max(out.get(_field(name), 0.0), m)
    return out


ACCURACY_OF = {"forces": ("reaction", "driving", "frame", "moment"),
               "acceleration": ("acceleration", "com_acceleration", "alpha"),
               "velocity": ("velocity", "com_velocity", "omega"),
               "position": ("position", "com", "rotation")}


def assert_same_as_whole(whole: Analysis, got: dict, what: str, newton: bool = False):
    """Columns ``got`` (name -> array, as read back from a file) equal the whole run's.

    ``newton``: a Newton group's continuation solves a chunk's points in other blocks than
    the whole run's (``numeric/continuation/batched_path.py``), so their roots agree to rounding, not bit
    for bit, and an ill-conditioned step amplifies that; there a value may differ by the
    whole run's own accuracy estimate of the step, where that is larger than ``REL``
    (the triad's step 69, condition 3e3: 3e-11 of the largest reaction, estimate 9e-10),
    and the estimates themselves (condition numbers, the superposition's amplification)
    1e-10 of their value.
    """
    scales = _scales(whole.columns())
    assert list(got["status"]) == whole.status.tolist(), what
    for name, v, _ in whole.columns():
        if name in ("status", "message"):
            continue
        a, b = np.asarray(v, float), np.asarray(got[name], float)
        assert np.array_equal(np.isnan(a), np.isnan(b)), f"{what}: {name}: NaN at other steps"
        rel = np.full(len(a), REL)
        kind = [k for k, fields in ACCURACY_OF.items()
                if not name.startswith("accuracy.") and _field(name).split(".")[0] in fields]
        if newton and kind and whole.accuracy is not None:
            rel = np.fmax(rel, whole.accuracy[kind[0]])
        tol = rel * scales[_field(name)]
        if newton and name.startswith("accuracy."):
            tol = np.fmax(tol, 1e-10 * np.abs(a))
        err = np.abs(a - b)
        bad = ~np.isnan(a) & (err > tol)
        assert not bad.any(), f"{what}: {name} off by {err[bad].max():.3g} > {tol[bad].min():.3g}"


def _npz_columns(path):
    with np.load(path) as z:
        return {k: z[k] for k in z.files}


def _flat(record, prefix=""):
    """A JSON step record flattened to ``{path: number}`` (vectors as ``.x``/``.y``).

    The ``instant_centres`` list as docs/scene-format.md maps it to columns: per pair
    ``a, b`` its ``position`` or ``direction`` vector, and the flags ``undefined`` and
    ``from_velocities`` (``method: "velocity"``) as 1 or 0."""
    out = {}
    for k, v in record.items():
        key = f"{prefix}{k}"
        if k == "instant_centres":
            for rec in v:
                a, b = rec["links"]
                pair = f"{key}.{a}.{b}"
                for vector in ("position", "direction"):
                    if vector in rec:
                        out[f"{pair}.{vector}.x"], out[f"{pair}.{vector}.y"] = rec[vector]
                out[f"{pair}.undefined"] = 1.0 if rec.get("undefined") else 0.0
                out[f"{pair}.from_velocities"] = 1.0 if rec.get("method") == "velocity" else 0.0
        elif isinstance(v, dict):
            out.update(_flat(v, key + "."))
        elif isinstance(v, list):
            out[key + ".x"], out[key + ".y"] = v
        else:
            out[key] = v
    return out


# -- JSON: the contract's bytes --------------------------------------------------------------------

@pytest.mark.parametrize("name", slow_cases(example_names(), {
    "engine_four_stroke", "song_wang_sixbar", "watt_sixbar", "shaper", "stephenson_sixbar",
    "fivebar", "cam_cycloidal_roller", "slider_crank_offset", "gear_linkage", "planetary_train",
    "crank_rocker", "guide_bar_quick_return", "shaper_flywheel", "crank_rocker_motor", "fivebar_motors",
    "printing_mechanism_stroke", "crank_rocker_spring", "printing_mechanism",
    "slider_crank_press_friction"}))
def test_json_file_is_byte_identical_to_the_contract_writer(name, tmp_path):
    d = example_dict(name)
    if name in NEWTON:
        d = _with_steps(d, 41)
    scene = _write(tmp_path, d)
    whole = compile_plan(linkage_sym.load_scene(d)).run()
    for flags, indent in (([], None), (["--pretty"], 1)):
        out = tmp_path / "r.json"
        assert main(["analyze", str(scene), "-o", str(out), *flags]) == 0
        assert_contract_bytes(out.read_text(), whole, indent, (name, flags))


@pytest.mark.parametrize("make", [_slider_with_gap, scenes.change_point_fourbar,
                                  pytest.param(_triad_jump, marks=pytest.mark.slow),
                                  _ill_conditioned_fourbar])
def test_json_of_failures_points_and_warnings_is_byte_identical(make, tmp_path, capsys):
    d = make()
    whole = compile_plan(linkage_sym.load_scene(d)).run()
    out = tmp_path / "r.json"
    assert main(["analyze", str(_write(tmp_path, d)), "-o", str(out)]) == 0
    assert_contract_bytes(out.read_text(), whole, None)
    capsys.readouterr()
    assert main(["analyze", str(_write(tmp_path, d)), "-o", "-", "--pretty"]) == 0
    assert_contract_bytes(capsys.readouterr().out, whole, 1)


def test_json_streamed_in_chunks_names_left_out_values_by_their_sweep_step():
    """Non-finite values at steps 1..3 (injected) are left out and named ``steps[k]`` with k
    counted over the sweep, also when the steps come in chunks of two."""
    whole = linkage_sym.analyze(linkage_sym.load_example("crank_rocker"))
    whole.joints["C"].velocity[1, 0] = math.inf
    whole.links["coupler"].omega[2] = math.nan
    whole.forces.driving["A"][3] = -math.inf
    whole.forces.frame_moment[3] = math.nan
    expect = _text(whole.to_dict())
    assert whole.to_json() + "\n" == expect  # the API's writer: the same
    assert_contract_bytes(expect, whole, None)
    stream = _Text()
    output.write_sweep(_fake_sweep(whole), stream=stream, chunk=2)
    assert stream.getvalue() == expect
    assert "steps[1].joints.C.velocity, steps[2].links.coupler.omega" in expect


# -- columns: CSV, npz, Parquet --------------------------------------------------------------------

def _check_columns_against_json(whole, names, read, what):
    """Every number of every JSON record is in its column at its step; the rest is empty."""
    records = whole.to_dict()["steps"]  # (held to the frozen writer above)
    covered = {n.split(".", 1)[0] for n in names}  # extensions without columns are left aside
    flat = [_flat({k: v for k, v in r.items() if k in covered}) for r in records]
    keys = {k for f in flat for k in f}
    assert keys <= set(names), f"{what}: JSON fields without a column: {sorted(keys - set(names))[:5]}"
    assert names[:3] == ["step", "status", "message"], what
    assert set(names) - keys - {"step", "status", "message"} <= {
        n for n in names if all(n not in f for f in flat)}, what
    for i, (rec, f) in enumerate(zip(records, flat)):
        assert read("step", i) == i
        assert read("status", i) == rec["status"]
        assert read("message", i) == rec.get("message"), (what, i)
        for n in names[3:]:
            got = read(n, i)
            if n in f:
                assert got == f[n], (what, n, i)  # exact: every format keeps every bit
            else:
                assert got is None, (what, n, i)


def _with_centres(d, speed=None):
    """``d`` with the ``instant_centres`` output too (and every driver at ``speed``)."""
    d = dict(d, outputs=[*d.get("outputs", ["kinematics"]), "instant_centres"])
    if speed is not None:
        d["drivers"] = [dict(dr, speed=speed, acceleration=0.0) for dr in d["drivers"]]
    return d


@pytest.mark.parametrize("make", [
    _slider_with_gap, scenes.change_point_fourbar,
    pytest.param(lambda: example_dict("watt_sixbar"), marks=pytest.mark.slow),
    # instant centres: at infinity and a gap; found from the velocities; undefined at rest
    lambda: _with_centres(_slider_with_gap()),
    lambda: _with_centres(_with_steps(example_dict("fivebar"), 13)),
    lambda: _with_centres(_with_steps(example_dict("guide_bar_quick_return"), 13), speed=0.0),
], ids=["slider_with_gap", "change_point_fourbar", "watt_sixbar", "centres_slider_with_gap",
        "centres_fivebar", "centres_at_rest"])
def test_csv_npz_parquet_hold_the_json_numbers(make, tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    d = make()
    whole = compile_plan(linkage_sym.load_scene(d)).run()
    scene = _write(tmp_path, d)
    for fmt in ("csv", "npz", "parquet"):
        assert main(["analyze", str(scene), "-o", str(tmp_path / f"r.{fmt}")]) == 0
    # CSV, read by the standard library
    with open(tmp_path / "r.csv", newline="") as fh:
        rows = list(csv.reader(fh))
    names, body = rows[0], rows[1:]
    col = {n: k for k, n in enumerate(names)}

    def read_csv(n, i):
        t = body[i][col[n]]
        if n == "step":
            return int(t)
        if n in ("status", "message"):
            return t if t or n == "status" else None
        return float(t) if t else None

    _check_columns_against_json(whole, names, read_csv, "csv")
    # npz: NaN where the JSON has no value (NumPy's own reader)
    z = _npz_columns(tmp_path / "r.npz")

    def read_npz(n, i):
        v = z[n][i]
        if n == "step":
            return int(v)
        if n in ("status", "message"):
            return str(v) if str(v) or n == "status" else None
        return None if np.isnan(v) else float(v)

    assert list(z) == names + ["meta"]
    _check_columns_against_json(whole, names, read_npz, "npz")
    # Parquet: nulls where the JSON has no value
    table = pq.read_table(tmp_path / "r.parquet")
    cols = table.to_pydict()
    assert table.column_names == names

    def read_pq(n, i):
        return cols[n][i]

    _check_columns_against_json(whole, names, read_pq, "parquet")
    # the result's other keys: npz ``meta`` and the Parquet file's key-value metadata
    meta = {k: v for k, v in whole.to_dict().items() if k != "steps"}
    assert json.loads(z["meta"].item()) == meta
    kv = pq.ParquetFile(tmp_path / "r.parquet").metadata.metadata
    assert json.loads(kv[b"linkage_sym"]) == meta


def test_columns_equal_the_analysis_arrays(tmp_path):
    """The npz columns are the Analysis arrays themselves (NaN and all), by name."""
    d = _slider_with_gap()
    whole = compile_plan(linkage_sym.load_scene(d)).run()
    main(["analyze", str(_write(tmp_path, d)), "-o", str(tmp_path / "r.npz")])
    z = _npz_columns(tmp_path / "r.npz")
    expect = {
        "joints.C.velocity.y": whole.joints["C"].velocity[:, 1],
        "joints.G.reaction_moment": whole.forces.reaction_moments["G"],
        "links.rod.rotation": whole.links["rod"].rotation,
        "links.rod.com_acceleration.x": whole.links["rod"].com_acceleration[:, 0],
        "points.M.position.x": whole.points["M"].position[:, 0],
        "driving.A": whole.forces.driving["A"],
        "frame.force.y": whole.forces.frame_force[:, 1],
        "drivers.A.qdd": whole.drivers["A"]["qdd"],
    }
    for n, v in expect.items():
        assert np.array_equal(z[n], v, equal_nan=True), n
    assert np.isnan(z["links.rod.rotation"]).any()  # the gap
    assert (z["message"] != "").sum() == (whole.status != "ok").sum()


def test_format_from_the_suffix_and_options(tmp_path, capsys):
    scene = _write(tmp_path, _with_steps(example_dict("crank_rocker"), 5))
    assert main(["analyze", str(scene), "-o", str(tmp_path / "r.data"), "--format", "csv"]) == 0
    assert (tmp_path / "r.data").read_text().startswith("step,status,message,drivers.A.q,")
    assert main(["analyze", str(scene), "-o", str(tmp_path / "r.out")]) == 0
    assert json.loads((tmp_path / "r.out").read_text())["scene"] == "crank-rocker"
    capsys.readouterr()
    assert main(["analyze", str(scene), "-o", "-", "--format", "csv"]) == 0
    assert len(capsys.readouterr().out.splitlines()) == 6
    for args, msg in ((["--format", "csv"], "--format: needs -o FILE"),
                      (["-o", "-", "--format", "npz"], "not standard output"),
                      (["-o", str(tmp_path / "x.csv"), "--pretty"], "--pretty: indents JSON only")):
        assert main(["analyze", str(scene), *args]) == 2
        assert msg in capsys.readouterr().err
    assert not (tmp_path / "x.csv").exists()


def test_parquet_without_pyarrow_names_the_extra(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "pyarrow", None)  # import pyarrow -> ImportError
    monkeypatch.setitem(sys.modules, "pyarrow.parquet", None)
    scene = _write(tmp_path, _with_steps(example_dict("crank_rocker"), 5))
    assert main(["analyze", str(scene), "-o", str(tmp_path / "r.parquet")]) == 2
    assert "pip install 'linkage_sym[parquet]'" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == [scene]


# -- chunks ----------------------------------------------------------------------------------------

def _chunked(d, tmp_path, chunk, method="dyad"):
    scene = linkage_sym.load_scene(d)
    if method == "symbolic":
        sweep = output.compiled_sweep(linkage_sym.compile_mechanism(scene))
    else:
        sweep = output.plan_sweep(compile_plan(scene), method)
    path = tmp_path / f"c{chunk}.npz"
    stats = output.write_sweep(sweep, path, "npz", chunk=chunk)
    return stats, _npz_columns(path)


@pytest.mark.parametrize("name", slow_cases(example_names(), set(example_names()) - {
    "hydraulic_boom", "sixbar_class3"}))
def test_chunked_equals_whole_on_every_example(name, tmp_path):
    d = example_dict(name)
    whole = compile_plan(linkage_sym.load_scene(d)).run()
    for chunk in (1, 37, 100):
        if chunk == 1 and name in NEWTON:
            continue  # (one step a chunk: each walks its own path from the assembly; slow)
        stats, cols = _chunked(d, tmp_path, chunk)
        assert_same_as_whole(whole, cols, f"{name}, chunks of {chunk}", newton=name in NEWTON)
        assert stats.warnings == whole.warnings
        assert [str(m) for m in cols["message"]] == [m or "" for m in whole.messages]


@pytest.mark.parametrize("make", [
    lambda: _with_centres(_slider_with_gap()),
    lambda: _with_centres(_with_steps(example_dict("fivebar"), 97)),
], ids=["slider_with_gap", "fivebar"])
@pytest.mark.slow
def test_chunked_equals_whole_with_instant_centres(make, tmp_path):
    d = make()
    whole = compile_plan(linkage_sym.load_scene(d)).run()
    for chunk in (1, 37):
        stats, cols = _chunked(d, tmp_path, chunk)
        assert_same_as_whole(whole, cols, f"{d['name']}, chunks of {chunk}")
        assert stats.warnings == whole.warnings


@pytest.mark.slow
def test_chunked_equals_whole_symbolic_and_global(tmp_path):
    for name, method in (("sixbar_class3", "symbolic"), ("hydraulic_boom", "global"),
                         ("watt_sixbar", "global")):
        d = example_dict(name)
        scene = linkage_sym.load_scene(d)
        whole = (linkage_sym.compile_mechanism(scene).run() if method == "symbolic"
                 else compile_plan(scene).run(method=method))
        stats, cols = _chunked(d, tmp_path, 50, method)
        assert_same_as_whole(whole, cols, f"{name} ({method})", newton=name != "watt_sixbar")
        assert stats.warnings == whole.warnings


@pytest.mark.parametrize("name, stop, steps", [("crank_rocker", 1080, 1081),
                                               ("sixbar_class3", 540, 541)])
def test_rotations_continue_over_turns_across_chunks(name, stop, steps, tmp_path):
    """A sweep of more than a full turn in chunks: each link's rotation is continuous from the
    assembly configuration across every chunk boundary, and equals the whole run's."""
    d = example_dict(name)
    d["drivers"][0].update(stop_deg=stop, steps=steps)
    whole = compile_plan(linkage_sym.load_scene(d)).run()
    _, cols = _chunked(d, tmp_path, 100)
    assert_same_as_whole(whole, cols, f"{name} over {stop} deg", newton=name in NEWTON)
    for link in whole.links:
        rot = cols[f"links.{link}.rotation"]
        assert np.abs(np.diff(rot)).max() < math.radians(30), link  # no jump of a turn
    crank = cols["links.crank.rotation"]
    q = cols["drivers.A.q"]
    assert np.abs(crank - (q - q[0]) - crank[0]).max() < 1e-12  # the crank turns with its driver
    assert q[-1] - q[0] == pytest.approx(math.radians(stop), abs=1e-12)


def test_rotation_across_a_gap_in_chunks(tmp_path):
    """Two gaps (unassemblable steps near 270 deg, twice): chunk boundaries inside and at the
    edges of the gaps give the whole run's statuses, messages and rotations."""
    d = _slider_with_gap()
    whole = compile_plan(linkage_sym.load_scene(d)).run()
    bad = np.flatnonzero(whole.status != "ok")
    assert len(bad) > 4
    for chunk in (int(bad[0]), int(bad[0]) + 2, 13):
        _, cols = _chunked(d, tmp_path, chunk)
        assert_same_as_whole(whole, cols, f"gap, chunks of {chunk}")


def test_join_adds_whole_turns_only():
    whole = linkage_sym.analyze(linkage_sym.load_example("crank_rocker"))
    part = _take(whole, slice(8, 20))
    before = {n: lk.rotation.copy() for n, lk in whole.links.items()}
    prev = {n: float(lk.rotation[10]) + 2 * math.pi for n, lk in whole.links.items()}
    output.join_rotations(prev, part, 2, 10)
    for n, lk in part.links.items():
        assert lk.rotation[2] == pytest.approx(prev[n], abs=1e-12)
        assert np.allclose(lk.rotation, before[n][8:20] + 2 * math.pi, atol=1e-12)
    prev = {n: v + 0.5 for n, v in prev.items()}
    with pytest.raises(output.ChunkError, match="do not join"):
        output.join_rotations(prev, part, 2, 10)


# -- warnings merged over chunks -------------------------------------------------------------------

@pytest.mark.parametrize("chunk", [5, 13, 14])
@pytest.mark.slow
def test_newton_jump_warnings_merged_as_a_whole_run_words_them(chunk, tmp_path):
    """The triad's jump at step 14 (reached from step 13) is warned once, with the sweep's step
    numbers, wherever the chunk boundaries fall (14: the jump is between two chunks)."""
    d = _triad_jump()
    whole = compile_plan(linkage_sym.load_scene(d)).run()
    assert any("at step 14 (reached from step 13)" in w for w in whole.warnings)
    stats, cols = _chunked(d, tmp_path, chunk)
    assert stats.warnings == whole.warnings
    assert_same_as_whole(whole, cols, f"triad, chunks of {chunk}", newton=True)


def test_condition_warning_merged(tmp_path):
    d = _ill_conditioned_fourbar()
    whole = compile_plan(linkage_sym.load_scene(d)).run()
    assert len(whole.warnings) == 1 and "step 60" in whole.warnings[0]
    for chunk in (7, 60, 61):
        stats, _ = _chunked(d, tmp_path, chunk)
        assert stats.warnings == whole.warnings


def _take(res: Analysis, sl: slice) -> Analysis:
    """Steps ``sl`` of a run, as a run of those steps gives them (warnings recomputed).

    Every field over the steps is cut, whatever the Analysis holds (arrays of N
    steps, lists of N messages, dicts and dataclasses of them)."""
    n = res.n_steps

    def cut(v):
        if isinstance(v, np.ndarray) and v.ndim and len(v) == n:
            return v[sl]
        if isinstance(v, list) and len(v) == n:
            return v[sl]
        if isinstance(v, dict):
            return {k: cut(x) for k, x in v.items()}
        if isinstance(v, list):
            return [cut(x) for x in v]
        if dataclasses.is_dataclass(v) and not isinstance(v, type):
            return dataclasses.replace(v, **{f.name: cut(getattr(v, f.name))
                                            for f in dataclasses.fields(v) if f.init})
        return v

    part = cut(res)
    part.warnings = run_warnings(part)
    return part


def _fake_sweep(whole: Analysis) -> output.Sweep:
    """A sweep whose runs are slices of ``whole`` (driver value k at step k)."""
    steps = np.arange(whole.n_steps, dtype=float)

    def run(q, qd, qdd):
        k = np.asarray(next(iter(q.values()))).astype(int)
        return _take(whole, slice(int(k[0]), int(k[-1]) + 1))

    return output.Sweep(run, {"A": steps}, {"A": steps}, {"A": steps})


class _Text:
    def __init__(self):
        self.parts = []

    def write(self, s):
        self.parts.append(s)

    def getvalue(self):
        return "".join(self.parts)


def test_condition_and_superposition_warnings_merged_over_random_chunks():
    """Random condition numbers and superposition amplifications on a class-III run: the
    warnings merged over chunks of every size equal ``run_warnings`` of the whole run
    (counts, first five steps, worst value and its step), and so do the choice counts."""
    d = _with_steps(example_dict("sixbar_class3"), 61)
    base = compile_plan(linkage_sym.load_scene(d)).run()
    group = next(g for g in base.forces.groups if g.amplification is not None)
    rng = np.random.default_rng(3)
    base.condition = 10 ** rng.uniform(0, 9, base.n_steps)
    group.amplification = 10 ** rng.uniform(0, 12, base.n_steps)
    group.amplification[[7, 40]] = group.amplification.max()  # ties: the earlier step
    group.used = rng.integers(0, len(group.choices), base.n_steps)
    whole = _take(base, slice(None))
    assert len(whole.warnings) == 2
    for chunk in (1, 2, 5, 17, 61):
        stream = _Text()
        stats = output.write_sweep(_fake_sweep(whole), stream=stream, chunk=chunk)
        assert stats.warnings == whole.warnings, chunk
        assert stream.getvalue() == _text(whole.to_dict())


def test_summary_of_chunks_equals_the_whole_runs(tmp_path, capsys, monkeypatch):
    d = example_dict("watt_sixbar")
    scene = _write(tmp_path, d)
    assert main(["analyze", str(scene)]) == 0
    whole = capsys.readouterr().out
    monkeypatch.setattr(output, "chunk_steps", lambda *a: 50)
    assert main(["analyze", str(scene)]) == 0
    assert capsys.readouterr().out == whole
    assert "peak driving torque at A" in whole and "largest reaction" in whole


# -- memory ----------------------------------------------------------------------------------------

@pytest.mark.parametrize("name, method, steps, outputs", [
    ("crank_rocker", "dyad", 20000, None), ("watt_sixbar", "dyad", 20000, None),
    ("shaper", "dyad", 20000, None),
    ("watt_sixbar", "global", 5000, None), ("watt_sixbar", "symbolic", 20000, None),
    ("sixbar_class3", "dyad", 500, None), ("hydraulic_boom", "dyad", 500, None),
    ("printing_mechanism", "dyad", 500, None),
    # instant centres: their construction's memory grows with the pairs, not the columns
    ("crank_rocker", "dyad", 20000, ["instant_centres"]),
    pytest.param("watt_sixbar", "dyad", 20000, ["kinematics", "instant_centres"],
                 marks=pytest.mark.slow),
    ("fivebar", "dyad", 20000, ["kinematics", "reactions", "instant_centres"]),
])
def test_memory_estimate_covers_the_measured_peak(name, method, steps, outputs):
    """tracemalloc's peak of a run (numbers, temporaries, result) per step is under
    ``bytes_per_step``, and not below a third of it (the estimate is not idle)."""
    d = _with_steps(example_dict(name), steps)
    if outputs is not None:
        d["outputs"] = outputs
    scene = linkage_sym.load_scene(d)
    if method == "symbolic":
        sweep = output.compiled_sweep(linkage_sym.compile_mechanism(scene))
    else:
        sweep = output.plan_sweep(compile_plan(scene), method)
    template = sweep.solve(0, 1)
    sweep.solve(0, steps)  # warm: caches, the sweep's own arrays
    tracemalloc.start()
    try:
        sweep.solve(0, steps)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    n_values = sum(1 for n, _, _ in template.columns() if n not in ("status", "message"))
    pairs = len(template.instant_centres.pairs) if outputs and "instant_centres" in outputs else 0
    est = output.bytes_per_step(n_values, method, bool(sweep.heads), centre_pairs=pairs)
    assert peak / steps <= est, (peak / steps, est)
    assert peak / steps >= est / 3, (peak / steps, est)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["crank_rocker", "fivebar"])
def test_run_memory_grows_as_the_measured_peak(name, tmp_path, monkeypatch):
    """Issue 27: a run's peak was estimated from its driver values alone.  run_memory's
    growth per step is held against tracemalloc's peak at 10,000 and 40,000 steps (the
    growth: what does not depend on the steps -- compiled code, caches -- cancels): a
    whole run (centres, balance), analyze in chunks (two copies of the driver values, the
    path, a chunk), a design sweep's model (sweep --list) and a sweep of one design along
    its path.  The estimate is an upper bound and not idle: between 1 and 3 times the
    measured growth."""
    import os

    from linkage_sym.design.evaluate import Model

    monkeypatch.setattr(output, "CHUNK_MEMORY", 2**21)  # chunks of a few thousand steps

    def scene(n):
        return linkage_sym.load_scene(_with_steps(example_dict(name), n))

    def peak(f):
        tracemalloc.start()
        try:
            f()
            return tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()

    runs = {
        "whole": (lambda sc: compile_plan(sc).run(), {}),
        "chunks": (lambda sc: output.write_sweep(output.plan_sweep(compile_plan(sc)),
                                                 os.path.join(tmp_path, "r.csv"), "csv"),
                   {"fmt": "csv", "copies": 2}),
        "none": (lambda sc: Model(sc), {"copies": 4}),
        # a design sweep's chunk of one design along its path, forces included
        "path": (lambda sc: linkage_sym.sweep(sc, {"l_AB": [0.9 * l_AB]}, metrics),
                 {"copies": 4}),
    }
    from linkage_sym.design import scene_parameters

    metrics = ["assemblable", "peak_driving"]
    l_AB = dict((n, v) for n, v, _ in scene_parameters(scene(50)))["l_AB"]
    for run, _ in runs.values():  # caches: compiled mechanisms, their force blocks
        if run is not runs["chunks"][0]:
            run(scene(50))
    n1, n2 = 10_000, 40_000
    for results, (run, kw) in runs.items():
        low = peak(lambda: run(scene(n1)))
        measured = (peak(lambda: run(scene(n2))) - low) / (n2 - n1)
        est = [output.run_memory(scene(n), results, **kw)["total"] for n in (n1, n2)]
        ratio = (est[1] - est[0]) / (n2 - n1) / measured
        assert 1.0 <= ratio <= 3.0, (results, ratio, measured)


def test_chunk_size_follows_the_memory_available():
    per = 10_000
    assert output.chunk_steps(10**6, per, None, False) == output.CHUNK_MEMORY // per
    assert output.chunk_steps(10**6, per, 2**40, True) == output.NEWTON_CHUNK
    assert output.chunk_steps(100, per, 2**40, False) == 100
    small = output.FIXED_BYTES + 2 * 1000 * per
    assert output.chunk_steps(10**6, per, small, False) == 1000
    with pytest.raises(output.OutputError, match="not enough memory"):
        output.chunk_steps(10**6, per, output.FIXED_BYTES + per * output.MIN_CHUNK // 2, False)


@pytest.mark.slow
def test_too_large_runs_are_refused_before_anything_is_written(tmp_path, capsys, monkeypatch):
    scene = _write(tmp_path, _with_steps(example_dict("watt_sixbar"), 2000))
    monkeypatch.setattr(output, "available_memory", lambda: output.FIXED_BYTES + 2**18)
    for fmt in ("json", "csv", "npz", "parquet"):
        out = tmp_path / f"r.{fmt}"
        assert main(["analyze", str(scene), "-o", str(out)]) == 2, fmt
        err = capsys.readouterr().err
        assert "not enough memory" in err and "nothing written" in err, err
    # --plots keeps the whole sweep: refused where chunks would fit
    monkeypatch.setattr(output, "available_memory", lambda: output.FIXED_BYTES + 4 * 2**20)
    assert main(["analyze", str(scene), "-o", str(tmp_path / "r.json"),
                 "--plots", str(tmp_path / "p")]) == 2
    assert "--plots: not enough memory: the whole sweep in memory" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.json"]
    assert main(["analyze", str(scene), "-o", str(tmp_path / "r.json")]) == 0  # in chunks: fits


@pytest.mark.parametrize("fmt", ["json", "csv", "npz", "parquet"])
def test_a_failure_while_writing_leaves_no_partial_file(fmt, tmp_path, capsys, monkeypatch):
    if fmt == "parquet":
        pytest.importorskip("pyarrow")
    scene = _write(tmp_path, example_dict("watt_sixbar"))
    out = tmp_path / f"r.{fmt}"
    monkeypatch.setattr(output, "chunk_steps", lambda *a: 50)
    solve = output.Sweep.solve
    calls = []

    def failing(self, *args):
        calls.append(args)
        if len(calls) == 5:  # the probe, then chunks 0..2 written, the fourth fails
            raise OSError(28, "No space left on device")
        return solve(self, *args)

    monkeypatch.setattr(output.Sweep, "solve", failing)
    assert main(["analyze", str(scene), "-o", str(out)]) == 1
    assert "No space left on device" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.json"]
    # an existing file of that name is left as it was; an interrupt cleans up too
    out.write_text("earlier result")
    calls.clear()

    def interrupted(self, *args):
        calls.append(args)
        if len(calls) == 3:
            raise KeyboardInterrupt
        return solve(self, *args)

    monkeypatch.setattr(output.Sweep, "solve", interrupted)
    assert main(["analyze", str(scene), "-o", str(out)]) == 130
    assert out.read_text() == "earlier result"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r." + fmt, "scene.json"]


@pytest.mark.slow  # about 1-3 s each: the fast lane stays under two minutes
@pytest.mark.parametrize("signame, status", [pytest.param("SIGTERM", None, marks=pytest.mark.slow),
                                             ("SIGINT", 130)])
def test_a_killed_analyze_leaves_no_partial_file(signame, status, tmp_path):
    """Issue 27: SIGTERM ended analyze at once, leaving its ``.partial`` file.  A run of two
    million steps (about a minute) is signalled once its partial file exists: the file is
    removed, and the process ends as the signal ends it (killed by SIGTERM; Ctrl-C's status
    130)."""
    import os
    import signal
    import subprocess
    import time

    scene = _write(tmp_path, _with_steps(example_dict("crank_rocker"), 2_000_000))
    out = tmp_path / "out"
    out.mkdir()
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    p = subprocess.Popen([sys.executable, "-m", "linkage_sym", "analyze", str(scene), "-o",
                          str(out / "r.csv")], env=env, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 120
        while not any(out.iterdir()) and p.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
        partial = [f.name for f in out.iterdir()]
        assert len(partial) == 1 and partial[0].endswith(".partial"), partial
        time.sleep(1.0)  # some chunks solved and written
        assert p.poll() is None  # still running: killed mid-run
        p.send_signal(getattr(signal, signame))
        _, err = p.communicate(timeout=60)
    finally:
        if p.poll() is None:
            p.kill()
            p.communicate()
    expected = -getattr(signal, signame) if status is None else status
    assert p.returncode == expected, (p.returncode, err)
    assert "Traceback" not in err, err
    assert list(out.iterdir()) == []


def test_the_signal_handlers_are_restored_after_a_run(tmp_path):
    import signal

    before = {s: signal.getsignal(s) for s in output.SIGNALS}
    scene = linkage_sym.load_scene(_with_steps(example_dict("crank_rocker"), 30))
    output.write_sweep(output.plan_sweep(compile_plan(scene)), tmp_path / "r.json")
    assert {s: signal.getsignal(s) for s in output.SIGNALS} == before
    assert [p.name for p in tmp_path.iterdir()] == ["r.json"]


def test_memory_probe_reads_the_machine():
    avail = output.available_memory()
    assert avail is None or 0 < avail < 2**50


# -- progress --------------------------------------------------------------------------------------

def test_progress_bar_only_on_a_terminal(monkeypatch):
    class Tty:
        def __init__(self, tty):
            self.tty, self.text = tty, []

        def isatty(self):
            return self.tty

        def write(self, s):
            self.text.append(s)

        def flush(self):
            pass

    monkeypatch.setattr(sys, "stderr", Tty(False))
    assert output.progress_bar(100, True) is None
    monkeypatch.setattr(sys, "stderr", Tty(True))
    assert output.progress_bar(100, False) is None
    pytest.importorskip("tqdm")
    bar = output.progress_bar(100, True)
    assert bar is not None and bar.total == 100
    bar.close()
    monkeypatch.setitem(sys.modules, "tqdm", None)  # the optional extra is not installed
    assert output.progress_bar(100, True) is None


def test_the_numeric_core_loads_neither_tqdm_nor_pyarrow():
    """Only linkage_sym.output (the writers) uses the optional extras, and only when asked:
    an analysis, and writing it as JSON in chunks, imports neither."""
    import subprocess

    code = (
        "import io, sys, linkage_sym\n"
        "from linkage_sym import output\n"
        "plan = linkage_sym.compile_plan(linkage_sym.load_example('crank_rocker'))\n"
        "plan.run()\n"
        "output.write_sweep(output.plan_sweep(plan), stream=io.StringIO(), chunk=50)\n"
        "print(','.join(m for m in ('tqdm', 'pyarrow') if m in sys.modules))\n"
    )
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == ""


@pytest.mark.slow
def test_force_groups_when_the_first_step_fails(tmp_path):
    """A class-III six-bar whose first steps cannot be assembled (its crank pivot moved 1 m
    down, found by fuzzing): the one-step template of the sweep had no force groups at all,
    and the chunks' disconnection counts indexed past them (IndexError). Every run now
    records its groups whatever its steps' statuses; the file's ``groups`` equal a whole run's."""
    d = example_dict("sixbar_class3")
    [A] = [j for j in d["joints"] if j["name"] == "A"]
    A["at"] = [A["at"][0], -1.0]
    whole = compile_plan(linkage_sym.load_scene(d)).run()
    assert whole.status[0] != "ok" and (whole.status == "ok").any()
    first = [{n: np.asarray(dv[k])[:1] for n, dv in whole.drivers.items()}
             for k in ("q", "qd", "qdd")]
    empty = compile_plan(linkage_sym.load_scene(d)).run(*first)  # its one step fails
    assert [g.choices for g in empty.forces.groups] == [g.choices for g in whole.forces.groups]
    scene = _write(tmp_path, d)
    assert main(["analyze", str(scene), "-o", str(tmp_path / "r.json")]) == 0
    got = json.loads((tmp_path / "r.json").read_text())["groups"]
    assert got == whole.group_records()
    assert any("steps_per_choice" in g for g in got)
