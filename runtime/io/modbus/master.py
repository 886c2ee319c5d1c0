"""The Modbus master: every [[modbus]] connection of a configuration, its
channels (runtime/io/modbus/channel.py) and the program's MODBUS_EXCHANGE
requests (runtime/io/modbus/exchange.py), as one driver.

Each connection has one owner of its pymodbus client (link.py):
  real time     a worker thread per connection runs whatever is due (queued
                requests first, then channels in configuration order) and
                sleeps until the next due time or until the scan wakes it;
  virtual time  no thread: at each tick the engine's thread runs everything
                due by then (advance_to), so the answers are in the image of
                the same tick and a sequence always runs the same way. To a
                simulated line the link runs in memory (wire.py: real frames,
                no pseudo-terminal, no socket, no wait): a unit that does not
                answer costs its timeout in virtual time, during which the
                connection sends nothing else, and the error counts when the
                timeout ends. To a real port (or a line on sim_wire = "port")
                a silent slave costs real time, never virtual time.

The program sees each channel in MODBUS_CHANNEL[i] (i = the channel's place
in the file, counted over all connections; fblocks/comm/modbus.st).

While the engine holds the outputs safe (a task fault, the stop) the master
writes the safe values the program's device blocks declared with
MODBUS_SAFE_WRITE, and puts them in place of what the program's requests
would write there (safe.py); at the stop it sends them before it closes.
"""

from __future__ import annotations

import collections
import logging
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING

from ...image.memory import ProcessImage
from ...plugin.driver import Driver, DriverError, DriverStatus
from .channel import Channel
from .exchange import SERVICE as EXCHANGE_SERVICE
from .exchange import ModbusExchangeService
from .link import LinkSettings, ModbusLink, Outcome, Transaction, error_text
from .safe import SERVICE as SAFE_SERVICE
from .safe import SafeWrites

if TYPE_CHECKING:
    from .diag import ModbusDiag

from ..ratelog import RateLimitedLog

log = logging.getLogger(__name__)
lines = RateLimitedLog(log)  # a worker's failures, rate limited

#: real time: the longest a worker sleeps without looking at its channels
IDLE_WAIT_S = 0.05


def link_settings(cfg) -> LinkSettings:
    """LinkSettings of a ModbusConnectionConfig (runtime/config/)."""
    return LinkSettings(
        name=cfg.name,
        transport=cfg.transport,
        host=cfg.host,
        port=cfg.port,
        device=cfg.device,
        baud=cfg.baud,
        parity=cfg.parity,
        stop_bits=cfg.stop_bits,
        data_bits=cfg.data_bits,
        frame_gap_s=None if cfg.frame_gap_us is None else cfg.frame_gap_us / 1e6,
        timeout_s=cfg.timeout_ms / 1000,
        retries=cfg.retries,
        reconnect_s=cfg.reconnect_ms / 1000,
        reconnect_max_s=cfg.reconnect_max_ms / 1000,
    )


