"""The ST parser: source text -> ast.SourceFile, with positions, and coded
diagnostics instead of exceptions. Here: pragmas, invalid characters, whole
files, hostile input, threads; the parts are tested beside their modules
(test_lexer, test_build_*, test_parse_stack, test_parse_recovery)."""

from __future__ import annotations

import random
import threading

import pytest

from softplc.runtime.st import ast
from softplc.runtime.st.limits import MAX_SOURCE_CHARS

from .parse_helpers import REPO, errors, ok, parse, show, span

# ---------------------------------------------------------------- pragmas


def test_pragmas_attach_to_the_item_that_follows():
    sf = ok("""{attribute 'qualified_only'}
VAR_GLOBAL
    {attribute 'hide'} g : INT;
END_VAR
TYPE
    {attribute 'strict'} Color : (Red, Green);
END_TYPE
{attribute 'call_after_init'}
FUNCTION_BLOCK Fb
{attribute 'header'}
VAR x : INT; END_VAR
{warning 'check this'}
x := 1;
{text after everything}
END_FUNCTION_BLOCK
""")
    gvl, color, fb = sf.decls
    assert gvl.pragmas == ["attribute 'qualified_only'"]
    assert gvl.decls[0].pragmas == ["attribute 'hide'"]
    assert color.pragmas == ["attribute 'strict'"]
    assert fb.pragmas == ["attribute 'call_after_init'", "attribute 'header'"]
    assert fb.body[0].pragmas == ["warning 'check this'"]
    assert not fb.external


def test_external_pragma_marks_a_declaration_only_pou():
    sf = ok("""{external}
FUNCTION_BLOCK NativeFb
VAR_INPUT IN : BOOL; END_VAR
VAR_OUTPUT Q : BOOL; END_VAR
END_FUNCTION_BLOCK
FUNCTION Native : INT
{external}
VAR_INPUT a : INT; END_VAR
END_FUNCTION
FUNCTION_BLOCK Empty
END_FUNCTION_BLOCK
""")
    fb, fn, empty = sf.decls
    assert fb.external and fb.body == [] and fb.pragmas == ["external"]
    assert fn.external and fn.body == []
    assert not empty.external and empty.body == [] and empty.var_blocks == []


# ---------------------------------------------------------------- invalid characters


def test_lexical_errors():
    diags = errors("x := 1 § 2;\nw := größe;\ns := 'open\nt := 5;\n")
    assert [(d.code, d.pos.line, d.pos.col) for d in diags] == [("E002", 1, 8), ("E002", 2, 8), ("E004", 3, 6)]
    assert diags[1].hint == "identifiers may only use ASCII letters, digits and '_'"
    [d] = errors("x := %Z1;")
    assert d.code == "E002" and d.message == "invalid direct address"


# ---------------------------------------------------------------- files of bare statements


@pytest.mark.parametrize(
    "path, name",
    [
        ("ltmr/write_sdo.st", "write_sdo"),
        ("write-sdo.st", "write_sdo"),
        ("000 first.st", "_000_first"),
        ("<string>", "string"),
        ("---.st", "main"),
    ],
)
def test_bare_statements_become_a_program_named_after_the_file(path, name):
    sf = ok("x := 1;\ny := 2;", path)
    [pou] = sf.decls
    assert (pou.kind, pou.name, len(pou.body)) == ("PROGRAM", name, 2)
    assert span(pou) == (1, 1, 2, 7)


def _check_sdo_program(sf: ast.SourceFile, name: str, md: int, mw_value: int, mw_table: int, m_cmd: int, call: str):
    [pou] = sf.decls
    assert (pou.kind, pou.name, pou.var_blocks) == ("PROGRAM", name, [])
    *first, cond_if = pou.body
    assert isinstance(first[0], ast.Assign) and show(first[0].target) == f"%MD{md}"
    assert first[0].value.c_hex and first[0].value.kind == "int"
    [(cond, stmts)] = cond_if.branches
    assert show(cond) == f"(AND %M{m_cmd} (NOT %MW{mw_table}:X0))"
    assert cond.right.operand.addr.bit == 0 and cond.right.operand.addr.indices == (mw_table,)
    timeout, call_stmt, reset = stmts
    assert show(timeout.target) == f"%MW{mw_table + 3}" and timeout.value.value == 2
    c = call_stmt.call
    assert show(c.callee) == call and len(c.args) == 6
    assert all(a.name is None and not a.output for a in c.args)
    adr, sdo, var, node, value, table = (a.value for a in c.args)
    assert isinstance(adr, ast.SchneiderAddress) and adr.parts == ("0", "1", "SYS")
    assert (sdo.kind, sdo.value) == ("string", "SDO")
    assert var.addr == ast.LocatedAddress("M", "D", (md,), None, None, f"%MD{md}")
    assert (node.kind, node.value) == ("int", 40)
    assert value.addr == ast.LocatedAddress("M", "W", (mw_value,), None, 1, f"%MW{mw_value}:1")
    assert table.addr == ast.LocatedAddress("M", "W", (mw_table,), None, 4, f"%MW{mw_table}:4")
    assert isinstance(reset, ast.SetReset) and reset.kind == "RESET" and show(reset.target) == f"%M{m_cmd}"
    assert cond_if.else_body is None


def test_ltmr_write_sdo_example_verbatim():
    path = REPO / "st_programs" / "ltmr_write_sdo.st"
    sf = ok(path.read_text(encoding="utf-8"), str(path))
    _check_sdo_program(sf, "ltmr_write_sdo", 3200, 3202, 3250, 100, "WRITE_VAR")
    [pou] = sf.decls
    assert pou.body[0].value.value == 0x00032007
    assert show(pou.body[1].target) == "%MW3202" and pou.body[1].value.value == 50
    assert span(pou.body[2]) == (12, 1, 16, 7)  # the IF, from IF to END_IF


