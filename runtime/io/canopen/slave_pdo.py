"""The PDO side of a simulated CANopen slave (CiA 301): the communication
and mapping parameters as the object dictionary holds them, their write
rules, and the traffic: RPDOs into the dictionary, TPDOs out on change,
inhibit time, event timer and SYNC. A mixin of SimulatedCanopenSlave
(slave.py), which owns the dictionary, the NMT state and the endpoint.

Choices where CiA 301 leaves room: an event-driven TPDO (type 254/255) goes
out once on entering Operational, a synchronous one at the first SYNC after
it; the event timer is in ms (the LTMR manual says 0.1 ms, digest 001 A7),
the inhibit time in 100 us; a mapping changes only while its PDO is invalid
(COB-ID bit 31) and its sub-index 0 is 0; RTR-only types (252, 253) are not
supported.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial
from typing import TYPE_CHECKING, Any

from canopen.objectdictionary import ODArray, ODRecord, ODVariable
from canopen.objectdictionary.datatypes import INTEGER_TYPES, SIGNED_TYPES
from canopen.sdo import SdoAbortedError

from .cia301 import (
    ABORT_DEVICE_STATE,
    ABORT_NOT_MAPPABLE,
    ABORT_PDO_LENGTH,
    ABORT_VALUE_RANGE,
    COB_ID_INVALID,
    COB_SYNC,
    RPDO_COMM,
    RPDO_MAP,
    STATE_OPERATIONAL,
    TPDO_COMM,
    TPDO_MAP,
    split_mapping_entry,
)

if TYPE_CHECKING:
    from ..ratelog import RateLimitedLog


MS = 1_000_000


def _int_encoder(var: ODVariable) -> Callable[[object], int]:
    """int.from_bytes(var.encode_raw(value), "little"), with integers that
    encode_raw takes without a word (within the type and the EDS's limits)
    masked directly instead of packed and unpacked."""

    def slow(value) -> int:
        return int.from_bytes(var.encode_raw(value), "little")

    if var.data_type not in INTEGER_TYPES or not var.fixed_size:
        return slow
    bits = len(var)
    mask = (1 << bits) - 1
    lo, hi = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if var.data_type in SIGNED_TYPES else (0, mask)
    if var.min is not None:
        lo = max(lo, var.min)
    if var.max is not None:
        hi = min(hi, var.max)

    def encode(value) -> int:
        if type(value) is int and lo <= value <= hi:
            return value & mask
        return slow(value)

    return encode


SYNC_COB_ID = 0x1005
PDO_SLOTS = 512  # CiA 301: up to 512 RPDOs and 512 TPDOs
COB_ID_EXTENDED = 1 << 29  # 29-bit identifier: the LTMR is CAN 2.0A only (manual 001 §1.1)
PDO_MAX_BITS = 64

# Transmission types (CiA 301; manual 001 §2.2)
SYNC_ACYCLIC = 0  # on SYNC, when the data changed
SYNC_CYCLIC_LAST = 240  # 1..240: every n-th SYNC
EVENT_TYPES = (254, 255)  # on change, inhibit time, event timer


@dataclass
class Pdo:
    """One valid PDO as its communication and mapping parameters say."""

    number: int
    cob_id: int
    transmission: int
    entries: list  # (index, subindex, bits)
    inhibit_ns: int = 0  # TPDO sub 3, 100 us units
    event_ns: int = 0  # TPDO sub 5, ms (A7)
    readers: list = field(default_factory=list)  # TPDO: (read, mask, shift) per entry (_entry_reader)
    # TPDO: the raw values of every entry at once, when they all come from
    # one dict (_snapshot); None: no such shortcut
    snapshot: Callable[[], tuple] | None = None
    nbytes: int = field(init=False)

    def __post_init__(self) -> None:
        self.nbytes = (sum(bits for _i, _s, bits in self.entries) + 7) // 8


@dataclass
class TpdoState:
    last_data: bytes | None = None
    last_sent_ns: int | None = None
    sync_count: int = 0
    pending: bool = False  # send at the next opportunity, changed or not
    # Pdo.snapshot when last_data was packed from it: the same snapshot packs
    # the same data (None: not known)
    last_seen: tuple | None = None


@dataclass
class PdoTables:
    rpdos: dict = field(default_factory=dict)  # COB-ID -> Pdo
    tpdos: list = field(default_factory=list)  # [Pdo]
    # the event-driven TPDOs (types 254/255) with their state, looked at every step
    events: list = field(default_factory=list)  # [(Pdo, TpdoState)]


class PdoMixin:
    """The PDO machinery of SimulatedCanopenSlave (see the module docstring)."""

    od: Any
    node: Any
    name: str
    _state: int
    lines: RateLimitedLog  # what it logs, rate limited
    _tables: PdoTables | None
    _tpdo_state: dict[int, TpdoState]
    _sync_rpdos: dict[int, tuple]

    # provided by SimulatedCanopenSlave
    def _value(self, index: int, subindex: int) -> int:
        raise NotImplementedError

    def _cached_value(self, index: int, subindex: int) -> int:
        raise NotImplementedError

    def _send(self, can_id: int, data: bytes) -> None:
        raise NotImplementedError

    def _compound(self, index: int) -> ODRecord | ODArray:
        raise NotImplementedError

    def _variable_or_none(self, index: int, subindex: int) -> ODVariable | None:
        raise NotImplementedError

    def _flush_writes(self, now: int) -> None:
        raise NotImplementedError

    def _clock_ns(self) -> int:
        raise NotImplementedError

    def pdo_mappable(self, index: int, subindex: int, rpdo: bool) -> bool:
        raise NotImplementedError

    def pdo_source(self, index: int, subindex: int) -> Callable[[], int] | None:
        raise NotImplementedError

    def on_rpdo(self, number: int) -> None:
        raise NotImplementedError

    # ------------------------------------------------------------------ PDO parameters

    def _check_pdo_communication_write(self, index: int, sub: int, value: int) -> None:
        tpdo = index >= TPDO_COMM
        valid = not self._value(index, 1) & COB_ID_INVALID
        if sub == 1:
            if value & COB_ID_EXTENDED:
                raise SdoAbortedError(ABORT_VALUE_RANGE)
            if valid and not value & COB_ID_INVALID and (value & 0x7FF) != (self._value(index, 1) & 0x7FF):
                # CiA 301: the COB-ID of an existing PDO cannot change; invalidate it first
                raise SdoAbortedError(ABORT_VALUE_RANGE)
            mapping = index + 0x200
            if not value & COB_ID_INVALID and mapping in self.od:
                self._check_mapping_total(mapping, self._value(mapping, 0), rpdo=not tpdo)
        elif sub == 2:
            if not (value <= SYNC_CYCLIC_LAST or value in EVENT_TYPES):
                raise SdoAbortedError(ABORT_VALUE_RANGE)  # 241-251 reserved, 252/253 RTR only
        elif sub == 3 and tpdo and valid:
            raise SdoAbortedError(ABORT_DEVICE_STATE)  # CiA 301: inhibit time only while invalid

    def _check_mapping_write(self, index: int, sub: int, value: int, *, rpdo: bool) -> None:
        comm = index - 0x200
        if comm in self.od and not self._value(comm, 1) & COB_ID_INVALID:
            raise SdoAbortedError(ABORT_DEVICE_STATE)  # step 1: invalidate the PDO first
        if sub == 0:
            self._check_mapping_total(index, value, rpdo=rpdo)
            return
        if self._value(index, 0) != 0:
            raise SdoAbortedError(ABORT_DEVICE_STATE)  # step 2: sub-index 0 := 0 first
        if value:
            self._check_mappable(*split_mapping_entry(value), rpdo=rpdo)

    def _check_mapping_total(self, map_index: int, count: int, *, rpdo: bool) -> None:
        entries = sorted(s for s in self._compound(map_index).subindices if s)
        if count > len(entries):
            raise SdoAbortedError(ABORT_PDO_LENGTH)
        total = 0
        for sub in entries[:count]:
            index, subindex, bits = split_mapping_entry(self._value(map_index, sub))
            self._check_mappable(index, subindex, bits, rpdo=rpdo)
            total += bits
        if total > PDO_MAX_BITS:
            raise SdoAbortedError(ABORT_PDO_LENGTH)

    def _check_mappable(self, index: int, subindex: int, bits: int, *, rpdo: bool) -> None:
        var = self._variable_or_none(index, subindex)
        if (
            var is None
            or not var.pdo_mappable
            or not var.fixed_size
            or not (var.writable if rpdo else var.readable)
            or bits != len(var)
            or not self.pdo_mappable(index, subindex, rpdo)
        ):
            raise SdoAbortedError(ABORT_NOT_MAPPABLE)

    def _pdo_tables(self) -> PdoTables:
        """The valid PDOs, read from the OD (cached until a PDO object is written)."""
        if self._tables is None:
            tables = PdoTables()
            for number in range(1, PDO_SLOTS + 1):
                rpdo = self._read_pdo(RPDO_COMM + number - 1, RPDO_MAP + number - 1, number)
                if rpdo is not None:
                    tables.rpdos[rpdo.cob_id] = rpdo
                tpdo = self._read_pdo(TPDO_COMM + number - 1, TPDO_MAP + number - 1, number)
                if tpdo is not None:
                    tables.tpdos.append(tpdo)
                    state = self._tpdo_state.setdefault(number, TpdoState())
                    if tpdo.transmission in EVENT_TYPES:
                        # _boot clears the states only with the tables, so this one stays theirs
                        tables.events.append((tpdo, state))
            self._tables = tables
        return self._tables

    def _read_pdo(self, comm: int, mapping: int, number: int) -> Pdo | None:
        if comm not in self.od or mapping not in self.od:
            return None
        comm_record = self._compound(comm)
        cob = self._value(comm, 1)
        transmission = self._value(comm, 2) if 2 in comm_record else 255
        if cob & COB_ID_INVALID or not (transmission <= SYNC_CYCLIC_LAST or transmission in EVENT_TYPES):
            return None
        count = self._value(mapping, 0)
        entries = [
            split_mapping_entry(self._value(mapping, sub))
            for sub in sorted(self._compound(mapping).subindices)
            if 0 < sub <= count
        ]
        pdo = Pdo(number, cob & 0x7FF, transmission, entries)
        if comm >= TPDO_COMM:
            if 3 in comm_record:
                pdo.inhibit_ns = self._value(comm, 3) * 100_000  # 100 us units
            if 5 in comm_record:
                pdo.event_ns = self._value(comm, 5) * MS  # ms (CiA 301; manual says 0.1 ms: A7)
            shift = 0
            for index, subindex, bits in entries:
                pdo.readers.append((self._entry_reader(index, subindex), (1 << bits) - 1, shift))
                shift += bits
            pdo.snapshot = _snapshot([read for read, _mask, _shift in pdo.readers])
        return pdo

    def _entry_reader(self, index: int, subindex: int) -> Callable[[], int]:
        """How _pack_tpdo reads one mapped object: the device's pdo_source, or
        what LocalNode.get_data does (read callbacks, the store, the EDS value,
        its default) with the object looked up once; a refused or missing
        object packs as 0."""
        source = self.pdo_source(index, subindex)
        if source is not None:
            return source
        node = self.node
        try:
            var = node._find_object(index, subindex)
        except SdoAbortedError:
            return lambda: 0
        callbacks = node._read_callbacks  # canopen's list: one may be added later, so read at each call
        store = node.data_store
        own = self._own_read_callback()
        device_read = self._device_object_read()
        if own is not None:
            try:
                self._check_subindex_exists(var, subindex)  # what the own callback checks first: fixed by the EDS
            except SdoAbortedError:
                own = None  # the slow path refuses it at every read, as before
        encode = _int_encoder(var)

        def read() -> int:
            try:
                if own is not None and len(callbacks) == 1 and callbacks[0] is own:
                    # only the slave's own read callback: the device's object_read, called directly
                    result = device_read(index, subindex, var)
                    if result is not None:
                        return encode(result)
                else:
                    for callback in callbacks:
                        result = callback(index=index, subindex=subindex, od=var)
                        if result is not None:
                            return encode(result)
                stored = store.get(index)
                if stored is not None and subindex in stored:
                    return int.from_bytes(stored[subindex], "little")
                if var.value is not None:
                    return encode(var.value)
                if var.default is not None:
                    return encode(var.default)
            except SdoAbortedError:
                pass
            return 0

        return read

    # provided by SimulatedCanopenSlave, for _entry_reader's direct path: the
    # read callback it gave LocalNode (None: none), and what that callback
    # calls once the sub-index is checked (the device's object_read)
    def _own_read_callback(self) -> Callable | None:
        return None

    def _device_object_read(self) -> Callable:
        raise NotImplementedError

    @staticmethod
    def _check_subindex_exists(od: ODVariable, subindex: int) -> None:
        raise NotImplementedError

    # ------------------------------------------------------------------ PDO traffic

    def _on_rpdo_frame(self, pdo: Pdo, data: bytes) -> None:
        if len(data) < pdo.nbytes:
            self.lines.debug(
                ("short rpdo", pdo.number),
                "%s: RPDO %d with %d bytes, %d mapped: ignored",
                self.name,
                pdo.number,
                len(data),
                pdo.nbytes,
            )
            return
        if pdo.transmission <= SYNC_CYCLIC_LAST:
            self._sync_rpdos[pdo.number] = (pdo, data)  # applied at the next SYNC
            return
        self._apply_rpdo(pdo, data)

    def _apply_rpdo(self, pdo: Pdo, data: bytes) -> None:
        frame = int.from_bytes(data, "little")
        offset = 0
        for index, subindex, bits in pdo.entries:
            value = (frame >> offset) & ((1 << bits) - 1)
            offset += bits
            try:
                self.node.set_data(index, subindex, value.to_bytes((bits + 7) // 8, "little"))
            except SdoAbortedError as exc:
                # A PDO has no answer: the device keeps its value (an SDO would abort)
                self.lines.debug(
                    ("refused", pdo.number),
                    "%s: RPDO %d entry %04X:%02X refused (0x%08X)",
                    self.name,
                    pdo.number,
                    index,
                    subindex,
                    exc.code,
                )
        self.on_rpdo(pdo.number)

    def _pack_tpdo(self, pdo: Pdo) -> bytes:
        frame = 0
        for read, mask, shift in pdo.readers:
            frame |= (read() & mask) << shift
        return frame.to_bytes(pdo.nbytes, "little")

    def _send_tpdo(self, pdo: Pdo, data: bytes, now: int, seen: tuple | None = None) -> None:
        state = self._tpdo_state.setdefault(pdo.number, TpdoState())
        self._send(pdo.cob_id, data)
        state.last_data = data
        state.last_seen = seen
        state.last_sent_ns = now
        state.pending = False

    def _transmit_event_tpdos(self, now: int) -> None:
        """Types 254/255: on change of the packed data, after the inhibit time,
        and every event-timer period even without change."""
        tables = self._tables if self._tables is not None else self._pdo_tables()
        for pdo, state in tables.events:
            last = state.last_sent_ns
            since = 0
            if last is not None:
                since = now - last
                if since < pdo.inhibit_ns:
                    continue  # sent once the inhibit time is over (nothing to pack before)
            send = state.pending or (pdo.event_ns and last is not None and since >= pdo.event_ns)
            seen = None
            if pdo.snapshot is not None:
                seen = pdo.snapshot()
                if not send and seen == state.last_seen:
                    continue  # the values last_data was packed from: the same data
            frame = 0  # _pack_tpdo, inlined: this runs for every event TPDO at every step
            for read, mask, shift in pdo.readers:
                frame |= (read() & mask) << shift
            data = frame.to_bytes(pdo.nbytes, "little")
            if not (send or data != state.last_data):
                state.last_seen = seen  # other values, the same data (bits not mapped)
                continue
            self._send_tpdo(pdo, data, now, seen)

    def _on_sync(self, now: int) -> None:
        pending, self._sync_rpdos = self._sync_rpdos, {}
        if self._state != STATE_OPERATIONAL:
            return
        for pdo, data in pending.values():
            self._apply_rpdo(pdo, data)
        self._flush_writes(now)
        for pdo in self._pdo_tables().tpdos:
            if pdo.transmission > SYNC_CYCLIC_LAST:
                continue
            state = self._tpdo_state.setdefault(pdo.number, TpdoState())
            data = self._pack_tpdo(pdo)
            if pdo.transmission == SYNC_ACYCLIC:
                if state.pending or data != state.last_data:
                    self._send_tpdo(pdo, data, now)
                continue
            state.sync_count += 1
            if state.sync_count >= pdo.transmission:
                state.sync_count = 0
                self._send_tpdo(pdo, data, now)
        self._transmit_event_tpdos(now)  # RPDO data applied at SYNC may change TPDO data

    def _enter_operational(self) -> None:
        """Every TPDO goes out once: event-driven ones now, synchronous ones at
        the next SYNC (their cyclic count starts again)."""
        for pdo in self._pdo_tables().tpdos:
            state = self._tpdo_state.setdefault(pdo.number, TpdoState())
            state.pending = True
            state.sync_count = 0
        self._transmit_event_tpdos(self._clock_ns())

    def _sync_cob_id(self) -> int:
        return (self._cached_value(SYNC_COB_ID, 0) & 0x7FF) if SYNC_COB_ID in self.od else COB_SYNC


def _snapshot(readers: list) -> Callable[[], tuple] | None:
    """A TPDO's entries read at once, when every reader is a device's
    pdo_source of the form partial(values.get, key, 0) on one dict (the
    LTMR's registers): a tuple of the raw values, built in C, which
    _transmit_event_tpdos compares before it packs anything."""
    values = None
    keys = []
    for read in readers:
        get = read.func if type(read) is partial else None
        owner = getattr(get, "__self__", None)
        if (
            type(owner) is not dict
            or getattr(get, "__name__", "") != "get"
            or len(read.args) != 2
            or read.args[1] != 0
            or read.keywords
            or (values is not None and owner is not values)
        ):
            return None
        values = owner
        keys.append(read.args[0])
    if values is None:
        return None
    return partial(_values_of, values.get, tuple(keys))


def _values_of(get: Callable, keys: tuple) -> tuple:
    return tuple(map(get, keys))
