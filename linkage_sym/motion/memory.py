"""The memory a simulation's result takes, checked before the run (``simulate.samples``)."""

from __future__ import annotations

from linkage_sym.errors import SceneError

__all__ = ["check_memory"]


def check_memory(plan, samples: int) -> None:
    """Refuse ``simulate.samples`` the result of which would not fit in memory."""
    from linkage_sym.numeric.engine.block import WARM_FACTOR
    from linkage_sym.numeric.engine.heap import available_memory, gib

    need = int(WARM_FACTOR["numeric"][1] * 8 * plan.layout.n_rows * samples)
    available = available_memory() if need > 2**28 else None
    if available is not None and need > available:
        raise SceneError([f"simulate.samples: {samples} samples do not fit in memory: their "
                          f"analysis takes about {gib(need)} and this process can take "
                          f"{gib(available)} more; give fewer samples"])
