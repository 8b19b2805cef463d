"""The JSON of a simulation's result, shared by the one-motor and the several-motor results:
the analysis's layout of the contract with each step's ``time``, then the integrator, the
motion and, where the integration ended early, why."""

from __future__ import annotations

import json

__all__ = ["SimulationJSON"]


class SimulationJSON:
    """What a simulation result (``analysis``, ``time``, ``trajectory``, ``motion`` and
    ``message`` attributes) writes as JSON."""

    def to_dict(self) -> dict:
        """The result in the contract's JSON layout."""
        base = self.analysis.to_dict()
        steps = [{"time": float(t), **record} for t, record in zip(self.time, base["steps"])]
        extra = {"integrator": self.trajectory.integrator(), "motion": self.motion}
        if self.message is not None:
            extra["end"] = self.message
        return {**{k: v for k, v in base.items() if k != "steps"}, "steps": steps, **extra}

    def to_json(self, **kwargs) -> str:
        """:meth:`to_dict` as strict JSON text."""
        return json.dumps(self.to_dict(), **{**kwargs, "allow_nan": False})
