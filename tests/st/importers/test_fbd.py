"""FBD bodies in PLCopen XML (runtime/st/importers/network.py, fbd.py): a
network imported from a Beremiz-style and a CODESYS-style file runs in
virtual time as the same logic written in ST; diagnostics and runtime
faults point at the XML element; a malformed graph is a coded error."""

from __future__ import annotations

from pathlib import Path

import pytest

from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.faults import STFault
from softplc.runtime.st.importers import st_export

HERE = Path(__file__).parent
BEREMIZ = HERE / "fbd_beremiz.xml"
CODESYS = HERE / "fbd_codesys.xml"
NET = ["done", "et", "notdone", "cnt", "risen", "rises", "via", "a", "s2", "y", "yok", "cnt2"]
WATCHED = ["tick", "st.k", *(f"net.{v}" for v in NET)]


def run(path: Path, cycles: int, watched: list) -> list:
    """The watched values after each of cycles cycles of 10 ms."""
    r = compile_files([str(path)]).runner("Main", cycle_time_ms=10)
    seen = []
    for _ in range(cycles):
        r.run(1)
        seen.append({v: r.get(v) for v in watched})
    return seen


def test_a_beremiz_fbd_network_runs_as_its_st_twin():
    got = run(BEREMIZ, 45, WATCHED)
    assert got == run(HERE / "fbd_beremiz.st", 45, WATCHED)
    at = {c["tick"]: c for c in got}
    # the TON: start is TRUE from tick 1 to 11 (tick MOD 20 < 12); ET counts from the first
    # call (ms), Q once ET reaches PT = 50 ms, and both drop with IN
    assert [at[t]["net.et"] for t in (1, 4, 6, 7, 12)] == [0, 30, 50, 50, 0]
    assert [at[t]["net.done"] for t in (5, 6, 11, 12)] == [False, True, True, False]
    assert [at[t]["net.notdone"] for t in (5, 6)] == [True, False]
    # cnt counts up each cycle, SEL resets it at tick 17 (feedback through an in-out variable)
    assert (at[16]["net.cnt"], at[17]["net.cnt"], at[18]["net.cnt"]) == (16, 0, 1)
    # a rising edge of pulse (every third tick) on MOVE's input; CTU counts the same edges
    assert [at[t]["net.risen"] for t in (2, 3, 4, 6)] == [False, True, False, True]
    assert at[16]["net.rises"] == 5
    # the user function with EN: y keeps its value while en is FALSE (tick 5, 10 ...)
    assert (at[4]["net.y"], at[5]["net.y"], at[5]["net.yok"]) == (8, 8, False)
    # the jump skips cnt2 every fourth tick; RETURN skips st.k likewise
    assert at[8]["net.cnt2"] == 6 and at[8]["st.k"] == 6


def test_a_value_read_by_two_outputs_is_computed_once():
    got = run(BEREMIZ, 9, WATCHED)
    # a := a + v; s2 := the same sum (not a + v again, after a changed)
    assert all(c["net.a"] == c["net.s2"] for c in got)
    assert got[-1]["net.a"] == sum(t % 7 for t in range(1, 10))


def test_the_execution_order_codesys_gives_is_followed():
    watched = ["tick", "lamp", "late", "n"]
    got = run(CODESYS, 30, watched)
    assert got == run(HERE / "fbd_codesys.st", 30, watched)
    # lamp reads t.Q before t is called: one cycle after late
    assert any(c["late"] and not c["lamp"] for c in got)
    assert [c["lamp"] for c in got[1:]] == [c["late"] for c in got[:-1]]


def test_export_st_writes_the_network_in_evaluation_order_and_it_runs_alike(tmp_path):
    text = st_export(str(BEREMIZ), BEREMIZ.read_text(), DiagnosticBag())
    lines = [ln.strip() for ln in text.splitlines()]
    call, done = lines.index("t1(IN := start, PT := T#50ms);"), lines.index("done := t1.Q;")
    assert call < done  # the outVariable comes first in the XML, after the call in ST
    assert "IF skip THEN JMP over; END_IF;" in lines and "over:" in lines
    exported = tmp_path / "exported.st"
    exported.write_text(text)
    assert run(exported, 30, WATCHED) == run(BEREMIZ, 30, WATCHED)


# ---------------------------------------------------------------- diagnostics


def _position(text: str, needle: str, after: str = "") -> tuple:
    start = text.index(after) if after else 0
    before = text[: text.index(needle, start)]
    return before.count("\n") + 1, len(before) - before.rfind("\n")


def _errors(tmp_path, text: str) -> list:
    path = tmp_path / "net.xml"
    path.write_text(text)
    diags, _ = check_files([str(path)])
    return [d for d in diags if d.is_error]


def test_an_unknown_name_in_an_input_variable_points_at_it(tmp_path):
    text = BEREMIZ.read_text().replace("<expression>pulse</expression>", "<expression>pulse OR plse</expression>")
    errors = _errors(tmp_path, text)  # one for each of the three blocks reading it
    assert {(d.code, d.pos.line, d.pos.col) for d in errors} == {("E010", *_position(text, "plse<"))}
    assert "plse" in errors[0].message


