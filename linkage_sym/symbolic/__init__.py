"""The symbolic layer (SymPy only): a mechanism's equations, derived.

See :func:`linkage_sym.symbolic.mechanism.derive`.  Modules: ``vectors``
(the complex link vectors of the loops), ``mechanism`` (loops, closed forms,
rate matrices, points, force blocks), ``latex`` (the equations typeset).
"""

from linkage_sym.symbolic.mechanism import GroupEquations, MechanismEquations, derive

__all__ = ["GroupEquations", "MechanismEquations", "derive"]
