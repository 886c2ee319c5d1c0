"""Graphical SFC bodies in PLCopen XML (runtime/st/importers/sfc*.py): a
chart in the Beremiz style and one in the CODESYS style import, run in
virtual time and give, cycle after cycle, the values of the same sequence
written in textual SFC (the .st twins); problems in a chart are coded
diagnostics at its element, never a traceback."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.faults import STFault
from softplc.runtime.st.importers import st_export

HERE = Path(__file__).parent
BEREMIZ = HERE / "sfc_beremiz.xml"
CODESYS = HERE / "sfc_codesys.xml"

BEREMIZ_WATCH = [
    *(f"{s}.X" for s in ("Idle", "Run", "A", "B", "Done")),
    "Run.T",
    "lamp",
    "motor",
    "blink",
    "delayed",
    "cnt",
    "pulses",
    "stored",
    "Count.Q",
]
# cycle -> inputs set before it (10 ms a cycle)
BEREMIZ_INPUTS = {
    3: {"start": True},  # Idle -> Run
    5: {"hold": True},  # A and B wait for NOT hold
    15: {"hold": False},  # (A, B) -> Done
    20: {"start": False},  # Done -> Idle
    30: {"start": True, "abort": True},  # both leave Idle: abort, the left one, wins
    31: {"abort": False},
    35: {"start": False},
    40: {"start": True},  # Idle -> Run, where cnt >= 3 already ...
    41: {"abort": True},  # ... and abort: the left transition wins again
    45: {"abort": False, "start": False},
    50: {"start": True},
    60: {"start": False},
}
CODESYS_WATCH = ["Init.X", "Fill.X", "Rinse.X", "Fill.T", "entries", "exits", "ticks", "valve", "Fill_active.Q"]
CODESYS_INPUTS = {2: {"go": True}, 12: {"go": False}, 20: {"go": True}, 23: {"stop": True}, 24: {"stop": False}}


def put(r, path: str, value) -> None:
    holder, attr, _ty = r.program.locate(path, (r.instance,))
    setattr(holder, attr, value)


def trace(path: Path, entry: str, watch: list, inputs: dict, cycles: int) -> list:
    """The watched values after each cycle, inputs set as scheduled."""
    r = compile_files([str(path)]).runner(entry, cycle_time_ms=10)
    rows = []
    for k in range(cycles):
        for name, value in inputs.get(k, {}).items():
            put(r, name, value)
        r.run(1)
        rows.append({w: r.get(w) for w in watch})
    return rows


def active(row: dict, *steps: str) -> list:
    return [s for s in steps if row[f"{s}.X"]]


def test_the_beremiz_chart_runs_as_its_textual_twin():
    got = trace(BEREMIZ, "Main", BEREMIZ_WATCH, BEREMIZ_INPUTS, 70)
    assert got == trace(BEREMIZ.with_suffix(".st"), "Main", BEREMIZ_WATCH, BEREMIZ_INPUTS, 70)
    steps = ("Idle", "Run", "A", "B", "Done")
    assert active(got[0], *steps) == ["Idle"] and got[0]["lamp"]  # a BOOL variable as action (N)
    assert active(got[3], *steps) == ["Run"] and got[3]["motor"] and not got[3]["lamp"]  # S
    assert got[3]["pulses"] == 1 and got[5]["pulses"] == 2  # P: a pulse and its final scan
    # Count (N) ran in cycles 3, 4, 5, then Enough (cnt >= 3): a simultaneous divergence
    assert active(got[6], *steps) == ["A", "B"] and got[6]["cnt"] == 4  # and Count's final scan
    assert got[6]["blink"] and not got[11]["blink"]  # L T#50ms: cycles 6 .. 10
    assert not got[8]["delayed"] and got[9]["delayed"]  # D T#30ms
    assert active(got[14], *steps) == ["A", "B"]  # the convergence waits for NOT hold (an LD contact) ...
    assert active(got[15], *steps) == ["Done"] and not got[15]["motor"]  # R
    assert active(got[20], *steps) == ["Idle"]  # the jump back
    assert active(got[30], *steps) == ["Done"]  # abort (left, a named transition) before start
    assert active(got[40], *steps) == ["Run"] and active(got[41], *steps) == ["Done"]  # abort again, by a copy
    # ... and for tWait.Q (an FBD TON wired to the condition, called every cycle): B active 20 ms
    assert active(got[51], *steps) == ["A", "B"] and active(got[53], *steps) == ["A", "B"]
    assert active(got[54], *steps) == ["Done"]


def test_the_codesys_chart_runs_as_its_textual_twin():
    got = trace(CODESYS, "PRG_Seq", CODESYS_WATCH, CODESYS_INPUTS, 30)
    assert got == trace(CODESYS.with_suffix(".st"), "PRG_Seq", CODESYS_WATCH, CODESYS_INPUTS, 30)
    steps = ("Init", "Fill", "Rinse")
    assert active(got[1], *steps) == ["Init"] and active(got[2], *steps) == ["Fill"]
    # Fill.T >= T#50ms (an inVariable wired to the transition, as CODESYS draws it)
    assert active(got[6], *steps) == ["Fill"] and active(got[7], *steps) == ["Rinse"]
    assert got[6]["Fill.T"] == 40 and got[7]["Fill.T"] == 50
    # the step action (N) ran while Fill was active and once more; the entry and exit actions once each
    assert (got[7]["ticks"], got[8]["entries"], got[8]["exits"]) == (6, 1, 1)
    assert (got[2]["entries"], got[6]["exits"], got[7]["exits"]) == (1, 0, 1)  # entry as Fill starts, exit as it ends
    assert got[7]["valve"] and got[8]["valve"] and not got[9]["valve"]  # SL T#20ms
    assert active(got[12], *steps) == ["Init"]  # NOT go, then the jump to Init
    assert active(got[23], *steps) == ["Init"]  # stop, the right branch of Fill's divergence


def test_export_st_writes_the_textual_sfc():
    diags = DiagnosticBag()
    text = st_export(str(CODESYS), CODESYS.read_text(), diags)
    assert "TRANSITION FROM Init TO Fill := go ; END_TRANSITION" in text
    assert "STEP Fill:\n_Fill_entry(P1);\nFill_active(N);\n_Fill_exit(P0);\nEND_STEP" in text
    assert "ACTION _Fill_entry: IF _Fill_entry.Q THEN Fill_entry(); END_IF; END_ACTION" in text
    text = st_export(str(BEREMIZ), BEREMIZ.read_text(), diags)
    assert "TRANSITION Enough (PRIORITY := 4) FROM Run TO (A, B) :" in text  # a named transition, statements
    assert "TRANSITION Abort (PRIORITY := 2) FROM Run TO Done :=" in text  # its second use: a copy
    # a TON and a contact wired to the condition: the block runs in an action of the initial step
    assert "INITIAL_STEP Idle:\nlamp(N);\nT18_blocks(S);\nEND_STEP" in text
    assert "ACTION T18_blocks:\ntWait(IN := B.X, PT := T#20ms);\nEND_ACTION TRANSITION FROM (A, B) TO Done :=" in text
    assert "ACTION Run_inline1:\npulses := pulses + 1;\nEND_ACTION" in text
    assert not [d for d in diags.items if d.is_error]


def test_codesys_step_data_beside_iec_is_reported_where_it_is():
    diags, _ = check_files([str(CODESYS)])
    found = {(d.code, _line_text(CODESYS, d.pos.line).strip()) for d in diags}
    assert found == {
        ("W210", '<attribute guid="b693554c-1b01-4a8d-afde-9e3a46f7465d">T#5s</attribute>'),
        ("W212", '<Init Declare="true" Use="true" />'),
    }


def _line_text(path: Path, line: int) -> str:
    return path.read_text().split("\n")[line - 1]


def _position_of(text: str, needle: str) -> tuple:
    before = text[: text.index(needle)]
    return before.count("\n") + 1, len(before) - before.rfind("\n")


def _errors(tmp_path, text: str) -> list:
    path = tmp_path / "chart.xml"
    path.write_text(text)
    diags, _ = check_files([str(path)])
    return [d for d in diags if d.is_error]


def test_an_error_in_a_named_transition_points_at_its_own_text(tmp_path):
    text = BEREMIZ.read_text().replace("Enough := cnt >= 3;", "Enough := cnt >= three;")
    [d] = _errors(tmp_path, text)
    assert d.code == "E010" and (d.pos.line, d.pos.col) == _position_of(text, "three;")


def test_an_error_in_an_inline_condition_points_at_it(tmp_path):
    text = BEREMIZ.read_text().replace("<![CDATA[start]]>", "<![CDATA[strat]]>")
    [d] = _errors(tmp_path, text)
    assert d.code == "E010" and (d.pos.line, d.pos.col) == _position_of(text, "strat")


def test_an_error_in_a_codesys_wired_condition_points_at_its_expression(tmp_path):
    text = CODESYS.read_text().replace("<expression>stop</expression>", "<expression>stopp</expression>")
    [d] = _errors(tmp_path, text)
    assert d.code == "E010" and (d.pos.line, d.pos.col) == _position_of(text, "stopp")


# ---------------------------------------------------------------- malformed charts

HEAD = """<?xml version="1.0" encoding="utf-8"?>
<project xmlns="http://www.plcopen.org/xml/tc6_0201" xmlns:xhtml="http://www.w3.org/1999/xhtml">
  <types>
    <pous>
      <pou name="Main" pouType="program">
        <interface>
          <localVars>
            <variable name="go"><type><BOOL /></type></variable>
            <variable name="lamp"><type><BOOL /></type></variable>
          </localVars>
        </interface>
        <body>
          <SFC>
