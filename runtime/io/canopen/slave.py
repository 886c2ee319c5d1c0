"""A simulated CANopen slave (CiA 301): a real, separate peer on the bus,
built from an EDS, with no knowledge of any particular device.

    slave = SimulatedCanopenSlave(40, eds="ltmr.eds", settings=BusSettings("virtual", "plant"),
                                  clock=clock, pump=pump)
    slave.start()            # power-up: boot-up frame 0x728 [00], pre-operational
    slave.advance_to(t)      # virtual time: heartbeats, timeouts, TPDO timers up to t

It has its own python-can bus object (opened with open_bus, like any other
node) and a CanEndpoint; canopen's LocalNode provides the object dictionary
and the SDO server. Everything else is this module's: NMT slave, heartbeat
producer and consumer, PDOs from the OD's own communication and mapping
parameters, EMCY producer. canopen's own NMT slave and PDO classes send
with network.send_periodic, a real-time timer thread; here every
time-driven action happens in service(now_ns), so a run in virtual time is
the same every time.

A device simulator subclasses it and fills in the hooks:

    run_device(now_ns)            the device's own behaviour, before each service step
    object_read(index, sub, od)   a live value for an object (None: the stored one)
    object_write(index, sub, od, data, local)
                                  check or apply a write; raise SdoAbortedError(code) to refuse
    pdo_mappable(index, sub, rpdo) whether an object may go into an RPDO / TPDO
    on_state_change(old, new), on_reset_application(), on_comm_error(),
    on_comm_restored(), on_rpdo(number)

Choices where CiA 301 leaves room (each said again where it is made):
- An event-driven TPDO (type 254/255) goes out once on entering
  Operational; a synchronous one at the first SYNC after it.
- The TPDO event timer is in ms (CiA 301; the LTMR manual says 0.1 ms,
  digest 001 A7). The inhibit time is in 100 us.
- PDO mapping follows the CiA 301 procedure: a mapping changes only while
  its PDO is invalid (COB-ID bit 31) and its sub-index 0 is 0, otherwise
  ABORT_DEVICE_STATE; entries that cannot be mapped ABORT_NOT_MAPPABLE;
  more than 64 bits ABORT_PDO_LENGTH (the codes of manual 001 §3.3).
- RTR-only transmission types (252, 253) are not supported.
"""

from __future__ import annotations

import logging
import struct
import threading
from dataclasses import dataclass, field

import can
import canopen
from canopen.objectdictionary import ODArray, ODRecord, ODVariable
from canopen.sdo import SdoAbortedError

from ...sim.base import SimulatedDevice
from ..can.bus import BusPump, BusSettings, CanEndpoint, open_bus
from .cia301 import (
    ABORT_DEVICE_STATE,
    ABORT_NO_SUBINDEX,
    ABORT_NOT_MAPPABLE,
    ABORT_PDO_LENGTH,
    ABORT_VALUE_RANGE,
    COB_ID_INVALID,
    COB_NMT,
    COB_SYNC,
    NMT_PRE_OPERATIONAL,
    NMT_RESET_COMMUNICATION,
    NMT_RESET_NODE,
    NMT_START,
    NMT_STOP,
    RPDO_COMM,
    RPDO_MAP,
    STATE_BOOTUP,
    STATE_OPERATIONAL,
    STATE_PRE_OPERATIONAL,
    STATE_STOPPED,
    TPDO_COMM,
    TPDO_MAP,
    cob_emcy,
    cob_heartbeat,
    split_mapping_entry,
)

log = logging.getLogger(__name__)

MS = 1_000_000

# CiA 301 object dictionary areas and objects
COMMUNICATION_AREA = (0x1000, 0x1FFF)
APPLICATION_AREA = (0x2000, 0x9FFF)
ERROR_REGISTER = 0x1001
ERROR_HISTORY = 0x1003
SYNC_COB_ID = 0x1005
EMCY_COB_ID = 0x1014
CONSUMER_HEARTBEAT = 0x1016
PRODUCER_HEARTBEAT = 0x1017
ERROR_BEHAVIOUR = 0x1029
PDO_SLOTS = 512  # CiA 301: up to 512 RPDOs and 512 TPDOs

COB_ID_EXTENDED = 1 << 29  # 29-bit identifier: the LTMR is CAN 2.0A only (manual 001 §1.1)
PDO_MAX_BITS = 64

