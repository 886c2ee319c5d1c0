"""The Modbus application protocol as this server speaks it (Modbus
Application Protocol Specification V1.1b3): a request PDU parsed into a
``Request`` or refused with the exception code the specification gives,
and the answer PDU built. No I/O here: server.py frames, reads and writes.

    request = parse(pdu)          # ModbusError(code) for a request to refuse
    reply = answer(request, pdu, read_values)
    reply = exception(pdu[0], code)

The checks come in the specification's order (its figures 9 to 22, one per
function): the function code (01 ILLEGAL FUNCTION), then the quantity and
the structure of the request (03 ILLEGAL DATA VALUE: a count out of range,
a byte count that does not match, a PDU of the wrong length, a coil value
other than 0000h or FF00h), then the address (02, server.py's mapping),
then the execution (04).

Functions answered: 1 read coils, 2 read discrete inputs, 3 read holding
registers, 4 read input registers, 5 write single coil, 6 write single
register, 15 write multiple coils, 16 write multiple registers, 22 mask
write register, 23 read/write multiple registers. Every other code gets
01, among them the serial-line-only diagnostics (7, 8, 11, 12, 17: this
server names no stack and no device), the file records (20, 21), the FIFO
queue (24: the PLC has none) and device identification (43).
"""

from __future__ import annotations

import struct
from dataclasses import dataclass

ILLEGAL_FUNCTION = 0x01
ILLEGAL_DATA_ADDRESS = 0x02
ILLEGAL_DATA_VALUE = 0x03
SERVER_DEVICE_FAILURE = 0x04
SERVER_DEVICE_BUSY = 0x06

READ_COILS, READ_DISCRETE_INPUTS, READ_HOLDING, READ_INPUT = 1, 2, 3, 4
WRITE_COIL, WRITE_REGISTER, WRITE_COILS, WRITE_REGISTERS = 5, 6, 15, 16
MASK_WRITE, READ_WRITE = 22, 23
FUNCTIONS = frozenset(
    (READ_COILS, READ_DISCRETE_INPUTS, READ_HOLDING, READ_INPUT)
    + (WRITE_COIL, WRITE_REGISTER, WRITE_COILS, WRITE_REGISTERS, MASK_WRITE, READ_WRITE)
)

#: the quantities a request may ask for (the specification's limits: an answer fits 253 bytes)
MAX_READ_BITS = 2000
MAX_READ_REGISTERS = 125
MAX_WRITE_BITS = 1968
MAX_WRITE_REGISTERS = 123
MAX_READ_WRITE_REGISTERS = 121  # the write part of function 23
#: a PDU is at most 253 bytes (an ADU of 260 less the MBAP header and its unit id)
MAX_PDU = 253
COIL_ON, COIL_OFF = 0xFF00, 0x0000


class ModbusError(Exception):
    """A request answered with an exception code."""

    def __init__(self, code: int, why: str = "") -> None:
        super().__init__(why or f"exception {code:02X}")
        self.code = code


@dataclass(frozen=True)
class Request:
    """What a request asks: read count items from address, and/or write
    values (bools for coils, 0..65535 for registers) from write_address."""

    function: int
    address: int = 0
    count: int = 0
    values: tuple = ()
    write_address: int = 0
    and_mask: int = 0
    or_mask: int = 0

    @property
    def reads(self) -> bool:
        return self.function in (READ_COILS, READ_DISCRETE_INPUTS, READ_HOLDING, READ_INPUT, READ_WRITE)


def _quantity(n: int, most: int, what: str) -> None:
    if not 1 <= n <= most:
        raise ModbusError(ILLEGAL_DATA_VALUE, f"{what}: {n}, not 1..{most}")


def _length(pdu: bytes, expected: int) -> None:
    if len(pdu) != expected:
        raise ModbusError(ILLEGAL_DATA_VALUE, f"function {pdu[0]}: {len(pdu)} bytes, not {expected}")


