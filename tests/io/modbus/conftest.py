"""Fixtures of the Modbus tests: plants with the master and simulated drives (plant.py)."""

from .plant import plants  # noqa: F401
