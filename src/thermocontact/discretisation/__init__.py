"""Discretisation: representations of the unknowns, the operators of (D14) and (D18), methods."""
