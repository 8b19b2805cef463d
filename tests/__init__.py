"""The test suite, one package per folder of ``linkage_sym`` (plus ``paper``, ``project`` and
``support``).

Every folder is a package (it has an ``__init__.py``), so pytest imports each test module by its
dotted name from the repository root (``tests.numeric.test_extremes``): two folders may hold
files of the same name, and the shared helpers import as ``tests.support.scenes`` however pytest
is started (from the root, with one file's path, or in pytest-xdist workers), without touching
``sys.path``.
"""
