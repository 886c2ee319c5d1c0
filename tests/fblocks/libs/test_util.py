"""CODESYS's Util library (fblocks/libs/util) against the behaviour and the
examples of the CODESYS online help (libs/Util), in virtual time."""

from __future__ import annotations

import pytest

from .bench import runner, trace


def run_once(decls: str, body: str):
    r = runner(decls, body, "Util")
    r.run(1)
    return r


def test_bcd_and_bit_functions():
    r = run_once(
        "a : INT; b : INT; c : BYTE; d : BYTE; e : BOOL; f : DWORD; g : BYTE; u : UNPACK; h : BOOL; k : BOOL;",
        """a := BCD_TO_INT(16#42); b := BCD_TO_INT(16#4A); c := INT_TO_BCD(42); d := INT_TO_BCD(100);
        e := EXTRACT(2#0100, 2); f := PUTBIT(PUTBIT(16#FF, 0, FALSE), 9, TRUE);
        g := PACK(TRUE, FALSE, FALSE, FALSE, FALSE, FALSE, FALSE, TRUE);
        u(B := 16#81); h := u.B7 AND u.B0; k := u.B1 OR u.B6;""",
    )
    assert [r.get(n) for n in "abcdefgh"] == [42, -1, 0x42, 255, True, 0x2FE, 0x81, True]
    assert r.get("k") is False


def test_hysteresis_switches_below_low_and_above_high():
    # HIGH 100, LOW 30: the input walks 50, 29, 50, 100, 101, 30, 29
    decls = "h : HYSTERESIS; x : ARRAY[1..7] OF INT := [50, 29, 50, 100, 101, 30, 29]; n : INT;"
    got = trace(runner(decls, "n := n + 1; h(IN := x[n], HIGH := 100, LOW := 30);", "Util"), 7, "h.OUT")
    assert got == [False, True, True, True, False, False, True]


def test_limitalarm_tells_above_below_and_inside():
    decls = "l : LIMITALARM; x : ARRAY[1..3] OF INT := [101, 50, -1]; n : INT;"
    got = trace(runner(decls, "n := n + 1; l(IN := x[n], HIGH := 100, LOW := 0);", "Util"), 3, "l.O", "l.U", "l.IL")
    assert got == [(True, False, False), (False, False, True), (False, True, False)]


def test_lin_trafo_maps_4_20_ma_onto_percent_and_refuses_an_empty_range():
    r = run_once(
        "t : LIN_TRAFO; e : LIN_TRAFO; y : REAL; bad : BOOL;",
        """t(IN := 12, IN_MIN := 4, IN_MAX := 20, OUT_MIN := 0, OUT_MAX := 100); y := t.OUT;
        e(IN := 12, IN_MIN := 4, IN_MAX := 4, OUT_MIN := 0, OUT_MAX := 100); bad := e.ERROR;""",
    )
    assert (r.get("y"), r.get("bad"), r.get("t.ERROR")) == (50.0, True, False)


def test_blink_alternates_timelow_then_timehigh_in_virtual_time():
    decls = "b : BLINK; n : INT;"
    body = "n := n + 1; b(ENABLE := n <= 12, TIMELOW := T#30ms, TIMEHIGH := T#20ms);"
    got = trace(runner(decls, body, "Util", cycle_ms=10), 14, "b.OUT")
    # t = 0, 10, ... ms: 30 ms low, 20 ms high, again; ENABLE FALSE from the 13th call
    assert got == [c == "1" for c in "00011000110000"]


