"""Tc2_System (fblocks/libs/tc2_system): memory through pointers, the
clock, the task information, bit functions, ADSLOG*, synchronisation, and
the ADS and file blocks that answer "not available". Values and examples
from the Beckhoff Information System pages "TwinCAT 3 PLC Lib: Tc2_System"
(MEMCPY, MEMCMP, MEMSET, MEMMOVE, F_GetSystemTime, F_GetTaskTime,
GETCURTASKINDEX, SETBIT32, CSETBIT32, ADSLOGSTR, TestAndSet, DRAND,
ADSREAD, FB_FileOpen) and "ADS Return Codes" (6: target port not found)."""

from __future__ import annotations

import logging

import pytest

from softplc.runtime.program import compile_files
from softplc.runtime.program.context import VIRTUAL_EPOCH_NS
from softplc.runtime.st.faults import STFault

from .conftest import check, libs, run

FILETIME_2000 = 125_911_584_000_000_000  # 2000-01-01 in 100 ns since 1601-01-01


def test_memcpy_copies_a_structure_into_bytes_and_back():
    # MEMCPY: "> 0: if successful, the number of bytes copied (n)"
    src = """
    TYPE ST_A : STRUCT a : INT; b : REAL; s : STRING(5); END_STRUCT END_TYPE
    PROGRAM Main
    VAR st, st2 : ST_A; arr : ARRAY[0..15] OF BYTE; n, m, z, z2 : UDINT; END_VAR
    st.a := 258; st.b := 1.5; st.s := 'hi';
    n := MEMCPY(ADR(arr), ADR(st), SIZEOF(st));
    m := MEMCPY(destAddr := ADR(st2), srcAddr := ADR(arr), n := SIZEOF(st2));
    z := MEMCPY(ADR(st2), ADR(arr), 0);
    z2 := MEMCPY(0, ADR(arr), 4);  (* "0: incorrect parameter values (destAddr == 0 ...)" *)
    END_PROGRAM
    """
    r = run(src, "Tc2_System")
    # x64 layout: INT at 0, REAL at 4 (aligned), STRING(5) at 8
    assert r.get("arr")[:12] == [2, 1, 0, 0, 0, 0, 0xC0, 0x3F, ord("h"), ord("i"), 0, 0]
    assert (r.get("n"), r.get("m"), r.get("z"), r.get("z2")) == (16, 16, 0, 0)
    assert (r.get("st2.a"), r.get("st2.b"), r.get("st2.s")) == (258, 1.5, "hi")


def test_memcmp_answers_the_sign_of_the_first_differing_byte():
    # MEMCMP: -1 pBuf1 lower, 0 identical, 1 greater, 16#FF incorrect parameters
    src = """
    PROGRAM Main
    VAR b1 : ARRAY[0..3] OF BYTE := [1, 2, 9, 0]; b2 : ARRAY[0..3] OF BYTE := [1, 2, 3, 4];
        gt, lt, eq, bad : DINT; END_VAR
    gt := MEMCMP(ADR(b1), ADR(b2), 4);
    lt := MEMCMP(pBuf1 := ADR(b2), pBuf2 := ADR(b1), n := 4);
    eq := MEMCMP(ADR(b1), ADR(b2), 2);
    bad := MEMCMP(ADR(b1), ADR(b2), 0);
    END_PROGRAM
    """
    r = run(src, "Tc2_System")
    assert [r.get(n) for n in ("gt", "lt", "eq", "bad")] == [1, -1, 0, 0xFF]


def test_memset_fills_and_memmove_shifts_within_one_array():
    src = """
    PROGRAM Main
    VAR w : ARRAY[0..3] OF WORD; b : ARRAY[0..5] OF BYTE := [1, 2, 3, 4, 5, 6]; p : PVOID; END_VAR
    MEMSET(ADR(w), 16#AB, SIZEOF(w));
    p := ADR(b);
    MEMMOVE(p + 1, p, 4);          (* the areas overlap: MEMMOVE's case *)
    END_PROGRAM
    """
    r = run(src, "Tc2_System")
    assert r.get("w") == [0xABAB] * 4
    assert r.get("b") == [1, 1, 2, 3, 4, 6]


