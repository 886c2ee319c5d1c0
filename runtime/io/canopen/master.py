"""The CANopen master: a driver (plugin/driver.py) that boots the configured nodes
as a CANopen manager does, maps their PDOs into the process image every
cycle, produces heartbeat and SYNC, watches the nodes' heartbeats and
emergencies, and serves READ_VAR / WRITE_VAR over SDO.

Threads (real time): the endpoint's receive thread hands frames to
_on_frame; a service thread (service(), every millisecond) sends what is
due (heartbeat, SYNC, RPDOs) and moves the node state machines on; one
worker thread runs every SDO transfer (sdo_exchange.SdoWorker). The scan
thread only swaps buffers in read_inputs / write_outputs. In virtual time
the engine's thread does the receiving, the servicing and the SDO jobs in
advance_to() (no thread, no wait: sdo.SdoWorker), so runs repeat exactly.

Nothing in here knows a device: an LTMR, an FC 280 or any node with an EDS
is just a NodeConfig. Plain-CAN devices (the MPU2-S) can share the bus
through the same CanEndpoint (add_handler), which this driver exposes.
"""

from __future__ import annotations

import logging
import threading
from typing import TYPE_CHECKING

import can
import canopen

from ...engine.clock import PeriodicService
from ...image.memory import ProcessImage
from ...plugin.driver import Driver, DriverError, DriverStatus
from ...plugin.registry import registry
from ..can.bus import BusSettings, CanEndpoint, open_bus
from ..can.port import CanPort
from .cia301 import (
    COB_ID_INVALID,
    COB_NMT,
    COB_SYNC,
    CONSUMER_HEARTBEAT,
    GUARD_TIME,
    LIFE_TIME_FACTOR,
    NMT_RESET_COMMUNICATION,
    NMT_START,
    PRODUCER_HEARTBEAT,
    STATE_OPERATIONAL,
    cob_emcy,
    cob_heartbeat,
    restricted_cob_id,
)
from .emcy_log import EmcyLog, EmcyText
from .node import Emergency, NodeState, NodeSupervisor
from .pdo import PdoBinding, TxSchedule, default_cob_id
from .sdo import SERVICE as SDO_SERVICE
from .sdo import SchneiderSdoService, SdoJob, SdoWorker

if TYPE_CHECKING:
    from .diag import CanopenDiag

log = logging.getLogger(__name__)


class _EndpointNetwork(canopen.Network):
    """canopen's Network, sending through our endpoint (so an unplugged or
    failed bus is handled in one place) instead of owning a bus."""

    def __init__(self, endpoint: CanEndpoint) -> None:
        super().__init__(bus=None)
        self.endpoint = endpoint

    def send_message(self, can_id: int, data: bytes, remote: bool = False) -> None:
        if not self.endpoint.send(can_id, bytes(data), remote=remote):
            # canopen's SDO client then waits for its timeout, as on a real bus
            log.debug("frame 0x%03X not sent: %s", can_id, self.endpoint.last_error or "unplugged")


class _Node:
    """What the master keeps per configured node."""

    def __init__(
        self,
        cfg,
        od,
        supervisor: NodeSupervisor,
        tpdos: list,
        rpdos: list,
        sdo_writes: list,
        emcy_text: EmcyText | None = None,
    ) -> None:
        self.cfg = cfg
        self.od = od
        self.sup = supervisor
        self.tpdos: list[PdoBinding] = tpdos
        self.rpdos: list[tuple[PdoBinding, TxSchedule]] = rpdos
        self.sdo_writes = sdo_writes  # (index, subindex, bytes, key)
        self.emcy_text = emcy_text  # its device's words for an EMCY, if the device has them


