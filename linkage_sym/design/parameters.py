"""Design spaces: which named parameters of a scene vary, and the designs to evaluate.

A *design* is the scene with some of its named parameters (the symbolic
layer's names, :mod:`linkage_sym.structure.parameters`: ``l_AB``, ``x_D``,
``m_coupler`` ...) set to other values.  A :class:`Designs` holds them as a
table, one row per design, one column per varied name:

* :func:`grid` -- the product of axes of values (``--vary NAME=LO:HI:N``);
* :func:`monte_carlo` -- normal deviations around the scene's values
  (``--monte-carlo N --tolerance NAME=SIGMA``), reproducible from a
  ``random_state``; a :class:`MonteCarlo` asks :func:`linkage_sym.design.sweep` to
  draw them about its scene's values;
* :func:`read_samples` -- a CSV file whose header names the parameters
  (``--samples FILE.csv``).

The assembly angles ``theta0_<link>`` are not design parameters: each design's
are those of its own assembly configuration (:mod:`linkage_sym.design.evaluate`).

Examples
--------
>>> d = grid({"l_AB": [0.02, 0.024], "l_BC": [0.06, 0.065, 0.07]})
>>> d.names, d.values.shape
(('l_AB', 'l_BC'), (6, 2))
>>> d.values[:3].tolist()
[[0.02, 0.06], [0.02, 0.065], [0.02, 0.07]]
"""

from __future__ import annotations

import csv
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from linkage_sym.design.errors import SweepError
from linkage_sym.numeric.engine import heap
from linkage_sym.errors import POINTERS, finite_number

__all__ = ["Designs", "MonteCarlo", "grid", "monte_carlo", "read_samples", "parse_axis", "parse_tolerance",
           "check_names", "parameter_list", "design_problems", "refuse_invalid"]


@dataclass(frozen=True)
class Designs:
    """Designs to evaluate: ``values[i, k]`` is parameter ``names[k]`` of design ``i``.

    ``kind``: ``"grid"``, ``"monte-carlo"`` or ``"samples"``; ``axes``: a grid's
    ``(name, values)`` per axis (the first varies slowest).
    """

    names: tuple
    values: np.ndarray
    kind: str
    axes: tuple = field(default=())

    def __len__(self) -> int:
        return len(self.values)


@dataclass(frozen=True)
class MonteCarlo:
    """A Monte Carlo spread about a scene's values, for :func:`linkage_sym.design.sweep`:
    ``n`` designs with every parameter of ``tolerance`` (``name -> sigma``, the standard
    deviation in the parameter's unit) drawn from a normal distribution about the scene's
    value (:func:`monte_carlo`, ``numpy.random.default_rng(random_state)``: the same
    ``random_state`` gives the same designs).

    The sweep checks it; a problem names ``monte_carlo`` (``n``), ``tolerance`` or
    ``random_state``.

    Examples
    --------
    >>> MonteCarlo(1000, {"l_AB": 5e-5})
    MonteCarlo(n=1000, tolerance={'l_AB': 5e-05}, random_state=0)
    """

    n: int
    tolerance: Mapping[str, float]
    random_state: int = 0

    def designs(self, base) -> Designs:
        """The designs drawn about ``base`` (``name -> value``, the scene's values)."""
        return monte_carlo(base, self.tolerance, self.n, self.random_state)


DESIGN_BYTES = 64
"""Memory a design takes besides its parameters' values, at the least: its row of the
result table (a few metrics) and the designs' bookkeeping."""


def _fits(n_designs: int, n_names: int, field_name: str) -> None:
    """Refuse a sweep whose designs' table alone would not fit in the memory left."""
    need = n_designs * (8 * n_names + DESIGN_BYTES)
    available = heap.available_memory()
    if available is not None and need > available:
        raise SweepError(field_name, f"{n_designs} designs do not fit in memory: their table "
                                     f"alone takes {heap.gib(need)}, and this process can "
                                     f"take {heap.gib(available)} more")


def _finite(where: str, v) -> float:
    return finite_number(where, v, SweepError)


