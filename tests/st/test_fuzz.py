"""Fuzzing the ST front end: whatever the user feeds it, the compiler answers
with coded, located diagnostics, never with a Python traceback.

  * arbitrary text (control characters, NULs, unicode) goes into check_files;
  * a corpus of valid programs is mutated token-wise (spans deleted,
    duplicated, swapped; keywords, operators, literals inserted; identifiers
    renamed; types flipped; truncated). When the checker accepts a mutant,
    it must also compile, load and run (or stop with an STFault);
  * pathological nesting ends in a diagnostic, not a RecursionError.

The runs are derandomized (CI reproducible). For a deeper local run:
    SOFTPLC_FUZZ_EXAMPLES=5000 pytest tests/st/test_fuzz.py
"""

from __future__ import annotations

import os
import re

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from softplc.runtime.program import check_files, compile_files  # noqa: E402
from softplc.runtime.st.diagnostics import CompileError, Diagnostic  # noqa: E402
from softplc.runtime.st.faults import STFault  # noqa: E402

_SCALE = int(os.environ.get("SOFTPLC_FUZZ_EXAMPLES", "0"))


def fuzz_settings(examples: int):
    return settings(
        max_examples=_SCALE or examples,
        deadline=None,
        derandomize=True,
        database=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much],
    )


FILE = "fuzz.st"
CODE = re.compile(r"[EW]\d{3}\Z")


# "the compiler itself failed" (an exception caught and turned into a
# diagnostic, E009): a crash in disguise. Programs nested beyond CPython's
# limits get E006, which is a proper answer.
def is_internal_error(d) -> bool:
    return d.code == "E009"


# ---------------------------------------------------------------- corpus

