"""A compiled plan run many times: results independent, written completely.

``Plan.run`` writes every result array into one block per run, the solvers
writing link rates straight into their rows, and reuses the scene's sweep
and solving path between runs (see ``linkage_sym.numeric.plan``).  These
tests check what that must not change:

* two runs share no writable memory, and a run equals the run of a freshly
  compiled plan, bit for bit;
* a sweep given explicitly (a fresh solving path) gives the same result as
  the cached scene sweep, bit for bit;
* every centre of mass and joint row agrees with the same point recomputed
  from the link's rotation and origin by ``LinkKinematics.point*`` (NumPy
  stacking in ``result.py``, no code shared with the in-place writers) to
  1e-12 of the mechanism's size (rates: of the sweep's largest value),
  and nothing but a failed step holds NaN;
* compiling a plan, or loading a compiled symbolic mechanism, warms the memory
  a run takes (``numeric.engine.heap.warm``): in a fresh interpreter the first run of
  a four-bar over 3600 steps touches no fresh page, where without the warming
  it touches hundreds (counted by the kernel's minor page faults, not timed:
  the time is the benchmark's).
"""

from __future__ import annotations

import dataclasses
import json
import platform
import subprocess
import sys

import numpy as np
import pytest

import linkage_sym
from linkage_sym.examples import example_names
from linkage_sym.numeric.engine import heap
from linkage_sym.numeric.plan import compile_plan

NAMES = example_names()


def _scene(name, steps=181):
    scene = linkage_sym.load_example(name)
    drivers = tuple(dataclasses.replace(d, steps=steps) for d in scene.drivers)
    return dataclasses.replace(scene, drivers=drivers, outputs=("kinematics",))


def _arrays(res):
    """Every kinematic result array of a run, by a readable key."""
    out = {}
    for n, lk in res.links.items():
        for f in dataclasses.fields(lk):
            v = getattr(lk, f.name)
            if v is not None:
                out[f"links.{n}.{f.name}"] = v
    for n, jk in res.joints.items():
        for f in dataclasses.fields(jk):
            v = getattr(jk, f.name)
            if v is not None:
                out[f"joints.{n}.{f.name}"] = v
    out["condition"] = res.condition
    return out


@pytest.mark.parametrize("name", NAMES)
def test_runs_are_independent_and_repeatable(name):
    scene = _scene(name)
    plan = compile_plan(scene)
    r1, r2 = plan.run(), plan.run()
    fresh = compile_plan(scene).run()
    a1, a2, af = _arrays(r1), _arrays(r2), _arrays(fresh)
    assert a1.keys() == a2.keys() == af.keys()
    for k in a1:
        np.testing.assert_array_equal(a2[k], af[k], err_msg=k)
        assert not np.shares_memory(a1[k], a2[k]), k
    np.testing.assert_array_equal(r2.status, fresh.status)
    # writing into one run's results leaves the next run's alone
    for v in a1.values():
        v[...] = 0.0
    r3 = plan.run()
    for k, v in _arrays(r3).items():
        np.testing.assert_array_equal(v, af[k], err_msg=k)


@pytest.mark.parametrize("name", NAMES)
def test_scene_sweep_is_shared_read_only(name):
    plan = compile_plan(_scene(name))
    res = plan.run()
    for joint, d in res.drivers.items():
        for key, arr in d.items():
            with pytest.raises(ValueError, match="read-only"):
                arr[0] = 1.0
    # the same sweep given explicitly (its own solving path) gives the same result
    q, qd, qdd = plan.sweep()
    given = plan.run({k: v.copy() for k, v in q.items()}, qd, qdd)
    for k, v in _arrays(given).items():
        np.testing.assert_array_equal(v, _arrays(res)[k], err_msg=k)