def grid(axes) -> Designs:
    """The product of the ``axes`` (a mapping ``name -> values``), the first varying slowest.

    Examples
    --------
    >>> grid({"l_AB": [0.02, 0.03]}).values.ravel().tolist()
    [0.02, 0.03]
    """
    names = tuple(axes)
    if not names:
        raise SweepError("parameters", "no parameter to vary")
    vals = []
    for n in names:
        v = np.atleast_1d(np.asarray([_finite(f"parameters[{n!r}]", x)
                                      for x in np.ravel(np.asarray(axes[n], dtype=object))], float))
        if len(v) == 0:
            raise SweepError(f"parameters[{n!r}]", "no value given")
        vals.append(v)
    _fits(math.prod(len(v) for v in vals), len(names), "parameters")
    mesh = np.meshgrid(*vals, indexing="ij")
    table = np.stack([m.ravel() for m in mesh], axis=1)
    return Designs(names, table, "grid", tuple(zip(names, vals)))


def parse_axis(text: str) -> tuple[str, np.ndarray]:
    """``NAME=LO:HI:N`` (``N`` values from ``LO`` to ``HI``) or ``NAME=V1,V2,...``.

    Examples
    --------
    >>> name, v = parse_axis("l_AB=0.02:0.03:3")
    >>> name, v.tolist()
    ('l_AB', [0.02, 0.025, 0.03])
    >>> parse_axis("l_AB=0.02:0.03")
    Traceback (most recent call last):
    ...
    linkage_sym.design.errors.SweepError: parameters: 'l_AB=0.02:0.03': NAME=LO:HI:N (N values from LO to HI) or NAME=V1,V2,... is expected
    """
    form = "NAME=LO:HI:N (N values from LO to HI) or NAME=V1,V2,... is expected"
    name, sep, rest = text.partition("=")
    name = name.strip()
    if not sep or not name or not rest.strip():
        raise SweepError("parameters", f"{text!r}: {form}")
    if ":" in rest:
        parts = rest.split(":")
        if len(parts) != 3:
            raise SweepError("parameters", f"{text!r}: {form}")
        lo, hi = (_finite(f"parameters {name}", p) for p in parts[:2])
        try:
            n = int(parts[2])
        except ValueError:
            raise SweepError("parameters", f"{text!r}: N must be a whole number, got {parts[2]!r}") from None
        if n < 1:
            raise SweepError("parameters", f"{text!r}: N must be at least 1")
        _fits(n, 1, "parameters")
        return name, np.linspace(lo, hi, n)
    return name, np.array([_finite(f"parameters {name}", p) for p in rest.split(",")])


def parse_tolerance(text: str) -> tuple[str, float]:
    """``NAME=SIGMA`` of ``--tolerance`` (the standard deviation, in the parameter's unit).

    Examples
    --------
    >>> parse_tolerance("l_AB=5e-5")
    ('l_AB', 5e-05)
    """
    name, sep, rest = text.partition("=")
    if not sep or not name.strip():
        raise SweepError("tolerance", f"{text!r}: NAME=SIGMA is expected")
    sigma = _finite(f"tolerance {name.strip()}", rest)
    if sigma < 0:
        raise SweepError("tolerance", f"{text!r}: SIGMA is a standard deviation, >= 0")
    return name.strip(), sigma


