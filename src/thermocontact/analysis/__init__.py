"""Analysis of a solution: the gap and contact inequalities, and the theory's applicability."""
