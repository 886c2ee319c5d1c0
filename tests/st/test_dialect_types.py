"""Dialect rules of types met in real CODESYS and TwinCAT code (issue 30):
what each profile takes, seen from a program a user compiles and runs."""

from __future__ import annotations

import pytest

from .conftest import codes, diagnostics, run_st

QUALIFIED_DEFAULT = """
{attribute 'qualified_only'}
{attribute 'strict'}
TYPE E_Mode :
(
    NONE := 0,
    AUTO := 1,
    MANUAL := 2
) := MANUAL;
END_TYPE
{attribute 'qualified_only'}
TYPE E_State : (IDLE, RUN, STOPPED) INT := RUN;
END_TYPE
PROGRAM main
VAR
    m : E_Mode;
    s : E_State;
    isManual, isRunning : BOOL;
END_VAR
isManual := m = E_Mode.MANUAL;
isRunning := s = E_State.RUN;
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_a_qualified_only_enumeration_names_its_default_bare_in_its_type(profile):
    # TwinCAT's DUT editor writes `) := NONE;` under {attribute 'qualified_only'}
    r = run_st(QUALIFIED_DEFAULT, profile=profile)
    assert (r.get("isManual"), r.get("isRunning")) == (True, True)


def test_elsewhere_its_values_stay_qualified():
    assert codes(QUALIFIED_DEFAULT.replace("m = E_Mode.MANUAL", "m = MANUAL")) == ["E018"]


BITS = """
TYPE ST_Status :
STRUCT
    bReady : BIT;
    bBusy : BIT;
    bError : BIT;
    nCode : INT;
    b0, b1, b2, b3, b4, b5, b6, b7, b8 : BIT;
END_STRUCT
END_TYPE
PROGRAM main
VAR
    s, copy : ST_Status;
    size : UDINT;
    pb, pc : POINTER TO BYTE;
    flags, code, packed8, ninth : BYTE;
    i : INT;
END_VAR
s.bReady := TRUE;
s.bError := TRUE;
s.nCode := 258;
s.b0 := TRUE;
s.b7 := TRUE;
s.b8 := TRUE;
size := SIZEOF(s);
pb := ADR(s);
flags := pb^;
pb := ADR(s) + 2;
code := pb^;
pb := ADR(s) + 4;
packed8 := pb^;
pb := ADR(s) + 5;
ninth := pb^;
FOR i := 0 TO 5 DO
    pb := ADR(s) + i;
    pc := ADR(copy) + i;
    pc^ := pb^;
END_FOR
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_bit_fields_of_a_struct_share_bytes(profile):
    # CODESYS "Data type: BIT": consecutive BIT fields are packed eight to a
    # byte, the first in bit 0: bReady, bBusy, bError in byte 0, nCode at 2,
    # b0..b7 in byte 4, b8 alone in byte 5; the whole rounded up to INT's 2
    r = run_st(BITS, profile=profile)
    assert r.get("size") == 6
    assert (r.get("flags"), r.get("code"), r.get("packed8"), r.get("ninth")) == (0b101, 2, 0b1000_0001, 1)
    # a byte-wise copy (as MEMCPY makes it) carries every bit over
    assert [r.get(f"copy.{f}") for f in ("bReady", "bBusy", "bError", "nCode", "b0", "b6", "b7", "b8")] == [
        True,
        False,
        True,
        258,
        True,
        False,
        True,
        True,
    ]


def test_a_bit_is_a_bool_in_expressions():
    src = """
FUNCTION_BLOCK FB_Flags
VAR_INPUT
    set : BOOL;
END_VAR
VAR
    flag : BIT;
END_VAR
VAR_OUTPUT
    q : BOOL;
END_VAR
flag := set OR flag;
q := flag AND TRUE;
END_FUNCTION_BLOCK
PROGRAM main
VAR
    f : FB_Flags;
    q : BOOL;
END_VAR
f(set := TRUE);
f(set := FALSE, q => q);
END_PROGRAM
"""
    assert run_st(src).get("q") is True


@pytest.mark.parametrize("profile", ["iec", "matiec", "schneider"])
def test_bit_is_codesys_only(profile):
    ds = [d for d in diagnostics(BITS, profile) if d.code == "E012"]
    assert len(ds) == 12 and ds[0].message == "BIT is a CODESYS type"


