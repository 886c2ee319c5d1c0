"""One Modbus connection (RTU on a serial line, or TCP) and its transactions.

A ModbusLink owns one pymodbus client. pymodbus clients are not thread-safe,
so exactly one thread calls transact(): the connection's worker in real time,
the engine's thread in virtual time (runtime/io/modbus/master.py).

    link = ModbusLink(settings)
    outcome = link.transact(Transaction(unit=1, function=3, offset=5, count=1), now_ns)
    outcome.error     # 0, a Modbus exception code, or one of ModbusError's own codes
    outcome.values    # the registers (or bits) read

What the link adds to pymodbus:
  * every failure becomes an error code, never an exception: the codes are
    CODESYS's (IoDrvModbus MB_ErrorCodes), so a ported program's checks work;
  * every reply is checked against its request as it crossed the wire
    (replies.py: unit, function, exception code, byte and item counts, the
    echo of a write); a bad reply is an error with its reason, and nothing
    of it is taken;
  * the idle time between RTU frames (Modbus over serial line 2.5.1.1:
    3.5 character times, fixed 1.75 ms above 19200 bit/s; the Eaton manual
    asks for it too, digest §2.3) is kept before every request;
  * a connection that fails is closed and opened again after a back-off that
    doubles from `reconnect` up to `reconnect_max`, measured on the engine's
    clock (virtual time included), so a missing slave never blocks the others
    for longer than one timeout.
"""

from __future__ import annotations

import logging
import struct
import time
from collections.abc import Callable

from pymodbus.client import ModbusSerialClient, ModbusTcpClient
from pymodbus.client.mixin import ModbusClientMixin
from pymodbus.exceptions import ConnectionException, ModbusException, ModbusIOException
from pymodbus.pdu import ModbusPDU

from .errors import ModbusError, error_text
from .functions import FUNCTIONS, check_request
from .messages import LinkSettings, Outcome, Transaction, frame_gap
from .replies import BadReply, ReplyCheck, check_pdu
from .wire import CODEC_FRAMES, MemoryClient, MemoryServer

__all__ = ["LinkSettings", "ModbusError", "ModbusLink", "Outcome", "Transaction", "error_text", "frame_gap"]

# pymodbus logs every timeout as an error; the link reports them itself.
logging.getLogger("pymodbus").setLevel(logging.CRITICAL)


_OUT_OF_STEP = (
    ModbusError.RESPONSE_TIMEOUT,
    ModbusError.RESPONSE_INVALID_HEADER,
    ModbusError.RESPONSE_INVALID_PROTOCOL,
)


class _Tap:
    """pymodbus's trace_packet hook: the last request frame sent and the
    bytes received since (pymodbus hands over all it has gathered so far)."""

    def __init__(self) -> None:
        self.sent = b""
        self.received = b""

    def __call__(self, sending: bool, data: bytes) -> bytes:
        if sending:
            self.sent, self.received = bytes(data), b""
        else:
            self.received = bytes(data)
        return data


def _exception(tx: Transaction, code: int, elapsed: float = 0.0) -> Outcome:
    """The outcome of an exception response: its code, and what it means."""
    return Outcome(code, response_s=elapsed, message=f"unit {tx.unit} answered exception {code} ({error_text(code)})")


class _Build(ModbusClientMixin[ModbusPDU]):
    """pymodbus's request methods, answering the request PDU they build."""

    def execute(self, no_response_expected: bool, request: ModbusPDU) -> ModbusPDU:
        return request


_BUILD = _Build()


