"""STEP3 and GENSET_SYNC (fblocks/vendor/genset.st), stepped 10 ms a cycle in
virtual time: the scenario vectors S1-S8 of digest 004 §5.2, the sequence
of §4.3/§4.4 around them, and closed loops where the block drives the plant
model of runtime/devices/mpu2s/plant.py (outputs to its contacts, its
values, PHASE included, to the block's inputs) each cycle.

The test sets the block's inputs directly between cycles, as a program
would wire them; the task clock starts at 0 (the first cycle runs at
TIME() = T#0ms)."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.mpu2s.plant import Breaker, Busbar, Genset, GensetPlant

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


# ---------------------------------------------------------------- closed loop: the block drives the plant

MS = 1_000_000


class Loop:
    """GENSET_SYNC and the plant, one 10 ms cycle at a time: the plant moves
    to the cycle's time, its values go to the block's inputs, the block's
    relays to the plant's contacts (they act from that instant)."""

    def __init__(self, plant: GensetPlant, **inputs) -> None:
        self.plant = plant
        self.b = block(READY, **inputs)
        self.t = 0
        self.commands: list[tuple[int, float, float]] = []  # (t, PHASE_AT_COMMAND, ADVANCE)

    def cycle(self, **inputs) -> Loop:
        p, b = self.plant, self.b
        p.advance(self.t)
        put(b, F_GEN=p.f_gen, F_BUS=p.f_bus, U_GEN=p.u_gen, U_BUS=p.u_bus, PHASE=p.phase_deg)
        put(b, GCB_CLOSED=p.gcb_closed, BUS_LIVE=p.bus_live, GEN_LIVE=p.gen_live, **inputs)
        was = out(b, "CLOSE_CMD")
        b.step()
        p.raise_f, p.lower_f = out(b, "RAISE_F"), out(b, "LOWER_F")
        p.raise_u, p.lower_u = out(b, "RAISE_U"), out(b, "LOWER_U")
        p.gcb_close, p.gcb_open = out(b, "CLOSE_CMD"), out(b, "OPEN_CMD")
        if p.gcb_close and not was:
            self.commands.append((self.t, out(b, "PHASE_AT_COMMAND"), out(b, "ADVANCE")))
        self.t += CYCLE_MS * MS
        return self

    def until(self, done, limit_s: float) -> Loop:
        end = round(limit_s * 1e9)
        while not done(self) and self.t < end:
            self.cycle()
        return self


def sweep_plant(slip: float, closing_ms: int, phase: float, u_offset: float) -> GensetPlant:
    return GensetPlant(
        Genset(f_offset=slip, u_offset=u_offset),
        Busbar(f=50.0, u=400.0),
        Breaker(closing_time_ms=closing_ms),
        phase_deg=phase,
    )


SLIPS = (-0.4, -0.2, 0.05, 0.3, 0.45)
CLOSING_MS = (40, 80, 150, 300)


