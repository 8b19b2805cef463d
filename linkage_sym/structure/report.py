"""Plain-text report of a structural decomposition, as a person reads it."""

from __future__ import annotations

from linkage_sym.model import Scene
from linkage_sym.structure.disconnection import default_choice, usable_disconnections
from linkage_sym.structure.grashof import grashof_lines
from linkage_sym.structure.groups import Decomposition


def structure_report(scene: Scene, dec: Decomposition, pick: str = "disconnection=K") -> str:
    """Describe drivers and Assur groups in solving order, with disconnection choices,
    and the Grashof class of every four-bar loop (:mod:`linkage_sym.structure.grashof`).

    ``pick``: how the reader picks choice ``K`` of a complex group, named after the list
    (the ``disconnection`` argument of :func:`linkage_sym.analyze` and
    :func:`linkage_sym.compile_plan`; the command line gives its option).

    Examples
    --------
    >>> from linkage_sym.model import Scene, Link, Joint, Driver
    >>> from linkage_sym.structure import decompose
    >>> j = (Joint("A", "R", ("ground", "crank"), (0, 0)),
    ...      Joint("B", "R", ("crank", "coupler"), (1, 0)),
    ...      Joint("C", "R", ("coupler", "rocker"), (2, 1)),
    ...      Joint("D", "R", ("rocker", "ground"), (3, 0)))
    >>> s = Scene("4bar", (Link("crank"), Link("coupler"), Link("rocker")), j,
    ...           (Driver("A", "R", 0.0, 6.28, 10, 1.0, toward="B"),))
    >>> print(structure_report(s, decompose(s)))
    Scene '4bar': 3 moving links, 4 joints, mobility 1, 1 driver
    Solving order:
      1. input link: crank; driven joint A (R); external joints A
      2. dyad RRR (class II): coupler, rocker; external joints B, D; internal joints C
    Four-bar loops (Grashof class, textbook section 'Design of four-bar mechanisms' [2]):
      ground D-A 3, crank A-B 1, coupler B-C 1.414, rocker C-D 1.414 (m): triple-rocker
         not Grashof: s + l = 1 + 3 = 4 > p + q = 2.82843; no link turns fully: the three moving links rock
    """
    nd = len(scene.drivers)
    lines = [
        f"Scene '{scene.name}': {len(scene.links)} moving links, {len(scene.joints)} joints, "
        f"mobility {dec.mobility}, {nd} driver{'s' if nd != 1 else ''}",
        "Solving order:",
    ]
    roman = {2: "II", 3: "III", 4: "IV", 5: "V", 6: "VI"}
    jtype = {j.name: j.type for j in scene.joints}
    for i, g in enumerate(dec.groups, 1):
        head = g.label
        if g.assur_class is not None and g.kind in ("dyad", "input", "driven"):
            head += f" (class {roman.get(g.assur_class, g.assur_class)})"
        text = f"  {i}. {head}: {', '.join(g.links)}"
        if g.drivers:
            text += "; driven joint" + ("s " if len(g.drivers) > 1 else " ")
            text += ", ".join(f"{d} ({jtype[d]})" for d in g.drivers)
        text += f"; external joints {', '.join(g.external)}"
        if g.internal:
            text += f"; internal joints {', '.join(g.internal)}"
        lines.append(text)
        if g.kind == "gear":  # gear meshes: their forces along the lines of action
            how = ("positions and forces in closed form (moments about the pivot give the tooth "
                   "load)" if len(g.links) == 1 else
                   "positions by Newton on the group's rows (linear in the angles), forces by a "
                   "dense solve of the group's own equilibrium")
            lines.append(f"     gear meshes {', '.join(j for j in g.joints if jtype[j] == 'G')}: {how}")
        elif g.kind == "cam":  # cam contacts: one unknown along the contact normal
            lines.append(f"     cam contacts {', '.join(j for j in g.joints if jtype[j] == 'cam')}: "
                         "positions from the contact conditions (the profile parameter as an "
                         "extra unknown), rates by the instantaneous replacement by lower pairs, "
                         "the contact force along the normal by a dense solve of the group")
        elif g.kind not in ("input", "dyad"):
            choices = usable_disconnections(scene, g)
            if choices:
                lines.append(
                    "     disconnection choices (Dang and Zhang's virtual pure-dyad mechanism; "
                    f"pick one with {pick}):"
                )
                best = default_choice(choices)
                for k, c in enumerate(choices):
                    mark = "  (default)" if k == best else ""
                    lines.append(f"       {k:2d}) {c.describe()}{mark}")
            else:
                lines.append(
                    "     no disconnection leaves a pure-dyad mechanism: forces by a dense "
                    "solve of the group's own equilibrium"
                )
    lines += grashof_lines(scene)
    return "\n".join(lines)
