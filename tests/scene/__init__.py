"""Scenes: loading, validation, the JSON Schema, mutations, traced points, the shipped examples."""
