"""Plain CAN frames into the plain-CAN driver (runtime/io/plaincan) and the
MPU2-S node on it, in an engine built from a configuration as `softplc run`
builds it, in virtual time, on python-can's `virtual` interface (a channel
of its own per example); with or without the simulated MPU2-S on the bus,
which gets the requests sent to it.

The frames: telegram frames (DDh, a mux, three words), read and write
replies (FFh/EEh, with a checksum right or wrong), requests on 33Fh, frames
of other devices and of any id, of every length, in bursts and between
pauses. Every frame at the node's CAN-ID is counted as malformed and
dropped, or applied: a telegram frame's words are in %IW300.. after the
next read_inputs. Nothing escapes, nothing hangs, nothing is logged with a
traceback.
"""

from __future__ import annotations

import atexit
import itertools
import shutil
import tempfile
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from softplc.runtime.config import config_from_dict
from softplc.runtime.devices.mpu2s import frames as F
from softplc.runtime.engine.build import build_engine
from softplc.runtime.io.can.bus import BusSettings, CanEndpoint, open_bus
from softplc.runtime.io.plaincan import PlainCanDriver

from .support import LogWatch, assert_no_tracebacks, bounded, fuzz, long, short

DEVICE = 1
NODE_ID = F.device_can_id(DEVICE)  # 321h: what the device sends
_channels = itertools.count()
_dir = Path(tempfile.mkdtemp(prefix="softplc-fuzz-plaincan-"))
atexit.register(shutil.rmtree, _dir, True)
(_dir / "p.st").write_text("PROGRAM P\nEND_PROGRAM\n")


def _config(channel: str, with_sim: bool) -> dict:
    return {
        "plc": {"programs": [str(_dir / "p.st")]},
        "task": [{"name": "Main", "interval": "10ms", "programs": ["P"]}],
        "can": [{"name": "can0", "interface": "virtual", "channel": channel, "bitrate": 125000}],
        "plaincan": [{"type": "mpu2s", "device": DEVICE, "telegram": "%IW300", "password": 1234}],
        "sim": [{"type": "mpu2s", "node_id": DEVICE, "password": 1234}] if with_sim else [],
    }


@st.composite
def _frame(draw):
    kind = draw(st.sampled_from(["telegram", "telegram", "reply", "request", "other", "any"]))
    if kind == "telegram":
        mux = draw(st.integers(0, F.MUX_MAX) | st.integers(0, 255))
        data = bytes([F.KIND_TELEGRAM, mux]) + draw(st.binary(min_size=6, max_size=6))
        return NODE_ID, data[: draw(st.sampled_from([8, 8, 8, 0, 1, 7]))]
    if kind in ("reply", "request"):
        head = bytes([draw(st.sampled_from([F.KIND_READ, F.KIND_WRITE, 0x00])), draw(st.sampled_from([DEVICE, 2, 0]))])
        head += draw(st.binary(min_size=4, max_size=4))
        tail = F.checksum(head) if draw(st.booleans()) else draw(st.binary(min_size=2, max_size=2))
        return (NODE_ID if kind == "reply" else F.REQUEST_ID), (head + tail)[: draw(st.sampled_from([8, 8, 6, 0]))]
    if kind == "other":
        return draw(st.integers(0x320, 0x33F)), draw(st.binary(max_size=8))
    return draw(st.integers(0, 0x7FF)), draw(st.binary(max_size=8))


@st.composite
def traffic(draw):
    """(with the simulator, [events]): ("frame", id, data), ("burst", n, id, data), ("time", ms)."""
    out = []
    for _ in range(draw(st.integers(1, 40))):
        kind = draw(st.sampled_from(["frame", "frame", "frame", "time", "burst"]))
        if kind == "time":
            out.append(("time", draw(st.sampled_from([1, 10, 50, 300, 1500]))))
        elif kind == "burst":
            out.append(("burst", draw(st.integers(2, 40)), *draw(_frame())))
        else:
            out.append(("frame", *draw(_frame())))
    return draw(st.booleans()), out


def _send(engine, driver, producer, can_id: int, data: bytes) -> str:
    node = driver.nodes[0]
    malformed = driver.malformed[node.name]
    producer.send(can_id, data)
    driver.port.pump.settle()
    if can_id != NODE_ID:
        return "other id"
    if driver.malformed[node.name] == malformed + 1:
        return "malformed, counted"
    assert driver.malformed[node.name] == malformed, "one frame counted twice"
    if data[:1] == bytes([F.KIND_TELEGRAM]):
        driver.read_inputs(engine.image)
        mux = data[1]
        for i in range(3):
            word = int.from_bytes(data[2 + 2 * i : 4 + 2 * i], "big")
            got = engine.image.read(f"%IW{300 + 3 * mux + i}")
            assert got == word, f"telegram [{data.hex(' ')}]: %IW{300 + 3 * mux + i} = {got:04X}h, not {word:04X}h"
        return "telegram applied"
    return "reply taken"


def play(case) -> tuple[int, dict]:
    with_sim, events = case
    channel = f"fuzz-plaincan-{next(_channels)}"
    outcomes: dict = {}
    sent = 0
    with LogWatch() as watch, bounded("plain CAN frames"):
        engine = build_engine(config_from_dict(_config(channel, with_sim), _dir / "plant.toml"), virtual_time=True)
        driver = next(d for d in engine.drivers if isinstance(d, PlainCanDriver))
        engine.start()
        producer = CanEndpoint(open_bus(BusSettings("virtual", channel, 125000)), name="hostile", pump=driver.port.pump)
        producer.start()
        try:
            for event in events:
                if event[0] == "time":
                    engine.run(duration_ns=event[1] * 1_000_000)
                    outcome = "time"
                else:
                    n, can_id, data = (1, *event[1:]) if event[0] == "frame" else event[1:]
                    for _ in range(n):
                        outcome = _send(engine, driver, producer, can_id, data)
                    sent += n
                outcomes[outcome] = outcomes.get(outcome, 0) + 1
            engine.run(cycles=2)
            driver.status()
        finally:
            producer.stop()
            engine.stop()
    assert_no_tracebacks(watch, "plain CAN frames")
    return sent, outcomes


@pytest.mark.slow  # whole plants or buses
@short(15)
@given(traffic())
def test_plain_can_frames_are_applied_or_counted(case):
    play(case)


@fuzz
def test_long_plain_can_frames(tally, shard):
    counts = tally("frames")

    @long("frames", 0.15, shard, per_example=65)
    @given(traffic())
    def run(case):
        frames, outcomes = play(case)
        counts.inputs += frames
        counts.update({f"plaincan {k}": v for k, v in outcomes.items()})

    run()
