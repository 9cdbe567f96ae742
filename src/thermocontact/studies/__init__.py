"""Studies: sweeps with their validity boundaries, and the problem in physical units."""