EXTENDED = """
TYPE ST_Base :
STRUCT
    id : INT := 3;
    name : STRING(10);
END_STRUCT
END_TYPE
TYPE ST_Switch EXTENDS ST_Base :
STRUCT
    on : BOOL;
    level : DINT;
END_STRUCT
END_TYPE
FUNCTION Fill : BOOL
VAR_INPUT
    pBase : POINTER TO ST_Base;
    id : INT;
END_VAR
pBase^.id := pBase^.id + id;
pBase^.name := 'sw';
Fill := TRUE;
END_FUNCTION
PROGRAM main
VAR
    sw : ST_Switch;
    ok : BOOL;
    size : UDINT;
END_VAR
ok := Fill(pBase := ADR(sw), id := 7);
sw.level := 1000;
size := SIZEOF(sw);
END_PROGRAM
"""


def test_a_struct_extends_another_and_stands_for_it():
    # CODESYS "Extension of a structure": ST_Switch has ST_Base's fields
    # first, and a POINTER TO ST_Base takes it (a CODESYS export fills the
    # common fields of its messages so)
    r = run_st(EXTENDED)
    assert (r.get("ok"), r.get("sw.id"), r.get("sw.name"), r.get("sw.level")) == (True, 10, "sw", 1000)
    # id INT at 0, name STRING(10) 2..12, on BOOL 13, level DINT 16..19: CODESYS's layout
    assert r.get("size") == 20


def test_a_struct_that_does_not_extend_the_base_is_refused():
    assert "E020" in codes(EXTENDED.replace("TYPE ST_Switch EXTENDS ST_Base :", "TYPE ST_Switch :"))
    cycle = EXTENDED.replace("TYPE ST_Base :", "TYPE ST_Base EXTENDS ST_Switch :")
    assert "E012" in codes(cycle)


DERIVED = """
TYPE ST_Base :
STRUCT
    id : INT;
    name : STRING(10);
END_STRUCT
END_TYPE
TYPE ST_Switch EXTENDS ST_Base :
STRUCT
    on : BOOL;
    level : DINT;
END_STRUCT
END_TYPE
FUNCTION_BLOCK FB_Publisher
METHOD FillCommon : BOOL
VAR_INPUT
    pBase : POINTER TO ST_Base;
    id : INT;
END_VAR
pBase^.id := id;
pBase^.name := 'sw';
FillCommon := TRUE;
END_METHOD
METHOD Checksum : UDINT
VAR_INPUT
    pStruct : POINTER TO BYTE;
    size : UDINT;
END_VAR
VAR
    i : UDINT;
END_VAR
FOR i := 0 TO size - 1 DO
    Checksum := Checksum + pStruct[i];
END_FOR
pStruct[0] := 99;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM main
VAR
    fb : FB_Publisher;
    sw : ST_Switch;
    ok : BOOL;
    size, sum : UDINT;
    pInt : POINTER TO INT;
    ints : ARRAY[0..3] OF INT := [10, 20, 30, 40];
    third : INT;
END_VAR
ok := fb.FillCommon(pBase := ADR(sw), id := 7);
sw.level := 1000;
size := SIZEOF(sw);
sum := fb.Checksum(pStruct := ADR(sw), size := SIZEOF(sw));
pInt := ADR(ints);
third := pInt[2];
pInt[3] := pInt[1] + 1;
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_a_pointer_is_indexed_by_elements(profile):
    # a CODESYS export fills the common fields of several STRUCTs that EXTEND
    # one base through a POINTER TO the base, and sums a structure's bytes
    # through an indexed POINTER TO BYTE
    r = run_st(DERIVED, profile=profile)
    assert (r.get("ok"), r.get("sw.id"), r.get("sw.name"), r.get("sw.level")) == (True, 99, "sw", 1000)
    # id INT at 0, name STRING(10) 2..12, on BOOL 13, level DINT 16..19: CODESYS's layout
    assert r.get("size") == 20
    assert r.get("sum") == 7 + ord("s") + ord("w") + (1000 & 0xFF) + (1000 >> 8)
    assert (r.get("third"), r.get("ints")[3]) == (30, 21)  # p[i] counts elements, not bytes


@pytest.mark.parametrize("profile", ["iec", "matiec", "schneider"])
def test_indexing_a_pointer_is_codesys(profile):
    ds = [d for d in diagnostics(DERIVED, profile) if d.code == "E050"]
    assert len(ds) == 5
    assert ds[0].hint == "write (p + i)^ (the codesys and twincat profiles index a pointer)"


ADR_OF_LITERALS = """
FUNCTION StrEquals : BOOL
VAR_INPUT
    str1, str2 : POINTER TO STRING;
END_VAR
StrEquals := str1^ = str2^;
END_FUNCTION
FUNCTION ByteLen : INT
VAR_INPUT
    p : POINTER TO BYTE;
END_VAR
WHILE p[ByteLen] <> 0 DO
    ByteLen := ByteLen + 1;
