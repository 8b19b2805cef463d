"""Reproductions of the sources (paper_repro/) and the notebooks (notebooks/)."""
