"""What a hostile or careless ST file broke (issue 31, "The language"),
each through the command line as the user met it: a coded diagnostic and
exit 1, or the value kept, never a traceback and exit 4."""

from __future__ import annotations

import json

import pytest

from ..test_cli import softplc as run_cli
from .conftest import run_st


def softplc(*args):
    return run_cli(*args, timeout=300)  # deep inputs on a loaded machine


def no_traceback(proc):
    assert "Traceback" not in proc.stderr and "internal error" not in proc.stderr


# ---------------------------------------------------------------- WSTRING surrogates


@pytest.mark.parametrize(
    ("literal", "column"), [('"$D800"', 6), ('"ab$DC00"', 6), ('"$DE00$D83D"', 6), ('"x$D83Dy"', 6)]
)
def test_a_lone_surrogate_in_a_wstring_literal_is_an_error(tmp_path, literal, column):
    path = tmp_path / "w.st"
    path.write_text(f"PROGRAM Main\nVAR\n  w : WSTRING;\nEND_VAR\nw := {literal};\nEND_PROGRAM\n")
    proc = softplc("exec", path)
    no_traceback(proc)
    assert proc.returncode == 1
    assert f"w.st:5:{column}: error E003:" in proc.stderr and "lone UTF-16 surrogate" in proc.stderr


def test_a_surrogate_pair_in_a_wstring_literal_is_its_character(tmp_path):
    path = tmp_path / "w.st"
    path.write_text('PROGRAM Main\nVAR\n  w : WSTRING := "a$D83D$DE00b";\nEND_VAR\nEND_PROGRAM\n')
    proc = softplc("exec", path)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["w"] == "a\U0001f600b"


def test_a_surrogate_made_at_run_time_is_printed_as_its_json_escape(tmp_path):
    """CODESYS keeps WORD_TO_WCHAR(16#D800) as one WORD: exec keeps it too
    and prints it as \\ud800, valid JSON, not a UnicodeEncodeError."""
    path = tmp_path / "w.st"
    path.write_text(
        "PROGRAM Main\nVAR\n  w : WSTRING;\n  c : WCHAR;\nEND_VAR\n"
        "c := WORD_TO_WCHAR(16#D800);\nw := WCHAR_TO_WSTRING(c);\nEND_PROGRAM\n"
    )
    proc = softplc("exec", path)
    no_traceback(proc)
    assert proc.returncode == 0
    assert '"w": "\\ud800"' in proc.stdout
    assert json.loads(proc.stdout)["w"] == "\ud800"


# ---------------------------------------------------------------- types nested deeply


def _nested_types(n: int, reverse: bool = False, arrays: bool = False) -> str:
    if arrays:
        types = ["TYPE T0 : ARRAY[1..2] OF INT; END_TYPE"]
        types += [f"TYPE T{i} : ARRAY[1..1] OF T{i - 1}; END_TYPE" for i in range(1, n)]
    else:
        types = ["TYPE T0 : STRUCT x : INT; END_STRUCT END_TYPE"]
        types += [f"TYPE T{i} : STRUCT a : T{i - 1}; END_STRUCT END_TYPE" for i in range(1, n)]
    if reverse:
        types.reverse()
    return "\n".join(types) + f"\nPROGRAM Main\nVAR v : T{n - 1}; END_VAR\nEND_PROGRAM\n"


@pytest.mark.parametrize(("reverse", "arrays"), [(False, False), (True, False), (False, True)])
def test_600_nested_types_are_one_e006_at_the_first_too_deep(tmp_path, reverse, arrays):
    path = tmp_path / "nest.st"
    path.write_text(_nested_types(600, reverse, arrays))
    proc = softplc("check", path)
    no_traceback(proc)
    assert proc.returncode == 1
    line = 500 if reverse else 101  # T100, the first of 101 levels
    assert proc.stderr.count("error E006") == 1
    assert f"nest.st:{line}:6: error E006: type 'T100' is nested too deeply" in proc.stderr


def test_structs_100_deep_are_built_copied_and_reached():
    src = _nested_types(100, reverse=True).replace("v : T99;", "v, w : T99;")
    path = "v" + ".a" * 99 + ".x"
    src = src.replace("END_VAR\n", f"END_VAR\n{path} := 7;\nw := v;\n")
    assert run_st(src, entry="Main").get("w" + ".a" * 99 + ".x") == 7


def test_arrays_100_deep_are_built_and_copied():
    src = _nested_types(100, arrays=True).replace("v : T99;", "v, w : T99;")
    index = "[1]" * 99
    src = src.replace("END_VAR\n", f"END_VAR\nv{index}[2] := 7;\nw := v;\n")
    w = run_st(src, entry="Main").get("w")
    for _ in range(99):
        (w,) = w
    assert w == [0, 7]


# ---------------------------------------------------------------- a CASE of many branches


_SELECTORS = (0, 1, 2, 3, 4, 29_998, 29_999, 30_000, 30_099, 30_100, -10, -50, -51, -9)