def test_charcurve_interpolates_the_help_example_and_reports_its_errors():
    # the help's example: (0,0) (250,50) (500,150) (750,400) (1000,1000), N = 5
    decls = """kl : ARRAY[0..10] OF POINT := [(X:=0,Y:=0), (X:=250,Y:=50), (X:=500,Y:=150), (X:=750,Y:=400),
        7((X:=1000,Y:=1000))];
        bad : ARRAY[0..10] OF POINT := [(X:=0,Y:=0), (X:=500,Y:=50), (X:=400,Y:=80), 8((X:=1000,Y:=1000))];
        c : CHARCURVE; x : ARRAY[1..7] OF INT := [125, 375, 600, 1000, 1010, -5, 0];
        out : ARRAY[1..7] OF INT; err : ARRAY[1..7] OF BYTE; i : INT; e1 : BYTE; e4 : BYTE; o4 : INT;"""
    body = """FOR i := 1 TO 7 DO c(IN := x[i], N := 5, P := kl); out[i] := c.OUT; err[i] := c.ERR; END_FOR
        c(IN := 450, N := 3, P := bad); o4 := c.OUT; c(IN := 600, N := 3, P := bad); e1 := c.ERR;
        c(IN := 450, N := 12, P := kl); e4 := c.ERR;"""
    r = run_once(decls, body)
    assert r.get("out") == [25, 100, 250, 1000, 1000, 0, 0]
    assert r.get("err") == [0, 0, 0, 0, 2, 2, 0]
    # the wrong order is found once IN reaches it; N invalid: OUT as it was
    assert (r.get("o4"), r.get("e1"), r.get("e4"), r.get("c.OUT")) == (45, 1, 4, 45)


def test_statistics_and_variance_over_a_sequence_and_after_reset():
    decls = """s : STATISTICS_INT; sr : STATISTICS_REAL; v : VARIANCE; n : INT;
        xi : ARRAY[1..9] OF INT := [3, -2, 10, 5, 0, 7, 0, 0, 0];
        xr : ARRAY[1..9] OF REAL := [2, 4, 4, 4, 5, 5, 7, 9, 0];"""
    body = """n := n + 1; s(IN := xi[n], RESET := n = 5); sr(IN := xr[n], RESET := FALSE);
        v(IN := xr[n], RESET := n = 9);"""
    got = trace(runner(decls, body, "Util"), 9, "s.MN", "s.MX", "s.AVG", "sr.AVG", "v.OUT")
    assert got[3][:3] == (-2, 10, 4)  # 3, -2, 10, 5: their mean is 16 / 4
    assert got[4][:3] == (0, 0, 0) and got[5][:3] == (7, 7, 7)  # RESET, then 7 alone
    assert got[7][3:] == (5.0, 4.0)  # 2 4 4 4 5 5 7 9: mean 5, variance 4
    assert got[8][4] == 0.0


def test_integral_and_derivative_of_a_ramp():
    # IN = 3 per second of time, TM = 100 ms
    decls = "i : INTEGRAL; d : DERIVATIVE; n : INT; x : REAL;"
    body = "n := n + 1; x := 0.3 * INT_TO_REAL(n); i(IN := 2.0, TM := 100, RESET := n = 1); d(IN := x, TM := 100);"
    got = trace(runner(decls, body, "Util"), 11, "i.OUT", "d.OUT")
    assert got[10][0] == pytest.approx(2.0)  # 10 steps of 2.0 * 0.1 s after the RESET
    assert got[0][1] == 0.0 and got[5][1] == pytest.approx(3.0)


PID = """p : PID_FIXCYCLE; q : PID; n : INT;"""


def test_pid_step_response_integrates_and_stops_at_its_limit():
    # KP 2, TN 1 s, CYCLE 0.1 s, a step of 1: Y = 2 (1 + 0.1 k); Y_MAX 2.5 stops the integral
    body = """n := n + 1;
    p(ACTUAL := 0, SET_POINT := 1, KP := 2, TN := 1, TV := 0, Y_MIN := -10, Y_MAX := 2.5, CYCLE := 0.1);
    q(ACTUAL := 0, SET_POINT := 1, KP := 2, TN := 1, TV := 0, Y_MIN := -10, Y_MAX := 2.5);"""
    got = trace(runner(PID, body, "Util", cycle_ms=100), 6, "p.Y", "p.LIMITS_ACTIVE", "q.Y")
    assert [round(y, 5) for y, _, _ in got] == [2.0, 2.2, 2.4, 2.5, 2.5, 2.5]
    assert [lim for _, lim, _ in got] == [False, False, False, True, True, True]
    assert [round(y, 5) for _, _, y in got] == [2.0, 2.2, 2.4, 2.5, 2.5, 2.5]  # the task clock's 100 ms


