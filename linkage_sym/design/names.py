"""The names of the metrics a sweep computes (defined in :mod:`linkage_sym.design.metrics`).

Apart, and importing nothing, so that ``linkage-sym sweep --help`` lists them
without loading the sweep's machinery (NumPy, the compiled mechanism).
"""

__all__ = ["DEFAULT_METRICS", "METRICS"]

METRICS = ("assemblable", "grashof", "K", "swing", "min_transmission_deg", "peak_driving",
           "rms_driving", "peak_reaction", "rms_shaking_force", "rms_shaking_moment", "path")
"""Every metric a sweep computes (see the module docstring)."""

DEFAULT_METRICS = ("assemblable", "grashof", "K", "swing", "min_transmission_deg")
