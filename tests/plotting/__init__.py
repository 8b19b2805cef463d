"""The plotting layer: readable PNGs of motion, forces, balancing, instant centres."""