CORPUS = [
    # 0: elementary types, operators, strings, bit access, typed literals
    (
        "codesys",
        """
PROGRAM main
VAR
    a : INT := 7; b : DINT := -3; c : REAL := 1.5; d : LREAL; ok : BOOL;
    w : WORD := 16#00FF; bt : BYTE := 2#1010; s : STRING[20] := 'hi $'there$''; u : UINT;
    n : DINT;
END_VAR
n := n + 1;
d := c * 2.0E1 + INT_TO_LREAL(a);
b := b + a MOD 4 - (a / 2) * 3;
ok := (a > 3) AND NOT (b = 0) OR w.3 XOR FALSE;
w := SHL(w, 1) OR WORD#16#0001;
bt := bt AND 16#0F;
s := CONCAT(s, '!');
u := UINT#5 + 2;
a := -a;
END_PROGRAM
""",
    ),
    # 1: arrays (initialiser with repetition, 2-D), FOR with BY
    (
        "codesys",
        """
PROGRAM main
VAR
    arr : ARRAY[1..5] OF INT := [1, 2, 3(7)];
    grid : ARRAY[0..2, 0..2] OF DINT;
    i : INT; j : INT; total : DINT;
END_VAR
total := 0;
FOR i := 1 TO 5 DO
    arr[i] := arr[i] + i;
    total := total + arr[i];
END_FOR
FOR i := 0 TO 2 DO
    FOR j := 2 TO 0 BY -1 DO
        grid[i, j] := i * 3 + j;
    END_FOR
END_FOR
END_PROGRAM
""",
    ),
    # 2: enums, structs, struct initialisers, CASE with lists, ranges, ELSE
    (
        "codesys",
        """
TYPE Color : (Red, Green := 5, Blue); END_TYPE
TYPE Point :
STRUCT
    x : INT := 1;
    y : INT;
    tag : Color := Color#Blue;
END_STRUCT
END_TYPE
PROGRAM main
VAR p : Point; q : Point := (x := 3, y := 4); c : Color; out : INT; k : INT; END_VAR
k := k + 1;
p.x := q.x + q.y;
CASE k OF
    1: c := Red;
    2, 3: c := Green;
    4..10: c := Blue;
ELSE
    k := 0;
END_CASE
CASE c OF
    Red: out := 1;
    Green: out := 2;
    Blue: out := 3;
END_CASE
p := q;
END_PROGRAM
""",
    ),
    # 3: a user FB, standard FBs, named inputs and outputs
    (
        "codesys",
        """
FUNCTION_BLOCK Counter
VAR_INPUT inc : BOOL; step : INT := 1; END_VAR
VAR_OUTPUT count : INT; done : BOOL; END_VAR
VAR prev : BOOL; END_VAR
IF inc AND NOT prev THEN
    count := count + step;
END_IF
prev := inc;
done := count >= 3;
END_FUNCTION_BLOCK
PROGRAM main
VAR c1 : Counter; t : TON; edge : R_TRIG; pulse : BOOL; fin : BOOL; n : INT; END_VAR
pulse := NOT pulse;
c1(inc := pulse, step := 1, done => fin);
t(IN := TRUE, PT := T#30ms);
edge(CLK := t.Q);
n := c1.count;
END_PROGRAM
""",
    ),
    # 4: a FUNCTION with outputs and in-outs, WHILE, REPEAT, EXIT, CONTINUE
    (
        "codesys",
        """
FUNCTION Collatz : INT
VAR_INPUT start : DINT; END_VAR
VAR_OUTPUT peak : DINT; END_VAR
VAR_IN_OUT calls : INT; END_VAR
VAR n : DINT; steps : INT; END_VAR
n := start; peak := n; calls := calls + 1;
WHILE n > 1 DO
    IF n MOD 2 = 0 THEN n := n / 2; ELSE n := 3 * n + 1; END_IF
    IF n > peak THEN peak := n; END_IF
    steps := steps + 1;
    IF steps > 500 THEN EXIT; END_IF
END_WHILE
Collatz := steps;
END_FUNCTION
PROGRAM main
VAR steps : INT; peak : DINT; calls : INT; k : INT; acc : INT; END_VAR
steps := Collatz(start := 27, peak => peak, calls := calls);
k := 0;
REPEAT
    k := k + 1;
    IF k = 2 THEN CONTINUE; END_IF
    acc := acc + k;
UNTIL k >= 5
END_REPEAT
END_PROGRAM
""",
    ),
    # 5: references and pointers
    (
        "codesys",
        """
PROGRAM main
VAR
    x : INT := 5; r : REF_TO INT; p : POINTER TO INT; y : INT;
    arr : ARRAY[1..3] OF INT; isnull : BOOL;
END_VAR
r := REF(x);
r^ := r^ + 1;
p := ADR(arr[2]);
p^ := 42;
y := x + p^;
isnull := r = 0;
END_PROGRAM
""",
    ),
    # 6: time and date literals, globals, constants, subranges
    (
        "codesys",
        """
VAR_GLOBAL CONSTANT LIMIT : INT := 4; END_VAR
VAR_GLOBAL g_total : DINT; END_VAR
PROGRAM main
VAR
    t : TIME := T#1s250ms; u : TIME; tod1 : TOD := TOD#12:30:00; d : DATE := D#2024-02-29;
    dt1 : DT := DT#2024-01-01-00:00:00; pct : INT(0..100) := 50; lt : LTIME := LTIME#5us;
    buf : ARRAY[1..LIMIT] OF INT; i : INT; now : TIME;
END_VAR
u := t * 2 + T#250ms - T#1m;
tod1 := tod1 + T#1h;
now := TIME();
FOR i := 1 TO LIMIT DO
    buf[i] := i * pct;
    g_total := g_total + buf[i];
END_FOR
pct := LIMIT * 10;
END_PROGRAM
""",
    ),
    # 7: Schneider located variables, bit and table addresses, C hex, SET/RESET
    (
        "schneider",
        """
PROGRAM main
VAR
    level AT %MW100 : INT;
    flag AT %M10 : BOOL;
    big : DINT;
    w : WORD;
    cnt : INT;
END_VAR
cnt := cnt + 1;
%MW3250 := 0x00FF;
%MD3220 := 16#00032004;
flag := %MW3250:X0;
IF flag AND NOT %M101 THEN
    level := level + 1;
    SET %M101;
END_IF
big := %MD3220;
w := INT_TO_WORD(%MW3250);
RESET %M101;
END_PROGRAM
""",
    ),
    # 8: a bare statement list (a pasted Schneider section), READ_VAR
    (
        "schneider",
        """
%MD3220 := 0x00032004; (* index/sub-index *)
IF %M101 AND NOT %MW3260:X0 THEN
  %MW3263 := 2;
  READ_VAR(ADR#0.1.SYS, 'SDO', %MD3220, 40, %MW3222:1, %MW3260:4);
  RESET %M101;
END_IF;
""",
    ),
]

