"""namespaces.py: global variable lists named by their file (GVL.x), the
qualified_only and hide attributes, and the CODESYS/TwinCAT standard
library namespaces (Standard.TON, Tc2_Standard.TON)."""

from __future__ import annotations

import pytest

from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st.valuejson import encode_instance

GVL = """{attribute 'qualified_only'}
VAR_GLOBAL
    speed : INT := 5;
    {attribute 'hide'} secret : INT := 7;
END_VAR
"""

PLAIN_GVL = """VAR_GLOBAL
    level : INT := 40;
END_VAR
"""


def run(texts: dict, cycles: int = 1, profile: str = "codesys"):
    prog = compile_files([], profile=profile, texts=texts)
    runner = prog.runner("main")
    runner.run(cycles)
    return runner


def found(texts: dict, profile: str = "codesys") -> list:
    diags, _sources = check_files([], profile=profile, texts=texts)
    return [(d.code, d.pos.file, d.pos.line, d.pos.col, d.message) for d in diags]


# ---------------------------------------------------------------- global variable lists


def test_a_global_list_is_named_by_its_file_and_list_x_reaches_its_variable():
    # CODESYS: a GVL object's variables are reachable as <GVL name>.<variable>;
    # here the file GVL.st holds the list GVL.
    main = """PROGRAM main
VAR a : INT; b : INT; END_VAR
GVL.speed := GVL.speed + 1;
a := GVL.speed * 2;
b := Plant.level + plant.LEVEL;
END_PROGRAM
"""
    runner = run({"GVL.st": GVL, "plant.st": PLAIN_GVL, "main.st": main}, cycles=3)
    assert (runner.get("speed"), runner.get("a"), runner.get("b")) == (8, 16, 80)


def test_gvl_name_names_a_list_otherwise_than_its_file():
    # A PLCopen XML export holds several named lists in one file
    # (importers/plcopen.py writes {attribute 'gvl_name' := ...}); so may ST.
    lists = """{attribute 'gvl_name' := 'GVL_A'}
VAR_GLOBAL a : INT := 1; END_VAR
{attribute 'qualified_only'} {attribute 'gvl_name' := 'GVL_B'}
VAR_GLOBAL b : INT := 2; END_VAR
VAR_GLOBAL c : INT := 3; END_VAR
"""
    main = "PROGRAM main\nVAR x : INT; END_VAR\nx := GVL_A.a + GVL_B.b * 10 + lists.c * 100 + a;\nEND_PROGRAM\n"
    assert run({"lists.st": lists, "main.st": main}).get("x") == 322
    wrong = "PROGRAM main\nVAR x : INT; END_VAR\nx := lists.b + GVL_A.c;\nEND_PROGRAM\n"
    assert [(f[0], f[4]) for f in found({"lists.st": lists, "main.st": wrong})] == [
        ("E019", "the global variable list lists has no variable 'b'"),
        ("E019", "the global variable list GVL_A has no variable 'c'"),
    ]
    bad = "{attribute 'gvl_name' := 'GVL A'}\nVAR_GLOBAL a : INT; END_VAR\n"
    [(code, _file, line, _col, message)] = found({"lists.st": bad, "main.st": "PROGRAM main\nEND_PROGRAM\n"})
    assert code == "E019" and line == 2 and "named by an identifier" in message


def test_qualified_only_makes_a_bare_name_an_error():
    # CODESYS {attribute 'qualified_only'} before a GVL: "the variables can
    # only be accessed with the GVL name" (CODESYS Online Help, Attribute
    # qualified_only).
    main = "PROGRAM main\nVAR a : INT; END_VAR\na := speed;\nEND_PROGRAM\n"
    [(code, file, line, col, message)] = found({"GVL.st": GVL, "main.st": main})
    assert (code, file, line, col) == ("E018", "main.st", 3, 6)
    assert message == "'speed' belongs to the global variable list GVL, which is qualified_only"
    diags, _ = check_files([], texts={"GVL.st": GVL, "main.st": main})
    assert diags[0].hint.startswith("write GVL.speed")


def test_a_list_without_qualified_only_takes_both_spellings():
    main = "PROGRAM main\nVAR a : INT; END_VAR\na := level + Plant.level;\nEND_PROGRAM\n"
    assert run({"plant.st": PLAIN_GVL, "main.st": main}).get("a") == 80


