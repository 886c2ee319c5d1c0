"""The IEC standard function blocks (fblocks/iec/standard_fbs.st), driven
cycle by cycle in virtual time through small ST programs.

Each test wraps one block in a PROGRAM that copies the block's outputs into
program variables; the test sets the program's inputs between cycles. With
the default 10 ms cycle, TIME() advances 10 ms from one call to the next.
"""

import pytest

from softplc.runtime.program import compile_files

CYCLE_MS = 10


class Bench:
    """One PROGRAM around one block, stepped a cycle at a time."""

    def __init__(self, decls: str, body: str, profile: str = "codesys") -> None:
        text = f"PROGRAM bench\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"
        prog = compile_files([], texts={"bench.st": text}, profile=profile)
        self.runner = prog.runner("bench", cycle_time_ms=CYCLE_MS)
        self.inst = self.runner.instance
        self._attr = {name.upper(): py for name, py, _t, _s in type(self.inst)._VARS_}

    def __getitem__(self, name: str):
        return getattr(self.inst, self._attr[name.upper()])

    def __setitem__(self, name: str, value) -> None:
        setattr(self.inst, self._attr[name.upper()], value)

    def step(self, n: int = 1, **inputs) -> "Bench":
        for name, value in inputs.items():
            self[name] = value
        self.runner.run(n)
        return self

    def trace(self, signals: list, **inputs_per_cycle) -> list:
        """Run one cycle per element of the input lists; return the chosen
        signals after each cycle as tuples."""
        length = len(next(iter(inputs_per_cycle.values())))
        out = []
        for i in range(length):
            self.step(**{k: v[i] for k, v in inputs_per_cycle.items()})
            out.append(tuple(self[s] for s in signals))
        return out


def bits(text: str) -> list:
    """'0011' -> [False, False, True, True]"""
    return [c == "1" for c in text]


def fb_inner(bench: Bench, fb: str, var: str):
    """A variable inside an FB instance of the bench program."""
    inst = bench[fb]
    for name, py, _t, _s in type(inst)._VARS_:
        if name.upper() == var.upper():
            return inst, py
    raise KeyError(var)


# ---------------------------------------------------------------- clock


def test_clock_advances_one_cycle_time_per_cycle():
    b = Bench(
        "t0 : TIME; t1 : TIME; first : BOOL := TRUE;",
        "IF first THEN t0 := TIME(); first := FALSE; END_IF t1 := TIME();",
    )
    b.step(5)
    assert b["t1"] - b["t0"] == 4 * CYCLE_MS


# ---------------------------------------------------------------- TON

TON_BENCH = (
    "t : TON; in_ : BOOL; pt : TIME := T#50ms; q : BOOL; et : TIME;",
    "t(IN := in_, PT := pt); q := t.Q; et := t.ET;",
)


def test_ton_timing_diagram():
    b = Bench(*TON_BENCH)
    assert b.step(in_=False)["q"] is False and b["et"] == 0
    # IN rises: ET counts 0, 10, .. 40 ms, then reaches PT in the 6th cycle.
    got = b.trace(["q", "et"], in_=[True] * 8)
    assert got == [
        (False, 0),
        (False, 10),
        (False, 20),
        (False, 30),
        (False, 40),
        (True, 50),
        (True, 50),
        (True, 50),
    ]  # ET holds at PT
    assert b.step(in_=False)["q"] is False and b["et"] == 0  # IN low resets


def test_ton_short_input_never_sets_q():
    b = Bench(*TON_BENCH)
    got = b.trace(["q"], in_=bits("1111011110"))
    assert not any(q for (q,) in got)


def test_ton_pt_zero_is_immediate():
    b = Bench(*TON_BENCH)
    b["pt"] = 0
    assert b.step(in_=True)["q"] is True and b["et"] == 0


# ---------------------------------------------------------------- TOF

TOF_BENCH = ("t : TOF; in_ : BOOL; q : BOOL; et : TIME;", "t(IN := in_, PT := T#50ms); q := t.Q; et := t.ET;")


def test_tof_timing_diagram():
    b = Bench(*TOF_BENCH)
    assert b.step(in_=False)["q"] is False and b["et"] == 0  # never on: stays off
    assert b.step(in_=True)["q"] is True and b["et"] == 0  # Q follows IN up at once
    got = b.trace(["q", "et"], in_=[False] * 7)
    assert got == [
        (True, 0),
        (True, 10),
        (True, 20),
        (True, 30),
        (True, 40),
        (False, 50),
        (False, 50),
    ]  # ET holds at PT
    assert b.step(in_=True)["q"] is True and b["et"] == 0


def test_tof_input_back_during_delay_restarts_it():
    b = Bench(*TOF_BENCH)
    b.step(in_=True)
    b.step(3, in_=False)
    assert b["et"] == 20
    assert b.step(in_=True)["et"] == 0
    got = b.trace(["q"], in_=[False] * 6)
    assert [q for (q,) in got] == [True] * 5 + [False]


# ---------------------------------------------------------------- TP