@pytest.mark.parametrize("name", NAMES)
def test_point_rows_match_link_motion(name):
    scene = _scene(name)
    res = compile_plan(scene).run()
    ok = res.ok
    L = scene.characteristic_length()

    def close(a, b, scale, what):
        a, b = np.asarray(a)[ok], np.asarray(b)[ok]
        assert np.all(np.isfinite(a)), f"{what}: NaN at an ok step"
        err = np.max(np.abs(a - b), initial=0.0)
        assert err <= 1e-12 * scale, f"{what}: {err:.3g} > 1e-12 x {scale:.3g}"

    vmax = max(np.nanmax(np.abs(j.velocity)) for j in res.joints.values()) or 1.0
    amax = max(np.nanmax(np.abs(j.acceleration)) for j in res.joints.values()) or 1.0
    for link in scene.links:
        lk = res.links[link.name]
        for arr in (lk.rotation, lk.omega, lk.alpha):
            assert np.all(np.isfinite(arr[ok])), link.name
        if link.com is not None:
            close(lk.com, lk.point(link.com), L, f"{link.name} com")
            close(lk.com_velocity, lk.point_velocity(link.com), vmax, f"{link.name} com velocity")
            close(lk.com_acceleration, lk.point_acceleration(link.com), amax,
                  f"{link.name} com acceleration")
    for j in scene.joints:  # a joint's point is fixed on links[1] (a gear mesh's on its carrier)
        if j.type == "cam":  # the contact point, which moves on both links (test_cams.py)
            continue
        if j.moves_with == "ground":
            fixed = np.broadcast_to(np.array(j.at, float), res.joints[j.name].position.shape)
            close(res.joints[j.name].position, fixed, L, f"joint {j.name}")
            close(res.joints[j.name].velocity, 0.0 * fixed, vmax, f"joint {j.name} velocity")
            continue
        lk = res.links[j.moves_with]
        jk = res.joints[j.name]
        close(jk.position, lk.point(j.at), L, f"joint {j.name}")
        close(jk.velocity, lk.point_velocity(j.at), vmax, f"joint {j.name} velocity")
        close(jk.acceleration, lk.point_acceleration(j.at), amax, f"joint {j.name} acceleration")
    # failed steps hold NaN rates, and NaN positions unless singular
    bad = ~ok
    sing = res.status == "singular"
    for lk in res.links.values():
        assert np.all(np.isnan(lk.omega[bad])) and np.all(np.isnan(lk.alpha[bad]))
        assert np.all(np.isnan(lk.rotation[bad & ~sing]))


def test_heap_settles_and_warms_each_size_once(monkeypatch):
    monkeypatch.setattr(heap, "_warmed", 0)
    monkeypatch.setattr(heap, "_settled", 0)
    assert heap.settle(300_000) == 300_000
    assert heap.settle(300_000) == 0  # thresholds raised already
    assert heap.warm(100_000) == 100_000  # settled already, touched now
    assert heap.warm(100_000) == 0  # kept: nothing more to touch
    assert heap.warm(50_000) == 0
    assert heap.warm(400_000) == 400_000
    assert heap.settle(350_000) == 0  # warming settled it
    assert heap.warm(heap.MMAP_CAP + 1) == 0  # glibc would map it afresh anyway
    assert heap.settle(heap.MMAP_CAP + 1) == 0


FIRST_RUN = """
import dataclasses, json, resource, sys
import linkage_sym
from linkage_sym.codegen.runtime import load_compiled
from linkage_sym.numeric.engine import block
from linkage_sym.numeric.plan import compile_plan
if sys.argv[1] == "cold":
    block.ResultLayout.warm = lambda self, n, runtime: 0
scene = linkage_sym.load_example("crank_rocker")
drivers = tuple(dataclasses.replace(d, steps=3600) for d in scene.drivers)
scene = dataclasses.replace(scene, drivers=drivers, outputs=("kinematics",))
plan = compile_plan(scene) if sys.argv[2] == "numeric" else load_compiled(scene)
faults = []
for _ in range(3):
    f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    res = plan.run()
    faults.append(resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0)
    del res
print(json.dumps(faults))
"""


@pytest.mark.slow  # about 1-3 s each: the fast lane stays under two minutes
@pytest.mark.skipif(platform.system() != "Linux" or platform.libc_ver()[0] != "glibc",
                    reason="counts the page faults of glibc's heap on Linux")
@pytest.mark.parametrize("runtime", ["numeric", pytest.param("symbolic", marks=pytest.mark.slow)])
def test_first_run_touches_no_fresh_memory(runtime):
    scene = _scene("crank_rocker", 3600)
    if runtime == "symbolic":  # into this session's cache, which the subprocess reads
        from linkage_sym.codegen.compile import compile_mechanism

        compile_mechanism(scene)

    def faults(mode):
        p = subprocess.run([sys.executable, "-c", FIRST_RUN, mode, runtime], capture_output=True,
                           text=True, check=True)
        return json.loads(p.stdout)

    warm, cold = faults("warm"), faults("cold")
    pages = 8 * compile_plan(scene).layout.n_rows * 3600 / 4096
    # without warming, the first two runs fault in at least their result blocks' pages
    assert min(cold[:2]) > 0.9 * pages, cold
    # warmed, no run does (a few pages of slack for the interpreter's own objects)
    assert max(warm) < 0.05 * pages, warm
