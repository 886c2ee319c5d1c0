"""JSON encoding of ST values (softplc exec output)."""

import json
import math

import pytest

from softplc.runtime.st import types as T
from softplc.runtime.st.valuejson import encode_instance, encode_value

# ---------------------------------------------------------------- single values


@pytest.mark.parametrize(
    "t, v, expected",
    [
        (T.BOOL, True, True),
        (T.BOOL, 0, False),
        (T.INT, -32768, -32768),
        (T.LWORD, (1 << 64) - 1, (1 << 64) - 1),  # exact, no float rounding
        (T.LREAL, 0.1, 0.1),
        (T.StringType(80), "héllo", "héllo"),
        (T.SubrangeType(T.INT, 0, 10), 7, 7),
    ],
)
def test_elementary(t, v, expected):
    got = encode_value(t, v)
    assert got == expected and type(got) is type(expected)


def test_real_shows_shortest_binary32_digits():
    stored = 0.10000000149011612  # REAL 0.1 as held after rounding to 32 bits
    assert encode_value(T.REAL, stored) == 0.1
    assert encode_value(T.REAL, 16777216.0) == 16777216.0
    assert encode_value(T.REAL, 3.4028234663852886e38) == 3.4028235e38
    assert encode_value(T.LREAL, stored) == stored  # LREAL keeps every digit


@pytest.mark.parametrize("t", [T.REAL, T.LREAL])
def test_non_finite_reals_are_strings(t):
    assert encode_value(t, math.inf) == "inf"
    assert encode_value(t, -math.inf) == "-inf"
    assert encode_value(t, math.nan) == "nan"


def test_enum_name_or_value():
    color = T.EnumType("Color", {"RED": 0, "GREEN": 5}, {"RED": "Red", "GREEN": "Green"})
    assert encode_value(color, 5) == "Green"
    assert encode_value(color, 3) == 3  # no enumerator has this value


def test_arrays_nest_per_dimension():
    one = T.ArrayType([(1, 3)], T.BOOL)
    assert encode_value(one, [1, 0, 1]) == [True, False, True]
    two = T.ArrayType([(0, 1), (1, 3)], T.INT)
    assert encode_value(two, [[1, 2, 3], [4, 5, 6]]) == [[1, 2, 3], [4, 5, 6]]
    of_arrays = T.ArrayType([(0, 1)], T.ArrayType([(0, 1)], T.REAL))
    assert encode_value(of_arrays, [[0.5, 1.5], [2.5, 3.5]]) == [[0.5, 1.5], [2.5, 3.5]]


def test_refs():
    ref = T.RefType(T.INT)
    assert encode_value(ref, None) is None
    assert encode_value(ref, object()) == "<ref>"


def test_alias_is_resolved():
    assert encode_value(T.AliasType("Speed", T.REAL), 0.25) == 0.25


def test_time_values_are_iec_literals():
    assert encode_value(T.TIME, 3_723_004) == "T#1h2m3s4ms"
    assert encode_value(T.DATE, 1704153600) == "D#2024-01-02"


def test_instance_skips_references_and_temporaries():
    class Fake:
        _VARS_ = (
            ("Speed", "speed", T.REAL, "VAR"),
            ("Cmd", "cmd", T.BOOL, "VAR_INPUT"),
            ("Done", "done", T.BOOL, "VAR_OUTPUT"),
            ("Data", "data", T.INT, "VAR_IN_OUT"),
            ("G", "g", T.INT, "VAR_EXTERNAL"),
            ("Tmp", "tmp", T.INT, "VAR_TEMP"),
        )
        speed, cmd, done, data, g, tmp = 1.5, True, False, 1, 2, 3

    assert encode_instance(Fake()) == {"Speed": 1.5, "Cmd": True, "Done": False}


# ---------------------------------------------------------------- compiled programs