TP_BENCH = ("t : TP; in_ : BOOL; q : BOOL; et : TIME;", "t(IN := in_, PT := T#50ms); q := t.Q; et := t.ET;")


def test_tp_pulse_and_et_hold():
    b = Bench(*TP_BENCH)
    got = b.trace(["q", "et"], in_=[True] * 8)
    assert got == [
        (True, 0),
        (True, 10),
        (True, 20),
        (True, 30),
        (True, 40),
        (False, 50),
        (False, 50),
        (False, 50),
    ]  # one pulse; ET holds
    assert b.step(in_=False)["et"] == 0  # reset once IN is low


def test_tp_is_not_retriggerable():
    b = Bench(*TP_BENCH)
    # IN toggles during the pulse: the pulse still lasts exactly 5 cycles.
    got = b.trace(["q"], in_=bits("1010100000"))
    assert [q for (q,) in got] == bits("1111100000")


def test_tp_short_input_gives_full_pulse_and_new_edge_new_pulse():
    b = Bench(*TP_BENCH)
    got = b.trace(["q"], in_=bits("10000000100000"))
    assert [q for (q,) in got] == bits("11111000111110")


# ---------------------------------------------------------------- L-timers


def test_lton_counts_in_nanoseconds():
    b = Bench("t : LTON; in_ : BOOL; q : BOOL; et : LTIME;", "t(IN := in_, PT := LTIME#50ms); q := t.Q; et := t.ET;")
    got = b.trace(["q", "et"], in_=[True] * 7)
    ms = 1_000_000
    assert got == [
        (False, 0),
        (False, 10 * ms),
        (False, 20 * ms),
        (False, 30 * ms),
        (False, 40 * ms),
        (True, 50 * ms),
        (True, 50 * ms),
    ]


def test_ltof_and_ltp():
    b = Bench(
        "f : LTOF; p : LTP; in_ : BOOL; qf : BOOL; qp : BOOL;",
        "f(IN := in_, PT := LTIME#30ms); p(IN := in_, PT := LTIME#30ms); qf := f.Q; qp := p.Q;",
    )
    got = b.trace(["qf", "qp"], in_=bits("1000000"))
    assert [x for x, _ in got] == bits("1111000")  # off delay 30 ms after IN fell
    assert [y for _, y in got] == bits("1110000")  # 30 ms pulse


# ---------------------------------------------------------------- counters

CTU_BENCH = (
    "c : CTU; cu : BOOL; r : BOOL; pv : INT := 3; q : BOOL; cv : INT;",
    "c(CU := cu, R := r, PV := pv); q := c.Q; cv := c.CV;",
)


def test_ctu_counts_rising_edges_to_pv():
    b = Bench(*CTU_BENCH)
    got = b.trace(["cv", "q"], cu=bits("1101010110"))
    assert got == [
        (1, False),
        (1, False),
        (1, False),
        (2, False),
        (2, False),
        (3, True),
        (3, True),
        (4, True),
        (4, True),
        (4, True),
    ]
    assert b.step(r=True, cu=True)["cv"] == 0 and b["q"] is False  # R wins
    assert b.step(r=False, cu=True)["cv"] == 0  # CU held: no edge


def test_ctu_stops_at_int_max():
    b = Bench(*CTU_BENCH)
    b.step(cu=False)
    inst, cv = fb_inner(b, "c", "CV")
    setattr(inst, cv, 32766)
    b.trace(["cv"], cu=bits("101010"))
    assert b["cv"] == 32767


CTD_BENCH = (
    "c : CTD; cd : BOOL; ld : BOOL; pv : INT := 2; q : BOOL; cv : INT;",
    "c(CD := cd, LD := ld, PV := pv); q := c.Q; cv := c.CV;",
)


def test_ctd_load_and_count_down():
    b = Bench(*CTD_BENCH)
    assert b.step()["q"] is True and b["cv"] == 0  # CV = 0 counts as done
    assert b.step(ld=True)["cv"] == 2 and b["q"] is False
    got = b.trace(["cv", "q"], ld=[False] * 6, cd=bits("101010"))
    assert got == [(1, False), (1, False), (0, True), (0, True), (-1, True), (-1, True)]


def test_ctd_stops_at_int_min():
    b = Bench(*CTD_BENCH)
    b.step()
    inst, cv = fb_inner(b, "c", "CV")
    setattr(inst, cv, -32767)
    b.trace(["cv"], cd=bits("101010"))
    assert b["cv"] == -32768


CTUD_BENCH = (
    "c : CTUD; cu, cd, r, ld : BOOL; pv : INT := 2; qu : BOOL; qd : BOOL; cv : INT;",
    "c(CU := cu, CD := cd, R := r, LD := ld, PV := pv); qu := c.QU; qd := c.QD; cv := c.CV;",
)


def test_ctud_up_down():
    b = Bench(*CTUD_BENCH)
    assert b.step()["qd"] is True and b["qu"] is False
    got = b.trace(["cv", "qu", "qd"], cu=bits("1010000"), cd=bits("0000101"))
    assert got == [
        (1, False, False),
        (1, False, False),
        (2, True, False),
        (2, True, False),
        (1, False, False),
        (1, False, False),
        (0, False, True),
    ]


