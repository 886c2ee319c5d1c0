"""TcUnit's asserts (fblocks/libs/tcunit): each family passes and fails as
TcUnit documents it (tcunit.org, API), with TcUnit's messages; the failing
examples are those of TcUnit's API page and the texts those its verifier
project expects ("FAILED TEST 'PRG_TEST.PrimitiveTypes@Test_BYTE_Differ',
EXP: 0xAB, ACT: 0xCD, MSG: Values differ")."""

from __future__ import annotations

import pytest

from .conftest import FAILED, PASSED, failures, method, outcomes, suite

# (type, expected, actual, TcUnit's EXP text, ACT text): TcUnit's API examples
SCALARS = [
    ("BOOL", "TRUE", "FALSE", "TRUE", "FALSE"),
    ("BYTE", "16#AB", "16#CD", "0xAB", "0xCD"),
    ("WORD", "16#EF01", "16#2345", "0xEF01", "0x2345"),
    ("DWORD", "16#12345678", "16#90ABCDEF", "0x12345678", "0x90ABCDEF"),
    ("LWORD", "16#0123656789ABCBEC", "16#0123256789ABCAEE", "0x0123656789ABCBEC", "0x0123256789ABCAEE"),
    ("SINT", "127", "-30", "127", "-30"),
    ("INT", "-32000", "15423", "-32000", "15423"),
    ("DINT", "-55555", "70000", "-55555", "70000"),
    ("LINT", "-451416345", "589532453", "-451416345", "589532453"),
    ("USINT", "3", "7", "3", "7"),
    ("UINT", "64322", "32312", "64322", "32312"),
    ("UDINT", "34124214", "52343244", "34124214", "52343244"),
    ("ULINT", "10000", "53685437234", "10000", "53685437234"),
    ("STRING", "'This is a string'", "'This is another string'", "This is a string", "This is another string"),
    ("TIME", "T#12H34M15S10MS", "T#11H34M13S244MS", "T#12h34m15s10ms", "T#11h34m13s244ms"),
    (
        "LTIME",
        "LTIME#213503D23H34M33S709MS551US615NS",
        "LTIME#1000D15H23M12S34MS2US44NS",
        "LTIME#213503d23h34m33s709ms551us615ns",
        "LTIME#1000d15h23m12s34ms2us44ns",
    ),
    ("DATE", "D#1996-05-06", "D#2019-01-20", "D#1996-05-06", "D#2019-01-20"),
    (
        "DATE_AND_TIME",
        "DT#1996-05-06-15:36:30",
        "DT#1972-03-29-00:00:00",
        "DT#1996-05-06-15:36:30",
        "DT#1972-03-29-00:00:00",
    ),
    ("TIME_OF_DAY", "TOD#15:36:30.123", "TOD#06:21:11.492", "TOD#15:36:30.123", "TOD#06:21:11.492"),
]


@pytest.mark.parametrize("ty, expected, actual, exp_text, act_text", SCALARS, ids=[s[0] for s in SCALARS])
def test_a_typed_assert_fails_with_both_values_as_tcunit_prints_them(tcunit, ty, expected, actual, exp_text, act_text):
    decls = f"VAR a : {ty} := {expected}; b : {ty} := {actual}; END_VAR"
    methods = method(
        "Test_Differ", f"AssertEquals_{ty}(Expected := a, Actual := b, Message := 'Values differ');", decls
    ) + method("Test_Equals", f"AssertEquals_{ty}(Expected := a, Actual := a, Message := 'Values differ');", decls)
    run = tcunit(suite("FB_Types", methods, "Test_Differ();\nTest_Equals();"), {"PrimitiveTypes": "FB_Types"})
    assert outcomes(run) == {
        "PRG_TEST.PrimitiveTypes@Test_Differ": FAILED,
        "PRG_TEST.PrimitiveTypes@Test_Equals": PASSED,
    }
    assert failures(run) == [
        f"FAILED TEST 'PRG_TEST.PrimitiveTypes@Test_Differ', EXP: {exp_text}, ACT: {act_text}, MSG: Values differ"
    ]
    (failure,) = run.results[0].failures
    assert (failure.function, failure.expected, failure.actual) == (f"AssertEquals_{ty}", exp_text, act_text)


