"""`softplc run`, as a user runs it: the embedded default, configs from
files, watch/trace/final JSON, config and compile errors, scenarios, traces
and online change (signals and the retain file: test_launch_retain.py)."""

from __future__ import annotations

import csv
import json
import re
import signal
import subprocess
import sys

import pytest

from .launch_support import FAULTS_AT_SCAN_3, REPO, env, no_orphans, spawn, wait_for_line, write_config  # noqa: F401  # no_orphans: autouse
from .test_cli import softplc

# each test starts softplc in a process of its own
pytestmark = pytest.mark.slow


# ---------------------------------------------------------------- the embedded default


def test_default_example_runs_in_virtual_time(tmp_path):
    out = tmp_path / "final.json"
    proc = softplc("run", "--virtual-time", "--duration", "10s", "--final-json", out)
    assert proc.returncode == 0, proc.stderr
    final = json.loads(out.read_text())
    assert set(final) == {"Conveyor", "Panel", "Motor", "Drive", "Pump"}
    # START is pressed at 0.1 s and 5.1 s; each batch of 8 parts is done well within 5 s.
    assert final["Conveyor"]["batches"] == 2
    assert final["Conveyor"]["state"] == "Idle"
    # The LTMR on the simulated CANopen bus: forward at 0 s, reverse at 4 s, forward at 8 s,
    # and trip register 1 read by READ_VAR every 2 s without an error.
    assert "canopen: node motor (40) operational" in proc.stderr
    assert final["Motor"]["starts"] == 3 and final["Motor"]["trips"] == 0
    assert final["Motor"]["reads"] == 4 and final["Motor"]["readErrors"] == 0
    # The DA1 on Modbus RTU: at 40 Hz after 4 s, held 2 s, then reversing through zero
    # (80 Hz at 10 Hz/s) when the run ends; every exchange answered.
    drive = final["Drive"]
    assert drive["state"] == "RunReverse" and drive["faults"] == 0 and drive["MonitorOk"]
    assert drive["drive"]["MODEL"] == "DA1" and not drive["drive"]["ERROR"]
    assert drive["drive"]["EXCHANGES"] > 400 and drive["AccelRamp"] == 50
    assert "modbus: 1 up" in proc.stderr
    # The FC 280 on the same CANopen bus, guarded: up to 80 % (ramp 2 s per 50 Hz), held 5 s,
    # then 40 % (16-05 = 199Ah), no trip although the control word did not change for 5 s.
    assert "canopen: node pump (20) operational" in proc.stderr and "canopen: 2/2 up" in proc.stderr
    pump = final["Pump"]
    assert pump["state"] == "Low" and pump["trips"] == 0 and pump["actualWord"] == 0x199A
    assert pump["drive"]["RUNNING"] and pump["controlWord"] == 0x047C
    assert "stopped after 1000 scans" in proc.stderr


def test_watch_and_trace_sample_every_scan(tmp_path):
    trace = tmp_path / "trace.csv"
    proc = softplc(
        "run",
        "--virtual-time",
        "--cycles",
        "300",
        "--watch",
        "Conveyor.state,Conveyor.speedOut",
        "--watch",
        "%QX0.0",
        "--watch",
        "Panel.speedPercent",
        "--trace",
        trace,
    )
    assert proc.returncode == 0, proc.stderr
    rows = list(csv.DictReader(trace.open()))
    assert len(rows) == 300
    watched = ["Conveyor.state", "Conveyor.speedOut", "%QX0.0", "Panel.speedPercent"]
    assert list(rows[0]) == ["time_ms", "cycle", *watched, "[[sim]]"]  # the plant's devices' events last
    assert not any(r["[[sim]]"] for r in rows)  # none in the first 3 s
    assert [float(r["time_ms"]) for r in rows[:3]] == [0.0, 10.0, 20.0]
    running = [r for r in rows if r["%QX0.0"] == "1"]
    assert running, "the belt never ran"
    # The panel (100 ms task) sees the speed one loopback scan after the conveyor wrote it.
    full = [r for r in rows if r["Conveyor.speedOut"] == "1000"]
    assert full and any(float(r["Panel.speedPercent"]) == 100.0 for r in rows)
    # The status line at the end names the watched values.
    assert "Conveyor.state=" in proc.stderr and "%QX0.0=" in proc.stderr


