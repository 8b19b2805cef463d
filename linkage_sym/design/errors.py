"""The error every part of a design sweep raises for input it cannot use."""

from __future__ import annotations

__all__ = ["SweepError"]


class SweepError(ValueError):
    """A sweep's input that cannot be used: ``field`` names the argument of
    :func:`~linkage_sym.design.sweep` or the attribute of its ``MonteCarlo``, ``SceneFiles``
    or ``Execution`` (``parameters``, ``metrics``, ``tolerance``, ``rows``, ``workers`` ...),
    ``reason`` says why; the command line names its option for it.

    Examples
    --------
    >>> str(SweepError("metrics", "unknown metric 'Kk'"))
    "metrics: unknown metric 'Kk'"
    """

    def __init__(self, field: str, reason: str):
        self.field = field
        self.reason = reason
        super().__init__(f"{field}: {reason}")