# Transmission types (CiA 301; manual 001 §2.2)
SYNC_ACYCLIC = 0  # on SYNC, when the data changed
SYNC_CYCLIC_LAST = 240  # 1..240: every n-th SYNC
EVENT_TYPES = (254, 255)  # on change, inhibit time, event timer

# 0x1029:01, on a communication error (manual 001 L1017-1030)
ERROR_TO_PRE_OPERATIONAL = 0
ERROR_NO_STATE_CHANGE = 1
ERROR_TO_STOPPED = 2

# EMCY (CiA 301): 2 bytes error code, error register, 5 manufacturer bytes
EMCY_MANUFACTURER_BYTES = 5


class _SlaveNetwork(canopen.Network):
    """canopen's Network without a bus of its own: it sends through the
    slave's endpoint (so an unplugged cable drops frames in one place) and
    is fed by the endpoint's handler with notify()."""

    def __init__(self, endpoint: CanEndpoint) -> None:
        super().__init__(bus=None)
        self.endpoint = endpoint

    def send_message(self, can_id: int, data: bytes, remote: bool = False) -> None:
        self.endpoint.send(can_id, bytes(data), remote=remote)


class _SlaveNode(canopen.LocalNode):
    """canopen's LocalNode, used for its object dictionary and SDO server
    only: its NMT slave would start canopen's real-time heartbeat thread on
    a write to 0x1017, and NMT, heartbeat and PDOs are the simulator's."""

    def __init__(self, node_id: int, od) -> None:
        super().__init__(node_id, od)
        self._write_callbacks.remove(self.nmt.on_write)

    def associate_network(self, network: canopen.Network) -> None:
        # No NMT subscription (the simulator handles 0x000); a reopened bus
        # simply replaces the old network.
        self.network = network
        self.sdo.network = network
        self.emcy.network = network
        network.subscribe(self.sdo.rx_cobid, self.sdo.on_request)


@dataclass
class _Pdo:
    """One valid PDO as its communication and mapping parameters say."""

    number: int
    cob_id: int
    transmission: int
    entries: list  # (index, subindex, bits)
    inhibit_ns: int = 0  # TPDO sub 3, 100 us units
    event_ns: int = 0  # TPDO sub 5, ms (A7)

    @property
    def nbytes(self) -> int:
        return (sum(bits for _i, _s, bits in self.entries) + 7) // 8


@dataclass
class _TpdoState:
    last_data: bytes | None = None
    last_sent_ns: int | None = None
    sync_count: int = 0
    pending: bool = False  # send at the next opportunity, changed or not


@dataclass
class _Consumer:
    """One heartbeat consumer entry of 0x1016."""

    producer: int
    timeout_ns: int
    last_ns: int | None = None  # None: not monitoring yet (CiA 301: starts with the first heartbeat)
    lost: bool = False


@dataclass
class _PdoTables:
    rpdos: dict = field(default_factory=dict)  # COB-ID -> _Pdo
    tpdos: list = field(default_factory=list)  # [_Pdo]