def test_final_json_to_stdout_matches_exec_encoding():
    proc = softplc("run", "--virtual-time", "--cycles", "200", "--final-json", "-")
    assert proc.returncode == 0, proc.stderr
    final = json.loads(proc.stdout)
    conveyor = final["Conveyor"]
    assert conveyor["partCounter"]["CV"] == conveyor["batchSize"] == 8
    assert all(t.startswith("T#") for t in conveyor["partAt"])


# ---------------------------------------------------------------- errors


def test_config_error_names_file_and_key(tmp_path):
    cfg = write_config(
        tmp_path,
        '[plc]\nprograms = ["p.st"]\n[[task]]\nname = "T"\ninterval = "fast"\nprograms = ["Main"]\n',
        {"p.st": "PROGRAM Main\nEND_PROGRAM\n"},
    )
    proc = softplc("run", cfg, "--virtual-time", "--cycles", "1")
    assert proc.returncode == 2
    assert f"{cfg}: task[0].interval: expected a duration" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_unknown_program_in_a_task(tmp_path):
    cfg = write_config(
        tmp_path,
        '[plc]\nprograms = ["p.st"]\n[[task]]\nname = "T"\ninterval = "10ms"\nprograms = ["Mian"]\n',
        {"p.st": "PROGRAM Main\nEND_PROGRAM\n"},
    )
    proc = softplc("run", cfg, "--virtual-time", "--cycles", "1")
    assert proc.returncode == 2
    assert "task[0].programs[0]: 'Mian' is not a PROGRAM" in proc.stderr
    assert "did you mean 'Main'?" in proc.stderr


_MAIN = '[plc]\nprograms = ["p.st"]\n[[task]]\nname = "T"\ninterval = "10ms"\nprograms = ["Main"]\n'
_RTU = '[[modbus]]\nname = "drives"\ntransport = "rtu"\ndevice = "sim"\n'
_CHANNEL = '[[modbus.channel]]\nunit = 1\nfunction = 3\noffset = 5\nread_to = "%IW200"\n'
_NODE = '[[can]]\ninterface = "virtual"\nchannel = "hostile"\n[canopen]\n[[canopen.node]]\nname = "pump"\nid = 20\n'