def _big_case(n: int) -> str:
    labels = "\n".join(f"{k * 3}, {k * 3 + 1}: x := {k};" for k in range(n))  # 3k+2 goes to ELSE
    sels = ", ".join(map(str, _SELECTORS))
    return f"""PROGRAM Main
VAR sels : ARRAY[0..13] OF DINT := [{sels}]; got : ARRAY[0..13] OF DINT; i : INT; x : DINT; END_VAR
FOR i := 0 TO 13 DO
CASE sels[i] OF
{labels}
{n * 3}..{n * 3 + 99}, -50..-10: x := -1;
ELSE
  x := -2;
END_CASE;
got[i] := x;
END_FOR;
END_PROGRAM
"""


def test_a_case_of_10000_branches_checks_and_takes_the_right_branch():
    """Checked in n log n (LabelSet; it was pairwise, 8 s) and compiled to
    a table and a tree of ifs (an elif chain of 10,000 was E006)."""
    got = run_st(_big_case(10_000), entry="Main").get("got")
    assert got == [0, 0, -2, 1, 1, 9_999, -2, -1, -1, -2, -1, -1, -2, -2]


def test_duplicate_labels_of_a_big_case_are_reported_against_the_first(tmp_path):
    labels = "\n".join(f"{k % 100}: x := {k};" for k in range(2_000))
    path = tmp_path / "dup.st"
    path.write_text(f"PROGRAM Main\nVAR sel, x : DINT; END_VAR\nCASE sel OF\n{labels}\nEND_CASE;\nEND_PROGRAM\n")
    proc = softplc("check", path)
    no_traceback(proc)
    assert proc.returncode == 1
    assert "dup.st:104:1: error E061: CASE label overlaps an earlier one" in proc.stderr
    assert f"the earlier label is at {path}:4:1" in proc.stderr


def test_thousands_of_duplicate_labels_print_50_errors_and_the_count(tmp_path):
    """50,000 duplicate labels printed 7.9 MB: 50 errors a file are shown
    (config.errors.SHOWN, as for a configuration's errors), the rest counted."""
    labels = "\n".join(f"0: x := {k};" for k in range(5_000))
    path = tmp_path / "dup.st"
    path.write_text(f"PROGRAM Main\nVAR sel, x : DINT; END_VAR\nCASE sel OF\n{labels}\nEND_CASE;\nEND_PROGRAM\n")
    other = tmp_path / "other.st"
    other.write_text("FUNCTION F : INT\nF := undefined;\nEND_FUNCTION\n")
    proc = softplc("check", path, other)
    no_traceback(proc)
    assert proc.returncode == 1
    assert proc.stderr.count("error E061") == 50
    assert f"{path}: ... 4949 more errors\n" in proc.stderr
    assert f"{other}:2:6: error E010" in proc.stderr  # another file's errors are shown
    assert "5000 errors, 0 warnings" in proc.stderr
    assert len(proc.stderr) < 20_000


# ---------------------------------------------------------------- line endings

_LINES = ["PROGRAM Main", "VAR", "  x : INT;", "END_VAR", "x := 1;", "x := y;", "x := x +;", "END_PROGRAM", ""]


@pytest.mark.parametrize(
    "ends",
    [["\n"], ["\r\n"], ["\r"], ["\r\n", "\r", "\n"], ["\r", "\n", "\n", "\r\n"]],
    ids=["LF", "CRLF", "CR", "mixed", "mixed2"],
)
def test_errors_point_at_their_line_whatever_ends_the_lines(tmp_path, ends):
    text = "".join(line + ends[i % len(ends)] for i, line in enumerate(_LINES[:-1]))
    path = tmp_path / "ends.st"
    path.write_bytes(text.encode())
    proc = softplc("check", path)
    no_traceback(proc)
    assert proc.returncode == 1
    assert "ends.st:7:9: error E001: unexpected ';'" in proc.stderr  # the parser's
    assert "ends.st:6:6: error E010: unknown name 'y'" in proc.stderr  # the checker's
    assert "\n    x := x +;\n" in proc.stderr and "\n    x := y;\n" in proc.stderr  # the lines themselves


# ---------------------------------------------------------------- long expressions


def _chain(ty: str, op: str, n: int) -> str:
    return (
        f"PROGRAM Main\nVAR a : {ty} := 1; x : {ty}; END_VAR\nx := "
        + f" {op} ".join(["a"] * (n + 1))
        + ";\nEND_PROGRAM\n"
    )


@pytest.mark.parametrize(("ty", "op"), [("DINT", "+"), ("BOOL", "AND"), ("REAL", "+")])
def test_a_chain_past_the_old_limits_compiles_and_runs(ty, op):
    """The old limits were 197 integer, 200 BOOL and 100 REAL operators."""
    for n in (198, 201, 1000):
        src = _chain(ty, op, n).replace(":= 1;", ":= TRUE;") if ty == "BOOL" else _chain(ty, op, n)
        want = True if ty == "BOOL" else float(n + 1) if ty == "REAL" else n + 1
        assert run_st(src, entry="Main").get("x") == want


@pytest.mark.parametrize(("ty", "op"), [("DINT", "+"), ("BOOL", "OR"), ("REAL", "+")])
def test_a_chain_of_1000_operators_checks_clean(tmp_path, ty, op):
    """README: more than 1,000 operators compiled; 198 failed (E006, some
    of them E009: a RecursionError pickling the parse). Now none."""
    path = tmp_path / "ops.st"
    path.write_text(_chain(ty, op, 1000))
    proc = softplc("check", path)
    no_traceback(proc)
    assert proc.returncode == 0, proc.stderr
    assert "0 errors, 0 warnings" in proc.stderr
