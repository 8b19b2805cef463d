"""Code generation: the derived equations printed as functions, cached, and one evaluator.

:func:`linkage_sym.codegen.compile.compile_mechanism` (needs SymPy) derives and
generates, or loads from the cache; everything else here runs compiled mechanisms
without SymPy.

- ``compile``: the derived equations printed as NumPy (or mpmath, or JavaScript) functions (SymPy's
  ``cse`` and printers), with a fixed argument order written into each docstring;
- ``artifact``: what the generator wrote, as records (steps, groups, force blocks,
  parameter recipes, the generated sources); the JSON only at the cache's edge;
- ``cache``: the artifacts on disk and in memory, keyed on the topology, the
  generator's source and SymPy's version;
- ``evaluator``: the one evaluator of the generated functions -- the calls, the walk
  over the position steps, the block solves, the force blocks, the loads, the
  reactions -- with named hooks a backend fills in; its NumPy backend;
- ``blocks``: the rate matrix kept as its generated entries, solved block by block;
- ``runtime``: :class:`~linkage_sym.codegen.runtime.CompiledMechanism`, the NumPy
  backend run over a scene's sweep (the solving path and its continuation, the
  singularity screen, the result; the bookkeeping the numeric plan shares:
  :mod:`linkage_sym.numeric.engine`); ``parallels`` its dyads of two slides along the
  path (parallel slides, a joint passing through infinity);
- ``precision``: the mpmath backend, at any precision (``--precision``);
- ``javascript``: the JavaScript backend (``evaluator.js``: the walk, Newton's
  continuation, the statuses and the recipes of joint positions, in a browser), written
  into the page of :mod:`linkage_sym.page` (``linkage-sym view``).

The batched-designs backend is :class:`linkage_sym.design.evaluate.Model`.
"""