# ---------------------------------------------------------------- helpers

_TOKEN = re.compile(
    r"""\s+|\(\*.*?\*\)|'(?:[^'$\n]|\$.)*'|"(?:[^"$\n]|\$.)*"|%[A-Za-z]+[0-9.]*(?::X?\d+)?"""
    r"""|[A-Za-z_]\w*#[-+\w.:']+|[A-Za-z_]\w*|\d[\w.#]*|:=|=>|<=|>=|<>|\*\*|\.\.|.""",
    re.S,
)
_IDENT = re.compile(r"[A-Za-z_]\w*\Z")

KEYWORDS = """PROGRAM END_PROGRAM FUNCTION END_FUNCTION FUNCTION_BLOCK END_FUNCTION_BLOCK TYPE END_TYPE
STRUCT END_STRUCT ARRAY OF STRING WSTRING REF_TO POINTER TO VAR VAR_INPUT VAR_OUTPUT VAR_IN_OUT VAR_GLOBAL
VAR_EXTERNAL VAR_TEMP VAR_STAT VAR_CONFIG END_VAR CONSTANT RETAIN NON_RETAIN PERSISTENT AT IF THEN ELSIF ELSE
END_IF CASE END_CASE FOR BY DO END_FOR WHILE END_WHILE REPEAT UNTIL END_REPEAT EXIT CONTINUE RETURN AND AND_THEN
OR OR_ELSE XOR NOT MOD TRUE FALSE SET RESET CONFIGURATION END_CONFIGURATION RESOURCE END_RESOURCE TASK ON WITH
EXTENDS IMPLEMENTS REF ADR SIZEOF TIME THIS SUPER READ_VAR WRITE_VAR""".split()
OPERATORS = ":= => S= R= REF= + - * / ** = <> < > <= >= & ^ ( ) [ ] , ; : . .. # { } (* *) // /* */ ' \" $".split()
LITERALS = [
    "0",
    "1",
    "-1",
    "32767",
    "32768",
    "2147483648",
    "99999999999999999999999",
    "1.5",
    "1.0E308",
    "1e999",
    "1.0E-400",
    "16#FF",
    "2#102",
    "8#777",
    "16#",
    "36#ZZ",
    "T#1s",
    "T#-5ms",
    "T#1d2h3m4s5ms",
    "T#99999999d",
    "TIME#0s",
    "LTIME#1ns",
    "TOD#25:61:00",
    "D#2024-02-30",
    "DT#2024-01-01-00:00:00",
    "INT#40000",
    "BOOL#2",
    "'abc'",
    "'$N$T$$$''",
    "'$FF'",
    "'$'",
    '"w$0041"',
    'WSTRING#"x"',
    "STRING#'s'",
    "0x1F",
    "0x",
    "%MW1",
    "%MD3220",
    "%M101",
    "%IX0.1",
    "%QW7:X3",
    "%MW3250:4",
    "%MW3250:X99",
    "%I*",
    "%MD99999999999",
    "Color#Red",
    "Color#Purple",
    "ADR#0.1.SYS",
    "NULL",
    "0.0",
    "-0.0",
    "1_000",
    "[1, 2]",
    "(x := 1)",
    "3(0)",
]
TYPES = [
    "BOOL",
    "SINT",
    "INT",
    "DINT",
    "LINT",
    "USINT",
    "UINT",
    "UDINT",
    "ULINT",
    "BYTE",
    "WORD",
    "DWORD",
    "LWORD",
    "REAL",
    "LREAL",
    "TIME",
    "LTIME",
    "DATE",
    "TOD",
    "DT",
    "STRING",
    "WSTRING",
    "STRING[3]",
    "STRING[0]",
    "ARRAY[1..2] OF INT",
    "ARRAY[2..1] OF INT",
    "ARRAY[*] OF INT",
    "REF_TO INT",
    "POINTER TO BOOL",
    "REF_TO Point",
    "TON",
    "CTU",
    "Counter",
    "Point",
    "Color",
    "INT(0..3)",
    "INT(5..1)",
    "(A, B)",
]
TYPE_NAMES = {t for t in TYPES if _IDENT.match(t)}
IDENTS = [
    "x",
    "a",
    "main",
    "Counter",
    "Point",
    "Color",
    "Red",
    "Collatz",
    "lambda",
    "class",
    "self",
    "_G",
    "_ctx",
    "_K0",
    "__import__",
    "v_x",
    "print",
    "open",
    "TON",
    "Q",
    "IN",
    "ENO",
    "EN",
    "i",
    "k",
    "n",
    "LIMIT",
    "g_total",
    "STRING",
    "REF",
    "TIME",
    "ADR",
    "CONCAT",
    "SHL",
    "INT_TO_WORD",
]

