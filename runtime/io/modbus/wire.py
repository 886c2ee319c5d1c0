"""Modbus in memory: the master's client and the simulated line's server
joined without a pseudo-terminal or a socket, for virtual time.

The bytes are the real ones: the master's requests are built by pymodbus's
own request PDUs and framer (FramerRTU: address, PDU, CRC-16; FramerSocket:
the MBAP header), the line decodes them with pymodbus's server-side framer
(a frame with a bad CRC is dropped, as on a real line), executes them with
pymodbus's own request handling (``datastore_update`` against the line's
units) and frames the answer, which the master decodes with its framer.
Nothing waits: the answer is there when exchange() returns. Each end
remembers the RTU frames it built and decoded (Codec), so a request or an
answer repeated byte for byte is not framed or CRC-checked again.

    client = MemoryClient(line, settings)   # what ModbusLink uses instead of
    client.read_holding_registers(5, count=1, device_id=1)   # pymodbus's client
    client.line_s     # the modelled time of the last request on the line

Time, decided here and kept by the link and the worker (master.py):
  * an answer is in the image of the tick that asked (as before, when the
    engine's thread waited for a real answer); its response time is the
    modelled time on the line: both frames at the configured baud rate (RTU;
    bits per character from parity and stop bits) plus the idle gap, 0 for TCP;
  * a request that gets no answer costs its timeout, every retry included,
    in virtual time: the connection sends nothing else meanwhile, and the
    error (RESPONSE_TIMEOUT) reaches the program when the last timeout ends.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol

from pymodbus.client.mixin import ModbusClientMixin
from pymodbus.constants import ExcCodes
from pymodbus.exceptions import ModbusIOException, NoSuchIdException
from pymodbus.framer import FramerBase, FramerRTU, FramerSocket
from pymodbus.pdu import DecodePDU, ExceptionResponse, ModbusPDU

from ...sim.null_modem import keep_recent
from .messages import LinkSettings


class Line(Protocol):
    """What the in-memory server reads of its simulated line (line.py's
    SimulatedModbusLine): its name, RTU or TCP framing, its cable (a
    MemoryCable when the bytes cross in memory) and whether every unit is
    silent."""

    @property
    def name(self) -> str: ...

    @property
    def transport(self) -> str: ...

    @property
    def cable(self) -> object: ...

    @property
    def silent(self) -> bool: ...


def framer(transport: str, server: bool) -> FramerBase:
    """pymodbus's framer of a transport ("rtu" or "tcp"), a server's or a client's."""
    decoder = DecodePDU(server)
    return FramerRTU(decoder) if transport == "rtu" else FramerSocket(decoder)


#: how many frames a Codec remembers each way before it starts afresh
CODEC_FRAMES = 256


class Codec:
    """pymodbus's framer of one end, remembering frames: the same PDU bytes
    frame to the same bytes (RTU: address, PDU, CRC-16; TCP: the MBAP
    header, PDU), and the same frame decodes to the same PDU, so a master
    polling the same request and a drive giving the same answer are framed,
    decoded and CRC-checked once, not at every exchange. A frame seen for
    the first time goes through pymodbus's framer as before (one with a bad
    CRC is dropped there, and remembered as such). TCP frames differ only by
    the transaction id in their first two bytes (FramerSocket's layout): it
    is left out of the key and put back."""

    def __init__(self, transport: str, server: bool) -> None:
        self.framer = framer(transport, server)
        self._tcp = transport == "tcp"
        self._built: dict[tuple[int, bytes], bytes] = {}
        self._decoded: dict[tuple[bytes, int, int], tuple[int, ModbusPDU | None]] = {}

    def build(self, pdu: ModbusPDU) -> bytes:
        """framer.buildFrame(pdu)."""
        data = pdu.function_code.to_bytes(1, "big") + pdu.encode()
        key = (pdu.dev_id, data)
        frame = self._built.get(key)
        if frame is None:
            if len(self._built) >= CODEC_FRAMES:
                self._built.clear()
            frame = self._built[key] = self.framer.buildFrame(pdu)
        if self._tcp:
            return pdu.transaction_id.to_bytes(2, "big") + frame[2:]
        return frame

    def decode(self, frame: bytes, dev_id: int, tid: int) -> tuple[int, ModbusPDU | None]:
        """framer.handleFrame(frame, dev_id, tid); the PDU is shared by every
        decoding of the same frame: read it at once, do not change it."""
        if self._tcp:
            sent_tid = int.from_bytes(frame[0:2], "big")
            if tid and sent_tid and sent_tid != tid:  # the framer skips it: not remembered
                return self.framer.handleFrame(frame, dev_id, tid)
            key = (frame[2:], dev_id, 0)
        else:
            key = (frame, dev_id, tid)
        found = self._decoded.get(key)
        if found is None:
            if len(self._decoded) >= CODEC_FRAMES:
                self._decoded.clear()
            found = self._decoded[key] = self.framer.handleFrame(frame, dev_id, tid)
        if self._tcp and found[1] is not None:
            found[1].transaction_id = sent_tid
        return found


def run_now(coroutine):
    """The result of a coroutine that never suspends (pymodbus's
    datastore_update against the line's units, which await nothing)."""
    try:
        coroutine.send(None)
    except StopIteration as stop:
        return stop.value
    coroutine.close()
    raise RuntimeError("a simulated Modbus unit suspended; in-memory requests must complete at once")


