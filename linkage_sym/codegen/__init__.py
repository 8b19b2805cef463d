"""Code generation: lambdified NumPy functions of the derived equations, cached.

:func:`linkage_sym.codegen.compile.compile_mechanism` (needs SymPy) derives and
generates, or loads from the cache; :mod:`linkage_sym.codegen.runtime` and
:mod:`linkage_sym.codegen.cache` run and store compiled mechanisms with NumPy
only.
"""
