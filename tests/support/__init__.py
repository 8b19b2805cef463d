"""Helpers shared by the tests: independent references, scene builders, checks."""