TOKEN_POOL = KEYWORDS + OPERATORS + LITERALS + TYPES + IDENTS


def tokenize(src: str) -> list:
    toks = _TOKEN.findall(src)
    assert "".join(toks) == src
    return toks


def assert_well_formed(diags, user_files=(FILE,)) -> None:
    """Every diagnostic is coded, located in a file the user wrote, and says
    something; none is an internal error in disguise."""
    for d in diags:
        assert isinstance(d, Diagnostic), repr(d)
        assert isinstance(d.code, str) and CODE.match(d.code), d
        assert d.pos.file in user_files, f"diagnostic in a file the user did not write: {d.format()}"
        assert isinstance(d.pos.line, int) and d.pos.line >= 1, d
        assert isinstance(d.pos.col, int) and d.pos.col >= 1, d
        assert isinstance(d.message, str) and d.message.strip(), d
        assert d.severity in ("error", "warning"), d
        assert (d.code[0] == "E") == d.is_error, d
        assert not is_internal_error(d), f"internal compiler error: {d.format()}"
        d.format()  # formatting never fails either


def check_and_maybe_run(profile: str, src: str, cycles: int = 3) -> list:
    """check_files must not raise; an error-free source must compile, load
    and run (or stop with an STFault that is not an internal error)."""
    diags, _sources = check_files([], profile=profile, texts={FILE: src})
    assert isinstance(diags, list)
    assert_well_formed(diags)
    if any(d.is_error for d in diags):
        return diags
    try:
        prog = compile_files([], profile=profile, texts={FILE: src})
    except CompileError as exc:  # pragma: no cover - a failure, shown in full
        raise AssertionError(f"check_files found no error but compile_files did:\n{exc.format()}") from None
    for name, kind in prog.pous.items():
        if kind != "PROGRAM":
            continue
        try:
            runner = prog.runner(name, cycle_time_ms=10)
            runner.ctx.watchdog_s = 0.05  # a mutant may loop forever: the watchdog ends it quickly
            runner.run(cycles)
        except STFault as fault:
            assert fault.kind != "internal", f"internal fault (a code generator bug): {fault}\n{src}"
    return diags


# ---------------------------------------------------------------- the corpus itself is valid


@pytest.mark.parametrize("index", range(len(CORPUS)))
def test_corpus_programs_are_valid_and_run(index):
    profile, src = CORPUS[index]
    diags = check_and_maybe_run(profile, src, cycles=5)
    assert not [d for d in diags if d.is_error]
    assert len(tokenize(src)) > 20


# ---------------------------------------------------------------- arbitrary text

_ANY_CHAR = st.characters(exclude_categories=())  # any code point, lone surrogates included
_ST_ALPHABET = st.sampled_from(
    list("abcxyzABC_019 \t\n\r\0\x0b\x0c\x1b\x7f\u00e9\u00a0\u2028\u202e\ufeff'\"$#%:;=<>()[]{}*/+-.,^&@!?\\`|~")
)


@fuzz_settings(120)
@given(st.text(_ANY_CHAR, max_size=300))
def test_arbitrary_text_gives_only_diagnostics(text):
    diags, _ = check_files([], profile="codesys", texts={FILE: text})
    assert_well_formed(diags)


@fuzz_settings(80)
@given(st.text(_ST_ALPHABET, max_size=200), st.sampled_from(["codesys", "iec", "schneider", "twincat"]))
def test_punctuation_soup_gives_only_diagnostics(text, profile):
    diags, _ = check_files([], profile=profile, texts={FILE: text})
    assert_well_formed(diags)


