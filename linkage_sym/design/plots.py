"""Pictures of a sweep (``--plots DIR``): design maps and histograms (Matplotlib).

* a grid of two or more axes: one map per metric over the first two varied
  parameters (the other axes at their first value, said in the title), with
  the regions of the Grashof classes outlined and named when the sweep has
  them; a grid of one axis: the metric against the parameter;
* Monte Carlo and samples: a histogram per metric with its mean.

Every axis and colour bar names its column with the unit (:func:`column_label`): the
parameters in SI units as ``sweep --list`` prints them, the metrics in those of
:mod:`linkage_sym.design.metrics`.

Reads a :class:`~linkage_sym.design.table.SweepResult` (and the scene, for the
unit of a driver's effort) only; draws nothing that was not computed.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from linkage_sym.plotting.style import new_figure, safe_stem as _stem, save

__all__ = ["column_label", "column_unit", "sweep_plots"]

_PARAMETER_UNITS = {
    # the parameters' names (linkage_sym.structure.parameters): their prefix gives the unit
    "l": "m", "x": "m", "y": "m", "xG": "m", "yG": "m", "xi": "m", "eta": "m", "r": "m",
    "beta": "rad", "gamma": "rad", "delta": "rad", "phi": "rad", "epsilon": "rad",
    "theta0": "rad", "m": "kg", "I": "kg·m²", "g": "m/s²", "F": "N", "T": "N·m",
}
_METRIC_UNITS = {
    "assemblable": "fraction of the steps ok", "K": "ratio", "swing_deg": "deg",
    "min_transmission_deg": "deg", "rms_shaking_force": "N", "rms_shaking_moment": "N·m",
}

_WORDS = ("fraction of the steps ok", "ratio")
"""The "units" of dimensionless metrics: said on an axis, not after a number."""


def column_unit(name: str, scene=None) -> str:
    """The unit of a sweep table's column (``""`` when it has none, e.g. ``design``).

    Parameters
    ----------
    name : str
        A parameter (``l_AB``, ``m_crank``, ...) or metric column (``swing_deg``,
        ``peak_driving_A``, ...).
    scene : Scene, optional
        The swept scene: a driver's effort is a torque (N·m) at an ``R`` joint and a
        force (N) at a ``P`` joint; without it the unit says both.

    Examples
    --------
    >>> [column_unit(c) for c in ("l_AB", "beta_BP", "I_coupler", "T_1", "swing_deg", "K")]
    ['m', 'rad', 'kg·m²', 'N·m', 'deg', 'ratio']
    >>> column_unit("peak_driving_A")
    'N·m (R driver) or N (P driver)'
    """
    if name in _METRIC_UNITS:
        return _METRIC_UNITS[name]
    for metric in ("peak_driving_", "rms_driving_"):
        if name.startswith(metric):
            if scene is None:
                return "N·m (R driver) or N (P driver)"
            return "N·m" if scene.joint(name[len(metric):]).type == "R" else "N"
    if name.startswith("peak_reaction_"):
        return "N"
    if name.startswith("path_"):
        return "m"
    return _PARAMETER_UNITS.get(name.partition("_")[0], "")


def column_label(name: str, scene=None) -> str:
    """``name (unit)``: an axis label (see :func:`column_unit`)."""
    unit = column_unit(name, scene)
    return f"{name} ({unit})" if unit else name


def _numeric(res) -> list:
    return [c for c in res.metrics if not c.startswith("path_") and res[c].dtype.kind == "f"]


def sweep_plots(res, folder, scene=None) -> list[str]:
    """Draw the sweep's pictures into ``folder``; returns the files written.

    ``scene`` (the swept scene, optional) gives the unit of a driver's effort
    (:func:`column_unit`).

    Examples
    --------
    >>> import linkage_sym, tempfile
    >>> res = linkage_sym.sweep(linkage_sym.load_example("crank_rocker"),
    ...                         {"l_AB": [0.02, 0.03], "l_BC": [0.06, 0.07]}, ["K"])
    >>> [p.split("/")[-1] for p in sweep_plots(res, tempfile.mkdtemp())]
    ['crank-rocker_sweep_K.png']
    """
    folder = Path(folder)
    stem = _stem(res.scene)
    out = []
    for c in _numeric(res):
        if res.kind == "grid" and len(res.axes) >= 2:
            fig = _map(res, c, scene)
        elif res.kind == "grid":
            fig = _curve(res, c, scene)
        else:
            fig = _histogram(res, c, scene)
        out.append(str(save(fig, folder / f"{stem}_sweep_{_stem(c)}.png")))
    return out


def _grid_slice(res, column):
    """``(x values, y values, Z (ny, nx), note)`` of a column on the first two axes."""
    shape = tuple(len(v) for _, v in res.axes)
    Z = np.asarray(res[column], float).reshape(shape)
    rest = []
    while Z.ndim > 2:
        Z = Z[..., 0]
        name, vals = res.axes[Z.ndim]
        rest.append(f"{name} = {vals[0]:.6g}")
    (nx, x), (ny, y) = res.axes[0], res.axes[1]
    return x, y, Z.T, (", ".join(reversed(rest)))


def _map(res, column, scene=None):
    (xn, _), (yn, _) = res.axes[0], res.axes[1]
    x, y, Z, note = _grid_slice(res, column)
    fig = new_figure(6.4, 4.8)
    ax = fig.add_subplot()
    if np.isfinite(Z).any():
        mesh = ax.pcolormesh(x, y, np.ma.masked_invalid(Z), shading="nearest", cmap="viridis")
        fig.colorbar(mesh, ax=ax, label=column_label(column, scene))
    else:
        ax.text(0.5, 0.5, f"no design has a value of {column}", ha="center", va="center",
                transform=ax.transAxes)
    if "grashof" in res.columns and len(x) > 1 and len(y) > 1:
        _grashof_regions(ax, res, x, y)
    ax.set_xlabel(column_label(xn))
    ax.set_ylabel(column_label(yn))
    _title(ax, f"{res.scene}: {column}", f"at {note}" if note else "")
    return fig


def _title(ax, head: str, more: str = "") -> None:
    """A title of one or two lines, wrapped within the figure (none is cut off)."""
    ax.set_title(head + (f"\n{more}" if more else ""), fontsize=9, wrap=True)


def _grashof_regions(ax, res, x, y):
    """Outline and name the regions of each Grashof class and of the designs that cannot be
    assembled at the scene's driver values."""
    G = np.asarray(res["grashof"]).reshape(tuple(len(v) for _, v in res.axes))
    while G.ndim > 2:
        G = G[..., 0]
    G = G.T
    kinds = [k for k in np.unique(G) if k]
    code = np.full(G.shape, -1.0)
    for i, k in enumerate(kinds):
        code[G == k] = i
    if len(kinds) > 1 or (code < 0).any():
        levels = np.arange(-1, len(kinds)) + 0.5
        ax.contour(x, y, code, levels=levels, colors="k", linewidths=1.0)
    for i, k in enumerate(kinds):
        jj, ii = np.nonzero(code == i)
        ax.text(np.mean(x[ii]), np.mean(y[jj]), k, color="k", ha="center", va="center",
                fontsize=8, bbox={"facecolor": "white", "alpha": 0.7, "edgecolor": "none"})
    if (code < 0).any():
        jj, ii = np.nonzero(code < 0)
        ax.text(np.mean(x[ii]), np.mean(y[jj]), "not assembled at the\nscene's driver values",
                color="0.3", ha="center", va="center", fontsize=8)


