"""Error control of the simulated CANopen slave (runtime/io/canopen/slave_errors.py):
heartbeat producer and consumer, node and life guarding, and what a
communication error does, byte by byte on the virtual bus; the test is the
master."""

from __future__ import annotations

import pytest

from softplc.runtime.io.canopen.cia301 import (
    NMT_RESET_COMMUNICATION,
    NMT_RESET_NODE,
    NMT_START,
    STATE_OPERATIONAL,
    STATE_PRE_OPERATIONAL,
    STATE_STOPPED,
)

from .bench import MS, write_ok
from .slaves import NODE

HEARTBEAT = 0x728


# ---------------------------------------------------------------------------- heartbeat


def test_heartbeat_producer_in_virtual_time(bench, slave):
    bench.run_ms(50)
    assert bench.sdo_write(NODE, 0x1017, 0, 100, 2) == write_ok(0x1017, 0)  # 100 ms
    bench.clear()
    bench.run_ms(1000)
    assert bench.times_of(HEARTBEAT) == [t * MS for t in range(150, 1051, 100)]
    assert set(bench.frames_with(HEARTBEAT)) == {b"\x7f"}  # pre-operational
    bench.nmt(NMT_START, NODE)
    bench.clear()
    bench.run_ms(200)
    assert bench.frames_with(HEARTBEAT) == [b"\x05", b"\x05"]  # operational
    assert bench.sdo_write(NODE, 0x1017, 0, 0, 2) == write_ok(0x1017, 0)
    bench.clear()
    bench.run_ms(500)
    assert bench.frames_with(HEARTBEAT) == []


def _watch_master(bench, behaviour=None):
    # 0x1016:01 = producer 0x7F, 500 ms: the digest's example value 0x007F01F4 (digest 001 §1.5)
    assert bench.sdo_write(NODE, 0x1016, 1, 0x007F01F4, 4) == write_ok(0x1016, 1)
    if behaviour is not None:
        assert bench.sdo_write(NODE, 0x1029, 1, behaviour, 1) == write_ok(0x1029, 1)
    bench.nmt(NMT_START, NODE)


def test_heartbeat_consumer_waits_for_the_first_heartbeat(bench, slave):
    _watch_master(bench)
    bench.run_ms(2000)  # the master never sent one
    assert slave.nmt_state == STATE_OPERATIONAL
    assert ("comm error",) not in slave.events


def test_heartbeat_loss_sends_the_node_to_pre_operational_and_recovery_is_reported(bench, slave):
    _watch_master(bench)
    bench.master_heartbeat_ms = 100
    bench.run_ms(1000)
    assert slave.nmt_state == STATE_OPERATIONAL and not slave.heartbeat_lost
    bench.master_heartbeat_ms = 0
    bench.run_until(lambda: slave.heartbeat_lost, 1000, "heartbeat loss")
    # the first 10 ms step more than 500 ms after the last heartbeat
    assert bench.clock.now_ns() - bench.last_master_heartbeat_ns == 510 * MS
    assert slave.nmt_state == STATE_PRE_OPERATIONAL  # 0x1029:01 = 0 (factory)
    errors = [e for e in slave.events if e[0] == "comm error"]
    assert len(errors) == 1
    assert ("state", STATE_OPERATIONAL, STATE_PRE_OPERATIONAL) in slave.events
    bench.master_heartbeat_ms = 100
    bench.run_ms(20)
    assert not slave.heartbeat_lost and ("comm restored",) in slave.events
    assert slave.nmt_state == STATE_PRE_OPERATIONAL  # back in Operational only by NMT


@pytest.mark.parametrize("behaviour, state", [(1, STATE_OPERATIONAL), (2, STATE_STOPPED)])
def test_heartbeat_loss_follows_the_error_behaviour_object(bench, slave, behaviour, state):
    _watch_master(bench, behaviour)  # 0x1029:01: 1 no change, 2 stopped
    bench.master_heartbeat_ms = 100
    bench.run_ms(300)
    bench.master_heartbeat_ms = 0
    bench.run_ms(700)
    assert slave.heartbeat_lost
    assert slave.nmt_state == state
    assert ("comm error",) in slave.events


# ---------------------------------------------------------------------------- node guarding


def test_guarding_replies_carry_the_state_and_a_toggle_bit(bench, slave):
    # CiA 301: the reply's bit 7 toggles, starting with 0; 0x7F pre-operational, 0x05 operational
    assert bench.guard(NODE) == [b"\x7f"]
    assert bench.guard(NODE) == [b"\xff"]
    bench.nmt(NMT_START, NODE)
    assert bench.guard(NODE) == [b"\x05"]
    assert bench.guard(NODE) == [b"\x85"]
    bench.nmt(NMT_RESET_COMMUNICATION, NODE)
    assert bench.guard(NODE) == [b"\x7f"]  # a reset starts the toggle again


def test_a_node_producing_heartbeats_takes_no_part_in_guarding(bench, slave):
    assert bench.sdo_write(NODE, 0x1017, 0, 100, 2) == write_ok(0x1017, 0)
    assert bench.guard(NODE) == []


def test_life_guarding_a_silent_master_is_a_communication_error(bench, slave):
    # guard time 100 ms x life time factor 3: 300 ms without a request
    assert bench.sdo_write(NODE, 0x100C, 0, 100, 2) == write_ok(0x100C, 0)
    assert bench.sdo_write(NODE, 0x100D, 0, 3, 1) == write_ok(0x100D, 0)
    bench.nmt(NMT_START, NODE)
    bench.run_ms(1000)
    assert ("comm error",) not in slave.events  # not watching before the first request
    for _ in range(5):
        bench.guard(NODE)
        bench.run_ms(100)
    assert not slave.guarding_lost
    took = bench.run_until(lambda: slave.guarding_lost, 1000, "life guarding")
    assert 200 < took <= 310  # 300 ms after the last request, at the 10 ms steps
    assert ("comm error",) in slave.events
    assert slave.nmt_state == STATE_PRE_OPERATIONAL  # 0x1029 default: to pre-operational
    bench.guard(NODE)
    assert not slave.guarding_lost and slave.events[-1] == ("comm restored",)


def test_a_communication_error_outlives_a_communication_reset(bench, slave):
    # The master boots a lost node again with NMT reset communication; the
    # device hears that communication is back from the first request after.
    assert bench.sdo_write(NODE, 0x100C, 0, 100, 2) == write_ok(0x100C, 0)
    assert bench.sdo_write(NODE, 0x100D, 0, 3, 1) == write_ok(0x100D, 0)
    bench.nmt(NMT_START, NODE)
    bench.guard(NODE)
    bench.run_until(lambda: slave.guarding_lost, 1000, "life guarding")
    bench.nmt(NMT_RESET_COMMUNICATION, NODE)
    bench.send(0x701, b"\x05")  # another node's heartbeat says nothing about the master
    bench.run_ms(10)
    assert slave.events[-1] != ("comm restored",)
    bench.guard(NODE)
    assert slave.events[-1] == ("comm restored",)
    bench.nmt(NMT_RESET_NODE, NODE)  # a reset application starts afresh: nothing pending
    bench.guard(NODE)
    assert slave.events.count(("comm restored",)) == 1
