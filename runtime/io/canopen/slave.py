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
    pdo_source(index, sub)        a cheap reader of a live object for TPDO packing,
                                  which runs at every step (None: object_read)
    on_state_change(old, new), on_reset_application(), on_reset_communication(),
    on_comm_error(), on_comm_restored(), on_rpdo(number)

The PDO machinery (parameters, write rules, traffic, SYNC) is slave_pdo.py's,
with the choices it makes where CiA 301 leaves room; error control (heartbeat
producer and consumer, node and life guarding) is slave_errors.py's.
"""

from __future__ import annotations

import logging
import threading
from collections import deque
from collections.abc import Callable

import can
import canopen
from canopen.objectdictionary import ODArray, ODRecord, ODVariable
from canopen.sdo import SdoAbortedError

from ...plugin.seams import SimFault
from ...sim.base import SimulatedDevice
from ..can.bus import BusPump, BusSettings, CanEndpoint, open_bus
from ..ratelog import RateLimitedLog
from .cia301 import (
    ABORT_BAD_COMMAND,
    ABORT_NO_SUBINDEX,
    ABORT_VALUE_RANGE,
    COB_NMT,
    CONSUMER_HEARTBEAT,
    NMT_PRE_OPERATIONAL,
    NMT_RESET_COMMUNICATION,
    NMT_RESET_NODE,
    NMT_START,
    NMT_STOP,
    PRODUCER_HEARTBEAT,
    RPDO_COMM,
    RPDO_MAP,
    STATE_BOOTUP,
    STATE_OPERATIONAL,
    STATE_PRE_OPERATIONAL,
    STATE_STOPPED,
    TPDO_COMM,
    TPDO_MAP,
    cob_heartbeat,
    cob_sdo_rx,
    cob_sdo_tx,
)
from .library_log import route_library_log
from .slave_emcy import EMCY_RECORDS, ERROR_HISTORY, EmcyMixin
from .slave_errors import ERROR_BEHAVIOUR, ERROR_TO_STOPPED, ErrorControlMixin
from .slave_pdo import PDO_SLOTS, PdoMixin, PdoTables, TpdoState

log = logging.getLogger(__name__)

MS = 1_000_000

# CiA 301 object dictionary areas and objects
COMMUNICATION_AREA = (0x1000, 0x1FFF)
APPLICATION_AREA = (0x2000, 0x9FFF)

#: every simulated CANopen slave takes it (SimulatedCanopenSlave.inject)
UNPLUG = SimFault("unplug", "the node's cable out: it neither sends nor receives (a lost node)", lasting=True)


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


class SimulatedCanopenSlave(EmcyMixin, ErrorControlMixin, PdoMixin, SimulatedDevice):
    """See the module docstring."""

    pump: BusPump | None  # a CAN node: its endpoint is on the bus's pump (virtual time)
    #: the device's words for an EMCY (Device.emcy_text), for its records
    emcy_text: Callable[[int, int, bytes], str] | None = None

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
        self._sdo_read_callback = self._on_sdo_read  # one bound method: PDO packing knows it by identity
        self.node.add_read_callback(self._sdo_read_callback)
        self.node.add_write_callback(self._on_sdo_write)
        self.endpoint: CanEndpoint | None = None
        self.network: _SlaveNetwork | None = None
        self._lock = threading.RLock()
        self._state = STATE_BOOTUP
        self._now = 0
        self._local_writes = 0  # > 0 while write() runs: the device's own access
        self._tables: PdoTables | None = None
        self._tpdo_state: dict[int, TpdoState] = {}
        self._sync_rpdos: dict[int, tuple] = {}  # RPDO number -> (pdo, data) waiting for SYNC
        self._init_error_control()
        self._written: list[int] = []  # objects written, for _flush_writes
        self._cached: dict[tuple[int, int], int] = {}  # _cached_value: stored values read every tick
        self.malformed = 0  # SDO requests refused: not 8 bytes (dropped), a segment out of sequence (aborted)
        self.lines = RateLimitedLog(log, clock.now_ns, burst=3)  # what it logs, rate limited
        #: the EMCYs it sent, the newest EMCY_RECORDS (records(): --final-json)
        self.emcys_sent: deque[dict] = deque(maxlen=EMCY_RECORDS)

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

    def pdo_source(self, index: int, subindex: int) -> Callable[[], int] | None:
        """For a TPDO's packing, which runs at every service step: a function
        of no arguments giving the object's present value as object_read
        would (an int; the packing keeps its mapped bits), or None to read it
        through object_read and the store. Only for an object whose value
        never comes from the store and whose read is never refused."""
        return None

    def on_state_change(self, old: int, new: int) -> None:
        """The NMT state changed (STATE_* of devices.cia301)."""

    def on_reset_application(self) -> None:
        """NMT reset node or a power cycle: the application restarts. By default
        the application area (0x2000-0x9FFF) goes back to its EDS values."""
        self._clear_stored(*APPLICATION_AREA)

    def on_reset_communication(self) -> None:
        """The communication area (0x1000-0x1FFF) has just gone back to its EDS
        values (reset communication, reset node, power-up). A device that keeps
        communication parameters in non-volatile memory (0x1010) puts them back
        here (_store), before heartbeat, guarding and PDOs are set up from them."""

    def on_comm_error(self) -> None:
        """A watched heartbeat producer fell silent, or the master stopped
        guarding the node (life guarding), before the 0x1029 state change."""

    def on_comm_restored(self) -> None:
        """Heartbeats from every lost producer came back, or guarding did."""

    def on_rpdo(self, number: int) -> None:
        """RPDO `number` was received in Operational and its data stored."""

    # ------------------------------------------------------------------ life cycle

    def open(self) -> None:
        route_library_log()  # canopen's own log lines (its SDO server's): through ours, rate limited
        with self._lock:
            self.endpoint = CanEndpoint(open_bus(self.settings), name=self.name, pump=self.pump)
            self.network = _SlaveNetwork(self.endpoint)
            self.node.associate_network(self.network)
            self.endpoint.add_handler(self._on_frame)
            self.endpoint.start()
            self._boot(self._clock_ns(), application=True)

    def close(self) -> None:
        # The endpoint is stopped outside the lock: in real time stop() joins
        # the receive thread, which may be waiting for the lock in _on_frame
        # (the join then timed out after 1 s, and the stop took that long).
        with self._lock:
            endpoint = self.endpoint
            self._state = STATE_BOOTUP
        if endpoint is not None:
            endpoint.stop()

    def service(self, now_ns: int) -> None:
        with self._lock:
            self._now = max(self._now, now_ns)
            self.run_device(now_ns)
            if self._state == STATE_BOOTUP:
                return
            self._error_control(now_ns)
            if self._state == STATE_OPERATIONAL:
                self._transmit_event_tpdos(now_ns)

    # ------------------------------------------------------------------ test and operator API

    @property
    def nmt_state(self) -> int:
        return self._state

    def unplug(self) -> None:
        """Cut the cable: frames are dropped both ways until plug()."""
        self._opened_endpoint().connected = False

    def plug(self) -> None:
        self._opened_endpoint().connected = True

    def inject(self, fault: str, value, on: bool) -> None:
        """A fault from [[sim]] faults or a test (Device.sim_faults): UNPLUG
        here; a device's own in its subclass, which hands the rest to this."""
        if fault != UNPLUG.name:
            raise ValueError(f"{self.name}: no fault {fault!r}")
        if on:
            self.unplug()
        else:
            self.plug()

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

    def mark_changed(self, index: int, subindex: int) -> None:
        """Send the TPDOs that map this object at their next opportunity, even if
        the packed data happen to be the same as last time."""
        with self._lock:
            for pdo in self._pdo_tables().tpdos:
                if any(i == index and s == subindex for i, s, _b in pdo.entries):
                    self._tpdo_state.setdefault(pdo.number, TpdoState()).pending = True

    # ------------------------------------------------------------------ NMT (CiA 301)

    def _boot(self, now: int, *, application: bool) -> None:
        """Initialisation: (reset application,) reset communication, boot-up
        frame, pre-operational."""
        pending = self._error_outlives_reset(application)
        self._set_state(STATE_BOOTUP)
        if application:
            self.on_reset_application()
        self._clear_stored(*COMMUNICATION_AREA)
        self.on_reset_communication()
        self.node.sdo._buffer = None  # a segmented transfer in progress is gone
        self._tables = None
        self._tpdo_state.clear()
        self._sync_rpdos.clear()
        self._send(cob_heartbeat(self.node_id), bytes([STATE_BOOTUP]))
        self._restart_error_control(now, pending)
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

    # ------------------------------------------------------------------ frames

    def _on_frame(self, msg: can.Message) -> None:
        can_id, data = msg.arbitration_id, bytes(msg.data)
        with self._lock:
            now = self._clock_ns()
            if self._state == STATE_BOOTUP:
                return
            if msg.is_remote_frame:  # RTR: node guarding only (no RTR-requested PDOs)
                if can_id == cob_heartbeat(self.node_id):
                    self._on_guarding_request(now)
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
            if can_id != cob_sdo_rx(self.node_id):
                return  # not for this node
            if not self._on_sdo_request(msg):
                return
            self._flush_writes(now)
            if self._state == STATE_OPERATIONAL:
                self._transmit_event_tpdos(now)  # an SDO write may have changed mapped data

    def _on_sdo_request(self, msg: can.Message) -> bool:
        """One request to canopen's SDO server; False when it was refused
        before reaching it."""
        data = bytes(msg.data)
        if len(data) != 8:
            # an SDO frame has 8 bytes (CiA 301); canopen's server fails on a
            # shorter one
            self.malformed += 1
            self.lines.warning(
                "malformed", "%s: SDO request [%s] dropped: %d bytes, not 8", self.name, data.hex(" "), len(data)
            )
            return False
        assert self.network is not None  # open() made it before adding this handler
        server = self.node.sdo
        # A segment (upload 0x60, download 0x00) before any segmented transfer
        # began: canopen's server fails on its missing buffer (and, before any
        # request at all, on the index it has not got to abort with), logging a
        # traceback. Such a request gets the abort a device sends for an
        # unknown request code, here.
        if data[0] & 0xE0 in (0x00, 0x60) and server._buffer is None:
            self.malformed += 1
            self.lines.warning(
                "malformed", "%s: SDO segment [%s] outside a transfer: aborted", self.name, data.hex(" ")
            )
            where = (server._index or 0).to_bytes(2, "little") + bytes([server._subindex or 0])
            self._send(cob_sdo_tx(self.node_id), bytes([0x80]) + where + ABORT_BAD_COMMAND.to_bytes(4, "little"))
            return True
        self.network.notify(msg.arbitration_id, msg.data, msg.timestamp)
        return True

    def _send(self, can_id: int, data: bytes) -> None:
        if self.endpoint is not None:
            self.endpoint.send(can_id, data)

    def _clock_ns(self) -> int:
        self._now = max(self._now, self.clock.now_ns())
        return self._now

    # ------------------------------------------------------------------ SDO access rules

    def _own_read_callback(self) -> Callable | None:
        return self._sdo_read_callback

    def _device_object_read(self) -> Callable:
        return self.object_read

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
        if written:
            self._forget_cached()
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

    def _cached_value(self, index: int, subindex: int) -> int:
        """_value of a communication object the slave reads at every step or
        frame (SYNC COB-ID, heartbeat time, guard time): kept until the next
        write (SDO, PDO, write(), _store) or reset of the store."""
        key = (index, subindex)
        value = self._cached.get(key)
        if value is None:
            value = self._cached[key] = self._value(index, subindex)
        return value

    def _store(self, index: int, subindex: int, value: int) -> None:
        """Set a value directly, past every callback (error register, history, PKW response)."""
        var = self._variable(index, subindex)
        self.node.data_store.setdefault(index, {})[subindex] = var.encode_raw(value)
        self._forget_cached()

    def _forget_cached(self) -> None:
        """An object changed: the cached values go, and error control looks
        again at its next step (a heartbeat or guard time may be new)."""
        self._cached.clear()
        self._error_quiet_until = 0

    def _clear_stored(self, first: int, last: int) -> None:
        """Back to the EDS values for the objects first..last."""
        for index in [i for i in self.node.data_store if first <= i <= last]:
            del self.node.data_store[index]
        self._forget_cached()
