"""The forms of PLCopen XML that CODESYS, TwinCAT and Beremiz write, each
in a small export of its own (runtime/st/importers/plcopen*.py): the
defects a real CODESYS export showed (issue 29), what becomes ST of an
attribute or a text and what cannot, and the coded diagnostic each
malformed element gets."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.importers import st_export, st_views
from softplc.runtime.st.importers.bodies import ImportProblem
from softplc.runtime.st.importers.plcopen_text import duration
from softplc.testing import PLC

HERE = Path(__file__).parent
CODESYS = "http://www.3s-software.com/plcopenxml/"


def export(pous: str = "", types: str = "", instances: str = "", add: str = "") -> str:
    """A PLCopen XML project holding the given parts."""
    return f"""<?xml version="1.0" encoding="utf-8"?>
<project xmlns="http://www.plcopen.org/xml/tc6_0201">
  <fileHeader companyName="softplc tests" productName="CODESYS" productVersion="3.5"
              creationDateTime="2026-11-30T09:00:00" />
  <contentHeader name="forms" />
  <types>
    <dataTypes>
{types}
    </dataTypes>
    <pous>
{pous}
    </pous>
  </types>
  <instances>
    <configurations>
{instances}
    </configurations>
  </instances>
  <addData>
{add}
  </addData>
</project>
"""


def st_body(text: str) -> str:
    """A <body> in ST."""
    return f'<body><ST><xhtml xmlns="http://www.w3.org/1999/xhtml">{text}</xhtml></ST></body>'


def program(name: str, body: str, variables: str = "") -> str:
    return f"""      <pou name="{name}" pouType="program">
        <interface>
          <localVars>
{variables}
          </localVars>
        </interface>
        <body><ST><xhtml xmlns="http://www.w3.org/1999/xhtml">{body}</xhtml></ST></body>
      </pou>"""


def var(name: str, type_xml: str, value: str | None = None, add: str = "") -> str:
    init = f'<initialValue><simpleValue value="{value}" /></initialValue>' if value is not None else ""
    return f'            <variable name="{name}"><type>{type_xml}</type>{init}{add}</variable>'


def gvl(name: str, variables: str, constant: bool = False) -> str:
    qualifier = ' constant="true"' if constant else ""
    return f'<globalVars name="{name}"{qualifier}>\n{variables}\n</globalVars>'


def data(short: str, inner: str, handle: str = "implementation") -> str:
    return f'<data name="{CODESYS}{short}" handleUnknown="{handle}">{inner}</data>'


def run(text: str, entry: str, cycles: int, *paths: str) -> dict:
    r = compile_files([], texts={"forms.xml": text}).runner(entry, cycle_time_ms=10)
    r.run(cycles)
    return {p: r.get(p) for p in paths}


def diagnostics(text: str) -> list:
    diags, _ = check_files([], texts={"forms.xml": text})
    return [(d.code, d.message) for d in diags]


# ---------------------------------------------------------------- the defects of a real CODESYS export


def test_a_string_length_and_an_array_bound_may_be_constants(tmp_path):
    """1 and 10: <string length="GVL.TOPIC_LEN"/> crashed `softplc check`
    (exit 4); upper="ciN" was refused."""
    constants = gvl("GVL", var("TOPIC_LEN", "<INT />", "8") + var("ciN", "<INT />", "3"), constant=True)
    text = export(
        program(
            "Main",
            "topic := 'abcdefghijk'; arr[GVL.ciN - 1] := LEN(topic);",
            var("topic", '<string length="GVL.TOPIC_LEN" />')
            + var("arr", '<array><dimension lower="0" upper="GVL.ciN - 1" /><baseType><INT /></baseType></array>'),
        ),
        add=data("globalvars", constants),
    )
    assert run(text, "Main", 1, "topic", "arr") == {"topic": "abcdefgh", "arr": [0, 0, 8]}
    from tests.test_cli import softplc

    path = tmp_path / "lengths.xml"
    path.write_text(text)
    r = softplc("check", path)
    assert r.returncode == 0, r.stderr


def test_inheritance_in_the_interface_add_data_is_read():
    """2: CODESYS writes EXTENDS/IMPLEMENTS into <interface><addData>."""
    base = """      <pou name="FB_Base" pouType="functionBlock">
        <interface><outputVars><variable name="n"><type><INT /></type></variable></outputVars></interface>
        <body><ST><xhtml xmlns="http://www.w3.org/1999/xhtml">n := n + 1;</xhtml></ST></body>
      </pou>"""
    derived = f"""      <pou name="FB_Derived" pouType="functionBlock">
        <interface>
          <addData>{data("pouinheritance", "<Inheritance><Extends>FB_Base</Extends></Inheritance>")}</addData>
        </interface>
        <body><ST><xhtml xmlns="http://www.w3.org/1999/xhtml">SUPER^(); SUPER^();</xhtml></ST></body>
      </pou>"""
    text = export(base + derived + program("Main", "fb();", var("fb", '<derived name="FB_Derived" />')))
    assert run(text, "Main", 3, "fb.n") == {"fb.n": 6}


def test_an_interface_in_the_project_add_data_is_imported():
    """3: INTERFACEs live in the project's addData."""
    itf = data(
        "interface",
        """<Interface name="I_Get"><Methods><Method name="Get">
             <interface><returnType><INT /></returnType></interface><addData /></Method></Methods></Interface>""",
    )
    implements = "<Inheritance><Implements>I_Get</Implements></Inheritance>"
    method = (
        f'<Method name="Get"><interface><returnType><INT /></returnType></interface>{st_body("Get := 5;")}</Method>'
    )
    fb = f"""      <pou name="FB_Five" pouType="functionBlock">
        <interface><addData>{data("pouinheritance", implements)}</addData></interface>
        {st_body("")}
        <addData>{data("method", method)}</addData>
      </pou>"""
    main = program(
        "Main",
        "itf := fb; x := itf.Get();",
        var("fb", '<derived name="FB_Five" />') + var("itf", '<derived name="I_Get" />') + var("x", "<INT />"),
    )
    assert run(export(fb + main, add=itf), "Main", 1, "x") == {"x": 5}


