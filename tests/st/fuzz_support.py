"""What the fuzz tests of the ST front end share (test_fuzz.py,
test_fuzz_nesting.py): their hypothesis settings, the token pools the
mutations draw from, and the check that a source gives well-formed
diagnostics or compiles and runs."""

from __future__ import annotations

import os
import re

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, settings  # noqa: E402

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


# ---------------------------------------------------------------- helpers

_TOKEN = re.compile(
    r"""\s+|\(\*.*?\*\)|'(?:[^'$\n]|\$.)*'|"(?:[^"$\n]|\$.)*"|%[A-Za-z]+[0-9.]*(?::X?\d+)?"""
    r"""|[A-Za-z_]\w*#[-+\w.:']+|[A-Za-z_]\w*|\d[\w.#]*|:=|=>|<=|>=|<>|\*\*|\.\.|.""",
    re.S,
)
IDENT_RE = re.compile(r"[A-Za-z_]\w*\Z")

KEYWORDS = """PROGRAM END_PROGRAM FUNCTION END_FUNCTION FUNCTION_BLOCK END_FUNCTION_BLOCK TYPE END_TYPE
STRUCT END_STRUCT ARRAY OF STRING WSTRING REF_TO POINTER TO VAR VAR_INPUT VAR_OUTPUT VAR_IN_OUT VAR_GLOBAL
VAR_EXTERNAL VAR_TEMP VAR_STAT VAR_CONFIG END_VAR CONSTANT RETAIN NON_RETAIN PERSISTENT AT IF THEN ELSIF ELSE
END_IF CASE END_CASE FOR BY DO END_FOR WHILE END_WHILE REPEAT UNTIL END_REPEAT EXIT CONTINUE RETURN AND AND_THEN
OR OR_ELSE XOR NOT MOD TRUE FALSE SET RESET CONFIGURATION END_CONFIGURATION RESOURCE END_RESOURCE TASK ON WITH
EXTENDS IMPLEMENTS REF ADR SIZEOF TIME THIS SUPER READ_VAR WRITE_VAR REFERENCE __ISVALIDREF""".split()
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
    "REFERENCE TO INT",
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
TYPE_NAMES = {t for t in TYPES if IDENT_RE.match(t)}
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


def check_and_maybe_run(profile: str, src: str, cycles: int = 3, faults: list | None = None) -> list:
    """check_files must not raise; an error-free source must compile, load
    and run (or stop with an STFault that is not an internal error, appended
    to faults when given)."""
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
            if faults is not None:
                faults.append(fault)
    return diags
