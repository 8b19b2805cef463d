"""The symbolic layer: derivation, compiled functions, LaTeX."""
