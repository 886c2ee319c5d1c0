"""softplc's runtime: the ST compiler, the scan engine, the buses and devices."""

#: the distribution's version (pyproject.toml takes it from here); part of every cache key
__version__ = "0.1.0"
