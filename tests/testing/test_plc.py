"""The testing API on small ST programs in virtual time: construction,
running, typed reads and writes and their errors, force against write,
writes before the first scan, direct addresses, scripts, the trace and the
messages of run_until and expect."""

from __future__ import annotations

from datetime import timedelta

import pytest

from softplc.testing import PLC, EnumValue, PathError

SOURCE = """
TYPE E_State : (Idle, Run, Done); END_TYPE
TYPE S_Part : STRUCT weight : REAL; ok : BOOL; END_STRUCT END_TYPE
PROGRAM Main
VAR
    state : E_State;
    go : BOOL;
    count : INT;
    small : USINT;
    limit : TIME := T#2s;
    speed : REAL;
    name : STRING[8] := 'abc';
    parts : ARRAY[1..3] OF S_Part;
    grid : ARRAY[0..1, 0..2] OF INT;
    runTimer : TON;
    lamp AT %QX0.0 : BOOL;
    button AT %IX0.3 : BOOL;
    setpoint AT %QW1 : WORD;
    copyOfButton : BOOL;
END_VAR
count := count + 1;
copyOfButton := button;
runTimer(IN := state = Run, PT := limit);
CASE state OF
    Idle: IF go THEN state := Run; END_IF;
    Run: IF runTimer.Q THEN state := Done; END_IF;
END_CASE;
lamp := state = Run;
setpoint := INT_TO_WORD(count);
END_PROGRAM
"""


@pytest.fixture
def plc():
    with PLC.from_st(SOURCE) as made:
        yield made


def test_a_program_runs_in_virtual_time(plc):
    assert plc.now == timedelta(0)
    plc.run_for("1s")
    assert plc.now == timedelta(seconds=1)
    assert plc["Main.count"] == 100  # one 10 ms task: scans at 0, 10 .. 990 ms
    plc.run_for(timedelta(milliseconds=50))
    plc.run_for(50_000_000)  # int: nanoseconds
    assert plc["Main.count"] == 110
    plc.step(3)
    assert plc["Main.count"] == 113 and plc.cycles == 113


def test_the_cycle_and_the_tasks_of_st_sources():
    with PLC.from_st(SOURCE, cycle="50ms") as slow:
        slow.run_for("1s")
        assert slow["Main.count"] == 20
    tasks = [{"name": "Fast", "interval": "5ms", "programs": [{"instance": "A", "program": "Main"}]}]
    with PLC.from_st(SOURCE, tasks=tasks) as fast:
        fast.run_for("100ms")
        assert fast["A.count"] == 20


def test_st_files_and_texts(tmp_path):
    lib = tmp_path / "lib.st"
    lib.write_text("FUNCTION Twice : INT VAR_INPUT x : INT; END_VAR Twice := 2 * x; END_FUNCTION\n")
    main = "PROGRAM P VAR y : INT; END_VAR y := Twice(21); END_PROGRAM"
    with PLC.from_st([lib, main]) as plc:
        plc.step()
        assert plc["P.y"] == 42
    with PLC.from_st([str(lib), main]) as plc:
        plc.step()
        assert plc["P.y"] == 42


def test_reads_have_st_types(plc):
    plc.step()
    state = plc["Main.state"]
    assert isinstance(state, EnumValue)
    assert state == "Idle" and state == "idle" and state == "E_State.Idle" and state == 0
    assert state != "Run" and state != "Other.Idle"
    assert repr(state) == "E_State.Idle" and str(state) == "Idle"
    assert plc["Main.limit"] == timedelta(seconds=2)
    assert plc["Main.name"] == "abc"
    assert plc["Main.parts"] == [{"weight": 0.0, "ok": False}] * 3
    assert plc["Main.grid"] == [[0, 0, 0], [0, 0, 0]]
    assert plc["Main.runTimer"]["PT"] == timedelta(seconds=2)
    assert plc.read("main.RUNTIMER.q") is False  # ST names are case-insensitive


def test_writes_take_st_values(plc):
    plc.write("Main.state", "E_State.Run")
    assert plc["Main.state"] == "Run"
    plc["Main.state"] = "done"
    assert plc["Main.state"] == "Done"
    plc.write("Main.state", "E_State#Run")
    assert plc["Main.state"] == 1
    plc.write("Main.state", 2)
    assert plc["Main.state"] == "Done"
    plc.write("Main.state", EnumValue("Idle", "E_State", 0))
    plc.write("Main.limit", "T#1m30s")
    assert plc["Main.limit"] == timedelta(seconds=90)
    plc.write("Main.limit", timedelta(milliseconds=250))
    assert plc["Main.limit"] == timedelta(milliseconds=250)
    plc.write("Main.speed", 0.1)
    assert plc["Main.speed"] == pytest.approx(0.1) and plc["Main.speed"] != 0.1  # stored as a 32-bit REAL
    plc.write("Main.small", "16#FF")
    assert plc["Main.small"] == 255
    plc.write("Main.parts[2].weight", 1.5)
    plc.write("Main.parts[3]", {"ok": True})
    plc.write("Main.grid[1, 2]", 7)
    plc.write("Main.grid[0]", [1, 2, 3])
    assert plc["Main.parts"][1:] == [{"weight": 1.5, "ok": False}, {"weight": 0.0, "ok": True}]
    assert plc["Main.grid"] == [[1, 2, 3], [0, 0, 7]]


