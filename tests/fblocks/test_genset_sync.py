"""STEP3 and GENSET_SYNC (fblocks/vendor/genset.st), stepped 10 ms a cycle in
virtual time: the scenario vectors S1-S8 of digest 004 §5.2, the sequence
of §4.3/§4.4 around them.

The test sets the block's inputs directly between cycles, as a program
would wire them; the task clock starts at 0 (the first cycle runs at
TIME() = T#0ms)."""

from __future__ import annotations

import pytest

from .st_bench import CYCLE_MS, Bench

assert CYCLE_MS == 10  # the tests count cycles of 10 ms

IDLE, CHECK, SYNCHRONISING, DEAD_BUS, CLOSING, CLOSED, OPENING, FAULT = range(8)  # GENSET_STATE_*
PLC, SUPERVISE = 0, 1  # GENSET_MODE_*

READY = dict(
    ENABLE=True,
    GCB_RELEASE=True,
    COMM_OK=True,
    GEN_LIVE=True,
    BUS_LIVE=True,
    ENGINE_READY=True,
    MCB_OPEN=True,
    PHASE_VALID=True,
    F_GEN=50.0,
    F_BUS=50.0,
    U_GEN=400.0,
    U_BUS=400.0,
)
DEAD = dict(READY, BUS_LIVE=False, F_BUS=0.0, U_BUS=0.0, DEAD_BUS=True)
S7 = dict(DEAD, F_GEN=50.3, U_GEN=396.0, F_RATED=50.0, U_RATED=400.0, DB_DF_MAX=0.5, DB_DU_MAX=2.0)


class Sync(Bench):
    """GENSET_SYNC as g; step(NAME=value) sets g.NAME."""

    def __init__(self) -> None:
        super().__init__("g : GENSET_SYNC;", "g();")

    def step(self, cycles: int = 1, **inputs) -> Sync:
        super().step(cycles, **{f"g.{name}": value for name, value in inputs.items()})
        return self


def block(base: dict, **inputs) -> Sync:
    return put(Sync(), **{**base, **inputs})


def put(b: Sync, **inputs) -> Sync:
    for name, value in inputs.items():
        b[f"g.{name}"] = value
    return b


def out(b: Bench, name: str):
    return b[f"g.{name}"]


def trace(b: Bench, cycles: int, *names: str) -> list:
    """The outputs after each of the next cycles."""
    rows = []
    for _ in range(cycles):
        b.step()
        rows.append(tuple(out(b, n) for n in names))
    return rows


# ---------------------------------------------------------------- STEP3 (§4.5)


def step3(**inputs) -> Bench:
    b = Bench("c : STEP3;", "c();")
    for name, value in dict(ENABLE=True, DEADBAND=0.03, KP=10.0, PULSE_MIN=50, PERIOD=1000, **inputs).items():
        b[f"c.{name}"] = value
    return b


def on_cycles(b: Bench, cycles: int, name: str) -> list:
    """The cycles (from 0) on which the output is on."""
    seen = []
    for k in range(cycles):
        b.step()
        if b[f"c.{name}"]:
            seen.append(k)
    return seen


def test_step3_on_time_is_kp_times_error_times_100_ms_once_a_period():
    b = step3(SETPOINT=50.3, ACTUAL=50.0)  # error 0.3 Hz, KP 10: 300 ms
    assert on_cycles(b, 250, "RAISE") == list(range(30)) + list(range(100, 130)) + list(range(200, 230))
    assert b["c.ERROR"] == pytest.approx(0.3, abs=1e-5)
    assert not b["c.LOWER"]


def test_step3_minimum_pulse_dead_band_and_period_limit():
    b = step3(SETPOINT=49.99, ACTUAL=50.03)  # -0.04: 40 ms -> the 50 ms minimum, LOWER
    assert on_cycles(b, 100, "LOWER") == [0, 1, 2, 3, 4]
    b = step3(SETPOINT=50.02, ACTUAL=50.0)  # inside the 0.03 dead band
    assert on_cycles(b, 200, "RAISE") == []
    b = step3(SETPOINT=52.0, ACTUAL=50.0)  # 2000 ms, limited to the 1 s period: on throughout
    assert on_cycles(b, 300, "RAISE") == list(range(300))


def test_step3_disable_ends_a_pulse_at_once():
    b = step3(SETPOINT=50.3, ACTUAL=50.0)
    on_cycles(b, 10, "RAISE")
    b["c.ENABLE"] = False
    assert on_cycles(b, 5, "RAISE") == []
    b["c.ENABLE"] = True  # a new pulse may start at once
    assert on_cycles(b, 1, "RAISE") == [0]


# ---------------------------------------------------------------- S1-S8 (§5.2)