@fuzz_settings(80)
@given(st.lists(st.sampled_from(TOKEN_POOL), max_size=60), st.sampled_from(["codesys", "schneider"]))
def test_token_salad_gives_only_diagnostics(tokens, profile):
    check_and_maybe_run(profile, " ".join(tokens))


@fuzz_settings(40)
@given(st.binary(max_size=300) | st.text(_ST_ALPHABET, max_size=200).map(lambda t: t.encode("utf-16")))
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
    elif kind in ("latin-1", "bom", "empty"):
        assert not errors
        prog = compile_files([str(path)])
        if kind == "latin-1":
            r = prog.runner("main")
            r.run(1)
            assert r.get("s") == "\u00e9t\u00e9"
    else:
        assert errors


# ---------------------------------------------------------------- mutated valid programs


def _pos(draw, toks, extra: int = 0) -> int:
    return draw(st.integers(0, max(0, len(toks) - 1 + extra)))


def _m_delete(draw, toks):
    i = _pos(draw, toks)
    del toks[i : i + draw(st.integers(1, 12))]


def _m_duplicate(draw, toks):
    i = _pos(draw, toks)
    toks[i:i] = toks[i : i + draw(st.integers(1, 20))]


def _m_swap(draw, toks):
    i, j = sorted((_pos(draw, toks), _pos(draw, toks)))
    n = draw(st.integers(1, 8))
    if i + n <= j:
        toks[i : i + n], toks[j : j + n] = toks[j : j + n], toks[i : i + n]


def _m_insert(draw, toks):
    toks.insert(_pos(draw, toks, 1), " " + draw(st.sampled_from(TOKEN_POOL)) + " ")


def _m_truncate(draw, toks):
    del toks[_pos(draw, toks) :]


def _m_rename(draw, toks):
    names = sorted({t for t in toks if _IDENT.match(t)})
    if not names:
        return
    old = draw(st.sampled_from(names))
    new = draw(st.sampled_from(IDENTS) | st.from_regex(r"[A-Za-z_][A-Za-z0-9_]{0,12}", fullmatch=True))
    if draw(st.booleans()):  # every occurrence: the program often stays valid
        toks[:] = [new if t == old else t for t in toks]
    else:
        toks[draw(st.sampled_from([i for i, t in enumerate(toks) if t == old]))] = new


def _m_flip_type(draw, toks):
    at = [i for i, t in enumerate(toks) if t.upper() in TYPE_NAMES]
    if at:
        toks[draw(st.sampled_from(at))] = draw(st.sampled_from(TYPES))


def _m_literal(draw, toks):
    at = [i for i, t in enumerate(toks) if t[:1].isdigit() or t[:1] in "'\"%" or "#" in t]
    if at:
        toks[draw(st.sampled_from(at))] = draw(st.sampled_from(LITERALS))


def _m_char(draw, toks):
    i = _pos(draw, toks, 1)
    toks.insert(i, draw(st.text(_ST_ALPHABET, min_size=1, max_size=3)))


def _m_case(draw, toks):
    i = _pos(draw, toks)
    if toks:
        toks[i] = toks[i].swapcase()


MUTATIONS = [
    _m_delete,
    _m_duplicate,
    _m_swap,
    _m_insert,
    _m_truncate,
    _m_rename,
    _m_flip_type,
    _m_literal,
    _m_char,
    _m_case,
]


@st.composite
def mutated_programs(draw):
    profile, src = CORPUS[draw(st.integers(0, len(CORPUS) - 1))]
    toks = tokenize(src)
    for _ in range(draw(st.integers(1, 4))):
        draw(st.sampled_from(MUTATIONS))(draw, toks)
    return profile, "".join(toks)


@fuzz_settings(200)
@given(mutated_programs())
def test_mutated_programs_give_diagnostics_or_run(case):
    profile, src = case
    check_and_maybe_run(profile, src)


@st.composite
def gently_mutated_programs(draw):
    """Mutations that often keep the program valid, so the code generator
    and the runtime see unusual but legal programs too."""
    profile, src = CORPUS[draw(st.integers(0, len(CORPUS) - 1))]
    toks = tokenize(src)
    for _ in range(draw(st.integers(1, 3))):
        draw(st.sampled_from([_m_rename, _m_flip_type, _m_literal, _m_case]))(draw, toks)
    return profile, "".join(toks)


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