def test_a_variable_named_like_a_list_wins_over_the_list():
    main = """TYPE Pair : STRUCT speed : INT := 100; END_STRUCT END_TYPE
PROGRAM main
VAR GVL : Pair; a : INT; END_VAR
a := GVL.speed;
END_PROGRAM
"""
    assert run({"GVL.st": GVL, "main.st": main}).get("a") == 100


def test_list_x_is_the_global_even_where_a_local_is_called_x():
    main = "PROGRAM main\nVAR speed : INT := 1; a : INT; END_VAR\na := speed + GVL.speed;\nEND_PROGRAM\n"
    assert run({"GVL.st": GVL, "main.st": main}).get("a") == 6


def test_a_variable_the_list_does_not_have_is_e019():
    main = "PROGRAM main\nVAR a : INT; END_VAR\na := GVL.sped;\nEND_PROGRAM\n"
    [(code, file, line, col, message)] = found({"GVL.st": GVL, "main.st": main})
    assert (code, file, line, col) == ("E019", "main.st", 3, 6)
    assert message == "the global variable list GVL has no variable 'sped'"


# ---------------------------------------------------------------- hide


def test_a_global_constant_sizes_the_fields_of_a_type():
    # TwinCAT and CODESYS size a STRUCT's fields with a GVL's constants
    # (TcUnit: ARRAY[1..GVL_Param_TcUnit.MaxNumberOfTestsForEachTestSuite]);
    # the constants of elementary types are known before the types.
    params = """{attribute 'qualified_only'}
VAR_GLOBAL CONSTANT
    MaxN : UINT := 4;
    Twice : UINT := GVL_Param.MaxN * 2;
END_VAR
"""
    main = """TYPE ST_R :
STRUCT
    id : UINT(0..GVL_Param.MaxN);
    items : ARRAY[1..GVL_Param.Twice] OF INT;
END_STRUCT
END_TYPE
PROGRAM main
VAR r : ST_R; n : DINT; END_VAR
r.items[8] := 3;
n := UPPER_BOUND(r.items, 1);
END_PROGRAM
"""
    runner = run({"GVL_Param.st": params, "main.st": main})
    assert (runner.get("n"), runner.get("r.items")[7]) == (8, 3)


def test_a_global_of_a_named_type_cannot_size_a_type_and_says_why():
    params = """TYPE T_Size : UINT; END_TYPE
VAR_GLOBAL CONSTANT
    MaxN : T_Size := 4;
END_VAR
"""
    main = """TYPE ST_R : STRUCT items : ARRAY[1..GVL_Param.MaxN] OF INT; END_STRUCT END_TYPE
PROGRAM main VAR r : ST_R; END_VAR END_PROGRAM
"""
    errors = [d for d in found({"GVL_Param.st": params, "main.st": main}) if d[0] != "W"]
    assert [d[:4] for d in errors] == [("E010", "main.st", 1, 37)], errors
    assert "'GVL_Param.MaxN' is not known yet where the data types are declared" in [d[4] for d in errors]


def test_hide_leaves_a_variable_out_of_listings_but_a_path_still_reaches_it():
    # CODESYS {attribute 'hide'}: the variable is not shown in monitoring.
    main = """PROGRAM main
VAR
    shown : INT;
    {attribute 'hide'} internal : INT;
END_VAR
internal := internal + 1;
shown := internal * 10;
END_PROGRAM
"""
    runner = run({"GVL.st": GVL, "main.st": main}, cycles=2)
    assert encode_instance(runner.instance) == {"shown": 20}
    assert encode_instance(runner.globals, skip=runner.program.library_globals) == {"speed": 5}
    assert (runner.get("internal"), runner.get("secret")) == (2, 7)


# ---------------------------------------------------------------- library namespaces