@pytest.mark.parametrize(
    ("text", "key", "message"),
    [
        (_MAIN + _RTU + _CHANNEL + "count = '5'\n", "modbus[0].channel[0].count", "expected an integer from 1 to 2000"),
        (_MAIN + _RTU + 'timeout = "100000000000h"\n', "modbus[0].timeout", "expected a duration of at most 1d"),
        (_MAIN.replace('"p.st"', f'"{"p" * 300}.st"'), "plc.programs[0]", "file name too long: "),
        (_MAIN + f'[retain]\nfile = "{"r" * 300}"\n', "retain.file", "file name too long: "),
        (_MAIN.replace('"10ms"', f'"{"x" * 5000}"'), "task[0].interval", f"(got '{'x' * 60}…' (5000 characters))"),
        (_MAIN + '[[loopback]]\nfrom = "%QD1"\nto = "%ID2"\nbytes = 65535\n', "loopback[0].bytes", "run past"),
        (
            _MAIN + _NODE + 'eds = "fc280"\nguard_time = "100ms"\nheartbeat_timeout = "300ms"\n',
            "canopen.node[0].heartbeat_timeout",
            "only meaningful with a heartbeat",
        ),
        (
            _MAIN + _NODE + 'eds = "fc280"\nguard_time = "100ms"\nsdo = [{ parameter = "8-03", value = inf }]\n',
            "canopen.node[0].sdo[0].value",
            "(got inf)",
        ),
        (_MAIN.replace('"T"', f'"{"T" * 1_000_000}"'), "task[0].name", "of at most 100 characters (got 'TTTT"),
        (_MAIN + _NODE.replace('"hostile"', f'"{"c" * 1_000_000}"') + 'eds = "fc280"\n', "can[0].channel", "255"),
        (_MAIN + f'[web]\nport = 0\nhost = "{"h" * 1_000_000}"\n', "web.host", "(1000000 characters))"),
        (_MAIN + "[opcua]\nport = 0\nusers_file = 'p.st.bin'\n", "opcua.users_file", "not UTF-8 text (byte 0)"),
        (
            _MAIN + _NODE + 'eds = "ltmr"\nsdo = [{ object = "2007:21", value = 999999 }]\n',
            "canopen.node[0].sdo[0]",
            "",
        ),
    ],
    ids=[
        "count type",
        "RTU timeout",
        "program path",
        "retain path",
        "5000 chars",
        "loopback",
        "guarded",
        "inf",
        "1 MB task name",
        "1 MB CAN channel",
        "1 MB web host",
        "users file",
        "SDO value",
    ],
)
def test_hostile_configuration_values_exit_2_naming_file_and_key(tmp_path, text, key, message):
    """Each of these took softplc down (exit 4, a Python error) or named
    neither the file nor the key; the real clock, as a plant runs."""
    cfg = write_config(tmp_path, text, {"p.st": "PROGRAM Main\nEND_PROGRAM\n"})
    (tmp_path / "p.st.bin").write_bytes(b"\xff\xfe[users]\n")
    proc = softplc("run", cfg, "--duration", "0.1s")
    assert proc.returncode == 2, proc.stderr
    [line] = [ln for ln in proc.stderr.splitlines() if ln.startswith(f"softplc: {cfg}: ")]
    assert line.startswith(f"softplc: {cfg}: {key}: ") and message in line
    assert len(line) < 400 and "Traceback" not in proc.stderr and "internal error" not in proc.stderr
    assert len(proc.stderr) < 2000  # nothing long echoed into the log either


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (_MAIN + "x = " + "[" * 5000 + "]" * 5000 + "\n", ":7:37: tables, arrays or dotted keys nested more than 32"),
        (_MAIN + "x = " + "{a = " * 2000 + "1" + "}" * 2000 + "\n", ":7:165: tables, arrays or dotted keys"),
        (_MAIN + "[outputs]\n" + ".".join(["a"] * 5000) + " = 1\n", ": outputs.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a."),
        (_MAIN + "priority = " + "9" * 5000 + "\n", ":7:12: an integer of 5000 digits: no key takes a number"),
        (_MAIN + '[outputs]\nsafe = { "%QL65535" = 1 }\n', ': outputs.safe."%QL65535": %QL65535 (bytes 524280'),
    ],
    ids=["deep arrays", "deep inline tables", "deep dotted key", "5000 digits", "safe value past the image"],
)
def test_hostile_documents_exit_2_not_4(tmp_path, text, message):
    """Each of these was exit 4: a RecursionError, a ValueError of Python's
    int(), an AddressError at the start."""
    cfg = write_config(tmp_path, text, {"p.st": "PROGRAM Main\nEND_PROGRAM\n"})
    proc = softplc("run", cfg, "--virtual-time", "--cycles", "1")
    assert proc.returncode == 2, proc.stderr
    assert proc.stderr.startswith(f"softplc: {cfg}{message}")
    assert len(proc.stderr) < 2000 and "Traceback" not in proc.stderr and "internal error" not in proc.stderr


def test_compile_error_gives_st_location(tmp_path):
    cfg = write_config(
        tmp_path,
        '[plc]\nprograms = ["p.st"]\n',
        {"p.st": "PROGRAM Main\nVAR x : INT; END_VAR\nx := TRUE;\nEND_PROGRAM\n"},
    )
    proc = softplc("run", cfg, "--virtual-time", "--cycles", "1")
    assert proc.returncode == 1
    assert "p.st:3:6: error" in proc.stderr


def test_unknown_watch_variable(tmp_path):
    proc = softplc("run", "--virtual-time", "--cycles", "1", "--watch", "Conveyor.nope")
    assert proc.returncode == 2
    assert "--watch: no variable 'Conveyor.nope'" in proc.stderr


def test_runtime_fault_exit_code_and_message(tmp_path):
    cfg = write_config(tmp_path, '[plc]\nprograms = ["p.st"]\n', {"p.st": FAULTS_AT_SCAN_3})
    out = tmp_path / "final.json"
    proc = softplc("run", cfg, "--virtual-time", "--cycles", "10", "--final-json", out)
    assert proc.returncode == 3, proc.stderr
    assert "task MainTask stopped by a runtime fault: " in proc.stderr
    assert "p.st:5:5: runtime fault: division by zero" in proc.stderr
    assert "MainTask FAULT:" in proc.stderr and "faults=1 outputs SAFE" in proc.stderr  # the status line
    assert json.loads(out.read_text())["Main"]["n"] == 3


