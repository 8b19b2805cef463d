"""Reading the fields of a JSON mapping, collecting every problem (no model here).

:class:`FieldReader` checks one field at a time -- a key, a name, a number
within its limits, an integer, a boolean, a point -- and records each problem
as ``"field.path: reason"`` instead of raising, so a whole document is read in
one pass; :mod:`linkage_sym.scene.validate` builds the scene reader on it, and
any later section of the format (gear meshes, cam contacts, load tables) reads
its fields with the same checks and wording.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterator, Mapping
from typing import Any

from linkage_sym.model.scene import Point

MAX_MAGNITUDE = 1e30
"""Largest magnitude of any number of a scene, in SI units.

A coordinate (m), a mass, an inertia, a force, a torque, a driver's speed or
acceleration, a gravity component: the solver multiplies such quantities.  It
squares lengths in its closed forms, and its largest products -- the moment
about the origin of a d'Alembert force, a coordinate times a mass times a speed
squared times a length, divided by a determinant of two lengths -- have fewer
than ten factors.  With every factor within 1e30 (and lengths no smaller than
:data:`MIN_SIZE`), every product stays within 1e300, inside the range of a
float64 (1.8e308): no overflow, no ``inf`` or ``NaN`` in a result.
"""

MAX_ANGLE_DEG = 1e6
"""Largest magnitude of an angle in degrees (float64 resolves it to 1e-10 degree)."""

_MAGNITUDE_WHY = (
    f"must be within +-{MAX_MAGNITUDE:.0e} (SI units): the solver multiplies up to ten such "
    "quantities (e.g. a coordinate x a mass x a speed^2 x a length) and every product must stay "
    "within the float64 range 1.8e308"
)
ANGLE_WHY = (
    f"an angle must be within +-{MAX_ANGLE_DEG:.0e} degrees (float64 resolves such an angle "
    "to 1e-10 degree; beyond, the direction it gives is lost)"
)

ANGLE = {"limit": MAX_ANGLE_DEG, "limit_why": ANGLE_WHY}
"""Keyword arguments of :meth:`FieldReader.number` for an angle in degrees."""

REQUIRED = object()
"""Default marking a key that must be present."""

POINT_EXPECTED = "an array of 2 finite numbers [x, y]"
"""What a point's field must hold, as a problem says it."""



