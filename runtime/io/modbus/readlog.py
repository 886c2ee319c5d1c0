"""`softplc log STEM.modbus.log`: the Modbus frames `--bus-log` wrote
(buslog.py), each printed with its request or answer in words (Modbus
Application Protocol V1.1b3, 6: the function, the addresses as on the
wire, from 0, the values; 7: the exception codes), an answer read with
the request before it. An RTU frame's CRC is checked; a TCP frame's MBAP
header is shown as its transaction id.

    0.000000 drives TX 01 03 00 05 00 05 95 C8   unit 1: read holding registers 5..9
    0.003747 drives RX 01 03 0A 00 A1 ...        unit 1: holding registers 5..9 = 161, 0, 0, 0, 0
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

from pymodbus.framer.rtu import FramerRTU

from .buslog import HEADER
from .errors import EXCEPTION_CODES, error_text

_TABLES = {1: "coils", 2: "discrete inputs", 3: "holding registers", 4: "input registers"}


def read_log(path: Path, config) -> Iterator[str] | None:
    """The frames of path decoded, or None when it is no Modbus log of ours."""
    if not path.name.lower().endswith(".modbus.log"):
        return None
    transports = {conn.name: conn.transport for conn in config.modbus}
    return _lines(path, transports)


def _lines(path: Path, transports: dict) -> Iterator[str]:
    text = path.read_text(encoding="ascii", errors="replace")
    if not text.startswith(HEADER):
        raise ValueError("not a Modbus log of `softplc run --bus-log` (its first line is missing)")
    requests: dict = {}  # connection -> the last request's PDU
    for number, line in enumerate(text.splitlines()[1:], start=2):
        try:
            _t, connection, direction, *octets = line.split()
            frame = bytes.fromhex("".join(octets))
        except ValueError:
            raise ValueError(f"line {number}: not a frame line: {line[:60]!r}") from None
        words = _frame(frame, transports.get(connection, "rtu"), direction == "TX", requests, connection)
        yield f"{line:<60}  {words}"


def _frame(frame: bytes, transport: str, request: bool, requests: dict, connection: str) -> str:
    if transport == "tcp":
        if len(frame) < 8:
            return "(short frame)"
        head, unit, pdu = f"transaction {int.from_bytes(frame[:2], 'big')}, ", frame[6], frame[7:]
    else:
        if len(frame) < 4:
            return "(short frame)"
        if FramerRTU.compute_CRC(frame[:-2]) != int.from_bytes(frame[-2:], "big"):
            return "bad CRC"
        head, unit, pdu = "", frame[0], frame[1:-2]
    if request:
        requests[connection] = pdu
        return f"{head}unit {unit}: {_request(pdu)}"
    return f"{head}unit {unit}: {_answer(pdu, requests.get(connection, b''))}"


def _span(start: int, count: int) -> str:
    return f"{start}" if count == 1 else f"{start}..{start + count - 1}"


def _registers(data: bytes) -> list[int]:
    return [int.from_bytes(data[i : i + 2], "big") for i in range(0, len(data) - 1, 2)]


def _bits(data: bytes, count: int) -> str:
    return "".join(str((data[i // 8] >> (i % 8)) & 1) for i in range(min(count, 8 * len(data))))


def _request(pdu: bytes) -> str:
    fc = pdu[0] if pdu else 0
    if fc in _TABLES and len(pdu) >= 5:
        start, count = int.from_bytes(pdu[1:3], "big"), int.from_bytes(pdu[3:5], "big")
        return f"read {_TABLES[fc]} {_span(start, count)}"
    if fc == 5 and len(pdu) >= 5:
        state = {0xFF00: "ON", 0x0000: "OFF"}.get(int.from_bytes(pdu[3:5], "big"), f"0x{pdu[3:5].hex().upper()}")
        return f"write coil {int.from_bytes(pdu[1:3], 'big')} {state}"
    if fc == 6 and len(pdu) >= 5:
        return f"write holding register {int.from_bytes(pdu[1:3], 'big')} = {int.from_bytes(pdu[3:5], 'big')}"
    if fc == 15 and len(pdu) >= 6:
        start, count = int.from_bytes(pdu[1:3], "big"), int.from_bytes(pdu[3:5], "big")
        return f"write coils {_span(start, count)} = {_bits(pdu[6:], count)}"
    if fc == 16 and len(pdu) >= 6:
        start, count = int.from_bytes(pdu[1:3], "big"), int.from_bytes(pdu[3:5], "big")
        values = ", ".join(map(str, _registers(pdu[6:])))
        return f"write holding registers {_span(start, count)} = {values}"
    if fc == 23 and len(pdu) >= 10:
        read, count = int.from_bytes(pdu[1:3], "big"), int.from_bytes(pdu[3:5], "big")
        write, wcount = int.from_bytes(pdu[5:7], "big"), int.from_bytes(pdu[7:9], "big")
        values = ", ".join(map(str, _registers(pdu[10:])))
        return f"read holding registers {_span(read, count)}, write {_span(write, wcount)} = {values}"
    return f"function {fc}"


def _answer(pdu: bytes, request: bytes) -> str:
    fc = pdu[0] if pdu else 0
    if fc & 0x80:
        code = pdu[1] if len(pdu) > 1 else 0
        words = error_text(code) if code in EXCEPTION_CODES else "no exception code of Modbus"
        return f"exception {code} ({words}) to function {fc & 0x7F}"
    asked = request[0] if request else None
    if asked != fc:
        return f"function {fc} (no request of it before)"
    if fc in (1, 2) and len(pdu) >= 2 and len(request) >= 5:
        start, count = int.from_bytes(request[1:3], "big"), int.from_bytes(request[3:5], "big")
        return f"{_TABLES[fc]} {_span(start, count)} = {_bits(pdu[2:], count)}"
    if fc in (3, 4, 23) and len(pdu) >= 2:
        start = int.from_bytes(request[1:3], "big") if len(request) >= 3 else 0
        values = _registers(pdu[2 : 2 + pdu[1]])
        table = _TABLES.get(fc, "holding registers")
        return f"{table} {_span(start, len(values))} = {', '.join(map(str, values))}"
    if fc in (5, 6, 15, 16):
        return "done" if pdu == request[: len(pdu)] or fc in (15, 16) else "answer differs from the request"
    return f"function {fc}"


__all__ = ["read_log"]