def _curve(res, column, scene=None):
    name, x = res.axes[0]
    fig = new_figure(6.4, 4.0)
    ax = fig.add_subplot()
    ax.plot(x, res[column], marker=".")
    ax.set_xlabel(column_label(name))
    ax.set_ylabel(column_label(column, scene))
    _title(ax, f"{res.scene}: {column}")
    ax.grid(True, alpha=0.3)
    return fig


def _histogram(res, column, scene=None):
    v = np.asarray(res[column], float)
    fin = v[np.isfinite(v)]
    fig = new_figure(6.4, 4.0)
    ax = fig.add_subplot()
    if len(fin):
        ax.hist(fin, bins=min(50, max(5, int(np.sqrt(len(fin))))), color="#1f77b4", alpha=0.8)
        mean, sd = fin.mean(), fin.std()
        ax.axvline(mean, color="k", lw=1)
        unit = column_unit(column, scene)
        # after a number: a unit, not a word ("ratio") nor an alternative
        unit = f" {unit}" if unit and unit not in _WORDS and " or " not in unit else ""
        _title(ax, f"{res.scene}: {column} over {len(fin)} designs",
               f"mean {mean:.6g}{unit}, standard deviation {sd:.3g}{unit}")
    else:
        _title(ax, f"{res.scene}: {column}", "no design has a value")
    if len(fin) < len(v):
        ax.text(0.99, 0.97, f"{len(v) - len(fin)} design(s) without a value", ha="right",
                va="top", transform=ax.transAxes, fontsize=8)
    ax.set_xlabel(column_label(column, scene))
    ax.set_ylabel("designs")
    return fig
