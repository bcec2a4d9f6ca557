"""Gallery demos of the seed systems, run by ``pendula demo``."""
