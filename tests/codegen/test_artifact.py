"""The artifact's records: read from the cache's JSON and written back unchanged; the
parameter recipes evaluated by class for every number type."""

import json
import math

import mpmath as mp
import pytest

import linkage_sym
from linkage_sym.codegen import cache
from linkage_sym.codegen.artifact import Artifact, ClosedStep, NewtonStep
from linkage_sym.codegen.compile import compile_mechanism
from linkage_sym.structure.parameters import link_frames
from linkage_sym.structure.recipes import FLOAT, Numbers, Recipe
from tests.support.example_sets import symbolic_examples
from tests.support.marks import slow_cases


class _Mp(Numbers):
    number = staticmethod(lambda v: mp.mpf(float(v)))
    atan2 = staticmethod(mp.atan2)
    hypot = staticmethod(mp.hypot)
    cos = staticmethod(mp.cos)
    sin = staticmethod(mp.sin)


@pytest.mark.parametrize("name", slow_cases(["crank_rocker", "watt_sixbar", "gear_linkage",
                                              "guide_bar_quick_return", "sixbar_class3"],
                                             {"watt_sixbar", "guide_bar_quick_return"}))
def test_artifact_round_trips_through_json(name):
    """The records written as the cache's JSON and read back are the same records, and the
    JSON the same text: nothing is lost at the cache's edge."""
    scene = linkage_sym.load_example(name)
    art = compile_mechanism(scene).art
    text = json.dumps(art.to_dict(), sort_keys=True)
    again = Artifact.from_dict(json.loads(text))
    assert again == art
    assert json.dumps(again.to_dict(), sort_keys=True) == text
    assert cache.load_artifact(art.key) is not None
    kinds = {type(s) for s in art.steps}
    assert kinds <= {ClosedStep, NewtonStep}
    for g in art.groups:  # the blocks tile A's diagonal in solving order
        r0, r1, c0, c1 = g.block
        assert r1 - r0 == c1 - c0 == len(g.cols)


def test_unknown_recipe_and_step_kind_are_refused():
    with pytest.raises(ValueError, match="unknown parameter recipe"):
        Recipe.of(("zz", "crank"))
    with pytest.raises(ValueError, match="unknown parameter recipe"):
        Recipe.of(())
    with pytest.raises(KeyError):
        Artifact.from_dict({"steps": [{"kind": "spline", "function": "f", "x": []}]})


@pytest.mark.parametrize("name", slow_cases(symbolic_examples(), {
    "hydraulic_boom", "fivebar", "shaper", "planetary_train", "song_wang_sixbar", "printing_mechanism",
    "watt_sixbar", "shaper_flywheel", "stephenson_sixbar", "printing_mechanism_stroke"}))
def test_recipes_in_mpmath_agree_with_float64(name):
    """Every parameter of every shipped example by its recipe in binary64 and in mpmath at
    40 digits (the same scene numbers, another arithmetic): within 4 ulps of the parameter's
    scale (the float64 recipe rounds a few times: a frame angle, its cosine and sine, a
    difference); and the table's value is the float recipe's, exactly.  (Every example
    the symbolic layer derives: cam contacts are not, nor is joint friction; springs are.)"""
    scene = linkage_sym.load_example(name)
    frames = link_frames(scene)
    L = scene.characteristic_length() or 1.0
    from linkage_sym.symbolic.mechanism import MechanismEquations  # registers every parameter

    eqs = MechanismEquations(scene, symbolic=True, forces=True)
    assert eqs.parameters
    with mp.workdps(40):
        for p in eqs.table.params.values():
            r = Recipe.of(p.recipe)
            lo = r.value(scene, frames, FLOAT)
            hi = r.value(scene, frames, _Mp())
            assert lo == p.value
            scale = max(abs(lo), L if p.kind in ("length", "coordinate") else 1.0)
            assert abs(float(hi - mp.mpf(lo))) <= 4 * math.ulp(scale), (p.name, lo, hi)