END_WHILE
END_FUNCTION
PROGRAM main
VAR
    payload : STRING := 'STOP';
    stopped, opened : BOOL;
    n : INT;
    p : POINTER TO STRING;
    pInit : POINTER TO STRING := ADR('start');
    s, first : STRING;
    pw : POINTER TO WSTRING;
    w : WSTRING;
END_VAR
stopped := StrEquals(str1 := ADR(payload), str2 := ADR('STOP'));
opened := StrEquals(str1 := ADR(payload), str2 := ADR('OPEN'));
n := ByteLen(ADR('CLOSE'));
first := pInit^;
p := ADR('x');
p^ := 'y';
p := ADR('x');
s := p^;
pw := ADR("wide");
w := pw^;
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_adr_of_a_string_literal_points_at_its_text(profile):
    # codesys, twincat: ADR('TRUE') passed to a POINTER TO STRING input, as
    # a CODESYS project compares MQTT payloads; its bytes end with a 0 as a
    # STRING's do; a declaration may start with it. The pointer is to a copy
    # made each time ADR is evaluated: a write through it leaves the next
    # ADR('x') 'x' (CODESYS keeps one copy in memory; writing to a literal
    # is no use either way)
    r = run_st(ADR_OF_LITERALS, profile=profile)
    assert (r.get("stopped"), r.get("opened"), r.get("n")) == (True, False, 5)
    assert (r.get("first"), r.get("s"), r.get("w")) == ("start", "x", "wide")


@pytest.mark.parametrize("profile", ["iec", "matiec", "schneider"])
def test_elsewhere_adr_wants_a_variable(profile):
    # iec, matiec, schneider: E031, as ADR/REF of any expression
    found = diagnostics(ADR_OF_LITERALS, profile)
    assert sum(d.code == "E031" and "string literal" in d.message for d in found) == 7


ENUM_TO_STRING = """
{attribute 'qualified_only'}
{attribute 'strict'}
{attribute 'to_string'}
TYPE E_Sample :
(
    eInit := 0,
    eStart,
    eStop
);
END_TYPE
{attribute 'qualified_only'}
{attribute 'strict'}
TYPE E_Plain :
(
    eInit := 0,
    eStart,
    eStop
);
END_TYPE
{attribute 'to_string'}
TYPE COLOR : (red := 0, blue := 1, green := 2); END_TYPE
PROGRAM main
VAR
    eSample : E_Sample;
    ePlain : E_Plain;
    nCurrentValue, nPlain : INT;
    sCurrentValue, sComponent, sPlain, sPlainComponent, sUnnamed, s_show_color : STRING;
    wsCurrentValue, wsComponent : WSTRING;
    i_color, odd : COLOR;
END_VAR
nCurrentValue := TO_INT(eSample);
sCurrentValue := TO_STRING(eSample);
wsCurrentValue := TO_WSTRING(eSample);
sComponent := TO_STRING(E_Sample.eStart);
wsComponent := TO_WSTRING(E_Sample.eStop);
ePlain := E_Plain.eStop;
sPlain := TO_STRING(ePlain);
sPlainComponent := TO_STRING(E_Plain.eStart);
nPlain := TO_INT(ePlain);
i_color := 1;
s_show_color := TO_STRING(i_color);
odd := 7;
sUnnamed := TO_STRING(odd);
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_to_string_of_an_enumeration_gives_its_name_with_the_attribute(profile):
    # codesys, twincat: the documented examples. Beckhoff Infosys (TC3 PLC,
    # "TO_STRING/TO_WSTRING for enumeration variables", "Attribute
    # 'to_string'"): with {attribute 'to_string'} the component's name,
    # without it its number ('0', '1'); strict or not. CODESYS "Attribute:
    # to_string": i_color := 1 gives 'blue'. A value with no name (odd := 7):
    # its number, our choice (neither page says)
    r = run_st(ENUM_TO_STRING, profile=profile)
    assert [r.get(v) for v in ("nCurrentValue", "sCurrentValue", "wsCurrentValue")] == [0, "eInit", "eInit"]
    assert (r.get("sComponent"), r.get("wsComponent")) == ("eStart", "eStop")
    assert [r.get(v) for v in ("sPlain", "sPlainComponent", "nPlain")] == ["2", "1", 2]
    assert (r.get("s_show_color"), r.get("sUnnamed")) == ("blue", "7")


@pytest.mark.parametrize("profile", ["iec", "matiec", "schneider"])
def test_elsewhere_an_enumeration_converts_to_nothing(profile):
    # IEC 61131-3: an enumerated value is no number (E020 for each TO_*)
    found = [d for d in diagnostics(ENUM_TO_STRING, profile) if "TO_" in d.message]
    assert {d.code for d in found} == {"E020"} and len(found) == 10
