"""The record of a joint's passage through infinity (``Analysis.passages``).

A dyad of two slides whose slides become parallel between two steps carries its joint
through infinity (:mod:`tests.support.parallel_slides`: ``C`` of the guide-slider at
``(H / tan q, H)``, at infinity at ``q = 0``).  The run keeps where, for the plots:

* the joint, the steps on either side (the side of ``C`` changes there, by the lines'
  intersection written in the test) and the links carried off, the same from both runtimes,
  for several step counts;
* the links carried off are read from the structure: both links of a PRP dyad, the unpinned
  one of an RPP dyad, and the links of a later group tied to them (not those of a group tied
  only to the input);
* no passage, no record; the result's JSON has no key for it (the warning says it).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkage_sym
from linkage_sym.codegen.compile import compile_mechanism
from linkage_sym.numeric.plan import compile_plan
from linkage_sym.numeric.results.passages import InfinityPassage, far_links
from tests.support.parallel_slides import guide_slider, joint_c, pinned_rod


def _runtimes(scene):
    return {"numeric": compile_plan(scene).run(), "symbolic": compile_mechanism(scene).run()}


@pytest.mark.parametrize("steps", [10, 11, 41])
def test_the_passage_is_recorded_between_the_steps_where_the_joint_changes_side(steps):
    scene = linkage_sym.load_scene(guide_slider(steps))
    for name, res in _runtimes(scene).items():
        q = res.drivers["A"]["q"]
        ref_x = np.array([joint_c(v)[0] if abs(math.sin(v)) > 1e-12 else np.nan for v in q])
        # the reference: the last step on the near side and the first on the far side
        near = int(np.flatnonzero(ref_x > 0)[-1])
        far = int(np.flatnonzero(ref_x < 0)[0])
        assert res.passages == (InfinityPassage("C", far - 1, far, ("rod", "block")),), name
        assert far - 1 == near or (far - 2 == near and res.status[far - 1] == "unassemblable")
        assert len(res.warnings) == 1 and f"at step {far} " in res.warnings[0]
        assert "passages" not in res.to_dict()


def test_no_passage_no_record():
    for name, res in _runtimes(linkage_sym.load_scene(guide_slider(9, 30.0, 5.0))).items():
        assert res.passages == () and res.warnings == [], name
    assert compile_plan(linkage_sym.load_example("crank_rocker")).run().passages == ()


def test_the_links_carried_off_are_the_dyads_unpinned_links_and_those_tied_to_them():
    d = guide_slider(10)
    c = d["joints"][2]["at"]
    d["links"] += [{"name": n} for n in ("tail1", "tail2", "arm1", "arm2")]
    d["joints"] += [  # an RRR dyad hung on the block, another on the guide
        {"name": "D", "type": "R", "links": ["block", "tail1"], "at": [c[0], c[1] + 0.03]},
        {"name": "E", "type": "R", "links": ["tail1", "tail2"], "at": [c[0] + 0.03, c[1] + 0.05]},
        {"name": "F", "type": "R", "links": ["tail2", "ground"], "at": [c[0] + 0.06, c[1] + 0.03]},
        {"name": "G", "type": "R", "links": ["guide", "arm1"], "at": [-0.01, 0.0]},
        {"name": "I", "type": "R", "links": ["arm1", "arm2"], "at": [-0.03, 0.02]},
        {"name": "K", "type": "R", "links": ["arm2", "ground"], "at": [-0.05, 0.0]},
    ]
    assert far_links(linkage_sym.load_scene(d), "C") == ("rod", "block", "tail1", "tail2")
    # RPP: the rod is pinned to the ground at E, only the block goes with the joint
    assert far_links(linkage_sym.load_scene(pinned_rod(50.0)), "B_rod") == ("block",)