def test_ctud_simultaneous_edges_cancel():
    b = Bench(*CTUD_BENCH)
    b.step(cu=True)
    assert b["cv"] == 1
    b.step(cu=False)
    assert b.step(cu=True, cd=True)["cv"] == 1


def test_ctud_reset_wins_over_load_wins_over_counting():
    b = Bench(*CTUD_BENCH)
    assert b.step(ld=True, cu=True)["cv"] == 2 and b["qu"] is True
    assert b.step(r=True, ld=True, cu=False)["cv"] == 0 and b["qd"] is True
    b.step(r=False, ld=False)
    assert b.step(cu=True)["cv"] == 1


# ---------------------------------------------------------------- edges


def test_r_trig():
    b = Bench("e : R_TRIG; clk : BOOL; q : BOOL;", "e(CLK := clk); q := e.Q;")
    got = b.trace(["q"], clk=bits("1101100"))
    # The first call with CLK TRUE is an edge (memory starts FALSE), as CODESYS.
    assert [q for (q,) in got] == bits("1001000")


@pytest.mark.parametrize("profile", ["codesys", "twincat", "iec", "schneider"])
def test_f_trig(profile):
    b = Bench("e : F_TRIG; clk : BOOL; q : BOOL;", "e(CLK := clk); q := e.Q;", profile)
    got = b.trace(["q"], clk=bits("0011001"))
    # The memory starts TRUE (IEC 61131-3 ed.3 Table 44; the CODESYS Standard
    # and TwinCAT F_TRIG): CLK FALSE at the first call is no edge, only a
    # fall from TRUE is
    assert [q for (q,) in got] == bits("0000100")


def test_f_trig_in_matiec_fires_once_at_start_up():
    # MatIEC's library declares the memory without an initial value: the
    # first call with CLK FALSE reports an edge there
    b = Bench("e : F_TRIG; clk : BOOL; q : BOOL;", "e(CLK := clk); q := e.Q;", "matiec")
    got = b.trace(["q"], clk=bits("0011001"))
    assert [q for (q,) in got] == bits("1000100")


@pytest.mark.parametrize("profile", ["codesys", "matiec"])
def test_f_trig_first_call_high(profile):
    b = Bench("e : F_TRIG; clk : BOOL; q : BOOL;", "e(CLK := clk); q := e.Q;", profile)
    got = b.trace(["q"], clk=bits("1100"))
    assert [q for (q,) in got] == bits("0010")


# ---------------------------------------------------------------- bistables


@pytest.mark.parametrize(
    "fb, set_name, reset_name, both",
    [
        ("SR", "S1", "R", True),  # set dominant; the IEC 61131-3 ed.3 Table 43 names
        ("RS", "S", "R1", False),  # reset dominant
    ],
)
def test_bistables(fb, set_name, reset_name, both):
    b = Bench(f"b : {fb}; s : BOOL; r : BOOL; q : BOOL;", f"b({set_name} := s, {reset_name} := r); q := b.Q1;")
    assert b.step()["q"] is False
    assert b.step(s=True)["q"] is True
    assert b.step(s=False)["q"] is True  # latched
    assert b.step(r=True)["q"] is False
    assert b.step(r=False)["q"] is False
    assert b.step(s=True, r=True)["q"] is both
    b.step(s=False, r=False)
    assert b["q"] is both  # keeps what it had


@pytest.mark.parametrize("fb, both", [("SR", True), ("RS", False)])
def test_bistables_positional_set_then_reset(fb, both):
    """SR(set, reset) and RS(set, reset), positionally as in CODESYS."""
    b = Bench(f"b : {fb}; s : BOOL; r : BOOL; q : BOOL;", "b(s, r); q := b.Q1;")
    assert b.step(s=True)["q"] is True
    assert b.step(s=False, r=True)["q"] is False
    assert b.step(s=True, r=True)["q"] is both


def test_the_codesys_names_are_the_standard_librarys():
    """SR(SET1, RESET) is CODESYS's (fblocks/libs/standard): a program that
    does not choose that library has the IEC inputs only."""
    from softplc.runtime.program import check_files

    src = "PROGRAM Main VAR b : SR; s : BOOL; END_VAR b(SET1 := s); END_PROGRAM"
    diags, _ = check_files([], texts={"main.st": src})
    assert [d.code for d in diags if d.is_error] and "SET1" in diags[0].message


def test_user_pou_replaces_a_standard_block():
    text = """
    FUNCTION_BLOCK TON
    VAR_INPUT IN : BOOL; END_VAR
    VAR_OUTPUT Q : BOOL; END_VAR
    Q := NOT IN;
    END_FUNCTION_BLOCK
    PROGRAM p
    VAR t : TON; q : BOOL; END_VAR
    t(IN := FALSE); q := t.Q;
    END_PROGRAM
    """
    prog = compile_files([], texts={"shadow.st": text})
    r = prog.runner("p")
    r.run(1)
    assert {n: getattr(r.instance, py) for n, py, _t, _s in type(r.instance)._VARS_}["q"] is True
