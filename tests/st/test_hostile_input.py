"""No ST text ever reaches the generated Python source unescaped.

ST identifiers become prefixed Python names, string literals become inert
Python string literals, comments and pragmas vanish, and the generated
module runs with a handful of builtins: whatever names, strings or comments
an ST program contains, compiling, loading and running it imports nothing,
executes nothing but its own module, and computes exactly what the ST says.
"""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from softplc.runtime.program import check_files, compile_files

from .hostile_support import IDENT_RE, LIBRARY_SOURCE, assert_inert, compile_st, run, st_quote


class _FakeProgram:
    def __init__(self, source: str):
        self.python_source = source

    def load(self):
        return {"__builtins__": {}, "_G": None}


@pytest.mark.parametrize(
    "source",
    [
        "import os\n",
        "x = 1\nfrom os import system\n",
        "def f():\n    return eval('1')\n",
        "x = _G.__class__\n",
        "x = unknown_name\n",
        "x = 'some ST text'\n",
        "x = 1  # user comment\n",
        "x = (lambda: __import__)\n",
    ],
)
def test_the_inertness_check_itself_catches_injected_code(source):
    with pytest.raises(AssertionError):
        assert_inert(_FakeProgram(source))


# ---------------------------------------------------------------- identifiers

PYTHON_NAMES = [
    # Python keywords and soft keywords that are not ST keywords
    "lambda",
    "class",
    "def",
    "import",
    "from",
    "as",
    "assert",
    "async",
    "await",
    "del",
    "elif",
    "except",
    "finally",
    "global",
    "in",
    "is",
    "nonlocal",
    "pass",
    "raise",
    "try",
    "yield",
    "match",
    "None",
    "_",
    # builtins and modules
    "exec",
    "eval",
    "compile",
    "__import__",
    "print",
    "open",
    "input",
    "getattr",
    "globals",
    "locals",
    "vars",
    "breakpoint",
    "range",
    "float",
    "object",
    "property",
    "super",
    "len",
    "abs",
    "min",
    "max",
    "os",
    "sys",
    # dunders
    "__class__",
    "__builtins__",
    "__init__",
    "__slots__",
    "__call__",
    "__dict__",
    "__name__",
    "__",
    # the generated code's own vocabulary: prefixes, helpers, loader names
    "self",
    "o",
    "n",
    "None_",
    "_G",
    "_ctx",
    "_K0",
    "_K1",
    "_A0g",
    "_A0s",
    "v_x",
    "g_x",
    "f_x",
    "_o_v_x",
    "P_main",
    "FB_ton",
    "F_f",
    "S_s",
    "_Globals",
    "_VARS_",
    "_assign",
    "_copy",
    "_watchdog",
    "_deref",
    "_INF",
    "_NAN",
    "_f32",
    "_AttrRef",
    "_comm",
    "_time_ms",
    "_check_index",
    "_for_range",
    "_t1",
    "_c1",
    "_i1",
    "_result",
    "r_result",
    "v__result",
]


def _value(i: int) -> int:
    return i % 50 + 1


def test_python_names_as_program_variables():
    decls = "".join(f"{n} : INT := {_value(i)};\n" for i, n in enumerate(PYTHON_NAMES))
    body = "".join(f"{n} := {n} * 3;\n" for n in PYTHON_NAMES) + "lambda := class + def;\n"
    src = f"PROGRAM main\nVAR\n{decls}END_VAR\n{body}END_PROGRAM\n"
    prog, r = run(src)
    expected = {n: _value(i) * 3 for i, n in enumerate(PYTHON_NAMES)}
    expected["lambda"] = expected["class"] + expected["def"]
    assert {n: r.get(n) for n in PYTHON_NAMES} == expected
    assert r.get("LAMBDA") == r.get("lambda")  # ST names are case-insensitive
    assert_inert(prog)


def test_python_names_as_global_variables():
    decls = "".join(f"{n} : DINT := {_value(i)};\n" for i, n in enumerate(PYTHON_NAMES))
    body = "".join(f"{n} := {n} + 100;\n" for n in PYTHON_NAMES)
    src = f"VAR_GLOBAL\n{decls}END_VAR\nPROGRAM main\n{body}END_PROGRAM\n"
    prog, r = run(src, cycles=2)
    assert {n: r.get(n) for n in PYTHON_NAMES} == {n: _value(i) + 200 for i, n in enumerate(PYTHON_NAMES)}
    assert_inert(prog)