SURROGATE = """
PROGRAM Main
VAR RETAIN
    w : WSTRING[10];
END_VAR
w := WCHAR_TO_WSTRING(WORD_TO_WCHAR(16#D800));
END_PROGRAM
"""


def test_final_json_takes_a_string_holding_a_lone_surrogate(tmp_path):
    # A program can make one (a WCHAR of code D800h); --final-json exited 4 (UnicodeEncodeError) on
    # it, and on every later warm start of a retain file holding it. Now: JSON's \ud800 escape.
    cfg = write_config(
        tmp_path,
        '[plc]\nprograms = ["w.st"]\n[retain]\nfile = "w.retain"\n[[task]]\nname = "Main"\n'
        'interval = "10ms"\nprograms = ["Main"]\n',
        {"w.st": SURROGATE},
    )
    for _run in range(2):
        result = softplc("run", cfg, "--virtual-time", "--cycles", "2", "--final-json", "-")
        assert result.returncode == 0, result.stderr
        assert '"w": "\\ud800"' in result.stdout and json.loads(result.stdout)["Main"]["w"] == "\ud800"


_SCENARIO_ST = """TYPE Mode : (Off, Auto, Hand); END_TYPE
PROGRAM Main
VAR sp : REAL := 1.0; mode : Mode; t : TIME; seen : REAL; grid : ARRAY[1..2, 1..2] OF INT; END_VAR
seen := sp;
END_PROGRAM
"""


def test_a_scenario_from_the_file_and_the_command_line(tmp_path):
    """Issue 33: initial values and scheduled writes from the TOML and from
    --set, which goes over [init]; the log says what was written and when."""
    text = (
        _MAIN + '[init]\nMain.sp = 40\nMain.mode = "Auto"\n[[schedule]]\nat = "30ms"\nset = "Main.sp"\nvalue = 60.5\n'
    )
    cfg = write_config(tmp_path, text, {"p.st": _SCENARIO_ST})
    sets = ["--set", "Main.mode=Hand", "--set", "Main.t=T#2s", "--set", "Main.grid[2, 1]=7"]
    proc = softplc(
        "run",
        cfg,
        "--virtual-time",
        "--cycles",
        "5",
        "--watch",
        "Main.seen,Main.grid[2, 1]",
        *sets,
        "--final-json",
        "-",
    )
    assert proc.returncode == 0, proc.stderr
    main = json.loads(proc.stdout)["Main"]
    assert (main["sp"], main["seen"], main["mode"], main["t"]) == (60.5, 60.5, "Hand", "T#2s")
    assert main["grid"] == [[0, 0], [7, 0]]
    assert 'scenario: t=0.000s Main.sp := 40 (init."Main.sp")' in proc.stderr
    assert "scenario: t=0.030s Main.sp := 60.5 (schedule[0].set)" in proc.stderr
    bad = softplc("run", cfg, "--virtual-time", "--cycles", "1", "--set", "Main.nope=1")
    assert bad.returncode == 2 and f"softplc: {cfg}: --set Main.nope: " in bad.stderr, bad.stderr
    bad = softplc("run", cfg, "--virtual-time", "--cycles", "1", "--set", "Main.sp")
    assert bad.returncode == 2 and "--set 'Main.sp': expected VAR=VALUE" in bad.stderr, bad.stderr


def test_watch_and_trace_take_an_element_of_a_drivers_array(tmp_path):
    """Issue 33: --watch 'CANOPEN_NODE[33].State' was "no variable"."""
    watched = ["CANOPEN_NODE[40].Operational", "CANOPEN_NODE[20].State"]
    trace = tmp_path / "nodes.csv"
    proc = softplc("run", "--virtual-time", "--duration", "3s", "--watch", ",".join(watched), "--trace", trace)
    assert proc.returncode == 0, proc.stderr
    rows = list(csv.DictReader(trace.open()))
    assert rows[-1]["CANOPEN_NODE[40].Operational"] == "1"  # the LTMR (node 40) booted and operational
    assert {r["CANOPEN_NODE[20].State"] for r in rows} - {""}  # a value in every row
    assert "CANOPEN_NODE[20].State=" in proc.stderr  # on the status line


