"""build_decls.py: declarations, types, POUs and configurations in the AST."""

from __future__ import annotations

from softplc.runtime.st import ast

from .parse_helpers import ok, parse, show, span

# ---------------------------------------------------------------- declarations


def test_var_blocks_and_qualifiers():
    [pou] = ok("""FUNCTION_BLOCK Fb
VAR_INPUT a, b, c : INT := 0; END_VAR
VAR_OUTPUT q : BOOL; END_VAR
VAR_IN_OUT io : ARRAY[*] OF INT; END_VAR
VAR RETAIN PERSISTENT r : DINT; END_VAR
VAR PERSISTENT p : DINT; END_VAR
VAR CONSTANT k : INT := 3; END_VAR
VAR_TEMP t : INT; END_VAR
VAR_STAT s : INT; END_VAR
VAR_EXTERNAL e : INT; END_VAR
VAR_GLOBAL g : INT; END_VAR
VAR NON_RETAIN n : INT; END_VAR
END_FUNCTION_BLOCK""").decls
    kinds = [(b.kind, b.constant, b.retain, b.persistent) for b in pou.var_blocks]
    assert kinds == [
        ("VAR_INPUT", False, False, False),
        ("VAR_OUTPUT", False, False, False),
        ("VAR_IN_OUT", False, False, False),
        ("VAR", False, True, True),
        ("VAR", False, False, True),
        ("VAR", True, False, False),
        ("VAR_TEMP", False, False, False),
        ("VAR_STAT", False, False, False),
        ("VAR_EXTERNAL", False, False, False),
        ("VAR_GLOBAL", False, False, False),
        ("VAR", False, False, False),
    ]
    a, b, c = pou.var_blocks[0].decls
    assert [d.name for d in (a, b, c)] == ["a", "b", "c"]
    assert all(d.init.value == 0 for d in (a, b, c))
    assert a.type is b.type  # one type node shared by the names of one declaration
    assert span(b) == (2, 14, 2, 29)
    assert pou.var_blocks[2].decls[0].type.ranges == [None]


def test_located_variables():
    [pou] = ok("""PROGRAM p
VAR
    start AT %IX0.0 : BOOL;
    AT %QW1 : WORD;
    AT %MW3250:X0 : BOOL;
    word AT %MW3250 : WORD := 16#00FF;
END_VAR
END_PROGRAM""").decls
    start, unnamed, bit, word = pou.var_blocks[0].decls
    assert start.location == ast.LocatedAddress("I", "X", (0, 0), None, None, "%IX0.0")
    # An unnamed located variable is named after its address (no identifier has '__').
    assert unnamed.name == "__at_QW1" and unnamed.location.text == "%QW1"
    assert bit.name == "__at_MW3250_X0" and bit.location.bit == 0
    assert word.init.value == 255


def test_types():
    sf = ok("""TYPE
    Color : (Red, Green := 5, Blue) := Green;
    Codes : (A, B) DINT;
    Mode : INT (Off := 0, On := 1);
    Percent : INT(0..100);
    Speed : REAL := 1.0;
    Name : STRING[80];
    Wide : WSTRING(10);
    Short : STRING;
    Point : STRUCT
        x, y : REAL;
        tags : ARRAY[1..N + 1, 0..3] OF STRING(20);
        sub : STRUCT_B;
    END_STRUCT;
    Grid : ARRAY[1..2] OF ARRAY[-1..1] OF Point;
    PInt : REF_TO INT;
    Raw : POINTER TO BYTE;
    Plain : STRUCT a : INT; END_STRUCT
END_TYPE""")
    t = {d.name: d for d in sf.decls}
    assert len(sf.decls) == 13
    color = t["Color"]
    assert [(n, v.value if v else None) for n, v, _ in color.spec.values] == [
        ("Red", None),
        ("Green", 5),
        ("Blue", None),
    ]
    assert color.spec.base is None and show(color.init) == "Green"
    assert t["Codes"].spec.base.name == "DINT" and [v[0] for v in t["Codes"].spec.values] == ["A", "B"]
    assert t["Mode"].spec.base.name == "INT" and [v[1].value for v in t["Mode"].spec.values] == [0, 1]
    pct = t["Percent"].spec
    assert isinstance(pct, ast.SubrangeTypeSpec) and (pct.base.name, pct.lo.value, pct.hi.value) == ("INT", 0, 100)
    assert isinstance(t["Speed"].spec, ast.NamedType) and t["Speed"].init.value == 1.0
    assert (t["Name"].spec.wide, t["Name"].spec.length.value) == (False, 80)
    assert (t["Wide"].spec.wide, t["Wide"].spec.length.value) == (True, 10)
    assert t["Short"].spec.length is None
    point = t["Point"].spec
    assert [m.name for m in point.members] == ["x", "y", "tags", "sub"]
    tags = point.members[2].type
    assert [(show(lo), show(hi)) for lo, hi in tags.ranges] == [("1", "(+ N 1)"), ("0", "3")]
    assert tags.elem.length.value == 20
    grid = t["Grid"].spec
    assert isinstance(grid.elem, ast.ArrayTypeSpec) and show(grid.elem.ranges[0][0]) == "(- 1)"
    assert grid.elem.elem.name == "Point"
    assert isinstance(t["PInt"].spec, ast.RefTypeSpec) and not t["PInt"].spec.pointer
    assert t["PInt"].spec.target.name == "INT"
    assert t["Raw"].spec.pointer and t["Raw"].spec.target.name == "BYTE"


