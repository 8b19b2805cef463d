"""Exceptions shared by every layer of linkage_sym."""

from __future__ import annotations

import math


class SceneError(ValueError):
    """A scene that cannot be analysed.

    Carries every problem found, each as ``"field: reason"``, so that a user
    sees all of them at once instead of fixing one per run.

    Examples
    --------
    >>> err = SceneError(["links[0].mass: must be >= 0, got -1"])
    >>> err.problems
    ['links[0].mass: must be >= 0, got -1']
    >>> print(err)
    invalid scene (1 problem):
      links[0].mass: must be >= 0, got -1
    """

    def __init__(self, problems: list[str]):
        self.problems = list(problems)
        n = len(self.problems)
        head = f"invalid scene ({n} problem{'s' if n != 1 else ''}):"
        super().__init__("\n  ".join([head, *self.problems]))


class BalanceError(ValueError):
    """A balancing request that cannot be met (e.g. conditions that no
    counterweights on the given links satisfy); ``field``, when given, names the
    parameter of the request that could not be met (``optimize``).

    Examples
    --------
    >>> print(BalanceError("counterweights on crank only cannot balance the force"))
    cannot balance: counterweights on crank only cannot balance the force
    >>> print(BalanceError("no step could be assembled", field="optimize"))
    cannot balance: optimize: no step could be assembled
    """

    def __init__(self, reason: str, field: str | None = None):
        self.reason = reason
        self.field = field
        super().__init__(f"cannot balance: {field + ': ' if field else ''}{reason}")


POINTERS = {
    "parameters": "linkage_sym.design.scene_parameters(scene) lists them with their values",
    "analyze": "linkage_sym.analyze solves one design",
    "builders": "linkage_sym.synthesis.builders",
    "disconnections": "linkage_sym.structure.structure_report lists them",
}
"""Where a message sends its reader for more, as the library's user gets there (a function
to call), by topic.  Messages use these texts whole, so that the command line can put its
own command for each (``linkage_sym.cli.common.COMMAND_POINTERS``)."""


def finite_number(field: str, value, error: type) -> float:
    """``value`` as a finite float, else ``error(field, reason)``.

    One rule for every number a user types or passes (synthesis requests,
    design parameters and options): a bool is not a number, a string is read
    as ``float`` reads it, NaN and infinities are refused.

    Examples
    --------
    >>> class E(ValueError):
    ...     def __init__(self, field, reason):
    ...         super().__init__(f"{field}: {reason}")
    >>> finite_number("l_AB", "0.05", E)
    0.05
    >>> finite_number("l_AB", True, E)
    Traceback (most recent call last):
    ...
    linkage_sym.errors.E: l_AB: a finite number is expected, got True
    """
    if isinstance(value, bool):
        raise error(field, f"a finite number is expected, got {value!r}")
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise error(field, f"a finite number is expected, got {value!r}") from None
    if not math.isfinite(x):
        raise error(field, f"a finite number is expected, got {value!r}")
    return x


SYMBOLIC_LACKS = {"cam": "cam contacts"}
"""Joint types the symbolic layer does not derive yet, with their plural names."""
FRICTION = "friction"
"""What :class:`SymbolicUnsupportedError` names for a joint whose friction acts (``joints[i].friction``
with ``effects.friction``): the symbolic layer does not derive friction yet."""


class SymbolicUnsupportedError(SceneError):
    """Joints of a scene that the symbolic layer does not derive yet (:data:`SYMBOLIC_LACKS`).

    ``joints``: ``(index, name, type)`` of each; ``field``: the argument that picks a
    method that does support them (``method`` of :func:`linkage_sym.analyze`).  The
    problems name it as the library takes it; :meth:`problems_naming` words them with
    another name for that choice (the command line's option).

    Examples
    --------
    >>> err = SymbolicUnsupportedError([(1, "K", "cam")])
    >>> err.problems
    ["joints[1]: the symbolic method does not support cam contacts yet (joint 'K' is of type cam); the numeric methods do (method 'dyad' or 'global')"]
    >>> err.problems_naming("another method")[0][-19:]
    'do (another method)'
    """

    field = "method"

    def __init__(self, joints):
        self.joints = [tuple(j) for j in joints]
        super().__init__(self.problems_naming(f"{self.field} 'dyad' or 'global'"))

    def problems_naming(self, choice: str) -> list[str]:
        """The problems, ``choice`` saying how to pick a numeric method."""
        return [f"joints[{i}].friction: the symbolic method does not derive joint friction yet "
                f"(joint '{name}', with effects.friction true); the numeric methods do ({choice})"
                if t == FRICTION else
                f"joints[{i}]: the symbolic method does not support {SYMBOLIC_LACKS[t]} yet "
                f"(joint '{name}' is of type {t}); the numeric methods do ({choice})"
                for i, name, t in self.joints]


def refuse_symbolic_unsupported(scene, friction_derived: bool = False) -> None:
    """Raise :class:`SymbolicUnsupportedError` if ``scene`` has joints the symbolic layer
    does not derive.

    The symbolic method (derived equations, their compiled and arbitrary-precision
    runs, and what builds on them: LaTeX, balancing conditions, design sweeps)
    does not support cam contacts yet (issue 20); the numeric methods do.  Joint friction
    (issue 29: a joint's ``friction`` when ``effects.friction`` is true) is refused only
    where a caller does not write its terms out: :func:`linkage_sym.symbolic.derive` does,
    and the compiled runtime solves its laws (:mod:`linkage_sym.codegen.friction`).
    Every such joint is named (springs and dampers are derived:
    :mod:`linkage_sym.symbolic.springs`).
    ``friction_derived``: the caller writes the friction's terms out
    (:func:`linkage_sym.symbolic.derive`), so friction is not refused.

    Examples
    --------
    >>> from types import SimpleNamespace as NS
    >>> still = NS(friction=False)  # the scene's effects: no joint friction
    >>> refuse_symbolic_unsupported(NS(joints=[NS(name="A", type="R"), NS(name="M", type="G")],
    ...                                effects=still))
    >>> refuse_symbolic_unsupported(NS(joints=[NS(name="A", type="R"), NS(name="K", type="cam")],
    ...                                effects=still))
    Traceback (most recent call last):
    ...
    linkage_sym.errors.SymbolicUnsupportedError: invalid scene (1 problem):
      joints[1]: the symbolic method does not support cam contacts yet (joint 'K' is of type cam); the numeric methods do (method 'dyad' or 'global')
    >>> pin = NS(name="B", type="R", friction=NS(coefficient=0.1))
    >>> refuse_symbolic_unsupported(NS(joints=[pin], effects=NS(friction=True)))
    Traceback (most recent call last):
    ...
    linkage_sym.errors.SymbolicUnsupportedError: invalid scene (1 problem):
      joints[0].friction: the symbolic method does not derive joint friction yet (joint 'B', with effects.friction true); the numeric methods do (method 'dyad' or 'global')
    """
    joints = [(i, j.name, j.type) for i, j in enumerate(scene.joints) if j.type in SYMBOLIC_LACKS]
    if scene.effects.friction and not friction_derived:  # contract part two: numeric solvers
        joints += [(i, j.name, FRICTION) for i, j in enumerate(scene.joints)
                   if j.friction is not None and j.friction.coefficient > 0]
    if joints:
        raise SymbolicUnsupportedError(joints)