RESOURCE = """      <configuration name="Device">
        <resource name="Application">
          <task name="MainTask" interval="{interval}" priority="1">
            <pouInstance name="Main" typeName="{type_name}" />
          </task>
          <globalVars name="GVL">
            <variable name="g"><type><INT /></type></variable>
          </globalVars>
          <addData>
            {pou}
          </addData>
        </resource>
        <addData>
          <data name="configurations" handleUnknown="discard">
            <configurations><configuration name="Bus"><resource name="Io">
              <task name="T" interval="garbage" priority="x"><pouInstance name="P" typeName="Nope" /></task>
            </resource></configuration></configurations>
          </data>
        </addData>
      </configuration>"""


def test_a_resource_holds_the_application_as_codesys_writes_it(tmp_path):
    """4, 5, 7, 8: the POUs in the resource's addData, the device tree as
    discard data, typeName="", TC6 order (task, globalVars, pouInstance)."""
    pou = data("pou", program("Main", "GVL.g := GVL.g + 1;"))
    text = export(instances=RESOURCE.format(interval="PT0.02S", type_name="", pou=pou))
    assert diagnostics(text) == []
    st = st_export("forms.xml", text, DiagnosticBag())
    assert "PROGRAM Main\n" in st and "Bus" not in st and "Nope" not in st
    assert st.index("END_PROGRAM") < st.index("CONFIGURATION Device")  # not inside the RESOURCE
    assert "TASK MainTask(INTERVAL := T#20ms, PRIORITY := 1);\n        PROGRAM Main WITH MainTask : Main;\n" in st
    path = tmp_path / "forms.xml"
    path.write_text(text)
    with PLC.from_st([path]) as plc:
        plc.run_for("1s")
        assert plc["GVL.g"] == 50  # a 20 ms task


@pytest.mark.parametrize(
    "xsd, iec",
    [
        ("PT0.5S", "T#500ms"),
        ("PT10S", "T#10s"),
        ("PT0.05S", "T#50ms"),
        ("PT1M30S", "T#1m30s"),
        ("P1DT2H", "T#1d2h"),
        ("PT0.0005S", "T#500us"),
        ("PT0S", "T#0ms"),
        ("T#20ms", "T#20ms"),
        ("t#50ms", "t#50ms"),
        ("TIME#1s", "TIME#1s"),
    ],
)
def test_a_task_interval_is_an_xsd_duration_or_an_iec_literal(xsd, iec):
    """6: TC6 0201 types <task interval> as xsd:duration."""
    assert duration(xsd, None) == iec


