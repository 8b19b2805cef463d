"""The one sweep engine both runtimes call (the numeric plan and :mod:`linkage_sym.codegen.runtime`).

``run`` (a run's bookkeeping: the scene's sweep, stages, solving path and
unwrapping, step statuses, the singularity decision and its message, the
``Analysis``, what every run adds -- warnings, transmission angles, instant
centres -- and the accuracy calibration), ``block`` (the result block and its records), ``heap`` (the
allocator's state and the memory a run may take).  It imports neither runtime.
"""
