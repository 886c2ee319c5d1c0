"""Modbus replies for the fuzz harness: a request the master may send, and
the frames a hostile or broken unit answers it with (RTU: unit, PDU,
CRC-16; TCP: the MBAP header and the PDU), built byte by byte so that every
field can be wrong: the function code, the exception code, the unit, the
byte count, the number of items, the length, the CRC, the transaction id.

    requests()        a Transaction (link.py)
    replies(tx, tcp)  (frame or None, Reply) for that request
    HostileLine       what ModbusLink takes as its in-memory server
                      (wire.MemoryServer's place): it answers each request
                      frame with the next planned reply
"""

from __future__ import annotations

from dataclasses import dataclass

from hypothesis import strategies as st
from pymodbus.framer import FramerRTU

from softplc.runtime.io.modbus.functions import FUNCTIONS, READ_LIMIT, WRITE_LIMIT
from softplc.runtime.io.modbus.link import Transaction


@st.composite
def requests(draw) -> Transaction:
    fc = draw(st.sampled_from(sorted(FUNCTIONS)))
    reads, writes, bits = FUNCTIONS[fc]
    unit = draw(st.sampled_from([1, 2, 17, 247]) | st.integers(1, 247))
    count = draw(st.integers(1, min(READ_LIMIT[fc], 40))) if reads else 0
    values: tuple = ()
    if writes:
        n = draw(st.integers(1, min(WRITE_LIMIT[fc], 20)))
        values = tuple(draw(st.lists(st.booleans() if bits else st.integers(0, 0xFFFF), min_size=n, max_size=n)))
    offset = draw(st.integers(0, 0xFFFF - max(count, len(values))))
    return Transaction(unit=unit, function=fc, offset=offset, count=count, values=values, write_offset=offset)


@dataclass
class Reply:
    """What a reply is, for the oracle: faithful (True: a well-formed answer
    to the request, the master must take it; False: it must refuse it with
    an error code; None: either may be right, a TCP frame changed where no
    CRC tells), exception (a well-formed exception response, code 1..255),
    values: what a faithful read carries; how: the change, for messages."""

    faithful: bool | None
    exception: int = 0
    values: tuple = ()
    how: str = ""
    tid: int | None = None  # TCP: the transaction id sent back; None: the request's