@pytest.mark.parametrize(
    "bad", ["", "P", "PT", "P1Y", "P2M", "PT1.5", "10ms", "T#1s); PROGRAM x", "T#1s (*", "PT1H2S3"]
)
def test_a_task_interval_that_is_no_duration_is_e183(bad):
    with pytest.raises(ImportProblem):
        duration(bad, None)
    text = export(instances=RESOURCE.format(interval=bad, type_name="", pou=data("pou", program("Main", ""))))
    assert [c for c, _ in diagnostics(text)] == ["E183"]


def test_a_string_value_may_hold_what_opens_a_comment_elsewhere():
    """9: '//' in a string is no comment."""
    text = export(program("Main", "", var("s", "<string />", "'http://x/(*y*)/{z}'")))
    assert run(text, "Main", 1, "s") == {"s": "http://x/(*y*)/{z}"}


def test_fb_init_inputs_of_an_instance_are_read():
    """11: CODESYS writes them in the variable's inputassignments data."""
    fb = f"""      <pou name="FB_X" pouType="functionBlock">
        <interface><outputVars><variable name="n"><type><INT /></type></variable>
          <variable name="k"><type><INT /></type></variable></outputVars></interface>
        <body><ST><xhtml xmlns="http://www.w3.org/1999/xhtml">n := n + k;</xhtml></ST></body>
        <addData>{
        data(
            "method",
            '''<Method name="FB_init"><interface><returnType><BOOL /></returnType>
          <inputVars><variable name="bInitRetains"><type><BOOL /></type></variable>
          <variable name="bInCopyCode"><type><BOOL /></type></variable>
          <variable name="nStart"><type><INT /></type></variable>
          <variable name="nStep"><type><INT /></type></variable></inputVars></interface>
          <body><ST><xhtml xmlns="http://www.w3.org/1999/xhtml">n := nStart; k := nStep;</xhtml></ST></body>
          </Method>''',
        )
    }</addData>
      </pou>"""

    def assignments(*pairs: tuple) -> str:
        inner = "".join(
            "<InputAssignment>" + (f"<Name>{n}</Name>" if n else "") + f"<Value>{v}</Value></InputAssignment>"
            for n, v in pairs
        )
        return f"<addData>{data('inputassignments', f'<InputAssignments>{inner}</InputAssignments>')}</addData>"

    main = program(
        "Main",
        "a(); b();",
        var("a", '<derived name="FB_X" />', add=assignments(("nStep", "2"), ("nStart", "10")))
        + var("b", '<derived name="FB_X" />', add=assignments((None, "100"), (None, "5 * 2"))),
    )
    assert run(export(fb + main), "Main", 3, "a.n", "b.n") == {"a.n": 16, "b.n": 130}


# ---------------------------------------------------------------- the rest of CODESYS's addData


def test_unknown_add_data_is_dropped_or_reported_by_its_handle_unknown():
    unknown = data("newthing", "<New />") + data("newthing", "<Again />") + data("gadget", "<G />", "discard")
    text = export(
        program("Main", ""),
        add=unknown + data("projectstructure", "<ProjectStructure><Folder Name='f' /></ProjectStructure>", "discard"),
    )
    assert diagnostics(text) == [("W181", f"<data name='{CODESYS}newthing'> is not read by softplc")]


def test_a_struct_extends_another_of_the_file():
    base = f'<dataType name="ST_A"><baseType><struct>{var("a", "<INT />", "3")}</struct></baseType></dataType>'
    extends = data("datatypeinheritance", "<Inheritance><Extends>ST_A</Extends></Inheritance>")
    derived = f'<dataType name="ST_B"><baseType><struct>{var("b", "<INT />")}</struct></baseType>'
    derived += f"<addData>{extends}</addData></dataType>"
    text = export(program("Main", "s.b := s.a + 1;", var("s", '<derived name="ST_B" />')), types=base + derived)
    assert run(text, "Main", 1, "s.a", "s.b") == {"s.a": 3, "s.b": 4}
    cycle = derived.replace("ST_A</Extends>", "ST_B</Extends>")
    assert [c for c, _ in diagnostics(export(program("Main", ""), types=cycle))] == ["E183"]


