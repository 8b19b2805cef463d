"""Synthesis: builders, K ratio, coupler positions, design equations, new/synthesize."""
