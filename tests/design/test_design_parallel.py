"""The same sweep in this process, in 2 worker processes and on a Dask LocalCluster of 2
processes (the suite's only cluster): identical tables, bit for bit (chunks are whole designs
and every backend evaluates them by one function)."""

from __future__ import annotations

import numpy as np
import pytest

import linkage_sym
from linkage_sym.cli import main
from linkage_sym.design import Execution
from linkage_sym.examples import example_path

AXES = {"l_AB": np.linspace(0.02, 0.04, 5), "l_BC": [0.06, 0.065, 0.07]}
METRICS = ["assemblable", "grashof", "K", "swing", "min_transmission_deg", "peak_driving",
           "peak_reaction", "rms_shaking_force", "rms_shaking_moment"]


@pytest.mark.slow
def test_in_process_workers_and_dask_give_identical_tables():
    scene = linkage_sym.load_example("crank_rocker")
    ref = linkage_sym.sweep(scene, AXES, METRICS, execution=Execution(chunk_designs=4))
    by_workers = linkage_sym.sweep(scene, AXES, METRICS,
                                   execution=Execution(workers=2, chunk_designs=4))
    by_dask = linkage_sym.sweep(scene, AXES, METRICS,
                                execution=Execution(workers=2, dask="local", chunk_designs=4))
    assert list(ref.columns) == list(by_workers.columns) == list(by_dask.columns)
    for c in ref.columns:
        np.testing.assert_array_equal(ref[c], by_workers[c])
        np.testing.assert_array_equal(ref[c], by_dask[c])


def test_cli_workers_write_the_in_process_table(tmp_path, capsys):
    args = ["sweep", str(example_path("crank_rocker")), "--vary", "l_AB=0.02:0.04:3",
            "--vary", "l_BC=0.06:0.07:2", "--metrics", "K,min_transmission_deg",
            "--chunk-designs", "2"]
    assert main(args + ["-o", str(tmp_path / "one.csv")]) == 0
    assert main(args + ["-o", str(tmp_path / "two.csv"), "--workers", "2"]) == 0
    assert (tmp_path / "one.csv").read_text() == (tmp_path / "two.csv").read_text()