def test_python_names_as_struct_fields_and_struct_types():
    fields = "".join(f"{n} : INT := {_value(i)};\n" for i, n in enumerate(PYTHON_NAMES))
    types = "".join(f"{n} : STRUCT a : INT := {_value(i)}; END_STRUCT;\n" for i, n in enumerate(PYTHON_NAMES))
    insts = "".join(f"i_{i} : {n};\n" for i, n in enumerate(PYTHON_NAMES))
    body = (
        "".join(f"s.{n} := s.{n} * 2;\n" for n in PYTHON_NAMES)
        + "c := s;\n"
        + "".join(f"i_{i}.a := i_{i}.a + 1000;\n" for i in range(len(PYTHON_NAMES)))
    )
    src = (
        f"TYPE rec :\nSTRUCT\n{fields}END_STRUCT\nEND_TYPE\nTYPE\n{types}END_TYPE\n"
        f"PROGRAM main\nVAR\ns : rec; c : rec;\n{insts}END_VAR\n{body}END_PROGRAM\n"
    )
    prog, r = run(src)
    assert {n: r.get(f"c.{n}") for n in PYTHON_NAMES} == {n: _value(i) * 2 for i, n in enumerate(PYTHON_NAMES)}
    assert [r.get(f"i_{i}.a") for i in range(len(PYTHON_NAMES))] == [_value(i) + 1000 for i in range(len(PYTHON_NAMES))]
    assert_inert(prog)


def test_python_names_as_function_blocks_and_their_variables():
    fbs = "".join(
        f"FUNCTION_BLOCK {n}\nVAR_INPUT {n} : INT; END_VAR\nVAR_OUTPUT q : INT; END_VAR\n"
        f"VAR cnt : INT; END_VAR\ncnt := cnt + 1;\nq := {n} * 2 + cnt;\nEND_FUNCTION_BLOCK\n"
        for n in PYTHON_NAMES
    )
    insts = "".join(f"i_{i} : {n}; r_{i} : INT;\n" for i, n in enumerate(PYTHON_NAMES))
    body = "".join(f"i_{i}({n} := {_value(i)}, q => r_{i});\n" for i, n in enumerate(PYTHON_NAMES))
    src = f"{fbs}PROGRAM main\nVAR\n{insts}END_VAR\n{body}END_PROGRAM\n"
    prog, r = run(src, cycles=3)
    assert [r.get(f"r_{i}") for i in range(len(PYTHON_NAMES))] == [_value(i) * 2 + 3 for i in range(len(PYTHON_NAMES))]
    assert [r.get(f"i_{i}.{n}") for i, n in enumerate(PYTHON_NAMES)] == [_value(i) for i in range(len(PYTHON_NAMES))]
    assert_inert(prog)


def test_python_names_as_functions_and_their_parameters():
    m = len(PYTHON_NAMES)

    def p(i: int, k: int) -> str:  # the k-th parameter name of function i: other hostile names
        return PYTHON_NAMES[(i + k) % m]

    fns = "".join(
        f"FUNCTION {n} : DINT\nVAR_INPUT {p(i, 1)}, {p(i, 2)} : DINT; END_VAR\n"
        f"VAR_OUTPUT {p(i, 3)} : DINT; END_VAR\nVAR_IN_OUT {p(i, 4)} : DINT; END_VAR\n"
        f"VAR {p(i, 5)} : DINT := 1; END_VAR\n"
        f"{p(i, 3)} := {p(i, 2)}; {p(i, 4)} := {p(i, 4)} + {p(i, 5)};\n"
        f"{n} := {p(i, 1)} * 10 + {p(i, 2)};\nEND_FUNCTION\n"
        for i, n in enumerate(PYTHON_NAMES)
    )
    decls = "".join(f"r_{i} : DINT; s_{i} : DINT; c_{i} : DINT := {_value(i)};\n" for i in range(m))
    body = "".join(
        f"r_{i} := {n}({p(i, 1)} := {_value(i)}, {p(i, 2)} := 7, {p(i, 3)} => s_{i}, {p(i, 4)} := c_{i});\n"
        for i, n in enumerate(PYTHON_NAMES)
    )
    src = f"{fns}PROGRAM main\nVAR\n{decls}END_VAR\n{body}END_PROGRAM\n"
    prog, r = run(src, cycles=2)
    assert [r.get(f"r_{i}") for i in range(m)] == [_value(i) * 10 + 7 for i in range(m)]
    assert [r.get(f"s_{i}") for i in range(m)] == [7] * m
    assert [r.get(f"c_{i}") for i in range(m)] == [_value(i) + 2 for i in range(m)]
    assert_inert(prog)


