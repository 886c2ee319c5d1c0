"""CANopen frames in words, for `softplc log` (io/can's reader asks every
protocol through Bus.frame_text): NMT, SYNC, EMCY (in the device's words
where it has them, Device.emcy_text), heartbeats, boot-ups and node
guarding (CiA 301 7.2.8), SDO transfers with the object's name from the
node's EDS, and the configured PDOs with each mapped object's name and
value. A frame of another COB-ID, or of another [[can]] bus, is not
CANopen's: None.

    words = frame_text(config)            # the [canopen] section's nodes and PDOs
    words("can0", msg)                    # "pump (20) boot-up" ...
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import canopen
from canopen.objectdictionary.datatypes import SIGNED_TYPES

from ...plugin.registry import registry
from .cia301 import COB_NMT, COB_SYNC, STATE_NAMES, abort_text
from .pdo import default_cob_id

NMT_COMMANDS = {
    0x01: "start",
    0x02: "stop",
    0x80: "enter pre-operational",
    0x81: "reset node",
    0x82: "reset communication",
}


@dataclass
class _Node:
    name: str
    node_id: int
    od: object | None  # canopen's ObjectDictionary from the node's EDS (None: it did not read)
    emcy_text: Callable | None
    object_text: Callable | None  # its device's words for a value of one of its objects
    pdos: dict = field(default_factory=dict)  # COB-ID -> (label, [(index, sub, name, bits, signed)])

    def who(self) -> str:
        return f"{self.name} ({self.node_id})"

    def value(self, index: int, sub: int, raw: int) -> str:
        """A value of one of its objects: the number, and its device's words for it."""
        words = self.object_text(index, sub, raw) if self.object_text is not None else None
        return f"{_number(raw)}: {words}" if words else _number(raw)

    def object_name(self, index: int, sub: int) -> str:
        entry = _entry(self.od, index, sub)
        name = f" {entry.name}" if entry is not None else ""
        return f"{index:04X}:{sub:02X}{name}"


def _entry(od, index: int, sub: int):
    if od is None:
        return None
    try:
        obj = od[index]
        if isinstance(obj, canopen.objectdictionary.ODVariable):
            return obj
        return obj[sub]
    except (KeyError, TypeError):
        return None


def frame_text(config) -> Callable[[str, object], str | None]:
    """The words for the frames of the [canopen] section's bus (see the module's docstring)."""
    co = getattr(config, "canopen", None)
    if co is None:
        return lambda _bus, _msg: None
    nodes = {n.node_id: _node(n) for n in co.nodes}
    pdos = {cob: (node, label, entries) for node in nodes.values() for cob, (label, entries) in node.pdos.items()}
    master = co.node_id

    def words(bus: str, msg) -> str | None:
        if bus != co.bus or msg.is_extended_id:
            return None
        cob, data = msg.arbitration_id, bytes(msg.data)
        if cob == COB_NMT:
            return _nmt(data, nodes)
        if cob == COB_SYNC:
            return "SYNC"
        if cob in pdos:
            owner, label, entries = pdos[cob]
            return _pdo(owner, label, entries, data)
        function, node_id = cob & 0x780, cob & 0x7F
        node = nodes.get(node_id)
        who = node.who() if node is not None else ("the master" if node_id == master else f"node {node_id}")
        if function == 0x080 and node_id:
            return _emcy(who, node, data)
        if function == 0x700:
            return _error_control(who, msg, data)
        if function in (0x580, 0x600):
            return _sdo(who, node, data, request=function == 0x600)
        return None

    return words


