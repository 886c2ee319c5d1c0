"""[[sim]] faults = [...] (runtime/config/sim_faults.py): faults at times of
the run, each a fault the device's simulator takes, checked with messages
that name the key."""

from __future__ import annotations

from softplc.runtime.config.sim_faults import FaultEvent

from .support import CAN, PLC, error, errors, load

MS = 1_000_000
FC280 = '[[sim]]\ntype = "fc280"\nnode_id = 5\n'
LTMR = '[[sim]]\ntype = "ltmr"\nnode_id = 40\n'


def test_faults_in_time_order_with_their_values_and_durations(tmp_path):
    cfg = load(
        tmp_path,
        PLC
        + CAN
        + FC280
        + 'faults = [{ at = "40s", fault = "unplug", for = "2s" }, { at = "T#20s", fault = "Over_Current" },'
        + ' { at = "1m", fault = "warning", value = 0x40, for = "5000ms" }]\n',
    )
    assert cfg.sims[0].faults == (
        FaultEvent(20_000 * MS, "over_current"),
        FaultEvent(40_000 * MS, "unplug", None, 2_000 * MS),
        FaultEvent(60_000 * MS, "warning", 0x40, 5_000 * MS),
    )
    assert load(tmp_path, PLC + CAN + FC280).sims[0].faults == ()


def test_each_entry_is_checked_against_the_devices_faults(tmp_path):
    text = (
        "faults = ["
        '{ at = "1s", fault = "overheat" }, '
        '{ at = "2s", fault = "alarm" }, '
        '{ at = "3s", fault = "over_current", value = 1 }, '
        '{ at = "4s", fault = "alarm", value = 32, for = "1s" }, '
        '{ at = "-1s", fault = "unplug" }, '
        '{ at = "5s", fault = "unplug", for = "0s" }, '
        '{ at = "6s", fault = "warning", value = "x" }, '
        '{ at = "7s", fault = "unplug", until = "8s" }'
        "]\n"
    )
    assert errors(tmp_path, PLC + CAN + FC280 + text) == [
        (
            "sim[0].faults[0].fault",
            "fc280 has no fault 'overheat'; it has unplug, over_current, alarm, trip_lock, warning, power_cycle",
        ),
        ("sim[0].faults[1]", "fault alarm needs a value: a bit of alarm word 16-90"),
        ("sim[0].faults[2].value", "fault over_current takes no value"),
        ("sim[0].faults[3].for", "fault alarm does not last: it takes no 'for'"),
        ("sim[0].faults[4].at", "expected a time of the run such as 10ms, 1s, T#250ms (got '-1s')"),
        ("sim[0].faults[5].for", "expected a duration > 0 such as 10ms, 1s, T#250ms (got '0s')"),
        ("sim[0].faults[6].value", "expected a number (got 'x')"),
        ("sim[0].faults[7].until", "unknown key (expected one of at, fault, value, for)"),
    ]


def test_each_device_has_its_own_faults(tmp_path):
    assert error(tmp_path, PLC + CAN + LTMR + 'faults = [{ at = "1s", fault = "over_current" }]\n') == (
        "sim[0].faults[0].fault",
        "ltmr has no fault 'over_current'; it has unplug, load",
    )
    cfg = load(tmp_path, PLC + CAN + LTMR + 'faults = [{ at = "1s", fault = "load", value = 400.0, for = "30s" }]\n')
    assert cfg.sims[0].faults == (FaultEvent(1_000 * MS, "load", 400.0, 30_000 * MS),)