def test_s1_slip_inside_the_window():
    b = block(READY, F_GEN=50.15, DF_MAX=0.18, DF_MIN=0.10).step(2)
    assert out(b, "IN_WINDOW") and out(b, "STATE") == SYNCHRONISING
    assert out(b, "DF") == pytest.approx(0.15, abs=1e-5)


def test_s2_slip_above_df_max_blocks_and_the_controller_lowers():
    b = block(READY, F_GEN=50.20, DF_MAX=0.18, PHASE=-5.76).step(2)
    assert not out(b, "IN_WINDOW")
    assert out(b, "TEXT") == "slip +0.20 Hz above +0.18 Hz"
    # the f controller aims at F_BUS + SLIP_TARGET (0.10): error -0.10 Hz, beyond the 0.03 dead band
    assert out(b, "LOWER_F") and not out(b, "RAISE_F")
    assert not any(c for (c,) in trace(b, 100, "CLOSE_CMD"))


def test_s3_negative_slip_with_df_min_zero_is_outside():
    b = block(READY, F_GEN=49.95, DF_MIN=0.0).step(2)
    assert not out(b, "IN_WINDOW")
    assert out(b, "TEXT") == "slip -0.05 Hz below -0.00 Hz"
    assert out(b, "RAISE_F") and not out(b, "LOWER_F")


def test_s4_voltage_above_du_max_blocks_and_the_avr_lowers():
    b = block(READY, F_GEN=50.1, U_GEN=412.0, U_BUS=400.0, U_RATED=400.0, DU_MAX=2.5).step(2)
    assert out(b, "DU") == pytest.approx(3.0, abs=1e-4)
    assert not out(b, "IN_WINDOW")
    assert out(b, "TEXT") == "voltage +3.0 % above +2.5 %"
    assert out(b, "LOWER_U") and not out(b, "RAISE_U")


@pytest.mark.parametrize("sign", [1, -1])
def test_s5_the_close_command_goes_out_at_the_advance_angle(sign):
    """df = 0.2 Hz, t_close = 80 ms: advance 5.76 deg, the phase turning at
    72 deg/s, 0.72 deg a cycle towards 0: the command goes out on the cycle
    phi = -5.76 deg (+5.76 for a negative slip), not one before."""
    b = block(READY, F_GEN=50.0 + sign * 0.2, DF_MAX=0.25, DF_MIN=0.25, GCB_CLOSE_TIME=80)
    for k in range(40):
        b.step(PHASE=-sign * (5.76 + 0.72 * (20 - k)))
        assert out(b, "ADVANCE") == pytest.approx(-sign * 5.76, abs=1e-3)
        if out(b, "CLOSE_CMD"):
            break
    assert k == 20 and out(b, "STATE") == CLOSING
    assert out(b, "PHASE_AT_COMMAND") == pytest.approx(-sign * 5.76, abs=1e-4)


def test_s6_sync_time_alarm_at_10_s_and_synchronising_goes_on():
    b = block(READY, F_GEN=50.3, SYNC_TIME_MON=True, SYNC_TIME=10_000)
    b.step(1000)  # T#0ms .. T#9s990ms
    assert out(b, "STATE") == SYNCHRONISING and not out(b, "SYNC_TIME_ALARM")
    b.step()  # T#10s
    assert out(b, "SYNC_TIME_ALARM") and out(b, "STATE") == SYNCHRONISING
    b.step(500)
    assert out(b, "STATE") == SYNCHRONISING
    b.step(ACK=True)  # ACK clears it and starts the time again
    assert not out(b, "SYNC_TIME_ALARM")
    b.step(999, ACK=False)
    assert not out(b, "SYNC_TIME_ALARM")
    b.step()
    assert out(b, "SYNC_TIME_ALARM")


def test_s6_no_alarm_with_monitoring_off():
    b = block(READY, F_GEN=50.3, SYNC_TIME_MON=False, SYNC_TIME=10_000).step(1500)
    assert not out(b, "SYNC_TIME_ALARM")


def test_s7_dead_bus_close():
    b = block(S7).step()
    assert out(b, "IN_WINDOW") and out(b, "CLOSE_CMD") and out(b, "STATE") == CLOSING
    assert out(b, "DF") == pytest.approx(0.3, abs=1e-4) and out(b, "DU") == pytest.approx(-1.0, abs=1e-4)


