"""A compiled mechanism's artifact: what the generator wrote, as typed records (no SymPy).

:func:`linkage_sym.codegen.compile.build_artifact` derives a topology's equations and
prints them as functions; the cache (:mod:`linkage_sym.codegen.cache`) keeps the result
as JSON.  This module is the one place that reads that JSON: :meth:`Artifact.from_dict`
turns it into the records below, :meth:`Artifact.to_dict` writes it back, and every
evaluator (:mod:`linkage_sym.codegen.evaluator`) reads the records by name.

- :class:`Step` -- one stage of the positions, in solving order: a :class:`ClosedStep`
  (the nested closed forms of a run of groups) or a :class:`NewtonStep` (a group
  without a closed form, solved on its loop equations).  Each names its hook on the
  evaluator (:meth:`Step.solve`), the way ``sympy.physics.mechanics``'s ``Joint`` names
  its abstract methods: a backend says how it solves each kind, the walk over the
  steps is written once;
- :class:`Group` -- an Assur group: its links, its block of the rate matrix ``A``
  (rows and columns) and its assembly-mode sign's place in ``P``;
- :class:`ForceBlock` -- a group's equilibrium ``A_g F_g = b_g - C_g F_later``: the
  unknowns and the non-zero entries;
- :class:`Artifact` -- all of it, with the generated sources and the parameters'
  recipes (:mod:`linkage_sym.structure.recipes`).

Examples
--------
>>> art = Artifact.from_dict({
...     "scene": "s", "stages": ["kinematics"], "x": ["theta_crank", "theta_c"], "q": ["A"],
...     "params": [["l_AB", ["l", "crank", "B"]]], "sigmas": 0, "flanks": [],
...     "steps": [{"kind": "closed", "function": "positions_0", "x": [0, 1]}],
...     "groups": [{"index": 0, "links": ["crank"], "label": "input link", "closed": True,
...                 "cols": [0], "rows": [0, 1], "sigma": None}],
...     "rows_length": [False], "cols_length": [False, False], "pattern": [[0, 0]],
...     "layout": {}, "forces": [], "force_names": [], "functions": {}})
>>> art.steps[0].kind, art.groups[0].block, art.params[0].recipe.key
('closed', (0, 1, 0, 1), ('l', 'crank', 'B'))
>>> Artifact.from_dict(art.to_dict()) == art
True
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from linkage_sym.structure.recipes import Recipe

__all__ = ["Artifact", "ClosedStep", "ForceBlock", "FrictionJoint", "Group", "NewtonStep", "NamedParameter",
           "Step"]


@dataclass(frozen=True)
class Step(ABC):
    """One stage of the positions: the generated function ``function`` gives the
    coordinates ``x`` (indices into the artifact's ``x``)."""

    function: str
    x: tuple

    kind: ClassVar[str]

    @abstractmethod
    def solve(self, evaluator, X, ctx):
        """Fill the coordinates ``x`` of ``X`` (a list over every coordinate): the
        evaluator's hook for this kind of step, with the backend's context ``ctx``."""

    def to_dict(self) -> dict:
        return {"kind": self.kind, "function": self.function, "x": list(self.x)}


@dataclass(frozen=True)
class ClosedStep(Step):
    """Nested closed forms (input links, dyads): one call gives every coordinate.

    ``directions``: the generated function that gives the same
    coordinates without the angles' arctangents, and ``forms`` what it returns for each
    coordinate of ``x``, in order: ``"value"`` (a slide: its value), ``"unit"`` (an angle:
    its cosine and sine) or ``"atan2"`` (an angle ``atan2(Y, X) + r``: ``Y``, ``X``,
    ``cos r``, ``sin r``); see :func:`~linkage_sym.codegen.evaluator.unit_direction`.
    """

    directions: str | None = None
    forms: tuple = ()

    kind: ClassVar[str] = "closed"

    def solve(self, evaluator, X, ctx):
        return evaluator.closed_step(self, X, ctx)

    def to_dict(self) -> dict:
        out = super().to_dict()
        if self.directions is not None:
            out["directions"] = self.directions
            out["forms"] = list(self.forms)
        return out


@dataclass(frozen=True)
class NewtonStep(Step):
    """A group without a closed form: its function gives the loop residuals, then the
    Jacobian row by row; the backend's root finder solves it."""

    group: int = -1

    kind: ClassVar[str] = "newton"

    def solve(self, evaluator, X, ctx):
        return evaluator.newton_step(self, X, ctx)

    def to_dict(self) -> dict:
        return {**super().to_dict(), "group": self.group}


STEP_KINDS = {cls.kind: cls for cls in (ClosedStep, NewtonStep)}


@dataclass(frozen=True)
class Group:
    """An Assur group of the derivation, in solving order."""

    index: int
    links: tuple
    label: str
    closed: bool
    cols: tuple
    rows: tuple
    sigma: int | None

    @property
    def block(self) -> tuple:
        """``(r0, r1, c0, c1)``: its rows and columns of the rate matrix ``A``."""
        return (self.rows[0], self.rows[1], self.cols[0], self.cols[-1] + 1)

    @property
    def title(self) -> str:
        """The group as messages name it: ``"dyad RRR (coupler, rocker)"``."""
        return f"{self.label} ({', '.join(self.links)})"

    def to_dict(self) -> dict:
        return {"index": self.index, "links": list(self.links), "label": self.label,
                "closed": self.closed, "cols": list(self.cols), "rows": list(self.rows),
                "sigma": self.sigma}


@dataclass(frozen=True)
class ForceBlock:
    """A group's equilibrium block: ``unknowns`` (indices of the force names), the
    non-zero entries ``A`` ``(i, j)`` of ``A_g`` and ``C`` ``(i, force index)`` of ``C_g``."""

    unknowns: tuple
    A: tuple
    C: tuple

    def to_dict(self) -> dict:
        return {"unknowns": list(self.unknowns), "A": [list(p) for p in self.A],
                "C": [list(p) for p in self.C]}


@dataclass(frozen=True)
class FrictionJoint:
    """A joint whose friction acts (contract part two): ``kind`` ``"R"`` or ``"P"``,
    ``force`` the index of its friction (``Mf_<J>``, ``Ff_<J>``) among the force names,
    ``coefficient`` and ``radius`` (``None`` for a ``P`` joint) the indices of its
    coefficient and pin radius in ``P`` (:mod:`linkage_sym.codegen.friction`)."""

    joint: str
    kind: str
    force: int
    coefficient: int
    radius: int | None

    def to_dict(self) -> dict:
        return {"joint": self.joint, "kind": self.kind, "force": self.force,
                "coefficient": self.coefficient, "radius": self.radius}


@dataclass(frozen=True)
class NamedParameter:
    """An entry of the ``P`` argument: its symbol's name and its recipe."""

    name: str
    recipe: Recipe


def _pairs(seq) -> tuple:
    return tuple(tuple(p) for p in seq)


@dataclass(frozen=True, eq=False)
class Artifact:
    """A compiled topology: generated sources and the layout every evaluator reads.

    ``P`` (the generated functions' parameter argument) is :attr:`params`' values, then
    :attr:`sigmas` assembly-mode signs, then one flank sign per gear mesh of
    :attr:`flanks`.  ``layout`` maps a key (``"joint:<name>:<level>"``, ``"origin:..."``,
    ``"com:..."``, ``"slide:<joint>"``, ``"mesh:<joint>"``, ``"A:<group>"``, ``"b:..."``,
    ``"C:..."``) to its rows ``[a, b)`` of the ``points`` function's outputs.
    ``friction``: the joints whose friction acts (:class:`FrictionJoint`), whose
    frictions follow the reactions and efforts in :attr:`force_names` (and in the force
    blocks' ``C``); their relative rates are the ``points`` outputs under ``"frate:<joint>"``.
    ``parallels``: each dyad of two slides (``PRP``, ``RPP``) as ``(group, slide joint,
    slide joint, joint at their intersection)``, whose slides' cross product the function
    ``parallels_<group>`` gives.
    """

    scene: str
    stages: tuple
    x: tuple
    q: tuple
    params: tuple
    sigmas: int
    flanks: tuple
    steps: tuple
    groups: tuple
    rows_length: tuple
    cols_length: tuple
    pattern: tuple
    layout: dict
    forces: tuple
    force_names: tuple
    functions: dict
    key: str | None = None
    signature: dict | None = None
    friction: tuple = ()
    parallels: tuple = ()
    _derived: dict = field(default_factory=dict, repr=False, compare=False)

    # -- the cache's edge ----------------------------------------------------------------
    @classmethod
    def from_dict(cls, d: dict) -> "Artifact":
        """The records of an artifact read from the cache's JSON (or built in memory)."""
        steps = []
        for st in d["steps"]:
            kind = STEP_KINDS[st["kind"]]
            extra = ({"group": st["group"]} if kind is NewtonStep
                     else {"directions": st.get("directions"), "forms": tuple(st.get("forms", ()))})
            steps.append(kind(st["function"], tuple(st["x"]), **extra))
        return cls(
            scene=d["scene"], stages=tuple(d["stages"]), x=tuple(d["x"]), q=tuple(d["q"]),
            params=tuple(NamedParameter(n, Recipe.of(r)) for n, r in d["params"]),
            sigmas=int(d["sigmas"]), flanks=tuple(d.get("flanks", ())), steps=tuple(steps),
            groups=tuple(Group(g["index"], tuple(g["links"]), g["label"], g["closed"],
                               tuple(g["cols"]), tuple(g["rows"]), g["sigma"])
                         for g in d["groups"]),
            rows_length=tuple(bool(v) for v in d["rows_length"]),
            cols_length=tuple(bool(v) for v in d["cols_length"]),
            pattern=_pairs(d["pattern"]),
            layout={k: tuple(v) for k, v in d["layout"].items()},
            forces=tuple(ForceBlock(tuple(f["unknowns"]), _pairs(f["A"]), _pairs(f["C"]))
                         for f in d["forces"]),
            force_names=tuple(d["force_names"]), functions=dict(d["functions"]),
            key=d.get("key"), signature=d.get("signature"),
            friction=tuple(FrictionJoint(**f) for f in d.get("friction", ())),
            parallels=tuple((int(g), a, b, j) for g, a, b, j in d.get("parallels", ())))

    def to_dict(self) -> dict:
        """The JSON the cache stores (:meth:`from_dict` reads it back)."""
        out = {
            "scene": self.scene, "stages": list(self.stages), "x": list(self.x),
            "q": list(self.q),
            "params": [[p.name, list(p.recipe.key)] for p in self.params],
            "sigmas": self.sigmas, "flanks": list(self.flanks),
            "steps": [s.to_dict() for s in self.steps],
            "groups": [g.to_dict() for g in self.groups],
            "rows_length": list(self.rows_length), "cols_length": list(self.cols_length),
            "pattern": [list(p) for p in self.pattern],
            "layout": {k: list(v) for k, v in self.layout.items()},
            "forces": [f.to_dict() for f in self.forces],
            "force_names": list(self.force_names), "functions": dict(self.functions),
        }
        if self.friction:  # only where friction acts: other artifacts keep their JSON
            out["friction"] = [f.to_dict() for f in self.friction]
        if self.parallels:  # only with a dyad of two slides: other artifacts keep their JSON
            out["parallels"] = [list(p) for p in self.parallels]
        if self.key is not None:
            out["key"] = self.key
        if self.signature is not None:
            out["signature"] = self.signature
        return out

    def __eq__(self, other):
        return isinstance(other, Artifact) and self.to_dict() == other.to_dict()

    __hash__ = None

    # -- derived, made once ----------------------------------------------------------------
    def _once(self, name, make):
        got = self._derived.get(name)
        if got is None:
            got = self._derived[name] = make()
        return got

    @property
    def n_params(self) -> int:
        """How many entries of ``P`` are the scene's parameters (the signs follow)."""
        return len(self.params)

    @property
    def flank_at(self) -> int:
        """Where the gear meshes' flank signs start in ``P``."""
        return len(self.params) + self.sigmas

    @property
    def is_angle(self) -> np.ndarray:
        """Which coordinates are angles (the others are slides, lengths)."""
        return self._once("is_angle", lambda: np.array([n.startswith("theta_") for n in self.x]))

    @property
    def blocks(self) -> list:
        """Each group's ``(r0, r1, c0, c1)`` of ``A``, in solving order."""
        return self._once("blocks", lambda: [g.block for g in self.groups])

    def group(self, index: int) -> Group:
        """The group with this index."""
        return self._once("by_index", lambda: {g.index: g for g in self.groups})[index]

    def group_of_column(self) -> dict:
        """``{coordinate: the index of the group solving it}``."""
        return self._once("gidx", lambda: {c: g.index for g in self.groups for c in g.cols})

    @property
    def newton_steps(self) -> list:
        """The steps without a closed form."""
        return [s for s in self.steps if isinstance(s, NewtonStep)]

    def rows(self, values, key):
        """The ``points`` outputs under ``key`` of :attr:`layout` (a slice of ``values``)."""
        a, b = self.layout[key]
        return values[a:b]

    def load_entries(self) -> dict:
        """``{load index: [indices into P of its force and torque]}``: what a load's
        factor over the cycle scales."""
        def make():
            out: dict = {}
            for j, p in enumerate(self.params):
                load = p.recipe.scaled_load()
                if load is not None:
                    out.setdefault(load, []).append(j)
            return out

        return self._once("loads", make)

    def force_index(self) -> dict:
        """``{force name: its index}``."""
        return self._once("fidx", lambda: {n: i for i, n in enumerate(self.force_names)})