def test_ltmr_read_sdo_example_verbatim():
    path = REPO / "st_programs" / "ltmr_read_sdo.st"
    sf = ok(path.read_text(encoding="utf-8"), str(path))
    _check_sdo_program(sf, "ltmr_read_sdo", 3220, 3222, 3260, 101, "READ_VAR")
    assert sf.decls[0].body[0].value.value == 0x00032004


def test_the_fixtures_are_the_manual_text():
    manual = REPO.parent / "shared" / "manuals" / "000_97161f374cfc3d02.txt"
    if not manual.exists():
        pytest.skip("the manuals are not beside the project")
    lines = manual.read_text(encoding="utf-8").splitlines(keepends=True)
    assert "".join(lines[997:1013]) == (REPO / "st_programs" / "ltmr_write_sdo.st").read_text(encoding="utf-8")
    assert "".join(lines[1020:1035]) == (REPO / "st_programs" / "ltmr_read_sdo.st").read_text(encoding="utf-8")


# ---------------------------------------------------------------- hostile input


@pytest.mark.parametrize(
    "src",
    [
        "",
        " \n\t ",
        "\x00" * 100,
        "x := 1;\x00",
        "\ufeffPROGRAM p END_PROGRAM",
        "(*",
        "*)",
        "'",
        '"',
        "{",
        "}",
        "%",
        "#",
        "T#",
        "16#",
        "x := \ud800;",
        "😀" * 50,
        ")))]]];;;:=:=",
        "END_IF END_PROGRAM END_VAR",
        "PROGRAM",
        "IF TRUE THEN " * 200,
        "[" * 5000,
        "(" * 10000,
        "x := " + "(" * 10000 + "1" + ")" * 10000 + ";",
        "x := " + "-" * 10000 + "1;",
        "x := " + " + ".join(["a"] * 5000) + ";",
        "x := " + "f(" * 3000 + ")" * 3000,
        "CASE x OF " * 500,
        "a" * 100_000,
        "'" + "x" * 100_000,
        "(* " * 5000 + "*)" * 5000,
    ],
)
def test_hostile_input_gives_diagnostics_not_exceptions(src):
    sf, diags = parse(src)
    assert isinstance(sf, ast.SourceFile)
    assert all(d.code[0] in "EW" and d.code != "E009" for d in diags), [d.format() for d in diags]


def test_random_bytes():
    rng = random.Random(1234)
    for _ in range(200):
        data = bytes(rng.getrandbits(8) for _ in range(rng.randint(1, 400)))
        sf, diags = parse(data.decode("latin-1"))
        assert all(d.code != "E009" for d in diags)


def test_random_token_soup():
    rng = random.Random(99)
    words = [
        "IF ",
        "THEN ",
        "ELSE ",
        "END_IF",
        "CASE ",
        "OF ",
        "END_CASE",
        "VAR ",
        "END_VAR",
        "PROGRAM ",
        "END_PROGRAM",
        "FUNCTION_BLOCK ",
        "FOR ",
        "TO ",
        "DO ",
        "END_FOR",
        "TYPE ",
        "STRUCT ",
        "(*",
        "*)",
        "x",
        "1",
        ":=",
        ";",
        ":",
        "(",
        ")",
        "[",
        "]",
        ",",
        ".",
        "..",
        "T#1s",
        "16#F",
        "%MW1",
        "'s'",
        " ",
        "\n",
        "+",
        "=",
        "=>",
        "^",
        "#",
        "SET ",
        "AT ",
    ]
    for _ in range(300):
        src = "".join(rng.choice(words) for _ in range(rng.randint(1, 80)))
        sf, diags = parse(src)
        assert all(d.code != "E009" for d in diags), src


def test_arbitrary_text_property():
    pytest.importorskip("hypothesis")
    from hypothesis import given, settings
    from hypothesis import strategies as st

    @settings(max_examples=150, deadline=None, derandomize=True, database=None)
    @given(st.text(max_size=300))
    def never_raises(text):
        sf, diags = parse(text)
        assert all(d.code != "E009" for d in diags)

    never_raises()


def test_parses_in_threads_do_not_mix():
    sources = {f"t{i}.st": f"PROGRAM P{i}\nx{i} := {i};\nEND_PROGRAM\n" * 50 for i in range(4)}
    results = {}

    def work(path):
        results[path] = parse(sources[path], path)

    threads = [threading.Thread(target=work, args=(p,)) for p in sources]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for i in range(4):
        sf, diags = results[f"t{i}.st"]
        assert not diags and len(sf.decls) == 50
        assert all(p.name == f"P{i}" and p.pos.file == f"t{i}.st" for p in sf.decls)


def test_a_file_larger_than_the_limit_is_e007_where_the_limit_is_passed():
    line = "(* " + "c" * 93 + " *)\n"  # 100 characters
    fits = line * (MAX_SOURCE_CHARS // len(line)) + "x := 1;"
    assert len(fits) <= MAX_SOURCE_CHARS
    ok(fits)
    sf, [d] = parse(line * (MAX_SOURCE_CHARS // len(line) + 1) + "x := 1;")
    assert (d.code, d.message) == ("E007", f"the file is too large: more than {MAX_SOURCE_CHARS:,} characters")
    assert (d.pos.line, d.pos.col) == (MAX_SOURCE_CHARS // len(line) + 1, MAX_SOURCE_CHARS % len(line) + 1)
    assert sf.decls == []