# ---------------------------------------------------------------- pathological nesting


def _prog(body: str, decls: str = "x : DINT;") -> str:
    return f"PROGRAM main\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"


@pytest.mark.parametrize("depth", [50, 5000])
def test_deeply_nested_parentheses(depth):
    src = _prog(f"x := {'(' * depth}1{')' * depth};")
    diags = check_and_maybe_run("codesys", src, cycles=1)
    if depth >= 5000:
        assert [d for d in diags if d.is_error], "5000 levels should be refused with a diagnostic"


@pytest.mark.parametrize("depth", [2000])
def test_deeply_nested_ifs(depth):
    body = "IF x < 10 THEN x := x + 1;\n" * depth + "END_IF;\n" * depth
    diags = check_and_maybe_run("codesys", _prog(body), cycles=1)
    assert [d for d in diags if d.is_error]


# Shapes the ST front end may accept but whose straightforward Python
# translation exceeds a CPython limit: 20 statically nested loops
# ("too many statically nested blocks"), 100 indentation levels, 200 nested
# brackets in one expression, the compiler's recursion limit. The compiler
# must refuse them with a diagnostic or generate code that Python accepts.
def _nested(open_: str, close: str, n: int) -> str:
    return open_ * n + close * n


BEYOND_PYTHON_LIMITS = {
    "21 nested WHILE": lambda: _nested("WHILE x < 0 DO\n", "END_WHILE\n", 21),
    "21 nested REPEAT": lambda: _nested("REPEAT\n", "UNTIL TRUE END_REPEAT\n", 21),
    "21 nested FOR": lambda: (
        "".join(f"FOR i{k} := 1 TO 1 DO\n" for k in range(21)) + "x := x + 1;\n" + "END_FOR\n" * 21
    ),
    "25 mixed loops": lambda: _nested("WHILE x < 0 DO\nREPEAT\n", "UNTIL TRUE END_REPEAT\nEND_WHILE\n", 13),
    "98 nested IF": lambda: _nested("IF x < 1000 THEN x := x + 1;\n", "END_IF;\n", 98),
    "98 nested CASE": lambda: _nested("CASE x OF 0..1000: x := x + 1;\n", "END_CASE\n", 98),
    "98 nested IF/ELSE": lambda: _nested("IF x > 1000 THEN x := 0; ELSE\n", "END_IF;\n", 98),
    "200 unary minus": lambda: f"x := {'-' * 200}x;",
    "200 spaced unary minus": lambda: f"x := {'- ' * 200}x;",
    "210 NOT": lambda: f"b := {'NOT ' * 210}b;",
    "200-term sum": lambda: "x := " + " + ".join(["x"] * 200) + ";",
    "200-term difference": lambda: "x := " + " - ".join(["x"] * 200) + ";",
    "210-term AND": lambda: "b := " + " AND ".join(["b"] * 210) + ";",
    "210-term power": lambda: "r := " + " ** ".join(["r"] * 210) + ";",
    "200 nested sums": lambda: "x := " + "(x + " * 200 + "x" + ")" * 200 + ";",
    "200 nested ABS": lambda: f"x := {'ABS(' * 200}x{')' * 200};",
    "110 nested indices": lambda: f"x := {'a[' * 110}1{']' * 110};",
    "4000 ELSIF": lambda: "IF x = 0 THEN x := 1;\n" + "ELSIF x = 1 THEN x := 2;\n" * 4000 + "END_IF",
}
_LIMIT_DECLS = "x : DINT; b : BOOL; r : LREAL := 1.0; a : ARRAY[1..2] OF DINT := [1, 1]; " + " ".join(
    f"i{k} : INT;" for k in range(21)
)


@pytest.mark.parametrize("shape", list(BEYOND_PYTHON_LIMITS))
def test_programs_beyond_cpython_compiler_limits(shape):
    check_and_maybe_run("codesys", _prog(BEYOND_PYTHON_LIMITS[shape](), _LIMIT_DECLS), cycles=1)


