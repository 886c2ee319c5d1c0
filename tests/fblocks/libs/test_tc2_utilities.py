"""Tc2_Utilities (fblocks/libs/tc2_utilities): numbers as strings, string
helpers, byte order, checksums, FB_FormatString, the time conversions and
the engine's local time, time zones, FB_MemRingBuffer, and the blocks that
act on the computer. Values and examples from the Beckhoff Information
System pages "TwinCAT 3 PLC Lib: Tc2_Utilities" (DWORD_TO_HEXSTR, F_LTrim,
HOST_TO_BE16, F_BYTE_TO_CRC16_CCITT, HEXSTR_TO_DATA, DATA_TO_HEXSTR,
FB_FormatString with "Format specification" and "Format error codes",
FILETIME_TO_DT, F_GetDOYOfYearMonthDay, NT_GetTime, FB_MemRingBuffer)."""

from __future__ import annotations

from softplc.runtime.st.valuejson import encode_instance

from .conftest import check, run


def strings(body: str, decls: str = "", n: int = 8, cycles: int = 1) -> list:
    src = f"PROGRAM Main\nVAR s : ARRAY[0..{n - 1}] OF STRING(255); {decls} END_VAR\n{body}\nEND_PROGRAM\n"
    return run(src, "Tc2_Utilities", cycles=cycles).get("s")


def test_numbers_as_hex_binary_octal_and_decimal_strings():
    # DWORD_TO_HEXSTR: the documentation's four examples, then the other bases
    got = strings(
        """
        s[0] := DWORD_TO_HEXSTR(43981, 1, FALSE);
        s[1] := DWORD_TO_HEXSTR(43981, 1, TRUE);
        s[2] := DWORD_TO_HEXSTR(15, 4, FALSE);
        s[3] := DWORD_TO_HEXSTR(0, 0, FALSE);
        s[4] := BYTE_TO_HEXSTR(in := 16#0F, iPrecision := 2);     (* bLoCase := FALSE by default *)
        s[5] := BYTE_TO_BINSTR(5, 8);
        s[6] := WORD_TO_OCTSTR(8, 0);
        s[7] := DWORD_TO_DECSTR(42, 5);
        """
    )
    assert got == ["ABCD", "abcd", "000F", "", "0F", "00000101", "10", "00042"]


def test_the_string_helpers():
    # F_LTrim(' <trim ') = '<trim ' ... F_LTrim('') = ''
    got = strings(
        """
        s[0] := F_LTrim(' <trim ');
        s[1] := F_LTrim('<trim');
        s[2] := F_LTrim('');
        s[3] := F_RTrim(in := ' trim> ');
        s[4] := F_ToUCase('Motor 3 ab');
        s[5] := F_ToLCase('Motor 3 AB');
        s[6] := F_ToCHR(66);
        s[7] := LREAL_TO_FMTSTR(-2.5678, 2, FALSE);
        """,
        "a : BYTE;",
    )
    assert got == ["<trim ", "<trim", "", " trim>", "MOTOR 3 AB", "motor 3 ab", "B", "-2.56"]
    r = run(
        "PROGRAM Main VAR a : BYTE; s : STRING; END_VAR a := F_ToASC('A'); s := LREAL_TO_FMTSTR(3.14159, 2, TRUE); "
        "END_PROGRAM",
        "Tc2_Utilities",
    )
    assert (r.get("a"), r.get("s")) == (65, "3.14")


