"""MODBUS_CHANNEL[i] (fblocks/comm/modbus.st) as the program sees it,
filled by the Modbus master. Written only when something changed."""

from __future__ import annotations

from ...program import StructWriter
from ...program import global_variable as _global


class ModbusDiag:
    """MODBUS_CHANNEL[i], from the Modbus master's channels
    (runtime/io/modbus/channel.py)."""

    def __init__(self, globals_obj) -> None:
        channels = _global(globals_obj, "MODBUS_CHANNEL")
        self._channels = [StructWriter(s) for s in channels] if channels is not None else []
        self._seen: dict = {}  # index -> (version, connection ok) written

    @property
    def active(self) -> bool:
        """The program declares MODBUS_CHANNEL (it names something of modbus.st)."""
        return bool(self._channels)

    def stale(self, index: int, version: int, link_ok: bool) -> bool:
        """MODBUS_CHANNEL[index] does not show this version of the channel yet."""
        return index < len(self._channels) and self._seen.get(index) != (version, link_ok)

    def update(self, snapshot) -> None:
        """snapshot: (index, Channel.snapshot(), connection ok) per channel."""
        for index, (version, ok, last_error, requests, errors, response_ms, message), link_ok in snapshot:
            if index >= len(self._channels) or self._seen.get(index) == (version, link_ok):
                continue
            self._seen[index] = (version, link_ok)
            self._channels[index].set(
                Configured=True,
                Ok=ok,
                Error=requests > 0 and not ok,
                ConnectionOk=link_ok,
                LastError=last_error,
                Requests=requests,
                Errors=errors,
                ResponseTime=response_ms,
                Message=message,
            )