def test_a_property_of_a_program_and_attributes_as_pragmas():
    prop = data(
        "property",
        f"""<Property name="Twice"><interface><returnType><INT /></returnType></interface>
        <GetAccessor><interface />{st_body("Twice := n * 2;")}</GetAccessor></Property>""",
    )
    hide = '<Attributes><Attribute Name="hide" Value="" /></Attributes>'
    pou = f"""      <pou name="P" pouType="program">
        <interface><localVars><variable name="n"><type><INT /></type>
          <addData>{data("attributes", hide)}</addData></variable>
          <variable name="t"><type><INT /></type></variable></localVars></interface>
        <body><ST><xhtml xmlns="http://www.w3.org/1999/xhtml">n := n + 1; t := Twice;</xhtml></ST></body>
        <addData>{prop}</addData>
      </pou>"""
    text = export(pou)
    st = st_export("forms.xml", text, DiagnosticBag())
    assert "{attribute 'hide'}\n    n : INT;" in st and "PROPERTY Twice : INT\nGET\nTwice := n * 2;\nEND_GET" in st
    assert run(text, "P", 2, "t") == {"t": 4}


def test_reference_to_as_codesys_names_it():
    text = export(
        program("Main", "r REF= x; r := 5;", var("x", "<INT />") + var("r", '<derived name="REFERENCE TO INT" />'))
    )
    assert run(text, "Main", 1, "x") == {"x": 5}


# ---------------------------------------------------------------- the project's structure


def test_a_name_declared_twice_is_e184_and_a_copy_of_a_global_is_dropped():
    twice = program("Main", "") + program("Main", "")
    assert diagnostics(export(twice))[0][0] == "E184"
    same = data("globalvars", gvl("GVL", var("g", "<INT />"))) * 2
    assert diagnostics(export(program("Main", "GVL.g := 1;"), add=same)) == []
    other = data("globalvars", gvl("GVL", var("g", "<INT />"))) + data("globalvars", gvl("GVL", var("g", "<DINT />")))
    assert [c for c, _ in diagnostics(export(program("Main", ""), add=other))] == ["E184"]


def test_an_instance_of_no_program_is_e185_and_one_of_a_refused_program_is_left_out():
    inst = RESOURCE.format(interval="T#10ms", type_name="Missing", pou="")
    assert diagnostics(export(instances=inst)) == [
        ("E185", "the program instance Main names Missing, which is no POU of this file")
    ]
    cfc = '<pou name="Main" pouType="program"><interface /><body><CFC /></body></pou>'
    assert [
        c for c, _ in diagnostics(export(cfc, instances=RESOURCE.format(interval="T#10ms", type_name="", pou="")))
    ] == ["E182"]


# ---------------------------------------------------------------- what becomes ST


def _attributed(value: str) -> str:
    attribute = f'<Attributes><Attribute Name="a" Value="{value}" /></Attributes>'
    return program("Main", "", var("v", "<INT />", add=f"<addData>{data('attributes', attribute)}</addData>"))


def _fb_init(value: str) -> str:
    inputs = (
        f"<InputAssignments><InputAssignment><Name>PT</Name><Value>{value}</Value></InputAssignment></InputAssignments>"
    )
    return program(
        "Main", "", var("v", '<derived name="TON" />', add=f"<addData>{data('inputassignments', inputs)}</addData>")
    )


INJECTIONS = [
    ("an initial value", lambda x: program("Main", "", var("v", "<INT />", x))),
    ("a string length", lambda x: program("Main", "", var("v", f'<string length="{x}" />'))),
    (
        "an array bound",
        lambda x: program(
            "Main", "", var("v", f'<array><dimension lower="0" upper="{x}" /><baseType><INT /></baseType></array>')
        ),
    ),
    ("an FB_init value", _fb_init),
    ("an address", lambda x: program("Main", "", f'<variable name="v" address="{x}"><type><BOOL /></type></variable>')),
]
HOSTILE = [
    "1; END_VAR VAR y : INT := 2",
    "1 (* y",
    "x' := 1 }",
    "{attribute 'x'} 1",
    "1 END_VAR",
    "(1",
    "1]",
    "'a'; y",
    "1 // y",
]


