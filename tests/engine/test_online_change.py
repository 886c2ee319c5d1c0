"""Online change (engine/online_change.py, engine/carry.py): a changed
program swapped in between two scans in virtual time, its values kept by
CODESYS's rules, the report by ST path."""

from __future__ import annotations

from pathlib import Path

import pytest

from softplc.runtime.engine.monitor import Watch
from softplc.runtime.engine.online_change import OnlineChange, apply_program
from softplc.runtime.plugin.driver import Driver, DriverStatus
from softplc.testing import PLC

from .conftest import compile_st, task

BEFORE = """
VAR_GLOBAL
    G_total : DINT;
    G_gone : INT := 3;
END_VAR

PROGRAM Main
VAR
    count : INT;
    level : INT := 5;
    mode : INT := 1;
    old_flag : BOOL;
    hist : ARRAY[1..3] OF INT;
    t1 : TON;
    c1 : CTU;
    run : BOOL := TRUE;
END_VAR
count := count + 1;
G_total := G_total + 10;
hist[1] := count;
t1(IN := run, PT := T#10s);
c1(CU := NOT c1.CU, PV := 1000);
END_PROGRAM
"""

AFTER = """
VAR_GLOBAL
    G_total : DINT;
    G_new : INT := 42;
END_VAR

PROGRAM Main
VAR
    count : INT;
    level : INT := 5;
    mode : REAL := 2.5;
    added : INT := 7;
    hist : ARRAY[1..5] OF INT;
    t1 : TON;
    c1 : CTU;
    run : BOOL := TRUE;
END_VAR
count := count + 1;
G_total := G_total + 10;
hist[1] := count;
t1(IN := run, PT := T#10s);
c1(CU := NOT c1.CU, PV := 1000);
END_PROGRAM
"""


def plant(tmp_path: Path, source: str) -> PLC:
    st = tmp_path / "plant.st"
    st.write_text(source, encoding="utf-8")
    return PLC.from_st([st], cycle="10ms")


def rewrite(plc: PLC, source: str) -> None:
    Path(plc.config.programs[0]).write_text(source, encoding="utf-8")


def change_now(plc: PLC, source: str, reason: str = "test"):
    """Rewrite the file, compile (as the watcher's thread does), take the change at the next scan."""
    rewrite(plc, source)
    request = OnlineChange(plc.engine, plc.config).submit(reason)
    plc.step()
    return request.wait(0)


def test_values_are_kept_new_ones_initialised_retyped_reset_removed_dropped(tmp_path):
    with plant(tmp_path, BEFORE) as plc:
        plc.step(20)
        plc.write("Main.level", 9)
        plc.write("Main.mode", 4)
        report = change_now(plc, AFTER)
        assert report.applied, report.errors
        assert report.cycle == 20
        # the change was taken before scan 21, which then ran on the new program with the old values
        assert plc["Main.count"] == 21 and plc["G_total"] == 210
        assert plc["Main.level"] == 9  # kept
        assert plc["Main.added"] == 7 and plc["G_new"] == 42  # new: initial values
        assert plc["Main.mode"] == 2.5  # INT -> REAL: reset to its initial value
        assert plc["Main.hist"][:1] == [21]
        assert "Main.level" in report.kept and "G_total" in report.kept and "Main.t1" in report.kept
        assert "Main.added" in report.initialised and "G_new" in report.initialised
        assert [p for p, _why in report.reset] == ["Main.mode"]
        assert "INT -> REAL" in report.reset[0][1]
        assert sorted(report.dropped) == ["G_gone", "Main.old_flag"]
        assert any(n.startswith("Main.hist: bounds [1..3] -> [1..5]") for n in report.notes)
        assert "PLC_DIAG" not in " ".join(report.kept)  # the libraries' globals are carried silently
        with pytest.raises(KeyError):
            plc["Main.old_flag"]


def test_array_elements_in_both_bounds_keep_their_values(tmp_path):
    src = (
        "PROGRAM Main\nVAR a : ARRAY[{}] OF INT; i : INT; END_VAR\n"
        "FOR i := 2 TO 4 DO a[i] := i * 10; END_FOR\nEND_PROGRAM\n"
    )
    with plant(tmp_path, src.format("2..4")) as plc:
        plc.step()
        after = src.format("3..6").replace("FOR i := 2 TO 4 DO a[i] := i * 10; END_FOR", ";")
        report = change_now(plc, after)
        assert report.applied, report.errors
        assert plc["Main.a"] == [30, 40, 0, 0]  # a[3], a[4] kept; a[5], a[6] new; a[2] gone
        assert "Main.a" in report.kept


