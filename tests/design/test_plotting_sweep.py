"""The pictures of a design sweep (``sweep --plots``): units on every axis, whole titles.

The sweep results are built by hand (:class:`~linkage_sym.design.table.SweepResult` is a
plain container), so these tests check the drawing, not the sweep; the figures are read
back from Matplotlib's objects.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkage_sym
from linkage_sym.design import plots
from linkage_sym.design.api import scene_parameters
from linkage_sym.design.table import SweepResult


@pytest.fixture
def figures(monkeypatch):
    """The figures :func:`sweep_plots` makes, by file name, instead of writing them."""
    made = {}

    def keep(fig, path):
        made[str(path).rsplit("/", 1)[-1]] = fig
        return path

    monkeypatch.setattr(plots, "save", keep)
    return made


def _grid(scene_name="crank-rocker"):
    a, b = np.linspace(0.02, 0.03, 3), np.linspace(0.3, 0.6, 4)
    A, B = np.meshgrid(a, b, indexing="ij")
    n = A.size
    cols = {"design": np.arange(n, dtype=float), "l_AB": A.ravel(), "m_coupler": B.ravel(),
            "assemblable": np.ones(n), "swing_deg": 40 + 100 * A.ravel(),
            "peak_driving_A": B.ravel() ** 2, "rms_shaking_moment": 0.02 * B.ravel()}
    return SweepResult(cols, ("l_AB", "m_coupler"),
                       ("assemblable", "swing_deg", "peak_driving_A", "rms_shaking_moment"),
                       "grid", (("l_AB", a), ("m_coupler", b)), scene_name)


def _monte_carlo(scene_name, n=400):
    rng = np.random.default_rng(0)
    cols = {"design": np.arange(n, dtype=float), "l_AB": 0.024 + 1e-3 * rng.standard_normal(n),
            "rms_shaking_moment": 0.0209921 + 0.00193 * rng.standard_normal(n),
            "peak_driving_A": 0.2 + 0.01 * rng.standard_normal(n)}
    return SweepResult(cols, ("l_AB",), ("rms_shaking_moment", "peak_driving_A"),
                       "monte-carlo", (), scene_name)


# the unit of each metric, from the table of linkage_sym.design.metrics' docstring
METRIC_UNITS = {"swing_deg": "deg", "rms_shaking_moment": "N·m"}


def test_maps_name_the_units_of_their_parameters_and_metrics(figures):
    """A map's axes and colour bar said ``l_AB``, ``m_coupler``, ``swing_deg``: no unit."""
    plots.sweep_plots(_grid(), "unused")
    assert set(figures) == {f"crank-rocker_sweep_{c}.png" for c in
                            ("assemblable", "swing_deg", "peak_driving_A", "rms_shaking_moment")}
    for column, unit in METRIC_UNITS.items():
        fig = figures[f"crank-rocker_sweep_{column}.png"]
        ax, bar = fig.axes
        assert ax.get_xlabel() == "l_AB (m)"
        assert ax.get_ylabel() == "m_coupler (kg)"
        assert bar.get_ylabel() == f"{column} ({unit})"
    assert figures["crank-rocker_sweep_assemblable.png"].axes[1].get_ylabel() == (
        "assemblable (fraction of the steps ok)")
    figures.clear()  # with the scene, a driver's effort is a torque or a force
    plots.sweep_plots(_grid(), "unused", scene=linkage_sym.load_example("crank_rocker"))
    bar = figures["crank-rocker_sweep_peak_driving_A.png"].axes[1]
    assert bar.get_ylabel() == "peak_driving_A (N·m)"


def test_histograms_name_the_unit_and_their_titles_are_whole(figures):
    """A histogram's x axis said ``rms_shaking_moment`` without its unit, and its title
    (scene, metric, mean and standard deviation on one line) ran off the figure for a
    longer scene name: every title's extent is now inside the figure (renderer extents)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    plots.sweep_plots(_monte_carlo("single-cylinder four-stroke engine"), "unused")
    assert len(figures) == 2
    for name, fig in figures.items():
        renderer = FigureCanvasAgg(fig).get_renderer()
        fig.draw(renderer)
        ax = fig.axes[0]
        box = ax.title.get_window_extent(renderer)
        assert box.x0 >= 0 and box.x1 <= fig.bbox.width and box.y1 <= fig.bbox.height, name
        assert "mean" in ax.get_title() and "standard deviation" in ax.get_title()
        column = name.removeprefix("single-cylinder_four-stroke_engine_sweep_")[:-4]
        unit = "N·m" if column == "rms_shaking_moment" else "N·m (R driver) or N (P driver)"
        assert ax.get_xlabel() == f"{column} ({unit})"
        assert ax.get_ylabel() == "designs"


def test_a_drivers_effort_is_a_torque_or_a_force():
    boom = linkage_sym.load_example("hydraulic_boom")  # driven at its slide P
    assert plots.column_unit("peak_driving_P", boom) == "N"
    assert plots.column_unit("rms_driving_A", linkage_sym.load_example("crank_rocker")) == "N·m"
    assert plots.column_unit("peak_driving_P") == "N·m (R driver) or N (P driver)"


# the unit of a parameter from its meaning (what `sweep --list` prints), not from its name
MEANINGS = (("distance from joint", "m"), ("x of point", "m"), ("y of point", "m"),
            ("centre of mass of link", "m"), (": point x in the frame", "m"),
            (": point y in the frame", "m"), ("slide direction", "rad"), ("angle of", "rad"),
            ("moment of inertia", "kg·m²"), ("mass of link", "kg"), ("gravity", "m/s²"),
            (": torque", "N·m"), (": force", "N"))


@pytest.mark.parametrize("example", ["crank_rocker", "slider_crank_offset", "shaper",
                                     pytest.param("watt_sixbar", marks=pytest.mark.slow)])
def test_every_parameter_has_the_unit_its_meaning_says(example):
    rows = scene_parameters(linkage_sym.load_example(example))
    assert rows
    for name, _, meaning in rows:
        want = next(unit for text, unit in MEANINGS if text in meaning)
        assert plots.column_unit(name) == want, (name, meaning)