@pytest.mark.parametrize(
    "path, value, message",
    [
        ("Main.count", 40_000, "Main.count is INT (-32768..32767): write an integer from -32768 to 32767, not 40000"),
        ("Main.count", 1.5, "Main.count is INT (-32768..32767): write an integer"),
        ("Main.small", -1, "Main.small is USINT (0..255): write an integer from 0 to 255, not -1"),
        ("Main.go", 2, "Main.go is BOOL: write True/False, 1/0 or 'TRUE'/'FALSE', not 2"),
        (
            "Main.state",
            "Running",
            "Main.state is E_State (Idle, Run, Done): write one of Idle, Run, Done, not 'Running'",
        ),
        ("Main.state", "Other.Run", "write one of Idle, Run, Done"),
        ("Main.state", 7, "write one of Idle, Run, Done (or their values 0, 1, 2), not 7"),
        ("Main.limit", 5, "Main.limit is TIME: write a duration: a timedelta or 'T#2s'"),
        ("Main.limit", "soon", "Main.limit is TIME: write a duration"),
        ("Main.speed", "fast", "Main.speed is REAL: write a number, not 'fast'"),
        ("Main.speed", 1e39, "within the REAL range"),
        ("Main.name", "much too long", "Main.name is STRING[8]: write a str of at most 8 characters"),
        ("Main.parts[1]", {"mass": 1}, "Main.parts[1] (S_Part) has no field 'mass' (it has weight, ok)"),
        ("Main.grid[0]", [1, 2], "Main.grid[0] is ARRAY[0..2] OF INT: write a list of 3 values"),
        ("%QW1", 70_000, "%QW1 is WORD (0..65535): write an integer from 0 to 65535"),
    ],
)
def test_a_wrong_value_names_the_variable_and_its_type(plc, path, value, message):
    before = plc[path]
    with pytest.raises(ValueError) as err:
        plc.write(path, value)
    assert message in str(err.value)
    assert plc[path] == before  # nothing written, not even in part


@pytest.mark.parametrize(
    "path, message",
    [
        ("Main.cuont", "Main.cuont: no variable Main.cuont in 'Main' (did you mean 'Main.count'?)"),
        ("Mian.count", "Mian.count: no variable Mian in the program instances and globals (did you mean 'Main'?)"),
        ("Main.count.x", "Main.count.x: Main.count is INT, it has no field x"),
        ("Main.parts[4]", "Main.parts[4]: index 4 is outside 1..3"),
        ("Main.grid[0, 1, 2]", "Main.grid has 2 dimension(s), not 3"),
        ("Main.count[1]", "Main.count is INT, not an array"),
        ("%QZ9", "%QZ9"),
        ("", "expected a variable path"),
    ],
)
def test_a_wrong_path_is_named(plc, path, message):
    with pytest.raises(PathError) as err:
        plc.read(path)
    assert message in str(err.value)
    with pytest.raises(KeyError):  # PathError is a KeyError
        plc.write(path, 1)


def test_writes_before_the_first_scan_are_initial_conditions():
    with PLC.from_st(SOURCE) as plc:
        plc.write("Main.go", True)
        plc.write("Main.limit", "T#30ms")
        plc.write("Main.count", 1000)
        assert plc.cycles == 0
        plc.step()
        assert plc["Main.count"] == 1001 and plc["Main.state"] == "Run"
        plc.run_until(lambda: plc["Main.state"] == "Done", timeout="100ms")


def test_a_write_lasts_until_the_program_writes_a_force_holds(plc):
    plc.write("Main.count", 500)
    plc.step()
    assert plc["Main.count"] == 501  # the program goes on from the written value
    plc.force("Main.count", 7)
    assert plc["Main.count"] == 7  # at once
    plc.step(5)
    assert plc["Main.count"] == 7  # the program's count := count + 1 cannot change it
    assert plc["%QW1"] == 8  # but it computed with the forced value in every scan
    assert plc.forced == {"Main.count": 7}
    plc.unforce("main.COUNT")
    plc.step()
    assert plc["Main.count"] == 8 and plc.forced == {}
    with pytest.raises(KeyError, match="Main.count is not forced"):
        plc.unforce("Main.count")


