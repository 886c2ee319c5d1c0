"""RETAIN / PERSISTENT variables: what a warm and a cold start bring back,
what survives a new program version (the file itself: test_retain_file.py)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from softplc.runtime.engine import retain as R
from softplc.runtime.engine.retain_file import RetainStore, write_file
from softplc.runtime.image.memory import ProcessImage
from softplc.runtime.program import ExecContext, compile_files
from softplc.runtime.st.rtlib import rtlib

V1 = """
TYPE E_Mode : (Off := 0, Manual := 5, Auto := 10); END_TYPE
TYPE T_Speed : REAL; END_TYPE
TYPE ST_Rec :
STRUCT
    id : INT;
    vals : ARRAY[1..3] OF REAL;
    name : STRING[12];
    grid : ARRAY[0..1, 1..2] OF DINT;
    link : REF_TO INT;
END_STRUCT
END_TYPE

FUNCTION_BLOCK FB_Hours
VAR RETAIN total : UDINT; END_VAR
total := total + 1;
END_FUNCTION_BLOCK

FUNCTION_BLOCK FB_Axis
VAR_INPUT pulse : BOOL; END_VAR
VAR_IN_OUT shared : INT; END_VAR
VAR RETAIN parts : CTU; hours : LREAL; END_VAR
VAR PERSISTENT serial : UDINT; END_VAR
VAR calls : INT; meter : FB_Hours; END_VAR
calls := calls + 1;
meter();
parts(CU := pulse, PV := 1000);
hours := hours + 0.25;
shared := shared + 1;
END_FUNCTION_BLOCK

VAR_GLOBAL RETAIN
    G_total : LINT;
    G_located AT %MW4 : WORD;
END_VAR
VAR_GLOBAL PERSISTENT
    G_rec : ST_Rec;
END_VAR
VAR_GLOBAL
    G_plain : INT := 7;
    G_axis : FB_Axis;
END_VAR

PROGRAM Main
VAR RETAIN
    count : DINT;
    mode : E_Mode := Manual;
    speed : T_Speed := 1.5;
    t : TIME;
    lt : LTIME;
    r : REAL;
    lr : LREAL;
    rinf : REAL;
    lnan : LREAL;
    text : STRING[20] := 'init';
    arr : ARRAY[1..4] OF INT;
    lmin : LINT;
    lmax : LINT;
    umax : ULINT;
    level : INT(0..100) := 50;
    ptr : REF_TO INT;
END_VAR
VAR PERSISTENT
    keep : DINT;
    rec : ST_Rec;
    renamed : INT;
END_VAR
VAR RETAIN PERSISTENT
    both : INT;
END_VAR
VAR_OUTPUT RETAIN
    done : BOOL;
END_VAR
VAR_INPUT RETAIN
    setpoint : INT := 20;
END_VAR
VAR_STAT RETAIN
    stat : INT;
END_VAR
VAR_TEMP RETAIN
    scratch : INT;  (* holds nothing between calls: never retained *)
END_VAR
VAR
    plain : INT := 3;
    pulse : BOOL;
    x : INT;
    axis : FB_Axis;
    axes : ARRAY[1..2] OF FB_Axis;
