"""LTMR_CONTROL (fblocks/vendor/ltmr.st), driven cycle by cycle in virtual
time through a small ST program, with the LTMR manual's numbers.

The program copies its variables into the block and the block's outputs
back; the test sets the variables between cycles, as TPDO1 would fill them,
and reads what would go out in RPDO1. With the 10 ms cycle, the task clock
(TIME()) advances 10 ms from one call to the next.

Register values come from manual 001 (shared/manuals/001_...): 455 System
status register 1 bits at L3520-3542, 456 at L3544-3571, 704 Control
register 1 at L4917-4937; the DERIVED values are digest 001's (section 6.3,
section 7.2, section 2.5).
"""

from __future__ import annotations

from .st_bench import Bench

CONTROL_DECLS = """
    m : LTMR_CONTROL;
    fwd : BOOL; rev : BOOL; reset : BOOL; low : BOOL; selftest : BOOL;
    s1 : WORD; s2 : WORD; trip : UINT; alarm : UINT; nodeOk : BOOL := TRUE;
"""
CONTROL_BODY = """
m(RunForward := fwd, RunReverse := rev, TripReset := reset, LowSpeed := low, SelfTest := selftest,
  Status1 := s1, Status2 := s2, TripCode := trip, AlarmCode := alarm, NodeOk := nodeOk);
"""

# 455 bits, manual 001 L3522-3542
READY, ON, TRIP, ALARM = 0x0001, 0x0002, 0x0004, 0x0008
RESET_AUTHORIZED, RUNNING, IN_REMOTE, STARTING = 0x0020, 0x0080, 0x4000, 0x8000
# 456 bits, manual 001 L3563-3565
HMI_COMM_LOSS, NETWORK_COMM_LOSS = 0x0080, 0x0100
# 704 bits, manual 001 L4917-4937
RUN_FORWARD, RUN_REVERSE, TRIP_RESET, SELF_TEST, LOW_SPEED = 0x0001, 0x0002, 0x0008, 0x0020, 0x0040

STATUS_FLAGS = (
    "Ready",
    "On",
    "Running",
    "Starting",
    "Tripped",
    "Alarm",
    "ResetAuthorized",
    "Remote",
    "CommLoss",
    "HmiCommLoss",
)


def bench() -> Bench:
    return Bench(CONTROL_DECLS, CONTROL_BODY)


def flags(b: Bench) -> set:
    """The status outputs that are TRUE."""
    return {name for name in STATUS_FLAGS if b[f"m.{name}"]}


# ---------------------------------------------------------------- status 455 / 456


def test_digest_sample_0x6083_is_ready_on_running_at_100_percent_in_remote():
    # digest 001 section 6.3, DERIVED: ready + on + running + ratio 32 + in remote = 0x6083
    b = bench().step(s1=0x6083)
    assert flags(b) == {"Ready", "On", "Running", "Remote"}
    assert b["m.CurrentRatio"] == 100.0  # L3538: 32 = 100 % FLC


def test_each_status_1_bit_has_its_own_output():
    cases = {
        READY: "Ready",
        ON: "On",
        TRIP: "Tripped",
        ALARM: "Alarm",
        RESET_AUTHORIZED: "ResetAuthorized",
        RUNNING: "Running",
        IN_REMOTE: "Remote",
        STARTING: "Starting",
    }
    b = bench()
    for bit, name in cases.items():
        assert flags(b.step(s1=bit)) == {name}, hex(bit)


def test_status_1_bit_4_alone_does_not_read_as_a_trip():
    # 455 bit 4 is "System tripped" in English but "System ausgeschaltet"
    # (system off) in the German edition (digest 001 A13): Tripped follows
    # bit 2 "System trip" only.
    b = bench().step(s1=0x0010)
    assert flags(b) == set()


def test_current_ratio_field_is_linear_and_63_reads_about_200_percent():
    # L3538 "32 = 100% FLC - 63 = 200% FLC"; A14: % = field x 100 / 32
    b = bench()
    assert b.step(s1=16 << 8)["m.CurrentRatio"] == 50.0
    assert b.step(s1=(63 << 8) | RUNNING)["m.CurrentRatio"] == 196.875
    assert b["m.Running"] is True  # the field does not spill into other bits
    assert b.step(s1=0)["m.CurrentRatio"] == 0.0


def test_status_2_network_and_hmi_comm_loss():
    b = bench().step(s1=0x6083, s2=NETWORK_COMM_LOSS)
    assert b["m.CommLoss"] is True and b["m.HmiCommLoss"] is False
    b.step(s2=HMI_COMM_LOSS)
    assert b["m.CommLoss"] is False and b["m.HmiCommLoss"] is True


def test_node_lost_reads_as_not_ready_not_running_with_comm_loss():
    b = bench().step(s1=0x6083, fwd=True)
    assert b["m.Running"] is True
    b.step(nodeOk=False)  # the master lost the node; TPDO1 values are stale
    assert flags(b) == {"CommLoss"}
    assert b["m.CurrentRatio"] == 0.0
    assert b["m.Control1"] == RUN_FORWARD  # the command is still computed
    b.step(nodeOk=True)
    assert flags(b) == {"Ready", "On", "Running", "Remote"}