def test_traces_by_their_ending_csv_vcd_and_png(tmp_path):
    from matplotlib import image

    from softplc.runtime.trace.vcd import read_vcd

    watched = ["Motor.state", "Motor.ltmr.Running", "Drive.drive.ACTUAL_HZ", "Pump.drive.ACTUAL", "%QX0.0"]
    proc = softplc(
        "run",
        "--virtual-time",
        "--duration",
        "3s",
        "--watch",
        ",".join(watched),
        "--trace",
        tmp_path / "run.csv",
        "--trace",
        tmp_path / "run.vcd",
        "--trace",
        tmp_path / "run.png",
        "--unit",
        "Drive.drive.ACTUAL_HZ=Hz",
        "--unit",
        "Pump.drive.ACTUAL=Hz",
    )
    assert proc.returncode == 0, proc.stderr
    rows = list(csv.DictReader((tmp_path / "run.csv").open()))
    assert len(rows) == 300 and rows[-1]["time_ms"] == "2990.0"
    assert {r["Motor.state"] for r in rows} >= {"Forward"}  # enumerations by name
    vcd = read_vcd(tmp_path / "run.vcd")
    assert sorted(vcd.names()) == sorted(watched)
    running = next(s for s in vcd.series if s.name == "Motor.ltmr.Running")
    assert running.kind == "bool" and running.times[-1] == 3.0  # the VCD ends where the run did
    in_csv = [(float(r["time_ms"]) / 1e3, int(r["Motor.ltmr.Running"])) for r in rows]
    assert _changes(zip(running.times, running.values)) == _changes(in_csv)
    assert len(_changes(in_csv)) > 1  # it did change
    pixels = image.imread(tmp_path / "run.png")
    assert pixels.shape[1] == 1210 and pixels.shape[0] > 500
    assert f"wrote {tmp_path / 'run.png'}" in proc.stderr
    # --duration 3s ends at 3.00 s of engine time, shown on the last status line and the log lines
    assert "t=3.00s | cycles=300" in proc.stderr
    assert "t=3.000s softplc INFO: stopped after 300 scans" in proc.stderr

    # `softplc plot` draws the existing traces, a chosen few signals
    for source, out in (("run.csv", "a.svg"), ("run.vcd", "b.png")):
        plotted = softplc(
            "plot", tmp_path / source, "-o", tmp_path / out, "--signals", "Motor.state,Pump.drive.ACTUAL", cwd=tmp_path
        )
        assert plotted.returncode == 0, plotted.stderr
        assert f"wrote {tmp_path / out}" in plotted.stderr
    assert "Pump.drive.ACTUAL" in (tmp_path / "a.svg").read_text()
    assert (tmp_path / "b.png").read_bytes()[:4] == b"\x89PNG"
    default = softplc("plot", tmp_path / "run.csv")
    assert default.returncode == 0 and (tmp_path / "run.png").exists()


def _changes(samples) -> list:
    out: list = []
    for t, v in samples:
        if not out or out[-1][1] != v:
            out.append((round(t, 6), v))
    return out


@pytest.mark.parametrize(
    "args, message",
    [
        (["--trace", "run.txt"], "--trace run.txt: say which trace by the name's ending: .csv, .vcd, .png, .svg, .pdf"),
        (["--watch", "Motor.state", "--unit", "Motor.speed=Hz"], "--unit Motor.speed: not watched"),
        (["--unit", "Motor.speed"], "--unit 'Motor.speed': write PATH=UNIT"),
        (["--trace", "/nonexistent/dir/run.png"], "--trace: cannot write /nonexistent/dir/run.png"),
    ],
)
def test_bad_trace_options_are_refused_before_the_run(args, message):
    proc = softplc("run", "--virtual-time", "--cycles", "1", *args)
    assert proc.returncode == 2
    assert message in proc.stderr


