"""Every Modbus reply checked against its request, before anything of it
reaches the image or the program.

pymodbus's client takes a reply for what it says it is: an answer of
function 4 to a function 3 request decodes as input registers, an exception
reply with code 0 as an exception "0", a byte count that disagrees with the
registers asked for as whatever registers it holds. The link (link.py)
therefore hands every reply frame it received, as it crossed the wire, to a
ReplyCheck, which splits it with pymodbus's own framer (RTU: address, PDU,
CRC-16; TCP: the MBAP header) and checks, in this order:

    header      TCP: the transaction id of the request, protocol id 0, a
                length that frames the PDU (RESPONSE_INVALID_HEADER,
                RESPONSE_INVALID_PROTOCOL); RTU: the CRC (RESPONSE_CRC_FAIL)
    unit        the unit asked (RESPONSE_WRONG_SLAVE)
    function    the function asked, or it with bit 7 set for an exception
                (RESPONSE_WRONG_FUNCTIONCODE)
    exception   two bytes, a code Modbus defines: 1..6, 8, 10, 11
                (RESPONSE_INVALID_DATA; 0 is not "no error")
    reads       byte count = 2 x registers, or (coils + 7) / 8, and exactly
                that many data bytes (RESPONSE_INVALID_DATA)
    writes      the echo of FC 5 / 6 (address, value) and FC 15 / 16
                (address, count) (RESPONSE_INVALID_DATA)

A bad reply is a BadReply: the error code and a message that says what was
wrong, in the unit's terms ("unit 1 answered function 4 to a function 3
request"). The link makes it the transaction's outcome: the channel fails
with it, the image keeps its last good values.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass

from .errors import EXCEPTION_CODES, ModbusError
from .functions import FUNCTIONS
from .messages import Transaction
from .wire import CODEC_FRAMES, framer


@dataclass(frozen=True)
class BadReply:
    error: int  # a ModbusError
    message: str


_ITEMS = {1: "coil", 2: "input", 3: "register", 4: "register", 23: "register"}


def _items(function: int, count: int) -> str:
    return f"{count} {_ITEMS[function]}{'' if count == 1 else 's'}"


def check_pdu(tx: Transaction, unit: int, pdu: bytes) -> BadReply | None:
    """What is wrong with the reply PDU of unit `unit` to tx, or None."""
    asked = tx.unit
    if unit != asked:
        return BadReply(ModbusError.RESPONSE_WRONG_SLAVE, f"unit {unit} answered a request to unit {asked}")
    if not pdu:
        return BadReply(ModbusError.RESPONSE_INVALID_DATA, f"unit {asked} sent an empty reply")
    function = pdu[0]
    if function == tx.function | 0x80:
        if len(pdu) != 2:
            return BadReply(
                ModbusError.RESPONSE_INVALID_DATA,
                f"unit {asked} sent an exception reply of {len(pdu)} bytes (2 expected)",
            )
        if pdu[1] not in EXCEPTION_CODES:
            return BadReply(
                ModbusError.RESPONSE_INVALID_DATA,
                f"unit {asked} answered exception code {pdu[1]}, which Modbus does not define",
            )
        return None
    if function != tx.function:
        what = f"function {function & 0x7F}"
        if function & 0x80:
            what += f" (exception {pdu[1]})" if len(pdu) > 1 else " (exception)"
        return BadReply(
            ModbusError.RESPONSE_WRONG_FUNCTIONCODE, f"unit {asked} answered {what} to a function {tx.function} request"
        )
    reads, _writes, bits = FUNCTIONS[function]
    if reads:
        return _check_read(tx, pdu, bits)
    return _check_echo(tx, pdu)


def _check_read(tx: Transaction, pdu: bytes, bits: bool) -> BadReply | None:
    if len(pdu) < 2:
        return BadReply(ModbusError.RESPONSE_INVALID_DATA, f"unit {tx.unit} sent a reply without a byte count")
    expected = (tx.count + 7) // 8 if bits else 2 * tx.count
    count = pdu[1]
    if count != expected:
        return BadReply(
            ModbusError.RESPONSE_INVALID_DATA,
            f"unit {tx.unit} sent byte count {count} for {_items(tx.function, tx.count)} ({expected} expected)",
        )
    if len(pdu) - 2 != count:
        return BadReply(
            ModbusError.RESPONSE_INVALID_DATA,
            f"unit {tx.unit} sent {len(pdu) - 2} data bytes after a byte count of {count}",
        )
    return None


def _check_echo(tx: Transaction, pdu: bytes) -> BadReply | None:
    """FC 5, 6, 15, 16 answer with address and value (5, 6) or count (15, 16)."""
    function = tx.function
    if len(pdu) != 5:
        return BadReply(
            ModbusError.RESPONSE_INVALID_DATA,
            f"unit {tx.unit} sent a reply of {len(pdu)} bytes to a function {function} write (5 expected)",
        )
    address, value = struct.unpack_from(">HH", pdu, 1)
    if address != tx.offset:
        return BadReply(ModbusError.RESPONSE_INVALID_DATA, f"unit {tx.unit} echoed address {address} for {tx.offset}")
    if function == 5:
        expected, what = (0xFF00 if tx.values[0] else 0x0000), "value"
    elif function == 6:
        expected, what = int(tx.values[0]) & 0xFFFF, "value"
    else:
        expected, what = len(tx.values), "count"
    if value != expected:
        return BadReply(ModbusError.RESPONSE_INVALID_DATA, f"unit {tx.unit} echoed {what} {value} for {expected}")
    return None


class ReplyCheck:
    """The checks of one connection: split(sent, frame) with pymodbus's
    client framer, then check_pdu. Splitting a frame (an RTU CRC) is
    remembered, like the in-memory wire's Codec does, so a reply repeated
    byte for byte is split once."""

    def __init__(self, transport: str) -> None:
        self.transport = transport
        self._framer = framer(transport, server=False)
        self._split: dict[bytes, tuple[int, bytes] | BadReply] = {}

    def __call__(self, tx: Transaction, sent: bytes, frame: bytes) -> BadReply | None:
        """What is wrong with frame, the reply to tx (sent: the request frame), or None."""
        split = self.split(sent, frame)
        if isinstance(split, BadReply):
            return BadReply(split.error, f"unit {tx.unit}: {split.message}")
        return check_pdu(tx, *split)

    def split(self, sent: bytes, frame: bytes) -> tuple[int, bytes] | BadReply:
        """(unit, PDU) of a reply frame, or what keeps it from framing."""
        tcp = self.transport == "tcp"
        if tcp:
            if len(frame) < 8:
                return BadReply(
                    ModbusError.RESPONSE_INVALID_HEADER,
                    f"a reply of {len(frame)} bytes, shorter than a Modbus TCP header",
                )
            if frame[2:4] != b"\0\0":
                return BadReply(
                    ModbusError.RESPONSE_INVALID_PROTOCOL,
                    f"protocol id {int.from_bytes(frame[2:4], 'big')} in the reply's header (Modbus is 0)",
                )
            if frame[:2] != sent[:2]:
                return BadReply(
                    ModbusError.RESPONSE_INVALID_HEADER,
                    f"transaction id {int.from_bytes(frame[:2], 'big')} in the reply to "
                    f"transaction {int.from_bytes(sent[:2], 'big')}",
                )
            key = frame[2:]
        else:
            key = frame
        found = self._split.get(key)
        if found is None:
            if len(self._split) >= CODEC_FRAMES:
                self._split.clear()
            found = self._split[key] = self._decode(frame, tcp)
        return found

    def _decode(self, frame: bytes, tcp: bool) -> tuple[int, bytes] | BadReply:
        used, unit, _tid, pdu = self._framer.decode(frame)
        size = len(pdu) + (7 if tcp else 3)  # the frame around the PDU: MBAP header; address and CRC
        if pdu and len(frame) != size:
            # pymodbus's framer takes a frame out of what came (skipping bytes
            # before it, ignoring any after): all of it is the reply, and a
            # master that frames by the line's silence (RTU) checks the CRC
            # over all of it; a TCP reply is its header's length, no more
            return BadReply(
                ModbusError.RESPONSE_INVALID_HEADER if tcp else ModbusError.RESPONSE_CRC_FAIL,
                f"a reply of {len(frame)} bytes around a {size}-byte frame",
            )
        if pdu:
            return unit, bytes(pdu)
        if tcp:
            return BadReply(
                ModbusError.RESPONSE_INVALID_HEADER,
                f"a reply of {len(frame)} bytes, shorter than its header's length {int.from_bytes(frame[4:6], 'big')}",
            )
        if used:
            return BadReply(ModbusError.RESPONSE_CRC_FAIL, f"a reply of {len(frame)} bytes whose CRC does not match")
        return BadReply(ModbusError.RESPONSE_INVALID_DATA, f"a reply of {len(frame)} bytes that does not frame")