@pytest.mark.parametrize(
    ("inputs", "text"),
    [
        ({"F_GEN": 50.6}, "dead bus: frequency +0.60 Hz off rated, limit 0.50 Hz"),
        ({"U_GEN": 390.0}, "dead bus: voltage -2.5 % off rated, limit 2.0 %"),
        ({"MCB_OPEN": False}, "busbar dead, mains breaker not open (T4)"),
        ({"DEAD_BUS": False}, "busbar dead, dead-bus closing off (DEAD_BUS)"),
    ],
)
def test_s7_dead_bus_blocked(inputs, text):
    b = block(S7, **inputs)
    assert not any(c for (c,) in trace(b, 50, "CLOSE_CMD"))
    assert out(b, "TEXT") == text


@pytest.mark.parametrize("monitor", [True, False])
def test_s8_five_failed_close_pulses_raise_the_close_fault(monitor):
    """Impuls, 0.20 s, no T5 reply: an attempt fails after pulse + closing
    time (280 ms); the fifth raises event 89 and, as [E] says, the attempts
    go on."""
    b = block(S7, CLOSE_PULSE=200, GCB_CLOSE_TIME=80, GCB_MONITOR=monitor)
    rows = trace(b, 200, "CLOSE_CMD", "ATTEMPTS", "CLOSE_FAULT")
    starts = [k for k in range(len(rows)) if rows[k][0] and (k == 0 or not rows[k - 1][0])]
    assert starts[:6] == [0, 29, 58, 87, 116, 145]  # 280 ms, then the next cycle
    assert all(rows[s + 19][0] and not rows[s + 20][0] for s in starts[:6])  # 200 ms pulses
    fifth = next(k for k in range(len(rows)) if rows[k][1] == 5)
    assert fifth == 144
    assert not any(fault for _c, _a, fault in rows[:fifth])
    assert rows[fifth][2] is monitor and rows[-1][2] is monitor
    assert rows[-1][1] == 6
    b.step(ACK=True)
    assert out(b, "ATTEMPTS") == 0 and not out(b, "CLOSE_FAULT")


# ---------------------------------------------------------------- the sequence (§4.3, §4.4)


def closing_block(**inputs) -> Sync:
    """A dead-bus close under way (S7): the command is out."""
    b = block(S7, **inputs).step()
    assert out(b, "CLOSE_CMD")
    return b


@pytest.mark.parametrize(
    "lost",
    [{"ENABLE": False}, {"COMM_OK": False}, {"ALARM_F2F3": True}, {"GCB_RELEASE": False}, {"OPEN": True}],
)
def test_a_close_command_is_dropped_at_once_when_a_precondition_goes(lost):
    b = closing_block(CLOSE_CONSTANT=True)
    b.step(**lost)
    assert not out(b, "CLOSE_CMD") and out(b, "STATE") != CLOSING
    assert not any(c for (c,) in trace(b, 100, "CLOSE_CMD"))
    b.step(2, **{k: not v for k, v in lost.items()})
    assert out(b, "CLOSE_CMD")  # back: the dead-bus close goes again


@pytest.mark.parametrize(("cycle", "dropped"), [(3, True), (8, False)])
def test_the_dead_bus_turning_live_while_closing(cycle, dropped):
    """Before the closing time (80 ms) another source: drop the close; after
    it, this GCB has energised the bar and T5 may come later: hold on."""
    b = closing_block(CLOSE_CONSTANT=True, GCB_CLOSE_TIME=80)
    b.step(cycle - 1)
    b.step(BUS_LIVE=True, F_BUS=50.3, U_BUS=396.0)
    assert out(b, "CLOSE_CMD") is not dropped
    b.step(GCB_CLOSED=True)
    assert out(b, "STATE") == CLOSED and out(b, "CLOSE_CMD")  # "Konstant": held once closed


def test_without_phase_valid_plc_mode_never_closes_onto_a_live_bus():
    b = block(READY, F_GEN=50.1, PHASE_VALID=False)
    for k in range(1000):  # a whole turn and more, 0.36 deg a cycle
        b.step(PHASE=((k * 0.36 + 180.0) % 360.0) - 180.0)
        assert not out(b, "CLOSE_CMD")
    assert out(b, "TEXT") == "no fast phase input (PHASE_VALID): no close onto a live bus"


def test_supervise_mode_requests_and_watches():
    b = block(READY, MODE=SUPERVISE, F_GEN=50.3)
    rows = trace(b, 300, "SYNC_REQUEST", "CLOSE_CMD", "RAISE_F", "LOWER_F")
    assert all(r == (True, False, False, False) for r in rows)
    assert out(b, "TEXT") == "MPU2-S synchronising (T6)"
    b.step(COMM_OK=False)
    assert not out(b, "SYNC_REQUEST")
    b.step(COMM_OK=True, GCB_CLOSED=True)  # the MPU2-S closed the GCB
    assert out(b, "STATE") == CLOSED and not out(b, "CLOSE_CMD") and not out(b, "SYNC_REQUEST")