def monte_carlo(base, tolerance, n: int, random_state: int = 0) -> Designs:
    """``n`` designs with every parameter of ``tolerance`` (``name -> sigma``) drawn from a
    normal distribution about its value in ``base`` (``name -> value``).

    The draws are ``numpy.random.default_rng(random_state).standard_normal((n, k))``,
    so the same ``random_state`` gives the same designs.

    Examples
    --------
    >>> d = monte_carlo({"l_AB": 0.024}, {"l_AB": 5e-5}, 4, random_state=1)
    >>> d.values.shape, bool(abs(d.values - 0.024).max() < 5e-4)
    ((4, 1), True)
    """
    if not tolerance:
        raise SweepError("tolerance", "a Monte Carlo sweep needs at least one NAME=SIGMA")
    try:
        n = int(n)
    except (TypeError, ValueError):
        raise SweepError("monte_carlo", f"a number of designs is expected, got {n!r}") from None
    if n < 1:
        raise SweepError("monte_carlo", f"at least one design is needed, got {n}")
    if not (isinstance(random_state, (int, np.integer)) and not isinstance(random_state, bool)
            and random_state >= 0):
        raise SweepError("random_state", f"a whole number >= 0 is expected, got {random_state!r}")
    names = tuple(tolerance)
    _fits(n, len(names), "monte_carlo")
    for k in names:
        if k not in base:
            raise SweepError("tolerance", f"unknown parameter {k!r}")
    mean = np.array([float(base[k]) for k in names])
    sigma = np.array([float(tolerance[k]) for k in names])
    z = np.random.default_rng(random_state).standard_normal((n, len(names)))
    with np.errstate(over="ignore"):  # a draw beyond float64 is inf: an invalid design
        values = mean + sigma * z
    return Designs(names, values, "monte-carlo")


def read_samples(path) -> Designs:
    """Designs from a CSV file: a header of parameter names, then one row of numbers per design.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> f = pathlib.Path(tempfile.mkdtemp()) / "s.csv"
    >>> _ = f.write_text("l_AB,l_BC\\n0.02,0.06\\n0.025,0.065\\n")
    >>> read_samples(f).values.tolist()
    [[0.02, 0.06], [0.025, 0.065]]
    """
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8-sig")  # a spreadsheet's byte-order mark is no name
    except OSError as err:
        raise SweepError("samples", f"{str(path)!r}: {err.strerror or err}") from None
    except UnicodeDecodeError as err:
        raise SweepError("samples", f"{str(path)!r} is not a text (UTF-8) CSV file: byte "
                                      f"{err.object[err.start]:#04x} at position {err.start}") from None
    rows = [r for r in csv.reader(text.splitlines()) if any(c.strip() for c in r)]
    if not rows:
        raise SweepError("samples", f"{str(path)!r} is empty; a header of parameter names is expected")
    names = tuple(c.strip() for c in rows[0])
    if len(set(names)) != len(names) or not all(names):
        raise SweepError("samples", f"{str(path)!r}: the header must name each parameter once")
    values = []
    for i, r in enumerate(rows[1:], start=2):
        if len(r) != len(names):
            raise SweepError("samples", f"{str(path)!r} line {i}: {len(r)} values for "
                                          f"{len(names)} parameters")
        values.append([_finite(f"samples {str(path)!r} line {i} column {names[k]!r}", c)
                       for k, c in enumerate(r)])
    if not values:
        raise SweepError("samples", f"{str(path)!r} has a header but no design")
    return Designs(names, np.array(values, float), "samples")


def check_names(designs: Designs, valid, field_name: str = "parameters") -> None:
    """Refuse names that are not design parameters of the scene, listing the valid ones."""
    valid = [n for n in valid if not n.startswith("theta0_")]
    for n in designs.names:
        if n.startswith("theta0_"):
            raise SweepError(field_name, f"{n!r} is the angle of a link in the assembly "
                                         "configuration: each design's is computed from its own "
                                         "assembly, so it cannot be varied")
        if n not in valid:
            raise SweepError(field_name, f"unknown parameter {n!r}; the scene's parameters are "
                                         f"{', '.join(valid)} ({POINTERS['parameters']})")


