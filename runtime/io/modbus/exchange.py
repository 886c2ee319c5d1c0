"""MODBUS_EXCHANGE: one Modbus transaction started by the program
(ExecContext.modbus), the runtime side of MODBUS_REQUEST (fblocks/comm/modbus.st).

    MODBUS_EXCHANGE(CONNECTION, UNIT, FUNCTION, READ_OFFSET, READ_COUNT,
                    WRITE_OFFSET, WRITE_COUNT, SEND, RECEIVE, MGMT)

queues the transaction to the connection's worker and returns at once, like
READ_VAR (runtime/io/canopen/sdo.py); the result is copied into RECEIVE and
MGMT at the start of a later cycle. Offsets are PDU addresses (an Eaton "ID n"
is offset n-1). SEND and RECEIVE are word tables; coils and discrete inputs
travel packed, 16 to a word, the first one in bit 0.

The management table (4 words):

    word 0  bit 0 activity (set by the call, cleared when the exchange ends),
            MSB exchange number
    word 1  result: 0 done, 1..11 the slave's exception code, 16#A1..16#FF
            the master's codes (runtime/io/link.ModbusError)
    word 2  items received (registers or bits)
    word 3  response time in ms (real time)

A call while word 0 bit 0 is set starts nothing and returns FALSE.
"""

from __future__ import annotations

import threading
from collections.abc import Callable

from ...st.native import ANY_INT, STRING, WORDS, NativeFunction, Param
from ..canopen.sdo import store_word
from .functions import FUNCTIONS, check_request
from .link import ModbusError, Outcome, Transaction


