"""Tc2_Standard (fblocks/libs/tc2_standard): TwinCAT's counters with their
RESET and LOAD inputs and WORD counts, and the string functions with their
formal parameter names. Values from the Beckhoff Information System pages
"TwinCAT 3 PLC Lib: Tc2_Standard" (CTU, CTD, CTUD, CONCAT, DELETE, FIND,
INSERT, LEFT, LEN, MID, REPLACE, RIGHT)."""

from __future__ import annotations

from .conftest import check, run


def test_ctu_counts_rising_edges_until_reset_with_twincat_input_names():
    # Tc2_Standard, CTU: "If RESET is TRUE, CV is initialised with 0. If CU has a
    # rising edge ... CV is incremented by 1 ... Q returns TRUE if CV >= PV"
    src = """
    PROGRAM Main
    VAR c : CTU; n : INT; q3 : BOOL; cv4 : WORD; END_VAR
    n := n + 1;
    c(CU := n MOD 2 = 1, RESET := n = 9, PV := 3);
    IF n = 6 THEN q3 := c.Q; END_IF
    IF n = 8 THEN cv4 := c.CV; END_IF
    END_PROGRAM
    """
    r = run(src, "Tc2_Standard", cycles=9)
    assert (r.get("q3"), r.get("cv4"), r.get("c.CV"), r.get("c.Q")) == (True, 4, 0, False)


def test_ctd_loads_pv_and_stops_at_zero_as_a_word():
    # Tc2_Standard, CTD: "CV is decremented by 1 as long as CV is greater than 0";
    # "Q returns TRUE if CV is less than or equal to 0"
    src = """
    PROGRAM Main
    VAR d : CTD; n : INT; END_VAR
    n := n + 1;
    d(CD := n MOD 2 = 0, LOAD := n = 1, PV := 2);
    END_PROGRAM
    """
    r = run(src, "Tc2_Standard", cycles=9)  # loaded 2, four rising edges
    assert (r.get("d.CV"), r.get("d.Q")) == (0, True)


def test_ctud_reset_wins_over_load_which_wins_over_counting():
    src = """
    PROGRAM Main
    VAR c : Tc2_Standard.CTUD; n : INT; a, b : WORD; END_VAR
    n := n + 1;
    c(CU := n MOD 2 = 0, CD := FALSE, RESET := n = 5, LOAD := n = 1 OR n = 5, PV := 10);
    IF n = 4 THEN a := c.CV; END_IF
    IF n = 5 THEN b := c.CV; END_IF
    END_PROGRAM
    """
    r = run(src, "Tc2_Standard", cycles=6)
    assert (r.get("a"), r.get("b"), r.get("c.CV"), r.get("c.QU")) == (12, 0, 1, False)


def test_the_string_functions_take_twincat_formal_names():
    src = """
    PROGRAM Main
    VAR s : ARRAY[0..8] OF STRING; n, f : INT; END_VAR
    s[0] := CONCAT(STR1 := 'SUSI', STR2 := 'WILLI');
    s[1] := LEFT(STR := 'SUSI', SIZE := 3);
    s[2] := RIGHT(STR := 'SUSI', SIZE := 3);
    s[3] := MID(STR := 'SUSI', LEN := 2, POS := 2);
    s[4] := INSERT(STR1 := 'SUSI', STR2 := 'XY', POS := 2);
    s[5] := DELETE(STR := 'SUXYSI', LEN := 2, POS := 3);
    s[6] := REPLACE(STR1 := 'SUXYSI', STR2 := 'K', L := 2, P := 2);
    s[7] := REPLACE('SUXYSI', 'K', 2, 2);
    n := LEN(STR := 'SUSI');
    f := FIND(STR1 := 'SUXYSI', STR2 := 'XY');
    END_PROGRAM
    """
    r = run(src, "Tc2_Standard")
    # the documented examples of each function's page
    assert r.get("s")[:8] == ["SUSIWILLI", "SUS", "USI", "US", "SUXYSI", "SUSI", "SKYSI", "SKYSI"]
    assert (r.get("n"), r.get("f")) == (4, 3)


def test_the_iec_names_are_not_twincat_ones():
    src = "PROGRAM Main VAR s : STRING; END_VAR s := CONCAT(IN1 := 'a', IN2 := 'b'); END_PROGRAM"
    [(code, line, message)] = check(src, "Tc2_Standard")
    assert (code, message) == ("E040", "CONCAT has no parameter 'IN1'")


def test_without_tc2_standard_the_iec_names_and_blocks_remain():
    src = """
    PROGRAM Main VAR s : STRING; c : CTU; END_VAR
    s := CONCAT(IN1 := 'a', IN2 := 'b'); c(CU := TRUE, R := FALSE, PV := 1);
    END_PROGRAM
    """
    assert check(src) == []