def _field(scene, name: str, recipe: tuple):
    """``(scene field, rule, how)`` that parameter ``name`` (its ``recipe``) fills in a
    design's scene: ``how`` is ``"length"`` (a distance, > 0 besides the field's rule),
    ``"angle"`` (radians, held in degrees to the angle rule) or ``""``."""
    from linkage_sym.scene.validate import ANGLE_RULE, MASS_RULE

    kind = recipe[0]
    links = {lk: i for i, lk in enumerate(scene.link_names)}
    joints = {j.name: i for i, j in enumerate(scene.joints)}
    xy = {"x": 0, "y": 1, "gx": 0, "gy": 1, "Fx": 0, "Fy": 1}
    if kind in ("m", "I"):
        return f"links[{links[recipe[1]]}].{'mass' if kind == 'm' else 'inertia'}", MASS_RULE, ""
    if kind in ("x", "y"):
        return f"joints[{joints[recipe[1]]}].at[{xy[kind]}]", None, ""
    if kind == "l":
        return f"joints[{joints[recipe[2]]}].at", None, "length"
    if kind in ("p", "q"):
        return f"links[{links[recipe[1]]}].com", None, ""
    if kind in ("gx", "gy"):
        return f"effects.gravity[{xy[kind]}]", None, ""
    if kind in ("Fx", "Fy"):
        return f"loads[{recipe[1]}].force[{xy[kind]}]", None, ""
    if kind in ("xi", "eta"):
        return f"loads[{recipe[1]}].at", None, ""
    if kind == "T":
        return f"loads[{recipe[1]}].torque", None, ""
    if kind == "gamma":
        return f"joints[{joints[recipe[1]]}].axis_deg", ANGLE_RULE, "angle"
    if kind in ("beta", "delta", "phi", "epsilon"):
        return f"{name} in degrees", ANGLE_RULE, "angle"
    if kind == "radius":
        return f"joints[{joints[recipe[1]]}].radius", None, "length"
    if kind in ("mu", "rpin"):  # a joint's friction (contract part two)
        field = "coefficient" if kind == "mu" else "radius"
        return (f"joints[{joints[recipe[1]]}].friction.{field}", MASS_RULE,
                "length" if kind == "rpin" else "")
    if kind in SPRING_FIELDS:  # a spring's (the contract's springs and dampers)
        from linkage_sym.scene.springs import RULE

        i = [k.name for k in scene.springs].index(recipe[1])
        field, rule, how = SPRING_FIELDS[kind]
        return f"springs[{i}].{field}", RULE if rule else None, how
    return name, None, ""


SPRING_FIELDS = {"k": ("stiffness", True, ""), "c": ("damping", True, ""),
                 "L0": ("free_length", True, ""), "theta_f": ("free_angle_deg", False, "angle"),
                 "xi_s": ("at", False, ""), "eta_s": ("at", False, "")}
"""A spring parameter's recipe tag: its field, whether the spring rule (not negative)
holds, and how it is held."""


def _problem(name: str, field: str, rule, how: str, v: float) -> str:
    """Why the value ``v`` of parameter ``name`` breaks the scene's rules ("" if it does not)."""
    from linkage_sym.scene.validate import value_problem

    problem = value_problem(field, math.degrees(v) if how == "angle" and math.isfinite(v) else v,
                            rule)
    if problem is None and how == "length" and v <= 0:
        # a distance between two joints of a link: 0 puts them at one point (the scene
        # refuses it for a driven joint's `toward`, and a link loses its direction), and the
        # closed forms would read a negative one as the same distance the other way
        problem = f"{field}: a length must be > 0 (a distance between two joints), got {v!r}"
    return "" if problem is None else f"{name}: {problem}"