def test_a_compile_error_leaves_the_running_program_untouched(tmp_path):
    with plant(tmp_path, BEFORE) as plc:
        plc.step(5)
        broken = BEFORE.replace("count := count + 1;", "count := count + ;")
        rewrite(plc, broken)
        request = OnlineChange(plc.engine, plc.config).submit("test")
        assert request.done.is_set()  # refused at once: nothing queued for the scan
        report = request.wait(0)
        assert not report.applied
        assert "compile error" in report.errors[0] and "running program is unchanged" in report.errors[0]
        assert report.diagnostics and report.diagnostics[0].code.startswith("E")
        assert any(line.startswith(f"{tmp_path / 'plant.st'}:") and ": error E" in line for line in report.errors[1:])
        generation = plc.engine.generation
        plc.step(5)
        assert plc["Main.count"] == 10 and plc.engine.generation == generation


def test_no_scan_is_missed_or_run_twice_at_the_swap(tmp_path):
    counter = "PROGRAM Main\nVAR n : DINT; {} END_VAR\nn := n + 1;\nEND_PROGRAM\n"
    with plant(tmp_path, counter.format("")) as plc:
        plc.run_for("95ms")  # scans at 0, 10 ... 90 ms
        assert plc["Main.n"] == 10 == plc.cycles
        rewrite(plc, counter.format("extra : INT := 1;"))
        request = OnlineChange(plc.engine, plc.config).submit("test")
        plc.run_for("100ms")  # scans at 100 ... 190 ms, the first on the new program
        report = request.wait(0)
        assert report.applied and report.cycle == 10
        assert plc.cycles == 20 and plc["Main.n"] == 20 and plc["Main.extra"] == 1
        assert plc.engine.tasks[0].stats.overruns == 0


def test_function_block_instances_keep_their_state(tmp_path):
    with plant(tmp_path, BEFORE) as plc:
        plc.run_for("3s")
        elapsed, counted = plc["Main.t1.ET"], plc["Main.c1.CV"]
        assert elapsed.total_seconds() > 2.9 and counted > 100
        report = change_now(plc, AFTER)
        assert report.applied
        # one more scan on the new program: the timer and the counter went on from where they were
        assert plc["Main.t1.ET"] > elapsed and plc["Main.c1.CV"] in (counted, counted + 1)
        plc.run_for("8s")
        assert plc["Main.t1.Q"]  # 10 s in all: no restart of the timer at the change


def test_a_changed_function_block_keeps_the_members_that_remain(tmp_path):
    src = """
FUNCTION_BLOCK Acc
VAR_INPUT x : INT; END_VAR
VAR sum : DINT; {extra} END_VAR
sum := sum + x;
END_FUNCTION_BLOCK
PROGRAM Main
VAR a : Acc; END_VAR
a(x := 2);
END_PROGRAM
"""
    with plant(tmp_path, src.format(extra="")) as plc:
        plc.step(4)
        report = change_now(plc, src.format(extra="peak : DINT := -1;"))
        assert report.applied
        assert plc["Main.a.sum"] == 10 and plc["Main.a.peak"] == -1
        assert "Main.a.sum" in report.kept and "Main.a.peak" in report.initialised


def test_a_global_keeps_its_value_and_a_watch_follows_the_new_program(tmp_path):
    with plant(tmp_path, BEFORE) as plc:
        plc.step(3)
        watch = Watch(plc.engine, ["G_total", "Main.count"])
        assert watch.raw() == [30, 3]
        report = change_now(plc, AFTER)
        assert report.applied and plc["G_total"] == 40
        assert watch.raw() == [40, 4]  # resolved again in the new program (Engine.generation)


def test_forces_stay_when_the_variable_stays_and_are_released_otherwise(tmp_path):
    with plant(tmp_path, BEFORE) as plc:
        plc.step(2)
        plc.force("Main.level", 77)
        plc.force("Main.old_flag", True)
        plc.force("Main.hist[2]", 5)
        plc.step()
        report = change_now(plc, AFTER)
        assert report.applied
        forces = dict(report.forces)
        assert forces["MAIN.LEVEL"] == "kept" and forces["MAIN.HIST[2]"] == "kept"
        assert forces["MAIN.OLD_FLAG"] == "released: the variable is gone"
        assert set(plc.engine.forces) == {"MAIN.LEVEL", "MAIN.HIST[2]"}
        plc.write("Main.level", 1)
        plc.write("Main.hist", [0, 0, 0, 0, 0])
        plc.step()
        assert plc["Main.level"] == 77 and plc["Main.hist"][1] == 5  # still held in the new program


def test_a_change_of_the_tasks_is_refused_it_needs_a_restart(tmp_path):
    src = "PROGRAM Main\nVAR n : INT; END_VAR\nn := n + 1;\nEND_PROGRAM\n"
    other = src.replace("PROGRAM Main", "PROGRAM Other")
    with plant(tmp_path, src) as plc:
        plc.step(2)
        rewrite(plc, other)
        report = OnlineChange(plc.engine, plc.config).submit("test").wait(0)
        assert not report.applied and "not a PROGRAM" in report.errors[0]
        plc.step()
        assert plc["Main.n"] == 3


