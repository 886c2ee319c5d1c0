"""Fuzzing the ST front end: whatever the user feeds it, the compiler answers
with coded, located diagnostics, never with a Python traceback.

  * arbitrary text (control characters, NULs, unicode) goes into check_files;
  * a corpus of valid programs is mutated token-wise (fuzz_mutations.py:
    spans deleted, duplicated, swapped; keywords, operators, literals
    inserted; identifiers renamed; types flipped; truncated). When the
    checker accepts a mutant, it must also compile, load and run (or stop
    with an STFault);
  * pathological nesting ends in a diagnostic, not a RecursionError.

The runs are derandomized (CI reproducible). For a deeper local run:
    SOFTPLC_FUZZ_EXAMPLES=5000 pytest tests/st/test_fuzz.py
The cross-cutting harness (tests/fuzz/) adds programs generated from the
typed grammar, more mutations and the long seeded run (pytest -m fuzz).
"""

from __future__ import annotations

import os

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from softplc.runtime.program import check_files, compile_files  # noqa: E402

from .fuzz_corpus import CORPUS  # noqa: E402
from .fuzz_mutations import ST_ALPHABET, gently_mutated_programs, mutated_programs  # noqa: E402
from .fuzz_support import (  # noqa: E402
    FILE,
    TOKEN_POOL,
    assert_well_formed,
    check_and_maybe_run,
    fuzz_settings,
    tokenize,
)

# ---------------------------------------------------------------- the corpus itself is valid


@pytest.mark.parametrize("index", range(len(CORPUS)))
def test_corpus_programs_are_valid_and_run(index):
    profile, src = CORPUS[index]
    diags = check_and_maybe_run(profile, src, cycles=5)
    assert not [d for d in diags if d.is_error]
    assert len(tokenize(src)) > 20


# ---------------------------------------------------------------- arbitrary text

_ANY_CHAR = st.characters(exclude_categories=())  # any code point, lone surrogates included


@fuzz_settings(120)
@given(st.text(_ANY_CHAR, max_size=300))
def test_arbitrary_text_gives_only_diagnostics(text):
    diags, _ = check_files([], profile="codesys", texts={FILE: text})
    assert_well_formed(diags)


@fuzz_settings(80)
@given(st.text(ST_ALPHABET, max_size=200), st.sampled_from(["codesys", "iec", "schneider", "twincat"]))
def test_punctuation_soup_gives_only_diagnostics(text, profile):
    diags, _ = check_files([], profile=profile, texts={FILE: text})
    assert_well_formed(diags)


@fuzz_settings(80)
@given(st.lists(st.sampled_from(TOKEN_POOL), max_size=60), st.sampled_from(["codesys", "schneider"]))
def test_token_salad_gives_only_diagnostics(tokens, profile):
    check_and_maybe_run(profile, " ".join(tokens))


@fuzz_settings(40)
@given(st.binary(max_size=300) | st.text(ST_ALPHABET, max_size=200).map(lambda t: t.encode("utf-16")))
def test_arbitrary_bytes_in_a_file_give_only_diagnostics(data):
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "bytes.st")
        with open(path, "wb") as f:
            f.write(data)
        diags, _ = check_files([path])
    assert_well_formed(diags, user_files=(path,))


@pytest.mark.parametrize("kind", ["directory", "missing", "latin-1", "bom", "utf-16", "empty"])
def test_unreadable_or_odd_files_give_diagnostics(tmp_path, kind):
    path = tmp_path / "p.st"
    if kind == "directory":
        path.mkdir()
    elif kind == "latin-1":
        path.write_bytes(b"PROGRAM main VAR s : STRING := '\xe9t\xe9'; END_VAR END_PROGRAM")
    elif kind == "bom":
        path.write_bytes(b"\xef\xbb\xbfPROGRAM main VAR x : INT; END_VAR x := 1; END_PROGRAM")
    elif kind == "utf-16":
        path.write_bytes("PROGRAM main END_PROGRAM".encode("utf-16"))
    elif kind == "empty":
        path.write_bytes(b"")
    diags, _ = check_files([str(path)])
    assert_well_formed(diags, user_files=(str(path),))
    errors = [d for d in diags if d.is_error]
    if kind in ("directory", "missing"):
        assert [d.code for d in errors] == ["E000"]
    elif kind in ("latin-1", "bom", "utf-16", "empty"):  # UTF-16 with its byte order mark is text
        assert not errors
        prog = compile_files([str(path)])
        if kind == "latin-1":
            r = prog.runner("main")
            r.run(1)
            assert r.get("s") == "\u00e9t\u00e9"
    else:
        assert errors


