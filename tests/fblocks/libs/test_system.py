"""CODESYS's system libraries: SysTime reading softplc's clock (in virtual
time the epoch plus the virtual clock), CAA Types, SysTypes/CmpErrors,
and SysFile/SysDir/SysSocket/SysCom declared, answering ERR_NOTIMPLEMENTED
as a runtime without the component does."""

from __future__ import annotations

from softplc.runtime.program import check_files

from .bench import chosen, runner, trace

ERR_NOTIMPLEMENTED = 0x000C  # CmpErrors


def test_systime_reads_the_task_clock_and_the_date_in_virtual_time():
    decls = "ms : UDINT; us : SYSTIME; hr : SYSTIME; sec : UDINT; res : RTS_IEC_RESULT := 99;"
    body = "ms := SysTimeGetMs(); SysTimeGetUs(ADR(us)); sec := SysTimeRtcGet(ADR(res)); SysTimeRtcHighResGet(ADR(hr));"
    r = runner(decls, body, "SysTime", cycle_ms=250)
    got = trace(r, 9, "ms", "us", "hr", "sec", "res")
    # the ninth cycle starts at 2 s: the date is 2000-01-01 00:00:02 UTC in
    # virtual time (946,684,800 s after 1970; the same date F_GetSystemTime reads)
    assert got[8] == (2000, 2_000_000, 946_684_802_000, 946_684_802, 0)


def test_systimertc_converts_dates_both_ways():
    decls = """d : SYSTIMEDATE; e : SYSTIMEDATE; back : UDINT; hr : SYSTIME; r1 : RTS_IEC_RESULT; r2 : RTS_IEC_RESULT;
        ms : SYSTIME := 951782400123; (* 2000-02-29 00:00:00.123 *)"""
    body = """r1 := SysTimeRtcConvertUtcToDate(1709164799, ADR(d));  (* 2024-02-28 23:59:59 *)
        r2 := SysTimeRtcConvertDateToUtc(ADR(d), ADR(back));
        SysTimeRtcConvertHighResToDate(ADR(ms), ADR(e)); SysTimeRtcConvertDateToHighRes(ADR(e), ADR(hr));"""
    r = runner(decls, body, "SysTime")
    r.run(1)
    fields = ("wYear", "wMonth", "wDay", "wHour", "wMinute", "wSecond", "wMilliseconds", "wDayOfWeek", "wYday")
    assert [r.get(f"d.{f}") for f in fields] == [2024, 2, 28, 23, 59, 59, 0, 3, 59]  # a Wednesday
    assert [r.get(f"e.{f}") for f in fields] == [2000, 2, 29, 0, 0, 0, 123, 2, 60]  # a Tuesday
    assert (r.get("back"), r.get("hr"), r.get("r1"), r.get("r2")) == (1709164799, 951782400123, 0, 0)


def test_systimertcset_is_refused():
    r = runner("res : RTS_IEC_RESULT;", "res := SysTimeRtcSet(0);", "SysTime")
    r.run(1)
    assert r.get("res") == ERR_NOTIMPLEMENTED


def test_caa_types_are_named_in_the_caa_namespace():
    decls = (
        "h : CAA.HANDLE := CAA.gc_hINVALID; s : CAA.SIZE; c : CAA.COUNT; e : CAA.ERROR; f : CAA.FILENAME; count : INT;"
    )
    body = "s := SIZEOF(h); c := c + 1; f := 'a/b.txt'; count := count + 2;"
    r = runner(decls, body, "CAA Types")
    r.run(2)
    assert (r.get("s"), r.get("c"), r.get("f"), r.get("count"), r.get("e")) == (8, 2, "a/b.txt", 4, 0)


SYSFILE = """h : SysFile.SysTypes.RTS_IEC_HANDLE; res : SysFile.SysTypes.RTS_IEC_RESULT; n : RTS_IEC_SIZE;
    mode : SysFile.ACCESS_MODE := SysFile.AM_APPEND_PLUS; buf : ARRAY[0..9] OF BYTE; closed : RTS_IEC_RESULT;
    failed : BOOL; settings : SysCom.SysComSettings; port : RTS_IEC_HANDLE; comRes : RTS_IEC_RESULT; got : UDINT;
    ping : RTS_IEC_RESULT;"""
SYSFILE_BODY = """h := SysFile.SysFileOpen(szFile := 'log.txt', am := mode, pResult := ADR(res));
    n := SysFile.SysFileRead(hFile := h, pbyBuffer := ADR(buf), ulSize := SIZEOF(buf), pResult := ADR(res));
    closed := SysFile.SysFileClose(hFile := h);
    failed := h = SysFile.SysTypes.RTS_INVALID_HANDLE AND res <> SysDir.CmpErrors.Errors.ERR_OK;
    settings.sPort := SysCom.SYS_COM_PORTS.SYS_COMPORT1; settings.ulBaudrate := 19200;
    settings.byParity := SysCom.SYS_COM_PARITY.SYS_EVENPARITY;
    port := SysCom.SysComOpen2(pSettings := ADR(settings), pSettingsEx := 0, pResult := ADR(comRes));
    got := SysCom.SysComRead(port, ADR(buf), SIZEOF(buf), 0, ADR(comRes));
    ping := SysSockPing(szIPAddress := '127.0.0.1', ulTimeout := 100, pulReplyTime := 0);"""


def test_sysfile_syscom_and_syssocket_answer_not_implemented():
    r = runner(SYSFILE, SYSFILE_BODY, "SysFile", "SysDir", "SysCom", "SysSocket")
    r.run(1)
    assert r.get("failed") is True and r.get("n") == 0 and r.get("got") == 0
    assert (r.get("res"), r.get("closed"), r.get("comRes"), r.get("ping")) == (ERR_NOTIMPLEMENTED,) * 4


def test_an_unavailable_system_library_warns_once_and_its_types_come_along():
    src = {"main.st": f"PROGRAM Main VAR {SYSFILE} END_VAR {SYSFILE_BODY} END_PROGRAM"}
    diags, _ = check_files([], texts=src, libraries=chosen("SysFile", "SysDir", "SysCom", "SysSocket"))
    warned = sorted(d.message.split(" ")[0] for d in diags if d.code == "W230")
    assert warned == ["SysCom", "SysFile", "SysSocket"] and not [d for d in diags if d.is_error]
    # SysDir only lends its namespace: no W230 for it; SysTypes2 Interfaces came with them


def test_byte_order_helpers_compute():
    r = runner("a : UINT; b : UDINT;", "a := SysSockHtons(16#1234); b := SysSockHtonl(16#12345678);", "SysSocket")
    r.run(1)
    assert (r.get("a"), r.get("b")) == (0x3412, 0x78563412)