def parse(pdu: bytes) -> Request:
    """The request in pdu (function code first); ModbusError with its exception code."""
    if not pdu:
        raise ModbusError(ILLEGAL_FUNCTION, "no function code")
    function = pdu[0]
    if function not in FUNCTIONS:
        raise ModbusError(ILLEGAL_FUNCTION, f"function {function} is not served")
    if function in (READ_COILS, READ_DISCRETE_INPUTS, READ_HOLDING, READ_INPUT):
        _length(pdu, 5)
        address, count = struct.unpack_from(">HH", pdu, 1)
        bits = function in (READ_COILS, READ_DISCRETE_INPUTS)
        _quantity(count, MAX_READ_BITS if bits else MAX_READ_REGISTERS, "quantity")
        return Request(function, address, count)
    if function in (WRITE_COIL, WRITE_REGISTER):
        _length(pdu, 5)
        address, value = struct.unpack_from(">HH", pdu, 1)
        if function == WRITE_COIL:
            if value not in (COIL_ON, COIL_OFF):
                raise ModbusError(ILLEGAL_DATA_VALUE, f"coil value {value:04X}h, not FF00h or 0000h")
            return Request(function, write_address=address, values=(value == COIL_ON,))
        return Request(function, write_address=address, values=(value,))
    if function in (WRITE_COILS, WRITE_REGISTERS):
        if len(pdu) < 6:
            raise ModbusError(ILLEGAL_DATA_VALUE, f"function {function}: {len(pdu)} bytes")
        address, count, size = struct.unpack_from(">HHB", pdu, 1)
        if function == WRITE_COILS:
            _quantity(count, MAX_WRITE_BITS, "quantity")
            expected = (count + 7) // 8
        else:
            _quantity(count, MAX_WRITE_REGISTERS, "quantity")
            expected = 2 * count
        if size != expected:
            raise ModbusError(ILLEGAL_DATA_VALUE, f"byte count {size}, not {expected}")
        _length(pdu, 6 + size)
        data = pdu[6:]
        if function == WRITE_COILS:
            packed = int.from_bytes(data, "little")
            return Request(function, write_address=address, values=tuple(bool(packed >> i & 1) for i in range(count)))
        return Request(function, write_address=address, values=struct.unpack(f">{count}H", data))
    if function == MASK_WRITE:
        _length(pdu, 7)
        address, and_mask, or_mask = struct.unpack_from(">HHH", pdu, 1)
        return Request(function, write_address=address, and_mask=and_mask, or_mask=or_mask)
    # READ_WRITE
    if len(pdu) < 10:
        raise ModbusError(ILLEGAL_DATA_VALUE, f"function {function}: {len(pdu)} bytes")
    address, count, write_address, write_count, size = struct.unpack_from(">HHHHB", pdu, 1)
    _quantity(count, MAX_READ_REGISTERS, "read quantity")
    _quantity(write_count, MAX_READ_WRITE_REGISTERS, "write quantity")
    if size != 2 * write_count:
        raise ModbusError(ILLEGAL_DATA_VALUE, f"byte count {size}, not {2 * write_count}")
    _length(pdu, 10 + size)
    values = struct.unpack(f">{write_count}H", pdu[10:])
    return Request(function, address, count, values, write_address)


def masked(current: int, and_mask: int, or_mask: int) -> int:
    """Function 22's result: (current AND and_mask) OR (or_mask AND NOT and_mask)."""
    return (current & and_mask) | (or_mask & ~and_mask & 0xFFFF)


def answer(request: Request, pdu: bytes, read: list | None = None) -> bytes:
    """The normal answer to request (pdu as received), with the values read."""
    function = request.function
    if function in (READ_COILS, READ_DISCRETE_INPUTS):
        assert read is not None
        bits = sum(1 << i for i, bit in enumerate(read) if bit)
        data = bits.to_bytes((len(read) + 7) // 8, "little")
        return bytes((function, len(data))) + data
    if function in (READ_HOLDING, READ_INPUT, READ_WRITE):
        assert read is not None
        return bytes((function, 2 * len(read))) + struct.pack(f">{len(read)}H", *read)
    if function in (WRITE_COILS, WRITE_REGISTERS):
        return struct.pack(">BHH", function, request.write_address, len(request.values))
    return bytes(pdu)  # 5, 6, 22: the request echoed


def exception(function: int, code: int) -> bytes:
    """The exception answer: the function code with its high bit set, then the code."""
    return bytes(((function | 0x80) & 0xFF, code))