@pytest.mark.parametrize("constant", [False, True])
def test_closed_then_opened(constant):
    b = closing_block(CLOSE_CONSTANT=constant, CLOSE_PULSE=200)
    b.step(8)  # 80 ms
    b.step(GCB_CLOSED=True)
    assert out(b, "STATE") == CLOSED
    b.step(30)
    assert out(b, "CLOSE_CMD") is constant  # "Konstant" holds, "Impuls" has ended
    b.step(ENABLE=False)
    assert out(b, "STATE") == CLOSED  # the request dropping does not open it
    b.step(OPEN=True)
    assert out(b, "STATE") == OPENING and out(b, "OPEN_CMD") and not out(b, "CLOSE_CMD")
    b.step(5, GCB_CLOSED=False)
    assert out(b, "STATE") == IDLE and not out(b, "OPEN_CMD") and out(b, "TEXT") == "open requested (OPEN)"


def test_open_relay_de_energised_to_open():
    b = closing_block(OPEN_RELAY_NO=False)
    assert out(b, "OPEN_CMD")  # "Ruhestrom": energised at rest
    b.step(GCB_CLOSED=True)
    b.step(OPEN=True)
    assert not out(b, "OPEN_CMD")


def test_no_open_reply_in_2_s_is_the_open_fault():
    b = closing_block()
    b.step(GCB_CLOSED=True)
    b.step(OPEN=True)
    rows = trace(b, 199, "STATE", "OPEN_CMD")  # T5 stays on
    assert rows[-1] == (OPENING, True)
    b.step()  # 2 s after the open command
    assert out(b, "OPEN_FAULT") and out(b, "STATE") == FAULT and out(b, "OPEN_CMD")
    assert out(b, "TEXT") == "GCB did not open within 2 s (event 91): ACK"
    b.step(5, GCB_CLOSED=False)
    assert out(b, "STATE") == FAULT and not out(b, "OPEN_CMD")  # latched until ACK
    b.step(ACK=True, OPEN=False)
    b.step()
    assert not out(b, "OPEN_FAULT") and out(b, "STATE") != FAULT


def test_f2_f3_alarm_is_a_fault_and_opens_a_closed_gcb():
    b = block(READY, ALARM_F2F3=True, F_GEN=50.1).step()
    assert out(b, "STATE") == FAULT and out(b, "TEXT") == "F2/F3 alarm"
    b.step(2, ALARM_F2F3=False)
    assert out(b, "STATE") == SYNCHRONISING
    b.step(GCB_CLOSED=True)
    b.step(ALARM_F2F3=True)
    assert out(b, "STATE") == OPENING and out(b, "OPEN_CMD")


def test_auto_unlock_gives_an_open_pulse_before_each_close():
    b = block(S7, AUTO_UNLOCK=True, CLOSE_PULSE=200, GCB_CLOSE_TIME=80)
    rows = trace(b, 60, "OPEN_CMD", "CLOSE_CMD")
    opens = [k for k, r in enumerate(rows) if r[0]]
    closes = [k for k, r in enumerate(rows) if r[1]]
    assert opens[:21] == [*range(20), 49]  # a 200 ms open pulse; the attempt fails at 48: again
    assert closes[:1] == [20]  # the close after the open pulse
    assert not any(o and c for o, c in rows)


def test_dead_bus_time_alarm_and_the_bus_going_live():
    b = block(S7, F_GEN=51.0, DB_TIME=5000)
    b.step(500)
    assert not out(b, "DEAD_BUS_TIME_ALARM") and out(b, "STATE") == DEAD_BUS
    b.step()
    assert out(b, "DEAD_BUS_TIME_ALARM") and out(b, "STATE") == DEAD_BUS
    b.step(BUS_LIVE=True, F_BUS=50.0, U_BUS=400.0)
    assert out(b, "STATE") == SYNCHRONISING


@pytest.mark.parametrize(
    ("inputs", "text"),
    [
        ({"GCB_RELEASE": False}, "no GCB release (T3)"),
        ({"COMM_OK": False}, "no fresh data from the MPU2-S (COMM_OK)"),
        ({"GEN_LIVE": False}, "generator voltage/frequency not present"),
        ({"ENGINE_READY": False}, "engine monitoring delay running (ENGINE_READY)"),
        ({"ENABLE": False}, "no sync request (ENABLE)"),
    ],
)
def test_preconditions_hold_in_check(inputs, text):
    b = block(READY, **inputs).step(3)
    assert out(b, "TEXT") == text and out(b, "STATE") in (IDLE, CHECK)
    assert not out(b, "RAISE_F") and not out(b, "LOWER_F") and not out(b, "CLOSE_CMD")
