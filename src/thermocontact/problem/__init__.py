"""The problem statement: dimensionless parameters, validation, materials and units."""