class ConnectionWorker:
    """The owner of one link: runs its requests and due channels, and logs
    what changes (a channel that fails or works again, the connection lost
    or made), rate limited."""

    def __init__(self, link: ModbusLink, channels: list, clock, lines: RateLimitedLog | None = None) -> None:
        self.link = link
        self.lines = lines if lines is not None else RateLimitedLog(log, clock.now_ns)
        self._was_up: bool | None = None  # the connection when last looked at (None: not yet)
        self._late: tuple[int, Callable[[int], None]] | None = None  # in memory: (when, deliver) of a timeout
        self.channels = channels
        self.clock = clock
        self._requests: collections.deque = collections.deque()
        self._wake = threading.Event()
        self._thread: threading.Thread | None = None
        self._running = False

    def submit(self, tx: Transaction, done: Callable[[Outcome], None]) -> None:
        self._requests.append((tx, done))
        self.wake()

    def wake(self) -> None:
        """Real time: the thread sees new work at once. In virtual time no
        thread waits (the engine calls run_due) and an Event costs a lock
        and a notification."""
        if self._running:
            self._wake.set()

    def run_due(self, now_ns: int) -> None:
        self.lines.flush(now_ns)
        if self._late is not None:
            when, deliver = self._late
            if now_ns < when:
                return  # the line is still waiting for an answer that does not come
            self._late = None
            deliver(when)
        self.link.try_connect(now_ns)
        self._watch_link()
        while self._requests:
            tx, done = self._requests.popleft()
            outcome = self.link.transact(tx, now_ns)
            self._watch_link()
            if outcome.late_s:
                self._late = (now_ns + int(outcome.late_s * 1e9), lambda _t, done=done, o=outcome: done(o))
                return
            done(outcome)
        for ch in self.channels:
            if ch.due(now_ns):
                outcome = self.link.transact(ch.transaction(), now_ns)
                self._watch_link()
                if outcome.late_s:
                    self._late = (
                        now_ns + int(outcome.late_s * 1e9),
                        lambda t, ch=ch, o=outcome: self._complete(ch, o, t),
                    )
                    return
                self._complete(ch, outcome, now_ns)

    def _complete(self, ch: Channel, outcome: Outcome, now_ns: int) -> None:
        """The channel's transaction is over: its stats, and a log line when
        it starts failing (or fails for another reason) or works again."""
        was_ok, was_message, tried = ch.stats.ok, ch.stats.message, ch.stats.requests
        ch.complete(outcome, now_ns)
        stats, name = ch.stats, self.link.settings.name
        if not stats.ok and (was_ok or stats.message != was_message or not tried):
            self.lines.warning(("channel", ch.name), "modbus %s: channel %s: %s", name, ch.name, stats.message)
        elif stats.ok and not was_ok and tried:
            self.lines.info(("channel ok", ch.name), "modbus %s: channel %s works again", name, ch.name)

    def _watch_link(self) -> None:
        """A log line when the connection is made or lost."""
        up = self.link.connected
        if up == self._was_up:
            return
        self._was_up = up
        level = logging.INFO if up else logging.WARNING
        self.lines.log(level, ("link", up), "modbus %s: %s", self.link.settings.name, self.link.message)

    def _next_wait_s(self, now_ns: int) -> float:
        dues = [d for d in (ch.next_due_ns() for ch in self.channels) if d is not None]
        if not dues:
            return IDLE_WAIT_S
        return min(IDLE_WAIT_S, max(0.0, (min(dues) - now_ns) / 1e9))

    # real time ------------------------------------------------------------

    def start_thread(self) -> None:
        self._running = True
        self._thread = threading.Thread(target=self._loop, name=f"modbus {self.link.settings.name}", daemon=True)
        self._thread.start()

    def _loop(self) -> None:
        try:
            while self._running:
                self.run_due(self.clock.now_ns())
                wait = self._next_wait_s(self.clock.now_ns())
                if wait > 0 and not self._requests:
                    self._wake.wait(wait)
                self._wake.clear()
            self.drain(self.clock.now_ns())
        except Exception:  # a bug must not die silently in a thread
            lines.exception(None, "modbus %s: worker failed", self.link.settings.name)
            self.link.message = "worker failed (see the log)"
        finally:
            self.link.close()

    def drain(self, now_ns: int) -> None:
        """At the stop: the requests still queued (the safe writes the last
        write_outputs queued), each once, whatever answer is late."""
        self._late = None
        while self._requests:
            tx, done = self._requests.popleft()
            done(self.link.transact(tx, now_ns))

    def stop(self) -> None:
        self._running = False
        self._wake.set()
        if self._thread is not None:
            self._thread.join(timeout=5 + self.link.settings.timeout_s * (1 + self.link.settings.retries))
            self._thread = None
        else:
            self.drain(self.clock.now_ns())
            self.link.close()


