"""Instant centres: Kennedy's construction, the velocity method, polygons, the output."""