# ---------------------------------------------------------------- mutated valid programs


@fuzz_settings(200)
@given(mutated_programs())
def test_mutated_programs_give_diagnostics_or_run(case):
    profile, src = case
    check_and_maybe_run(profile, src)


@fuzz_settings(100)
@given(gently_mutated_programs())
def test_gently_mutated_programs_give_diagnostics_or_run(case):
    profile, src = case
    check_and_maybe_run(profile, src)


# ---------------------------------------------------------------- random statements

# Random (often ill-typed) statements over variables of every kind: the
# checker's type rules decide; what it accepts must compile and run.
_RANDOM_DECLS = """
TYPE Mode : (Idle, Run := 5, Fault); END_TYPE
TYPE Rec : STRUCT x : INT; m : Mode; v : ARRAY[0..2] OF REAL; END_STRUCT END_TYPE
FUNCTION Twice : DINT
VAR_INPUT v : DINT; END_VAR
Twice := v * 2;
END_FUNCTION
PROGRAM main
VAR
    i : INT := 3; si : SINT; d : DINT := -7; li : LINT; us : USINT; u : UDINT := 9; ul : ULINT;
    b : BOOL; r : REAL := 1.5; l : LREAL := -2.25; w : WORD := 16#F0F0; bt : BYTE := 7; dw : DWORD;
    t : TIME := T#1s; lt : LTIME; tod1 : TOD; dt1 : DT; dd : DATE;
    s : STRING[12] := 'abc'; ws : WSTRING[12] := "xyz";
    a : ARRAY[1..3] OF INT := [1, 2, 3]; rec : Rec; e : Mode; sub : INT(-5..5);
    p : POINTER TO INT; rf : REF_TO DINT; k : INT; tmr : TON; ctr : CTU;
END_VAR
"""
_R_VARS = [
    "i",
    "si",
    "d",
    "li",
    "us",
    "u",
    "ul",
    "b",
    "r",
    "l",
    "w",
    "bt",
    "dw",
    "t",
    "lt",
    "tod1",
    "dt1",
    "dd",
    "s",
    "ws",
    "a[2]",
    "a[k]",
    "rec.x",
    "rec.m",
    "rec.v[1]",
    "e",
    "sub",
    "p^",
    "rf^",
    "tmr.Q",
    "tmr.ET",
    "ctr.CV",
    "k",
]
_R_LITERALS = [
    "0",
    "1",
    "-1",
    "7",
    "255",
    "32767",
    "-32768",
    "2147483647",
    "4294967295",
    "1.0",
    "-0.5",
    "1.0E10",
    "TRUE",
    "FALSE",
    "16#FF",
    "2#1010",
    "T#5ms",
    "T#-1s",
    "LTIME#1us",
    "TOD#01:02:03",
    "DT#2024-01-01-00:00:00",
    "D#2024-01-01",
    "'q'",
    "''",
    '"w"',
    "Run",
    "Mode#Fault",
    "INT#-3",
    "REAL#2.5",
    "BYTE#16#80",
    "WORD#1",
]
_R_BINOPS = [
    "+",
    "-",
    "*",
    "/",
    "MOD",
    "**",
    "AND",
    "OR",
    "XOR",
    "&",
    "=",
    "<>",
    "<",
    ">",
    "<=",
    ">=",
    "AND_THEN",
    "OR_ELSE",
]
_R_FUNCS = [
    "ABS",
    "SQRT",
    "LN",
    "EXP",
    "SIN",
    "TRUNC",
    "INT_TO_REAL",
    "REAL_TO_INT",
    "DINT_TO_TIME",
    "TIME_TO_DINT",
    "TO_STRING",
    "TO_INT",
    "TO_LREAL",
    "LEN",
    "BOOL_TO_INT",
    "Twice",
    "NOT",
    "MOVE",
    "TO_BYTE",
    "TO_WSTRING",
    "SHL",
    "ROL",
    "MIN",
    "MAX",
    "SEL",
    "LIMIT",
    "MUX",
    "CONCAT",
    "LEFT",
    "MID",
    "FIND",
    "EXPT",
    "ADD",
    "MUL",
    "INSERT",
    "DELETE",
    "REPLACE",
    "SUB_DT_DT",
    "ADR",
    "REF",
    "SIZEOF",
]