def _node(cfg) -> _Node:
    try:
        od = canopen.import_od(str(cfg.eds), cfg.node_id)
    except Exception:  # an EDS canopen cannot read: the frames without the objects' names
        od = None
    device = registry().device_with_name(cfg.device) if cfg.device else None
    node = _Node(
        cfg.name,
        cfg.node_id,
        od,
        device.emcy_text if device is not None else None,
        device.object_text if device is not None else None,
    )
    for direction, pdos in (("tpdo", cfg.tpdo), ("rpdo", cfg.rpdo)):
        for pdo in pdos:
            try:
                cob = default_cob_id(direction, pdo.number, cfg.node_id)
            except ValueError:
                continue
            entries = []
            for e in pdo.entries:
                entry = _entry(od, e.index, e.subindex)
                sized = entry is not None and entry.fixed_size
                bits = len(entry) if sized else 16  # as the master packs it (pdo.py); 16 if the EDS cannot say
                signed = sized and entry.data_type in SIGNED_TYPES
                entries.append((e.index, e.subindex, node.object_name(e.index, e.subindex), bits, signed))
            node.pdos[cob] = (f"{direction.upper()}{pdo.number}", entries)
    return node


def _nmt(data: bytes, nodes: dict) -> str:
    if len(data) < 2:
        return "NMT (short frame)"
    command = NMT_COMMANDS.get(data[0], f"command 0x{data[0]:02X}")
    target = "all nodes" if data[1] == 0 else (nodes[data[1]].who() if data[1] in nodes else f"node {data[1]}")
    return f"NMT {command}: {target}"


def _emcy(who: str, node: _Node | None, data: bytes) -> str:
    if len(data) < 3:
        return f"{who} EMCY (short frame)"
    code, register, extra = int.from_bytes(data[:2], "little"), data[2], data[3:8]
    if code == 0 and register == 0 and not any(extra):
        return f"{who} EMCY cleared"
    text = f"{who} EMCY {code:04X}h, error register {register:02X}h"
    if node is not None and node.emcy_text is not None:
        text += f": {node.emcy_text(code, register, bytes(extra))}"
    return text


def _error_control(who: str, msg, data: bytes) -> str:
    if msg.is_remote_frame:
        return f"{who} node guarding request"
    if not data:
        return f"{who} heartbeat (empty)"
    state = STATE_NAMES.get(data[0] & 0x7F, f"state 0x{data[0] & 0x7F:02X}")
    if data[0] == 0:
        return f"{who} boot-up"
    return f"{who} {'guarding answer' if data[0] & 0x80 else 'heartbeat'}: {state}"


def _sdo(who: str, node: _Node | None, data: bytes, *, request: bool) -> str:
    side = f"SDO {'request to' if request else 'answer of'} {who}"
    if len(data) < 8:
        return f"{side} (short frame)"
    command = data[0] >> 5
    index, sub = int.from_bytes(data[1:3], "little"), data[3]
    what = node.object_name(index, sub) if node is not None else f"{index:04X}:{sub:02X}"
    if command == 4:
        return f"{side}: abort {what}: {abort_text(int.from_bytes(data[4:8], 'little'))}"
    expedited, sized = data[0] & 0x02, data[0] & 0x01
    size = 4 - ((data[0] >> 2) & 0x03) if expedited and sized else 4
    raw = int.from_bytes(data[4 : 4 + size], "little")
    value = node.value(index, sub, raw) if node is not None else _number(raw)
    if request and command == 1:  # initiate download
        return f"{side}: write {what} = {value}" if expedited else f"{side}: write {what} (segmented)"
    if request and command == 2:
        return f"{side}: read {what}"
    if not request and command == 2:  # initiate upload response
        return f"{side}: {what} = {value}" if expedited else f"{side}: {what} (segmented)"
    if not request and command == 3:
        return f"{side}: written {what}"
    return f"{side}: segment"


def _number(value: int) -> str:
    """A value as the manuals write it: in decimal, and in hex too past one byte (a COB-ID, a mapping)."""
    return f"{value} (0x{value:X})" if value > 0xFF else str(value)


def _pdo(node: _Node, label: str, entries: list, data: bytes) -> str:
    bits_in = int.from_bytes(data, "little")
    offset, parts = 0, []
    for index, sub, name, bits, signed in entries:
        raw = (bits_in >> offset) & ((1 << bits) - 1)
        if signed and raw >> (bits - 1):
            raw -= 1 << bits
        parts.append(f"{name} = {node.value(index, sub, raw)}")
        offset += bits
    return f"{node.who()} {label}: " + " | ".join(parts)


__all__ = ["frame_text"]