class FieldReader:
    """Reads fields, collecting every problem on the way (see the module docstring)."""

    def __init__(self) -> None:
        self.problems: list[str] = []
        self.positions: list[tuple[str, Point]] = []  # every valid point read, with its path

    def add(self, path: str, reason: str) -> None:
        self.problems.append(f"{path}: {reason}")

    def keys(self, obj: Mapping[str, Any], path: str, allowed: tuple[str, ...]) -> None:
        for key in obj:
            if key not in allowed:
                where = _join(path, str(key))
                self.add(where, f"unknown key{did_you_mean(str(key), allowed)}")

    def forbid(self, obj: Mapping[str, Any], path: str, keys: tuple[str, ...], where: str) -> None:
        for key in keys:
            if key in obj:
                self.add(_join(path, key), f"not allowed {where}")

    def missing(self, path: str, why: str = "") -> None:
        self.add(path, "required key is missing" + (f" ({why})" if why else ""))

    def present(self, obj: Mapping[str, Any], key: str, path: str, default: Any, why: str) -> bool:
        """Whether ``key`` is there to be read; reports it if required and missing."""
        if key in obj:
            return True
        if default is REQUIRED:
            self.missing(_join(path, key), why)
        return False

    def object(self, value: Any, path: str) -> bool:
        if isinstance(value, Mapping):
            return True
        self.add(path, f"must be an object, got {json_kind(value)}")
        return False

    def array(self, obj: Mapping[str, Any], key: str, path: str) -> list[Any] | None:
        if not self.present(obj, key, path, REQUIRED, ""):
            return None
        value = obj[key]
        if isinstance(value, (list, tuple)):
            return list(value)
        self.add(_join(path, key), f"must be an array, got {json_kind(value)}")
        return None

    def named_entries(
        self, data: Mapping[str, Any], section: str, allowed: tuple[str, ...], noun: str,
        *, taken: Mapping[str, str] | None = None,
    ) -> Iterator[tuple[str, Mapping[str, Any], str | None, int]]:
        """Each object entry of the optional array ``data[section]`` whose entries are named
        (``springs``, ``points``): ``(path, entry, name, before)``.

        Checked here, each problem recorded: the section is an array, each entry an object
        with only the ``allowed`` keys, its ``name`` a name unique in the section and not one
        of ``taken`` (a name another section owns, mapped to where it stands).  ``before``
        is the count of problems before the entry, so the caller keeps the entry only if its
        own checks add none.

        Examples
        --------
        >>> r = FieldReader()
        >>> data = {"points": [{"name": "P"}, {"name": "P"}, 3, {"name": "B"}]}
        >>> [(path, name) for path, _, name, _ in
        ...  r.named_entries(data, "points", ("name",), "point", taken={"B": "joints[1]"})]
        [('points[0]', 'P'), ('points[1]', 'P'), ('points[3]', 'B')]
        >>> r.problems  # doctest: +NORMALIZE_WHITESPACE
        ["points[1].name: duplicate point name 'P' (first at points[0])",
         'points[2]: must be an object, got a number',
         "points[3].name: 'B' already names joints[1]; a point needs its own name"]
        """
        if section not in data:
            return
        entries = self.array(data, section, "")
        if entries is None:
            return
        seen: dict[str, int] = {}
        for i, entry in enumerate(entries):
            path = f"{section}[{i}]"
            before = len(self.problems)
            if not self.object(entry, path):
                continue
            self.keys(entry, path, allowed)
            name = self.name(entry, "name", path)
            if name in seen:
                self.add(f"{path}.name",
                         f"duplicate {noun} name '{name}' (first at {section}[{seen[name]}])")
            elif name is not None and taken is not None and name in taken:
                self.add(f"{path}.name",
                         f"'{name}' already names {taken[name]}; a {noun} needs its own name")
            elif name is not None:
                seen[name] = i
            yield path, entry, name, before

    def name(self, obj: Mapping[str, Any], key: str, path: str, *, why: str = "") -> str | None:
        if not self.present(obj, key, path, REQUIRED, why):
            return None
        value = obj[key]
        if isinstance(value, str) and value:
            return value
        self.add(_join(path, key), f"must be a non-empty string, got {show_value(value)}")
        return None

    def number(
        self,
        obj: Mapping[str, Any],
        key: str,
        path: str,
        *,
        default: Any = REQUIRED,
        minimum: float | None = None,
        why: str = "",
        limit: float = MAX_MAGNITUDE,
        limit_why: str = _MAGNITUDE_WHY,
    ) -> float | None:
        if not self.present(obj, key, path, default, why):
            return None if default is REQUIRED else default
        value = obj[key]
        number = _finite(value)
        if number is None or (minimum is not None and number < minimum):
            bound = "" if minimum is None else f" >= {minimum:g}"
            self.add(_join(path, key), f"must be a finite number{bound}, got {show_value(value)}")
            return None
        if abs(number) > limit:
            self.add(_join(path, key), f"{limit_why}, got {show_value(value)}")
            return None
        return number

    def numbers(
        self,
        obj: Mapping[str, Any],
        key: str,
        path: str,
        *,
        length: int | None = None,
        min_length: int = 1,
        angle: bool = False,
    ) -> list[float] | None:
        """An array of finite numbers (``angle``: degrees, within their limit)."""
        values = self.array(obj, key, path)
        if values is None:
            return None
        where = _join(path, key)
        if length is not None and len(values) != length:
            self.add(where, f"must be an array of {length} numbers, got {len(values)}")
            return None
        if len(values) < min_length:
            self.add(where, f"must have at least {min_length} numbers, got {len(values)}")
            return None
        limit, why = (MAX_ANGLE_DEG, ANGLE_WHY) if angle else (MAX_MAGNITUDE, _MAGNITUDE_WHY)
        out, ok = [], True
        for i, v in enumerate(values):
            x = _finite(v)
            if x is None:
                self.add(f"{where}[{i}]", f"must be a finite number, got {show_value(v)}")
                ok = False
            elif abs(x) > limit:
                self.add(f"{where}[{i}]", f"{why}, got {show_value(v)}")
                ok = False
            else:
                out.append(x)
        return out if ok else None

    def integer(self, obj: Mapping[str, Any], key: str, path: str, *, minimum: int) -> int | None:
        if not self.present(obj, key, path, REQUIRED, ""):
            return None
        value = obj[key]
        if isinstance(value, int) and not isinstance(value, bool) and value >= minimum:
            return value
        self.add(_join(path, key), f"must be an integer >= {minimum}, got {show_value(value)}")
        return None

    def boolean(self, obj: Mapping[str, Any], key: str, path: str, *, default: bool) -> bool | None:
        if key not in obj:
            return default
        value = obj[key]
        if isinstance(value, bool):
            return value
        self.add(_join(path, key), f"must be true or false, got {show_value(value)}")
        return None

    def point(
        self,
        obj: Mapping[str, Any],
        key: str,
        path: str,
        *,
        default: Any = REQUIRED,
        expected: str = POINT_EXPECTED,
        position: bool = False,
    ) -> Point | None:
        """A point ``[x, y]``; ``position``: a point fixed on a link (checked against the size)."""
        if not self.present(obj, key, path, default, ""):
            return None if default is REQUIRED else default
        value = obj[key]
        field = _join(path, key)
        if not isinstance(value, (list, tuple)) or len(value) != 2:
            self.add(field, f"must be {expected}, got {show_value(value)}")
            return None
        x, y = (_finite(c) for c in value)
        for i, (given, number) in enumerate(zip(value, (x, y))):
            if number is None:
                self.add(f"{field}[{i}]", f"must be a finite number, got {show_value(given)}")
            elif abs(number) > MAX_MAGNITUDE:
                self.add(f"{field}[{i}]", f"{_MAGNITUDE_WHY}, got {show_value(given)}")
                x = y = None
        if x is None or y is None:
            return None
        if position:
            self.positions.append((field, (x, y)))
        return (x, y)


