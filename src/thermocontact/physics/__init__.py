"""Physics: Green's functions of both bodies and reference solutions (Hertz, Barber)."""
