"""The FC 280 on the CANopen benches and plants (tests/io/canopen)."""

from ...io.canopen.bench import bench  # noqa: F401
from ...io.canopen.plant import plants  # noqa: F401
