"""Files: written whole (temporary name, then rename), output paths checked first, tables."""