def test_byte_order_and_swapped_reals():
    src = """
    PROGRAM Main
    VAR a, b : WORD; c : DWORD; d : LWORD; u, v : T_ULARGE_INTEGER; f, g : REAL; ok : BOOL; END_VAR
    a := HOST_TO_BE16(16#1234);
    b := BE16_TO_HOST(a);
    c := HOST_TO_BE32(16#12345678);
    d := HOST_TO_BE64EX(16#0102030405060708);
    u.dwLowPart := 16#05060708; u.dwHighPart := 16#01020304;
    v := HOST_TO_BE64(u);
    f := 1.5; g := F_SwapReal(f);
    ok := F_SwapRealEx(g);
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities")
    assert (r.get("a"), r.get("b"), r.get("c"), r.get("d")) == (0x3412, 0x1234, 0x78563412, 0x0807060504030201)
    assert (r.get("v.dwLowPart"), r.get("v.dwHighPart")) == (0x04030201, 0x08070605)
    assert (r.get("g"), r.get("ok")) == (1.5, True)  # swapped twice


def test_crc16_ccitt_and_checksum_of_data():
    # polynomial 16#1021; '123456789' is the check string of CRC-16/CCITT:
    # initial 16#FFFF gives 16#29B1, initial 0 gives 16#31C3
    src = """
    PROGRAM Main
    VAR s : STRING := '123456789'; b : ARRAY[0..2] OF BYTE := [1, 2, 250];
        ffff, zero, chained, sum : WORD; i : INT; END_VAR
    ffff := F_DATA_TO_CRC16_CCITT(ADR(s), LEN(s), 16#FFFF);
    zero := F_DATA_TO_CRC16_CCITT(pData := ADR(s), cbData := 9, crc := 0);
    chained := 16#FFFF;
    FOR i := 1 TO 9 DO chained := F_BYTE_TO_CRC16_CCITT(INT_TO_BYTE(48 + i), chained); END_FOR
    sum := F_CheckSum16(ADR(b), 3, 16#FFFF);
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities")
    assert (r.get("ffff"), r.get("zero"), r.get("chained")) == (0x29B1, 0x31C3, 0x29B1)
    assert r.get("sum") == (0xFFFF + 253) & 0xFFFF


def test_hex_strings_to_data_and_back():
    # HEXSTR_TO_DATA('AB CD EF 01 23 45 67 89', ADR(data), SIZEOF(data)); "only spaces may be
    # used as separators ... an illegal character ... a zero length"; DATA_TO_HEXSTR: "a dot
    # ('.') is added" beyond 85 bytes
    src = """
    PROGRAM Main
    VAR sH : STRING := 'AB CD EF 01 23 45 67 89'; data : ARRAY[0..10] OF BYTE; big : ARRAY[0..99] OF BYTE;
        n, bad : UDINT; back, lower, dotted : T_MaxString; END_VAR
    n := HEXSTR_TO_DATA(sH, ADR(data), SIZEOF(data));
    bad := HEXSTR_TO_DATA('AB-CD', ADR(data), SIZEOF(data));
    back := DATA_TO_HEXSTR(ADR(data), 4, FALSE);
    lower := DATA_TO_HEXSTR(pData := ADR(data), cbData := 2, bLoCase := TRUE);
    dotted := DATA_TO_HEXSTR(ADR(big), SIZEOF(big), FALSE);
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities")
    assert (r.get("n"), r.get("bad")) == (8, 0)
    assert r.get("data")[:9] == [0xAB, 0xCD, 0xEF, 0x01, 0x23, 0x45, 0x67, 0x89, 0]
    assert (r.get("back"), r.get("lower")) == ("AB CD EF 01", "ab cd")
    assert r.get("dotted") == " ".join(["00"] * 85) + "."


def test_fb_formatstring_formats_as_fprintf():
    # 'Measure X: %+.10d, Y: %+.10d' and '%+20.5f' are the documentation's formats
    src = """
    PROGRAM Main
    VAR f1, f2, f3 : FB_FormatString; iX : DINT := 1; iY : DINT := -2; r : LREAL := 3.14159; i : INT := -1;
        w : WORD := 16#BEEF; sName : STRING := 'pump'; END_VAR
    f1(sFormat := 'Measure X: %+.10d, Y: %+.10d', arg1 := F_DINT(iX), arg2 := F_DINT(iY));
    f2(sFormat := '%+20.5f|%-6s|%x|%#X|%o|%b|100%%', arg1 := F_LREAL(r), arg2 := F_STRING(sName), arg3 := F_INT(i),
       arg4 := F_WORD(w), arg5 := F_BYTE(8), arg6 := F_BYTE(5));
    f3(sFormat := '%*.*f', arg1 := F_INT(8), arg2 := F_INT(2), arg3 := F_REAL(2.5));
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities")
    assert (r.get("f1.sOut"), r.get("f1.bError")) == ("Measure X: +0000000001, Y: -0000000002", False)
    assert r.get("f2.sOut") == "            +3.14159|pump  |ffff|0XBEEF|10|101|100%"
    assert r.get("f3.sOut") == "    2.50"


def test_fb_formatstring_answers_the_format_error_codes():
    # "Format error codes": 16#800 + n unsupported type, 16#1000 + n type and argument differ,
    # 16#4000 + n more arguments in the format than given
    src = """
    PROGRAM Main
    VAR f1, f2, f3 : FB_FormatString; s : STRING := 'x'; n : DINT := 3; END_VAR
    f1(sFormat := 'a %y', arg1 := F_DINT(n));
    f2(sFormat := 'a %d', arg1 := F_STRING(s));
    f3(sFormat := '%d %d', arg1 := F_DINT(n));
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities")
    got = [(r.get(f"f{k}.bError"), r.get(f"f{k}.nErrId"), r.get(f"f{k}.sOut")) for k in (1, 2, 3)]
    assert got == [(True, 0x801, ""), (True, 0x1001, ""), (True, 0x4002, "")]


def test_time_conversions_between_dt_timestruct_filetime_and_string():
    src = """
    PROGRAM Main
    VAR d : DT := DT#2020-02-29-12:34:56; t, t2 : TIMESTRUCT; ft, zero : T_FILETIME; d2, d0 : DT;
        s : STRING(24); END_VAR
    t := DT_TO_SYSTEMTIME(d);
    t.wMilliseconds := 789;
    ft := SYSTEMTIME_TO_FILETIME(t);
    d2 := FILETIME_TO_DT(ft);          (* milliseconds dropped *)
    d0 := FILETIME_TO_DT(zero);        (* limited to DT#1970-01-01-00:00:00 *)
    s := SYSTEMTIME_TO_STRING(FILETIME_TO_SYSTEMTIME(ft));
    t2 := STRING_TO_SYSTEMTIME(s);
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities")
    assert encode_instance(r.get("t")) == {
        "wYear": 2020, "wMonth": 2, "wDayOfWeek": 6, "wDay": 29,
        "wHour": 12, "wMinute": 34, "wSecond": 56, "wMilliseconds": 789,
    }  # fmt: skip
    assert (r.get("d2"), r.get("d0")) == (r.get("d"), 0)
    assert r.get("s") == "2020-02-29-12:34:56.789"
    assert encode_instance(r.get("t2")) == encode_instance(r.get("t"))
    assert (
        r.get("ft.dwHighDateTime") * 2**32 + r.get("ft.dwLowDateTime") == 132274532967890000
    )  # (2020-02-29 12:34:56.789 - 1601-01-01) in 100 ns


def test_calendar_functions():
    # F_GetDOYOfYearMonthDay(2009, 1, 31) = 31, (2009, 2, 1) = 32, (2009, 3, 1) = 60; 0: wrong parameters
    src = """
    PROGRAM Main VAR a, b, c, d : WORD; l1, l2, l3 : BOOL; END_VAR
    a := F_GetDOYOfYearMonthDay(2009, 1, 31); b := F_GetDOYOfYearMonthDay(2009, 2, 1);
    c := F_GetDOYOfYearMonthDay(2009, 3, 1); d := F_GetDOYOfYearMonthDay(2009, 2, 29);
    l1 := F_YearIsLeapYear(2000); l2 := F_YearIsLeapYear(1900); l3 := F_YearIsLeapYear(2024);
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities")
    assert [r.get(n) for n in ("a", "b", "c", "d", "l1", "l2", "l3")] == [31, 32, 60, 0, True, False, True]


def test_the_local_time_is_the_engine_clock_in_utc_in_virtual_time():
    src = """
    PROGRAM Main
    VAR nt : NT_GetTime; lt : FB_LocalSystemTime; tz : FB_GetTimeZoneInformation; n : INT; END_VAR
    n := n + 1;
    nt(NETID := '', START := n = 3);
    lt(bEnable := TRUE, dwCycle := 1);
    tz(bExecute := TRUE);
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities", cycles=4, cycle_time_ms=1500)
    # virtual time starts on 2000-01-01 (a Saturday); cycle 3 starts at 3 s, cycle 4 at 4.5 s
    assert encode_instance(r.get("nt.TIMESTR")) == {
        "wYear": 2000, "wMonth": 1, "wDayOfWeek": 6, "wDay": 1,
        "wHour": 0, "wMinute": 0, "wSecond": 3, "wMilliseconds": 0,
    }  # fmt: skip
    assert (r.get("nt.BUSY"), r.get("nt.ERR"), r.get("lt.bValid")) == (False, False, True)
    assert (r.get("lt.systemTime.wSecond"), r.get("lt.systemTime.wMilliseconds")) == (4, 500)
    assert (r.get("tz.tzInfo.bias"), r.get("tz.bError")) == (0, False)


CET = """
tz.bias := -60; tz.standardBias := 0; tz.daylightBias := -60;
tz.standardDate.wMonth := 10; tz.standardDate.wDay := 5; tz.standardDate.wDayOfWeek := 0; tz.standardDate.wHour := 3;
tz.daylightDate.wMonth := 3; tz.daylightDate.wDay := 5; tz.daylightDate.wDayOfWeek := 0; tz.daylightDate.wHour := 2;
"""


def test_local_time_to_utc_and_back_under_a_zone_with_daylight_time():
    # Central European time: UTC+1, daylight time UTC+2 from the last Sunday of March 2:00
    # to the last Sunday of October 3:00 (Windows' TIME_ZONE_INFORMATION rules)
    src = f"""
    PROGRAM Main
    VAR tz : ST_TimeZoneInformation; toUtc : FB_TzSpecificLocalTimeToSystemTime;
        toLocal : FB_SystemTimeToTzSpecificLocalTime; summer, winter, t : TIMESTRUCT; h1, h2, h3 : WORD; END_VAR
    {CET}
    summer.wYear := 2021; summer.wMonth := 7; summer.wDay := 1; summer.wHour := 12;
    winter.wYear := 2021; winter.wMonth := 1; winter.wDay := 15; winter.wHour := 12;
    toUtc(in := summer, tzInfo := tz); h1 := toUtc.out.wHour;
    toLocal(in := toUtc.out, tzInfo := tz); h3 := toLocal.out.wHour;
    toUtc(in := winter, tzInfo := tz); h2 := toUtc.out.wHour;
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities")
    assert (r.get("h1"), r.get("h2"), r.get("h3")) == (10, 11, 12)
    assert (r.get("toUtc.eTzID"), r.get("toLocal.eTzID")) == (1, 2)  # eTimeZoneID_Standard, _Daylight


def test_ams_net_ids_and_ipv4_addresses():
    src = """
    PROGRAM Main
    VAR ids : T_AmsNetIdArr := [5, 12, 34, 56, 1, 1]; s : T_AmsNetId; back, bad : T_AmsNetIdArr;
        ip : T_IPv4Addr; ipa : T_IPv4AddrArr; END_VAR
    s := F_CreateAmsNetId(ids);
    back := F_ScanAmsNetIds(s);
    bad := F_ScanAmsNetIds('5.12.x.56.1.1');
    ipa := F_ScanIPv4Addr('192.168.1.20');
    ip := F_CreateIPv4Addr(ipa);
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities")
    assert (r.get("s"), r.get("back"), r.get("bad")) == ("5.12.34.56.1.1", [5, 12, 34, 56, 1, 1], [0] * 6)
    assert (r.get("ipa"), r.get("ip")) == ([192, 168, 1, 20], "192.168.1.20")


def test_mem_ring_buffer_keeps_records_first_in_first_out():
    # TcUnit's use: records of a structure, each taking its size and 4 bytes more
    src = """
    TYPE ST_Msg : STRUCT code : DINT; text : STRING(11); END_STRUCT END_TYPE
    PROGRAM Main
    VAR rb : FB_MemRingBuffer; buf : ARRAY[0..49] OF BYTE; m, got : ST_Msg; i : INT;
        order : ARRAY[1..9] OF DINT; k : INT; full : BOOL; counts : ARRAY[1..2] OF UDINT; END_VAR
    FOR i := 1 TO 9 DO                        (* 2 records fit (2 x 20 bytes): add, add, remove, ... *)
        m.code := i; m.text := CONCAT('msg ', INT_TO_STRING(i));
        rb.A_AddTail(pWrite := ADR(m), cbWrite := SIZEOF(m), pBuffer := ADR(buf), cbBuffer := SIZEOF(buf));
        IF i = 2 THEN
            counts[1] := rb.nCount;
            rb.A_AddTail(pWrite := ADR(m), cbWrite := SIZEOF(m), pBuffer := ADR(buf), cbBuffer := SIZEOF(buf));
            full := NOT rb.bOk;
        END_IF
        IF i >= 2 THEN
            rb.A_RemoveHead(pRead := ADR(got), cbRead := SIZEOF(got), pBuffer := ADR(buf), cbBuffer := SIZEOF(buf));
            k := k + 1; order[k] := got.code;
        END_IF
    END_FOR
    counts[2] := rb.nCount;
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities")
    assert r.get("order")[:8] == [1, 2, 3, 4, 5, 6, 7, 8]  # through the wrap-around of 50 bytes
    assert (r.get("full"), r.get("counts"), r.get("rb.cbSize"), r.get("got.text")) == (True, [2, 1], 20, "msg 8")


def test_mem_ring_buffer_refuses_a_read_too_small_and_tells_the_size():
    src = """
    PROGRAM Main
    VAR rb : FB_MemRingBuffer; buf : ARRAY[0..31] OF BYTE; v : LREAL := 1.25; small : DINT; ok : BOOL;
        size, left : UDINT; END_VAR
    rb.A_AddTail(pWrite := ADR(v), cbWrite := SIZEOF(v), pBuffer := ADR(buf), cbBuffer := SIZEOF(buf));
    rb.A_RemoveHead(pRead := ADR(small), cbRead := SIZEOF(small), pBuffer := ADR(buf), cbBuffer := SIZEOF(buf));
    ok := rb.bOk; size := rb.cbReturn; left := rb.nCount;
    rb.A_Reset();
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities")
    assert (r.get("ok"), r.get("size"), r.get("left"), r.get("rb.nCount")) == (False, 8, 1, 0)


def test_blocks_that_act_on_the_computer_answer_an_ads_error_and_warn():
    src = """
    PROGRAM Main VAR sd : NT_Shutdown; hn : FB_GetHostName; END_VAR
    sd(NETID := '', DELAY := 0, START := TRUE);
    hn(bExecute := TRUE);
    END_PROGRAM
    """
    [(code, _line, message)] = check(src, "Tc2_Utilities")
    assert code == "W230" and message.startswith("Tc2_Utilities FB_GetHostName, NT_Shutdown are declared but not")
    r = run(src, "Tc2_Utilities")
    assert (r.get("sd.BUSY"), r.get("sd.ERR"), r.get("sd.ERRID")) == (False, True, 6)
    assert (r.get("hn.bBusy"), r.get("hn.bError"), r.get("hn.nErrId"), r.get("hn.sHostName")) == (False, True, 6, "")


def test_tc2_utilities_brings_the_tc2_system_it_uses():
    src = """
    PROGRAM Main VAR s : T_MaxString; n : UDINT; v : UINT; END_VAR
    n := MEMCPY(ADR(s), ADR(s), 1); v := F_GetVersionTcUtilities(1);
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities")
    assert (r.get("n"), r.get("v")) == (1, 3)


def test_lreal_to_fmtstr_rounds_half_up_and_names_what_has_no_digits():
    # LREAL_TO_FMTSTR: "0.46523 ... two decimal places and rounded ... '0.47'"; "If in = 0 and
    # iPrecision = 0 then string '0'"; '#INF', '-#INF', '#QNAN'; '#OVF' beyond its STRING(510)
    got = strings(
        """
        s[0] := LREAL_TO_FMTSTR(0.46523, 2, TRUE);
        s[1] := LREAL_TO_FMTSTR(0.46523, 2, FALSE);
        s[2] := LREAL_TO_FMTSTR(0.0, 0, FALSE);
        s[3] := LREAL_TO_FMTSTR(2.5, 0, TRUE);
        s[4] := LREAL_TO_FMTSTR(-1.0 / z, 3, TRUE);
        s[5] := LREAL_TO_FMTSTR(z / z, 3, TRUE);
        s[6] := LREAL_TO_FMTSTR(1.0E300, 300, FALSE);
        s[7] := LREAL_TO_FMTSTR(-12.5, 3, FALSE);
        """,
        "z : LREAL := 0.0;",
    )
    assert got == ["0.47", "0.46", "0", "3", "-#INF", "#QNAN", "#OVF", "-12.500"]
    r = run(
        "PROGRAM Main VAR s : STRING(510); n : INT; END_VAR s := LREAL_TO_FMTSTR(1.0E300, 2, TRUE); n := LEN(s); "
        "END_PROGRAM",
        "Tc2_Utilities",
    )
    # 15 significant digits, then zeros: 301 digits before the point
    assert (r.get("n"), r.get("s")[:16], set(r.get("s")[15:301])) == (304, "1000000000000000", {"0"})


def test_len2_counts_the_characters_a_pointer_to_string_points_to():
    # LEN2(pSTRING : POINTER TO STRING) : UDINT, "the number of characters in a string"
    src = """
    PROGRAM Main
    VAR big : STRING(400); short : STRING := 'motor'; p : POINTER TO STRING; a, b, c : UDINT; i : INT; END_VAR
    FOR i := 1 TO 30 DO big := CONCAT(big, '0123456789'); END_FOR
    p := ADR(big);
    a := LEN2(p);
    b := LEN2(ADR(short));
    c := LEN2(0);
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities")
    assert (r.get("a"), r.get("b"), r.get("c")) == (300, 5, 0)


def test_guids_as_strings_and_back():
    # GUID_TO_STRING: 'xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx' "without curly brackets", the zero
    # GUID as '00000000-0000-0000-0000-000000000000'; STRING_TO_GUID: zeros when it fails
    src = """
    PROGRAM Main
    VAR g, zero, back, bad : GUID; s, z : STRING(36); END_VAR
    g.Data1 := 16#C200E360; g.Data2 := 16#38C5; g.Data3 := 16#11CE;
    g.Data4[0] := 16#AE; g.Data4[1] := 16#62; g.Data4[2] := 16#08; g.Data4[3] := 16#00;
    g.Data4[4] := 16#2B; g.Data4[5] := 16#2B; g.Data4[6] := 16#79; g.Data4[7] := 16#EF;
    s := GUID_TO_STRING(g);
    z := GUID_TO_STRING(zero);
    back := STRING_TO_GUID('c200e360-38c5-11ce-ae62-08002b2b79ef');
    bad := STRING_TO_GUID('{c200e360-38c5-11ce-ae62-08002b2b79ef}');
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities")
    assert (r.get("s"), r.get("z")) == ("C200E360-38C5-11CE-AE62-08002B2B79EF", "00000000-0000-0000-0000-000000000000")
    assert encode_instance(r.get("back")) == encode_instance(r.get("g"))
    assert encode_instance(r.get("bad")) == encode_instance(r.get("zero"))


def test_days_and_weeks_of_the_calendar():
    # F_GetDayOfMonthEx: "the second Monday in August 2011 ... 8"; wWOM 5 "the last week";
    # F_GetWeekOfTheYear(DT#2008-03-17-12:00) = 12; 2021-01-01 (a Friday) is in week 53 of 2020,
    # 2019-12-30 (a Monday) in week 1 of 2020
    src = """
    PROGRAM Main VAR a, b, c, w1, w2, w3, d1, d2 : WORD; END_VAR
    a := F_GetDayOfMonthEx(2011, 8, 2, 1);
    b := F_GetDayOfMonthEx(wYear := 2021, wMonth := 3, wWOM := 5, wDOW := 0);
    c := F_GetDayOfMonthEx(2011, 13, 1, 1);
    w1 := F_GetWeekOfTheYear(DT#2008-03-17-12:00);
    w2 := F_GetWeekOfTheYear(DT#2021-01-01-00:00);
    w3 := F_GetWeekOfTheYear(DT#2019-12-30-00:00);
    d1 := F_GetDayOfWeek(DT#2008-03-17-12:00);
    d2 := F_GetDayOfWeek(DT#2000-01-01-00:00);
    END_PROGRAM
    """
    r = run(src, "Tc2_Utilities")
    got = [r.get(n) for n in ("a", "b", "c", "w1", "w2", "w3", "d1", "d2")]
    assert got == [8, 28, 0, 12, 53, 1, 1, 6]  # last Sunday of March 2021: the 28th; Monday 1, Saturday 6