def test_trip_and_alarm_codes_with_their_texts():
    # DT_FaultCode 4 "Thermal overload", DT_WarningCode 109 "Network port comm loss" (digest 001 section 6.7)
    b = bench().step(s1=READY | TRIP, trip=4, alarm=109)
    assert b["m.TripCodeOut"] == 4 and b["m.TripText"] == "Thermal overload"
    assert b["m.AlarmCodeOut"] == 109 and b["m.AlarmText"] == "Network port comm loss"
    b.step(trip=10, alarm=10)  # code 10: "Test" trip but "HMI port" alarm
    assert (b["m.TripText"], b["m.AlarmText"]) == ("Test", "HMI port")


# ---------------------------------------------------------------- control register 704


def test_run_commands_give_the_digest_control_words():
    # digest 001 section 7.2: run forward 01 00, run reverse 02 00, fwd + low speed 41 00
    b = bench().step(s1=0x4001)
    assert b.step(fwd=True)["m.Control1"] == 0x0001
    assert b.step(fwd=False, rev=True)["m.Control1"] == 0x0002
    assert b.step(rev=False, fwd=True, low=True)["m.Control1"] == 0x0041
    assert b.step(fwd=False, rev=True)["m.Control1"] == RUN_REVERSE | LOW_SPEED
    assert b.step(rev=False, low=False)["m.Control1"] == 0x0000  # stop


def test_low_speed_alone_sends_nothing():
    b = bench().step(low=True)
    assert b["m.Control1"] == 0


def test_both_directions_at_once_send_no_run_bit_and_raise_interlock():
    b = bench().step(fwd=True, rev=True, low=True)
    assert b["m.Control1"] == 0 and b["m.Interlock"] is True
    b.step(rev=False)
    assert b["m.Control1"] == RUN_FORWARD | LOW_SPEED and b["m.Interlock"] is False


# ---------------------------------------------------------------- trip reset

TRIPPED_STATUS = READY | TRIP | RESET_AUTHORIZED | IN_REMOTE


def test_trip_reset_holds_the_reset_bit_without_run_bits_until_the_trip_clears():
    b = bench().step(s1=0x6083, fwd=True)
    b.step(s1=TRIPPED_STATUS)  # the LTMR trips; the program still asks to run
    assert b["m.Tripped"] is True
    assert b.step(reset=True)["m.Control1"] == TRIP_RESET
    assert b.step(reset=False)["m.Control1"] == TRIP_RESET  # a pulse at the input is enough
    assert b.step(5)["m.Control1"] == TRIP_RESET  # until 455 says the trip is gone
    b.step(s1=READY | IN_REMOTE)
    assert b["m.Tripped"] is False
    assert b["m.Control1"] == RUN_FORWARD  # then back to the run command


def test_trip_reset_gives_up_after_2_s():
    b = bench().step(s1=TRIPPED_STATUS, fwd=True)
    b.step(reset=True)
    assert b["m.Control1"] == TRIP_RESET
    start = b.runner.now_ms
    b.step(190)  # 1.9 s later the LTMR still reports the trip
    assert b.runner.now_ms - start == 1900
    assert b["m.Control1"] == TRIP_RESET
    b.step(20)  # 2.1 s: the block has given up
    assert b["m.Control1"] == RUN_FORWARD
    b.step(reset=False)
    assert b.step(reset=True)["m.Control1"] == TRIP_RESET  # a new edge tries again


def test_trip_reset_needs_a_trip_and_a_new_edge():
    b = bench().step(s1=0x6083, fwd=True, reset=True)  # no trip: nothing to reset
    assert b["m.Control1"] == RUN_FORWARD
    b.step(s1=TRIPPED_STATUS)  # a trip while reset is held high
    assert b["m.Control1"] == RUN_FORWARD
    b.step(reset=False).step(reset=True)
    assert b["m.Control1"] == TRIP_RESET


def test_trip_reset_ends_when_the_node_is_lost():
    b = bench().step(s1=TRIPPED_STATUS, fwd=True).step(reset=True)
    assert b["m.Control1"] == TRIP_RESET
    b.step(nodeOk=False)  # no status to wait for any more
    assert b["m.Control1"] == RUN_FORWARD


# ---------------------------------------------------------------- self test


def test_self_test_is_a_pulse_until_the_ltmr_trips():
    b = bench().step(s1=0x6083, fwd=True)
    assert b.step(selftest=True)["m.Control1"] == RUN_FORWARD | SELF_TEST
    assert b.step(selftest=False)["m.Control1"] == RUN_FORWARD | SELF_TEST
    b.step(s1=TRIPPED_STATUS)  # the test trips the LTMR (trip code 10 "Test")
    assert b["m.Control1"] == RUN_FORWARD


def test_self_test_gives_up_after_2_s_and_is_not_sent_while_tripped():
    b = bench().step(s1=0x6083).step(selftest=True)
    b.step(190)
    assert b["m.Control1"] == SELF_TEST
    b.step(20)
    assert b["m.Control1"] == 0
    b.step(selftest=False, s1=TRIPPED_STATUS).step(selftest=True)
    assert b["m.Control1"] == 0