@pytest.mark.parametrize("hostile", HOSTILE)
@pytest.mark.parametrize("place, make", INJECTIONS, ids=[p for p, _ in INJECTIONS])
def test_no_text_of_the_file_ends_its_declaration(place, make, hostile):
    text = export(make(hostile.replace("'", "&apos;")))
    diags = DiagnosticBag()
    views = st_views("inject.xml", text, diags)
    assert [d.code for d in diags.items] == ["E183"], (place, diags.items)
    assert not any("y : INT" in v.text or "END_VAR VAR" in v.text for v in views)


def test_an_attribute_value_stays_in_its_pragma():
    text = export(_attributed("1; END_VAR VAR y : INT := 2 (* //"))
    assert diagnostics(text) == []
    assert "{attribute 'a' := '1; END_VAR VAR y : INT := 2 (* //'}\n    v : INT;" in st_export(
        "f.xml", text, DiagnosticBag()
    )


@pytest.mark.parametrize(
    "attr",
    [
        "Name=\"a' := 'b'} x : INT; {x\"",
        'Name="a b"',
        'Name="hide" Value="x}"',
    ],
)
def test_an_attribute_that_is_no_pragma_is_e183(attr):
    v = var(
        "v", "<INT />", add=f"<addData>{data('attributes', f'<Attributes><Attribute {attr} /></Attributes>')}</addData>"
    )
    assert [c for c, _ in diagnostics(export(program("Main", "", v)))] == ["E183"]


@pytest.mark.parametrize("name", ["GVL; VAR_GLOBAL x : INT", "G V", "1G"])
def test_a_list_name_that_is_no_identifier_is_e183(name):
    text = export(program("Main", ""), add=data("globalvars", gvl(name, var("g", "<INT />"))))
    assert [c for c, _ in diagnostics(text)] == ["E183"]


@pytest.mark.parametrize("depth, codes", [(20, []), (5000, ["E183"])])
def test_types_and_values_nested_deep_end_in_e183(depth, codes):
    array = '<array><dimension lower="0" upper="1" /><baseType>'
    deep_type = array * depth + "<INT />" + "</baseType></array>" * depth
    deep_value = "<arrayValue><value>" * depth + '<simpleValue value="1" />' + "</value></arrayValue>" * depth
    value = f"<initialValue>{deep_value}</initialValue>"
    text = export(program("Main", "", f'<variable name="v"><type><INT /></type>{value}</variable>'))
    found = [c for c, _ in diagnostics(export(program("Main", "", var("t", deep_type))))]
    assert found == codes
    # an INT with a nested array value: the checker's error (E024), unless the importer refuses it
    assert ("E183" in [c for c, _ in diagnostics(text)]) == bool(codes)
    chain = "".join(
        f'<dataType name="S{i}"><baseType><struct>{var(f"m{i}", "<INT />")}</struct></baseType>'
        f"<addData>{data('datatypeinheritance', f'<Inheritance><Extends>S{i + 1}</Extends></Inheritance>')}</addData>"
        "</dataType>"
        for i in range(depth)
    )
    # a chain of STRUCT EXTENDS (S0 EXTENDS S1 ...): its end is no type (E012), or too far (E183)
    assert ("E183" if codes else "E012") in [c for c, _ in diagnostics(export(program("Main", ""), types=chain))]


# ---------------------------------------------------------------- where a checker's error points


def _at(text: str, needle: str, nth: int = 0) -> tuple:
    start = -1
    for _ in range(nth + 1):
        start = text.index(needle, start + 1)
    before = text[:start]
    return before.count("\n") + 1, len(before) - before.rfind("\n")


def _errors(text: str) -> list:
    diags, _ = check_files([], texts={"forms.xml": text})
    return [(d.code, d.pos.line, d.pos.col) for d in diags if d.is_error]


