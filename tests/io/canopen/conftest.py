"""Fixtures of the CANopen tests: a bench for simulated devices (bench.py),
the generic slave on it (slaves.py) and plants with the master (plant.py)."""

from .bench import bench  # noqa: F401
from .plant import plants  # noqa: F401
from .slaves import slave  # noqa: F401
