"""Pictures of a sweep (``--plots DIR``): design maps and histograms (Matplotlib).

* a grid of two or more axes: one map per metric over the first two varied
  parameters (the other axes at their first value, said in the title), with
  the regions of the Grashof classes outlined and named when the sweep has
  them; a grid of one axis: the metric against the parameter;
* Monte Carlo and samples: a histogram per metric with its mean.

Reads a :class:`~linkage_sym.design.table.SweepResult` only; draws nothing
that was not computed.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from linkage_sym.plotting.style import new_figure, safe_stem as _stem, save

__all__ = ["sweep_plots"]




def _numeric(res) -> list:
    return [c for c in res.metrics if not c.startswith("path_") and res[c].dtype.kind == "f"]


def sweep_plots(res, folder) -> list[str]:
    """Draw the sweep's pictures into ``folder``; returns the files written.

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
            fig = _map(res, c)
        elif res.kind == "grid":
            fig = _curve(res, c)
        else:
            fig = _histogram(res, c)
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


def _map(res, column):
    (xn, _), (yn, _) = res.axes[0], res.axes[1]
    x, y, Z, note = _grid_slice(res, column)
    fig = new_figure(6.4, 4.8)
    ax = fig.add_subplot()
    if np.isfinite(Z).any():
        mesh = ax.pcolormesh(x, y, np.ma.masked_invalid(Z), shading="nearest", cmap="viridis")
        fig.colorbar(mesh, ax=ax, label=column)
    else:
        ax.text(0.5, 0.5, f"no design has a value of {column}", ha="center", va="center",
                transform=ax.transAxes)
    if "grashof" in res.columns and len(x) > 1 and len(y) > 1:
        _grashof_regions(ax, res, x, y)
    ax.set_xlabel(xn)
    ax.set_ylabel(yn)
    title = f"{res.scene}: {column}"
    ax.set_title(title + (f" ({note})" if note else ""), fontsize=9)
    return fig


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


def _curve(res, column):
    name, x = res.axes[0]
    fig = new_figure(6.4, 4.0)
    ax = fig.add_subplot()
    ax.plot(x, res[column], marker=".")
    ax.set_xlabel(name)
    ax.set_ylabel(column)
    ax.set_title(f"{res.scene}: {column}", fontsize=9)
    ax.grid(True, alpha=0.3)
    return fig


def _histogram(res, column):
    v = np.asarray(res[column], float)
    fin = v[np.isfinite(v)]
    fig = new_figure(6.4, 4.0)
    ax = fig.add_subplot()
    if len(fin):
        ax.hist(fin, bins=min(50, max(5, int(np.sqrt(len(fin))))), color="#1f77b4", alpha=0.8)
        mean, sd = fin.mean(), fin.std()
        ax.axvline(mean, color="k", lw=1)
        ax.set_title(f"{res.scene}: {column} over {len(fin)} designs (mean {mean:.6g}, "
                     f"standard deviation {sd:.3g})", fontsize=9)
    else:
        ax.set_title(f"{res.scene}: {column}: no design has a value", fontsize=9)
    if len(fin) < len(v):
        ax.text(0.99, 0.97, f"{len(v) - len(fin)} design(s) without a value", ha="right",
                va="top", transform=ax.transAxes, fontsize=8)
    ax.set_xlabel(column)
    ax.set_ylabel("designs")
    return fig
