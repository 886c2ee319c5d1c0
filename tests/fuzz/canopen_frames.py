"""CANopen traffic for the fuzz harness (canopen_rig.Rig): what the hostile
node 41 answers to the master's SDO requests, and the frames and pauses it
puts on the bus: boot-ups, heartbeats, EMCY, TPDOs of every length,
unsolicited SDO responses, NMT, SDO requests, RPDOs, SYNC and remote frames
to the simulated LTMR, frames of any id, bursts.

    sdo_plans()    [answer, ...]: each answers one SDO request (answer())
    events()       [(kind, ...), ...]: see canopen_rig.play
"""

from __future__ import annotations

from hypothesis import strategies as st

from .canopen_rig import HOSTILE, LTMR

NODES = (LTMR, HOSTILE)
OBJECTS = [(0x1017, 0), (0x1016, 1), (0x1800, 1), (0x1A00, 0), (0x1A00, 1), (0x2008, 5), (0x2004, 6), (0x1000, 0)]


def answer(request: bytes, plan: tuple) -> bytes | None:
    """The hostile node's answer to one SDO request: plan's kind, echoing the
    request's index and sub-index where the kind does."""
    req = request.ljust(8, b"\0")
    where = req[1:4]
    kind = plan[0]
    if kind == "ack":  # download confirmed
        return bytes([0x60]) + where + bytes(4)
    if kind == "upload":  # expedited upload of 1..4 bytes, or size not given
        data = plan[1]
        if not data:
            return bytes([0x42]) + where + bytes(4)
        return bytes([0x43 | ((4 - len(data)) << 2)]) + where + data.ljust(4, b"\0")
    if kind == "segmented":  # a segmented upload announced with its size
        return bytes([0x41]) + where + plan[1].to_bytes(4, "little")
    if kind == "abort":
        return bytes([0x80]) + where + plan[1].to_bytes(4, "little")
    if kind == "other object":  # the answer of another index
        return bytes([0x43]) + bytes([0x00, 0x20, 0x01]) + bytes(4)
    if kind == "raw":
        return plan[1]
    return None  # silence


def sdo_plans():
    answers = st.one_of(
        st.just(("ack",)),
        st.just(("ack",)),
        st.tuples(st.just("upload"), st.binary(max_size=4)),
        st.tuples(st.just("upload"), st.sampled_from([b"\xa8\x01\x00\x00", b"\xa9\x01\x00\x80", b"\x04"])),
        st.tuples(st.just("segmented"), st.sampled_from([0, 1, 7, 100, 0xFFFFFFFF])),
        st.tuples(
            st.just("abort"), st.sampled_from([0x06020000, 0x08000000, 0, 0xFFFFFFFF]) | st.integers(0, 2**32 - 1)
        ),
        st.just(("other object",)),
        st.tuples(st.just("raw"), st.binary(max_size=9).map(lambda b: b[:8])),
        st.just(("silence",)),
    )
    return st.lists(answers, max_size=40)


def _data(draw, lo: int = 0, hi: int = 8) -> bytes:
    return draw(st.binary(min_size=lo, max_size=hi))


@st.composite
def _frame(draw):
    kind = draw(
        st.sampled_from(
            ["boot", "heartbeat", "emcy", "tpdo", "tpdo", "sdo response", "nmt", "sdo request", "rpdo", "sync", "any"]
        )
    )
    node = draw(st.sampled_from([*NODES, *NODES, 1, 127]))
    if kind == "boot":
        return 0x700 + HOSTILE, b"\x00", False
    if kind == "heartbeat":
        # short ones and states that are no NMT state (issue 16: a traceback per frame)
        state = draw(st.sampled_from([0x00, 0x04, 0x05, 0x7F, 0x84, 0x85, 0xFF]) | st.integers(0, 255))
        return 0x700 + node, (bytes([state]) + _data(draw, 0, 7))[: draw(st.integers(0, 8))] or b"", False
    if kind == "emcy":
        code = draw(st.sampled_from([0x0000, 0x1000, 0x2310, 0xFF00]) | st.integers(0, 0xFFFF))
        return 0x80 + node, (code.to_bytes(2, "little") + _data(draw, 6, 6))[: draw(st.integers(0, 8))], False
    if kind == "tpdo":
        return draw(st.sampled_from([0x180, 0x280, 0x380, 0x480])) + node, _data(draw), False
    if kind == "sdo response":
        return 0x580 + node, _data(draw), False
    if kind == "nmt":
        command = draw(st.sampled_from([0x01, 0x02, 0x80, 0x81, 0x82]) | st.integers(0, 255))
        target = draw(st.sampled_from([0, LTMR, HOSTILE]) | st.integers(0, 255))
        return 0x000, (bytes([command, target]) + _data(draw, 0, 6))[: draw(st.integers(0, 8))], False
    if kind == "sdo request":
        if draw(st.booleans()):
            return 0x600 + LTMR, _data(draw), False
        index, sub = draw(st.sampled_from(OBJECTS))
        command = draw(st.sampled_from([0x40, 0x2F, 0x2B, 0x23, 0x22, 0x21, 0x60, 0x80, 0xA0, 0xC0]))
        return 0x600 + LTMR, bytes([command]) + index.to_bytes(2, "little") + bytes([sub]) + _data(draw, 4, 4), False
    if kind == "rpdo":
        return draw(st.sampled_from([0x200, 0x300, 0x400, 0x500])) + LTMR, _data(draw), False
    if kind == "sync":
        return 0x080, _data(draw, 0, 2), False
    remote = draw(st.booleans())
    can_id = draw(st.integers(0, 0x7FF) | st.integers(0x800, 0x1FFFFFFF))
    return can_id, b"" if remote else _data(draw), remote


@st.composite
def events(draw):
    out = [("frame", 0x700 + HOSTILE, b"\x00", False)]  # node 41 boots, the master configures it
    for _ in range(draw(st.integers(1, 40))):
        kind = draw(st.sampled_from(["frame", "frame", "frame", "time", "burst"]))
        if kind == "time":
            out.append(("time", draw(st.sampled_from([1, 10, 30, 100, 250, 1000]))))
        elif kind == "burst":
            out.append(("burst", draw(st.integers(2, 60)), *draw(_frame())))
        else:
            out.append(("frame", *draw(_frame())))
    return out
