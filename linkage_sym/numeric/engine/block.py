"""The result block: one allocation holds every result array of a run (NumPy only).

Both runtimes -- the numeric plan (:mod:`linkage_sym.numeric.plan`) and the
compiled symbolic mechanism (:mod:`linkage_sym.codegen.runtime`) -- write
their positions, rates and points into the rows of one ``(n_rows, N)``
block laid out by :class:`ResultLayout`, hand out the
:class:`~linkage_sym.numeric.results.result.LinkKinematics` and
:class:`~linkage_sym.numeric.results.result.JointKinematics` records as views of it
(:meth:`ResultLayout.records`), and blank the steps without a solution by
one rule (:meth:`ResultLayout.invalidate`).

A run's block and its temporaries take a few megabytes; :meth:`ResultLayout.warm`
touches them once, when a plan is compiled, so that a fresh process's first run does
not fault them in page by page (:mod:`linkage_sym.numeric.engine.heap`;
``benchmarks/bench_kinematics.py``, case ``fourbar_3600_fresh``, measures the first
call and the compile time this adds).
"""

from __future__ import annotations

import numpy as np

from linkage_sym.model import Scene
from linkage_sym.numeric.engine import heap
from linkage_sym.numeric.results.result import OK, SINGULAR, JointKinematics, LinkKinematics


WARM_FACTOR = {"numeric": (2.0, 2.5), "symbolic": (2.5, 3.0)}
"""Memory a run takes, in units of its result block, by runtime: kinematics, and with forces.
tracemalloc's peaks over 3600 steps of the four-bar, the offset slider-crank and the Watt and
class-III six-bars: numeric 1.7-2.0 blocks (2.1-2.3 with forces), symbolic 2.3-2.5 (2.8-2.9)."""


class ResultLayout:
    """Where each result array lives in a run's result block.

    Both runtimes write their results into such a block.  Every result array is a row (scalars over the steps) or a pair of rows
    (vectors, handed out as the ``(N, 2)`` transposed view) of one
    ``(n_rows, N)`` block: one allocation per run instead of one per array
    and per temporary, which is most of the cost of a sweep once the groups
    are solved.  Positional rows come first, so the steps without a
    position (or without rates) are set to NaN in two operations.

    ``rows`` maps ``(link, field)`` for ``rotation, origin, com, w, vx, al,
    ax, com_velocity, com_acceleration``, ``(joint, field)`` and
    ``("point", name, field)`` for ``position, velocity, acceleration`` to
    the first row (``vx``/``ax`` start the pairs ``vx, vy`` / ``ax, ay``).
    """

    def __init__(self, scene: Scene, stages):
        self.stages = tuple(stages)
        rows = {}
        i = 0

        def put(key, n):
            nonlocal i
            rows[key] = i
            i += n

        for link in scene.links:
            put((link.name, "rotation"), 1)
            put((link.name, "origin"), 2)
            if link.com is not None:
                put((link.name, "com"), 2)
        for j in scene.joints:
            put((j.name, "position"), 2)
        for pt in scene.points:
            put(("point", pt.name, "position"), 2)
        self.n_pos = i
        for stage, (rot, lin, name) in (
            ("velocity", ("w", "vx", "velocity")),
            ("acceleration", ("al", "ax", "acceleration")),
        ):
            if stage not in stages:
                continue
            for link in scene.links:
                put((link.name, rot), 1)
                put((link.name, lin), 2)
                if link.com is not None:
                    put((link.name, f"com_{name}"), 2)
            for j in scene.joints:
                put((j.name, name), 2)
            for pt in scene.points:
                put(("point", pt.name, name), 2)
        self.rows = rows
        self.n_rows = i

    def warm(self, n_steps: int, runtime: str) -> int:
        """Warm the memory a run of ``n_steps`` by ``runtime`` (``"numeric"`` or
        ``"symbolic"``) takes (:data:`WARM_FACTOR`, :func:`heap.warm`); returns the bytes
        touched."""
        factor = WARM_FACTOR[runtime]["forces" in self.stages]
        return heap.warm(factor * 8 * self.n_rows * n_steps)

    def rate_rows(self, block, link) -> dict:
        """The rows of ``block`` a link's rate fields are bound to (see ``LinkState``)."""
        out = {}
        for rot, lin in (("w", "vx"), ("al", "ax")):
            if (link, rot) in self.rows:
                i = self.rows[link, lin]
                out[rot] = block[self.rows[link, rot]]
                out[lin], out[lin[0] + "y"] = block[i], block[i + 1]
        return out

    def pair(self, block, key) -> np.ndarray:
        """The two rows ``(2, N)`` of a vector result."""
        i = self.rows[key]
        return block[i : i + 2]

    def records(self, scene: Scene, block, stages):
        """The result records of a run as views of ``block``: ``(links, joints, points)``.

        Vectors are the ``(N, 2)`` transposed views of their pairs of rows, so
        writing a record's ``.T`` (or :meth:`pair`) fills the block.
        """
        has_v = "velocity" in stages
        has_a = "acceleration" in stages
        pair = lambda key: self.pair(block, key).T  # noqa: E731
        links = {}
        for link in scene.links:
            n = link.name
            lk = LinkKinematics(rotation=block[self.rows[n, "rotation"]], origin=pair((n, "origin")))
            if has_v:
                lk.omega = block[self.rows[n, "w"]]
                lk.origin_velocity = pair((n, "vx"))
            if has_a:
                lk.alpha = block[self.rows[n, "al"]]
                lk.origin_acceleration = pair((n, "ax"))
            if link.com is not None:
                lk.com = pair((n, "com"))
                if has_v:
                    lk.com_velocity = pair((n, "com_velocity"))
                if has_a:
                    lk.com_acceleration = pair((n, "com_acceleration"))
            links[n] = lk

        def tracked(key):
            rec = JointKinematics(position=pair((*key, "position")))
            if has_v:
                rec.velocity = pair((*key, "velocity"))
            if has_a:
                rec.acceleration = pair((*key, "acceleration"))
            return rec

        joints = {j.name: tracked((j.name,)) for j in scene.joints}
        points = {pt.name: tracked(("point", pt.name)) for pt in scene.points}
        return links, joints, points

    def invalidate(self, block, status) -> None:
        """NaN where a step has no solution: a singular step keeps its positions, no step
        that is not ``ok`` keeps rates."""
        bad = status != OK
        if bad.any():
            block[: self.n_pos, bad & (status != SINGULAR)] = np.nan
            block[self.n_pos :, bad] = np.nan
