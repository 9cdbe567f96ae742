"""Numerics: Gauss-Chebyshev rules, kernel moments, the edge-graded map, caches, extrema."""
