"""Pictures (matplotlib, imported inside the functions)."""