class ModbusDriver(Driver):
    """Driver for all [[modbus]] connections (one instance per engine)."""

    def __init__(self, connections: list, addressing: str, *, clock, servers: dict | None = None, wire=None) -> None:
        """servers: connection name -> the MemoryServer of its simulated
        line, for the connections that run in memory (virtual time); wire:
        the run's ModbusWireLog (buslog.py), when it records its wire."""
        self.name = "modbus"
        image = ProcessImage(addressing)  # the layout, for the channels' byte spans
        self.clock = clock
        self.lines = RateLimitedLog(log, clock.now_ns)  # what the connections log, rate limited
        self.channels: list[Channel] = []
        self.workers: dict[str, ConnectionWorker] = {}
        for cfg in connections:
            channels = []
            for ch_cfg in cfg.channels:
                try:
                    channels.append(Channel(ch_cfg, image))
                except Exception as exc:
                    raise DriverError(str(exc)) from None
            self.channels.extend(channels)
            link = ModbusLink(link_settings(cfg), (servers or {}).get(cfg.name))
            if wire is not None:
                link.wire = wire.connection(cfg.name)
            self.workers[cfg.name] = ConnectionWorker(link, channels, clock, self.lines)
        self.exchange = ModbusExchangeService(self._submit)
        self.safe = SafeWrites(self.workers.__contains__)
        self.services = {EXCHANGE_SERVICE: self.exchange, SAFE_SERVICE: self.safe}
        self._held = False  # the engine holds the outputs safe (safe.py)
        self._diag: ModbusDiag | None = None

    def _submit(self, connection: str, tx: Transaction, done) -> bool:
        worker = self.workers.get(connection)
        if worker is None:
            return False
        if self._held:  # the device's safe values, not the program's
            tx = self.safe.substitute(connection, tx)
        worker.submit(tx, done)
        return True

    def _send_safe(self) -> None:
        """The safe writes due now (safe.py), queued after the program's."""
        for connection, tx, key in self.safe.due(self.clock.now_ns()):

            def done(outcome: Outcome, tx=tx, key=key, connection=connection) -> None:
                self.safe.done(key, outcome.error == 0)
                if outcome.error:
                    log.warning(
                        "modbus %s: unit %d: safe values to registers %d..%d not written: %s",
                        connection,
                        tx.unit,
                        tx.offset,
                        tx.offset + len(tx.values) - 1,
                        outcome.message or error_text(outcome.error),
                    )

            self.workers[connection].submit(tx, done)

    # life cycle -------------------------------------------------------------

    def start(self) -> None:
        if not self.clock.virtual:
            for worker in self.workers.values():
                worker.start_thread()

    def advance_to(self, now_ns: int) -> None:
        for worker in self.workers.values():
            worker.run_due(now_ns)

    def stop(self) -> None:
        for worker in self.workers.values():
            worker.stop()

    def bind_program(self, globals_obj) -> None:
        from .diag import ModbusDiag

        diag = ModbusDiag(globals_obj)
        # a program that does not read MODBUS_CHANNEL costs no snapshot per cycle
        self._diag = diag if diag.active else None

    # scan side ----------------------------------------------------------------

    def read_inputs(self, image: ProcessImage) -> None:
        for ch in self.channels:
            ch.publish(image)
        self.exchange.collect()
        diag = self._diag
        if diag is not None:  # a snapshot only of the channels that changed since the last one shown
            changed = []
            for i, ch in enumerate(self.channels):
                link_ok = self.workers[ch.cfg.connection].link.connected
                if diag.stale(i, ch.stats.version, link_ok):
                    changed.append((i, ch.snapshot(), link_ok))
            if changed:
                diag.update(changed)

    def write_outputs(self, image: ProcessImage) -> None:
        for ch in self.channels:
            if ch.stage(image):
                self.workers[ch.cfg.connection].wake()
        if image.held_safe != self._held:
            self._held = image.held_safe
            if self._held:
                self.safe.hold()
        if self._held:
            self._send_safe()

    def status(self) -> DriverStatus:
        down = [w.link for w in self.workers.values() if not w.link.connected]
        failing = [ch for ch in self.channels if ch.stats.requests and not ch.stats.ok]
        if down:
            return DriverStatus(False, "modbus: " + "; ".join(f"{link.settings.name} {link.message}" for link in down))
        if failing:
            first = failing[0]
            others = "".join(f", {ch.name}" for ch in failing[1:3])
            return DriverStatus(
                False,
                f"modbus: {len(failing)}/{len(self.channels)} channels failing "
                f"({first.name}: {first.stats.message}{others})",
            )
        return DriverStatus(True, f"modbus: {len(self.workers)} up")