@pytest.mark.parametrize(
    "body,var,expected",
    [
        ("".join(f"FOR i{k} := 1 TO 1 DO\n" for k in range(18)) + "x := x + 1;\n" + "END_FOR\n" * 18, "x", 1),
        (_nested("WHILE x < 1 DO\n", "x := x + 1; END_WHILE\n", 18), "x", 18),
        (_nested("IF x < 1000 THEN x := x + 1;\n", "END_IF;\n", 60), "x", 60),
        ("x := 2; x := " + " + ".join(["x"] * 150) + ";", "x", 300),
        ("x := 3; x := " + "-" * 100 + "x;", "x", 3),
        ("b := " + "NOT " * 101 + "b;", "b", True),
        (
            "x := 7; IF x = 0 THEN x := 1;\n"
            + "".join(f"ELSIF x = {k} THEN x := {k * 10};\n" for k in range(1, 1000))
            + "END_IF",
            "x",
            70,
        ),
    ],
    ids=["18 FOR", "18 WHILE", "60 IF", "150-term sum", "100 minus", "101 NOT", "1000 ELSIF"],
)
def test_deep_but_reasonable_programs_still_compile_and_compute(body, var, expected):
    diags = check_and_maybe_run("codesys", _prog(body, _LIMIT_DECLS), cycles=1)
    assert not [d for d in diags if d.is_error], [d.format() for d in diags]
    r = compile_files([], texts={FILE: _prog(body, _LIMIT_DECLS)}).runner("main")
    r.run(1)
    assert r.get(var) == expected


@pytest.mark.parametrize(
    "build",
    [
        lambda n: f"x := {'-' * n}1;",  # unary chain
        lambda n: f"x := {'NOT ' * n}TRUE;",
        lambda n: "x := " + " + ".join(["1"] * n) + ";",  # long flat (left-assoc) chain
        lambda n: "x := 2" + " ** 1" * n + ";",
        lambda n: "WHILE x < 0 DO\n" * n + "END_WHILE\n" * n,
        lambda n: "CASE x OF 1:\n" * n + "END_CASE\n" * n,
        lambda n: "FOR x := 1 TO 2 DO\n" * n + "END_FOR\n" * n,
        lambda n: "REPEAT\n" * n + "UNTIL TRUE END_REPEAT\n" * n,
        lambda n: f"x := {'ABS(' * n}1{')' * n};",  # nested calls
        lambda n: "x := a" + "[1]" * n + ";",
        lambda n: "x := a" + "^" * n + ";",
        lambda n: "x := s" + ".f" * n + ";",
        lambda n: "(*" * n + "*)" * n,  # nested comments
        lambda n: "(" * n,  # never closed
        lambda n: "IF TRUE THEN " * n,  # never closed
        lambda n: "x := " + "[" * n,
    ],
    ids=[
        "neg",
        "not",
        "sum",
        "pow",
        "while",
        "case",
        "for",
        "repeat",
        "calls",
        "index",
        "deref",
        "member",
        "comments",
        "open-parens",
        "open-ifs",
        "open-brackets",
    ],
)
def test_other_pathological_shapes(build):
    check_and_maybe_run("codesys", _prog(build(3000)), cycles=1)


def test_deep_nesting_of_types_and_initialisers():
    n = 2000
    decls = f"a : {'ARRAY[1..1] OF ' * n}INT; b : ARRAY[1..1] OF INT := {'[' * n}1{']' * n}; c : {'REF_TO ' * n}INT;"
    check_and_maybe_run("codesys", _prog("x := 1;", decls), cycles=1)


def test_many_declarations_and_statements():
    decls = "".join(f"v{i} : INT := {i % 100};\n" for i in range(3000))
    body = "".join(f"v{i} := v{i - 1} + 1;\n" for i in range(1, 3000))
    r = compile_files([], texts={FILE: _prog(body, decls)}).runner("main")
    r.run(1)
    assert r.get("v2999") == 2999


def test_huge_literals_and_lines():
    src = _prog("x := " + "9" * 5000 + ";\ns := '" + "a" * 100_000 + "';\n", "x : DINT; s : STRING[255];")
    diags = check_and_maybe_run("codesys", src, cycles=1)
    assert [d for d in diags if d.is_error]  # 9999... does not fit a DINT


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