PROGRAM = """
TYPE Mode : (Off, Manual, Auto := 10); END_TYPE
TYPE Point : STRUCT x : INT; y : INT; END_STRUCT END_TYPE

FUNCTION_BLOCK Axis
VAR_INPUT enable : BOOL; END_VAR
VAR_OUTPUT pos : Point; END_VAR
VAR_IN_OUT shared : INT; END_VAR
VAR_TEMP scratch : INT; END_VAR
IF enable THEN
    scratch := pos.x + 1;
    pos.x := scratch;
    shared := shared + 1;
END_IF
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    flag : BOOL := TRUE;
    small : SINT := 127;
    big : LWORD := 16#FFFF_FFFF_FFFF_FFFF;
    r : REAL := 0.1;
    lr : LREAL := 0.1;
    t : TIME := T#1h2m3s4ms;
    lt : LTIME := LTIME#1s;
    d : DATE := D#2024-01-02;
    tod1 : TOD := TOD#12:30:00;
    dt1 : DT := DT#2024-01-02-12:30:00;
    s : STRING := 'hi';
    m : Mode := Mode#Auto;
    row : ARRAY[1..3] OF INT := [1, 2, 3];
    grid : ARRAY[0..1, 0..2] OF BOOL;
    p : Point := (x := 1, y := 2);
    ax : Axis;
    counter : INT;
    nothing : REF_TO INT;
    something : REF_TO INT;
END_VAR
small := small + 1;                 (* wraps to -128 *)
grid[1, 2] := TRUE;
ax(enable := TRUE, shared := counter);
something := REF(counter);
END_PROGRAM
"""


@pytest.fixture(scope="module")
def dump():
    from softplc.runtime.program import compile_files

    prog = compile_files([], texts={"main.st": PROGRAM})
    runner = prog.runner("Main")
    runner.run(2)
    return encode_instance(runner.instance)


def test_program_dump(dump):
    json.dumps(dump)  # JSON-ready all the way down
    assert dump["flag"] is True
    assert dump["small"] == -127  # 127 +1 wraps to -128, +1 again
    assert dump["big"] == 0xFFFF_FFFF_FFFF_FFFF
    assert dump["r"] == 0.1 and dump["lr"] == 0.1
    assert dump["s"] == "hi"
    assert dump["m"] == "Auto"
    assert dump["row"] == [1, 2, 3]
    assert dump["grid"] == [[False, False, False], [False, False, True]]
    assert dump["p"] == {"x": 1, "y": 2}
    assert dump["counter"] == 2
    assert dump["nothing"] is None
    assert dump["something"] == "<ref>"


def test_program_dump_time_literals(dump):
    assert dump["t"] == "T#1h2m3s4ms"
    assert dump["lt"].upper().startswith("LTIME#") or dump["lt"].upper().startswith("LT#")
    assert dump["d"] == "D#2024-01-02"
    assert dump["tod1"].upper().startswith("TOD#12:30")
    assert dump["dt1"].upper().startswith("DT#2024-01-02-12:30")


def test_fb_dump_leaves_out_in_out_and_temp(dump):
    assert dump["ax"] == {"enable": True, "pos": {"x": 2, "y": 0}}


def test_an_interface_variable_dumps_as_a_reference():
    """An INTERFACE variable designates an instance (CODESYS): unassigned it
    is null, assigned it shows "<ref>" as a REF_TO does, not a Python repr;
    the instance itself has its own entry."""
    from softplc.runtime.program import compile_files

    src = """
INTERFACE I_Run
METHOD Go : INT
END_METHOD
END_INTERFACE
FUNCTION_BLOCK Motor IMPLEMENTS I_Run
VAR n : INT; END_VAR
METHOD Go : INT
n := n + 1;
Go := n;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main
VAR m : Motor; used : I_Run; unused : I_Run; k : INT; END_VAR
used := m;
k := used.Go();
END_PROGRAM
"""
    runner = compile_files([], texts={"main.st": src}).runner("Main")
    runner.run(2)
    dump = encode_instance(runner.instance)
    json.dumps(dump)
    assert dump["used"] == "<ref>"
    assert dump["unused"] is None
    assert dump["m"] == {"n": 2} and dump["k"] == 2
