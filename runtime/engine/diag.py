"""The engine's side of the diagnostic globals a program reads:
PLC_DIAG (fblocks/system/plc_diag.st, the engine's own state) and
CANOPEN_NODE / CANOPEN_MASTER (fblocks/comm/canopen_diag.st, filled by the
CANopen master) and MODBUS_CHANNEL (fblocks/comm/modbus.st, filled by the
Modbus master). Written only when something changed, so the scan pays
(almost) nothing for them."""
from __future__ import annotations

from ..io.canopen_node import NodeState
from ..st import types as T
from ..st.loader import locate


class StructWriter:
    """Sets the fields of one ST struct instance by their ST names."""

    def __init__(self, struct) -> None:
        self._struct = struct
        self._fields: dict = {}  # field name (upper) -> (attr, max length or None)
        if struct is None:
            return
        for st_name, attr, ty, _section in type(struct)._VARS_:
            t = T.resolve(ty)
            self._fields[st_name.upper()] = (attr, t.length if isinstance(t, T.StringType) else None)

    def set(self, **values) -> None:
        if self._struct is None:
            return
        for name, value in values.items():
            entry = self._fields.get(name.upper())
            if entry is None:
                continue
            attr, length = entry
            if length is not None:
                value = str(value)[:length]
            setattr(self._struct, attr, value)

    def get(self, name: str):
        entry = self._fields.get(name.upper())
        return None if entry is None else getattr(self._struct, entry[0])


def _global(globals_obj, name: str):
    try:
        holder, attr, _ty = locate(name, (globals_obj,))
    except KeyError:  # not loaded with the library that declares it
        return None
    return getattr(holder, attr)


class DiagVariable(StructWriter):
    """PLC_DIAG."""

    def __init__(self, globals_obj) -> None:
        super().__init__(_global(globals_obj, "PLC_DIAG"))


class CanopenDiag:
    """CANOPEN_NODE[id] and CANOPEN_MASTER, from the master's node
    supervisors (runtime/io/canopen_node.py)."""

    def __init__(self, globals_obj) -> None:
        nodes = _global(globals_obj, "CANOPEN_NODE")
        self._nodes = [StructWriter(s) for s in nodes] if nodes is not None else []
        self._master = StructWriter(_global(globals_obj, "CANOPEN_MASTER"))
        self._seen: dict = {}   # node id -> version written

    def update(self, snapshot, master: dict) -> None:
        """snapshot: (node id, version, node) for every configured node."""
        self._master.set(**master)
        for node_id, version, node in snapshot:
            if self._seen.get(node_id) == version or node_id >= len(self._nodes):
                continue
            self._seen[node_id] = version
            sup = node.sup
            emcy = sup.last_emcy
            self._nodes[node_id].set(
                Configured=True, State=int(sup.state), Operational=sup.state == NodeState.OPERATIONAL,
                HeartbeatLost=sup.state == NodeState.LOST, Missing=sup.state == NodeState.MISSING,
                NmtState=sup.nmt_state or 0, Boots=sup.boots, Emergencies=sup.emergencies,
                EmcyCode=emcy.code if emcy else 0, EmcyRegister=emcy.register if emcy else 0,
                EmcyData=int.from_bytes(emcy.data[:4], "little") if emcy else 0,
                Message=sup.message if sup.state != NodeState.OPERATIONAL else "")


class ModbusDiag:
    """MODBUS_CHANNEL[i], from the Modbus master's channels
    (runtime/io/modbus_channel.py)."""

    def __init__(self, globals_obj) -> None:
        channels = _global(globals_obj, "MODBUS_CHANNEL")
        self._channels = [StructWriter(s) for s in channels] if channels is not None else []
        self._seen: dict = {}   # index -> (version, connection ok) written

    @property
    def active(self) -> bool:
        """The program declares MODBUS_CHANNEL (it names something of modbus.st)."""
        return bool(self._channels)

    def update(self, snapshot) -> None:
        """snapshot: (index, Channel.snapshot(), connection ok) per channel."""
        for index, (version, ok, last_error, requests, errors, response_ms, message), link_ok in snapshot:
            if index >= len(self._channels) or self._seen.get(index) == (version, link_ok):
                continue
            self._seen[index] = (version, link_ok)
            self._channels[index].set(
                Configured=True, Ok=ok, Error=requests > 0 and not ok, ConnectionOk=link_ok,
                LastError=last_error, Requests=requests, Errors=errors, ResponseTime=response_ms,
                Message=message)
