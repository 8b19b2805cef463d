"""The error every part of a design sweep raises for input it cannot use."""

from __future__ import annotations

__all__ = ["SweepError"]


class SweepError(ValueError):
    """A sweep's input that cannot be used: ``field`` names the argument or option
    (``parameters``, ``metrics``, ``tolerance`` ...), ``reason`` says why.

    Examples
    --------
    >>> str(SweepError("metrics", "unknown metric 'Kk'"))
    "metrics: unknown metric 'Kk'"
    """

    def __init__(self, field: str, reason: str):
        self.field = field
        self.reason = reason
        super().__init__(f"{field}: {reason}")
