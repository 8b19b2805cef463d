"""The layers of an animation's frames: arrows of velocities, accelerations, forces and the
driving effort, instant centres with their three-centre lines, transmission angles (Matplotlib
only).  :class:`Layers` is a part of :class:`~linkage_sym.plotting.animation.MechanismAnimation`,
which holds the figure, the analysis and the scales these methods read.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
from matplotlib.patches import Arc, FancyArrowPatch
from matplotlib.path import Path as MplPath

from linkage_sym.model import GROUND
from linkage_sym.plotting import style
from linkage_sym.plotting.animation_scale import BREAK_MARK, TORQUE_CUT, cut_vectors
from linkage_sym.plotting.centres import KIND_STYLE, centre_kind, three_centre_segments

__all__ = ["COLORS", "Layers"]

COLORS = {"velocity": "#00838f", "acceleration": "#c2185b", "reactions": "0.1",
          "driving": "#e65100", "transmission": "#6a1b9a"}
"""Colours of the layers' arrows (apart from the links' colours)."""


class Layers:
    """Drawing the layers on the current frame (a part of ``MechanismAnimation``)."""

    def _quiver(self, rows, scale, color, gid):
        """Arrows from each point along its vector times ``scale`` (axis units); one longer
        than :attr:`longest` (axis units, :data:`~linkage_sym.plotting.animation_scale.CUT`
        times the usual longest) is drawn that long, with a break mark across it."""
        rows = [(p, v) for p, v in rows if np.all(np.isfinite(p)) and np.all(np.isfinite(v))
                and np.hypot(*v) * scale > 1e-9 * self.L * self.unit_scale]
        if not rows:
            return None
        p = np.array([r[0] for r in rows]) * self.unit_scale
        v, cut = cut_vectors(np.array([r[1] for r in rows]), scale, self.longest)
        for k in np.flatnonzero(cut):  # the break mark, across the shaft
            at = p[k] + 0.6 * v[k]
            self.ax.plot([at[0]], [at[1]], ls="none", marker=BREAK_MARK, ms=11, color=color,
                         zorder=8, gid=f"{gid} cut")
        return self.ax.quiver(p[:, 0], p[:, 1], v[:, 0], v[:, 1], angles="xy",
                              scale_units="xy", scale=1.0, color=color, width=0.004,
                              headwidth=4.0, headlength=5.0, headaxislength=4.5, zorder=7,
                              gid=gid)

    def _arrows(self, layer: str, step: int) -> None:
        rows = [(p[step], v[step]) for _, p, v in self._vectors(layer)]
        self._quiver(rows, self.scales[layer], COLORS[layer], layer)

    def _forces(self, step: int) -> None:
        rows = [(p[step], r[step]) for _, p, r in self._reactions()]
        self._quiver(rows, self.scales["reactions"], COLORS["reactions"], "reactions")
        s = self.unit_scale
        for name, kind, values in self._drivers():
            value = float(values[step])
            if not math.isfinite(value):
                continue
            p = np.asarray(self.analysis.joints[name].position[step], dtype=float) * s
            if kind == "R":
                sweep = math.radians(float(np.clip(value * self.scales["driving"],
                                                   -TORQUE_CUT, TORQUE_CUT)))
                r = 0.12 * self.L * s
                t = np.linspace(0.0, sweep, 40)
                ring = p + r * np.stack([np.cos(t), np.sin(t)], axis=-1)
                if abs(sweep) > 1e-6:
                    self.ax.add_patch(FancyArrowPatch(
                        path=MplPath(ring), arrowstyle="-|>", mutation_scale=10,
                        color=COLORS["driving"], lw=1.6, zorder=7, gid=f"driving {name}"))
                text = f"T {name} = {style.fmt_number(value)} N·m"
            else:
                axis = self.scene.joint(name).axis + self._turn(self.scene.joint(name).links[0], step)
                u = np.array([math.cos(axis), math.sin(axis)])
                self._quiver([(p / s, value * u)], self.scales["driving force"],
                             COLORS["driving"], f"driving {name}")
                text = f"F {name} = {style.fmt_number(value)} N"
            self.ax.annotate(text, tuple(p), xytext=(-8, -14), textcoords="offset points",
                             ha="right", va="top", fontsize=7.5, color=COLORS["driving"], zorder=9,
                             bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none",
                                   "alpha": 0.75})

    def _turn(self, link: str, step: int) -> float:
        if link == GROUND:
            return 0.0
        return float(self.analysis.links[link].rotation[step])

    def _centres(self, step: int) -> None:
        c, s, ax = self.centres, self.unit_scale, self.ax
        for seg in three_centre_segments(c, step, self.L):
            seg = seg * s
            ax.plot(seg[:, 0], seg[:, 1], color="#d62728", lw=0.7, ls=(0, (5, 3)), alpha=0.55,
                    zorder=2)
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        groups, off = [], []
        for k in range(len(c.pairs)):
            label = c.label(k)
            if c.undefined[step, k]:
                continue
            if c.at_infinity[step, k]:
                off.append(f"{label} at infinity")
                continue
            p = c.position[step, k]
            if not np.all(np.isfinite(p)):
                continue
            q = p * s
            if not (x0 <= q[0] <= x1 and y0 <= q[1] <= y1):
                off.append(f"{label} off the drawing")
                continue
            kind = "velocity" if c.from_velocities[step, k] else centre_kind(c, k)
            ax.plot([q[0]], [q[1]], ls="none", zorder=8, gid=f"centre {label}", **KIND_STYLE[kind])
            for g in groups:  # centres close together share one label
                if np.hypot(*(g[0] - p)) <= 0.03 * self.L:
                    g[1].append(label)
                    break
            else:
                groups.append([p, [label], KIND_STYLE[kind]["mec"]])
        for p, labels, color in groups:
            ax.annotate(", ".join(labels), tuple(p * s), xytext=(5, -9), textcoords="offset points",
                        fontsize=7, color=color, zorder=9,
                        bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none",
                              "alpha": 0.7})
        if off:
            ax.text(0.99, 0.01, textwrap.fill("; ".join(off), 60), transform=ax.transAxes, ha="right", va="bottom",
                    fontsize=7, color="0.3", zorder=9)

    def _transmission(self, step: int) -> None:
        s, ax = self.unit_scale, self.ax
        for inner, e1, e2 in self.dyads:
            gamma = float(self.analysis.transmission_angles[inner][step])
            if not math.isfinite(gamma):
                continue
            J = np.asarray(self.analysis.joints[inner].position[step], dtype=float)
            a1 = math.atan2(*(np.asarray(self.analysis.joints[e1].position[step]) - J)[::-1])
            a2 = math.atan2(*(np.asarray(self.analysis.joints[e2].position[step]) - J)[::-1])
            # the arc from the first link to the second, the short way (gamma <= 180 degrees)
            start, stop = (a1, a2) if (a2 - a1) % (2 * math.pi) <= math.pi else (a2, a1)
            r = 0.14 * self.L * s
            ax.add_patch(Arc(tuple(J * s), 2 * r, 2 * r, theta1=math.degrees(start),
                             theta2=math.degrees(stop), color=COLORS["transmission"], lw=1.4,
                             zorder=6, gid=f"transmission {inner}"))
            mid = start + 0.5 * ((stop - start) % (2 * math.pi))
            at = J * s + 1.25 * r * np.array([math.cos(mid), math.sin(mid)])
            deg = math.degrees(gamma)
            ax.annotate(f"γ {inner} = {deg:.1f}°", tuple(at), ha="center", va="center",
                        fontsize=7.5, color=COLORS["transmission"], zorder=9,
                        bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none",
                              "alpha": 0.75})
