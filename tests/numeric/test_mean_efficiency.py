"""The sweep's mean efficiency in the result file (an extension of the contract's part two:
the top-level ``mean_efficiency``, :mod:`linkage_sym.numeric.results.efficiency`).

Checked against an independent trapezoid sum of the per-step powers the result files
themselves carry: the driver's power ``driving * qd`` over time with the friction (work
in), and the same from the result of the scene with its friction switched off (work out);
the same key from a sweep written in chunks and by the compiled symbolic runtime; none
without friction.
"""

from __future__ import annotations

import copy
import json

import numpy as np
import pytest

import linkage_sym
from linkage_sym import output
from linkage_sym.examples import example_dict
from linkage_sym.numeric.plan import compile_plan

PRESS = "slider_crank_press_friction"


def _work(doc) -> float:
    """The driver's work from a result's steps: the power ``driving * qd`` summed by
    trapezoids over the time (``q`` at a constant speed: t = (q - q0) / qd), on pairs of
    consecutive ok steps."""
    steps = doc["steps"]
    w = 0.0
    for a, b in zip(steps[:-1], steps[1:]):
        if a["status"] != "ok" or b["status"] != "ok":
            continue
        pa = a["driving"]["A"] * a["drivers"]["A"]["qd"]
        pb = b["driving"]["A"] * b["drivers"]["A"]["qd"]
        dt = (b["drivers"]["A"]["q"] - a["drivers"]["A"]["q"]) / a["drivers"]["A"]["qd"]
        w += 0.5 * (pa + pb) * dt
    return w


def test_mean_efficiency_is_work_out_over_work_in_of_the_step_powers():
    d = example_dict(PRESS)
    doc = json.loads(linkage_sym.analyze(linkage_sym.load_scene(d)).to_json())
    plain = copy.deepcopy(d)
    plain["effects"]["friction"] = False
    ref = json.loads(linkage_sym.analyze(linkage_sym.load_scene(plain)).to_json())
    assert "mean_efficiency" not in ref
    w_in, w_out = _work(doc), _work(ref)
    got = doc["mean_efficiency"]
    assert got["work_in"] == pytest.approx(w_in, rel=1e-12)
    assert got["work_out"] == pytest.approx(w_out, rel=1e-12)
    assert got["efficiency"] == pytest.approx(w_out / w_in, rel=1e-12)
    assert 0.5 < got["efficiency"] < 1.0
    assert list(doc).index("mean_efficiency") > list(doc).index("steps")


def test_the_same_from_chunks_and_from_the_symbolic_runtime(tmp_path):
    scene = linkage_sym.load_example(PRESS)
    whole = json.loads(linkage_sym.analyze(scene).to_json())["mean_efficiency"]
    output.write_sweep(output.plan_sweep(compile_plan(scene), "dyad"), tmp_path / "r.json",
                       "json", chunk=37)
    chunked = json.loads((tmp_path / "r.json").read_text())["mean_efficiency"]
    assert chunked == pytest.approx(whole, rel=1e-12)
    sym = json.loads(linkage_sym.analyze(scene, method="symbolic").to_json())["mean_efficiency"]
    assert sym == pytest.approx(whole, rel=1e-9)


def test_no_positive_work_in_no_efficiency():
    """Where the driver's work with the friction is not positive (a sweep that runs the press
    backwards against gravity only, or a static one) the works are said, the ratio is not."""
    from linkage_sym.numeric.results.efficiency import mean_efficiency_record

    assert mean_efficiency_record(-2.0, -1.5) == {"work_in": -2.0, "work_out": -1.5}
    assert mean_efficiency_record(0.0, 0.0) == {"work_in": 0.0, "work_out": 0.0}
    d = example_dict(PRESS)
    d["effects"]["friction"] = False
    assert "mean_efficiency" not in linkage_sym.analyze(linkage_sym.load_scene(d)).to_dict()
    d = example_dict("fivebar")  # two drivers: no single driver's efficiency
    d["effects"]["friction"] = True
    assert "mean_efficiency" not in linkage_sym.analyze(linkage_sym.load_scene(d)).to_dict()
    assert np.isfinite(mean_efficiency_record(1.0, 0.5)["efficiency"])