def test_a_pvoid_moves_by_bytes_through_an_array_of_lreal():
    # lcls-twincat-general's buffers: destAddr := pPartialAdr + iArrayIndex * iInputSize
    src = """
    PROGRAM Main
    VAR x : LREAL := 2.5; arr : ARRAY[1..4] OF LREAL; pArr, pX : PVOID; i : INT; END_VAR
    pArr := ADR(arr); pX := ADR(x);
    FOR i := 0 TO 3 DO
        MEMCPY(pArr + i * SIZEOF(x), pX, SIZEOF(x));
        x := x * 2;
    END_FOR
    END_PROGRAM
    """
    assert run(src, "Tc2_System").get("arr") == [2.5, 5.0, 10.0, 20.0]


def test_memcpy_past_its_variable_is_a_reference_fault_not_a_neighbour():
    src = """
    PROGRAM Main VAR a : ARRAY[0..3] OF BYTE; b : DINT; END_VAR
    MEMCPY(ADR(a), ADR(b), 8);
    END_PROGRAM
    """
    with pytest.raises(STFault) as err:
        run(src, "Tc2_System")
    assert err.value.kind == "reference"
    assert "MEMCPY: 8 byte(s) from byte offset 0 of a 4-byte variable" in str(err.value)


def test_the_system_types_are_those_of_twincat_x64():
    src = """
    PROGRAM Main
    VAR s : T_MaxString; p : PVOID; u : UXINT; x : XINT; g : GUID; a, b, c, d : UDINT; hr : HRESULT := -1; END_VAR
    a := SIZEOF(s); b := SIZEOF(p); c := SIZEOF(u); d := SIZEOF(g);
    END_PROGRAM
    """
    r = run(src, "Tc2_System")
    assert [r.get(n) for n in "abcd"] == [256, 8, 8, 16]


