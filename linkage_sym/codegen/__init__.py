"""Code generation: lambdified NumPy functions of the derived equations, cached.

:func:`linkage_sym.codegen.compile.compile_mechanism` (needs SymPy) derives and
generates, or loads from the cache; :mod:`linkage_sym.codegen.runtime` and
:mod:`linkage_sym.codegen.cache` run and store compiled mechanisms with NumPy
only.

- ``compile``: the derived equations printed as NumPy functions (SymPy's
  ``cse`` and ``NumPyPrinter``), with a fixed argument order written into
  each docstring;
- ``cache``: the artifacts on disk and in memory, keyed on the topology, the
  generator's source and SymPy's version;
- ``runtime``: :class:`~linkage_sym.codegen.runtime.CompiledMechanism` runs
  the functions over a sweep, through the sweep engine the numeric plan
  uses (:mod:`linkage_sym.numeric.engine.run`, :mod:`linkage_sym.numeric.engine.block`,
  :mod:`linkage_sym.numeric.continuation`);
- ``precision``: the same functions at mpmath precision (``--precision``).
"""
