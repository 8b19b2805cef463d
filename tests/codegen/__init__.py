"""Compiled mechanisms: the cache and the arbitrary-precision run."""