def _r_expr(draw, depth: int = 0) -> str:
    kind = draw(st.integers(0, 9 if depth < 3 else 1))
    if kind == 0:
        return draw(st.sampled_from(_R_VARS))
    if kind == 1:
        return draw(st.sampled_from(_R_LITERALS))
    if kind in (2, 3, 4):
        return f"({_r_expr(draw, depth + 1)} {draw(st.sampled_from(_R_BINOPS))} {_r_expr(draw, depth + 1)})"
    if kind == 5:
        return f"{draw(st.sampled_from(['-', 'NOT ']))}{_r_expr(draw, depth + 1)}"
    n = draw(st.integers(1, 3))
    args = ", ".join(_r_expr(draw, depth + 1) for _ in range(n))
    return f"{draw(st.sampled_from(_R_FUNCS))}({args})"


def _r_stmt(draw, depth: int = 0) -> str:
    kind = draw(st.integers(0, 9 if depth < 2 else 3))
    target = draw(st.sampled_from(_R_VARS))
    if kind <= 3:
        op = draw(st.sampled_from([":=", ":=", ":=", "S=", "R=", "REF="]))
        return f"{target} {op} {_r_expr(draw)};"
    if kind == 4:
        return f"IF {_r_expr(draw)} THEN {_r_block(draw, depth)} ELSE {_r_block(draw, depth)} END_IF;"
    if kind == 5:
        return (
            f"FOR k := {_r_expr(draw)} TO {_r_expr(draw)} BY {draw(st.sampled_from(['1', '-1', '2', 'i']))} DO "
            f"{_r_block(draw, depth)} END_FOR;"
        )
    if kind == 6:
        labels = draw(st.sampled_from(["1", "1, 2", "0..3", "Run", "Idle, Fault", "-1"]))
        return f"CASE {_r_expr(draw)} OF {labels}: {_r_block(draw, depth)} ELSE {_r_block(draw, depth)} END_CASE;"
    if kind == 7:
        call = draw(
            st.sampled_from(
                [
                    f"tmr(IN := {_r_expr(draw)}, PT := {_r_expr(draw)});",
                    f"ctr(CU := {_r_expr(draw)}, PV := {_r_expr(draw)}, Q => b);",
                    "p := ADR(a[2]);",
                    "rf := REF(d);",
                    "SET b;",
                    "RESET b;",
                ]
            )
        )
        return call
    if kind == 8:
        return f"WHILE k < 3 AND {_r_expr(draw)} DO k := k + 1; {_r_block(draw, depth)} END_WHILE;"
    return f"REPEAT {_r_block(draw, depth)} UNTIL TRUE END_REPEAT;"


def _r_block(draw, depth: int) -> str:
    return " ".join(_r_stmt(draw, depth + 1) for _ in range(draw(st.integers(0, 2))))


@st.composite
def random_statement_programs(draw):
    body = "\n".join(_r_stmt(draw) for _ in range(draw(st.integers(1, 4))))
    return f"{_RANDOM_DECLS}p := ADR(i); rf := REF(d); k := 0;\n{body}\nEND_PROGRAM\n"


@fuzz_settings(80)
@given(random_statement_programs())
def test_random_statements_give_diagnostics_or_run(src):
    check_and_maybe_run("codesys", src)


def test_random_statement_declarations_are_valid():
    diags = check_and_maybe_run("codesys", f"{_RANDOM_DECLS}p := ADR(i); rf := REF(d);\nEND_PROGRAM\n")
    assert not [d for d in diags if d.is_error]


# ---------------------------------------------------------------- diagnostics are well formed


@pytest.mark.parametrize(
    "src",
    [
        "",
        "\0",
        "\ufeff",
        "(*",
        "{",
        "'",
        '"',
        "*)",
        "PROGRAM",
        "END_PROGRAM",
        "PROGRAM main",
        "x := ;",
        "PROGRAM p VAR x : INT END_VAR END_PROGRAM",
        "\r\n\r\n\x00PROGRAM\tmain\r\nEND_PROGRAM",
        "PROGRAM main\nVAR x : INT; END_VAR\nx := 'never closed;\nEND_PROGRAM",
        "PROGRAM main\n\u00e9t\u00e9 := 1;\nEND_PROGRAM",
        "TYPE t : STRUCT END_STRUCT END_TYPE",
        "FUNCTION f END_FUNCTION",
        "FUNCTION_BLOCK TON END_FUNCTION_BLOCK",
        "TYPE TON : INT; END_TYPE PROGRAM main VAR t : TON; END_VAR t := 1; END_PROGRAM",
        "FUNCTION TON : INT TON := 1; END_FUNCTION",
        "PROGRAM main VAR AT %QW1 : WORD; END_VAR END_PROGRAM",
        "CONFIGURATION c RESOURCE r ON cpu TASK t(INTERVAL := T#10ms); PROGRAM p WITH t : main; "
        "END_RESOURCE END_CONFIGURATION",
    ],
)
def test_diagnostics_are_well_formed_and_only_in_user_files(src):
    check_and_maybe_run("codesys", src)


