"""The master's view of one node (CiA 301/302 manager behaviour) and when it
sends an RPDO, step by step in time."""

from __future__ import annotations

from softplc.runtime.io.canopen.node import NodeState, NodeSupervisor
from softplc.runtime.io.canopen.pdo import TxSchedule

MS = 1_000_000


def _sup(**kw):
    kw.setdefault("mandatory", True)
    kw.setdefault("heartbeat_timeout_ns", 300 * MS)
    kw.setdefault("boot_timeout_ns", 500 * MS)
    kw.setdefault("retry_ns", 1000 * MS)
    return NodeSupervisor("motor", 40, **kw)


def test_a_node_boots_reset_bootup_configure_start():
    s = _sup()
    assert s.tick(0) == "reset" and s.state == NodeState.BOOTING
    assert s.heartbeat(0x00, 20 * MS) == "configure" and s.state == NodeState.CONFIGURING
    assert s.boots == 1
    assert s.configured(True, "", 40 * MS) == "start" and s.state == NodeState.OPERATIONAL
    assert s.heartbeat(0x05, 100 * MS) is None
    assert s.tick(399 * MS) is None
    assert s.tick(400 * MS) is None and s.state == NodeState.LOST  # 300 ms after the last heartbeat
    assert "heartbeat lost" in s.message


def test_no_boot_up_is_missing_and_retried():
    s = _sup()
    s.tick(0)
    assert s.tick(500 * MS) is None and s.state == NodeState.MISSING
    assert s.tick(1499 * MS) is None
    assert s.tick(1500 * MS) == "reset" and s.state == NodeState.BOOTING


def test_a_lost_node_heard_again_is_booted_again():
    s = _sup()
    s.tick(0), s.heartbeat(0, 1), s.configured(True, "", 2)
    s.tick(400 * MS)
    assert s.state == NodeState.LOST
    assert s.heartbeat(0x7F, 450 * MS) == "reset"  # back, in pre-operational after its fallback
    assert s.heartbeat(0x00, 460 * MS) == "configure"


def test_an_operational_node_reporting_pre_operational_is_restarted():
    s = _sup()
    s.tick(0), s.heartbeat(0, 1), s.configured(True, "", 2)
    assert s.heartbeat(0x7F, 50 * MS) == "reset"
    assert "pre-operational" in s.message


def test_a_failed_configuration_is_retried_after_the_retry_time():
    s = _sup()
    s.tick(0), s.heartbeat(0, 1)
    assert s.configured(False, "motor.sdo[0]: aborted", 10 * MS) is None
    assert s.state == NodeState.CONFIG_ERROR and "aborted" in s.message
    assert s.tick(1010 * MS) == "reset"


# A flood of NMT reset-node commands or bogus heartbeat states made the master
# boot a node 2,000 times in 10 s: boots a frame asks for are BOOT_BURST per window.


def _operational(s, now):
    assert s.heartbeat(0x00, now) == "configure"
    assert s.configured(True, "", now + MS) == "start"


def test_bogus_heartbeat_states_restart_a_node_at_most_three_times_in_ten_seconds():
    s = _sup()
    s.tick(0)
    _operational(s, 1 * MS)
    actions = []
    for i in range(1000):  # a bogus pre-operational heartbeat every 10 ms, each answered by a boot-up
        now = 10 * MS + i * 10 * MS
        actions.append(s.heartbeat(0x7F, now))
        actions.append(s.tick(now + 5 * MS))
        if s.state == NodeState.BOOTING:
            _operational(s, now + 6 * MS)
    assert actions.count("reset") == 3  # three boots a frame asked for; the rest held off
    assert actions.count("hold") == 1 and s.held_off == 997
    assert s.state == NodeState.LOST and s.held_until_ns == 10 * MS + 10_000 * MS
    assert s.message == (
        "node reported pre-operational; booted 3 times in 10 s (a flood of resets or bogus heartbeats?): "
        "the next boot in 9970 ms"  # held at 40 ms, by the fourth
    )
    assert s.tick(s.held_until_ns) == "reset" and s.state == NodeState.BOOTING  # then booted, by the clock


def test_boot_ups_it_sends_unasked_configure_a_node_at_most_three_times_in_ten_seconds():
    """An NMT reset-node flood: the node resets and sends a boot-up each time."""
    s = _sup()
    s.tick(0)
    configured = 0
    for i in range(2000):
        now = 1 * MS + i * 5 * MS
        action = s.heartbeat(0x00, now)
        if action == "configure":
            configured += 1
            assert s.configured(True, "", now + MS) == "start"
        s.tick(now + 2 * MS)
    assert configured == 1 + 3  # the answer to the first reset, then three boots it started itself
    assert s.boots == 2000 and s.state == NodeState.LOST and "node sent a boot-up" in s.message


def test_a_node_restarted_now_and_then_is_never_held_off():
    s = _sup()
    s.tick(0)
    _operational(s, 1 * MS)
    for k in range(10):  # once every 4 s: at most three in any 10 s
        now = (k + 1) * 4000 * MS
        assert s.heartbeat(0x7F, now) == "reset"
        _operational(s, now + MS)
    assert s.held_off == 0


def test_event_driven_rpdo_on_change_inhibit_and_event_timer():
    t = TxSchedule(255, inhibit_us=5000, event_ms=100)
    a, b = b"\x01\x00", b"\x02\x00"
    assert t.due(a, 0, False)
    t.sent(a, 0)
    assert not t.due(a, 10 * MS, False)  # unchanged
    assert not t.due(b, 4 * MS, False)  # changed, but within the 5 ms inhibit time
    assert t.due(b, 5 * MS, False)
    t.sent(b, 5 * MS)
    assert not t.due(b, 104 * MS, False)
    assert t.due(b, 105 * MS, False)  # the event timer resends it


def test_synchronous_rpdo_types():
    every_second = TxSchedule(2, 0, 0)
    assert [every_second.due(b"x", 0, sync) for sync in (False, True, True, True, True)] == [
        False,
        False,
        True,
        False,
        True,
    ]
    on_change = TxSchedule(0, 0, 0)
    assert not on_change.due(b"x", 0, False)
    assert on_change.due(b"x", 0, True)
    on_change.sent(b"x", 0)
    assert not on_change.due(b"x", 0, True)