def test_closed_loop_live_bus_sweep_of_slips_and_closing_times():
    """Each initial slip with each breaker closing time, the starting phase
    and voltage varied: the breaker's contacts touch within 10 deg every
    time. Measured over the 20 closes: |phase at close| min 0.004, median
    0.069, max 0.178 deg, at slips of 0.07..0.12 Hz (the f controller aims
    at SLIP_TARGET 0.1 Hz): the command goes within half a cycle's slip
    phase of the advance angle (0.18 deg at 0.1 Hz), and the slip moves a
    little under the governor's lag while the breaker closes. pytest -s
    prints the numbers."""
    errors = []
    for i, (slip, closing_ms) in enumerate((s, c) for s in SLIPS for c in CLOSING_MS):
        phase0 = (i * 137.0) % 360.0 - 180.0
        u_offset = (-12.0, 6.0, 12.0)[i % 3]
        loop = Loop(sweep_plant(slip, closing_ms, phase0, u_offset), GCB_CLOSE_TIME=closing_ms, DU_MAX=2.5, DU_MIN=2.5)
        loop.until(lambda lp: lp.plant.gcb_closed, 60.0)
        plant = loop.plant
        assert plant.gcb_closed and plant.trips == 0, (slip, closing_ms)
        (close,) = plant.closes
        (command,) = loop.commands
        assert close.t_ns == command[0] + closing_ms * MS
        assert -0.10 <= close.slip_hz <= 0.18  # the window, DF_MIN / DF_MAX
        assert abs(close.voltage_diff) <= 0.025 * 400.0
        assert abs(command[1] - command[2]) <= 180.0 * 0.18 * 0.01  # commanded within half a cycle
        errors.append(abs(close.phase_deg))
        loop.until(lambda lp: out(lp.b, "STATE") == CLOSED, 61.0)
        assert out(loop.b, "STATE") == CLOSED
    errors.sort()
    lo, median, hi = errors[0], errors[len(errors) // 2], errors[-1]
    print(f"\n|phase at close| over {len(errors)} closes: min {lo:.3f} median {median:.3f} max {hi:.3f} deg")
    assert max(errors) < 10.0


@pytest.mark.parametrize("closing_ms", CLOSING_MS)
def test_closed_loop_fast_slip_large_advance_angles(closing_ms):
    """SLIP_TARGET 0.4 Hz in a window to 0.49 Hz: advance angles up to about
    50 deg, the slip still moving under governor pulses. Measured |phase at
    close| 0.07 .. 1.05 deg."""
    for slip in (0.0, 0.45):
        loop = Loop(sweep_plant(slip, closing_ms, 100.0, 0.0), GCB_CLOSE_TIME=closing_ms, DF_MAX=0.49, SLIP_TARGET=0.4)
        loop.until(lambda lp: lp.plant.gcb_closed, 60.0)
        (close,) = loop.plant.closes
        assert close.slip_hz > 0.2 and abs(close.phase_deg) < 10.0


@pytest.mark.parametrize(
    ("constant", "normally_open", "unlock"),
    [(False, True, False), (True, True, False), (False, False, True), (True, False, True)],
)
def test_closed_loop_relay_options(constant, normally_open, unlock):
    """Konstant or Impuls, energise or de-energise to open, with and without
    the unlock pulse: the breaker wired to match closes in phase, stays
    closed, and opens on OPEN."""
    plant = GensetPlant(
        Genset(f_offset=0.25),
        Busbar(),
        Breaker(closing_time_ms=120, constant_close=constant, open_energise=normally_open),
        phase_deg=30.0,
    )
    loop = Loop(plant, GCB_CLOSE_TIME=120, CLOSE_CONSTANT=constant, OPEN_RELAY_NO=normally_open, AUTO_UNLOCK=unlock)
    loop.until(lambda lp: lp.plant.gcb_closed, 60.0)
    assert plant.gcb_closed and abs(plant.closes[0].phase_deg) < 10.0
    loop.until(lambda lp: False, loop.t / 1e9 + 5.0)
    assert plant.gcb_closed and out(loop.b, "STATE") == CLOSED and plant.p_kw > 0.0
    loop.b.step(0, OPEN=True)
    loop.until(lambda lp: out(lp.b, "STATE") == IDLE, loop.t / 1e9 + 1.0)
    assert not plant.gcb_closed and not out(loop.b, "OPEN_FAULT")


def test_closed_loop_dead_bus_close():
    """S7 in the loop: the genset starts 0.8 Hz and 3 % off rated, outside the
    dead-bus window; the controllers bring it in and the GCB closes onto the
    dead bar, which goes live at the genset's f and U."""
    plant = GensetPlant(Genset(f_offset=0.8, u_offset=-12.0), Busbar(live=False), Breaker(closing_time_ms=80))
    loop = Loop(plant, **{k: v for k, v in S7.items() if k not in ("F_GEN", "U_GEN")})
    loop.until(lambda lp: lp.plant.gcb_closed, 30.0)
    assert plant.gcb_closed and plant.bus_live
    (close,) = plant.closes
    assert close.dead_bus and not close.tripped
    assert abs(close.slip_hz - 50.0) <= 0.5 and abs(close.voltage_diff - 400.0) <= 8.0  # against 0 Hz, 0 V
    loop.cycle()
    assert out(loop.b, "STATE") == CLOSED and plant.f_bus == plant.f_gen


def test_closed_loop_sync_time_alarm_when_the_window_is_never_reached():
    """The bus at 470 V: the AVR reaches 440 V (rated + 10 %), 7.5 % short of it."""
    plant = GensetPlant(Genset(f_offset=0.1), Busbar(u=470.0), Breaker())
    loop = Loop(plant, SYNC_TIME_MON=True, SYNC_TIME=10_000)
    loop.until(lambda lp: False, 9.995)
    assert not out(loop.b, "SYNC_TIME_ALARM") and out(loop.b, "STATE") == SYNCHRONISING
    loop.until(lambda lp: False, 15.0)
    assert out(loop.b, "SYNC_TIME_ALARM") and out(loop.b, "STATE") == SYNCHRONISING
    assert plant.genset.u.setpoint == pytest.approx(440.0) and out(loop.b, "TEXT").startswith("voltage -")
    assert loop.commands == [] and plant.closes == []


def test_closed_loop_refusing_breaker_close_fault_after_five_attempts():
    plant = GensetPlant(Genset(f_offset=0.1), Busbar(), Breaker(closing_time_ms=80, refuse_close=True))
    loop = Loop(plant, CLOSE_PULSE=200, GCB_CLOSE_TIME=80, GCB_MONITOR=True)
    loop.until(lambda lp: out(lp.b, "ATTEMPTS") == 4, 120.0)
    assert not out(loop.b, "CLOSE_FAULT")
    loop.until(lambda lp: out(lp.b, "ATTEMPTS") == 5, 120.0)
    assert out(loop.b, "CLOSE_FAULT") and plant.breaker.refused == 5
    # every attempt went out at the advance angle of its moment, about one slip period apart
    assert all(abs(phi - adv) <= 180.0 * 0.18 * 0.01 for _t, phi, adv in loop.commands)
    gaps = [b[0] - a[0] for a, b in zip(loop.commands, loop.commands[1:])]
    assert all(5e9 < gap < 20e9 for gap in gaps)
    loop.until(lambda lp: out(lp.b, "ATTEMPTS") == 6, 200.0)  # [E]: the attempts go on
    assert out(loop.b, "ATTEMPTS") == 6 and not plant.gcb_closed


def test_closed_loop_comm_lost_mid_sequence_no_close_command_while_false():
    """COMM_OK falls while the phase approaches the advance angle and stays
    FALSE for a whole slip period: no close command. Back, the close goes on
    the next turn, in phase."""
    plant = GensetPlant(Genset(f_offset=0.1), Busbar(), Breaker(closing_time_ms=80), phase_deg=-120.0)
    loop = Loop(plant)

    def approaching(lp: Loop) -> bool:
        b = lp.b
        return out(b, "IN_WINDOW") and out(b, "DF") > 0.05 and -40.0 < out(b, "PHASE") - out(b, "ADVANCE") < -20.0

    loop.until(approaching, 60.0)
    assert approaching(loop) and not plant.gcb_closed and loop.commands == []
    lost_until = loop.t + 15 * 10**9  # 1.5 turns at 0.1 Hz
    while loop.t < lost_until:
        loop.cycle(COMM_OK=False)
        assert not out(loop.b, "CLOSE_CMD") and not plant.gcb_closed
    assert out(loop.b, "TEXT") == "no fresh data from the MPU2-S (COMM_OK)"
    loop.b.step(0, COMM_OK=True)
    loop.until(lambda lp: lp.plant.gcb_closed, 120.0)
    assert plant.gcb_closed and abs(plant.closes[0].phase_deg) < 10.0