def test_f_getsystemtime_counts_100ns_since_1601_on_the_virtual_clock():
    # F_GetSystemTime: "the number of 100 ns intervals since January 1, 1601 (UTC)";
    # here the engine's date: virtual time starts on 2000-01-01
    src = """
    PROGRAM Main
    VAR t0, t, task : ULINT; g : GETSYSTEMTIME; lo, hi : UDINT; END_VAR
    t := F_GetSystemTime();
    IF t0 = 0 THEN t0 := t; END_IF
    task := F_GetTaskTime();
    g(timeLoDW => lo, timeHiDW => hi);
    END_PROGRAM
    """
    r = run(src, "Tc2_System", cycles=11, cycle_time_ms=100)
    assert r.get("t0") == FILETIME_2000 == (VIRTUAL_EPOCH_NS // 100 + 116_444_736_000_000_000)
    assert r.get("t") - r.get("t0") == 10_000_000  # one virtual second in 100 ns
    assert r.get("task") == r.get("t")  # the cycle's start
    assert r.get("hi") * 2**32 + r.get("lo") == r.get("t")


def test_task_info_tells_the_cycle_count_and_the_first_cycle():
    src = """
    PROGRAM Main
    VAR idx : DINT; gi : GETCURTASKINDEX; first : ARRAY[1..3] OF BOOL; count : UDINT; ct : UDINT; n : INT; END_VAR
    n := n + 1;
    idx := GETCURTASKINDEXEX();
    gi();
    IF n <= 3 THEN first[n] := _TaskInfo[idx].FirstCycle; END_IF
    count := TwinCAT_SystemInfoVarList._TaskInfo[gi.index].CycleCount;
    ct := _TaskInfo[1].CycleTime;
    END_PROGRAM
    """
    r = run(src, "Tc2_System", cycles=5, cycle_time_ms=10)
    assert (r.get("idx"), r.get("gi.index"), r.get("count")) == (1, 1, 5)
    assert r.get("first") == [True, False, False]
    assert r.get("ct") == 100_000  # 10 ms in 100 ns units


def test_getcurtaskindex_in_a_program_of_the_second_task_is_2():
    from softplc.runtime.engine.clock import VirtualClock
    from softplc.runtime.engine.scan import Engine
    from tests.engine.conftest import task

    src = """
    PROGRAM A VAR idx : BYTE; gi : GETCURTASKINDEX; END_VAR gi(); idx := gi.index; END_PROGRAM
    PROGRAM B
    VAR gi : GETCURTASKINDEX; idx : BYTE; cycles : UDINT; name : STRING; END_VAR
    gi(); idx := gi.index;
    cycles := _TaskInfo[idx].CycleCount;
    name := _TaskInfo[idx].TaskName;
    END_PROGRAM
    """
    prog = compile_files([], profile="twincat", texts={"main.st": src}, libraries=libs("Tc2_System"))
    engine = Engine(prog, [task("fast", 10, "A"), task("slow", 50, "B")], clock=VirtualClock())
    engine.start()
    try:
        engine.run(cycles=11)  # 0 .. 100 ms: B at 0, 50, 100
        assert (engine.get("A.idx"), engine.get("B.idx")) == (1, 2)
        assert (engine.get("B.cycles"), engine.get("B.name")) == (3, "slow")
    finally:
        engine.stop()


def test_the_bit_functions_of_the_documentation():
    # SETBIT32(0, 31) = 16#80000000; CSETBIT32(16#80000000, 15, TRUE) = 16#80008000;
    # "bitNo ... is internally converted to a modulo 32 value"
    src = """
    PROGRAM Main
    VAR a, b, c, d : DWORD; e, f : BOOL; END_VAR
    a := SETBIT32(0, 31);
    b := CSETBIT32(16#80000000, 15, TRUE);
    c := CLEARBIT32(16#FFFF, 33);
    d := CSETBIT32(inVal32 := 16#80008000, bitNo := 31, bitVal := FALSE);
    e := GETBIT32(16#10, 4);
    f := GETBIT32(16#10, 5);
    END_PROGRAM
    """
    r = run(src, "Tc2_System")
    assert [r.get(n) for n in "abcdef"] == [0x80000000, 0x80008000, 0xFFFD, 0x8000, True, False]


def test_hresult_succeeded_and_failed():
    src = """
    PROGRAM Main VAR hr : HRESULT := -2147467259; a, b, c : BOOL; END_VAR
    a := FAILED(hr); b := SUCCEEDED(S_OK); c := SUCCEEDED(hr);
    END_PROGRAM
    """
    r = run(src, "Tc2_System")
    assert (r.get("a"), r.get("b"), r.get("c")) == (True, True, False)


def test_adslog_writes_into_softplc_log_with_the_message_type(caplog):
    # ADSLOGSTR: the format string's %s takes strArg; "0 if successful"
    src = """
    PROGRAM Main VAR r1, r2, r3 : DINT; END_VAR
    r1 := ADSLOGSTR(ADSLOG_MSGTYPE_WARN, 'valve %s stuck', 'V12');
    r2 := ADSLOGDINT(msgCtrlMask := ADSLOG_MSGTYPE_ERROR OR ADSLOG_MSGTYPE_LOG, msgFmtStr := 'code %d', dintArg := -7);
    r3 := ADSLOGLREAL(ADSLOG_MSGTYPE_HINT, 'T = %f', 21.5);
    END_PROGRAM
    """
    with caplog.at_level(logging.INFO, logger="softplc.plc"):
        r = run(src, "Tc2_System")
    got = [(rec.levelname, rec.getMessage()) for rec in caplog.records if rec.name == "softplc.plc"]
    assert got == [("WARNING", "valve V12 stuck"), ("ERROR", "code -7"), ("INFO", "T = 21.500000")]
    assert (r.get("r1"), r.get("r2"), r.get("r3")) == (0, 0, 0)


def test_testandset_blocks_the_second_taker_and_the_critical_section_opens():
    # TestAndSet: FALSE -> set and TRUE; already TRUE -> FALSE
    src = """
    PROGRAM Main VAR flag : BOOL; first, second : BOOL; cs : FB_IecCriticalSection; entered, left : BOOL; END_VAR
    first := TestAndSet(flag);
    second := TestAndSet(flag);
    entered := cs.Enter();
    left := cs.Leave();
    END_PROGRAM
    """
    r = run(src, "Tc2_System")
    assert [r.get(n) for n in ("first", "second", "flag", "entered", "left")] == [True, False, True, True, True]


def test_drand_repeats_its_series_for_a_seed():
    # DRAND: "a deterministically reproducible random number series ... identical Seed value"
    src = """
    PROGRAM Main
    VAR r1, r2, r3 : DRAND; a, b, c : ARRAY[1..5] OF LREAL; i : INT; END_VAR
    FOR i := 1 TO 5 DO
        r1(Seed := 7); a[i] := r1.Num;
        r2(Seed := 7); b[i] := r2.Num;
        r3(Seed := 8); c[i] := r3.Num;
    END_FOR
    END_PROGRAM
    """
    r = run(src, "Tc2_System")
    a, b, c = r.get("a"), r.get("b"), r.get("c")
    assert a == b and a != c and len(set(a)) == 5
    assert all(0.0 <= x < 1.0 for x in a + c)


def test_ads_blocks_answer_target_port_not_found_and_warn_once():
    # ADSREAD: ERR "is set once the BUSY output was reset"; ADS Return Codes: 6 target port not found
    src = """
    PROGRAM Main
    VAR rd, rd2 : ADSREAD; wr : ADSWRITE; buf : ARRAY[0..3] OF BYTE; n : INT; busy, err : BOOL; id : UDINT; END_VAR
    n := n + 1;
    rd(NETID := '', PORT := 851, IDXGRP := 16#4020, IDXOFFS := 0, LEN := SIZEOF(buf), DESTADDR := ADR(buf),
       READ := n >= 2, BUSY => busy, ERR => err, ERRID => id);
    wr(WRITE := FALSE);
    END_PROGRAM
    """
    diags = check(src, "Tc2_System")
    assert [(c, m.split(":")[0]) for c, _line, m in diags] == [
        ("W230", "Tc2_System ADSREAD, ADSWRITE are declared but not available here")
    ]
    r = run(src, "Tc2_System", cycles=1)
    assert (r.get("busy"), r.get("err"), r.get("id")) == (False, False, 0)  # no request yet
    r.run(2)
    assert (r.get("busy"), r.get("err"), r.get("id")) == (False, True, 6)


def test_file_blocks_answer_an_error_and_write_nothing():
    src = """
    PROGRAM Main
    VAR fo : FB_FileOpen; h : UINT; END_VAR
    fo(sNetId := '', sPathName := 'C:\\data.txt', nMode := FOPEN_MODEWRITE OR FOPEN_MODETEXT, ePath := PATH_GENERIC,
       bExecute := TRUE);
    h := fo.hFile;
    END_PROGRAM
    """
    [(code, _line, message)] = check(src, "Tc2_System")
    assert code == "W230" and message.startswith("Tc2_System FB_FileOpen is declared but not available here: softplc")
    r = run(src, "Tc2_System")
    assert (r.get("fo.bBusy"), r.get("fo.bError"), r.get("fo.nErrId"), r.get("h")) == (False, True, 6, 0)


def test_names_may_be_qualified_with_the_library():
    src = """
    PROGRAM Main VAR s : Tc2_System.T_MaxString; t : STRING(3) := 'abc'; n : UDINT; v : UINT; END_VAR
    n := Tc2_System.MEMCPY(ADR(s), ADR(t), 4);
    v := Tc2_System.F_GetVersionTcSystem(1);
    END_PROGRAM
    """
    r = run(src, "Tc2_System")
    assert (r.get("s"), r.get("n"), r.get("v")) == ("abc", 4, 3)