TIMERS = """PROGRAM main
VAR
    t1 : Tc2_Standard.TON;
    t2 : Standard.TOF;
    edge : standard.R_TRIG;
    n : INT;
    q1 : BOOL;
    pulses : INT;
END_VAR
t1(IN := TRUE, PT := T#30ms);
q1 := t1.Q;
edge(CLK := q1);
IF edge.Q THEN pulses := pulses + 1; END_IF
n := Tc2_Standard.LEN('abcd') + Standard.FIND('abcd', 'c');
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_standard_library_namespaces_name_our_blocks(profile):
    # CODESYS "Standard" and TwinCAT "Tc2_Standard" hold the IEC timers,
    # counters, triggers and string functions; Tc2_Standard.TON is our TON.
    runner = run({"main.st": TIMERS}, cycles=5, profile=profile)
    # TON: Q after PT = 30 ms, the 4th call at 10 ms a cycle (clock 0, 10, 20, 30, 40)
    assert (runner.get("q1"), runner.get("t1.ET"), runner.get("pulses"), runner.get("n")) == (True, 30, 1, 7)


def test_an_unknown_namespace_is_e019_with_the_known_ones():
    src = "PROGRAM main\nVAR t : Foo.TON; END_VAR\nt(IN := TRUE, PT := T#1s);\nEND_PROGRAM\n"
    diags, _ = check_files([], texts={"plant.st": PLAIN_GVL, "main.st": src})
    [d] = diags
    assert (d.code, d.pos.file, d.pos.line, d.pos.col) == ("E019", "main.st", 2, 9)
    assert d.message == "unknown namespace 'Foo' in 'Foo.TON'"
    assert d.hint == "known namespaces: Standard, Tc2_Standard, plant"


def test_a_vendor_library_softplc_lacks_is_named():
    src = "PROGRAM main\nVAR b : Tc3_JsonXml.FB_JsonSaxWriter; x : INT; END_VAR\nx := Util.LEN('a');\nEND_PROGRAM\n"
    found_ = [(c, line, col, m) for c, _f, line, col, m in found({"main.st": src})]
    assert ("E012", 2, 9, "unknown type 'FB_JsonSaxWriter' (Tc3_JsonXml, a library softplc does not have)") in found_
    message = "softplc has no library Tc3_JsonXml ('Tc3_JsonXml.FB_JsonSaxWriter')"
    assert ("E019", 2, 9, message) in found_
    # Util ships: the namespace written names it, whatever the name behind it
    message = "'Util.LEN' is of a library the program did not choose (Util; add it to libraries = [...])"
    assert ("E019", 3, 6, message) in found_


def test_a_name_the_standard_library_does_not_hold_is_e019():
    src = "PROGRAM main\nVAR x : INT; END_VAR\nx := Standard.SQRTX(4);\nEND_PROGRAM\n"
    message = "'SQRTX' is not in the Standard library as softplc has it"
    assert ("E019", "main.st", 3, 6, message) in found({"main.st": src})


# ---------------------------------------------------------------- GVL.x as a path


def test_a_path_names_a_global_by_its_list_as_st_does(tmp_path):
    # CODESYS and TwinCAT monitor a GVL's variable as <GVL name>.<variable>:
    # --watch, the testing API and a runner's get() take GVL.speed (and speed)
    from softplc.runtime.engine.monitor import Watch
    from softplc.testing import PLC

    main = "PROGRAM main\nVAR a : INT; END_VAR\nGVL.speed := GVL.speed + 1;\na := GVL.speed;\nEND_PROGRAM\n"
    runner = run({"GVL.st": GVL, "main.st": main}, cycles=2)
    assert runner.get("GVL.speed") == 7 and runner.get("gvl.SPEED") == 7
    with pytest.raises(KeyError):
        runner.get("GVL.level")  # not a variable of that list
    (tmp_path / "GVL.st").write_text(GVL, encoding="utf-8")
    (tmp_path / "main.st").write_text(main, encoding="utf-8")
    with PLC.from_st([tmp_path / "GVL.st", tmp_path / "main.st"]) as plc:
        plc.watch("GVL.speed")
        plc.step(3)
        assert plc["GVL.speed"] == 8 and plc["Main.a"] == 8
        plc["GVL.speed"] = 100
        plc.step(1)
        assert plc["Main.a"] == 101
        assert plc.trace.changes("GVL.speed")[-1][1] == 101
        assert dict(Watch(plc.engine, ["GVL.speed"]).shown()) == {"GVL.speed": "101"}


def test_a_global_named_like_a_list_wins_in_a_path():
    pair = "TYPE Pair : STRUCT speed : INT := 100; END_STRUCT END_TYPE\n"
    glob = "VAR_GLOBAL GVL : Pair; END_VAR\n"
    main = "PROGRAM main\nVAR a : INT; END_VAR\na := 1;\nEND_PROGRAM\n"
    runner = run({"types.st": pair + glob, "GVL.st": GVL.replace("speed", "other"), "main.st": main})
    assert runner.get("GVL.speed") == 100