def test_user_declarations_replacing_library_ones_never_surface_library_errors():
    import re as _re
    from importlib import resources

    lib = resources.files("softplc.fblocks.iec").joinpath("standard_fbs.st").read_text("utf-8")
    names = _re.findall(r"^(?:FUNCTION_BLOCK|FUNCTION)\s+(\w+)", lib, _re.M)
    assert {"TON", "CTU", "R_TRIG"} <= set(names)
    for n in names:
        for decl in (f"TYPE {n} : STRUCT a : INT; END_STRUCT END_TYPE", f"FUNCTION {n} : INT {n} := 1; END_FUNCTION"):
            src = f"{decl}\nPROGRAM main VAR t : TON; c : CTU; r : R_TRIG; x : INT; END_VAR x := 1; END_PROGRAM"
            check_and_maybe_run("codesys", src, cycles=1)


def test_diagnostics_in_several_files_name_the_right_file():
    texts = {
        "a.st": "PROGRAM a\nVAR x : INT; END_VAR\nx := y;\nEND_PROGRAM\n",
        "b.st": "PROGRAM b\nVAR z : BOOL; END_VAR\n\nz := 1 +;\nEND_PROGRAM\n",
    }
    diags, _ = check_files([], texts=texts)
    assert_well_formed(diags, user_files=("a.st", "b.st"))
    assert {d.pos.file for d in diags if d.is_error} == {"a.st", "b.st"}
    assert any(d.pos.file == "a.st" and d.pos.line == 3 for d in diags)
    assert any(d.pos.file == "b.st" and d.pos.line == 4 for d in diags)


# ---------------------------------------------------------------- minimal inputs of crashes found by fuzzing


@pytest.mark.parametrize(
    "profile,src",
    [
        ("codesys", "TYPE t : STRUCT a.b : INT; END_STRUCT END_TYPE"),
        ("codesys", "PROGRAM p VAR a.b : INT; END_VAR END_PROGRAM"),
        ("codesys", "PROGRAM main VAR AT %QW1 : WORD; END_VAR END_PROGRAM"),
        ("schneider", "PROGRAM main VAR AT %MW100 : INT; END_VAR END_PROGRAM"),
        (
            "codesys",
            "PROGRAM main VAR CONSTANT c : INT := 's'; END_VAR VAR p : INT(0..100); END_VAR p := c; END_PROGRAM",
        ),
        ("codesys", "PROGRAM main VAR x : INT; END_VAR x := %MW70000; END_PROGRAM"),
        ("schneider", "PROGRAM main VAR x : INT; END_VAR %MD99999999999 := 1; END_PROGRAM"),
        ("codesys", "PROGRAM main VAR w : WORD; END_VAR w := WORD#16#36#ZZ; END_PROGRAM"),
        ("codesys", "PROGRAM main VAR w : WORD; END_VAR w := WORD#16x#1; END_PROGRAM"),
        ("codesys", "PROGRAM main VAR i : INT; END_VAR FOR i := 0.0 TO 5 DO END_FOR END_PROGRAM"),
        ("codesys", "PROGRAM main VAR i : INT; END_VAR FOR i := 0 TO 5 BY 1.5 DO END_FOR END_PROGRAM"),
        ("codesys", "PROGRAM main VAR x : DINT; END_VAR x := " + "9" * 5000 + "; END_PROGRAM"),
        ("codesys", "VAR_CONFIG main.x AT %MW1 : INT; END_VAR PROGRAM main VAR x : INT; END_VAR END_PROGRAM"),
        ("codesys", "FUNCTION_BLOCK f VAR_INPUT a.b : INT; END_VAR END_FUNCTION_BLOCK"),
        ("codesys", "PROGRAM main VAR x AT %I* : BOOL; END_VAR END_PROGRAM"),
        ("schneider", "FUNCTION_BLOCK fb VAR x AT %IX* : BOOL; y AT %QW* : WORD; END_VAR END_FUNCTION_BLOCK"),
    ],
    ids=[
        "dotted-field",
        "dotted-var",
        "unnamed-located",
        "unnamed-located-schneider",
        "string-constant-subrange",
        "address-outside-area",
        "address-outside-area-schneider",
        "double-base-literal",
        "bad-base-literal",
        "for-real-start",
        "for-real-step",
        "5000-digit-literal",
        "var-config",
        "dotted-input",
        "unconfigured-bit-address",
        "unconfigured-addresses-in-fb",
    ],
)
def test_minimal_inputs_of_crashes_found_by_fuzzing(profile, src):
    check_and_maybe_run(profile, src, cycles=1)