class ModbusLink:
    """One connection; see the module docstring. Not thread-safe by design:
    one owner calls transact()."""

    def __init__(self, settings: LinkSettings, server: MemoryServer | None = None) -> None:
        self.settings = settings
        self.server = server  # in memory to a simulated line (virtual time), see wire.py
        self._client: ModbusTcpClient | ModbusSerialClient | MemoryClient | None = None
        self._tap = _Tap()  # the frames of the last request, as they crossed the wire
        #: a run that records its wire (buslog.py): (sent at, request, answer, response time) after each request
        self.wire: Callable[[int, bytes, bytes, float], None] | None = None
        self._replies = ReplyCheck(settings.transport)
        #: in memory: (unit, function, offset, count, values, write offset) -> pymodbus's request PDU and frame
        self._requests: dict[tuple, tuple[ModbusPDU, bytes]] = {}
        self._next_attempt_ns = 0
        self._backoff_s = settings.reconnect_s
        self._last_frame_end = 0.0
        self.connected = False
        self.connects = 0  # successful (re)connections
        self.message = "not connected yet"
        gap = settings.frame_gap_s
        if gap is None and settings.transport == "rtu":
            gap = frame_gap(settings.baud, settings.parity, settings.stop_bits, settings.data_bits)
        self._gap_s = gap or 0.0

    # ---------------------------------------------------------------- connection

    def _new_client(self) -> ModbusTcpClient | ModbusSerialClient | MemoryClient:
        s = self.settings
        if self.server is not None:
            return MemoryClient(self.server, s, self._gap_s)
        if s.transport == "tcp":
            return ModbusTcpClient(
                s.host,
                port=s.port,
                timeout=s.timeout_s,
                retries=s.retries,
                reconnect_delay=0,
                trace_packet=self._tap,
            )
        return ModbusSerialClient(
            s.device,
            baudrate=s.baud,
            parity=s.parity,
            stopbits=s.stop_bits,
            bytesize=s.data_bits,
            timeout=s.timeout_s,
            retries=s.retries,
            reconnect_delay=0,
            trace_packet=self._tap,
        )

    def try_connect(self, now_ns: int) -> bool:
        """Connected, or connect now unless the back-off says wait."""
        if self.connected:
            return True
        if now_ns < self._next_attempt_ns:
            return False
        s = self.settings
        if self.server is not None:
            where = f"the simulated line {self.server.line.name} (in memory)"
        else:
            where = f"{s.host}:{s.port}" if s.transport == "tcp" else s.device
        try:
            self._client = self._new_client()
            ok = self._client.connect()
        except (ModbusException, OSError, ValueError) as exc:
            ok, why = False, str(exc)
        else:
            why = "connection refused or port missing"
        if ok:
            self.connected = True
            self.connects += 1
            self._backoff_s = s.reconnect_s
            self.message = f"connected to {where}"
            return True
        self._drop(now_ns, f"cannot open {where}: {why}")
        return False

    def _drop(self, now_ns: int, why: str) -> None:
        """Close the client; the next attempt waits for the back-off."""
        if self._client is not None:
            try:
                self._client.close()
            except (ModbusException, OSError):
                pass
        self._client = None
        self.connected = False
        self.message = f"{why}; retrying in {self._backoff_s:g} s"
        self._next_attempt_ns = now_ns + int(self._backoff_s * 1e9)
        self._backoff_s = min(self._backoff_s * 2, self.settings.reconnect_max_s)

    def close(self) -> None:
        if self._client is not None:
            self._client.close()
        self._client = None
        self.connected = False

    # ---------------------------------------------------------------- transactions

    def transact(self, tx: Transaction, now_ns: int) -> Outcome:
        why = check_request(tx.function, tx.count, len(tx.values))
        if why is not None:
            return Outcome(ModbusError.INVALID_REQUEST, message=why)
        if not self.try_connect(now_ns):
            return Outcome(ModbusError.REQUEST_FAILED_TO_SEND, message=self.message)
        client = self._client
        assert client is not None  # connected: try_connect() made it, only _drop() and close() clear it
        if isinstance(client, MemoryClient):
            return self._transact_in_memory(client, tx, now_ns)
        if self._gap_s:
            wait = self._last_frame_end + self._gap_s - time.perf_counter()
            if wait > 0:
                time.sleep(wait)
        start = time.perf_counter()
        tap = self._tap
        tap.sent = tap.received = b""
        try:
            response = self._call(client, tx)
        except ModbusIOException as exc:
            # a timeout, or a reply pymodbus skipped or could not decode
            outcome = self._no_reply(tx, tap.sent, tap.received, exc, 0.0)
            if self._out_of_step(outcome):
                self._drop(now_ns, outcome.message)
            return outcome
        except (ConnectionException, OSError) as exc:
            self._drop(now_ns, f"connection lost: {exc}")
            return Outcome(ModbusError.REQUEST_FAILED_TO_SEND, message=self.message)
        except ModbusException as exc:
            return Outcome(ModbusError.RESPONSE_INVALID_DATA, message=str(exc))
        finally:
            self._last_frame_end = time.perf_counter()
            if self.wire is not None:
                self.wire(now_ns, tap.sent, tap.received, self._last_frame_end - start)
        return self._outcome(tx, response, self._last_frame_end - start, self._check(tx, tap.sent, tap.received))

    def _transact_in_memory(self, client: MemoryClient, tx: Transaction, now_ns: int) -> Outcome:
        """transact() over a MemoryClient: nothing waits; a timeout is
        reported as late_s, the virtual time it costs.

        A request is built by pymodbus once (its PDU and frame are kept, the
        last CODEC_FRAMES of them) and sent again as those bytes. A reply
        that the reply check finds good (replies.py: framed by pymodbus's
        framer, its CRC, unit, function and counts) is taken from its bytes
        (_taken); any other goes through pymodbus's client as before."""
        client.sent = client.received = b""
        key = (tx.unit, tx.function, tx.offset, tx.count, tuple(tx.values), tx.write_offset)
        try:
            known = self._requests.get(key)
            if known is None:
                if len(self._requests) >= CODEC_FRAMES:
                    self._requests.clear()
                request = self._call(_BUILD, tx)  # what pymodbus refuses to build raises here, as it did
                known = self._requests[key] = (request, client.codec.build(request))
            response = client.resend(*known, lambda answer: self._taken(tx, client.sent, answer))
        except ModbusIOException as exc:
            outcome = self._no_reply(tx, client.sent, client.received, exc, client.line_s)
            if self._out_of_step(outcome):
                self._drop(now_ns + int(client.line_s * 1e9), outcome.message)
            return outcome
        except ModbusException as exc:
            return Outcome(ModbusError.RESPONSE_INVALID_DATA, message=str(exc))
        finally:
            if self.wire is not None:
                self.wire(now_ns, client.sent, client.received, client.line_s)
        if isinstance(response, Outcome):
            response.response_s = client.line_s
            return response
        return self._outcome(tx, response, client.line_s, self._check(tx, client.sent, client.received))

    def _taken(self, tx: Transaction, sent: bytes, answer: bytes) -> Outcome | None:
        """The outcome of a reply the checks find good, from its PDU's bytes
        as _outcome() takes it from pymodbus's decoding; None for any other
        reply, which pymodbus's client decodes (or skips, and tries again)."""
        split = self._replies.split(sent, answer)
        if isinstance(split, BadReply) or check_pdu(tx, *split) is not None:
            return None
        pdu = split[1]
        if pdu[0] & 0x80:
            return _exception(tx, pdu[1])
        reads, _writes, bits = FUNCTIONS[tx.function]
        if not reads:
            return Outcome()
        data = pdu[2:]
        if bits:
            return Outcome(values=[bool(data[i >> 3] >> (i & 7) & 1) for i in range(tx.count)])
        return Outcome(values=list(struct.unpack(f">{tx.count}H", data)))

    def _no_reply(self, tx: Transaction, sent: bytes, received: bytes, exc: Exception, line_s: float) -> Outcome:
        """pymodbus gave up on a request: no reply came (a timeout), or the
        one that came was skipped (another unit's) or did not decode; the
        reply check says what was wrong with it."""
        bad = self._check(tx, sent, received) if received else None
        if bad is None and not received:
            return Outcome(
                ModbusError.RESPONSE_TIMEOUT,
                response_s=line_s,
                message=f"no answer from unit {tx.unit}: {exc}",
                late_s=line_s,
            )
        if bad is None:
            bad = BadReply(ModbusError.RESPONSE_INVALID_DATA, f"unit {tx.unit}: a reply that does not decode: {exc}")
        return Outcome(bad.error, response_s=line_s, message=bad.message, late_s=line_s)

    def _out_of_step(self, outcome: Outcome) -> bool:
        """TCP: the stream may be out of step with the requests (no answer
        came, and a late one would be taken for the next request's; or a
        header did not frame): the connection is closed and opened again."""
        return self.settings.transport == "tcp" and outcome.error in _OUT_OF_STEP

    def _check(self, tx: Transaction, sent: bytes, received: bytes) -> BadReply | None:
        if not received:  # pymodbus answered without a frame (a broadcast): nothing to check
            return None
        return self._replies(tx, sent, received)

    @staticmethod
    def _outcome(tx: Transaction, response: ModbusPDU, elapsed: float, bad: BadReply | None) -> Outcome:
        if bad is not None:
            return Outcome(bad.error, response_s=elapsed, message=bad.message)
        if response.isError():
            return _exception(tx, int(getattr(response, "exception_code", ModbusError.UNDEFINED)), elapsed)
        reads, _writes, bits = FUNCTIONS[tx.function]
        if not reads:
            return Outcome(response_s=elapsed)
        values = list(response.bits[: tx.count]) if bits else list(response.registers)
        if len(values) != tx.count:
            return Outcome(
                ModbusError.RESPONSE_INVALID_DATA,
                response_s=elapsed,
                message=f"unit {tx.unit} sent {len(values)} items for {tx.count}",
            )
        return Outcome(values=values, response_s=elapsed)

    @staticmethod
    def _call(c: ModbusTcpClient | ModbusSerialClient | ModbusClientMixin, tx: Transaction) -> ModbusPDU:
        unit, fc = tx.unit, tx.function
        if fc == 1:
            return c.read_coils(tx.offset, count=tx.count, device_id=unit)
        if fc == 2:
            return c.read_discrete_inputs(tx.offset, count=tx.count, device_id=unit)
        if fc == 3:
            return c.read_holding_registers(tx.offset, count=tx.count, device_id=unit)
        if fc == 4:
            return c.read_input_registers(tx.offset, count=tx.count, device_id=unit)
        if fc == 5:
            return c.write_coil(tx.offset, bool(tx.values[0]), device_id=unit)
        if fc == 6:
            return c.write_register(tx.offset, tx.values[0], device_id=unit)
        if fc == 15:
            return c.write_coils(tx.offset, [bool(v) for v in tx.values], device_id=unit)
        if fc == 16:
            return c.write_registers(tx.offset, list(tx.values), device_id=unit)
        return c.readwrite_registers(
            read_address=tx.offset,
            read_count=tx.count,
            write_address=tx.write_offset,
            values=list(tx.values),
            device_id=unit,
        )
