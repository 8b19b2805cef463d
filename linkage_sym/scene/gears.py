"""Reading gear meshes (``G`` joints), an extension of the scene format.

A mesh joins two gears turning on pivots of a carrier link; see the
extension "gear meshes" of ``docs/scene-format.md``.  The fields of a ``G``
joint are read with the checks and wording of
:class:`~linkage_sym.scene.fields.FieldReader` (:func:`read_mesh_fields`);
once every joint is read, :func:`place_meshes` finds each gear's pivot on the
carrier, checks the pivots' distance against the radii and computes the pitch
point, which becomes the joint's ``at``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, NamedTuple

from linkage_sym.model.scene import GROUND, Joint, Point
from linkage_sym.scene.fields import FieldReader, did_you_mean, show_value

GEAR_KEYS = ("carrier", "radii", "internal", "pressure_angle_deg")
"""The keys only a ``G`` joint has."""

CENTRE_TOLERANCE = 1e-6
"""Relative tolerance of the pivots' distance against ``ra + rb`` (``|ra - rb|``
for an internal mesh), and of a given ``at`` against the pitch point (relative
to that distance): a micrometre on a metre."""

DEFAULT_PRESSURE_ANGLE_DEG = 20.0
"""The pressure angle of a mesh that does not give one (the standard involute's)."""

MAX_PRESSURE_ANGLE_DEG = 45.0
"""Largest pressure angle accepted (involute gears use 14.5 to 25 degrees)."""


class MeshFields(NamedTuple):
    """A ``G`` joint's own fields, read; placed later by :func:`place_meshes`."""

    index: int
    name: str
    links: tuple[str, str]
    at: Point | None
    carrier: str
    radii: tuple[float, float]
    internal: bool
    pressure_angle: float


def read_mesh_fields(
    reader: FieldReader,
    entry: Mapping[str, Any],
    path: str,
    links: tuple[str, str] | None,
    link_names: Any,
) -> tuple[str | None, tuple[float, float] | None, bool | None, float | None]:
    """``carrier``, ``radii``, ``internal`` and the pressure angle (radians) of a ``G`` joint.

    Each invalid field is reported through ``reader`` (and returned as ``None``).
    """
    carrier = GROUND
    field = f"{path}.carrier"
    if "carrier" in entry:
        carrier = entry["carrier"]
        if not isinstance(carrier, str) or not carrier:
            reader.add(field, f"must be a non-empty link name, got {show_value(carrier)}")
            carrier = None
        elif link_names is not None and carrier != GROUND and carrier not in link_names:
            choices = [GROUND, *link_names]
            reader.add(field, f"unknown link '{carrier}'{did_you_mean(carrier, choices)}")
            carrier = None
    if carrier is not None and links is not None and carrier in links:
        reader.add(
            field,
            f"link '{carrier}' is one of the mesh's gears; the carrier is the link both gears "
            "turn on (default 'ground')",
        )
        carrier = None
    radii = None
    values = reader.numbers(entry, "radii", path, length=2)
    if values is not None:
        bad = [i for i, r in enumerate(values) if r <= 0]
        for i in bad:
            reader.add(f"{path}.radii[{i}]", f"a pitch radius must be > 0, got {values[i]:g}")
        if not bad:
            radii = (values[0], values[1])
    internal = reader.boolean(entry, "internal", path, default=False)
    if internal and radii is not None and radii[0] == radii[1]:
        reader.add(
            f"{path}.radii",
            f"an internal mesh needs two different radii (the larger gear is the ring), got "
            f"{radii[0]:g} twice",
        )
        radii = None
    angle = reader.number(
        entry, "pressure_angle_deg", path, default=DEFAULT_PRESSURE_ANGLE_DEG, minimum=0.0
    )
    if angle is not None and angle > MAX_PRESSURE_ANGLE_DEG:
        reader.add(
            f"{path}.pressure_angle_deg",
            f"must be at most {MAX_PRESSURE_ANGLE_DEG:g} degrees (involute gears use 14.5 to 25), "
            f"got {angle:g}",
        )
        angle = None
    return carrier, radii, internal, None if angle is None else math.radians(angle)


def pitch_point(pa: Point, pb: Point, radii: tuple[float, float], internal: bool) -> Point:
    """The pitch point of gears with pivots ``pa``, ``pb`` (on their line of centres).

    At ``ra`` from ``pa``: towards ``pb`` for an external mesh or when gear a
    is the ring, away from it when gear a is the pinion of an internal mesh.
    """
    ra, rb = radii
    d = math.dist(pa, pb)
    ex, ey = (pb[0] - pa[0]) / d, (pb[1] - pa[1]) / d
    sigma = -1.0 if internal and ra < rb else 1.0
    return (pa[0] + sigma * ra * ex, pa[1] + sigma * ra * ey)


def place_meshes(reader: FieldReader, meshes: list[MeshFields], joints: list[Joint]) -> dict[int, Joint]:
    """Each valid mesh as a :class:`Joint`, keyed by its index among the joints.

    ``joints`` are the valid ``R`` and ``P`` joints.  A mesh needs exactly one
    ``R`` joint between each gear and the carrier (its pivot), pivots whose
    distance is ``ra + rb`` (external) or ``|ra - rb|`` (internal) within
    :data:`CENTRE_TOLERANCE`, and, if it gives ``at``, its pitch point there.
    """
    out = {}
    for m in meshes:
        path = f"joints[{m.index}]"
        pivots = []
        for k, gear in enumerate(m.links):
            found = _pivot(joints, gear, m.carrier, sum(m.radii))
            if len(found) != 1:
                why = (
                    "no R joint joins them, and the gear is pinned to no link at a point where "
                    "the carrier is pinned too"
                    if not found
                    else f"{len(found)} joints could be its pivot ({', '.join(j.name for j in found)})"
                )
                reader.add(
                    f"{path}.links[{k}]",
                    f"gear '{gear}' needs one R joint with the carrier '{m.carrier}' to turn on "
                    f"(its pivot): {why}",
                )
            else:
                pivots.append(found[0])
        if len(pivots) != 2:
            continue
        (ja, jb), (ra, rb) = pivots, m.radii
        d = math.dist(ja.at, jb.at)
        need = abs(ra - rb) if m.internal else ra + rb
        kind = "an internal mesh needs |ra - rb|" if m.internal else "an external mesh needs ra + rb"
        sign = "-" if m.internal else "+"
        if abs(d - need) > CENTRE_TOLERANCE * need:
            reader.add(
                f"{path}.radii",
                f"mesh '{m.name}': the pivots {ja.name} ({m.links[0]}) and {jb.name} "
                f"({m.links[1]}) are {d:.9g} m apart, but {kind} = {ra:g} {sign} {rb:g} = "
                f"{need:.9g} m (relative difference {abs(d - need) / need:.2g}, tolerance "
                f"{CENTRE_TOLERANCE:g})",
            )
            continue
        p = pitch_point(ja.at, jb.at, m.radii, m.internal)
        if m.at is not None and math.dist(m.at, p) > CENTRE_TOLERANCE * need:
            reader.add(
                f"{path}.at",
                f"[{m.at[0]:g}, {m.at[1]:g}] is not the pitch point [{p[0]:.9g}, {p[1]:.9g}] of "
                f"mesh '{m.name}' (on the line of centres {ja.name}-{jb.name}, {ra:g} m from "
                f"{ja.name}); leave 'at' out to have it computed",
            )
            continue
        reader.positions.append((f"{path}.at", p))
        out[m.index] = Joint(
            m.name, "G", m.links, p, None, m.carrier, m.radii, m.internal, m.pressure_angle,
            (ja.name, jb.name),
        )
    return out


def _pivot(joints: list[Joint], gear: str, carrier: str, scale: float) -> list[Joint]:
    """The R joints a gear can turn on relative to ``carrier``.

    Those joining it to the carrier; if none, those joining it to another
    link ``X`` at the point where an R joint pins the carrier to ``X`` too
    (coaxial: a sun and its arm both pinned to the ground at one point),
    the two points within :data:`CENTRE_TOLERANCE` of ``scale`` (the radii's sum).
    """
    direct = [j for j in joints if j.type == "R" and set(j.links) == {gear, carrier}]
    if direct:
        return direct
    out = []
    for j in joints:
        if j.type != "R" or gear not in j.links:
            continue
        x = j.links[0] if j.links[1] == gear else j.links[1]
        if any(
            k.type == "R" and set(k.links) == {carrier, x}
            and math.dist(k.at, j.at) <= CENTRE_TOLERANCE * scale
            for k in joints
        ):
            out.append(j)
    return out
