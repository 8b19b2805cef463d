"""The balancing plots write readable PNGs from shaking-load series.

The *before* series is the real one of the crank-rocker
(:func:`~linkage_sym.balancing.series.module_series`); the *after* series are
made here by hand (scaled, rotated, zero), since the balancing design is not
what is tested.  A few steps are marked not ``ok`` and NaN like the result
contract says.
"""

from __future__ import annotations

import ast
import struct
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import linkage_sym
from linkage_sym.balancing.series import BalanceSeries, module_series
from linkage_sym.plotting import balance
from linkage_sym.plotting.balance import (
    shaking_force_polar,
    shaking_force_polar_figure,
    shaking_moment_curve,
    shaking_moment_figure,
)

ROOT = Path(__file__).resolve().parents[2]
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
BAD_STEPS = {40: "unassemblable", 41: "unassemblable", 200: "singular"}


@pytest.fixture(scope="module")
def before() -> BalanceSeries:
    return module_series(linkage_sym.load_example("crank_rocker"), label="before")


def _copy(s: BalanceSeries, label: str, force_scale=1.0, moment_scale=1.0, turn=0.0):
    c, d = np.cos(turn), np.sin(turn)
    rot = np.array([[c, -d], [d, c]])
    return BalanceSeries(label, s.q.copy(), s.status.copy(), force_scale * s.force @ rot.T,
                         moment_scale * s.moment.copy())


def _with_bad_steps(s: BalanceSeries, label: str) -> BalanceSeries:
    out = _copy(s, label)
    out.status = out.status.astype("<U13")
    for k, st in BAD_STEPS.items():
        out.status[k] = st
        out.force[k] = np.nan
        out.moment[k] = np.nan
    return out


def _png_size(path: Path) -> tuple[int, int]:
    data = path.read_bytes()
    assert data[:8] == PNG_SIGNATURE
    assert data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


def _curves(ax) -> list:
    """The labelled artists of an axis: one per series."""
    return [line for line in ax.lines if not line.get_label().startswith("_")]


def _legend_texts(fig) -> list:
    return [t.get_text() for t in fig.legends[0].get_texts()]


def _all_text(fig) -> str:
    texts = [fig._suptitle.get_text() if fig._suptitle else ""]
    for ax in fig.axes:
        texts += [ax.get_title()] + [t.get_text() for t in ax.texts]
    for leg in fig.legends:
        texts += [t.get_text() for t in leg.get_texts()]
    return "\n".join(texts)


# ------------------------------------------------------------------------- files


@pytest.mark.slow
def test_files_are_valid_pngs_of_sensible_size(before, tmp_path):
    after = _copy(before, "after", 0.05, 0.1, turn=0.6)
    out = tmp_path / "new" / "dir"
    f = shaking_force_polar([before, after], out / "force.png", title="crank-rocker")
    m = shaking_moment_curve([before, after], out / "moment.png")
    assert f == out / "force.png" and m == out / "moment.png"
    for path in (f, m):
        w, h = _png_size(path)
        assert 800 <= w <= 2500 and 600 <= h <= 1600, (path, w, h)
        assert path.stat().st_size > 20_000  # a drawn figure, not an empty canvas


def test_path_may_be_a_string(before, tmp_path):
    p = shaking_force_polar([before], str(tmp_path / "f.png"))
    assert isinstance(p, Path) and p.exists()


# ------------------------------------------------------------- force polar diagram


def test_force_polar_one_curve_and_legend_entry_per_series(before):
    mid = _copy(before, "half", 0.5)
    fig = shaking_force_polar_figure([before, mid])
    assert len(fig.axes) == 1  # comparable sizes: no zoom panel
    ax = fig.axes[0]
    assert len(_curves(ax)) == 2
    texts = _legend_texts(fig)
    assert len(texts) == 2
    peak = float(np.nanmax(np.hypot(*before.force.T)))
    assert texts[0].startswith("before: peak |F| = ") and f"{peak:.3g} N" in texts[0]
    assert texts[1].startswith("half: peak |F| = ") and f"{0.5 * peak:.3g} N" in texts[1]
    assert ax.get_aspect() == 1.0  # equal axes
    assert "F_x" in ax.get_xlabel() and "(N)" in ax.get_xlabel()
    assert "F_y" in ax.get_ylabel() and "(N)" in ax.get_ylabel()
    # the origin is marked and inside the view
    assert any(line.get_marker() == "+" and list(line.get_xdata()) == [0.0]
               for line in ax.lines)
    assert ax.get_xlim()[0] < 0 < ax.get_xlim()[1] and ax.get_ylim()[0] < 0 < ax.get_ylim()[1]


def test_force_curve_is_closed_over_a_full_turn(before):
    fig = shaking_force_polar_figure([before])
    x = _curves(fig.axes[0])[0].get_xdata()
    assert x[-1] == x[0]
    assert "over the cycle" in fig._suptitle.get_text()


