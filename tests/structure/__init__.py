"""Structural analysis: mobility, Assur groups, disconnections, Grashof."""
