"""CODESYS's Standard library (fblocks/libs/standard): the counters and
bistables with CODESYS's input names, RTC, and the string functions with
their formal names, as the CODESYS online help documents them."""

from __future__ import annotations

from softplc.runtime.program import check_files

from .bench import chosen, runner, trace

# the cycle number n (1, 2, ...) drives the inputs
COUNT = "n : INT; c : CTU; d : CTD; ud : CTUD; clk : BOOL;"


def test_ctu_counts_rising_edges_in_word_and_reset_wins():
    # CU pulses every other cycle; RESET at cycles 9 and 10
    r = runner(COUNT, "n := n + 1; clk := n MOD 2 = 1; c(CU := clk, RESET := n = 9 OR n = 10, PV := 3);", "Standard")
    got = trace(r, 12, "c.CV", "c.Q")
    assert [cv for cv, _ in got] == [1, 1, 2, 2, 3, 3, 4, 4, 0, 0, 1, 1]
    assert [q for _, q in got] == [False] * 4 + [True] * 4 + [False] * 4


def test_ctd_loads_pv_counts_down_to_zero_and_stops():
    r = runner(COUNT, "n := n + 1; d(CD := n MOD 2 = 0, LOAD := n = 1, PV := 2);", "Standard")
    got = trace(r, 8, "d.CV", "d.Q")
    assert got == [(2, False), (1, False), (1, False), (0, True), (0, True), (0, True), (0, True), (0, True)]


def test_ctud_reset_wins_over_load_and_the_word_limits_hold():
    body = "n := n + 1; ud(CU := n MOD 2 = 1, CD := n = 4, RESET := n = 6, LOAD := n = 6 OR n = 8, PV := 16#FFFF);"
    r = runner(COUNT, body, "Standard")
    got = trace(r, 10, "ud.CV", "ud.QU", "ud.QD")
    assert [cv for cv, _, _ in got] == [1, 1, 2, 1, 2, 0, 1, 65535, 65535, 65535]
    assert got[5] == (0, False, True) and got[7] == (65535, True, False)


def test_sr_is_set_dominant_and_rs_reset_dominant_with_codesys_names():
    decls = "n : INT; s : SR; r : RS; a : BOOL; b : BOOL;"
    # n: 1 set, 2 hold, 3 reset, 4 both, 5 none
    body = "n := n + 1; a := n = 1 OR n = 4; b := n = 3 OR n = 4; s(SET1 := a, RESET := b); r(SET := a, RESET1 := b);"
    got = trace(runner(decls, body, "Standard"), 5, "s.Q1", "r.Q1")
    assert got == [(True, True), (True, True), (False, False), (True, False), (True, False)]


def test_rtc_starts_at_pdt_and_runs_on_the_task_clock():
    decls = "clock : RTC; en : BOOL; n : INT; t : DT;"
    body = "n := n + 1; clock(EN := n < 300, PDT := DT#2024-02-28-23:59:58); t := clock.CDT;"
    r = runner(decls, body, "Standard", cycle_ms=10)
    got = trace(r, 300, "clock.Q", "t")
    assert got[0] == (True, 1709164798)  # DT#2024-02-28-23:59:58
    assert got[250] == (True, 1709164798 + 2)  # 2.5 s later: DT#2024-02-29-00:00:00
    assert got[299] == (False, 0)  # EN FALSE: DT#1970-01-01-00:00:00


def test_string_functions_take_codesys_formal_names():
    decls = "s : STRING; l : INT; p : INT; m : STRING;"
    body = """
    s := CONCAT(STR1 := 'Hello', STR2 := ' World');
    l := LEN(STR := s);
    p := FIND(STR1 := s, STR2 := 'World');
    m := MID(STR := s, LEN := 3, POS := 2);
    m := CONCAT(STR1 := m, STR2 := LEFT(STR := s, SIZE := 1));
    m := CONCAT(STR1 := m, STR2 := RIGHT(STR := s, SIZE := 1));
    m := INSERT(STR1 := m, STR2 := '-', POS := 3);
    m := REPLACE(STR1 := m, STR2 := 'E', L := 1, P := 1);
    m := DELETE(STR := m, LEN := 1, POS := 6);
    """
    r = runner(decls, body, "Standard")
    r.run(1)
    assert (r.get("s"), r.get("l"), r.get("p")) == ("Hello World", 11, 7)
    # MID: 'ell'; + 'H' + 'd' = 'ellHd'; INSERT after 3: 'ell-Hd'; REPLACE 1 at 1: 'Ell-Hd'; DELETE 1 at 6
    assert r.get("m") == "Ell-H"


def test_standard_qualifies_the_iec_blocks_it_shares_and_its_own():
    decls = "t : Standard.TON; c : Standard.CTU; e : Standard.R_TRIG; n : INT;"
    body = "n := n + 1; t(IN := TRUE, PT := T#30ms); e(CLK := t.Q); c(CU := e.Q, RESET := FALSE, PV := 1);"
    got = trace(runner(decls, body, "Standard"), 5, "t.Q", "c.CV")
    assert got == [(False, 0), (False, 0), (False, 0), (True, 1), (True, 1)]


def test_without_the_library_the_iec_names_stay():
    src = "PROGRAM Main VAR c : CTU; END_VAR c(CU := TRUE, R := FALSE, PV := 3); END_PROGRAM"
    assert check_files([], texts={"main.st": src})[0] == []
    diags, _ = check_files([], texts={"main.st": src}, libraries=chosen("Standard"))
    assert [d.code for d in diags if d.is_error], "CODESYS's CTU has RESET, not R"