def test_the_watcher_sees_a_rewritten_file(tmp_path):
    with plant(tmp_path, BEFORE) as plc:
        change = OnlineChange(plc.engine, plc.config)
        assert change.check() is None  # nothing changed since it looked
        plc.step(2)
        rewrite(plc, AFTER + "\n(* one more line: another size *)\n")
        request = change.check()
        assert request is not None and request.reason == "changed: plant.st"
        plc.step()
        assert change.record(request.wait(0)).applied and change.reports[-1] is request.report
        assert plc["Main.added"] == 7
        assert change.check() is None
        change.wake("web page")
        again = change.check()
        assert again is not None and again.reason == "web page"


OOP = """
FUNCTION_BLOCK Box
VAR_OUTPUT
    copied : BOOL; init_retains : BOOL := TRUE; reinits : INT; exits_in_copy : INT;
END_VAR
VAR value : INT; {extra} END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; END_VAR
copied := bInCopyCode;
init_retains := bInitRetains;
{init}
END_METHOD
METHOD FB_reinit : BOOL
reinits := reinits + 1;
END_METHOD
METHOD FB_exit : BOOL
VAR_INPUT bInCopyCode : BOOL; END_VAR
IF bInCopyCode THEN G_exits := G_exits + 1; END_IF
END_METHOD
value := value + 1;
END_FUNCTION_BLOCK
VAR_GLOBAL G_exits : INT; END_VAR
PROGRAM Main
VAR b : Box; END_VAR
b();
END_PROGRAM
"""


def test_function_blocks_get_fb_exit_fb_init_and_fb_reinit_as_in_codesys(tmp_path):
    with plant(tmp_path, OOP.format(extra="", init="")) as plc:
        plc.step(3)
        assert not plc["Main.b.copied"] and plc["Main.b.init_retains"]
        init = "more := bInCopyCode AND NOT bInitRetains;"
        report = change_now(plc, OOP.format(extra="more : BOOL;", init=init))
        assert report.applied, report.errors
        assert plc["G_exits"] == 1  # the old instance's FB_exit(bInCopyCode := TRUE)
        assert plc["Main.b.value"] == 4  # copied, then one scan
        assert plc["Main.b.reinits"] == 1  # FB_reinit after the copy
        # FB_init(bInitRetains := FALSE, bInCopyCode := TRUE) ran on the new instance: what it set
        # in a new variable stays, what it set in a carried one the copy overwrote (init, copy, reinit)
        assert plc["Main.b.more"] and not plc["Main.b.copied"]


class Recorder(Driver):
    """A driver that records the globals objects it is bound to."""

    name = "recorder"

    def __init__(self) -> None:
        self.bound: list = []

    def bind_program(self, globals_obj) -> None:
        self.bound.append(globals_obj)

    def read_inputs(self, image) -> None:
        pass

    def write_outputs(self, image) -> None:
        pass

    def status(self) -> DriverStatus:
        return DriverStatus(True, "")


def test_the_engine_swaps_drivers_diag_and_instances(engines):
    src = "PROGRAM Main\nVAR n : INT; out AT %QW0 : INT := 5; END_VAR\nn := n + 1; out := n;\nEND_PROGRAM\n"
    driver = Recorder()
    engine = engines(src, [task("T", 10, "Main")], drivers=[driver])
    engine.run(cycles=3)
    engine.image.write("%QW0", 1234)  # the image is the machine's: the swap writes nothing into it
    new = compile_st(src.replace("n : INT;", "n : INT; m : INT := 8;"))
    report = apply_program(engine, new, "direct")
    assert report.applied and engine.program is new
    assert driver.bound[-1] is engine.ns["_G"] and len(driver.bound) == 2
    assert engine.diag is not None and engine.get("PLC_DIAG.StartMode") == "warm"
    assert engine.image.read("%QW0") == 1234
    assert engine.get("Main.n") == 3 and engine.get("Main.m") == 8
    engine.run(cycles=1)
    assert engine.get("Main.n") == 4 and engine.image.read("%QW0") == 4


FAULTY_INIT = """
FUNCTION_BLOCK Div
VAR_OUTPUT q : INT; END_VAR
VAR zero : INT; END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; END_VAR
IF bInCopyCode THEN q := 1 / zero; END_IF
END_METHOD
END_FUNCTION_BLOCK
"""


def test_a_new_program_that_faults_at_its_start_leaves_the_old_one_running(engines):
    src = "PROGRAM Main\nVAR n : INT; END_VAR\nn := n + 1;\nEND_PROGRAM\n"
    engine = engines(src, [task("T", 10, "Main")])
    engine.run(cycles=2)
    old_program, old_ns, generation = engine.program, engine.ns, engine.generation
    faulty = compile_st(FAULTY_INIT + src.replace("n : INT;", "n : INT; d : Div;"))
    report = apply_program(engine, faulty, "direct")
    assert not report.applied and "division by zero" in report.errors[0].lower()
    refused = apply_program(engine, compile_st(src.replace("PROGRAM Main", "PROGRAM Other")), "direct")
    assert not refused.applied and "needs a restart" in refused.errors[0]
    assert engine.program is old_program and engine.ns is old_ns and engine.generation == generation
    assert engine.ctx.namespaces == [old_ns]
    engine.run(cycles=1)
    assert engine.get("Main.n") == 3
