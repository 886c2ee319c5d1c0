"""The checker's diagnostics: coded, located, with a hint; all errors of a
file in one run; never a Python traceback."""
from __future__ import annotations

from softplc.runtime.st.diagnostics import SourceSet

from .conftest import codes, diagnostics


def prog(decls: str, body: str) -> str:
    return f"PROGRAM main\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"


def test_unknown_name_has_location_and_a_did_you_mean_hint():
    src = prog("counter : INT;", "countr := 1;")
    [d] = diagnostics(src)
    assert (d.code, d.pos.line, d.pos.col) == ("E010", 5, 1)
    assert "countr" in d.message and "counter" in d.hint
    sources = SourceSet()
    sources.add("test.st", src)
    text = d.format(sources)
    assert text.splitlines()[0].startswith("test.st:5:1: error E010")
    assert "countr := 1;" in text and "^" in text and "hint:" in text


def test_all_errors_of_a_file_are_reported_in_one_run():
    src = prog("a : INT; b : BOOL; c : CONSTANT_NOT_A_TYPE;", "a := TRUE;\nb := 5;\nzz := 1;\nEXIT;")
    found = codes(src)
    assert found.count("E020") == 2 and "E012" in found and "E010" in found and "E070" in found


def test_narrowing_is_an_error_in_iec_and_a_warning_in_codesys():
    src = prog("d : DINT := 100000; i : INT; r : REAL; l : LREAL;", "i := d; r := l;")
    assert codes(src, "iec") == ["E021", "E021"]
    assert codes(src, "codesys") == ["W121", "W121"]


def test_widening_is_silent():
    src = prog("s : SINT; i : INT; d : DINT; r : REAL; l : LREAL; u : USINT; w : WORD; b : BYTE;",
               "i := s; d := i; l := r; r := i; i := u; w := b; l := d;")
    assert codes(src, "iec") == []


def test_literal_out_of_range_for_its_type():
    assert codes(prog("x : SINT := 200;", "")) == ["E022"]
    assert codes(prog("x : INT;", "x := 70000;")) == ["E022"]
    assert codes(prog("x : USINT;", "x := -1;")) == ["E022"]


def test_assignments_to_constants_inputs_and_foreign_outputs_are_rejected():
    src = """
FUNCTION_BLOCK Fb
VAR_INPUT i : INT; END_VAR
VAR_OUTPUT o : INT; END_VAR
i := 1;
END_FUNCTION_BLOCK
PROGRAM main
VAR CONSTANT k : INT := 1; END_VAR
VAR f : Fb; END_VAR
k := 2;
f.o := 3;
f.i := 4;
END_PROGRAM
"""
    ds = diagnostics(src)
    assert [(d.code, d.pos.line) for d in ds] == [("E030", 5), ("E030", 10), ("E030", 11)]


def test_call_parameters_are_checked():
    src = """
FUNCTION f : INT
VAR_INPUT a : INT; END_VAR
VAR_IN_OUT io : INT; END_VAR
f := a;
END_FUNCTION
PROGRAM main
VAR t : TON; x : INT; q : BOOL; END_VAR
x := f(a := 1, nosuch := 2, io := x);
x := f(a := 1);
t(IN := TRUE, PT := 5);
t(IN := TRUE, Q := q);
x := f(1, x, 3);
END_PROGRAM
"""
    found = [(d.code, d.pos.line) for d in diagnostics(src) if d.is_error]
    assert ("E040", 9) in found  # unknown parameter
    assert ("E042", 10) in found  # VAR_IN_OUT not connected
    assert ("E020", 11) in found  # PT is TIME, not an integer
    assert ("E040", 12) in found  # output bound with :=
    assert ("E041", 13) in found  # too many arguments


def test_fb_called_as_a_value_and_program_called_directly():
    src = """
PROGRAM other
END_PROGRAM
PROGRAM main
VAR t : TON; b : BOOL; END_VAR
b := t(IN := TRUE);
other();
END_PROGRAM
"""
    assert codes(src) == ["E043", "E043"]


def test_type_errors_in_conditions_and_operators():
    src = prog("i : INT; s : STRING; b : BOOL; r : REAL;",
               "IF i THEN END_IF\nb := s + 1;\nr := r MOD 2.0;\nb := b < s;")
    assert codes(src) == ["E020", "E023", "E023", "E020"]


def test_for_variable_must_not_be_assigned_in_the_loop():
    assert codes(prog("i : INT;", "FOR i := 1 TO 3 DO i := 5; END_FOR")) == ["E072"]


def test_duplicate_declarations_and_case_labels():
    src = prog("a : INT; a : INT; x : INT;", "CASE x OF 1: ; 0..2: ; END_CASE")
    assert codes(src) == ["E011", "E061"]


def test_constant_index_out_of_bounds_is_a_compile_error():
    assert codes(prog("a : ARRAY[1..3] OF INT;", "a[4] := 1;")) == ["E051"]


def test_schneider_addresses_need_the_schneider_profile():
    src = prog("x : BOOL;", "x := %MW3250:X0;")
    assert codes(src, "codesys") == ["E080"]
    assert codes(src, "schneider") == []


def test_c_style_hex_only_in_the_schneider_profile():
    src = prog("d : DINT;", "d := 0x00032007;")
    assert codes(src, "codesys") == ["E026"]
    assert codes(src, "schneider") == []


def test_nesting_beyond_the_python_compilers_limits_is_e006_at_the_st_location():
    body = "WHILE FALSE DO\n" * 21 + "x := 1;\n" + "END_WHILE\n" * 21
    ds = diagnostics(prog("x : INT;", body))
    assert [d.code for d in ds] == ["E006"]
    assert ds[0].pos.line >= 5 and "FUNCTION" in ds[0].hint


def test_retain_where_nothing_can_be_kept_is_a_warning():
    src = ("FUNCTION F : INT\nVAR RETAIN t : INT; END_VAR\nF := t;\nEND_FUNCTION\n"
           "PROGRAM main\nVAR RETAIN\n    kept : INT;\n    x AT %MW4 : INT;\nEND_VAR\n"
           "VAR_TEMP PERSISTENT\n    tmp : INT;\nEND_VAR\nkept := F() + x + tmp;\nEND_PROGRAM\n")
    found = [(d.code, d.pos.line, d.message.split(",")[0]) for d in diagnostics(src)]
    assert found == [("W111", 2, "RETAIN has no effect on t"), ("W111", 8, "RETAIN has no effect on x"),
                     ("W111", 11, "PERSISTENT has no effect on tmp")]
