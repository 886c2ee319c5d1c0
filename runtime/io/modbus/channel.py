"""A Modbus channel, as CODESYS has them: one request to one slave, repeated
on a trigger, between a register (or coil) block and the process image.

    function 1, 2, 3, 4   read  -> `read_to` (%I or %M) at the start of a cycle
    function 5, 6, 15, 16 write <- `write_from` (%Q or %M) after a cycle
    function 23           both in one transaction

Registers lie in the image as consecutive 16-bit words (little-endian bytes,
as every word of the image); coils and discrete inputs as consecutive bits
from bit 0 of the byte at the address.

Triggers:
    cyclic   every `period`
    change   (writes) when the bytes to write differ from the last ones sent;
             once at start
    edge     on a rising edge of the BOOL at `edge` (read after each cycle)
After a failed transaction a channel waits one period before it tries again,
whatever its trigger, so a dead slave cannot flood the line.

The scan thread calls stage() (after a cycle) and publish() (before one); the
connection's worker calls due(), transaction() and complete(). They meet
under the channel's lock for as long as a copy takes.
"""

from __future__ import annotations

import threading

from ...image.memory import ProcessImage
from ...st import types as T
from .exchange import pack_bits
from .functions import FUNCTIONS
from .link import ModbusError, Outcome, Transaction, error_text


class ChannelStats:
    """What the program reads in MODBUS_CHANNEL[i] (fblocks/comm/modbus.st)."""

    __slots__ = ("requests", "errors", "last_error", "response_ms", "ok", "message", "version")

    def __init__(self) -> None:
        self.requests = 0
        self.errors = 0
        self.last_error = 0
        self.response_ms = 0
        self.ok = False
        self.message = "no transaction yet"
        self.version = 0


class Channel:
    def __init__(self, cfg, image: ProcessImage) -> None:
        self.cfg = cfg
        self.name = cfg.name
        self.reads, self.writes, self.bits = FUNCTIONS[cfg.function]
        self._lock = threading.Lock()
        self.stats = ChannelStats()
        # (area, byte offset, bytes) in the image; None where the function does not read (write)
        self._read_span = self._span(image, cfg.read_to, cfg.count) if self.reads else None
        write_count = cfg.write_count if cfg.function == 23 else cfg.count
        self._write_span = self._span(image, cfg.write_from, write_count) if self.writes else None
        self._write_count = write_count
        self._stages = self._write_span is not None or cfg.trigger == "edge"  # stage() has work
        self._staged: bytes | None = None  # the last bytes the program left to write
        self._sent: bytes | None = None  # the bytes of the last good write
        self._pending = cfg.trigger == "change"
        self._edge_was = False
        self._fresh: bytes | None = None  # read data not yet in the image
        self._next_due_ns = 0
        self._in_flight: bytes | None = None

    def _span(self, image: ProcessImage, addr, count: int) -> tuple[str, int, int]:
        area, offset, _n = image.region(addr)
        nbytes = (count + 7) // 8 if self.bits else 2 * count
        if offset + nbytes > image.size:
            raise ValueError(
                f"{self.cfg.key}: {count} {'bits' if self.bits else 'registers'} from "
                f"{addr.text} run past the end of the %{area} area ({image.size} bytes)"
            )
        return area, offset, nbytes

    # ---------------------------------------------------------------- scan side

    def stage(self, image: ProcessImage) -> bool:
        """After a cycle: take the bytes to write and evaluate the trigger;
        True when the channel became due (wake the worker)."""
        if not self._stages:
            return False
        woke = False
        with self._lock:
            if self._write_span is not None:
                area, offset, n = self._write_span
                data = bytes(image.areas[area][offset : offset + n])
                if data != self._staged:
                    self._staged = data
                    if self.cfg.trigger == "change" and data != self._sent:
                        self._pending = woke = True
            if self.cfg.trigger == "edge":
                level = bool(image.read(self.cfg.edge, T.BOOL))
                if level and not self._edge_was:
                    self._pending = woke = True
                self._edge_was = level
        return woke

    def publish(self, image: ProcessImage) -> bool:
        """Before a cycle: new read data into the image; True if the stats changed."""
        if self._fresh is None:  # nothing new (one attribute read; what arrives now is next cycle's)
            return False
        with self._lock:
            fresh, self._fresh = self._fresh, None
        if fresh is None:
            return False
        assert self._read_span is not None  # only a reading channel has fresh data
        area, offset, n = self._read_span
        image.areas[area][offset : offset + n] = fresh
        return True

    # ---------------------------------------------------------------- worker side

    def due(self, now_ns: int) -> bool:
        with self._lock:
            if self.writes and self._staged is None:
                return False  # nothing to write before the first cycle
            if now_ns < self._next_due_ns:
                return False
            return self.cfg.trigger == "cyclic" or self._pending

    def next_due_ns(self) -> int | None:
        """When a cyclic channel (or one that failed) is next due; None: on a trigger."""
        with self._lock:
            if self.cfg.trigger == "cyclic" or self._pending:
                return self._next_due_ns
            return None

    def transaction(self) -> Transaction:
        cfg = self.cfg
        with self._lock:
            staged = self._staged
            self._in_flight = staged
            if self.cfg.trigger != "cyclic":
                self._pending = False
        values: tuple = ()
        if self.writes:
            assert staged is not None  # due() holds a writing channel back until a cycle staged its data
            if self.bits:
                values = tuple(bool(staged[i // 8] >> (i % 8) & 1) for i in range(self._write_count))
            else:
                values = tuple(int.from_bytes(staged[2 * i : 2 * i + 2], "little") for i in range(self._write_count))
        offset = cfg.offset
        return Transaction(cfg.unit, cfg.function, offset, cfg.count if self.reads else 0, values, cfg.write_offset)

    def complete(self, outcome: Outcome, now_ns: int) -> None:
        cfg = self.cfg
        with self._lock:
            s = self.stats
            s.requests += 1
            s.response_ms = int(outcome.response_s * 1000)
            s.last_error = int(outcome.error)
            s.ok = outcome.error == ModbusError.OK
            s.version += 1
            if s.ok:
                s.message = ""
                if self._read_span is not None:
                    vals = outcome.values
                    if self.bits:
                        words = pack_bits(vals)
                        raw = b"".join(w.to_bytes(2, "little") for w in words)
                    else:
                        raw = b"".join((v & 0xFFFF).to_bytes(2, "little") for v in vals)
                    self._fresh = raw[: self._read_span[2]]
                if self.writes:
                    self._sent = self._in_flight
            else:
                s.errors += 1
                s.message = outcome.message or error_text(outcome.error)
                if cfg.trigger != "cyclic":
                    self._pending = True  # try again after one period
            if cfg.trigger == "cyclic" or not s.ok:
                base = self._next_due_ns if cfg.trigger == "cyclic" and s.ok else now_ns
                self._next_due_ns = base + cfg.period_ns
                if self._next_due_ns <= now_ns:  # missed periods are skipped, not caught up
                    self._next_due_ns = now_ns + cfg.period_ns
            elif cfg.trigger == "change" and self._staged != self._sent:
                self._pending = True  # the program changed it again meanwhile

    def snapshot(self) -> tuple:
        with self._lock:
            s = self.stats
            return (s.version, s.ok, s.last_error, s.requests, s.errors, s.response_ms, s.message)
