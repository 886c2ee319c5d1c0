"""The Eaton drives in the Modbus plants (tests/io/modbus)."""

from ...io.modbus.plant import plants  # noqa: F401