def test_python_names_as_enumerations_and_their_values():
    vals = list(PYTHON_NAMES)
    enum = "TYPE lambda_e : (" + ", ".join(f"{n} := {i * 2}" for i, n in enumerate(vals)) + "); END_TYPE\n"
    types = "".join(f"TYPE {n} : (red_{i}, green_{i} := {i + 5}); END_TYPE\n" for i, n in enumerate(PYTHON_NAMES))
    decls = "e : lambda_e; hits : INT; last : INT;\n" + "".join(
        f"c_{i} : {n} := {n}#green_{i}; k_{i} : INT;\n" for i, n in enumerate(PYTHON_NAMES)
    )
    cases = "".join(f"  {n}: hits := hits + 1; last := {i};\n" for i, n in enumerate(vals))
    body = "".join(f"e := lambda_e#{n};\nCASE e OF\n{cases}END_CASE\n" for n in vals[::7]) + "".join(
        f"IF c_{i} = {n}#green_{i} THEN k_{i} := {i + 5}; END_IF\n" for i, n in enumerate(PYTHON_NAMES)
    )
    src = f"{enum}{types}PROGRAM main\nVAR\n{decls}END_VAR\n{body}END_PROGRAM\n"
    prog, r = run(src)
    assert r.get("hits") == len(vals[::7])
    assert r.get("last") == (len(vals) - 1) // 7 * 7
    assert r.get("e") == ((len(vals) - 1) // 7 * 7) * 2
    assert [r.get(f"k_{i}") for i in range(len(PYTHON_NAMES))] == [i + 5 for i in range(len(PYTHON_NAMES))]
    assert_inert(prog)


def test_python_names_as_programs():
    progs = "".join(
        f"PROGRAM {n}\nVAR self : INT := {_value(i)}; END_VAR\nself := self + 1;\nEND_PROGRAM\n"
        for i, n in enumerate(PYTHON_NAMES)
    )
    prog = compile_st(progs)
    for i, n in enumerate(PYTHON_NAMES):
        r = prog.runner(n)
        r.run(2)
        assert r.get("self") == _value(i) + 2, n
    assert_inert(prog)


def test_a_very_long_identifier():
    name = "x" * 5000
    prog, r = run(
        f"PROGRAM main\nVAR {name} : INT := 4; y : INT; END_VAR\n{name} := {name} + 1; y := {name};\nEND_PROGRAM\n"
    )
    assert r.get("y") == 5
    assert_inert(prog)


@pytest.mark.parametrize("where", ["local", "output"])
def test_a_function_variable_named_like_the_result_slot(where):
    """The generated code keeps a FUNCTION's result in a Python local: an ST
    variable must not share it, whatever its name."""
    section = {"local": "VAR", "output": "VAR_OUTPUT"}[where]
    src = f"""
FUNCTION f : INT
VAR_INPUT a : INT; END_VAR
{section} _result : INT; END_VAR
f := a * 3;
_result := 100;
END_FUNCTION
PROGRAM main
VAR r : INT; z : INT; END_VAR
r := f(a := 2);
END_PROGRAM
"""
    prog, r = run(src)
    assert r.get("r") == 6


def test_a_function_input_named_like_the_result_slot_keeps_its_value():
    src = """
FUNCTION f : INT
VAR_INPUT _result : INT; END_VAR
f := _result * 3;
END_FUNCTION
PROGRAM main
VAR r : INT; END_VAR
r := f(_result := 2);
END_PROGRAM
"""
    prog, r = run(src)
    assert r.get("r") == 6


@pytest.mark.parametrize("ch", ["\u017f", "\u212a", "\u0131", "\u0130", "\u00e9", "\u0430"])
def test_non_ascii_letters_are_not_identifiers(ch):
    # Python's re with IGNORECASE lets [a-z] match U+017F, U+212A, U+0131,
    # U+0130: the lexer must still refuse them (not crash in pyname()).
    diags, _ = check_files([], texts={"u.st": f"PROGRAM main VAR x{ch} : INT; END_VAR x{ch} := 1; END_PROGRAM"})
    assert diags and all(d.is_error for d in diags)
    assert {d.code for d in diags} <= {"E001", "E002"}


# ---------------------------------------------------------------- strings

HOSTILE_STRINGS = [
    "'); import os; os.system(\"x\"); ('",
    "\"); import os; os.system('x'); (\"",
    "'",
    "''",
    "'''",
    '"',
    '"""',
    '\\"\\"\\"',
    "\\'",
    '\\n__import__("os")',
    "a\nimport os\nos.system('x')\n",
    "C:\\temp\\new\\",
    "\\",
    "\\\\",
    "\\x41\\u0041\\N{BULLET}",
    "{}",
    "{0}",
    "{__import__('os').system('x')}",
    "%s",
    "%(x)s%%",
    "$",
    "$N",
    "$$",
    "\x00",
    "\x00import os",
    "\x7f",
    "\r\n",
    "\t",
    "# not a comment",
    '"""; import os; """',
    "\u00e9\u00fc\u00df",
    "\u2028",
    "\ufeff",
    "x" * 250,
]


@pytest.mark.parametrize("text", HOSTILE_STRINGS, ids=[repr(s)[:30] for s in HOSTILE_STRINGS])
def test_hostile_string_literals_hold_exactly_their_text(text):
    lit = st_quote(text)
    n = max(len(text) + 1, 2)
    src = f"""
VAR_GLOBAL CONSTANT K : STRING[{n}] := {lit}; END_VAR
TYPE holder : STRUCT s : STRING[{n}] := {lit}; END_STRUCT END_TYPE
FUNCTION echo : STRING[{n + 1}]
VAR_INPUT s : STRING[{n}] := {lit}; END_VAR
echo := s;
END_FUNCTION
PROGRAM main
VAR
    init : STRING[{n}] := {lit};
    assigned : STRING[{n}];
    joined : STRING[{n + 1}];
    arr : ARRAY[1..2] OF STRING[{n}] := [{lit}, {lit}];
    h : holder;
    h2 : holder := (s := {lit});
    fromconst : STRING[{n}];
    viafn : STRING[{n + 1}];
    defaulted : STRING[{n + 1}];
    typed : STRING[{n}];
    same : BOOL;
    w : WSTRING[{n}] := {st_quote(text, '"')};
    wassigned : WSTRING[{n}];
END_VAR
assigned := {lit};
joined := CONCAT({lit}, 'z');
fromconst := K;
viafn := echo(s := {lit});
defaulted := echo();
typed := STRING#{lit};
same := assigned = {lit};
wassigned := {st_quote(text, '"')};
END_PROGRAM
"""
    prog, r = run(src)
    for var in (
        "init",
        "assigned",
        "arr[1]",
        "h.s",
        "h2.s",
        "fromconst",
        "viafn",
        "defaulted",
        "typed",
        "w",
        "wassigned",
    ):
        if var == "arr[1]":
            got = r.get("arr")[0]
        else:
            got = r.get(var)
        assert got == text, f"{var}: {got!r} != {text!r}"
    assert r.get("arr") == [text, text]
    assert r.get("joined") == text + "z"
    assert r.get("same") is True
    assert_inert(prog, strings=(text, "z", text + "z"))


@settings(max_examples=20, deadline=None, derandomize=True, database=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.text(st.characters(exclude_categories=("Cs",)), max_size=40))
def test_any_text_round_trips_through_a_string_literal(text):
    n = max(len(text), 1)
    nw = max(len(text.encode("utf-16-le")) // 2, 1)  # a WSTRING's length counts UTF-16 units
    src = f"""PROGRAM main
VAR s : STRING[{n}] := {st_quote(text)}; w : WSTRING[{nw}] := {st_quote(text, '"')}; t : STRING[{n}]; END_VAR
t := {st_quote(text)};
END_PROGRAM
"""
    prog, r = run(src)
    assert (r.get("s"), r.get("w"), r.get("t")) == (text, text, text)
    assert_inert(prog, strings=(text,))


def test_string_escapes_mean_what_the_standard_says():
    src = """PROGRAM main
VAR a : STRING; b : STRING; c : WSTRING; d : STRING; END_VAR
a := '$'$$$L$N$P$R$T$0A$41';
b := 'it$'s a "test"';
c := "$"$0041$00e9'";
d := '\\n\\t\\0';
END_PROGRAM
"""
    prog, r = run(src)
    assert r.get("a") == "'$\n\n\f\r\t\nA"
    assert r.get("b") == 'it\'s a "test"'
    assert r.get("c") == "\"A\u00e9'"
    assert r.get("d") == "\\n\\t\\0"
    assert_inert(prog, strings=("'$\n\n\f\r\t\nA", 'it\'s a "test"', "\"A\u00e9'", "\\n\\t\\0"))


# ---------------------------------------------------------------- comments and pragmas

COMMENT_PAYLOADS = """
(* __import__('os').system('PWNED_1') *)
// import os; os.system('PWNED_2')
/* exec("PWNED_3") */
{ import os }
{ __import__('os').system('PWNED_4') }
{attribute 'PWNED_5' := '__import__("os")'}
(* nested (* __import__('os').system('PWNED_6') *) still a comment: eval('PWNED_7') *)
"""


def test_comments_and_pragmas_never_reach_the_generated_source():
    body_payload = COMMENT_PAYLOADS.replace("\n", "\n    ")
    src = f"""{COMMENT_PAYLOADS}
TYPE rec : STRUCT {COMMENT_PAYLOADS} a : INT; END_STRUCT END_TYPE
{{ import os }}
FUNCTION_BLOCK fb {COMMENT_PAYLOADS}
VAR_INPUT i : INT; {COMMENT_PAYLOADS} END_VAR
VAR_OUTPUT q : INT; END_VAR
q := i {COMMENT_PAYLOADS} + 1;
END_FUNCTION_BLOCK
{{external}}
FUNCTION f : INT {COMMENT_PAYLOADS}
f := 41;
END_FUNCTION
PROGRAM main
VAR {COMMENT_PAYLOADS}
    x : INT; (* import os *) y : INT := 1 (* , z : INT *); s : STRING := '(* not a comment *)';
    t : STRING := '// nor this'; u : STRING := '{{ nor this }}'; inst : fb; r : rec;
END_VAR
{body_payload}
x := f() {COMMENT_PAYLOADS} + y;
IF x > 0 THEN {COMMENT_PAYLOADS} inst(i := x); END_IF
r.a := inst.q;
{COMMENT_PAYLOADS}
END_PROGRAM
{COMMENT_PAYLOADS}
"""
    prog, r = run(src)
    assert r.get("x") == 42 and r.get("r.a") == 43
    assert r.get("s") == "(* not a comment *)" and r.get("t") == "// nor this" and r.get("u") == "{ nor this }"
    source = prog.python_source
    for marker in ("PWNED", "__import__", "import os", "system", "exec(", "eval(", "attribute"):
        # (the libraries' own code may contain a word such as 'system'; the program adds none)
        assert source.count(marker) == LIBRARY_SOURCE.count(marker), marker
    assert_inert(prog, strings=("(* not a comment *)", "// nor this", "{ nor this }"))


# ---------------------------------------------------------------- file names


@pytest.mark.parametrize(
    "path",
    [
        "x'); import os; os.system('PWNED'); ('.st",
        "__import__('os').st",
        "lambda.st",
        "1 import os.st",
        "\n\nimport os\n.st",
        "../../etc/passwd",
    ],
)
def test_hostile_file_names_are_data(path):
    # a file of bare statements becomes a PROGRAM named after the file
    prog = compile_files([], texts={path: "%MW10 := %MW10 + 1;\n"}, profile="schneider")
    (name,) = prog.pous
    assert IDENT_RE.match(name)
    r = prog.runner(name)
    r.run(3)
    assert r.ctx.image is not None
    source = prog.python_source
    assert "PWNED" not in source and "__import__" not in source and "etc" not in source
    assert_inert(prog)


def test_a_hostile_file_name_is_reported_as_is_in_diagnostics():
    path = "x'); import os; ('.st"
    diags, _ = check_files([], texts={path: "PROGRAM main x := ; END_PROGRAM"})
    assert diags and {d.pos.file for d in diags} == {path}
