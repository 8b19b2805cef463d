"""Driver values are worded by one module in every message."""

import math

import numpy as np

import linkage_sym
from linkage_sym.cli.accuracy import _drivers_text
from linkage_sym.numeric.continuation.messages import driver_values_text as along_path
from linkage_sym.numeric.results.wording import driver_number, driver_values_text


def test_driver_values_read_alike_in_every_message():
    """The continuation's messages, the accuracy report and the wording module give one
    text for one set of driver values: degrees with a degree sign, metres, six digits."""
    scene = linkage_sym.load_example("slider_crank_offset")
    kinds = {d.joint: scene.joint(d.joint).type for d in scene.drivers}
    name = scene.drivers[0].joint
    path = {name: np.radians([10.0, 37.25, 80.0])}
    want = driver_values_text({name: math.radians(37.25)}, kinds)
    assert want == f"{name} = 37.25°"
    assert along_path(path, kinds, 1) == want
    assert _drivers_text(scene, {name: math.radians(37.25)}) == want
    # a fraction of the way from the previous path point
    assert along_path(path, kinds, 2, 0.5) == f"{name} = 58.625°"


def test_driver_number_never_shows_minus_zero():
    assert driver_number(-1e-13, "R") == "-5.72958e-12°"  # six digits, not rounded away
    assert driver_number(-1e-13, "R", decimals=6) == "0.000000°"
    assert driver_number(-0.0, "P") == "0 m"