def test_initialisers():
    [pou] = ok("""PROGRAM p
VAR
    a : ARRAY[1..5] OF INT := [1, 2, 3(0)];
    b : ARRAY[1..10] OF REAL := [10(1.5)];
    c : ARRAY[1..3] OF INT := [2(), 7];
    d : Point := (x := 1.0, y := -2.0);
    e : Line := (p1 := (x := 1), tags := [1, 2], name := 'n');
    f : ARRAY[1..2] OF Point := [(x := 1), (x := 2)];
    g : ARRAY[1..2, 1..2] OF INT := [[1, 2], [3, 4]];
    h : INT := (1 + 2) * 3;
    i : Color := Color#Red;
END_VAR
END_PROGRAM""").decls
    d = {v.name: v.init for v in pou.var_blocks[0].decls}
    assert [(c and c.value, show(v)) for c, v in d["a"].items] == [(None, "1"), (None, "2"), (3, "0")]
    assert [(c.value, v.value) for c, v in d["b"].items] == [(10, 1.5)]
    assert d["c"].items[0][0].value == 2 and d["c"].items[0][1] is None
    assert [(n, show(v)) for n, v, _ in d["d"].fields] == [("x", "1.0"), ("y", "(- 2.0)")]
    e = d["e"].fields
    assert isinstance(e[0][1], ast.StructInit) and isinstance(e[1][1], ast.ArrayInit)
    assert all(isinstance(v, ast.StructInit) for _, v in d["f"].items)
    assert all(isinstance(v, ast.ArrayInit) for _, v in d["g"].items)
    assert show(d["h"]) == "(* (+ 1 2) 3)"
    assert show(d["i"]) == "Color#Red"
    assert span(d["d"]) == (6, 18, 6, 39)


def test_pous():
    sf = ok("""FUNCTION Add : INT
VAR_INPUT a, b : INT; END_VAR
Add := a + b;
END_FUNCTION
FUNCTION NoResult
VAR_INPUT a : INT; END_VAR
;
END_FUNCTION
FUNCTION Text : STRING[20]
Text := 'x';
END_FUNCTION
FUNCTION_BLOCK Timer
VAR_INPUT IN : BOOL; END_VAR
END_FUNCTION_BLOCK
PROGRAM Main
VAR t : Timer; END_VAR
t(IN := TRUE);
END_PROGRAM;
""")
    add, noresult, text, timer, main = sf.decls
    assert (add.kind, add.name, add.return_type.name) == ("FUNCTION", "Add", "INT")
    assert noresult.return_type is None and noresult.body == []
    assert text.return_type.length.value == 20
    assert (timer.kind, main.kind) == ("FUNCTION_BLOCK", "PROGRAM")
    assert span(add) == (1, 1, 4, 13)
    assert span(main) == (15, 1, 18, 12)