def _pack_bits(bits) -> bytes:
    out = bytearray((len(bits) + 7) // 8)
    for i, b in enumerate(bits):
        if b:
            out[i // 8] |= 1 << (i % 8)
    return bytes(out)


def _pdu(tx: Transaction, fc: int, data) -> bytes:
    """The PDU of a faithful answer to tx (data: the items a read returns)."""
    reads, writes, bits = FUNCTIONS[tx.function]
    if reads:
        body = _pack_bits(data) if bits else b"".join(v.to_bytes(2, "big") for v in data)
        return bytes([fc, len(body)]) + body
    if tx.function in (5, 6):
        value = (0xFF00 if tx.values[0] else 0) if tx.function == 5 else tx.values[0]
        return bytes([fc]) + tx.offset.to_bytes(2, "big") + value.to_bytes(2, "big")
    return bytes([fc]) + tx.offset.to_bytes(2, "big") + len(tx.values).to_bytes(2, "big")


def frame(pdu: bytes, unit: int, tcp: bool, tid: int = 0) -> bytes:
    if tcp:
        return tid.to_bytes(2, "big") + b"\0\0" + (len(pdu) + 1).to_bytes(2, "big") + bytes([unit & 0xFF]) + pdu
    adu = bytes([unit & 0xFF]) + pdu
    return adu + FramerRTU.compute_CRC(adu).to_bytes(2, "big")


CHANGES = [
    "none",
    "none",
    "exception",
    "function",
    "unit",
    "byte count",
    "items",
    "truncate",
    "append",
    "flip",
    "crc",
    "garbage",
    "silence",
    "tid",
    "length",
]


@st.composite
def replies(draw, tx: Transaction, tcp: bool):
    """One reply to tx: (the frame, or None for no answer; its Reply). A TCP
    frame's transaction id is the request's (HostileLine puts it in) unless
    Reply.tid says another."""
    reads, _writes, bits = FUNCTIONS[tx.function]
    data: tuple = ()
    if reads:
        items = st.booleans() if bits else st.integers(0, 0xFFFF)
        data = tuple(draw(st.lists(items, min_size=tx.count, max_size=tx.count)))
    change = draw(st.sampled_from(CHANGES))
    if change == "garbage":
        return draw(st.binary(max_size=300)), Reply(False, how="garbage")
    if change == "silence":
        return None, Reply(False, how="silence")
    fc, unit = tx.function, tx.unit
    pdu = _pdu(tx, fc, data)
    reply = Reply(True, values=data, how=change)
    if change == "exception":
        code = draw(st.sampled_from([1, 2, 3, 4, 6, 11, 0x80, 0xFF]) | st.integers(1, 255))
        pdu, reply = bytes([fc | 0x80, code]), Reply(False, exception=code, how=f"exception {code}")
    elif change == "function":
        other = draw(st.sampled_from([f for f in range(1, 128) if f != fc]))
        pdu, reply = bytes([other]) + pdu[1:], Reply(False, how=f"function code {other}")
    elif change == "unit" and not tcp:  # a TCP reply's unit is only an echo
        unit = draw(st.sampled_from([u for u in (0, 1, 2, 247, 255) if u != tx.unit]))
        reply = Reply(False, how=f"unit {unit}")
    elif change == "byte count" and reads:
        wrong = draw(st.sampled_from([b for b in (0, 1, pdu[1] - 1, pdu[1] + 1, 255) if b != pdu[1] and 0 <= b <= 255]))
        pdu, reply = pdu[:1] + bytes([wrong]) + pdu[2:], Reply(False, how=f"byte count {wrong}")
    elif change == "items" and reads:
        n = draw(st.sampled_from([k for k in (0, tx.count - 1, tx.count + 1, tx.count + 8) if k not in (-1, tx.count)]))
        items = st.booleans() if bits else st.integers(0, 0xFFFF)
        other = tuple(draw(st.lists(items, min_size=n, max_size=n)))
        # a bit read answers in whole bytes: a count in the same bytes is no change
        same = bits and (n + 7) // 8 == (tx.count + 7) // 8
        pdu, reply = _pdu(tx, fc, other), Reply(same, values=other[: tx.count], how=f"{n} items")
        if same and n < tx.count:
            # fewer coils in the same bytes: the unset bits read as the missing
            # coils, and nothing on the wire tells it from a faithful answer
            reply = Reply(None, how=f"{n} items, in the bytes of {tx.count}")
    elif change == "tid" and tcp:
        wrong = draw(st.sampled_from([0, 0x1234, 0xFFFF]))
        reply = Reply(False, how=f"transaction id {wrong}", tid=wrong)
    out = frame(pdu, unit, tcp)
    if change == "length" and tcp:
        length = draw(st.sampled_from([0, 1, len(out) - 7, len(out) - 5, 0xFFFF]))
        out, reply = out[:4] + length.to_bytes(2, "big") + out[6:], Reply(False, how=f"length {length}")
    elif change == "truncate":
        out, reply = out[: draw(st.integers(0, len(out) - 1))], Reply(False, how="truncated")
    elif change == "append":
        out, reply = out + draw(st.binary(min_size=1, max_size=8)), Reply(None if tcp else False, how="bytes appended")
    elif change == "flip":
        i = draw(st.integers(0, len(out) - 1))
        flipped = out[:i] + bytes([out[i] ^ draw(st.integers(1, 255))]) + out[i + 1 :]
        out, reply = flipped, Reply(None if tcp else False, how=f"byte {i} changed")
    elif change == "crc" and not tcp:
        out, reply = out[:-2] + bytes([out[-2] ^ 0x01, out[-1]]), Reply(False, how="bad CRC")
    return out, reply


class HostileLine:
    """The in-memory server a ModbusLink talks to (wire.MemoryServer's
    place): each request frame gets the next planned reply."""

    class _Line:
        name = "hostile"

    def __init__(self, planned: list, tcp: bool) -> None:
        self.tcp = tcp
        self.line = self._Line()
        self.planned = list(planned)  # (frame or None, Reply)
        self.requests: list[bytes] = []

    def exchange(self, request: bytes) -> bytes | None:
        self.requests.append(request)
        if not self.planned:
            return None
        out, reply = self.planned.pop(0)
        if out is not None and len(out) >= 2 and self.tcp and reply.how not in ("garbage", "truncated"):
            asked = int.from_bytes(request[:2], "big")
            tid = asked if reply.tid is None else reply.tid if reply.tid != asked else reply.tid ^ 1
            out = tid.to_bytes(2, "big") + out[2:]
        return out
