"""Gallery demos of the source texts' systems, run by ``pendula demo``."""
