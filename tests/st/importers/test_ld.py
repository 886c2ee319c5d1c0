"""LD bodies in PLCopen XML (runtime/st/importers/ld.py): rungs of contacts
(NO, NC, P, N, in series and parallel), coils (plain, negated, SET, RESET,
P, N, chained) and a timer block run in virtual time as the same logic
written in ST; the contacts wired to an SFC transition give its condition
(network.condition); errors point at the element."""

from __future__ import annotations

from pathlib import Path

from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.importers.bodies import BodyOut
from softplc.runtime.st.importers.network import Graph, condition
from softplc.runtime.st.importers.view import LineView
from softplc.runtime.st.importers.xmlsafe import TextPositions, parse_xml

HERE = Path(__file__).parent
LD = HERE / "ld_beremiz.xml"
WATCHED = ["tick", "r.a", "r.b", "r.c", *(f"r.q{i}" for i in range(1, 11))]


def run(path: Path, cycles: int) -> list:
    r = compile_files([str(path)]).runner("Main", cycle_time_ms=10)
    seen = []
    for _ in range(cycles):
        r.run(1)
        seen.append({v.removeprefix("r."): r.get(v) for v in WATCHED})
    return seen


def test_ld_rungs_run_as_their_st_twin():
    got = run(LD, 40)
    assert got == run(HERE / "ld_beremiz.st", 40)
    at = {c["tick"]: c for c in got}
    for c in got:
        assert c["q1"] == (c["a"] and not c["b"])  # NO and NC in series
        assert c["q2"] == (not (c["a"] or c["c"]))  # parallel branches, negated coil
        assert c["q10"] == c["q1"]  # a contact reads the coil of the rung above, this evaluation
        assert c["q9"] != c["q8"]  # q9 takes the flow the contact had before q8's coil wrote q8
    # SET on a's rising edge (a = tick MOD 4 < 2: rises at ticks 1, 4, 8 ...), RESET while b
    # (tick MOD 7 > 4: ticks 5, 6, 12, 13 ...); the RESET rung is below: it wins at tick 12
    assert [at[t]["q3"] for t in (1, 4, 5, 6, 7, 8, 12)] == [True, True, False, False, False, True, False]
    # c = (tick MOD 5 = 1): N contact on its fall, P coil on its rise; q6 gets the flow a P coil passes on
    assert [at[t]["q4"] for t in (6, 7)] == [False, True]
    assert [(at[t]["q5"], at[t]["q6"]) for t in (6, 7)] == [(True, True), (False, False)]
    # TON in the rung (b TRUE for 20 ms at a time < PT 40 ms: never Q); its N coil never pulses
    # (F_TRIG's memory starts TRUE, as in CODESYS: Q FALSE at the first evaluation is no fall)
    assert not any(c["q7"] for c in got)


def _errors(tmp_path, text: str) -> list:
    path = tmp_path / "ld.xml"
    path.write_text(text)
    diags, _ = check_files([str(path)])
    return [d for d in diags if d.is_error]


def _position(text: str, needle: str) -> tuple:
    before = text[: text.index(needle)]
    return before.count("\n") + 1, len(before) - before.rfind("\n")


def test_an_unknown_contact_variable_points_at_the_contact(tmp_path):
    text = LD.read_text().replace("<variable>c</variable>", "<variable>cc</variable>", 1)
    errors = _errors(tmp_path, text)
    assert {(d.code, d.pos.line, d.pos.col) for d in errors} == {("E010", *_position(text, "cc</variable>"))}


def test_a_coil_with_nothing_on_its_left_is_e202_at_the_coil(tmp_path):
    text = LD.read_text().replace('<connection refLocalId="2" />', "", 1)
    [d] = _errors(tmp_path, text)
    assert d.code == "E202" and (d.pos.line, d.pos.col) == _position(text, '<coil localId="3"')


SFC = """<?xml version="1.0" encoding="utf-8"?>
<project xmlns="http://www.plcopen.org/xml/tc6_0201">
  <types><pous><pou name="Seq" pouType="program">
    <interface><localVars>
      <variable name="go"><type><BOOL /></type></variable>
      <variable name="stop"><type><BOOL /></type></variable>
    </localVars></interface>
    <body>
      <SFC>
        <step localId="1" name="Init" initialStep="true"><position x="0" y="0" /></step>
        <leftPowerRail localId="2"><position x="10" y="50" /><connectionPointOut /></leftPowerRail>
        <contact localId="3" edge="rising"><position x="40" y="50" />
          <connectionPointIn><connection refLocalId="2" /></connectionPointIn>
          <variable>go</variable>
        </contact>
        <contact localId="4" negated="true"><position x="80" y="50" />
          <connectionPointIn><connection refLocalId="3" /></connectionPointIn>
          <variable>stop</variable>
        </contact>
        <transition localId="5"><position x="120" y="50" />
          <condition>
            <connectionPointIn><connection refLocalId="4" /></connectionPointIn>
          </condition>
        </transition>
      </SFC>
    </body>
  </pou></pous></types>
</project>
"""


def test_contacts_wired_to_an_sfc_transition_give_its_condition():
    diags = DiagnosticBag()
    root = parse_xml(SFC, "seq.xml", diags)
    assert root is not None
    sfc = root.walk("SFC")[0]
    out = BodyOut(LineView(SFC.count("\n") + 1), TextPositions(SFC), "seq.xml", diags)
    point = root.walk("condition")[0].kid("connectionPointIn")
    assert point is not None
    expr = condition(Graph(sfc, out, foreign=True), point, out)
    assert expr == "_RT3.Q AND ( NOT ( stop ) )"
    assert out.decls == ["_RT3 : R_TRIG;"]
    assert out.view.plain() == "_RT3(CLK := go);\n"  # the edge memory is called before the condition
    assert not diags.has_errors


def test_a_block_in_a_rung_takes_the_flow_at_en_and_gives_it_at_eno(tmp_path):
    # rung 6 rewired: b's contact drives the TON's EN, its IN is the rail, its ENO drives q7
    text = (
        LD.read_text()
        .replace(
            '<variable formalParameter="IN">\n                  <connectionPointIn><relPosition x="0" y="30" />'
            '<connection refLocalId="51" />',
            '<variable formalParameter="EN">\n                  <connectionPointIn><relPosition x="0" y="30" />'
            '<connection refLocalId="51" /></connectionPointIn>\n                </variable>\n'
            '                <variable formalParameter="IN">\n                  <connectionPointIn>'
            '<connection refLocalId="50" />',
        )
        .replace('<coil localId="54" height="15" width="21" edge="falling">', '<coil localId="54">')
        .replace(
            '<connection refLocalId="52" formalParameter="Q" />', '<connection refLocalId="52" formalParameter="ENO" />'
        )
    )
    path = tmp_path / "eno.xml"
    path.write_text(text)
    got = run(path, 30)
    assert all(c["q7"] == c["b"] for c in got)  # ENO is EN: the flow passes when b is closed
    assert any(c["b"] for c in got) and not all(c["b"] for c in got)
