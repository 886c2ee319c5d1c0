"""The FC 280 on the CANopen bench (tests/io/canopen)."""

from ...io.canopen.bench import bench  # noqa: F401