END_VAR
count := count + 1;
pulse := NOT pulse;
axis(pulse := pulse, shared := x);
plain := plain + 1;
rec.link := REF(plain);
ptr := REF(x);
done := count > 3;
END_PROGRAM
"""

# The next version of the program: one PERSISTENT variable changes type, one
# is renamed, one is added, one is spelled in another case.
V2 = (
    V1.replace("keep : DINT;", "keep : LINT;")
    .replace("renamed : INT;", "newname : INT;\n    extra : INT := 9;")
    .replace("    both : INT;", "    BOTH : INT;")
)

_compiled: dict = {}


def compiled(source: str):
    if source not in _compiled:
        _compiled[source] = compile_files([], texts={"t.st": source})
    return _compiled[source]


class Plc:
    """One run of the PLC process: the program loaded afresh, Main instantiated."""

    def __init__(self, source: str = V1) -> None:
        self.prog = compiled(source)
        self.ctx = ExecContext(ProcessImage("iec"))
        self.ns = self.prog.load(self.ctx)
        self.info = self.prog.pou("Main")
        self.main = self.ns[self.info.pyname]()
        self.g = self.ns["_G"]
        self.plan = R.plan_retain(self.prog.checked, {"Main": (self.info, self.main)}, self.g)
        self.now = 0
        self.cycles = 0

    def run(self, n: int) -> None:
        for _ in range(n):
            self.main()
            self.cycles += 1
            self.now += 10_000_000
            self.ctx.set_time(self.now)

    def _locate(self, path: str):
        parts = path.split(".")
        obj = self.main if _find(self.main, parts[0]) else self.g
        for part in parts[:-1]:
            obj = getattr(obj, _find(obj, part))
        return obj, _find(obj, parts[-1])

    def get(self, path: str):
        obj, attr = self._locate(path)
        return getattr(obj, attr)

    def set(self, path: str, value) -> None:
        obj, attr = self._locate(path)
        setattr(obj, attr, value)


def _find(obj, name: str):
    for st_name, attr, _t, _s in type(obj)._VARS_:
        if st_name.upper() == name.upper():
            return attr
    return None


def fill_v1(plc: Plc) -> None:
    """Run some cycles and give every retained variable a telling value."""
    plc.run(7)  # count 7, axis.parts.CV 4, axis.hours 1.75
    plc.set("mode", 10)  # Auto
    plc.set("speed", rtlib.f32(0.1))
    plc.set("t", -5000)  # T#-5s
    plc.set("lt", (1 << 63) - 1)
    plc.set("r", rtlib.f32(3.14159))
    plc.set("lr", 1 / 3)
    plc.set("rinf", float("-inf"))
    plc.set("lnan", float("nan"))
    plc.set("text", 'héllo "wörld"\n')
    plc.get("arr")[:] = [1, -2, 32767, -32768]
    plc.set("lmin", -(1 << 63))
    plc.set("lmax", (1 << 63) - 1)
    plc.set("umax", (1 << 64) - 1)
    plc.set("level", 99)
    plc.set("keep", 123456)
    plc.set("rec.id", 42)
    plc.get("rec.vals")[:] = [rtlib.f32(1.1), float("inf"), -0.0]
    plc.set("rec.name", "Pump 3")
    plc.get("rec.grid")[1][:] = [-7, 2147483647]
    plc.set("renamed", 11)
    plc.set("both", -3)
    plc.set("axis.serial", 4_000_000_000)
    plc.set("G_total", -(1 << 62))
    plc.set("G_rec.id", 5)
    plc.set("G_axis.hours", 12.5)
    plc.set("G_axis.parts.CV", 17)
    plc.set("G_plain", 99)
    plc.set("G_axis.calls", 5)
    plc.set("setpoint", 77)
    plc.set("stat", -1)


def save(plc: Plc, path: Path) -> None:
    store = RetainStore(path)
    store.submit(R.capture(plc.plan, 1_700_000_000_000_000_000, plc.cycles))
    store.close()
    assert store.last_error is None


def start(path: Path, mode: str, source: str = V1):
    """A new process: load the program, read the retain file, restore."""
    plc = Plc(source)
    data, warning = RetainStore(path, threaded=False).load()
    assert warning is None
    return plc, R.restore(plc.plan, data, mode)


def same_float(a: float, b: float) -> bool:
    return (math.isnan(a) and math.isnan(b)) or (a == b and math.copysign(1, a) == math.copysign(1, b))


# ================================================================ which variables


def test_plan_lists_retained_variables_by_path_with_their_kind():
    plc = Plc()
    kinds = {rv.path: rv.kind for rv in plc.plan}
    assert list(kinds) == sorted(kinds, key=str.upper)
    assert kinds == {
        "G_axis.hours": "RETAIN",
        "G_axis.meter.total": "RETAIN",
        "G_axis.parts": "RETAIN",
        "G_axis.serial": "PERSISTENT",
        "G_rec": "PERSISTENT",
        "G_total": "RETAIN",
        "Main.arr": "RETAIN",
        "Main.axis.hours": "RETAIN",
        "Main.axis.meter.total": "RETAIN",
        "Main.axis.parts": "RETAIN",
        "Main.axis.serial": "PERSISTENT",
        "Main.both": "PERSISTENT",
        "Main.count": "RETAIN",
        "Main.done": "RETAIN",
        "Main.keep": "PERSISTENT",
        "Main.level": "RETAIN",
        "Main.lmax": "RETAIN",
        "Main.lmin": "RETAIN",
        "Main.lnan": "RETAIN",
        "Main.lr": "RETAIN",
        "Main.lt": "RETAIN",
        "Main.mode": "RETAIN",
        "Main.r": "RETAIN",
        "Main.rec": "PERSISTENT",
        "Main.renamed": "PERSISTENT",
        "Main.rinf": "RETAIN",
        "Main.setpoint": "RETAIN",
        "Main.speed": "RETAIN",
        "Main.stat": "RETAIN",
        "Main.t": "RETAIN",
        "Main.text": "RETAIN",
        "Main.umax": "RETAIN",
    }
    # Not retained: a located variable (it lives in the process image), a
    # REF_TO (an address in the old process), FBs in an array (not searched).
    # VAR_TEMP holds nothing between calls.
    assert "G_located" not in kinds and "Main.ptr" not in kinds and "Main.scratch" not in kinds
    assert not any(p.startswith("Main.axes") for p in kinds)


def test_type_signatures_are_canonical_and_change_with_the_structure():
    sig = {rv.path: rv.signature for rv in Plc().plan}
    assert sig["Main.speed"] == "REAL"  # the alias T_Speed resolved
    assert sig["Main.level"] == "INT(0..100)"
    assert sig["Main.text"] == "STRING[20]"
    assert sig["Main.mode"] == "ENUM E_MODE:INT(OFF:=0,MANUAL:=5,AUTO:=10)"
    assert sig["Main.rec"] == (
        "ST_REC{ID:INT;VALS:ARRAY[1..3] OF REAL;NAME:STRING[12];GRID:ARRAY[0..1, 1..2] OF DINT;LINK:REF_TO INT}"
    )
    assert sig["Main.axis.parts"] == "CTU{CU:BOOL;R:BOOL;PV:INT;Q:BOOL;CV:INT;LASTCU:BOOL}"

    def sig_of(decl: str) -> str:
        prog = compile_files(
            [],
            texts={
                "s.st": f"""
            TYPE E : (A, B); END_TYPE
            TYPE S : STRUCT a : INT; b : STRING[5]; END_STRUCT END_TYPE
            PROGRAM Main VAR RETAIN v : {decl}; END_VAR END_PROGRAM"""
            },
        )
        info = prog.pou("Main")
        return R.type_signature(info.vars["V"].type)

    assert sig_of("ARRAY[1..3] OF S") == sig_of("ARRAY [1 .. 3] OF s")  # spelling does not matter
    variants = [
        "ARRAY[1..3] OF S",
        "ARRAY[0..2] OF S",
        "ARRAY[1..4] OF S",
        "ARRAY[1..3] OF E",
        "ARRAY[1..3] OF INT",
        "ARRAY[1..3] OF UINT",
        "ARRAY[1..3, 1..1] OF S",
        "STRING[5]",
        "STRING[6]",
        "WSTRING[5]",
        "INT(0..10)",
        "INT(0..11)",
        "TIME",
        "LTIME",
    ]
    assert len({sig_of(v) for v in variants}) == len(variants)


# ================================================================ warm and cold start


def test_warm_start_restores_retain_and_persistent_values(tmp_path):
    path = tmp_path / "plc.retain"
    old = Plc()
    fill_v1(old)
    save(old, path)

    new, report = start(path, "warm")
    assert report.mode == "warm" and report.layout_matched
    assert report.dropped == []
    assert report.restored == [rv.path for rv in new.plan]
    for rv in new.plan:
        if rv.path != "Main.lnan":
            assert R.snapshot([rv]) == R.snapshot([next(o for o in old.plan if o.path == rv.path)])
    # the values themselves, bit for bit
    assert new.get("count") == 7 and new.get("mode") == 10 and new.get("level") == 99
    assert new.get("speed") == rtlib.f32(0.1) and new.get("r") == rtlib.f32(3.14159)
    assert new.get("lr") == 1 / 3
    assert new.get("rinf") == float("-inf") and math.isnan(new.get("lnan"))
    assert new.get("t") == -5000 and new.get("lt") == (1 << 63) - 1
    assert new.get("text") == 'héllo "wörld"\n'
    assert new.get("arr") == [1, -2, 32767, -32768]
    assert (new.get("lmin"), new.get("lmax"), new.get("umax")) == (-(1 << 63), (1 << 63) - 1, (1 << 64) - 1)
    assert new.get("keep") == 123456 and new.get("both") == -3 and new.get("renamed") == 11
    assert new.get("done") is True
    assert new.get("rec.id") == 42 and new.get("rec.name") == "Pump 3"
    vals = new.get("rec.vals")
    assert vals[0] == rtlib.f32(1.1) and vals[1] == float("inf") and same_float(vals[2], -0.0)
    assert new.get("rec.grid") == [[0, 0], [-7, 2147483647]]
    assert new.get("G_total") == -(1 << 62) and new.get("G_rec.id") == 5
    # inside FB instances that are not retained themselves
    assert new.get("axis.parts.CV") == 4 and new.get("axis.hours") == 1.75
    assert new.get("axis.serial") == 4_000_000_000
    assert new.get("G_axis.hours") == 12.5 and new.get("G_axis.parts.CV") == 17
    assert new.get("axis.meter.total") == 7  # an FB inside an FB
    assert new.get("setpoint") == 77 and new.get("stat") == -1
    # everything else starts afresh
    assert new.get("plain") == 3 and new.get("G_plain") == 7 and new.get("x") == 0
    assert new.get("axis.calls") == 0 and new.get("G_axis.calls") == 0
    assert new.get("rec.link") is None  # a reference is never restored
    # and the program carries on counting where it stopped
    new.run(1)
    assert new.get("count") == 8 and new.get("axis.hours") == 2.0


def test_restore_updates_aggregates_in_place():
    """Generated code and references hold on to arrays, structs and FB
    instances: restoring must not replace those objects."""
    old = Plc()
    fill_v1(old)
    data = R.capture(old.plan, 0, old.cycles)
    new = Plc()
    objects = [new.get(p) for p in ("arr", "rec", "rec.grid", "axis", "axis.parts", "G_rec", "G_axis.parts")]
    rows = list(new.get("rec.grid"))
    R.restore(new.plan, data, "warm")
    after = [new.get(p) for p in ("arr", "rec", "rec.grid", "axis", "axis.parts", "G_rec", "G_axis.parts")]
    assert all(a is b for a, b in zip(objects, after))
    assert all(a is b for a, b in zip(rows, new.get("rec.grid")))
    new.run(3)  # the FB instance the program calls is the restored one
    assert new.get("axis.parts.CV") == 5


def test_snapshot_is_a_copy_the_program_cannot_change():
    plc = Plc()
    fill_v1(plc)
    data = R.capture(plc.plan, 0, plc.cycles)
    text = json.dumps(data.vars, allow_nan=True)
    plc.run(5)
    plc.get("rec.grid")[0][0] = 99
    plc.get("arr")[0] = 99
    assert json.dumps(data.vars, allow_nan=True) == text


def test_cold_start_restores_nothing(tmp_path):
    path = tmp_path / "plc.retain"
    old = Plc()
    fill_v1(old)
    save(old, path)
    new, report = start(path, "cold")
    assert report.mode == "cold" and report.restored == [] and report.dropped == []
    assert new.get("count") == 0 and new.get("mode") == 5 and new.get("text") == "init"
    assert new.get("keep") == 0 and new.get("axis.serial") == 0 and new.get("G_total") == 0
    assert new.get("level") == 50


def test_warm_start_without_a_file_initialises_and_says_why(tmp_path):
    new, report = start(tmp_path / "never-written.retain", "warm")
    assert report.restored == [] and not report.layout_matched
    assert report.dropped == [(rv.path, "no retain data") for rv in new.plan]
    assert new.get("mode") == 5


def test_new_program_version_keeps_matching_persistent_only(tmp_path):
    path = tmp_path / "plc.retain"
    old = Plc(V1)
    fill_v1(old)
    save(old, path)

    new, report = start(path, "warm", V2)
    assert not report.layout_matched
    dropped = dict(report.dropped)
    # PERSISTENT with the same path and type: kept (BOTH is both: ST ignores case)
    assert set(report.restored) == {"G_axis.serial", "G_rec", "Main.axis.serial", "Main.BOTH", "Main.rec"}
    assert new.get("both") == -3 and new.get("rec.name") == "Pump 3" and new.get("axis.serial") == 4_000_000_000
    assert new.get("G_rec.id") == 5
    # PERSISTENT whose type changed, renamed or new: initialised, with the reason
    assert dropped["Main.keep"] == "type changed (saved DINT, now LINT)"
    assert dropped["Main.newname"] == "not in the file"
    assert dropped["Main.extra"] == "not in the file"
    assert new.get("keep") == 0 and new.get("newname") == 0 and new.get("extra") == 9
    # every RETAIN variable: initialised after a program change
    for path_ in ("Main.count", "Main.text", "Main.axis.hours", "Main.axis.parts", "G_total", "G_axis.hours"):
        assert dropped[path_] == "program changed (RETAIN)"
    assert new.get("count") == 0 and new.get("text") == "init" and new.get("axis.hours") == 0.0
    assert new.get("G_total") == 0
    assert set(report.restored) | set(dropped) == {rv.path for rv in new.plan}


def test_same_program_compiled_again_has_the_same_layout():
    a = Plc(V1)
    b = Plc(V1.replace("count : DINT;", "COUNT : DINT;"))  # a change of case only
    c = Plc(V2)
    assert R.layout_hash(a.plan) == R.layout_hash(b.plan) != R.layout_hash(c.plan)


def test_a_hand_edited_bad_value_is_dropped_alone(tmp_path):
    path = tmp_path / "plc.retain"
    old = Plc()
    fill_v1(old)
    data = R.capture(old.plan, 0, old.cycles)
    data.vars["Main.level"]["value"] = 101  # outside INT(0..100)
    data.vars["Main.rec"]["value"]["vals"] = [1.0, "x", 2.0]
    data.vars["Main.text"]["value"] = "much too long for a STRING[20]"
    write_file(path, data)
    new, report = start(path, "warm")
    dropped = dict(report.dropped)
    assert dropped["Main.level"] == "bad value in the file (Main.level: 101 is outside 0..100)"
    assert dropped["Main.rec"] == 'bad value in the file (Main.rec.vals[2]: expected a number, found "x")'
    assert "longer than 20" in dropped["Main.text"]
    assert new.get("level") == 50 and new.get("rec.id") == 0 and new.get("text") == "init"
    assert new.get("count") == 7 and "Main.count" in report.restored


def test_restart_after_a_fault_carries_values_in_memory():
    """What the engine does for a faulted task: capture, new instances, restore."""
    old = Plc()
    fill_v1(old)
    carried = R.capture(old.plan, 0, old.cycles)
    new = Plc()
    report = R.restore(new.plan, carried, "warm")
    assert report.dropped == [] and new.get("count") == 7 and new.get("rec.grid")[1] == [-7, 2147483647]
    new.get("rec.grid")[1][0] = 0  # the restored lists are not the captured ones
    assert carried.vars["Main.rec"]["value"]["grid"][1][0] == -7


def test_unknown_start_mode_is_refused():
    with pytest.raises(ValueError, match="start mode"):
        R.restore(Plc().plan, None, "hot")


LIMITED = """
FUNCTION_BLOCK Limited
VAR CONSTANT limit : INT := {limit}; END_VAR
VAR count : INT; END_VAR
count := MIN(count + 1, limit);
END_FUNCTION_BLOCK

PROGRAM Main
VAR PERSISTENT lim : Limited; END_VAR
lim();
END_PROGRAM
"""


def test_a_constant_of_a_kept_instance_is_the_new_program_s_not_the_file_s(tmp_path):
    # members.py: a CONSTANT is the program's, never the instance's state: a warm start keeps
    # the persistent FB's count, and its limit is what the new program says
    path = tmp_path / "plc.retain"
    old = Plc(LIMITED.format(limit=10))
    old.run(25)
    assert old.get("lim.count") == 10
    save(old, path)
    new, report = start(path, "warm", LIMITED.format(limit=20))
    assert "Main.lim" in report.restored
    assert new.get("lim.count") == 10 and new.get("lim.limit") == 20
    new.run(15)
    assert new.get("lim.count") == 20
