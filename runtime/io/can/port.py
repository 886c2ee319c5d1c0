"""The PLC's own connection to a [[can]] bus, shared by every protocol driver
on that bus: the CANopen master and the plain-CAN devices (io/plaincan) send
and receive through one CanEndpoint, so one python-can bus object and one
receive thread (or, in virtual time, one pumped endpoint) serve them all, as
one CAN adapter serves every protocol on a plant PC.

    port = port_of(ctx, bus_config)          # io/can: the same object for every driver of one engine
    endpoint = port.acquire(now_ns)          # opened and started by the first driver
    endpoint.add_handler(my_frames)
    port.try_open(now_ns)                    # the bus down: open it again when due (True: open)
    ...
    port.release(my_frames)                  # closed when the last driver lets go

The adapter may be missing when the PLC starts (a USB adapter on a plant PC
comes up after the PLC's service) or go away later (unplugged, interface
down). Either way the port is down (`is_open` false, `error` says why): the
endpoint exists, sends nothing and receives nothing, and the drivers call
try_open() from their service; it opens the adapter again after a back-off
of REOPEN_FIRST_NS, doubled after every failed try up to REOPEN_MAX_NS, on
the engine's clock (virtual time in a test), and swaps the new bus object
into the same endpoint, so the drivers' handlers stay. The port logs it
(rate limited): the adapter missing at the start, the tries that fail, the
bus open again. With `fail_fast` ([[can]] missing_adapter = "fail") a
missing adapter at the start is a DriverError instead: `softplc run` exits
with code 2.

Simulated devices are other nodes on the bus: they open endpoints of their
own (a simulated device is a separate peer), never the PLC's port.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable

from ...plugin.driver import DriverError
from ..ratelog import RateLimitedLog, monotonic_ns
from .bus import BusPump, BusSettings, CanEndpoint, Handler, open_bus

log = logging.getLogger(__name__)

#: a bus that cannot be opened: the first wait before the next try, doubled after each failed one ...
REOPEN_FIRST_NS = 500_000_000
#: ... up to this
REOPEN_MAX_NS = 10_000_000_000


class CanPort:
    def __init__(
        self,
        settings: BusSettings,
        pump: BusPump | None = None,
        name: str = "plc",
        *,
        bus: str = "can0",
        clock=None,
        fail_fast: bool = False,
    ) -> None:
        """bus: the [[can]] name, for messages; clock: the engine's (for the
        back-off and the log's rate limit); fail_fast: a missing adapter at
        the start is a DriverError, not a wait."""
        self.settings = settings
        self.pump = pump
        self.name = name
        self.bus = bus
        self.fail_fast = fail_fast
        now: Callable[[], int] = clock.now_ns if clock is not None else monotonic_ns
        self.lines = RateLimitedLog(log, now)
        self.endpoint: CanEndpoint | None = None
        self.wire: Callable[[int, bytes, bool, bool, bool], None] | None = None  # wire.py: the run records its wire
        self.error = ""  # why the bus is not open; "" when it is
        self.next_try_ns = 0  # down: when try_open() tries again
        self.tries = 0  # failed tries since the bus went down
        self._backoff_ns = REOPEN_FIRST_NS
        self._users = 0
        self._lock = threading.Lock()

    # ------------------------------------------------------------ users

    def acquire(self, now_ns: int = 0) -> CanEndpoint:
        """The started endpoint; the first caller opens the bus. A bus that
        cannot be opened leaves the port down (try_open() opens it later),
        or, with fail_fast, raises DriverError naming the bus and the
        interface."""
        with self._lock:
            if self.endpoint is None:
                try:
                    bus = open_bus(self.settings)
                except DriverError as exc:
                    if self.fail_fast:
                        raise DriverError(
                            f'{self.bus}: {exc} (missing_adapter = "fail"; the default, "retry", waits for it)'
                        ) from None
                    bus = None
                    self._down(now_ns, str(exc))
                    self.lines.error(
                        ("missing", self.bus),
                        "%s: %s; trying again in %g s, then less and less often (every %g s at most)",
                        self.bus,
                        exc,
                        (self.next_try_ns - now_ns) / 1e9,
                        REOPEN_MAX_NS / 1e9,
                    )
                self.endpoint = CanEndpoint(bus, name=f"{self.name} on {self.settings.channel}", pump=self.pump)
                self.endpoint.wire = self.wire
                self.endpoint.start()
            self._users += 1
            return self.endpoint

    def release(self, *handlers: Handler) -> None:
        """A driver is done: its handlers go; the last one closes the bus."""
        with self._lock:
            endpoint = self.endpoint
            if endpoint is None:
                return
            for handler in handlers:
                endpoint.remove_handler(handler)
            self._users -= 1
            if self._users <= 0:
                self._users = 0
                self.endpoint = None
                endpoint.stop()

    @property
    def users(self) -> int:
        return self._users

    # ------------------------------------------------------------ down and open again

    @property
    def is_open(self) -> bool:
        return self.endpoint is not None and not self.error

    def failed(self, now_ns: int, why: str) -> None:
        """A driver found the bus gone (a send failed): the port is down
        and try_open() opens it again after the back-off."""
        with self._lock:
            if not self.error:
                self._down(now_ns, why)

    def try_open(self, now_ns: int) -> bool:
        """Open the bus again if it is down and a try is due; True when the
        bus is open (already, or now). The drivers call it from their
        service, so the port's log lines held back are told from here too."""
        self.lines.flush(now_ns)
        if not self.error:
            return self.endpoint is not None
        with self._lock:
            endpoint = self.endpoint
            if not self.error or endpoint is None:
                return endpoint is not None
            if now_ns < self.next_try_ns:
                return False
            try:
                bus = open_bus(self.settings)
            except DriverError as exc:
                self._down(now_ns, str(exc))
                self.lines.warning(
                    ("still missing", self.bus),
                    "%s: %s; try %d failed, the next in %g s",
                    self.bus,
                    exc,
                    self.tries,
                    (self.next_try_ns - now_ns) / 1e9,
                )
                return False
            endpoint.reopen(bus)
            tries, self.tries = self.tries, 0
            self.error = ""
            self._backoff_ns = REOPEN_FIRST_NS
        self.lines.warning(
            ("open", self.bus), "%s: CAN bus open (%s) after %d failed tries", self.bus, self.settings.describe(), tries
        )
        return True

    def _down(self, now_ns: int, why: str) -> None:
        """Down (lock held): the next try after the back-off, which doubles."""
        self.error = why
        self.tries += 1
        self.next_try_ns = now_ns + self._backoff_ns
        self._backoff_ns = min(2 * self._backoff_ns, REOPEN_MAX_NS)

    def describe_down(self, now_ns: int) -> str:
        """Why the bus is down and when the next try is, for a status line."""
        wait = max(self.next_try_ns - now_ns, 0) / 1e9
        return f"{self.error}; next try in {wait:.1f} s"


def shared_port(
    shared: dict,
    bus: str,
    settings: BusSettings,
    pump: BusPump | None,
    *,
    clock=None,
    fail_fast: bool = False,
) -> CanPort:
    """The one CanPort of an engine for the [[can]] bus named bus (shared: the
    dict the buses of one engine share, BuildContext.shared)."""
    ports: dict[str, CanPort] = shared.setdefault("can.ports", {})
    port = ports.get(bus)
    if port is None:
        port = ports[bus] = CanPort(settings, pump, bus=bus, clock=clock, fail_fast=fail_fast)
    return port