def test_forced_outputs_and_inputs_at_direct_addresses(plc):
    plc.force("%QX0.0", True)  # the program writes lamp := FALSE every scan
    plc.step(2)
    assert plc["%QX0.0"] is True and plc["Main.lamp"] is True
    plc.force("Main.button", True)  # a located input, by its name
    plc.step()
    assert plc["Main.copyOfButton"] is True and plc["%IX0.3"] is True
    plc.unforce_all()
    assert plc.forced == {}
    plc.write("%IX0.3", False)
    plc.step()
    assert plc["Main.copyOfButton"] is False and plc["%QX0.0"] is False


def test_a_forced_struct_holds_every_field(plc):
    plc.force("Main.parts[1]", {"weight": 2.5, "ok": True})
    plc.step()
    assert plc["Main.parts[1]"] == {"weight": 2.5, "ok": True}
    plc.write("Main.parts[1].ok", False)  # a write to a forced field lasts until the next scan
    plc.step()
    assert plc["Main.parts[1].ok"] is True


def test_a_script_writes_at_engine_times(plc):
    plc.watch("Main.go", "Main.state", "Main.lamp")
    plc.write("Main.limit", "T#100ms")
    plc.script([("200ms", "Main.go", True), (timedelta(milliseconds=250), "Main.go", False)])
    plc.run_for("1s")
    assert plc.trace.changes("Main.go") == [(0, False), (200_000_000, True), (250_000_000, False)]
    assert plc.trace.changes("Main.state") == [
        (0, "Idle"),
        (200_000_000, "Run"),
        (310_000_000, "Done"),
    ]  # the TON starts a scan later
    assert [row.time for row in plc.trace][-1] == timedelta(milliseconds=310)
    called = []
    plc.at("1.5s", lambda: called.append(plc.now))
    plc.run_for("1s")
    assert called == [timedelta(seconds=1.5)]
    with pytest.raises(ValueError, match="Main.go is BOOL"):
        plc.script([("2s", "Main.go", "maybe")])
    with pytest.raises(ValueError, match=r"each event is \(time, path, value\)"):
        plc.script([("2s", "Main.go")])


def test_run_until_returns_the_time_and_times_out_with_the_trace(plc):
    plc.write("Main.limit", "T#100ms")
    plc.script([("50ms", "Main.go", True)])
    assert plc.run_until("Main.lamp", timeout="1s") == timedelta(milliseconds=50)
    plc.watch("Main.state", "Main.count")
    with pytest.raises(AssertionError) as err:
        plc.run_until(lambda: plc["Main.state"] == "Idle", timeout="300ms", what="back to Idle")
    text = str(err.value)
    assert text.startswith("back to Idle did not become true within 0.300s (from t=0.050s to t=0.350s)")
    assert "time    Main.lamp  Main.state  Main.count" in text
    assert text.endswith("0.350s  False      Done        36")  # the rows up to the timeout
    with pytest.raises(KeyError, match="Main.nothing"):
        plc.run_until("Main.nothing")


def test_run_until_s_time_is_in_the_trace_s_unit_too(plc):
    """Issue 33: run_until gave a timedelta, trace.changes integer ns: the
    two did not compare. The time is both: a timedelta with .ns."""
    plc.write("Main.limit", "T#100ms")
    plc.script([("50ms", "Main.go", True)])
    plc.watch("Main.lamp")
    t = plc.run_until("Main.lamp", timeout="1s")
    assert t == timedelta(milliseconds=50) and t.ns == 50_000_000
    assert plc.trace.changes("Main.lamp")[-1] == (t.ns, True)
    assert plc.now.ns == plc.now_ns and plc.now - t == timedelta(0)


def test_expect_raises_with_the_trace(plc):
    plc.watch("Main.count")
    plc.step(2)
    plc.expect(plc["Main.count"] == 2)
    with pytest.raises(AssertionError) as err:
        plc.expect(lambda: plc["Main.count"] > 5, "count above 5")
    assert str(err.value).splitlines()[:2] == ["count above 5 at t=0.010s", "time    Main.count"]


def test_durations_are_checked(plc):
    with pytest.raises(ValueError, match="expected a duration such as '2s'"):
        plc.run_for("a while")
    with pytest.raises(ValueError, match="timeout: expected a duration"):
        plc.run_until("Main.go", timeout=-1)


def test_no_simulators_without_a_configuration(plc):
    assert plc.sims == {}
    with pytest.raises(KeyError, match="no simulated device 'x' \\(there are: none\\)"):
        plc.fault("x", "unplug")


def test_stop_is_final_and_idempotent():
    plc = PLC.from_st(SOURCE)
    plc.step()
    plc.stop()
    plc.stop()
    with PLC.from_st(SOURCE) as never_started:
        assert never_started["Main.count"] == 0
