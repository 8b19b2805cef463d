"""Design sweeps: the API, parallel runs, linkage-sym sweep, its pictures."""
