"""The symbolic layer (SymPy only): a mechanism's equations, derived.

See :func:`linkage_sym.symbolic.mechanism.derive`.
"""

from linkage_sym.symbolic.mechanism import GroupEquations, MechanismEquations, derive

__all__ = ["GroupEquations", "MechanismEquations", "derive"]