def test_reals_are_equal_within_delta_and_print_as_twincat_does(tcunit):
    methods = (
        method(
            "Test_REAL_Equals", "AssertEquals_REAL(Expected := 1234.5, Actual := 1234.4, Delta := 0.1, Message := 'm');"
        )
        + method(
            "Test_REAL_Differ",
            "AssertEquals_REAL(Expected := 1234.5, Actual := 1234.4, Delta := 0.05, Message := 'm');",
        )
        + method(
            "Test_LREAL_Differ",
            "AssertEquals_LREAL(Expected := 1234567.89, Actual := 1234567.76, Delta := 0.1, Message := 'm');",
        )
    )
    body = "Test_REAL_Equals();\nTest_REAL_Differ();\nTest_LREAL_Differ();"
    run = tcunit(suite("FB_Reals", methods, body), {"Reals": "FB_Reals"})
    assert list(outcomes(run).values()) == [PASSED, FAILED, FAILED]
    assert failures(run) == [
        "FAILED TEST 'PRG_TEST.Reals@Test_REAL_Differ', EXP: 1234.5, ACT: 1234.4, MSG: m",
        "FAILED TEST 'PRG_TEST.Reals@Test_LREAL_Differ', EXP: 1234567.89, ACT: 1234567.76, MSG: m",
    ]


def test_assert_true_and_false_as_assert_equals_bool(tcunit):
    decls = "VAR a : INT := -33; b : INT := -44; END_VAR"
    methods = (
        method("AssertThatINTsAreEqual", "AssertFalse(Condition := (a <> b), Message := 'INTs are equal');", decls)
        + method("AssertThatINTsAreNotEqual", "AssertFalse(Condition := (a = b), Message := 'INTs are equal');", decls)
        + method(
            "AssertThatWORDsAreEqual", "AssertTrue(Condition := (a = b), Message := 'WORDs are not equal');", decls
        )
    )
    body = "AssertThatINTsAreEqual();\nAssertThatINTsAreNotEqual();\nAssertThatWORDsAreEqual();"
    run = tcunit(suite("FB_TF", methods, body), {"AssertTrueFalse": "FB_TF"})
    assert list(outcomes(run).values()) == [FAILED, PASSED, FAILED]
    assert failures(run) == [
        "FAILED TEST 'PRG_TEST.AssertTrueFalse@AssertThatINTsAreEqual', EXP: FALSE, ACT: TRUE, MSG: INTs are equal",
        "FAILED TEST 'PRG_TEST.AssertTrueFalse@AssertThatWORDsAreEqual', EXP: TRUE, ACT: FALSE, "
        "MSG: WORDs are not equal",
    ]
    assert {r.failures[0].function for r in run.results if r.failures} == {"AssertFalse", "AssertTrue"}


def test_a_wstring_is_not_printed_and_an_empty_message_leaves_out_msg(tcunit):
    methods = method(
        "Test_WSTRING_Differ", 'AssertEquals_WSTRING(Expected := "äö", Actual := "æå", Message := \'Values differ\');'
    ) + method("Test_NoMessage", "AssertEquals_INT(Expected := 1, Actual := 2, Message := '');")
    run = tcunit(suite("FB_W", methods, "Test_WSTRING_Differ();\nTest_NoMessage();"), {"W": "FB_W"})
    assert failures(run) == [
        "FAILED TEST 'PRG_TEST.W@Test_WSTRING_Differ', EXP: Not possible to print EXP unicode WSTRING value, "
        "ACT: Not possible to print ACT unicode WSTRING value, MSG: Values differ",
        "FAILED TEST 'PRG_TEST.W@Test_NoMessage', EXP: 1, ACT: 2",
    ]


