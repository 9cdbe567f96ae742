"""Solvers: the linear system, the refinement driver, Model and solve(), results."""