def test_a_wrong_parameter_points_at_the_block(tmp_path):
    text = BEREMIZ.read_text().replace('formalParameter="PV"', 'formalParameter="PRESET"')
    [d] = _errors(tmp_path, text)
    assert d.code == "E040" and "PRESET" in d.message
    assert (d.pos.line, d.pos.col) == _position(text, '<block localId="33"')


def test_a_division_by_zero_in_a_div_block_is_a_runtime_fault_at_the_block(tmp_path):
    text = (
        BEREMIZ.read_text()
        .replace('typeName="Scale"', 'typeName="DIV"')
        .replace('formalParameter="EN"', 'formalParameter="IN1"')
        .replace('<variable formalParameter="x">', '<variable formalParameter="IN2">')
        .replace("<expression>en</expression>", "<expression>10</expression>")
    )
    path = tmp_path / "div.xml"
    path.write_text(text)
    r = compile_files([str(path)]).runner("Main", cycle_time_ms=10)
    r.run(6)  # v = tick MOD 7: 1..6, no fault
    assert r.get("net.y") == 10 // 6
    with pytest.raises(STFault) as err:
        r.run(1)  # tick 7: v = 0
    assert err.value.kind == "division"
    assert (err.value.pos.file, err.value.pos.line) == (str(path), _position(text, '<block localId="60"')[0])


MALFORMED = [
    # (code, replaced, by, the element the error is at: its text, and a text before it)
    # a connection to a localId no element has
    ("E201", '<connection refLocalId="14" />', '<connection refLocalId="99" />', '<connection refLocalId="99"', ""),
    # an output the block does not have
    (
        "E201",
        'refLocalId="13" formalParameter="ET"',
        'refLocalId="13" formalParameter="XX"',
        '<connection refLocalId="13" formalParameter="XX"',
        "",
    ),
    # a function's input with nothing connected
    ("E202", '<connection refLocalId="25" />', "", '<variable formalParameter="IN1">', '<block localId="22"'),
    # a block without a typeName
    ("E200", 'typeName="MOVE"', "", '<block localId="30"', ""),
    # a function block without an instance name
    ("E200", 'typeName="TON" instanceName="t1"', 'typeName="TON"', '<block localId="13"', ""),
    # a localId given twice
    ("E200", '<inVariable localId="25"', '<inVariable localId="24"', '<inVariable localId="24"', "<expression>reset<"),
    # a continuation without its connector
    ("E204", '<continuation name="c"', '<continuation name="d"', '<continuation name="d"', ""),
    # a statement slipped into an expression; a comment opener
    ("E206", "<expression>reset</expression>", "<expression>reset; a := 1</expression>", "<expression>reset;", ""),
    ("E206", "<expression>reset</expression>", "<expression>reset (* x</expression>", "<expression>reset (*", ""),
]


@pytest.mark.parametrize(("code", "old", "new", "at", "after"), MALFORMED)
def test_a_malformed_network_is_a_coded_error_at_the_element(tmp_path, code, old, new, at, after):
    text = BEREMIZ.read_text()
    assert old in text
    text = text.replace(old, new, 1)
    errors = _errors(tmp_path, text)
    assert [d.code for d in errors] == [code], [(d.code, d.message) for d in errors]
    assert (errors[0].pos.line, errors[0].pos.col) == _position(text, at, after)


def test_an_output_variable_with_nothing_connected_writes_nothing(tmp_path):
    # A wire lost in Beremiz (OSCAT's port has one): its ST leaves the
    # variable out; so does softplc, with W202, and the network still runs
    text = BEREMIZ.read_text()
    old = '<connection refLocalId="13" formalParameter="ET" />'
    assert text.count(old) == 1
    text = text.replace(old, "")
    path = tmp_path / "net.xml"
    path.write_text(text)
    diags, _ = check_files([str(path)])
    [d] = diags
    assert (d.code, d.severity) == ("W202", "warning") and "nothing is written" in d.message
    assert (d.pos.line, d.pos.col) == _position(text, '<outVariable localId="11"')
    got = run(path, 8, ["net.et", "net.done"])
    want = run(BEREMIZ, 8, ["net.et", "net.done"])
    assert [c["net.done"] for c in got] == [c["net.done"] for c in want]
    assert {c["net.et"] for c in got} == {0} and want[5]["net.et"] == 50  # et is never written


def test_an_element_of_another_language_is_named(tmp_path):
    text = (
        BEREMIZ.read_text()
        .replace('<label localId="74"', '<macroStep localId="74"')
        .replace("</label>", "</macroStep>")
    )
    [d] = _errors(tmp_path, text)
    assert d.code == "E205" and "<macroStep>" in d.message
    assert (d.pos.line, d.pos.col) == _position(text, "<macroStep")


def test_an_algebraic_loop_is_reported_at_a_block_of_the_loop(tmp_path):
    # ADD reads SEL's output directly, not through the in-out variable cnt: a loop of functions alone
    text = BEREMIZ.read_text()
    start = text.index('<block localId="21"')
    text = text[:start] + text[start:].replace('refLocalId="20" />', 'refLocalId="22" formalParameter="OUT" />', 1)
    [d] = _errors(tmp_path, text)
    assert d.code == "E203"
    assert d.pos.line in (_position(text, '<block localId="21"')[0], _position(text, '<block localId="22"')[0])