def test_extends_and_implements_are_kept_for_the_checker():
    sf, diags = parse("FUNCTION_BLOCK B EXTENDS A IMPLEMENTS I1, Lib.I2\nVAR x : INT; END_VAR\nEND_FUNCTION_BLOCK")
    [fb] = sf.decls
    assert fb.name == "B" and len(fb.var_blocks) == 1 and diags == []
    assert fb.extends[0] == "A" and [n for n, _pos in fb.implements] == ["I1", "Lib.I2"]
    assert fb.implements[1][1].col == 43


def test_global_variable_lists_and_type_blocks_stand_alone():
    sf = ok("VAR_GLOBAL CONSTANT N : INT := 10; END_VAR\nVAR_GLOBAL x : INT; END_VAR\nTYPE T : INT; END_TYPE\n")
    g1, g2, t = sf.decls
    assert isinstance(g1, ast.VarBlock) and g1.kind == "VAR_GLOBAL" and g1.constant
    assert isinstance(g2, ast.VarBlock) and isinstance(t, ast.TypeDecl)
    sf, diags = parse("VAR x : INT; END_VAR\nVAR_CONFIG a.b AT %QX0.0 : BOOL; END_VAR\nTYPE T : INT; END_TYPE")
    assert [(d.code, d.pos.line) for d in diags] == [("E005", 1), ("E005", 2)]
    assert "outside a POU" in diags[0].message
    # Reported and left out: later stages only see what can stand.
    assert [type(x) for x in sf.decls] == [ast.TypeDecl]


def test_qualified_names_only_in_var_config():
    sf = ok("CONFIGURATION c\nVAR_CONFIG inst.x AT %QX1.0 : BOOL; END_VAR\nEND_CONFIGURATION")
    assert sf.decls[0].var_blocks[0].decls[0].name == "inst.x"
    sf, [d] = parse("PROGRAM p VAR a.b : INT; c : INT; END_VAR END_PROGRAM")
    assert d.code == "E005" and "'a.b'" in d.message
    assert [v.name for v in sf.decls[0].var_blocks[0].decls] == ["c"]
    sf, [d] = parse("TYPE S : STRUCT a.b : INT; c : INT; END_STRUCT END_TYPE")
    assert d.code == "E005" and [m.name for m in sf.decls[0].spec.members] == ["c"]


def test_configuration():
    sf = ok("""CONFIGURATION Plant
    VAR_GLOBAL speed : REAL; END_VAR
    RESOURCE Cpu ON PLC
        TASK Fast(INTERVAL := T#10ms, PRIORITY := 1);
        TASK Slow (interval := T#100ms, PRIORITY := 5, SINGLE := trigger);
        PROGRAM Line1 WITH Fast : Conveyor(Speed := speed, Done => ok);
        PROGRAM RETAIN Log : Logger;
    END_RESOURCE
    RESOURCE Spare
        PROGRAM Idle WITH Slow : Nothing;
    END_RESOURCE
END_CONFIGURATION
CONFIGURATION Small
    TASK T1(INTERVAL := T#1s);
    PROGRAM P WITH T1 : Main;
END_CONFIGURATION""")
    plant, small = sf.decls
    assert plant.name == "Plant" and plant.var_blocks[0].decls[0].name == "speed"
    cpu, spare = plant.resources
    assert (cpu.name, cpu.on, spare.on) == ("Cpu", "PLC", None)
    fast, slow = cpu.tasks
    assert fast.name == "Fast" and fast.params["INTERVAL"].value == 10_000_000 and fast.params["PRIORITY"].value == 1
    assert set(slow.params) == {"INTERVAL", "PRIORITY", "SINGLE"}
    line1, log = cpu.programs
    assert (line1.name, line1.task, line1.type_name, line1.retain) == ("Line1", "Fast", "Conveyor", False)
    assert [show(a) for a in line1.args] == ["Speed := speed", "Done => ok"]
    assert (log.name, log.task, log.type_name, log.retain, log.args) == ("Log", None, "Logger", True, [])
    # Without RESOURCE: one implicit resource named after the configuration.
    [res] = small.resources
    assert (res.name, res.on, [t.name for t in res.tasks], [p.name for p in res.programs]) == (
        "Small",
        None,
        ["T1"],
        ["P"],
    )
