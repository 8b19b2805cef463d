"""Balancing of hinged linkages (Song and Wang 1992 and its reference [1]).

Modules
-------
module
    The mass/acceleration-parameter module of one link (SymPy).
assembly
    The module summed over a mechanism's links: the shaking moment (SymPy).
force
    Shaking force balance conditions by linearly independent vectors (SymPy).
optimize
    Counterweights and partial balancing by optimisation (NumPy/SciPy only).
"""
