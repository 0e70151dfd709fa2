"""Writers for verified tool paths. Every write is atomic (see :mod:`.atomic`)."""
