"""CANopen frames into a real master and a real slave (canopen_rig.Rig, on
python-can's `virtual` interface, a channel of its own per example, virtual
time): EMCY, heartbeats, boot-ups, TPDOs of every length, SDO responses
(node 41 answers the master's configuration with drawn responses), NMT, SDO
requests and RPDOs to the simulated LTMR, frames of any id, bursts.

Whatever comes, nothing escapes (advance_to, read_inputs, write_outputs
return), nothing hangs (support.bounded), nothing is logged with a
traceback, the master's status stays a status; and a TPDO of a configured
mapping is applied (its bytes in the image at the next read_inputs) or, too
short, counted (rx_short) and dropped.
"""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from softplc.runtime.plugin.driver import DriverStatus

from .canopen_frames import answer, events, sdo_plans
from .canopen_rig import LTMR, Rig
from .support import LogWatch, assert_no_tracebacks, bounded, fuzz, long, short


def _binding(rig: Rig, can_id: int):
    """The TPDO the master takes on can_id: of a node whose configuration
    went through (a binding's COB-ID is known as soon as it is read, but
    the master listens to it only once the whole configuration worked)."""
    return rig.master._tpdo_by_cob.get(can_id)


def _frame(rig: Rig, can_id: int, data: bytes, remote: bool) -> str:
    binding = None if remote else _binding(rig, can_id)
    short_before = rig.master.rx_short
    rig.inject(can_id, data, remote)
    if binding is None:
        return "frame"
    rig.scan()
    if len(data) < binding.nbytes:
        assert rig.master.rx_short == short_before + 1, f"a short TPDO 0x{can_id:03X} [{data.hex(' ')}] not counted"
        return "short TPDO counted"
    area = rig.image.areas["I"]
    for e in binding.entries:  # the rig maps whole words
        sent = data[e.bit_offset // 8 : (e.bit_offset + e.bits) // 8]
        got = bytes(area[e.byte_offset : e.byte_offset + e.bits // 8])
        assert got == sent, f"TPDO 0x{can_id:03X} [{data.hex(' ')}]: {e.key} holds [{got.hex(' ')}]"
    return "TPDO applied"


def play(case) -> tuple[int, dict]:
    """(frames the hostile endpoint sent, events by outcome)"""
    plans, steps = case
    outcomes: dict = {}
    virtual_ms = 0
    with LogWatch() as watch, bounded("CANopen frames"):
        rig = Rig(plans, answer)
        try:
            for step in steps:
                if step[0] == "time":
                    rig.run_ms(step[1])
                    virtual_ms += step[1]
                    outcome = "time"
                elif step[0] == "burst":
                    for _ in range(step[1]):
                        outcome = _frame(rig, *step[2:])
                else:
                    outcome = _frame(rig, *step[1:])
                outcomes[outcome] = outcomes.get(outcome, 0) + 1
            rig.run_ms(50)
            assert isinstance(rig.master.status(), DriverStatus)
        finally:
            rig.close()
    assert_no_tracebacks(watch, "CANopen frames")
    # issue 16, "an EMCY flood logs 10,000 lines a second ... every log message
    # from a bus is rate limited"
    lines = len(watch.records)
    assert lines <= 20 + virtual_ms // 50, f"{lines} log lines in {virtual_ms} ms of bus time"
    return rig.sent, outcomes


@pytest.mark.slow  # whole plants or buses
@short(12)
@given(sdo_plans(), events())
def test_canopen_frames_are_applied_counted_or_dropped(plans, steps):
    play((plans, steps))


@fuzz
def test_long_canopen_frames(tally, shard):
    counts = tally("frames")

    @long("frames", 0.4, shard, per_example=95)
    @given(sdo_plans(), events())
    def run(plans, steps):
        frames, outcomes = play((plans, steps))
        counts.inputs += frames
        counts.update({f"canopen {k}": v for k, v in outcomes.items()})

    run()


# ------------------------------------------------------------ floods (issue 31)
# NMT commands to the LTMR (reset node, reset communication, stop, pre-operational)
# or heartbeats in its name with any state, one every 1-10 ms for seconds: the
# master booted the node on every frame (999 times in 10 s).


@st.composite
def floods(draw, most_s: int):
    frame = draw(
        st.tuples(st.just(0x000), st.sampled_from([0x81, 0x82, 0x02, 0x80]).map(lambda c: bytes([c, LTMR])))
        | st.tuples(st.just(0x700 + LTMR), st.integers(0, 255).map(lambda b: bytes([b])))
    )
    return frame, draw(st.integers(1, 10)), draw(st.integers(2, most_s))


def flood(case) -> int:
    """Frames sent; the boots the master started stay within the limit."""
    (can_id, data), every_ms, seconds = case
    configurations = [0]
    with LogWatch() as watch, bounded("a CANopen flood"):
        rig = Rig([], answer)
        try:

            def count(msg) -> None:  # the master configures the LTMR: 1017h first
                if msg.arbitration_id == 0x600 + LTMR and bytes(msg.data[:4]) == bytes.fromhex("2B 17 10 00"):
                    configurations[0] += 1

            rig.hostile.add_handler(count)
            rig.run_ms(500)  # booted
            for _ in range(seconds * 1000 // every_ms):
                rig.inject(can_id, data)
                rig.run_ms(every_ms)
        finally:
            rig.close()
    assert_no_tracebacks(watch, "a CANopen flood")
    windows = seconds // 10 + 1
    # BOOT_BURST a window, the timed boot that ends a hold, and the first boot's
    assert configurations[0] <= 4 * windows + 1, f"{configurations[0]} configurations in {seconds} s"
    assert len(watch.records) <= 20 + seconds * 20, f"{len(watch.records)} log lines in {seconds} s"
    return rig.sent


@pytest.mark.slow  # whole plants or buses
@short(4)
@given(floods(most_s=3))
def test_floods_boot_a_node_within_the_limit(case):
    flood(case)


@fuzz
def test_long_canopen_floods(tally, shard):
    counts = tally("frames")

    @long("frames", 0.05, shard, per_example=3000)
    @given(floods(most_s=30))
    def run(case):
        counts.inputs += flood(case)
        counts["canopen flood"] += 1

    run()
