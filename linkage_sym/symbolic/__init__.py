"""The symbolic layer (SymPy only): a mechanism's equations, derived.

See :func:`linkage_sym.symbolic.mechanism.derive`.  Modules: ``vectors``
(the complex link vectors of the loops), ``mechanism`` (loops, gear meshes,
rate matrices, points: :class:`MechanismEquations`, which inherits
``closed_forms``, the explicit positions of inputs, gears and dyads, and
``forces``, the links' equilibrium, the groups' force blocks and the frame
loads), ``tangent`` (the dyads' square root, whose tangency rounding may
miss: the generated code takes it as the numeric solver does), ``latex`` (the
equations typeset).
"""

from linkage_sym.symbolic.mechanism import GroupEquations, MechanismEquations, derive

__all__ = ["GroupEquations", "MechanismEquations", "derive"]
