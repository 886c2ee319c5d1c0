"""Frames of the wrong length and floods, from a real python-can bus on the
virtual interface, at the CANopen master of a plant in virtual time: a short
EMCY, heartbeat, SDO answer or TPDO is counted (CANOPEN_NODE[n].Malformed,
CANOPEN_MASTER.Malformed, the status line) and logged once per 10 s, never
with a traceback; a flood of EMCYs gives a bounded number of log lines whose
"suppressed" counts add up; canopen's own lines ("Transfer aborted ...") come
through softplc's logging, rate limited too."""

from __future__ import annotations

import io
import logging
import re

import can
import pytest

from softplc.runtime.io.canopen.sdo import SdoJob

from .plant import LTMR_NODE

S = 1_000_000_000
MS = 1_000_000

WATCH = """
PROGRAM Watch
VAR
    operational : BOOL;
    malformed : UDINT;
    allMalformed : UDINT;
    emergencies : UDINT;
END_VAR
operational := CANOPEN_NODE[40].Operational;
malformed := CANOPEN_NODE[40].Malformed;
allMalformed := CANOPEN_MASTER.Malformed;
emergencies := CANOPEN_NODE[40].Emergencies;
END_PROGRAM
"""


@pytest.fixture
def plant(plants, caplog):
    caplog.set_level(logging.INFO)
    plant = plants(WATCH, program="Watch")
    plant.run_until(lambda: plant.get("Watch.operational"), 300, "node 40 operational")
    bus = can.Bus(interface="virtual", channel=plant.config.can[0].channel)  # someone else on the bus
    plant.send = lambda can_id, data: bus.send(can.Message(arbitration_id=can_id, data=data, is_extended_id=False))
    yield plant
    bus.shutdown()


def _canopen_lines(caplog) -> list:
    return [r for r in caplog.records if r.name.startswith("softplc.runtime.io.canopen")]


def _suppressed(lines) -> int:
    return sum(int(m.group(1)) for r in lines if (m := re.match(r"suppressed (\d+) ", r.getMessage())))


@pytest.mark.parametrize(
    "can_id, data, rule",
    [
        (0x0A8, b"\x10\x81\x11", "3 bytes, an EMCY has 8"),  # EMCY of node 40, cut short
        (0x728, b"", "0 bytes, a heartbeat has 1"),
        (0x728, b"\x05\x00", "2 bytes, a heartbeat has 1"),
        (0x5A8, b"\x43\x00", "2 bytes, an SDO answer has 8"),
        (0x1A8, b"\x01\x02", "2 bytes, its mapping needs 8"),  # TPDO1: four words mapped
    ],
)
def test_a_malformed_frame_is_counted_and_logged_once_without_a_traceback(plant, caplog, can_id, data, rule):
    caplog.clear()
    for _ in range(50):
        plant.send(can_id, data)
    plant.scan(2)
    assert plant.get("Watch.malformed") == 50 and plant.get("Watch.allMalformed") == 50
    assert plant.get("Watch.operational")  # nothing else happened to the node
    assert "1/1 up, 50 malformed" in plant.master.status().message
    assert not [r for r in caplog.records if r.exc_info], "a traceback was logged"
    dropped = [r.getMessage() for r in _canopen_lines(caplog) if "dropped" in r.getMessage()]
    assert dropped == [f"canopen: node motor (40): frame 0x{can_id:03X} [{data.hex(' ')}] dropped: {rule}"]
    plant.run_ms(10_100)  # the interval ends: the 49 held back are told
    told = [r.getMessage() for r in _canopen_lines(caplog) if r.getMessage().startswith("suppressed")]
    assert told == [f"suppressed 49 similar messages in 10 s; the last: {dropped[0]}"]


def test_an_emcy_flood_gives_a_few_lines_that_add_up(plant, caplog):
    caplog.clear()
    emcy = bytes.fromhex("10 81 11 00 00 00 00 00")  # 8110h CAN overrun, error register 11h
    for _ in range(100):  # 100 ticks of 10 ms, 100 EMCYs each: 10,000 in 1 s
        for _ in range(100):
            plant.send(0x0A8, emcy)
        plant.scan()
    assert plant.get("Watch.emergencies") == 10_000 and plant.get("Watch.malformed") == 0
    plant.run_ms(10_000)
    lines = [r for r in _canopen_lines(caplog) if "emergency 0x8110" in r.getMessage()]
    assert len(lines) == 2  # the first and, when its 10 s are over, how many followed
    assert not lines[0].getMessage().startswith("suppressed")
    assert 1 + _suppressed(lines) == 10_000


def test_an_emcy_flood_with_a_new_code_each_time_is_held_to_the_budget(plant, caplog):
    caplog.clear()
    for tick in range(100):
        for i in range(100):
            code = 0x1000 + tick * 100 + i
            plant.send(0x0A8, code.to_bytes(2, "little") + bytes([0x01, 0, 0, 0, 0, 0]))
        plant.scan()
    plant.run_ms(20_000)
    lines = [r for r in _canopen_lines(caplog) if "emergency" in r.getMessage()]
    assert len(lines) <= 21
    written = [r for r in lines if not r.getMessage().startswith("suppressed")]
    assert len(written) + _suppressed(lines) == 10_000


def test_canopen_library_lines_come_through_our_log_rate_limited(plant, caplog):
    """SDO transfers to a node that does not answer: canopen's client logs
    "Transfer aborted by client" for each. They reach softplc's own log
    handler (the one `softplc run` puts on the "softplc" logger; canopen's
    lines used to go raw to stderr instead), once per 10 s."""
    caplog.clear()
    ours = io.StringIO()
    handler = logging.StreamHandler(ours)
    handler.setFormatter(logging.Formatter("%(name)s %(levelname)s: %(message)s"))
    logging.getLogger("softplc").addHandler(handler)
    try:
        for _ in range(30):
            job = SdoJob(41, 0x1000, 0, None, 0.1)  # node 41 is not on the bus
            plant.master.worker.transfer(job)
            assert job.timed_out
        assert ours.getvalue().splitlines() == [
            "softplc.runtime.io.canopen.library ERROR: canopen library: Transfer aborted by client with code 0x05040000"
        ]
        plant.run_ms(10_100)
    finally:
        logging.getLogger("softplc").removeHandler(handler)
    text = ours.getvalue().splitlines()
    assert len(text) == 2 and text[1].startswith(
        "softplc.runtime.io.canopen.library ERROR: suppressed 29 similar messages in 10 s; the last: canopen library: "
        "Transfer aborted"
    )


def test_a_short_sdo_request_to_a_simulated_node_is_dropped_and_counted(plant, caplog):
    caplog.clear()
    sim = plant.sims[40]
    plant.send(0x628, b"\x40\x00")
    plant.scan()
    assert sim.malformed == 1 and not [r for r in caplog.records if r.exc_info]
    assert plant.get("Watch.operational")


def test_the_ltmr_node_still_boots_with_the_checks(plants):
    """Nothing a real node sends is taken for malformed (boot-up, heartbeats, SDO, PDOs)."""
    plant = plants(WATCH, program="Watch", nodes=[LTMR_NODE])
    plant.run_until(lambda: plant.get("Watch.operational"), 300, "node 40 operational")
    plant.run_ms(2000)
    assert plant.master.malformed == 0 and plant.get("Watch.operational")