def unpack_bits(words, count: int) -> list:
    return [bool((int(words[i // 16]) >> (i % 16)) & 1) for i in range(count)]


def pack_bits(bits) -> list:
    words = [0] * ((len(bits) + 15) // 16)
    for i, bit in enumerate(bits):
        if bit:
            words[i // 16] |= 1 << (i % 16)
    return words


class _Exchange:
    def __init__(self, receive, mgmt, receive_signed: bool, mgmt_signed: bool, bits: bool) -> None:
        self.receive = receive
        self.mgmt = mgmt
        self.receive_signed = receive_signed
        self.mgmt_signed = mgmt_signed
        self.bits = bits
        self.outcome: Outcome | None = None  # set by the worker


class ModbusExchangeService:
    """request() runs in the scan thread while the program runs; collect() at
    the start of each cycle. submit(connection name, transaction, done) hands
    a transaction to that connection's worker (False: no such connection)."""

    def __init__(self, submit: Callable[[str, Transaction, Callable[[Outcome], None]], bool]) -> None:
        self._submit = submit
        self._running: list[_Exchange] = []
        self._lock = threading.Lock()

    def request(
        self,
        name: str,
        connection: str,
        unit: int,
        function: int,
        read_offset: int,
        read_count: int,
        write_offset: int,
        write_count: int,
        send,
        receive,
        mgmt,
        send_signed: bool = False,
        receive_signed: bool = False,
        mgmt_signed: bool = False,
    ) -> bool:
        m0 = int(mgmt[0]) & 0xFFFF
        if m0 & 1:
            return False
        function, read_count, write_count = int(function), int(read_count), int(write_count)
        reads, writes, bits = FUNCTIONS.get(function, (False, False, False))
        ex = _Exchange(receive, mgmt, receive_signed, mgmt_signed, bits)
        store_word(mgmt, 0, ((((m0 >> 8) + 1) & 0xFF) << 8) | 1, mgmt_signed)
        for i in (1, 2, 3):
            store_word(mgmt, i, 0, mgmt_signed)
        problem = check_request(function, read_count, write_count if writes else 0)
        room = 16 * len(receive) if bits else len(receive)
        send_room = 16 * len(send) if bits else len(send)
        if problem is None and ((reads and read_count > room) or (writes and write_count > send_room)):
            problem = "table too small"
        if problem is not None or not 0 <= int(unit) <= 255:
            self._finish(ex, Outcome(ModbusError.INVALID_REQUEST, message=problem or "unit beyond 0..255"))
            return False
        if writes:
            values = tuple(
                unpack_bits(send, write_count) if bits else [int(send[i]) & 0xFFFF for i in range(write_count)]
            )
        else:
            values = ()
        offset = int(write_offset) if writes and not reads else int(read_offset)
        tx = Transaction(
            int(unit), function, offset & 0xFFFF, read_count if reads else 0, values, int(write_offset) & 0xFFFF
        )

        def done(outcome: Outcome, ex=ex) -> None:
            ex.outcome = outcome

        with self._lock:
            self._running.append(ex)
        if not self._submit(str(connection), tx, done):
            with self._lock:
                self._running.remove(ex)
            self._finish(
                ex, Outcome(ModbusError.REQUEST_FAILED_TO_SEND, message=f"no Modbus connection named {connection!r}")
            )
            return False
        return True

    def collect(self) -> None:
        if not self._running:  # only request(), in this same thread, adds to it
            return
        finished = []
        with self._lock:
            running, self._running = self._running, []
            for ex in running:  # outcome is set by the worker thread: read it once
                outcome = ex.outcome
                if outcome is None:
                    self._running.append(ex)
                else:
                    finished.append((ex, outcome))
        for ex, outcome in finished:
            self._finish(ex, outcome)

    def busy(self) -> bool:
        with self._lock:
            return bool(self._running)

    @staticmethod
    def _finish(ex: _Exchange, outcome: Outcome) -> None:
        values = outcome.values if outcome.error == ModbusError.OK else []
        words = pack_bits(values) if ex.bits else values
        for i, w in enumerate(words[: len(ex.receive)]):
            store_word(ex.receive, i, int(w), ex.receive_signed)
        mgmt, signed = ex.mgmt, ex.mgmt_signed
        store_word(mgmt, 1, int(outcome.error), signed)
        store_word(mgmt, 2, len(values), signed)
        store_word(mgmt, 3, min(int(outcome.response_s * 1000), 0xFFFF), signed)
        store_word(mgmt, 0, int(mgmt[0]) & ~1, signed)


class NoModbus:
    """MODBUS_EXCHANGE without a [[modbus]] connection: the exchange ends at
    once with result 16#A5, REQUEST_FAILED_TO_SEND (link.ModbusError).
    The Modbus master's service replaces this."""

    def request(
        self,
        name: str,
        connection,
        unit,
        function,
        read_offset,
        read_count,
        write_offset,
        write_count,
        send,
        receive,
        mgmt,
        *signed,
    ) -> bool:
        mgmt[0] = mgmt[0] & ~1
        mgmt[1] = int(ModbusError.REQUEST_FAILED_TO_SEND)
        return False


#: the ExecContext service of MODBUS_EXCHANGE (ModbusExchangeService)
SERVICE = "modbus.exchange"
_ARGS = (
    "CONNECTION",
    "UNIT",
    "FUNCTION",
    "READ_OFFSET",
    "READ_COUNT",
    "WRITE_OFFSET",
    "WRITE_COUNT",
    "SEND",
    "RECEIVE",
    "MGMT",
)
_TABLE = "an ARRAY OF WORD (or INT/UINT)"

MODBUS_EXCHANGE = NativeFunction(
    "MODBUS_EXCHANGE",
    (
        Param("CONNECTION", STRING, "CONNECTION", "the name of a [[modbus]] connection, a STRING"),
        *(Param(name, ANY_INT, name) for name in _ARGS[1:7]),
        Param("SEND", WORDS, "SEND", _TABLE),
        Param("RECEIVE", WORDS, "RECEIVE", _TABLE),
        Param("MGMT", WORDS, "MGMT", _TABLE, min_words=4),
    ),
    service=SERVICE,
    fallback=NoModbus(),
    usage=f"MODBUS_EXCHANGE({', '.join(_ARGS)}); or use the MODBUS_REQUEST block",
)