class CanopenDriver(Driver):
    name = "canopen"

    def __init__(
        self,
        config,
        settings: BusSettings,
        *,
        clock,
        pump=None,
        addressing: str = "iec",
        image_size: int | None = None,
        port: CanPort | None = None,
    ) -> None:
        """config: a CanopenConfig (config.py); settings: its bus's.
        DriverError (naming the config key) for a node that cannot work:
        an EDS that does not load, a PDO entry the EDS does not have ..."""
        self.config = config
        self.settings = settings
        self.clock = clock
        self.pump = pump
        # the PLC's connection to the bus, shared with the other protocols on it
        self.port = port if port is not None else CanPort(settings, pump)
        self.node_id = config.node_id
        probe = ProcessImage(addressing) if image_size is None else ProcessImage(addressing, image_size)
        self.nodes: dict[int, _Node] = {}
        for ncfg in config.nodes:
            self.nodes[ncfg.node_id] = self._prepare(ncfg, probe)
        self._by_heartbeat = {cob_heartbeat(n): node for n, node in self.nodes.items()}
        self._by_emcy = {cob_emcy(n): node for n, node in self.nodes.items()}
        self._lock = threading.RLock()
        self._tpdo_by_cob: dict[int, PdoBinding] = {}
        self._rx_fresh: dict[PdoBinding, bytes] = {}
        self._tx_data: dict[PdoBinding, bytes] = {}
        self._next_heartbeat_ns = 0
        self._next_sync_ns = 0
        self._next_reopen_ns = 0
        self._bus_ok = False
        self._bus_error = ""
        self._started = False
        self.endpoint: CanEndpoint | None = None
        self.network: _EndpointNetwork | None = None
        self.worker: SdoWorker | None = None
        self._service: PeriodicService | None = None
        self.sdo_service = SchneiderSdoService(
            self._submit_exchange,
            default_timeout_s=config.sdo_timeout_ms / 1000,
            object_size=self._object_size,
            available=lambda: self._bus_ok,
        )
        self.services = {SDO_SERVICE: self.sdo_service}
        self.rx_short = 0  # TPDOs shorter than their mapping (dropped)
        self._emcy_log = EmcyLog()
        self._diag: CanopenDiag | None = None

    def _prepare(self, ncfg, probe: ProcessImage) -> _Node:
        try:
            od = canopen.import_od(str(ncfg.eds), ncfg.node_id)
        except Exception as exc:
            raise DriverError(f"{ncfg.key}.eds: cannot load {ncfg.eds}: {exc}") from None
        c = self.config
        sup = NodeSupervisor(
            ncfg.name,
            ncfg.node_id,
            mandatory=ncfg.mandatory,
            heartbeat_timeout_ns=ncfg.heartbeat_timeout_ms * 1_000_000,
            boot_timeout_ns=c.boot_timeout_ms * 1_000_000,
            retry_ns=c.retry_ms * 1_000_000,
            guard_ns=ncfg.guard_time_ms * 1_000_000,
            life_time_factor=ncfg.life_time_factor,
        )
        if ncfg.master_timeout_ms and ncfg.master_timeout_explicit and od.get_variable(CONSUMER_HEARTBEAT, 1) is None:
            raise DriverError(
                f"{ncfg.key}.master_timeout: the node has no heartbeat consumer (no 1016h in its EDS): it cannot "
                "watch the master's heartbeat; watch it with node guarding (guard_time) instead"
            )
        tpdos = [PdoBinding.from_config(p, "tpdo", od, probe) for p in ncfg.tpdo]
        rpdos = [
            (b, TxSchedule(b.transmission, b.inhibit_us, b.event_ms))
            for b in (PdoBinding.from_config(p, "rpdo", od, probe) for p in ncfg.rpdo)
        ]
        writes = []
        for w in ncfg.sdo:
            size = w.size
            var = od.get_variable(w.index, w.subindex)
            if size is None:
                if var is None or not var.fixed_size:
                    raise DriverError(
                        f"{w.key}: {w.index:04X}:{w.subindex:02X} is not in the EDS; give its "
                        "size in bytes (size = 1, 2 or 4)"
                    )
                size = len(var) // 8
            if not 0 <= w.value < (1 << (8 * size)) and not -(1 << (8 * size - 1)) <= w.value < 0:
                raise DriverError(f"{w.key}: {w.value} does not fit in {size} byte(s)")
            writes.append((w.index, w.subindex, (w.value & ((1 << (8 * size)) - 1)).to_bytes(size, "little"), w.key))
        device = registry().device_with_name(ncfg.device) if ncfg.device else None
        return _Node(ncfg, od, sup, tpdos, rpdos, writes, device.emcy_text if device is not None else None)

    # ------------------------------------------------------------ life cycle

    def start(self) -> None:
        self.endpoint = self.port.acquire()
        self.network = _EndpointNetwork(self.endpoint)
        for node in self.nodes.values():
            self.network.add_node(canopen.RemoteNode(node.cfg.node_id, node.od))
        self.endpoint.add_handler(self._on_frame)
        self.worker = SdoWorker(self.network, pump=self.pump)  # virtual time: no thread
        self.worker.start()
        self._bus_ok = True
        self._started = True
        log.info(
            "canopen: master node %d on %s, %d node(s) configured",
            self.node_id,
            self.settings.describe(),
            len(self.nodes),
        )
        if not self.clock.virtual:
            self._service = PeriodicService("canopen service", self.clock, self.service, 0.001)
            self._service.start()

    def stop(self) -> None:
        if not self._started:
            return
        if self._service is not None:
            self._service.stop()
            self._service = None
        # The last write_outputs (the safe values) goes out before the bus closes.
        self._send_rpdos(self.clock.now_ns(), sync=False, force=True)
        worker = self._started_worker
        if self.pump is not None:
            self.pump.settle()
        worker.stop()
        self.port.release(self._on_frame)
        self._started = False

    # What start() makes and never clears: the bus side (the service, the
    # frame handler, the SDO worker's tasks) runs only once it has.

    @property
    def _started_endpoint(self) -> CanEndpoint:
        assert self.endpoint is not None, "the CANopen master is not started"
        return self.endpoint

    @property
    def _started_network(self) -> _EndpointNetwork:
        assert self.network is not None, "the CANopen master is not started"
        return self.network

    @property
    def _started_worker(self) -> SdoWorker:
        assert self.worker is not None, "the CANopen master is not started"
        return self.worker

    def advance_to(self, now_ns: int) -> None:
        self.service(now_ns)
        if self.pump is not None:
            worker = self._started_worker
            endpoint = self._started_endpoint
            received = endpoint.received
            self.pump.settle()
            # the SDO jobs due, each pumping the bus for its answers
            if not worker.run_pending() and endpoint.received == received:
                # Nothing came in and no job ran: the state machines, the
                # timers and the outputs are as service() left them, so a
                # second service() would send nothing and the bus is quiet.
                return
            # What the settle delivered (boot-ups, finished configurations)
            # may call for frames now, not a tick later.
            self.service(now_ns)
            self.pump.settle()
            if worker.run_pending():
                self.service(now_ns)
                self.pump.settle()

    # ------------------------------------------------------------ the bus side

    def service(self, now_ns: int) -> None:
        """Send what is due and move the node state machines on."""
        with self._lock:
            c = self.config
            if not self._bus_ok:
                if now_ns < self._next_reopen_ns:
                    return
                self._reopen(now_ns)
            if c.heartbeat_ms and now_ns >= self._next_heartbeat_ns:
                self._next_heartbeat_ns = now_ns + c.heartbeat_ms * 1_000_000
                self._send(cob_heartbeat(self.node_id), bytes([STATE_OPERATIONAL]))
            sync = False
            if c.sync_us and now_ns >= self._next_sync_ns:
                self._next_sync_ns = now_ns + c.sync_us * 1000
                sync = True
            for node in self.nodes.values():
                sup = node.sup
                before = sup.state
                # tick() does nothing before its deadline (most steps): not called then
                if before == NodeState.UNKNOWN or (sup.deadline_ns is not None and now_ns >= sup.deadline_ns):
                    action = sup.tick(now_ns)
                    if sup.state != before and sup.state in (NodeState.MISSING, NodeState.LOST):
                        log.warning("canopen: node %s (%d): %s", node.cfg.name, node.cfg.node_id, sup.message)
                    self._act(node, action)
                if sup.guard_ns and sup.guard_due(now_ns):
                    self._send_remote(cob_heartbeat(node.cfg.node_id))
            self._send_rpdos(now_ns, sync=sync)
            if sync:
                self._send(COB_SYNC, b"")

    def _reopen(self, now_ns: int) -> None:
        """The bus failed: open it again (every retry time until it works)."""
        self._next_reopen_ns = now_ns + self.config.retry_ms * 1_000_000
        try:
            self._started_endpoint.reopen(open_bus(self.settings))
        except DriverError as exc:
            if exc.args[0] != self._bus_error:
                log.error("canopen: %s", exc)
            self._bus_error = exc.args[0]
            return
        log.warning("canopen: bus reopened (%s)", self.settings.describe())
        self._bus_ok = True
        self._bus_error = ""

    def _send(self, can_id: int, data: bytes, *, remote: bool = False) -> None:
        endpoint = self._started_endpoint
        if endpoint.send(can_id, data, remote=remote) or not endpoint.connected or not self._bus_ok:
            return
        log.error(
            "canopen: cannot send on %s: %s; reopening it every %d ms",
            self.settings.describe(),
            endpoint.last_error,
            self.config.retry_ms,
        )
        self._bus_ok = False
        self._bus_error = endpoint.last_error
        self._next_reopen_ns = self.clock.now_ns() + self.config.retry_ms * 1_000_000

    def _send_remote(self, can_id: int) -> None:
        """A remote frame (RTR): a node-guarding request."""
        self._send(can_id, b"", remote=True)

    def _send_rpdos(self, now_ns: int, *, sync: bool, force: bool = False) -> None:
        with self._lock:
            for node in self.nodes.values():
                if node.sup.state != NodeState.OPERATIONAL:
                    continue
                for binding, schedule in node.rpdos:
                    data = self._tx_data.get(binding)
                    if data is None or binding.cob_id is None:
                        continue
                    if force and data == schedule.last_sent:
                        continue
                    if force or schedule.due(data, now_ns, sync):
                        self._send(binding.cob_id, data)
                        schedule.sent(data, now_ns)

    def _on_frame(self, msg: can.Message) -> None:
        """Every received frame (receive thread, or the pump in virtual time)."""
        can_id, data = msg.arbitration_id, bytes(msg.data)
        now = self.clock.now_ns()
        with self._lock:
            binding = self._tpdo_by_cob.get(can_id)
            if binding is not None:
                if len(data) < binding.nbytes:
                    self.rx_short += 1
                else:
                    self._rx_fresh[binding] = data
            elif can_id in self._by_heartbeat and data and not msg.is_remote_frame:
                node = self._by_heartbeat[can_id]
                if node.sup.guard_ns and data[0] & 0x7F:  # a guarding reply (a boot-up is 00)
                    self._act(node, node.sup.guard_reply(data[0], now))
                else:
                    self._act(node, node.sup.heartbeat(data[0], now))
            elif can_id in self._by_emcy and data:
                node = self._by_emcy[can_id]
                padded = data + bytes(8 - len(data))
                emcy = Emergency(int.from_bytes(padded[0:2], "little"), padded[2], padded[3:8], now)
                node.sup.emergency(emcy)
                self._emcy_log.emergency(
                    node.cfg.name, node.cfg.node_id, emcy.code, emcy.register, emcy.data, now, node.emcy_text
                )
        self._started_network.notify(can_id, msg.data, msg.timestamp)

    def _act(self, node: _Node, action: str | None) -> None:
        """Carry out what a node's state machine asked for (lock held)."""
        if action is None:
            return
        nid = node.cfg.node_id
        if action == "reset":
            log.info(
                "canopen: node %s (%d): reset communication%s",
                node.cfg.name,
                nid,
                f" ({node.sup.message})" if node.sup.message else "",
            )
            self._send(COB_NMT, bytes([NMT_RESET_COMMUNICATION, nid]))
        elif action == "configure":
            self._started_worker.submit_task(lambda: self._configure(node))
        elif action == "start":
            for _binding, schedule in node.rpdos:
                schedule.reset()
            self._send(COB_NMT, bytes([NMT_START, nid]))
            log.info("canopen: node %s (%d) operational", node.cfg.name, nid)

    # ------------------------------------------------------------ boot-time configuration (worker)

    def _configure(self, node: _Node) -> None:
        """The node booted: write its heartbeat, its SDO list and its PDOs,
        then read back the PDO COB-IDs. Runs in the SDO worker."""
        cfg = node.cfg
        timeout = self.config.sdo_timeout_ms / 1000
        steps = [(PRODUCER_HEARTBEAT, 0, cfg.heartbeat_ms.to_bytes(2, "little"), f"{cfg.key}.heartbeat")]
        if cfg.guard_time_ms:
            steps.append((GUARD_TIME, 0, cfg.guard_time_ms.to_bytes(2, "little"), f"{cfg.key}.guard_time"))
            steps.append((LIFE_TIME_FACTOR, 0, bytes([cfg.life_time_factor]), f"{cfg.key}.life_time_factor"))
        # a node without a heartbeat consumer (no 1016h) is not told the default
        if cfg.master_timeout_ms and node.od.get_variable(CONSUMER_HEARTBEAT, 1) is not None:
            value = (self.node_id << 16) | cfg.master_timeout_ms
            steps.append((CONSUMER_HEARTBEAT, 1, value.to_bytes(4, "little"), f"{cfg.key}.master_timeout"))
        steps.extend(node.sdo_writes)
        error = ""
        try:
            for index, sub, data, key in steps:
                self._sdo(node, index, sub, data, key, timeout)
            for binding in node.tpdos + [b for b, _s in node.rpdos]:
                self._configure_pdo(node, binding, timeout)
        except _ConfigFailed as exc:
            error = str(exc)
            log.error("canopen: node %s (%d): %s", cfg.name, cfg.node_id, error)
        now = self.clock.now_ns()
        with self._lock:
            if not error:
                self._tpdo_by_cob = {c: b for c, b in self._tpdo_by_cob.items() if b not in node.tpdos}
                self._tpdo_by_cob.update((b.cob_id, b) for b in node.tpdos if b.cob_id is not None)
            self._act(node, node.sup.configured(not error, error, now))

    def _sdo(self, node: _Node, index: int, sub: int, data: bytes | None, key: str, timeout: float) -> bytes:
        job = SdoJob(node.cfg.node_id, index, sub, data, timeout)
        self._started_worker.transfer(job)
        if job.error:
            raise _ConfigFailed(f"{key}: {job.error}")
        return job.received

    def _configure_pdo(self, node: _Node, b: PdoBinding, timeout: float) -> None:
        """CiA 301 PDO (re)mapping: invalidate, clear, write the entries, set
        their number, set the parameters, validate. configure = false only
        reads the COB-ID the node uses."""
        nid = node.cfg.node_id
        raw = self._sdo(node, b.comm_index, 1, None, f"{b.key}: read COB-ID", timeout)
        cob = int.from_bytes(raw[:4].ljust(4, b"\0"), "little")
        if not b.configure:
            if cob & COB_ID_INVALID:
                raise _ConfigFailed(
                    f"{b.key}: the node's {b.direction.upper()} {b.number} is not valid "
                    f"(COB-ID 0x{cob:08X}); set configure = true"
                )
            if restricted_cob_id(cob & 0x7FF):
                # taken as it is, NMT (0x000) or heartbeat frames would be read as
                # this TPDO, or this RPDO sent as them
                raise _ConfigFailed(
                    f"{b.key}: the node's {b.direction.upper()} {b.number} has COB-ID 0x{cob & 0x7FF:03X}, "
                    "which CiA 301 keeps for other services; set configure = true"
                )
            b.cob_id = cob & 0x7FF
            return
        if restricted_cob_id(cob & 0x7FF):  # 0 (none), or one no PDO may use
            cob = default_cob_id(b.direction, b.number, nid)
        cob_id = cob & 0x7FF
        what = f"{b.key}"
        self._sdo(node, b.comm_index, 1, (cob_id | COB_ID_INVALID).to_bytes(4, "little"), what, timeout)
        self._sdo(node, b.map_index, 0, b"\0", what, timeout)
        for i, e in enumerate(b.entries, start=1):
            self._sdo(node, b.map_index, i, e.mapping_value.to_bytes(4, "little"), e.key, timeout)
        self._sdo(node, b.map_index, 0, bytes([len(b.entries)]), what, timeout)
        self._sdo(node, b.comm_index, 2, bytes([b.transmission]), f"{b.key}.transmission", timeout)
        # A TPDO's inhibit time and event timer are written even when 0: a node's
        # own default may not be (the FC 280 inhibits its TPDOs for 30 ms,
        # manual 003 §4.1.4), and the configuration says what is wanted.
        comm = node.od.get(b.comm_index)
        tpdo = b.direction == "tpdo"
        if (tpdo or b.inhibit_us) and comm is not None and 3 in comm:
            self._sdo(node, b.comm_index, 3, (b.inhibit_us // 100).to_bytes(2, "little"), f"{b.key}.inhibit", timeout)
        if (tpdo or b.event_ms) and comm is not None and 5 in comm:
            self._sdo(node, b.comm_index, 5, b.event_ms.to_bytes(2, "little"), f"{b.key}.event", timeout)
        self._sdo(node, b.comm_index, 1, cob_id.to_bytes(4, "little"), what, timeout)
        b.cob_id = cob_id

    # ------------------------------------------------------------ READ_VAR / WRITE_VAR

    def _submit_exchange(self, job: SdoJob) -> None:
        self._started_worker.submit(job)

    def _object_size(self, node_id: int, index: int, subindex: int) -> int | None:
        node = self.nodes.get(node_id)
        var = node.od.get_variable(index, subindex) if node is not None else None
        return len(var) // 8 if var is not None and var.fixed_size else None

    # ------------------------------------------------------------ the scan side

    def bind_program(self, globals_obj) -> None:
        from .diag import CanopenDiag

        self._diag = CanopenDiag(globals_obj)

    def read_inputs(self, image: ProcessImage) -> None:
        with self._lock:
            fresh, self._rx_fresh = self._rx_fresh, {}
            snapshot = [(n.cfg.node_id, n.sup.version, n) for n in self.nodes.values()]
        for binding, data in fresh.items():
            binding.unpack(data, image)
        self.sdo_service.collect()
        if self._diag is not None:
            self._diag.update(snapshot, self._master_view())

    def _master_view(self) -> tuple:
        """CANOPEN_MASTER's fields, in diag.MASTER_FIELDS order."""
        ep = self.endpoint
        return (
            self._bus_ok,
            len(self.nodes),
            sum(n.sup.state == NodeState.OPERATIONAL for n in self.nodes.values()),
            ep.received if ep else 0,
            ep.sent if ep else 0,
            ep.send_errors if ep else 0,
        )

    def write_outputs(self, image: ProcessImage) -> None:
        packed = {binding: binding.pack(image) for node in self.nodes.values() for binding, _s in node.rpdos}
        with self._lock:
            self._tx_data.update(packed)

    def status(self) -> DriverStatus:
        if not self._bus_ok:
            return DriverStatus(False, f"canopen: bus down ({self._bus_error})")
        bad = [n for n in self.nodes.values() if n.cfg.mandatory and n.sup.state != NodeState.OPERATIONAL]
        up = sum(n.sup.state == NodeState.OPERATIONAL for n in self.nodes.values())
        if bad:
            n = bad[0]
            why = n.sup.message or n.sup.state.name.lower()
            return DriverStatus(False, f"canopen: {up}/{len(self.nodes)} up; {n.cfg.name} ({n.cfg.node_id}): {why}")
        return DriverStatus(True, f"canopen: {up}/{len(self.nodes)} up")

    def node_state(self, node_id: int) -> NodeState:
        return self.nodes[node_id].sup.state


class _ConfigFailed(Exception):
    pass