def test_small_after_series_gets_its_own_scale(before):
    after = _copy(before, "after", 0.01, turn=1.0)
    fig = shaking_force_polar_figure([before, after])
    assert len(fig.axes) == 2
    main, zoom = fig.axes
    assert len(_curves(main)) == 2  # every series on the common scale
    zoom_lines = [line for line in zoom.lines if len(line.get_xdata()) > 10]
    assert len(zoom_lines) == 1  # only the small one in the zoom panel
    peak = float(np.nanmax(np.hypot(*after.force.T)))
    (x0, x1), (y0, y1) = zoom.get_xlim(), zoom.get_ylim()
    fx, fy = after.force.T
    assert x0 < fx.min() and fx.max() < x1 and y0 < fy.min() and fy.max() < y1  # all of it
    assert x1 - x0 < 3 * peak  # at its own scale, not the before series'
    assert "zoom" in zoom.get_title()
    assert "also in the zoom panel" in _legend_texts(fig)[1]
    assert len(main.patches) == 1  # the dashed square showing the zoomed region


def test_zero_after_series_is_drawn_and_labelled(before):
    zero = _copy(before, "after", 0.0, 0.0)
    fig = shaking_force_polar_figure([before, zero])
    assert len(fig.axes) == 1  # nothing to magnify
    curves = _curves(fig.axes[0])
    assert len(curves) == 2
    mark = curves[1]
    assert mark.get_marker() == "D" and list(mark.get_xdata()) == [0.0]
    text = _legend_texts(fig)[1]
    assert text.startswith("after: numerically zero") and "peak |F| = 0 N" in text


def test_tiny_after_series_counts_as_zero(before):
    """Round-off (1e-17 of the before series) is labelled zero, with its value."""
    tiny = _copy(before, "after", 1e-17)
    fig = shaking_force_polar_figure([before, tiny])
    text = _legend_texts(fig)[1]
    assert "numerically zero" in text and "e-17 N" in text


@pytest.mark.slow
def test_zero_series_alone(tmp_path):
    q = np.linspace(0.0, 2 * np.pi, 37)
    zero = BalanceSeries("balanced", q, np.full(37, "ok"), np.zeros((37, 2)), np.zeros(37))
    assert shaking_force_polar(zero, tmp_path / "f.png").exists()  # one series, not a list
    assert shaking_moment_curve([zero], tmp_path / "m.png").exists()
    fig = shaking_moment_figure([zero])
    assert "balanced: numerically zero" in _legend_texts(fig)[0]
    line = _curves(fig.axes[0])[0]
    assert line.get_marker() == "D"  # visible on top of the zero axis


def test_force_nan_steps_make_gaps(before):
    bad = _with_bad_steps(before, "before")
    fig = shaking_force_polar_figure([bad])
    line = _curves(fig.axes[0])[0]
    x, y = np.asarray(line.get_xdata()), np.asarray(line.get_ydata())
    for k in BAD_STEPS:
        assert np.isnan(x[k]) and np.isnan(y[k])
    assert np.isfinite(x[39]) and np.isfinite(x[42])
    assert "3 of 361 steps skipped" in fig._suptitle.get_text()
    assert "3 of 361 steps skipped" in _legend_texts(fig)[0]


def test_status_not_ok_is_a_gap_even_with_a_value(before):
    """A finite value at a step whose status is not ok is not drawn."""
    s = _copy(before, "before")
    s.status = s.status.astype("<U13")
    s.status[100] = "singular"
    fig = shaking_force_polar_figure([s])
    assert np.isnan(_curves(fig.axes[0])[0].get_xdata()[100])
    fig = shaking_moment_figure([s])
    assert np.isnan(_curves(fig.axes[0])[0].get_ydata()[100])
    assert "1 of 361 steps skipped" in _all_text(fig)


def test_no_solved_step_at_all():
    n = 19
    q = np.full(n, np.nan)
    none = BalanceSeries("none", q, np.full(n, "unassemblable"), np.full((n, 2), np.nan),
                         np.full(n, np.nan))
    for make in (shaking_force_polar_figure, shaking_moment_figure):
        fig = make([none])
        assert "no solved step" in _all_text(fig)
        assert f"{n} of {n} steps skipped" in fig._suptitle.get_text()


# ------------------------------------------------------------------ moment curve


def test_moment_legend_gives_peak_and_rms(before):
    mid = _copy(before, "partly", moment_scale=0.6)
    fig = shaking_moment_figure([before, mid])
    assert len(fig.axes) == 1
    ax = fig.axes[0]
    assert len(_curves(ax)) == 2
    texts = _legend_texts(fig)
    assert len(texts) == 2
    m = before.moment
    # a whole turn: the RMS over the cycle counts the repeated end point once
    peak, rms = float(np.max(np.abs(m))), float(np.sqrt(np.mean(m[:-1] ** 2)))
    assert f"peak |M| = {peak:.3g} N·m" in texts[0] and f"RMS {rms:.3g} N·m" in texts[0]
    assert f"peak |M| = {0.6 * peak:.3g} N·m" in texts[1]
    assert ax.get_xlabel().startswith("driver angle θ (deg")
    assert "(N·m)" in ax.get_ylabel()
    x = _curves(ax)[0].get_xdata()
    assert x[0] == pytest.approx(0.0) and x[-1] == pytest.approx(360.0)  # degrees