def test_pid_manual_reset_and_the_derivative_part():
    body = """n := n + 1;
    p(ACTUAL := 0.1 * INT_TO_REAL(n), SET_POINT := 0, KP := 1, TN := 0, TV := 0.5, Y_OFFSET := 10,
      MANUAL := n = 4, Y_MANUAL := 42, RESET := n = 5, CYCLE := 0.1);"""
    got = trace(runner(PID, body, "Util", cycle_ms=100), 6, "p.Y")
    # e = -0.1 n, de/dt = -1/s: Y = 10 - 0.1 n - 0.5 once there is a previous call
    assert [round(y, 4) for y in got] == [9.9, 9.3, 9.2, 42.0, 10.0, 8.9]


def test_pd_is_pid_without_integral():
    r = runner(
        "p : PD; n : INT;",
        "n := n + 1; p(ACTUAL := 0, SET_POINT := 1, KP := 3, TV := 0, Y_MIN := 0, Y_MAX := 0);",
        "Util",
        cycle_ms=100,
    )
    assert trace(r, 3, "p.Y") == [3.0, 3.0, 3.0]


def test_ramp_int_limits_the_slope_per_timebase():
    # 25 per second, called every 100 ms: 2.5 per call; the first call only starts the ramp
    decls = "r : RAMP_INT; rr : RAMP_REAL; n : INT;"
    body = """n := n + 1; r(IN := 100, ASCEND := 25, DESCEND := 10, TIMEBASE := T#1s, RESET := n = 13);
        rr(IN := SEL(n < 4, -1.0, 1.0), ASCEND := 0.5, DESCEND := 0.25, TIMEBASE := T#0s);"""
    got = trace(runner(decls, body, "Util", cycle_ms=100), 15, "r.OUT", "rr.OUT")
    assert [o for o, _ in got][:12] == [0, 2, 5, 7, 10, 12, 15, 17, 20, 22, 25, 27]
    assert got[12][0] == 27 and got[13][0] == 27  # RESET keeps OUT; the ramp starts again from it
    assert [o for _, o in got][:6] == [0.5, 1.0, 1.0, 0.75, 0.5, 0.25]


@pytest.mark.parametrize(
    "mode, values",
    [
        ("TRIANGLE", [0, 100, 0, -100, 0]),
        ("TRIANGLE_POS", [0, 50, 100, 50, 0]),
        ("SAWTOOTH_RISE", [-100, -50, 0, 50, -100]),
        ("SAWTOOTH_FALL", [100, 50, 0, -50, 100]),
        ("RECTANGLE", [100, 100, -100, -100, 100]),
        ("SINE", [0, 100, 0, -100, 0]),
        ("COSINE", [100, 0, -100, 0, 100]),
    ],
)
def test_gen_by_calls(mode, values):
    r = runner("g : GEN;", f"g(MODE := GEN_MODE.{mode}, BASE := FALSE, CYCLES := 4, AMPLITUDE := 100);", "Util")
    assert trace(r, 5, "g.OUT") == values


def test_gen_by_time_and_freq_measure():
    decls = "g : GEN; f : FREQ_MEASURE; clk : BOOL;"
    body = """g(MODE := GEN_MODE.SAWTOOTH_RISE, BASE := TRUE, PERIOD := T#100ms, AMPLITUDE := 10);
        clk := NOT clk; f(IN := clk, PERIODS := 3);"""
    got = trace(runner(decls, body, "Util", cycle_ms=25), 9, "g.OUT", "f.OUT", "f.VALID")
    assert [o for o, _, _ in got][:5] == [-10, -5, 0, 5, -10]
    assert got[5][2] is False and got[8][1:] == (20.0, True)  # a period of 50 ms: 20 Hz
