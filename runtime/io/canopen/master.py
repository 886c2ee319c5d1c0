"""The CANopen master: a driver (plugin/driver.py) that boots the configured nodes
as a CANopen manager does, maps their PDOs into the process image every
cycle, produces heartbeat and SYNC, watches the nodes' heartbeats and
emergencies, and serves READ_VAR / WRITE_VAR over SDO.

Threads (real time): the endpoint's receive thread hands frames to
_on_frame; a service thread (service(), every millisecond) sends what is
due (heartbeat, SYNC, RPDOs) and moves the node state machines on; one
worker thread runs every SDO transfer (sdo_exchange.SdoWorker). In virtual
time the engine's thread does the receiving, the servicing and the SDO jobs
in advance_to() (no thread, no wait: sdo.SdoWorker), so runs repeat exactly.

The scan thread never waits behind supervision (issue 31). Three locks:
  _lock    supervision: the node state machines and the TPDO table; the
           scan never takes it. Frames decided under it go to an outbox
           (io/can/outbox.py), sent once it is released, in the order
           decided, by one thread at a time: no one waits behind a send
           but the sender.
  _io      the scan's: the TPDO data received, the RPDO data to send and
           the nodes' views (views.py, swapped in whole by _publish); held
           only for a copy, never across a send, a wait or a log line.
read_inputs / write_outputs / status / details take nothing but _io.

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
from ..can.bus import BusSettings, CanEndpoint
from ..can.outbox import Outbox
from ..can.port import CanPort
from ..ratelog import RateLimitedLog
from .boot import ConfigFailed, boot_steps, configure_node
from .cia301 import (
    COB_NMT,
    COB_SYNC,
    CONSUMER_HEARTBEAT,
    NMT_RESET_COMMUNICATION,
    NMT_START,
    STATE_OPERATIONAL,
    cob_emcy,
    cob_heartbeat,
    cob_sdo_tx,
)
from .emcy_log import EmcyLog, EmcyText
from .library_log import route_library_log
from .node import Emergency, NodeState, NodeSupervisor
from .pdo import PdoBinding, TxSchedule
from .sdo import SERVICE as SDO_SERVICE
from .sdo import SchneiderSdoService, SdoJob, SdoWorker
from .views import NodeView, node_details, nodes_status, view_of

if TYPE_CHECKING:
    from .diag import CanopenDiag

log = logging.getLogger(__name__)


#: the most lines per node and kind of event (reset, operational, lost ...) in the log per 10 s
EVENT_BURST = 3
SERVICE_PERIOD_S = 0.02  # real time: the service thread's longest wait (_service_period_s)


class _EndpointNetwork(canopen.Network):
    """canopen's Network, sending through our endpoint (so an unplugged or
    failed bus is handled in one place) instead of owning a bus."""

    def __init__(self, endpoint: CanEndpoint, lines: RateLimitedLog) -> None:
        super().__init__(bus=None)
        self.endpoint = endpoint
        self.lines = lines

    def send_message(self, can_id: int, data: bytes | bytearray, remote: bool = False) -> None:
        # canopen declares bytes, but its SDO client hands over a bytearray
        if not self.endpoint.send(can_id, bytes(data), remote=remote):
            # canopen's SDO client then waits for its timeout, as on a real bus
            self.lines.debug("not sent", "frame 0x%03X not sent: %s", can_id, self.endpoint.last_error or "unplugged")


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
        self.port = port if port is not None else CanPort(settings, pump, clock=clock)
        self.node_id = config.node_id
        probe = ProcessImage(addressing) if image_size is None else ProcessImage(addressing, image_size)
        self.nodes: dict[int, _Node] = {}
        for ncfg in config.nodes:
            self.nodes[ncfg.node_id] = self._prepare(ncfg, probe)
        self._by_heartbeat = {cob_heartbeat(n): node for n, node in self.nodes.items()}
        self._by_emcy = {cob_emcy(n): node for n, node in self.nodes.items()}
        self._lock = threading.RLock()  # supervision (see the module docstring)
        self._io = threading.Lock()  # the scan's buffers and views: held for a copy only
        self._outbox = Outbox(self._put)  # (COB-ID, data, remote) decided under _lock, not yet sent
        self._node_list = tuple(self.nodes.values())
        self._rpdo_bindings = tuple(binding for node in self._node_list for binding, _s in node.rpdos)
        self._views: tuple[NodeView, ...] = tuple(view_of(n.sup, n.cfg.mandatory) for n in self._node_list)
        self._operational = sum(v.operational for v in self._views)  # of _views: CANOPEN_MASTER's count
        self._tpdo_by_cob: dict[int, PdoBinding] = {}
        self._tpdo_node: dict[int, _Node] = {}  # COB-ID -> the node whose TPDO it is
        self._rx_fresh: dict[PdoBinding, bytes] = {}
        self._tx_data: dict[PdoBinding, bytes] = {}
        self._next_heartbeat_ns = 0
        self._next_sync_ns = 0
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
        self.malformed = 0  # frames dropped as malformed: short TPDOs, EMCYs, heartbeats, SDO answers
        # what the master logs: events (EVENT_BURST a node and kind per 10 s), frames (one a node per 10 s)
        self._log = RateLimitedLog(log, clock.now_ns, burst=EVENT_BURST)
        self._frames_log = RateLimitedLog(log, clock.now_ns)
        self._emcy_log = EmcyLog(clock=clock.now_ns)
        self._library_log: RateLimitedLog | None = None  # canopen's own lines (library_log.py), once started
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
        self._library_log = route_library_log(self.clock.now_ns)  # canopen's own lines: through ours, limited
        self.endpoint = self.port.acquire(self.clock.now_ns())  # the adapter may be missing: the port waits
        self.network = _EndpointNetwork(self.endpoint, self._log)
        for node in self.nodes.values():
            self.network.add_node(canopen.RemoteNode(node.cfg.node_id, node.od))
        self.endpoint.add_handler(self._on_frame)
        self.worker = SdoWorker(self.network, pump=self.pump)  # virtual time: no thread
        self.worker.start()
        self._started = True
        self._log.info(
            None,
            "canopen: master node %d on %s, %d node(s) configured",
            self.node_id,
            self.settings.describe(),
            len(self.nodes),
        )
        if not self.clock.virtual:
            self._service = PeriodicService("canopen service", self.clock, self.service, self._service_period_s())
            self._service.start()

    def _service_period_s(self) -> float:
        """At each idle of the scan (after its write_outputs: new RPDO data goes
        out then), and every 20 ms or SYNC period, if shorter, without one."""
        sync_s = self.config.sync_us / 1e6
        return min(SERVICE_PERIOD_S, sync_s) if sync_s else SERVICE_PERIOD_S

    def stop(self) -> None:
        if not self._started:
            return
        if self._service is not None:
            self._service.stop()
            self._service = None
        # The last write_outputs (the safe values) goes out before the bus closes.
        self._send_rpdos(self.clock.now_ns(), sync=False, force=True)
        self._outbox.flush()
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
        self._log.flush(now_ns)
        self._frames_log.flush(now_ns)
        self._emcy_log.flush(now_ns)
        if self._library_log is not None:
            self._library_log.flush(now_ns)
        if not self.port.try_open(now_ns):
            return  # the bus is down (the port opens it again with back-off)
        with self._lock:
            c = self.config
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
                        self._log.warning(
                            ("state", node.cfg.node_id),
                            "canopen: node %s (%d): %s",
                            node.cfg.name,
                            node.cfg.node_id,
                            sup.message,
                        )
                    self._act(node, action)
                if sup.guard_ns and sup.guard_due(now_ns):
                    self._send_remote(cob_heartbeat(node.cfg.node_id))
            self._send_rpdos(now_ns, sync=sync)
            if sync:
                self._send(COB_SYNC, b"")
            self._publish()
        self._outbox.flush()

    @property
    def _bus_ok(self) -> bool:
        """Started and the bus open (the port: shared with the other protocols on it)."""
        return self._started and self.port.is_open

    def _send(self, can_id: int, data: bytes, *, remote: bool = False) -> None:
        """A frame decided under _lock: into the outbox, sent by its flush once
        the lock is released."""
        self._outbox.add(can_id, data, remote)

    def _put(self, can_id: int, data: bytes, remote: bool) -> None:
        """One frame on the bus (no lock held but the outbox's)."""
        endpoint = self._started_endpoint
        if endpoint.send(can_id, data, remote=remote) or not endpoint.connected or not self._bus_ok:
            return
        self._log.error(
            "cannot send",
            "canopen: cannot send on %s: %s; opening it again with back-off",
            self.settings.describe(),
            endpoint.last_error,
        )
        self.port.failed(self.clock.now_ns(), endpoint.last_error)

    def _send_remote(self, can_id: int) -> None:
        """A remote frame (RTR): a node-guarding request."""
        self._send(can_id, b"", remote=True)

    def _send_rpdos(self, now_ns: int, *, sync: bool, force: bool = False) -> None:
        with self._io:
            tx_data = dict(self._tx_data)  # what the scan left to send
        with self._lock:
            for node in self.nodes.values():
                if node.sup.state != NodeState.OPERATIONAL:
                    continue
                for binding, schedule in node.rpdos:
                    data = tx_data.get(binding)
                    if data is None or binding.cob_id is None:
                        continue
                    if force and data == schedule.last_sent:
                        continue
                    if force or schedule.due(data, now_ns, sync):
                        self._send(binding.cob_id, data)
                        schedule.sent(data, now_ns)

    def _on_frame(self, msg: can.Message) -> None:
        """Every received frame (receive thread, or the pump in virtual time).
        A frame of the wrong length for what its CAN-ID carries (CiA 301: a
        heartbeat or guarding reply 1 byte, an EMCY and an SDO answer 8, a
        TPDO its mapping) is counted and dropped, never handed on."""
        if msg.is_remote_frame:
            return  # requests (node guarding): the nodes answer them, not the master
        can_id, data = msg.arbitration_id, bytes(msg.data)
        now = self.clock.now_ns()
        binding = self._tpdo_by_cob.get(can_id)  # a dict the worker swaps whole
        if binding is not None and len(data) >= binding.nbytes:
            with self._io:
                self._rx_fresh[binding] = data
            return
        sdo_answer = False
        with self._lock:
            try:
                sdo_answer = self._supervise(can_id, data, binding, now)
            finally:
                self._publish()
        self._outbox.flush()
        if sdo_answer:
            self._started_network.notify(can_id, msg.data, msg.timestamp)  # the SDO client's answer

    def _supervise(self, can_id: int, data: bytes, binding: PdoBinding | None, now: int) -> bool:
        """A received frame that is no good TPDO (_lock held): a short TPDO,
        a heartbeat or guarding reply, an EMCY; True for an SDO answer to
        hand to the SDO client."""
        if binding is not None:
            self.rx_short += 1
            self._malformed(self._tpdo_node.get(can_id), can_id, data, f"its mapping needs {binding.nbytes}")
            return False
        node = self._by_heartbeat.get(can_id)
        if node is not None:
            if len(data) != 1:
                self._malformed(node, can_id, data, "a heartbeat has 1")
            elif node.sup.guard_ns and data[0] & 0x7F:  # a guarding reply (a boot-up is 00)
                self._act(node, node.sup.guard_reply(data[0], now))
            else:
                self._act(node, node.sup.heartbeat(data[0], now))
            return False
        node = self._by_emcy.get(can_id)
        if node is not None:
            if len(data) != 8:
                self._malformed(node, can_id, data, "an EMCY has 8")
                return False
            emcy = Emergency(int.from_bytes(data[0:2], "little"), data[2], data[3:8], now)
            node.sup.emergency(emcy)
            self._emcy_log.emergency(
                node.cfg.name, node.cfg.node_id, emcy.code, emcy.register, emcy.data, node.emcy_text
            )
            return False
        if not cob_sdo_tx(1) <= can_id <= cob_sdo_tx(127):
            return False  # not the master's: SYNC, NMT, other PDOs ...
        if len(data) != 8:
            self._malformed(self.nodes.get(can_id - cob_sdo_tx(0)), can_id, data, "an SDO answer has 8")
            return False
        return True

    def _publish(self) -> None:
        """The nodes' views for the scan (views.py), swapped in whole when a
        supervisor changed (_lock held)."""
        views = self._views
        for view, node in zip(views, self._node_list):  # a loop, not all(): this runs at every service
            if view.version != node.sup.version:
                break
        else:
            return
        fresh = tuple(
            v if v.version == n.sup.version else view_of(n.sup, n.cfg.mandatory)
            for v, n in zip(views, self._node_list, strict=True)
        )
        with self._io:
            self._views = fresh
            self._operational = sum(v.operational for v in fresh)

    def _malformed(self, node: _Node | None, can_id: int, data: bytes, rule: str) -> None:
        """A frame of the wrong length: counted (on its node, if it is one of
        ours) and logged once per node every 10 s, with the count held back."""
        self.malformed += 1
        if node is not None:
            node.sup.malformed_frame()
            who = f"node {node.cfg.name} ({node.cfg.node_id})"
        else:
            who = "an unconfigured node"
        self._frames_log.warning(
            ("malformed", node.cfg.node_id if node is not None else None),
            "canopen: %s: frame 0x%03X [%s] dropped: %d bytes, %s",
            who,
            can_id,
            data.hex(" "),
            len(data),
            rule,
        )

    def _act(self, node: _Node, action: str | None) -> None:
        """Carry out what a node's state machine asked for (lock held)."""
        if action is None:
            return
        nid = node.cfg.node_id
        if action == "reset":
            self._log.info(
                ("reset", nid),
                "canopen: node %s (%d): reset communication%s",
                node.cfg.name,
                nid,
                f" ({node.sup.message})" if node.sup.message else "",
            )
            self._send(COB_NMT, bytes([NMT_RESET_COMMUNICATION, nid]))
        elif action == "configure":
            self._started_worker.submit_task(lambda: self._configure(node))
        elif action == "hold":  # booted BOOT_BURST times lately: the next boot waits
            self._log.warning(("hold", nid), "canopen: node %s (%d): %s", node.cfg.name, nid, node.sup.message)
        elif action == "start":
            for _binding, schedule in node.rpdos:
                schedule.reset()
            self._send(COB_NMT, bytes([NMT_START, nid]))
            self._log.info(("operational", nid), "canopen: node %s (%d) operational", node.cfg.name, nid)

    # ------------------------------------------------------------ boot-time configuration (worker)

    def _configure(self, node: _Node) -> None:
        """The node booted: write its heartbeat, its SDO list and its PDOs,
        then read back the PDO COB-IDs (boot.py). Runs in the SDO worker."""
        cfg = node.cfg
        steps = boot_steps(cfg, node.od, self.node_id) + node.sdo_writes
        bindings = node.tpdos + [b for b, _s in node.rpdos]
        error = ""
        try:
            configure_node(
                self._started_worker, cfg.node_id, node.od, steps, bindings, self.config.sdo_timeout_ms / 1000
            )
        except ConfigFailed as exc:
            error = str(exc)
            self._log.error(("configure", cfg.node_id), "canopen: node %s (%d): %s", cfg.name, cfg.node_id, error)
        now = self.clock.now_ns()
        with self._lock:
            if not error:
                by_cob = {c: b for c, b in self._tpdo_by_cob.items() if b not in node.tpdos}
                by_cob.update((b.cob_id, b) for b in node.tpdos if b.cob_id is not None)
                self._tpdo_by_cob = by_cob  # whole: the receive thread reads it without the lock
                self._tpdo_node.update((b.cob_id, node) for b in node.tpdos if b.cob_id is not None)
            self._act(node, node.sup.configured(not error, error, now))
            self._publish()
        self._outbox.flush()

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
        with self._io:
            fresh, self._rx_fresh = self._rx_fresh, {}
            views, operational = self._views, self._operational
        for binding, data in fresh.items():
            binding.unpack(data, image)
        self.sdo_service.collect()
        if self._diag is not None:
            self._diag.update(views, self._master_view(views, operational))

    def _master_view(self, views: tuple[NodeView, ...], operational: int) -> tuple:
        """CANOPEN_MASTER's fields, in diag.MASTER_FIELDS order."""
        ep = self.endpoint
        return (
            self._bus_ok,
            len(views),
            operational,
            ep.received if ep else 0,
            ep.sent if ep else 0,
            ep.send_errors if ep else 0,
            self.malformed,
        )

    def write_outputs(self, image: ProcessImage) -> None:
        sent = self._tx_data  # only this thread writes it: read without the lock
        packed = {b: data for b in self._rpdo_bindings if sent.get(b) != (data := b.pack(image))}  # the changed
        if packed:
            with self._io:
                sent.update(packed)

    def status(self) -> DriverStatus:
        if not self._bus_ok:
            return DriverStatus(False, f"canopen: bus down ({self.port.describe_down(self.clock.now_ns())})")
        return DriverStatus(*nodes_status(self._views, self.malformed))

    def details(self) -> dict:
        """For the monitors: each node's state, the NMT state its heartbeat
        or guarding reply last gave, its last error and latest emergencies."""
        nodes = [node_details(v, self.nodes[v.node_id].emcy_text) for v in self._views]
        return {"bus_ok": self._bus_ok, "malformed": self.malformed, "nodes": nodes}

    def node_state(self, node_id: int) -> NodeState:
        return self.nodes[node_id].sup.state