def test_assert_equals_of_any_compares_type_class_size_and_value(tcunit):
    types = "TYPE ST_Point : STRUCT x : INT; y : INT; END_STRUCT END_TYPE\n"
    decls = (
        "VAR i : INT := 5; u : UINT := 5; j : INT := 6; s1 : STRING := 'This is a string';"
        " s2 : STRING(40) := 'This is another string'; p : ST_Point := (x := 1, y := 2);"
        " q : ST_Point := (x := 1, y := 3); END_VAR"
    )
    methods = (
        method("Test_ANY_Equals", "AssertEquals(Expected := i, Actual := i, Message := 'Values differ');", decls)
        + method(
            "Test_ANY_Differ_DataType", "AssertEquals(Expected := i, Actual := u, Message := 'Values differ');", decls
        )
        + method("Test_ANY_INT_Differ", "AssertEquals(Expected := i, Actual := j, Message := 'Values differ');", decls)
        + method(
            "Test_ANY_STRING_Differ", "AssertEquals(Expected := s1, Actual := s2, Message := 'Values differ');", decls
        )
        + method(
            "Test_ANY_Struct_Differ", "AssertEquals(Expected := p, Actual := q, Message := 'Points differ');", decls
        )
        + method(
            "Test_ANY_Struct_Equals", "AssertEquals(Expected := p, Actual := p, Message := 'Points differ');", decls
        )
    )
    body = "\n".join(
        f"{m}();"
        for m in (
            "Test_ANY_Equals",
            "Test_ANY_Differ_DataType",
            "Test_ANY_INT_Differ",
            "Test_ANY_STRING_Differ",
            "Test_ANY_Struct_Differ",
            "Test_ANY_Struct_Equals",
        )
    )
    run = tcunit(types + suite("FB_Any", methods, body), {"AnyPrimitiveTypes": "FB_Any"})
    assert list(outcomes(run).values()) == [PASSED, FAILED, FAILED, FAILED, FAILED, PASSED]
    head = "FAILED TEST 'PRG_TEST.AnyPrimitiveTypes@"
    assert failures(run) == [
        f"{head}Test_ANY_Differ_DataType', EXP: (Type class = INT), ACT: (Type class = UINT), MSG: Values differ",
        f"{head}Test_ANY_INT_Differ', EXP: 5, ACT: 6, MSG: Values differ",
        f"{head}Test_ANY_STRING_Differ', EXP: (Data size (LEN) = 16), ACT: (Data size (LEN) = 22), MSG: Values differ",
        f"{head}Test_ANY_Struct_Differ', EXP: 0x01000200, ACT: 0x01000300, MSG: Points differ",  # little-endian bytes
    ]


ARRAYS = [
    (
        "a : ARRAY[1..6] OF BOOL := [6(TRUE)]; b : ARRAY[1..4] OF BOOL := [4(TRUE)];",
        "AssertArrayEquals_BOOL(Expecteds := a, Actuals := b, Message := 'Arrays differ');",
        "EXP: SIZE = 6, ACT: SIZE = 4, MSG: Arrays differ, size of arrays not matching.",
    ),
    (
        "a : ARRAY[0..5] OF BOOL := [TRUE, TRUE, FALSE, TRUE, FALSE, TRUE];"
        " b : ARRAY[0..5] OF BOOL := [TRUE, TRUE, TRUE, TRUE, FALSE, FALSE];",
        "AssertArrayEquals_BOOL(Expecteds := a, Actuals := b, Message := 'Arrays differ');",
        "EXP: ARRAY[2] = FALSE, ACT: ARRAY[2] = TRUE, MSG: Arrays differ",
    ),
    (
        "a : ARRAY[0..3] OF BYTE := [16#AB, 16#AA, 16#BB, 16#89];"
        " b : ARRAY[0..3] OF BYTE := [16#AB, 16#CD, 16#BB, 16#89];",
        "AssertArrayEquals_BYTE(Expecteds := a, Actuals := b, Message := 'Arrays differ');",
        "EXP: ARRAY[1] = 0xAA, ACT: ARRAY[1] = 0xCD, MSG: Arrays differ",
    ),
    (
        "a : ARRAY[-8..-6] OF INT := [42, -23, -32768]; b : ARRAY[1..3] OF INT := [42, 24, -32768];",
        "AssertArrayEquals_INT(Expecteds := a, Actuals := b, Message := 'Arrays differ');",
        "EXP: ARRAY[-7] = -23, ACT: ARRAY[2] = 24, MSG: Arrays differ",
    ),
    (
        "a : ARRAY[-8..-6] OF REAL := [42.0, -23.0, 1.5]; b : ARRAY[1..3] OF REAL := [42.05, 24.0, 1.5];",
        "AssertArrayEquals_REAL(Expecteds := a, Actuals := b, Delta := 0.1, Message := 'Arrays differ');",
        "EXP: ARRAY[-7] = -23.0, ACT: ARRAY[2] = 24.0, MSG: Arrays differ",
    ),
    (
        "a : ARRAY[-4..-2, -1..0] OF LREAL; b : ARRAY[1..2, 0..1] OF LREAL;",
        "AssertArray2dEquals_LREAL(Expecteds := a, Actuals := b, Delta := 0.0, Message := 'Arrays differ');",
        "EXP: SIZE = [-4..-2,-1..0] (3x2), ACT: SIZE = [1..2,0..1] (2x2), "
        "MSG: Arrays differ, size of arrays not matching.",
    ),
    (
        "a : ARRAY[-5..-3, -1..1] OF REAL;"
        " b : ARRAY[1..3, 3..5] OF REAL := [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0];",
        "AssertArray2dEquals_REAL(Expecteds := a, Actuals := b, Delta := 0.5, Message := 'Arrays differ');",
        "EXP: ARRAY[-3,1] = 0.0, ACT: ARRAY[3,5] = 1.0, MSG: Arrays differ",
    ),
    (
        "a : ARRAY[-5..-4, 0..2, -1..0] OF LREAL; b : ARRAY[0..1, 3..5, 6..6] OF LREAL;",
        "AssertArray3dEquals_LREAL(Expecteds := a, Actuals := b, Delta := 0.0, Message := 'Arrays differ');",
        "EXP: SIZE = [-5..-4,0..2,-1..0] (2x3x2), ACT: SIZE = [0..1,3..5,6..6] (2x3x1), "
        "MSG: Arrays differ, size of arrays not matching.",
    ),
]


