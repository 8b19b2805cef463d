"""Strict JSON: the values of a result that are not finite are left out, and named.

Any value that is not finite (a NaN or an infinity that a solver let through)
is left out of a step's record (:func:`finite_only`), and a ``warnings`` entry
of the result says how many and where (:class:`LeftOut`);
:meth:`~linkage_sym.numeric.results.result.Analysis.to_json` writes with
``allow_nan=False``.
"""

from __future__ import annotations

import math


class LeftOut:
    """Values left out of a result because they are not finite: how many, and the first paths."""

    SHOWN = 3

    def __init__(self):
        self.count = 0
        self.paths: list[str] = []

    def append(self, path: str) -> None:
        self.count += 1
        if len(self.paths) < self.SHOWN:
            self.paths.append(path)

    def warning(self) -> str:
        """The sentence added to the result's ``warnings``."""
        n = self.count
        shown = ", ".join(self.paths) + (f" and {n - self.SHOWN} more" if n > self.SHOWN else "")
        return (
            f"{n} computed value{'s are' if n != 1 else ' is'} not finite "
            f"(NaN or infinite) and left out of the result: {shown}"
        )


LEFT_OUT = object()
"""What :func:`finite_only` returns for a value that is left out."""


def finite_only(value, path: str, dropped: list):
    """``value`` (a step record) without its non-finite numbers; their paths go to ``dropped``.

    A vector ``[x, y]`` with a non-finite component is left out whole; a record
    keeps its other fields.
    """
    if isinstance(value, float):
        if math.isfinite(value):
            return value
        dropped.append(path)
        return LEFT_OUT
    if isinstance(value, dict):
        out = {}
        for key, item in value.items():
            kept = finite_only(item, f"{path}.{key}", dropped)
            if kept is not LEFT_OUT:
                out[key] = kept
        return out
    if isinstance(value, list):
        if all(isinstance(x, float) and math.isfinite(x) for x in value):
            return value
        if all(isinstance(x, (float, int)) for x in value):  # a vector: whole or not at all
            dropped.append(path)
            return LEFT_OUT
        return [x for x in (finite_only(x, f"{path}[{k}]", dropped) for k, x in enumerate(value))
                if x is not LEFT_OUT]
    return value