def design_problems(scene, designs: Designs, recipes) -> np.ndarray:
    """Each design checked by the scene's rules: ``""`` for a design whose scene the scene
    reader would accept, else why not (the first parameter, in ``designs.names``' order,
    that breaks a rule).

    Every varied parameter is held to the rule of the scene field it fills
    (:func:`linkage_sym.scene.validate.value_problem`: a mass or inertia >= 0, every
    number finite and within 1e30 in SI units, an angle within 1e6 degrees), and a
    length (``l_*``) must be > 0 besides.  The rules are intervals, so a column whose
    least and greatest values pass passes whole; otherwise each distinct value is checked.

    ``recipes``: the parameter's recipe (:mod:`linkage_sym.structure.parameters`) by name.

    Examples
    --------
    >>> import linkage_sym
    >>> from linkage_sym.design.evaluate import Model
    >>> scene = linkage_sym.load_example("crank_rocker")
    >>> model = Model(scene, forces=True)
    >>> recipes = {model.names[i]: r for r, i in model.recipes.items()}
    >>> d = grid({"l_AB": [0.0, 0.024], "m_coupler": [-1.0, 0.5]})
    >>> for why in design_problems(scene, d, recipes).tolist():
    ...     print(repr(why))
    'l_AB: joints[1].at: a length must be > 0 (a distance between two joints), got 0.0'
    'l_AB: joints[1].at: a length must be > 0 (a distance between two joints), got 0.0'
    'm_coupler: links[1].mass: must be a finite number >= 0, got -1.0'
    ''
    """
    out = np.full(len(designs), "", dtype=object)
    for k, name in enumerate(designs.names):
        field, rule, how = _field(scene, name, recipes[name])
        col = designs.values[:, k]
        fin = col[np.isfinite(col)]
        if len(fin) == len(col) and not any(_problem(name, field, rule, how, float(x))
                                            for x in (fin.min(), fin.max())):
            continue
        values, which = np.unique(col, return_inverse=True)
        why = np.array([_problem(name, field, rule, how, float(x)) for x in values], dtype=object)
        here = why[which.ravel()]
        fill = (out == "") & (here != "")
        out[fill] = here[fill]
    return out.astype(str)


def refuse_invalid(scene, designs: Designs, recipes, problems: np.ndarray,
                   field_name: str) -> None:
    """Refuse designs of which none is valid (``problems`` from :func:`design_problems`):
    a grid axis none of whose values is valid is named with the first value's problem,
    otherwise the first design's problem is given."""
    if (problems == "").any():
        return
    for name, values in designs.axes:
        field, rule, how = _field(scene, name, recipes[name])
        why = [_problem(name, field, rule, how, float(v)) for v in values]
        if all(why):
            raise SweepError(field_name, f"no value of {name} gives a valid design: {why[0]}")
    raise SweepError(field_name, f"none of the {len(problems)} designs is valid; design 0: "
                                 f"{problems[0]}")


def parameter_list(scene, names, values) -> list[tuple[str, float, str]]:
    """``(name, value, meaning)`` of every design parameter of the compiled ``scene``
    (``names``, ``values``: the compiled mechanism's), the assembly angles left out."""
    from linkage_sym.structure.parameters import ParameterTable

    table = ParameterTable(scene)
    out = []
    for name, value in zip(names, values):
        if name.startswith("theta0_"):
            continue
        out.append((name, float(value), _meaning(table, name)))
    return out


def _meaning(table, name: str) -> str:
    """The meaning the symbolic layer gives ``name`` (registered through its recipe)."""
    scene = table.scene
    kind, _, rest = name.partition("_")
    try:
        if kind in ("l", "beta"):
            for link in scene.link_names:
                for j in scene.joints:
                    if link in j.links:
                        table.point(link, j.name)
        elif kind in ("x", "y"):
            for j in scene.joints:
                if "ground" in j.links:
                    table.ground_point(j.name)
        elif kind == "gamma":
            for j in scene.joints:
                if j.type == "P":
                    table.gamma(j.name)
        elif kind == "delta":
            for d in scene.drivers:
                if d.toward is not None:
                    table.delta(d.joint, d.toward)
        elif kind in ("m", "I"):
            for link in scene.link_names:
                table.mass(link)
        elif kind in ("xG", "yG"):
            for link in scene.links:
                if link.com is not None:
                    table.com(link.name)
        elif kind == "g":
            table.gravity()
        elif kind in ("mu", "rpin"):  # a joint's friction: its coefficient, a pin's radius
            for j in scene.joints:
                if j.friction is not None and j.type in ("R", "P"):
                    table.friction(j.name)
        else:
            for i in range(len(scene.loads)):
                table.load(i)
            for k in scene.springs:  # the contract's springs: k_, c_, L0_, theta_f_, xi_, eta_
                table.spring(k.name)
    except (KeyError, ValueError, TypeError):
        pass
    p = table.params.get(name)
    return p.meaning if p is not None else ""