@pytest.mark.parametrize("decls, call, message", ARRAYS)
def test_array_asserts_name_the_size_or_the_first_element_that_differs(tcunit, decls, call, message):
    methods = method("Test_Array", call, f"VAR {decls} END_VAR")
    run = tcunit(suite("FB_Arrays", methods, "Test_Array();"), {"ArrayPrimitiveTypes": "FB_Arrays"})
    assert failures(run) == [f"FAILED TEST 'PRG_TEST.ArrayPrimitiveTypes@Test_Array', {message}"]


def test_equal_arrays_of_other_bounds_pass(tcunit):
    decls = (
        "VAR a : ARRAY[-5..1] OF INT := [64, 98, -32768, 32767, 5478, -378, 42];"
        " b : ARRAY[1..7] OF INT := [64, 98, -32768, 32767, 5478, -378, 42];"
        " c : ARRAY[2..3] OF DWORD := [16#6789ABCD, 16#EF012345];"
        " d : ARRAY[1..2] OF DWORD := [16#6789ABCD, 16#EF012345];"
        " e : ARRAY[1..2, 1..2] OF REAL := [1.0, 2.0, 3.0, 4.0];"
        " f : ARRAY[0..1, 5..6] OF REAL := [1.05, 2.0, 3.0, 3.95];"
        " END_VAR"
    )
    body = (
        "AssertArrayEquals_INT(Expecteds := a, Actuals := b, Message := 'm');\n"
        "AssertArrayEquals_DWORD(Expecteds := c, Actuals := d, Message := 'm');\n"
        "AssertArray2dEquals_REAL(Expecteds := e, Actuals := f, Delta := 0.1, Message := 'm');"
    )
    run = tcunit(suite("FB_Arrays", method("Test_Equal", body, decls), "Test_Equal();"), {"A": "FB_Arrays"})
    assert outcomes(run) == {"PRG_TEST.A@Test_Equal": PASSED} and failures(run) == []
    assert run.results[0].asserts == 3


def test_a_long_failure_message_is_cut_as_tcunit_cuts_it_for_the_ads_log(tcunit):
    long = "x" * 300
    methods = method("Test_Long", f"AssertEquals_INT(Expected := 1, Actual := 2, Message := '{long[:250]}');")
    run = tcunit(suite("FB_Long", methods, "Test_Long();"), {"L": "FB_Long"})
    (line,) = failures(run)
    # TcUnit fits the format ('..., MSG: %s') and the message in 253 characters
    assert len(line) == 253 - len("%s") and line.endswith("x...TestMsg too long")
    assert run.results[0].failures[0].message == long[:250]  # softplc's own report keeps it whole


def test_a_literal_given_to_assert_equals_takes_the_other_values_type(tcunit):
    decls = "VAR u : UINT := 5; r : REAL := 2.5; s : STRING(20) := 'abc'; i : INT := 5; END_VAR"
    body = (
        "AssertEquals(Expected := 5, Actual := u, Message := 'a UINT');\n"
        "AssertEquals(Expected := 2.5, Actual := r, Message := 'a REAL');\n"
        "AssertEquals(Expected := 'abc', Actual := s, Message := 'a STRING');\n"
        "AssertEquals(Expected := i, Actual := u, Message := 'two types');"
    )
    run = tcunit(suite("FB_Lit", method("Literals", body, decls), "Literals();"), {"Lit": "FB_Lit"})
    assert failures(run) == [
        "FAILED TEST 'PRG_TEST.Lit@Literals', EXP: (Type class = INT), ACT: (Type class = UINT), MSG: two types"
    ]
