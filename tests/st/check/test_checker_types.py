"""The checker's declared types (runtime/st/check/checker_types.py): collecting
names, resolving types as written."""

from __future__ import annotations

from softplc.runtime.st.limits import MAX_VAR_ELEMENTS

from ..conftest import codes, diagnostics, prog, run_st


def test_aliases_typed_enums_subranges_and_struct_defaults():
    src = """
TYPE
  Speed : REAL := 1.5;
  Level : INT (0..10);
  State : (Off, Starting := 10, Running) DINT;
  Axis : STRUCT pos : LREAL := 2.5; state : State := State#Running; name : STRING[8] := 'x1'; END_STRUCT;
END_TYPE
PROGRAM main
VAR v : Speed; lv : Level := 5; st : State; ax : Axis; n : DINT; END_VAR
n := ax.state;
st := State#Starting;
END_PROGRAM
"""
    r = run_st(src)
    assert r.get("v") == 1.5 and r.get("lv") == 5 and r.get("st") == 10
    assert r.get("ax.pos") == 2.5 and r.get("ax.name") == "x1" and r.get("n") == 11


def test_a_type_name_must_be_new_and_a_used_one_known():
    src = (
        "TYPE INT : STRUCT a : BOOL; END_STRUCT END_TYPE\n"
        "PROGRAM main\nVAR x : Motr; END_VAR\nEND_PROGRAM\n"
        "FUNCTION_BLOCK Motor\nEND_FUNCTION_BLOCK\n"
    )
    found = [(d.code, d.message, d.pos.line) for d in diagnostics(src)]
    assert found == [("E011", "'INT' is the name of an elementary type", 1), ("E012", "unknown type 'Motr'", 3)]
    assert "did you mean" in diagnostics(src)[1].hint


def test_types_declared_twice_and_empty_bounds():
    src = (
        "TYPE T1 : (A, B); END_TYPE\nTYPE T1 : INT; END_TYPE\n"
        "PROGRAM main\nVAR s : STRING[0]; a : ARRAY[3..1] OF INT; r : INT(5..1); END_VAR\nEND_PROGRAM\n"
    )
    assert [(d.code, d.message) for d in diagnostics(src)] == [
        ("E011", "'T1' is declared twice"),
        ("E022", "string length 0 is not within 1..65535"),
        ("E050", "array range 3..1 is empty"),
        ("E022", "subrange 5..1 is not within INT"),
    ]
    assert codes(src, "iec") == ["E011", "E022", "E050", "E022"]


def test_an_array_type_with_more_elements_than_a_variable_may_have_is_e054():
    src = prog(f"a : ARRAY[1..{MAX_VAR_ELEMENTS}] OF BYTE;\nb : ARRAY[0..9999, 0..9999, 0..99] OF INT;", "")
    [d] = diagnostics(src)
    assert (d.code, d.pos.line, d.pos.col) == ("E054", 4, 5)
    assert d.message == f"the array has more than 100,000,000 elements; one variable may have {MAX_VAR_ELEMENTS:,}"
    [d] = diagnostics(prog(f"a : ARRAY[0..{MAX_VAR_ELEMENTS}] OF BYTE;", ""))
    assert d.message == f"the array has {MAX_VAR_ELEMENTS + 1:,} elements; one variable may have {MAX_VAR_ELEMENTS:,}"


def test_twincat_takes_the_unsigned_range_of_time_and_ltime_literals():
    # TwinCAT's LTIME is 0 .. 2^64-1 ns (TcUnit's documentation asserts on its largest value)
    src = prog(
        "a : LTIME := LTIME#213503D23H34M33S709MS551US615NS; b : LTIME := LTIME#213503d23h34m33s709ms551us615ns;"
        " t : TIME := T#49d17h2m47s295ms; same : BOOL; other : BOOL;",
        "same := a = b; other := a = LTIME#1000d15h23m12s34ms2us44ns;",
    )
    r = run_st(src, profile="twincat")
    assert (r.get("same"), r.get("other")) == (True, False)
    assert codes(src, "codesys") == ["E022", "E022", "E022"]
    assert codes(src.replace("T#49d17h2m47s295ms", "T#49d17h2m47s296ms"), "twincat") == ["E022"]