class MemoryCable:
    """The in-memory line's record and its one fault, as NullModem has them
    (runtime/sim/null_modem.py): cut() and mend(), the bytes each side sent
    (the newest RECORD_BYTES at least)."""

    def __init__(self) -> None:
        self.is_cut = False
        self._wire = (bytearray(), bytearray())

    def cut(self) -> None:
        """Nothing goes through any more (bytes sent meanwhile are lost)."""
        self.is_cut = True

    def mend(self) -> None:
        self.is_cut = False

    def record(self, by_slave: bool, data: bytes) -> None:
        record = self._wire[by_slave]
        record.extend(data)
        keep_recent(record)

    def sent_by_master(self) -> bytes:
        return bytes(self._wire[0])

    def sent_by_slave(self) -> bytes:
        return bytes(self._wire[1])

    def clear(self) -> None:
        self._wire[0].clear()
        self._wire[1].clear()


class MemoryServer:
    """The line's end: one request frame in, the answer frame (or None: no
    answer) out, as pymodbus's ServerRequestHandler answers it."""

    def __init__(self, line: Line, context) -> None:
        self.line = line
        self.context = context  # the line's units as pymodbus's datastore (line._Line)
        self.codec = Codec(line.transport, server=True)
        self.malformed = 0  # request frames dropped: bad CRC, too short, unknown layout

    def exchange(self, frame: bytes) -> bytes | None:
        line = self.line
        cable = line.cable if isinstance(line.cable, MemoryCable) else None
        if cable is not None:
            if cable.is_cut:
                return None
            cable.record(False, frame)
        if line.silent:
            return None
        try:
            _used, pdu = self.codec.decode(frame, 0, 0)
        except ModbusIOException as exc:  # a function code pymodbus does not know
            response: ModbusPDU | None = ExceptionResponse(
                exc.fcode or 0, exception_code=ExcCodes.ILLEGAL_FUNCTION, device_id=exc.dev_id
            )
            assert response is not None
            response.transaction_id = exc.transaction_id
        else:
            if pdu is None:
                self.malformed += 1
                return None
            response = self._execute(pdu)
        if response is None:
            return None
        answer = self.codec.build(response)
        if cable is not None:
            cable.record(True, answer)
        return answer

    def _execute(self, pdu: ModbusPDU) -> ModbusPDU | None:
        """ServerRequestHandler.handle_request, with ignore_missing_devices
        and broadcast_enable, run at once."""
        try:
            if not pdu.dev_id:  # a broadcast: every unit executes it, none answers
                for dev_id in self.context.device_ids():
                    run_now(pdu.datastore_update(self.context, dev_id))
                return None
            response = run_now(pdu.datastore_update(self.context, pdu.dev_id))
        except NoSuchIdException:
            return None  # not on the line, or muted: no answer
        response.transaction_id = pdu.transaction_id
        response.dev_id = pdu.dev_id
        return response


class MemoryClient(ModbusClientMixin[ModbusPDU]):
    """pymodbus's request methods (read_coils ... readwrite_registers) over
    a MemoryServer; execute() frames, sends, retries and decodes as
    pymodbus's sync client does, without waiting."""

    def __init__(self, server: MemoryServer, settings: LinkSettings, gap_s: float) -> None:
        super().__init__()
        self.server = server
        self.settings = settings
        self.codec = Codec(settings.transport, server=False)
        self._tid = 0
        self._gap_s = gap_s
        if settings.transport == "rtu":
            char_bits = 1 + settings.data_bits + (0 if settings.parity == "N" else 1) + settings.stop_bits
            self._s_per_byte = char_bits / settings.baud
        else:
            self._s_per_byte = 0.0
        self.line_s = 0.0  # the last request: answered, the time on the line; not, every timeout
        self.sent = b""  # the last request frame
        self.received = b""  # the last reply frame to it (of the last attempt), b"" if none came

    def connect(self) -> bool:
        return True

    def close(self) -> None:
        pass

    def execute(self, no_response_expected: bool, request: ModbusPDU) -> ModbusPDU:
        self._number(request)
        return self.send(self.codec.build(request), request, no_response_expected)

    def resend(self, request: ModbusPDU, frame: bytes, taken: Callable[[bytes], object | None]):
        """execute(False, request) of a request sent before, whose frame
        (framed by pymodbus then) is at hand: a TCP frame gets the next
        transaction id. An answer that taken() accepts (not None) is what this
        returns; any other is decoded by pymodbus as execute() does."""
        if self._number(request):
            frame = self._tid.to_bytes(2, "big") + frame[2:]
        return self.send(frame, request, False, taken)

    def _number(self, request: ModbusPDU) -> bool:
        """TCP: give the request the next transaction id (True); RTU has none (False)."""
        if self.settings.transport != "tcp":
            return False
        self._tid = self._tid % 0xFFFF + 1
        request.transaction_id = self._tid
        return True

    def send(
        self,
        frame: bytes,
        request: ModbusPDU,
        no_response_expected: bool,
        taken: Callable[[bytes], object | None] | None = None,
    ):
        """The request's frame on the line, retried as pymodbus's sync client
        does; see execute() and resend()."""
        s = self.settings
        self.sent = frame
        self.received = b""
        self.line_s = 0.0
        for _attempt in range(s.retries + 1):
            answer = self.server.exchange(frame)
            if no_response_expected:
                return None
            if answer:
                self.received = answer
                on_line = self._gap_s + (len(frame) + len(answer)) * self._s_per_byte
                if taken is not None:
                    result = taken(answer)
                    if result is not None:
                        self.line_s += on_line
                        return result
                try:
                    _used, pdu = self.codec.decode(answer, request.dev_id, request.transaction_id)
                except ModbusIOException:
                    self.line_s += on_line  # pymodbus's client gives up at once on a reply it cannot decode
                    raise
                if pdu is not None:
                    self.line_s += on_line
                    return pdu
            self.line_s += s.timeout_s
        raise ModbusIOException(
            f"No response received after {s.retries} retries", request.function_code, dev_id=request.dev_id
        )