class SimulatedCanopenSlave(SimulatedDevice):
    """See the module docstring."""

    pump: BusPump | None  # a CAN node: its endpoint is on the bus's pump (virtual time)

    def __init__(
        self, node_id: int, *, eds, settings: BusSettings, clock, pump: BusPump | None = None, name: str | None = None
    ) -> None:
        if not 1 <= node_id <= 127:
            raise ValueError(f"CANopen node id {node_id} is not in 1..127")
        super().__init__(name or f"canopen slave {node_id}", clock=clock, pump=pump)
        self.node_id = node_id
        self.settings = settings
        self.od = canopen.import_od(eds, node_id)
        self.node = _SlaveNode(node_id, self.od)
        self.node.add_read_callback(self._on_sdo_read)
        self.node.add_write_callback(self._on_sdo_write)
        self.endpoint: CanEndpoint | None = None
        self.network: _SlaveNetwork | None = None
        self._lock = threading.RLock()
        self._state = STATE_BOOTUP
        self._now = 0
        self._local_writes = 0  # > 0 while write() runs: the device's own access
        self._tables: _PdoTables | None = None
        self._tpdo_state: dict[int, _TpdoState] = {}
        self._sync_rpdos: dict[int, tuple] = {}  # RPDO number -> (pdo, data) waiting for SYNC
        self._consumers: list[_Consumer] | None = None
        self._heartbeat_due: int | None = None
        self._written: list[int] = []  # objects written, for _flush_writes

    # ------------------------------------------------------------------ hooks

    def run_device(self, now_ns: int) -> None:
        """The device's own time-driven behaviour, called first in every service step."""

    def object_read(self, index: int, subindex: int, od: ODVariable):
        """A live value (int or bytes) for an SDO/PDO read, or None for the stored one.
        Raise SdoAbortedError(code) to refuse the read."""
        return None

    def object_write(self, index: int, subindex: int, od: ODVariable, data: bytes, local: bool) -> None:
        """Called before a write is stored. Raise SdoAbortedError(code) to refuse
        it. local: the device's own access (write()), not the network's."""

    def pdo_mappable(self, index: int, subindex: int, rpdo: bool) -> bool:
        """Device rules on top of the EDS PDOMapping flag (e.g. which objects go
        into RPDOs and which into TPDOs)."""
        return True

    def on_state_change(self, old: int, new: int) -> None:
        """The NMT state changed (STATE_* of devices.cia301)."""

    def on_reset_application(self) -> None:
        """NMT reset node or a power cycle: the application restarts. By default
        the application area (0x2000-0x9FFF) goes back to its EDS values."""
        self._clear_stored(*APPLICATION_AREA)

    def on_comm_error(self) -> None:
        """A watched heartbeat producer fell silent (before the 0x1029 state change)."""

    def on_comm_restored(self) -> None:
        """Heartbeats from every lost producer came back."""

    def on_rpdo(self, number: int) -> None:
        """RPDO `number` was received in Operational and its data stored."""

    # ------------------------------------------------------------------ life cycle

    def open(self) -> None:
        with self._lock:
            self.endpoint = CanEndpoint(open_bus(self.settings), name=self.name, pump=self.pump)
            self.network = _SlaveNetwork(self.endpoint)
            self.node.associate_network(self.network)
            self.endpoint.add_handler(self._on_frame)
            self.endpoint.start()
            self._boot(self._clock_ns(), application=True)

    def close(self) -> None:
        with self._lock:
            if self.endpoint is not None:
                self.endpoint.stop()
            self._state = STATE_BOOTUP

    def service(self, now_ns: int) -> None:
        with self._lock:
            self._now = max(self._now, now_ns)
            self.run_device(now_ns)
            if self._state == STATE_BOOTUP:
                return
            self._produce_heartbeat(now_ns)
            self._watch_heartbeats(now_ns)
            if self._state == STATE_OPERATIONAL:
                self._transmit_event_tpdos(now_ns)

    # ------------------------------------------------------------------ test and operator API

    @property
    def nmt_state(self) -> int:
        return self._state

    @property
    def heartbeat_lost(self) -> bool:
        """A watched producer's heartbeat is missing right now."""
        return any(c.lost for c in self._heartbeat_consumers())

    def unplug(self) -> None:
        """Cut the cable: frames are dropped both ways until plug()."""
        self._opened_endpoint().connected = False

    def plug(self) -> None:
        self._opened_endpoint().connected = True

    def _opened_endpoint(self) -> CanEndpoint:
        if self.endpoint is None:
            raise RuntimeError(f"{self.name}: not started (no cable to cut or mend)")
        return self.endpoint

    @property
    def plugged(self) -> bool:
        return self.endpoint is not None and self.endpoint.connected

    def power_cycle(self) -> None:
        """Switch the device off and on: application and communication restart,
        boot-up frame, pre-operational."""
        with self._lock:
            self._boot(self._clock_ns(), application=True)

    def read(self, index: int, subindex: int = 0):
        """An object's value as the device itself sees it (no access checks)."""
        with self._lock:
            var = self._variable(index, subindex)
            return var.decode_raw(self.node.get_data(index, subindex))

    def write(self, index: int, subindex: int, value) -> None:
        """Set an object as the device's own HMI would: read-only objects too,
        but still through the device's rules (object_write with local=True)."""
        with self._lock:
            var = self._variable(index, subindex)
            self._local_writes += 1
            try:
                self.node.set_data(index, subindex, var.encode_raw(value))
            finally:
                self._local_writes -= 1
                self._flush_writes(self._clock_ns())

    def send_emcy(self, error_code: int, error_register: int, manufacturer_bytes: bytes = b"") -> None:
        """Produce an emergency (CiA 301): keeps 0x1001 and the 0x1003 history;
        error code 0x0000 is "error reset" and is not added to the history."""
        with self._lock:
            data = bytes(manufacturer_bytes)
            if len(data) > EMCY_MANUFACTURER_BYTES:
                raise ValueError(f"an EMCY carries {EMCY_MANUFACTURER_BYTES} manufacturer bytes, not {len(data)}")
            if ERROR_REGISTER in self.od:
                self._store(ERROR_REGISTER, 0, error_register)
            if error_code:
                self._push_error_history(error_code)
            cob = self._value(EMCY_COB_ID, 0) if EMCY_COB_ID in self.od else cob_emcy(self.node_id)
            # CiA 301: no EMCY in Stopped; bit 31 of 0x1014 switches the EMCY off
            if cob & COB_ID_INVALID or self._state in (STATE_STOPPED, STATE_BOOTUP):
                return
            payload = struct.pack("<HB", error_code, error_register) + data.ljust(EMCY_MANUFACTURER_BYTES, b"\0")
            self._send(cob & 0x7FF, payload)

    def mark_changed(self, index: int, subindex: int) -> None:
        """Send the TPDOs that map this object at their next opportunity, even if
        the packed data happen to be the same as last time."""
        with self._lock:
            for pdo in self._pdo_tables().tpdos:
                if any(i == index and s == subindex for i, s, _b in pdo.entries):
                    self._tpdo_state.setdefault(pdo.number, _TpdoState()).pending = True

    # ------------------------------------------------------------------ NMT (CiA 301)

    def _boot(self, now: int, *, application: bool) -> None:
        """Initialisation: (reset application,) reset communication, boot-up
        frame, pre-operational."""
        self._set_state(STATE_BOOTUP)
        if application:
            self.on_reset_application()
        self._clear_stored(*COMMUNICATION_AREA)
        self.node.sdo._buffer = None  # a segmented transfer in progress is gone
        self._tables = None
        self._consumers = None
        self._tpdo_state.clear()
        self._sync_rpdos.clear()
        self._send(cob_heartbeat(self.node_id), bytes([STATE_BOOTUP]))
        period = self._heartbeat_period_ns()
        self._heartbeat_due = now + period if period else None
        self._set_state(STATE_PRE_OPERATIONAL)

    def _on_nmt(self, data: bytes, now: int) -> None:
        if len(data) < 2:
            return
        command, target = data[0], data[1]
        if target not in (0, self.node_id):  # node 0: every node
            return
        if command == NMT_START:
            self._set_state(STATE_OPERATIONAL)
        elif command == NMT_STOP:
            self._set_state(STATE_STOPPED)
        elif command == NMT_PRE_OPERATIONAL:
            self._set_state(STATE_PRE_OPERATIONAL)
        elif command == NMT_RESET_NODE:
            self._boot(now, application=True)
        elif command == NMT_RESET_COMMUNICATION:
            self._boot(now, application=False)

    def _set_state(self, new: int) -> None:
        old = self._state
        if new == old:
            return
        self._state = new
        self.on_state_change(old, new)
        if new == STATE_OPERATIONAL:
            self._enter_operational()

    # ------------------------------------------------------------------ heartbeat (CiA 301)

    def _heartbeat_period_ns(self) -> int:
        return self._value(PRODUCER_HEARTBEAT, 0) * MS if PRODUCER_HEARTBEAT in self.od else 0

    def _produce_heartbeat(self, now: int) -> None:
        if self._heartbeat_due is None or now < self._heartbeat_due:
            return
        self._send(cob_heartbeat(self.node_id), bytes([self._state]))
        period = self._heartbeat_period_ns()
        due = self._heartbeat_due + period
        self._heartbeat_due = due if due > now else now + period  # no burst after a long gap

    def _heartbeat_consumers(self) -> list:
        if self._consumers is None:
            self._consumers = []
            obj = self.od.get(CONSUMER_HEARTBEAT)
            if obj is not None:
                for sub in sorted(obj.subindices):
                    if sub == 0:
                        continue
                    entry = self._value(CONSUMER_HEARTBEAT, sub)
                    producer, time_ms = (entry >> 16) & 0xFF, entry & 0xFFFF
                    if 1 <= producer <= 127 and time_ms:  # 0 = entry not used
                        self._consumers.append(_Consumer(producer, time_ms * MS))
        return self._consumers

    def _on_heartbeat(self, producer: int, now: int) -> None:
        was_lost = self.heartbeat_lost
        for consumer in self._heartbeat_consumers():
            if consumer.producer == producer:
                consumer.last_ns = now
                consumer.lost = False
        if was_lost and not self.heartbeat_lost:
            self.on_comm_restored()

    def _watch_heartbeats(self, now: int) -> None:
        for consumer in self._heartbeat_consumers():
            if consumer.last_ns is None or consumer.lost:
                continue
            if now - consumer.last_ns > consumer.timeout_ns:
                consumer.lost = True
                log.info("%s: heartbeat of node %d lost", self.name, consumer.producer)
                self._communication_error()

    def _communication_error(self) -> None:
        self.on_comm_error()
        behaviour = ERROR_TO_PRE_OPERATIONAL
        if ERROR_BEHAVIOUR in self.od:
            behaviour = self._value(ERROR_BEHAVIOUR, 1)
        if behaviour == ERROR_TO_PRE_OPERATIONAL and self._state == STATE_OPERATIONAL:
            self._set_state(STATE_PRE_OPERATIONAL)  # CiA 301: only from Operational
        elif behaviour == ERROR_TO_STOPPED:
            self._set_state(STATE_STOPPED)

    # ------------------------------------------------------------------ frames

    def _on_frame(self, msg: can.Message) -> None:
        if msg.is_remote_frame:
            return  # RTR is not supported (CiA recommends against it)
        can_id, data = msg.arbitration_id, bytes(msg.data)
        with self._lock:
            now = self._clock_ns()
            if self._state == STATE_BOOTUP:
                return
            if can_id == COB_NMT:
                self._on_nmt(data, now)
                return
            if cob_heartbeat(1) <= can_id <= cob_heartbeat(127) and data:
                self._on_heartbeat(can_id - cob_heartbeat(0), now)
                return
            if self._state == STATE_STOPPED:
                return  # Stopped: NMT and error control only
            if can_id == self._sync_cob_id():
                self._on_sync(now)
                return
            if self._state == STATE_OPERATIONAL:
                pdo = self._pdo_tables().rpdos.get(can_id)
                if pdo is not None:
                    self._on_rpdo_frame(pdo, data)
                    self._flush_writes(now)
                    self._transmit_event_tpdos(now)
                    return
            assert self.network is not None  # open() made it before adding this handler
            self.network.notify(can_id, msg.data, msg.timestamp)  # the SDO server
            self._flush_writes(now)
            if self._state == STATE_OPERATIONAL:
                self._transmit_event_tpdos(now)  # an SDO write may have changed mapped data

    def _send(self, can_id: int, data: bytes) -> None:
        if self.endpoint is not None:
            self.endpoint.send(can_id, data)

    def _clock_ns(self) -> int:
        self._now = max(self._now, self.clock.now_ns())
        return self._now

    # ------------------------------------------------------------------ SDO access rules

    def _on_sdo_read(self, index: int, subindex: int, od: ODVariable):
        self._check_subindex_exists(od, subindex)
        return self.object_read(index, subindex, od)

    def _on_sdo_write(self, index: int, subindex: int, od: ODVariable, data: bytes) -> None:
        self._check_subindex_exists(od, subindex)
        value = int.from_bytes(data, "little") if od.fixed_size else None
        if value is not None:
            self._check_communication_write(index, subindex, value)
        self.object_write(index, subindex, od, bytes(data), self._local_writes > 0)
        # LocalNode stores the data once the callbacks return: what the write
        # changes is done after that (_flush_writes).
        self._written.append(index)

    @staticmethod
    def _check_subindex_exists(od: ODVariable, subindex: int) -> None:
        # canopen's ODArray makes up any sub-index 1..255 from its first entry,
        # so a sub-index the EDS does not list would not be refused by LocalNode.
        if isinstance(od.parent, ODArray) and subindex not in od.parent.subindices:
            raise SdoAbortedError(ABORT_NO_SUBINDEX)

    def _check_communication_write(self, index: int, sub: int, value: int) -> None:
        if index == ERROR_HISTORY and sub == 0 and value != 0:
            raise SdoAbortedError(ABORT_VALUE_RANGE)  # "Only the value 0 can be written" (manual 001 §4)
        if index == ERROR_BEHAVIOUR and sub == 1 and value > ERROR_TO_STOPPED:
            raise SdoAbortedError(ABORT_VALUE_RANGE)
        if RPDO_COMM <= index < RPDO_COMM + PDO_SLOTS or TPDO_COMM <= index < TPDO_COMM + PDO_SLOTS:
            self._check_pdo_communication_write(index, sub, value)
        elif RPDO_MAP <= index < RPDO_MAP + PDO_SLOTS:
            self._check_mapping_write(index, sub, value, rpdo=True)
        elif TPDO_MAP <= index < TPDO_MAP + PDO_SLOTS:
            self._check_mapping_write(index, sub, value, rpdo=False)

    def _flush_writes(self, now: int) -> None:
        written, self._written = self._written, []
        for index in dict.fromkeys(written):
            self._after_write(index, now)

    def _after_write(self, index: int, now: int) -> None:
        """What a stored write changes (SDO, PDO or local)."""
        if RPDO_COMM <= index < RPDO_MAP + PDO_SLOTS or TPDO_COMM <= index < TPDO_MAP + PDO_SLOTS:
            self._tables = None
        elif index == CONSUMER_HEARTBEAT:
            self._consumers = None  # monitoring restarts with the next heartbeat
        elif index == PRODUCER_HEARTBEAT:
            period = self._heartbeat_period_ns()
            self._heartbeat_due = now + period if period else None
        elif index == ERROR_HISTORY:
            if self._value(ERROR_HISTORY, 0) == 0:
                for sub in self._compound(ERROR_HISTORY).subindices:
                    if sub:
                        self._store(ERROR_HISTORY, sub, 0)

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

    def _pdo_tables(self) -> _PdoTables:
        """The valid PDOs, read from the OD (cached until a PDO object is written)."""
        if self._tables is None:
            tables = _PdoTables()
            for number in range(1, PDO_SLOTS + 1):
                rpdo = self._read_pdo(RPDO_COMM + number - 1, RPDO_MAP + number - 1, number)
                if rpdo is not None:
                    tables.rpdos[rpdo.cob_id] = rpdo
                tpdo = self._read_pdo(TPDO_COMM + number - 1, TPDO_MAP + number - 1, number)
                if tpdo is not None:
                    tables.tpdos.append(tpdo)
                    self._tpdo_state.setdefault(number, _TpdoState())
            self._tables = tables
        return self._tables

    def _read_pdo(self, comm: int, mapping: int, number: int) -> _Pdo | None:
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
        pdo = _Pdo(number, cob & 0x7FF, transmission, entries)
        if comm >= TPDO_COMM:
            if 3 in comm_record:
                pdo.inhibit_ns = self._value(comm, 3) * 100_000  # 100 us units
            if 5 in comm_record:
                pdo.event_ns = self._value(comm, 5) * MS  # ms (CiA 301; manual says 0.1 ms: A7)
        return pdo

    # ------------------------------------------------------------------ PDO traffic

    def _on_rpdo_frame(self, pdo: _Pdo, data: bytes) -> None:
        if len(data) < pdo.nbytes:
            log.debug("%s: RPDO %d with %d bytes, %d mapped: ignored", self.name, pdo.number, len(data), pdo.nbytes)
            return
        if pdo.transmission <= SYNC_CYCLIC_LAST:
            self._sync_rpdos[pdo.number] = (pdo, data)  # applied at the next SYNC
            return
        self._apply_rpdo(pdo, data)

    def _apply_rpdo(self, pdo: _Pdo, data: bytes) -> None:
        frame = int.from_bytes(data, "little")
        offset = 0
        for index, subindex, bits in pdo.entries:
            value = (frame >> offset) & ((1 << bits) - 1)
            offset += bits
            try:
                self.node.set_data(index, subindex, value.to_bytes((bits + 7) // 8, "little"))
            except SdoAbortedError as exc:
                # A PDO has no answer: the device keeps its value (an SDO would abort)
                log.debug(
                    "%s: RPDO %d entry %04X:%02X refused (0x%08X)", self.name, pdo.number, index, subindex, exc.code
                )
        self.on_rpdo(pdo.number)

    def _pack_tpdo(self, pdo: _Pdo) -> bytes:
        frame = 0
        offset = 0
        for index, subindex, bits in pdo.entries:
            try:
                raw = self.node.get_data(index, subindex)
            except SdoAbortedError:
                raw = b""
            frame |= (int.from_bytes(raw, "little") & ((1 << bits) - 1)) << offset
            offset += bits
        return frame.to_bytes(pdo.nbytes, "little")

    def _send_tpdo(self, pdo: _Pdo, data: bytes, now: int) -> None:
        state = self._tpdo_state.setdefault(pdo.number, _TpdoState())
        self._send(pdo.cob_id, data)
        state.last_data = data
        state.last_sent_ns = now
        state.pending = False

    def _transmit_event_tpdos(self, now: int) -> None:
        """Types 254/255: on change of the packed data, after the inhibit time,
        and every event-timer period even without change."""
        for pdo in self._pdo_tables().tpdos:
            if pdo.transmission not in EVENT_TYPES:
                continue
            state = self._tpdo_state.setdefault(pdo.number, _TpdoState())
            data = self._pack_tpdo(pdo)
            since = None if state.last_sent_ns is None else now - state.last_sent_ns
            event_due = pdo.event_ns and since is not None and since >= pdo.event_ns
            if not (state.pending or data != state.last_data or event_due):
                continue
            if since is not None and since < pdo.inhibit_ns:
                continue  # sent once the inhibit time is over
            self._send_tpdo(pdo, data, now)

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
            state = self._tpdo_state.setdefault(pdo.number, _TpdoState())
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
            state = self._tpdo_state.setdefault(pdo.number, _TpdoState())
            state.pending = True
            state.sync_count = 0
        self._transmit_event_tpdos(self._clock_ns())

    def _sync_cob_id(self) -> int:
        return (self._value(SYNC_COB_ID, 0) & 0x7FF) if SYNC_COB_ID in self.od else COB_SYNC

    # ------------------------------------------------------------------ OD storage

    def _variable_or_none(self, index: int, subindex: int) -> ODVariable | None:
        obj = self.od.get(index)
        if obj is None:
            return None
        if isinstance(obj, ODVariable):
            return obj if subindex == 0 else None
        return obj.subindices.get(subindex)

    def _compound(self, index: int) -> ODRecord | ODArray:
        """A RECORD or ARRAY object (PDO parameters, the error history)."""
        obj = self.od[index]
        if isinstance(obj, ODVariable):
            raise TypeError(
                f"{self.name}: object 0x{index:04X} is a VAR in the EDS; CiA 301 makes it a RECORD or ARRAY"
            )
        return obj

    def _variable(self, index: int, subindex: int) -> ODVariable:
        var = self._variable_or_none(index, subindex)
        if var is None:
            raise KeyError(f"{self.name}: no object 0x{index:04X}:{subindex:02X} in the object dictionary")
        return var

    def _value(self, index: int, subindex: int) -> int:
        """A numeric object's current value, for the slave's own use."""
        data = self.node.get_data(index, subindex)
        return int.from_bytes(data, "little")

    def _store(self, index: int, subindex: int, value: int) -> None:
        """Set a value directly, past every callback (error register, history, PKW response)."""
        var = self._variable(index, subindex)
        self.node.data_store.setdefault(index, {})[subindex] = var.encode_raw(value)

    def _clear_stored(self, first: int, last: int) -> None:
        """Back to the EDS values for the objects first..last."""
        for index in [i for i in self.node.data_store if first <= i <= last]:
            del self.node.data_store[index]

    def _push_error_history(self, error_code: int) -> None:
        """0x1003: newest first, as many entries as the EDS gives; bits 16-23
        additional information, all 0 (manual 001 §4)."""
        obj = self.od.get(ERROR_HISTORY)
        if obj is None:
            return
        subs = sorted(s for s in obj.subindices if s)
        count = min(self._value(ERROR_HISTORY, 0), len(subs))
        history = [error_code & 0xFFFF] + [self._value(ERROR_HISTORY, s) for s in subs[:count]]
        history = history[: len(subs)]
        for sub, value in zip(subs, history):
            self._store(ERROR_HISTORY, sub, value)
        self._store(ERROR_HISTORY, 0, len(history))
