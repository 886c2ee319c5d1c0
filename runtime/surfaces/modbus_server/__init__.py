"""The Modbus TCP server ([modbus_server]): the process image for HMIs and
SCADA, in OpenPLC's mapping (mapping.py; docs/guide/surfaces.md "Modbus TCP server").

    [modbus_server]
    port = 5020            # host = "127.0.0.1", writable = ["%Q*", "%M*"], unit = 0 (any)

    handle = start(surfaces, config)   # surfaces/host.py does this
    handle.url                         # "modbus-tcp://127.0.0.1:5020"
    handle.stop()

Public names: ``start``, ``ModbusServer`` (the handle), ``Mapping``.
"""

from __future__ import annotations

from .mapping import Mapping
from .server import ModbusServer

__all__ = ["Mapping", "ModbusServer", "start"]


def start(surfaces, config) -> ModbusServer:
    """Listen on config.host:config.port (0: any free port, handle.port says
    which) in a thread of its own; OSError if it cannot."""
    return ModbusServer(surfaces, config).start()