def test_moment_small_after_series_gets_its_own_panel(before):
    after = _copy(before, "after", moment_scale=0.02)
    fig = shaking_moment_figure([before, after])
    assert len(fig.axes) == 2
    main, zoom = fig.axes
    assert len(_curves(main)) == 2
    assert len([line for line in zoom.lines if len(line.get_xdata()) > 10]) == 1
    peak = float(np.max(np.abs(after.moment)))
    assert peak < zoom.get_ylim()[1] < 2 * peak
    assert "zoom" in zoom.get_title()


def test_moment_nan_steps_make_gaps_and_are_shaded(before):
    bad = _with_bad_steps(before, "before")
    fig = shaking_moment_figure([bad, _copy(before, "zero", 0.0, 0.0)])
    ax = fig.axes[0]
    y = np.asarray(_curves(ax)[0].get_ydata())
    assert all(np.isnan(y[k]) for k in BAD_STEPS)
    assert np.isfinite(y[39]) and np.isfinite(y[42])
    texts = _legend_texts(fig)
    assert len(texts) == 2 + 2  # two series, then the unassemblable and singular bands
    assert "3 of 361" in fig._suptitle.get_text() and "skipped" in fig._suptitle.get_text()
    assert "numerically zero" in texts[1]


def test_prismatic_driver_is_in_metres(before):
    s = _copy(before, "slider")
    s.q = np.linspace(0.0, 0.2, len(s.q))
    fig = shaking_moment_figure([s], driver_kind="P")
    assert fig.axes[0].get_xlabel() == "driver displacement s (m)"
    assert " m," in _legend_texts(fig)[0]  # peak position in metres
    fig = shaking_force_polar_figure([s], driver_kind="P")
    assert "over the sweep" in fig._suptitle.get_text()  # not a cycle: not closed


# ------------------------------------------------------------------------ inputs


def test_bad_inputs_raise(before):
    with pytest.raises(ValueError, match="no series"):
        shaking_force_polar_figure([])
    short = _copy(before, "short")
    short.force = short.force[:-1]
    with pytest.raises(ValueError, match="force has shape"):
        shaking_force_polar_figure([before, short])
    short = _copy(before, "short")
    short.moment = short.moment[:-1]
    with pytest.raises(ValueError, match="moment has shape"):
        shaking_moment_figure([short])


# ---------------------------------------------------------------------- contract


def test_module_imports_neither_sympy_nor_cli_nor_balancing():
    """balance and the modules it is split into (balance_series, balance_force, balance_moment)."""
    names = set()
    for node in (n for path in sorted(Path(balance.__file__).parent.glob("balance*.py"))
                 for n in ast.walk(ast.parse(path.read_text(encoding="utf-8")))):
        if isinstance(node, ast.Import):
            names |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            names.add(node.module or "")
    assert not any(n.split(".")[0] == "sympy" for n in names), names
    assert not any(n.startswith(("linkage_sym.cli", "linkage_sym.balancing")) for n in names), names


@pytest.mark.slow
def test_plots_run_without_loading_sympy(tmp_path):
    code = (
        "import sys\n"
        "from types import SimpleNamespace\n"
        "import numpy as np\n"
        "from linkage_sym.plotting.balance import shaking_force_polar, shaking_moment_curve\n"
        "q = np.linspace(0.0, 2 * np.pi, 37)\n"
        "s = SimpleNamespace(label='s', q=q, status=np.full(37, 'ok'),\n"
        "                    force=np.stack([np.cos(q), np.sin(2 * q)], axis=-1), moment=np.sin(q))\n"
        f"shaking_force_polar([s], {str(tmp_path / 'f.png')!r})\n"
        f"shaking_moment_curve([s], {str(tmp_path / 'm.png')!r})\n"
        "print([m for m in ('sympy', 'linkage_sym.cli', 'linkage_sym.balancing') if m in sys.modules])\n"
    )
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == "[]"
    assert (tmp_path / "f.png").exists() and (tmp_path / "m.png").exists()


@pytest.mark.slow
def test_demo_and_balance_plots_give_one_plot_one_name(tmp_path):
    """The demo's balancing plots have the names ``balance --plots`` gives the same plots
    (the demo called the polar plot ``_balance_force_polar.png``, ``balance`` called it
    ``_shaking_force_polar.png``)."""
    from linkage_sym.cli import main
    from linkage_sym.cli.demo import demo_balance

    scene = linkage_sym.load_example("crank_rocker")
    (tmp_path / "demo").mkdir()
    demo = demo_balance(scene, "crank-rocker", tmp_path / "demo")
    assert main(["balance", str(linkage_sym.examples.example_path("crank_rocker")),
                 "-o", str(tmp_path / "b.json"), "--plots", str(tmp_path / "balance")]) == 0
    pngs = sorted(p.name for p in (tmp_path / "balance").iterdir())
    assert pngs == ["crank-rocker_shaking_force_polar.png", "crank-rocker_shaking_moment.png"]
    assert sorted(Path(p).name for p in demo if str(p).endswith(".png")) == pngs