def _finite(value: Any) -> float | None:
    """``value`` as a float if it is a finite int or float (not a bool), else ``None``."""
    if not isinstance(value, (int, float)) or isinstance(value, bool):
        return None
    try:
        number = float(value)
    except OverflowError:
        return None
    return number if math.isfinite(number) else None


def radians_or_none(degrees: float | None) -> float | None:
    """``degrees`` in radians; ``None`` (a field that was missing or refused) stays ``None``.

    Examples
    --------
    >>> radians_or_none(180.0) == math.pi, radians_or_none(None)
    (True, None)
    """
    return None if degrees is None else math.radians(degrees)


def _join(path: str, key: str) -> str:
    return f"{path}.{key}" if path else key


def json_kind(value: Any) -> str:
    """The JSON type name of a value, for messages.

    Examples
    --------
    >>> json_kind(True), json_kind(2.5), json_kind({"a": 1}), json_kind(None)
    ('a boolean', 'a number', 'an object', 'null')
    """
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, (int, float)):
        return "a number"
    if isinstance(value, str):
        return "a string"
    if isinstance(value, Mapping):
        return "an object"
    if isinstance(value, (list, tuple)):
        return "an array"
    return type(value).__name__


def show_value(value: Any, limit: int = 40) -> str:
    """A short JSON rendering of a value, for messages (at most ``limit`` characters).

    Examples
    --------
    >>> show_value([1, 2]), show_value("x" * 50, limit=10)
    ('[1, 2]', '"xxxxxx...')
    """
    try:
        text = json.dumps(value)
    except (TypeError, ValueError):
        text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def did_you_mean(word: str, choices: Any) -> str:
    """`` (did you mean 'x'?)`` for the closest of ``choices``, or ``""``.

    Examples
    --------
    >>> did_you_mean("crnk", ["crank", "rocker"]), did_you_mean("zzz", ["crank"])
    (" (did you mean 'crank'?)", '')
    """
    import difflib  # only for a refusal's suggestion

    match = difflib.get_close_matches(word, [str(c) for c in choices], n=1)
    return f" (did you mean '{match[0]}'?)" if match else ""