def test_an_error_in_a_header_a_type_or_an_fb_init_value_points_at_its_xml():
    """EXTENDS/IMPLEMENTS stand in the interface's addData, after its
    variables; a type at its <derived>; FB_init inputs after the initial
    value in the XML and before it in ST: each error points where the XML
    has the name."""
    implements = data("pouinheritance", "<Inheritance>\n<Implements>I_Nope</Implements></Inheritance>")
    fb = f"""      <pou name="FB_A" pouType="functionBlock">
        <interface>
          <localVars>
            <variable name="x">
              <type>
                <derived name="T_Nope" />
              </type>
            </variable>
          </localVars>
          <addData>{implements}</addData>
        </interface>
        {st_body("")}
      </pou>"""
    method = (
        '<Method name="FB_init"><interface><returnType><BOOL /></returnType><inputVars>'
        + var("bInitRetains", "<BOOL />")
        + var("bInCopyCode", "<BOOL />")
        + var("nStart", "<INT />")
        + f"</inputVars></interface>{st_body('n := nStart;')}</Method>"
    )
    fb_init = f"""      <pou name="FB_I" pouType="functionBlock">
        <interface><localVars>{var("n", "<INT />")}</localVars></interface>
        {st_body("")}
        <addData>{data("method", method)}</addData>
      </pou>"""
    inputs = "<InputAssignments><InputAssignment><Name>nStart</Name>\n<Value>1 + nope</Value></InputAssignment>"
    init = '<initialValue><structValue><value member="n"><simpleValue value="2" /></value></structValue></initialValue>'
    add = f"\n{init}<addData>{data('inputassignments', inputs + '</InputAssignments>')}</addData>"
    timer = var("t", '<derived name="FB_I" />', add=add)
    text = export(fb + fb_init + program("Main", "", timer))
    found = _errors(text)
    assert ("E140", *_at(text, "I_Nope")) in found
    assert ("E012", *_at(text, "T_Nope")) in found
    assert ("E010", *_at(text, "nope<")) in found


def test_an_error_in_an_export_on_one_line_points_at_its_column():
    text = re.sub(r">\s+<", "><", (HERE / "codesys" / "project.xml").read_text())
    text = text.replace("last := GVL_Cfg.gTicks;", "last := GVL_Cfg.gTick;")
    [(code, line, col)] = _errors(text)
    assert (code, line, col) == ("E019", *_at(text, "GVL_Cfg.gTick;"))


def test_a_named_transition_in_fbd_used_twice_runs_as_in_st():
    """A named transition's body written at column 1 (an FBD network's
    statements) and copied to its second use: the views keep every line's
    placing (once a KeyError, an internal error E009)."""
    st_version = (HERE / "sfc_beremiz.xml").read_text()
    fbd = """<transition name="Abort">
            <body>
              <FBD>
                <inVariable localId="901" height="30" width="50">
                  <position x="10" y="10"/>
                  <connectionPointOut><relPosition x="50" y="15"/></connectionPointOut>
                  <expression>abort</expression>
                </inVariable>
                <outVariable localId="902" height="30" width="50">
                  <position x="100" y="10"/>
                  <connectionPointIn><relPosition x="0" y="15"/><connection refLocalId="901"/></connectionPointIn>
                  <expression>Abort</expression>
                </outVariable>
              </FBD>
            </body>
          </transition>"""
    fbd_version = re.sub(r'<transition name="Abort">.*?</transition>', fbd, st_version, count=1, flags=re.S)
    assert fbd_version != st_version
    diags, _ = check_files([], profile="matiec", texts={"sfc.xml": fbd_version})
    assert [d.code for d in diags if d.is_error] == []
    prog_fbd = compile_files([], profile="matiec", texts={"sfc.xml": fbd_version})
    prog_st = compile_files([], profile="matiec", texts={"sfc.xml": st_version})
    entry = next(name for name, kind in prog_st.pous.items() if kind == "PROGRAM")
    runs = []
    for prog in (prog_fbd, prog_st):
        r = prog.runner(entry, cycle_time_ms=10)
        r.run(30)
        runs.append(r.get("pulses"))
    assert runs[0] == runs[1]


@pytest.mark.parametrize("export_file", ["fbd_beremiz.xml", "sfc_beremiz.xml"])
@pytest.mark.parametrize("number", ["1e999", "-inf", "nan"])
def test_a_position_that_is_no_finite_number_is_no_crash(export_file, number):
    """The importers' fuzzing found it: x="1e999" on a graphical element was
    an OverflowError in int(float(...))."""
    text = re.sub(r'<position x="\d+"', f'<position x="{number}"', (HERE / export_file).read_text())
    text = re.sub(r' priority="\d+"', f' priority="{number}"', text)
    diags, _ = check_files([], profile="matiec", texts={"g.xml": text})
    assert all(d.code != "E009" for d in diags)
    assert st_export("g.xml", text, DiagnosticBag())