"""
TAIL = """          </SFC>
        </body>
      </pou>
    </pous>
  </types>
</project>
"""


def step(lid: int, name: str, after: int | None = None, initial: bool = False) -> str:
    cpi = f'<connectionPointIn><connection refLocalId="{after}" /></connectionPointIn>' if after is not None else ""
    return f'<step localId="{lid}" name="{name}" initialStep="{str(initial).lower()}">{cpi}</step>\n'


def transition(lid: int, after: int | None, cond: str = "go") -> str:
    cpi = f'<connectionPointIn><connection refLocalId="{after}" /></connectionPointIn>' if after is not None else ""
    return (
        f'<transition localId="{lid}">{cpi}'
        f"<condition><inline><ST><xhtml:p>{cond}</xhtml:p></ST></inline></condition></transition>\n"
    )


def jump(lid: int, after: int, target: str) -> str:
    cpi = f'<connectionPointIn><connection refLocalId="{after}" /></connectionPointIn>'
    return f'<jumpStep localId="{lid}" targetName="{target}">{cpi}</jumpStep>\n'


def chart(*elements: str) -> str:
    return HEAD + "".join(elements) + TAIL


GOOD = (step(1, "S1", None, True), transition(2, 1), step(3, "S2", 2), transition(4, 3), jump(5, 4, "S1"))


def test_the_malformed_cases_start_from_a_chart_that_compiles(tmp_path):
    assert _errors(tmp_path, chart(*GOOD)) == []


@pytest.mark.parametrize(
    ("elements", "code", "at", "message"),
    [
        # a transition with no step before it
        ((*GOOD, transition(6, None), jump(7, 6, "S2")), "E210", '<transition localId="6">', "nothing before it"),
        # one that leads nowhere
        ((*GOOD, transition(6, 3)), "E210", '<transition localId="6">', "leads to no step"),
        # a jump to an unknown step
        ((*GOOD[:4], jump(5, 4, "S9")), "E213", "<jumpStep", "'S9', which is not a step"),
        # two initial steps: the second is the error
        ((*GOOD, step(6, "S3", None, True)), "E150", '<step localId="6"', "a second INITIAL_STEP 'S3'"),
        # a connection to a localId the chart does not have
        ((*GOOD[:3], transition(4, 42), jump(5, 4, "S1")), "E211", '<transition localId="4">', "localId 42"),
        # a step right after a step
        ((*GOOD, step(6, "S3", 3)), "E211", '<step localId="6"', "a step cannot follow a step"),
        # a divergence with one branch
        (
            (
                step(1, "S1", None, True),
                '<selectionDivergence localId="2"><connectionPointIn><connection refLocalId="1" />'
                "</connectionPointIn></selectionDivergence>\n",
                transition(3, 2),
                jump(4, 3, "S1"),
            ),
            "E212",
            "<selectionDivergence",
            "fewer than two branches",
        ),
        # a macro step
        ((*GOOD, '<macroStep localId="6" name="M" />\n'), "E214", "<macroStep", "macro step"),
        # an action block's bad qualifier, and D without its duration
        (
            (
                *GOOD,
                '<actionBlock localId="6"><connectionPointIn><connection refLocalId="3" /></connectionPointIn>'
                '<action localId="0" qualifier="X"><reference name="lamp" /></action></actionBlock>\n',
            ),
            "E215",
            "<action localId",
            "the qualifier 'X'",
        ),
        (
            (
                *GOOD,
                '<actionBlock localId="6"><connectionPointIn><connection refLocalId="3" /></connectionPointIn>'
                '<action localId="0" qualifier="D"><reference name="lamp" /></action></actionBlock>\n',
            ),
            "E215",
            "<action localId",
            "takes a duration",
        ),
        # a condition wired to a graph network.py cannot evaluate: its own code
        (
            (
                step(1, "S1", None, True),
                '<block localId="9" typeName="AND"><inputVariables /><outputVariables /></block>\n',
                '<transition localId="2"><connectionPointIn><connection refLocalId="1" /></connectionPointIn>'
                '<condition><connectionPointIn><connection refLocalId="9" /></connectionPointIn></condition>'
                "</transition>\n",
                jump(3, 2, "S1"),
            ),
            "E201",
            '<connection refLocalId="9" />',
            "names no output",
        ),
        # an inline condition in another language than ST
        (
            (
                *GOOD[:3],
                transition(4, 3).replace("<ST><xhtml:p>go</xhtml:p></ST>", "<IL><xhtml:p>LD go</xhtml:p></IL>"),
                GOOD[4],
            ),
            "E216",
            "<inline><IL>",
            "an inline condition in IL",
        ),
    ],
    ids=[
        "no source",
        "no target",
        "unknown jump",
        "two initial steps",
        "unknown localId",
        "step after step",
        "one branch",
        "macro step",
        "bad qualifier",
        "D without duration",
        "wired to a broken graph",
        "inline IL condition",
    ],
)
def test_a_malformed_chart_gives_a_coded_error_at_its_element(tmp_path, elements, code, at, message):
    text = chart(*elements)
    errors = _errors(tmp_path, text)
    assert code in [d.code for d in errors], [(d.code, d.message) for d in errors]
    d = next(d for d in errors if d.code == code)
    assert message in d.message
    assert (d.pos.line, d.pos.col) == _position_of(text, at)


def test_transition_priority_attributes_and_positions_decide_a_divergence(tmp_path):
    # Idle -> (left: a) | (right: b), both TRUE: the priority attribute
    # first (lower first), then the left one
    def divergence(x_a: int, x_b: int, prio: str = "") -> str:
        return chart(
            step(1, "Idle", None, True),
            step(5, "A", 3),
            step(6, "B", 4),
            '<selectionDivergence localId="2"><connectionPointIn><connection refLocalId="1" /></connectionPointIn>'
            "</selectionDivergence>\n",
            transition(3, 2, "TRUE").replace(
                '<transition localId="3">', f'<transition localId="3"><position x="{x_a}" y="0" />'
            ),
            transition(4, 2, "TRUE").replace(
                '<transition localId="4">', f'<transition localId="4" {prio}><position x="{x_b}" y="0" />'
            ),
        )

    for x_a, x_b, prio, wins in [(10, 90, "", "A"), (90, 10, "", "B"), (10, 90, 'priority="0"', "A")]:
        path = tmp_path / f"d{x_a}{x_b}{len(prio)}.xml"
        path.write_text(divergence(x_a, x_b, prio))
        r = compile_files([str(path)]).runner("Main", cycle_time_ms=10)
        r.run(1)
        assert (r.get("A.X"), r.get("B.X")) == (wins == "A", wins == "B"), (x_a, x_b, prio)
    path.write_text(divergence(10, 90, 'priority="-1"'))  # an explicit lower priority beats the left one
    r = compile_files([str(path)]).runner("Main", cycle_time_ms=10)
    r.run(1)
    assert (r.get("A.X"), r.get("B.X")) == (False, True)


def test_no_mutation_of_the_chart_gives_a_traceback(tmp_path):
    """Every connection of the Beremiz chart pointed elsewhere, every name,
    qualifier and duration made odd, one at a time: coded diagnostics
    only (a crash would raise out of check_files)."""
    text = BEREMIZ.read_text()
    spots = [(m.start(1), m.end(1)) for m in re.finditer(r'refLocalId="(\d+)"', text)]
    assert len(spots) > 25
    odd = ["1", "12", "17", "22", "99", ""]
    variants = [text[:a] + new + text[e:] for a, e in spots for new in odd]
    for m in re.finditer(r'(?:name|targetName|qualifier|duration|localId)="([^"]*)"', text):
        for new in ("", "x y;(*", "Idle"):
            variants.append(text[: m.start(1)] + new + text[m.end(1) :])
    path = tmp_path / "mutated.xml"
    for k, variant in enumerate(variants):
        path.write_text(variant)
        diags, _ = check_files([str(path)])
        assert all(re.fullmatch(r"[EW]\d{3}", d.code) for d in diags), k


def _run(tmp_path, text: str, cycles: int, inputs: dict | None = None):
    path = tmp_path / "chart.xml"
    path.write_text(text)
    r = compile_files([str(path)]).runner("Main", cycle_time_ms=10)
    for k in range(cycles):
        for name, value in (inputs or {}).get(k, {}).items():
            put(r, name, value)
        r.run(1)
    return r


def test_a_condition_naming_no_named_transition_is_a_bool_variable(tmp_path):
    text = chart(*GOOD).replace("<inline><ST><xhtml:p>go</xhtml:p></ST></inline>", '<reference name="go" />')
    r = _run(tmp_path, text, 3)
    assert (r.get("S1.X"), r.get("S2.X")) == (True, False)
    r = _run(tmp_path, text, 3, {1: {"go": True}, 2: {"go": False}})
    assert (r.get("S1.X"), r.get("S2.X")) == (False, True)


DUPLICATE = """<addData><data name="http://www.3s-software.com/plcopenxml/sfc/element" handleUnknown="implementation">
<attributes xmlns=""><attribute guid="62e1754b-7629-4e63-9cec-10ae0c536f1f">TRUE</attribute></attributes>
</data></addData>"""


def test_a_codesys_step_drawn_twice_is_one_step(tmp_path):
    # S1 -> S2, and S2 drawn again (CODESYS's duplicate flag) -> S1: one
    # step S2 with the transitions of both drawings
    again = step(6, "S2", None).replace("</step>", DUPLICATE + "</step>")
    elements = (*GOOD[:3], again, transition(4, 6, "NOT go"), jump(5, 4, "S1"))
    r = _run(tmp_path, chart(*elements), 4, {1: {"go": True}, 3: {"go": False}})
    assert (r.get("S1.X"), r.get("S2.X")) == (True, False)
    r = _run(tmp_path, chart(*elements), 3, {1: {"go": True}})
    assert (r.get("S1.X"), r.get("S2.X")) == (False, True)
    # without the flag, the same name twice is a step declared twice
    plain = step(6, "S2", None)
    errors = _errors(tmp_path, chart(*GOOD[:3], plain, transition(4, 6, "NOT go"), jump(5, 4, "S1")))
    assert [d.code for d in errors] == ["E152"]


def test_an_error_in_a_named_transition_used_twice_points_at_its_text_for_both_uses(tmp_path):
    text = BEREMIZ.read_text().replace("<![CDATA[abort]]>", "<![CDATA[abortt]]>")
    errors = _errors(tmp_path, text)
    assert [d.code for d in errors] == ["E010", "E010"]  # its first use and its copy
    assert {(d.pos.line, d.pos.col) for d in errors} == {_position_of(text, "abortt")}


def test_a_runtime_fault_in_a_chart_points_at_its_element(tmp_path):
    # the inline action of Done divides by cnt - 8: cnt is 8 when Done is reached the third time
    text = BEREMIZ.read_text().replace("stored := stored + 1;", "stored := stored + 80 / (cnt - 8);")
    path = tmp_path / "fault.xml"
    path.write_text(text)
    r = compile_files([str(path)]).runner("Main", cycle_time_ms=10)
    with pytest.raises(STFault) as err:
        for k in range(70):
            for name, value in BEREMIZ_INPUTS.get(k, {}).items():
                put(r, name, value)
            r.run(1)
    assert err.value.kind == "division" and r.get("Done.X") and r.get("cnt") == 8
    assert (err.value.pos.file, err.value.pos.line) == (str(path), _position_of(text, "stored := stored + 80")[0])


def test_a_wired_condition_calls_the_blocks_its_blocks_read(tmp_path):
    # tWait's IN from another TON (tPre, 10 ms after B.X) instead of B.X itself:
    # both run every cycle, in data-flow order, so B stays 10 ms longer
    text = BEREMIZ.read_text()
    text = text.replace(
        '<variable name="tWait"><type><derived name="TON"/></type></variable>',
        '<variable name="tWait"><type><derived name="TON"/></type></variable>\n'
        '            <variable name="tPre"><type><derived name="TON"/></type></variable>',
    )
    tpre = """<block localId="90" width="60" height="60" typeName="TON" instanceName="tPre">
              <position x="100" y="420"/>
              <inputVariables>
                <variable formalParameter="IN"><connectionPointIn><connection refLocalId="28"/></connectionPointIn>
                </variable>
                <variable formalParameter="PT"><connectionPointIn><connection refLocalId="91"/></connectionPointIn>
                </variable>
              </inputVariables>
              <outputVariables><variable formalParameter="Q"><connectionPointOut/></variable></outputVariables>
            </block>
            <inVariable localId="91" height="30" width="60"><position x="40" y="450"/>
              <connectionPointOut/><expression>T#10ms</expression></inVariable>
            <block localId="30" """
    text = text.replace('<block localId="30" ', tpre, 1)
    text = text.replace(
        '<connection refLocalId="28"/>\n                  </connectionPointIn>\n                </variable>\n'
        '                <variable formalParameter="PT">',
        '<connection refLocalId="90" formalParameter="Q"/>\n                  </connectionPointIn>\n'
        '                </variable>\n                <variable formalParameter="PT">',
        1,
    )
    path = tmp_path / "chained.xml"
    path.write_text(text)
    got = trace(path, "Main", BEREMIZ_WATCH, BEREMIZ_INPUTS, 70)
    steps = ("Idle", "Run", "A", "B", "Done")
    assert active(got[54], *steps) == ["A", "B"]  # 20 ms would have left B here ...
    assert active(got[55], *steps) == ["Done"]  # ... 10 + 20 ms do
