"""Balancing: Song and Wang's module, counterweights, partial balancing."""
