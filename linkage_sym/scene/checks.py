"""The checks of a scene across its sections: its size, connectivity and mobility.

:class:`SceneChecks`, a part of the scene reader of
:mod:`linkage_sym.scene.validate`, runs once every section is read: the
mechanism's size (the largest distance between two joints) and every point
and slide against it, every link connected to the ground, and the
Gruebler-Kutzbach mobility against the number of drivers.

Examples
--------
>>> MIN_SIZE, MAX_SPREAD, MAX_SLIDE
(1e-30, 1000000000.0, 1000.0)
"""

from __future__ import annotations

import math
from collections import deque

from linkage_sym.model.scene import GROUND, Point
from linkage_sym.scene.fields import FieldReader

__all__ = ["COINCIDENCE_TOLERANCE", "MAX_SLIDE", "MAX_SPREAD", "MIN_SIZE", "SceneChecks"]

COINCIDENCE_TOLERANCE = 1e-9
"""Two joint points closer than this fraction of the mechanism's size coincide."""

MIN_SIZE = 1e-30
"""Smallest size (largest distance between two joints, m) of a mechanism.

Products of up to ten lengths of that size stay above float64's smallest normal
number (2.2e-308) instead of underflowing to 0.
"""

MAX_SPREAD = 1e9
"""Farthest a point may lie from the origin, in sizes of the mechanism.

A float64 keeps 16 significant digits of a coordinate: a point 1e9 sizes away
keeps 7 digits of the mechanism's geometry, and beyond it fewer.
"""

MAX_SLIDE = 1000.0
"""Largest ``|start|``, ``|stop|`` of a P driver, in sizes of the mechanism.

The solver follows a slide in increments of 2 % of the size (of 1 m when a single
joint gives no size), so such a sweep is already 150 000 solving points.
"""


class SceneChecks(FieldReader):
    """The checks across sections, on the reader's ``joint_points``, ``positions``,
    ``slides``, ``joints`` and ``link_index``."""

    def coincide(self, a: Point, b: Point) -> bool:
        """Whether two points are the same, relative to the size of the mechanism."""
        assert self.joints is not None
        points = [j.at for j in self.joints.values() if j.at is not None]
        size = max((math.dist(p, q) for p in points for q in points), default=0.0)
        # joints all at one point are reported once, by check_size
        return size > 0 and math.dist(a, b) <= COINCIDENCE_TOLERANCE * size

    def check_size(self) -> None:
        """The mechanism's size, and every point and slide against it.

        The size is the largest distance between two joints (the length the
        solver divides lengths by); it is checked only when every joint's
        point is valid.
        """
        if not self.joint_points or None in self.joint_points:
            return
        points = self.joint_points
        size = max(math.dist(p, q) for p in points for q in points)
        if len(points) >= 2 and size == 0:
            x, y = points[0]
            self.add(
                "joints",
                f"all {len(points)} joints are at the same point [{x:g}, {y:g}]: the mechanism "
                "has no size (the largest distance between two joints, by which the solver makes "
                "lengths dimensionless, is 0)",
            )
            return
        if 0 < size < MIN_SIZE:
            self.add(
                "joints",
                f"the mechanism's size (the largest distance between two joints) is {size:.3g} m, "
                f"below {MIN_SIZE:.0e} m: the solver squares and multiplies lengths, and such "
                "products would underflow float64 (smallest normal number 2.2e-308)",
            )
            return
        if size > 0:
            for field, point in self.positions:
                distance = math.hypot(*point)
                if distance > MAX_SPREAD * size:
                    self.add(
                        field,
                        f"is {distance:.3g} m from the origin, more than {MAX_SPREAD:.0e} times "
                        f"the mechanism's size ({size:.3g} m, the largest distance between two "
                        "joints): float64 keeps 16 digits of a coordinate, so fewer than 7 of the "
                        "mechanism's geometry would be left",
                    )
        scale = size if size > 0 else 1.0
        for field, value in self.slides:
            if abs(value) > MAX_SLIDE * scale:
                self.add(
                    field,
                    f"must be within +-{MAX_SLIDE * scale:.3g} m, {MAX_SLIDE:.0f} times the "
                    f"mechanism's size ({scale:.3g} m): the solver follows a slide in increments "
                    f"of 2% of the size, got {value:g}",
                )

    def check_connected(self) -> bool:
        """Report links in no joint or not connected to the ground; ``True`` if none."""
        assert self.link_index is not None and self.joints is not None
        neighbours: dict[str, set[str]] = {GROUND: set(), **{name: set() for name in self.link_index}}
        for info in self.joints.values():
            assert info.links is not None
            a, b = info.links
            neighbours[a].add(b)
            neighbours[b].add(a)
        reached = {GROUND}
        queue = deque([GROUND])
        while queue:
            for other in neighbours[queue.popleft()] - reached:
                reached.add(other)
                queue.append(other)
        ok = True
        for name, i in self.link_index.items():
            if not neighbours[name]:
                self.add(f"links[{i}]", f"link '{name}' appears in no joint")
                ok = False
            elif name not in reached:
                self.add(f"links[{i}]", f"link '{name}' is not connected to the ground")
                ok = False
        return ok

    def check_mobility(self, n_drivers: int) -> None:
        """Gruebler-Kutzbach: the mobility must equal the number of drivers."""
        assert self.link_index is not None and self.joints is not None
        n_links = len(self.link_index)
        n_meshes = sum(j.type in ("G", "cam") for j in self.joints.values())
        n_joints = len(self.joints) - n_meshes
        mobility = 3 * n_links - 2 * n_joints - n_meshes
        if mobility != n_drivers:
            higher = f" - {n_meshes}" if n_meshes else ""
            n_cams = sum(j.type == "cam" for j in self.joints.values())
            kinds = [f"{n} {what}" for n, what in ((n_meshes - n_cams, "gear meshes"),
                                                   (n_cams, "cam contacts")) if n]
            meshes = f", {' and '.join(kinds)} (higher pairs)" if n_meshes else ""
            self.add(
                "drivers",
                f"{n_drivers} driver{'s' if n_drivers != 1 else ''} given but the mobility is "
                f"M = 3*{n_links} - 2*{n_joints}{higher} = {mobility} (Gruebler-Kutzbach, {n_links} "
                f"moving links, {n_joints} joints{meshes}); the number of drivers must equal M",
            )