def test_plot_refuses_what_it_cannot_draw(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("a,b\n")
    proc = softplc("plot", bad)
    assert proc.returncode == 2 and "bad.csv: not a CSV trace of softplc run" in proc.stderr
    good = tmp_path / "good.csv"
    good.write_text("time_ms,cycle,x\n0.0,1,1\n")
    proc = softplc("plot", good, "--signals", "y")
    assert proc.returncode == 2 and "no signal y" in proc.stderr
    proc = softplc("plot", good, "-o", tmp_path / "x.jpg")
    assert proc.returncode == 2 and "the ending says the format" in proc.stderr


def test_duration_ends_at_that_engine_time_however_long_the_start_took():
    from softplc.runtime.engine.clock import VirtualClock
    from softplc.runtime.launch import run_for

    from .engine.conftest import MS, make_engine, task

    src = "PROGRAM Main VAR n : INT; END_VAR n := n + 1; END_PROGRAM"
    # the engine clock already reads 190 ms when the scan begins, as after a slow bus start-up
    engine = make_engine(src, [task("Main", 10, "Main")], clock=VirtualClock(start_ns=190 * MS))
    try:
        ran = run_for(engine, cycles=None, duration_ns=5000 * MS)
        assert engine.clock.now_ns() == 5000 * MS  # t=5.00s, not 5.19s
        assert ran == 481  # scans at 190, 200 .. 4990 ms
        assert run_for(engine, cycles=None, duration_ns=1000 * MS) == 0  # already past it: no scan
        assert run_for(engine, cycles=3, duration_ns=None) == 3
    finally:
        engine.stop()


def test_log_lines_carry_wall_time_and_engine_time():
    import io
    import logging

    from softplc.runtime.engine.clock import VirtualClock
    from softplc.runtime.launch import _setup_logging

    out = io.StringIO()
    handler, engine_time = _setup_logging(tty=False, stream=out)
    try:
        log = logging.getLogger("softplc.runtime.io.test")
        log.info("before the engine")
        engine_time.clock = VirtualClock(start_ns=12_340_000_000)
        log.warning("node %d lost", 20)
    finally:
        logging.getLogger("softplc").removeHandler(handler)
    before, after = out.getvalue().splitlines()
    wall = r"\d{4}-\d\d-\d\d \d\d:\d\d:\d\d,\d{3}"
    assert re.fullmatch(wall + r" softplc INFO: before the engine", before)
    assert re.fullmatch(wall + r" t=12\.340s softplc WARNING: node 20 lost", after)


@pytest.mark.realtime  # the real clock runs the PLC; the test waits for log lines, never for a time
def test_online_change_on_sighup_keeps_values_and_refuses_a_broken_file(tmp_path):
    counter = "PROGRAM Main\nVAR n : DINT; {} END_VAR\nn := n + 1;\nEND_PROGRAM\n"
    cfg = write_config(tmp_path, '[plc]\nprograms = ["p.st"]\n', {"p.st": counter.format("")})
    out = tmp_path / "final.json"
    proc = spawn("run", cfg, "--final-json", out)
    wait_for_line(proc, "online change: watching 1 file(s)")
    wait_for_line(proc, "running;")
    (tmp_path / "p.st").write_text(counter.format("added : INT := 7;"))
    proc.send_signal(signal.SIGHUP)  # or the watcher sees the file first: either way one change
    lines = wait_for_line(proc, "applied before scan")
    assert any("online change (" in line for line in lines)
    (tmp_path / "p.st").write_text(counter.format("added : INT := 7; broken"))
    proc.send_signal(signal.SIGHUP)
    lines = wait_for_line(proc, "NOT applied")
    lines += wait_for_line(proc, "p.st:2:")  # the diagnostic, with its file:line:column
    proc.send_signal(signal.SIGINT)
    _stdout, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 0, stderr
    final = json.loads(out.read_text())
    assert final["Main"]["added"] == 7 and final["Main"]["n"] > 1  # the counter went on, the new variable is there


def test_no_online_change_in_virtual_time_unless_asked(tmp_path):
    cfg = write_config(tmp_path, '[plc]\nprograms = ["p.st"]\n', {"p.st": "PROGRAM Main\nEND_PROGRAM\n"})
    plain = subprocess.run(
        [sys.executable, "-m", "softplc.runtime.cli", "run", cfg, "--virtual-time", "--cycles", "3"],
        capture_output=True,
        text=True,
        env=env(),
        timeout=120,
    )
    asked = subprocess.run(
        [sys.executable, "-m", "softplc.runtime.cli", "run", cfg, "--virtual-time", "--cycles", "3", "--online-change"],
        capture_output=True,
        text=True,
        env=env(),
        timeout=120,
    )
    assert plain.returncode == asked.returncode == 0
    assert "online change" not in plain.stderr and "online change: watching 1 file(s)" in asked.stderr
