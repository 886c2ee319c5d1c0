"""The softplc command, run as a subprocess the way a user runs it."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
CONVEYOR = REPO / "st_programs" / "conveyor.st"

GOOD = """\
PROGRAM Counter
VAR
    n : INT;
    total : DINT;
    running : BOOL;
    ratio : REAL;
    t0 : TIME;
    up : TIME;
END_VAR
n := n + 1;
total := total + n;
running := n < 3;
ratio := INT_TO_REAL(n) / 4.0;
IF n = 1 THEN
    t0 := TIME();
END_IF
up := TIME() - t0;
END_PROGRAM
"""

BROKEN = """\
PROGRAM Broken
VAR
    x : INT;
END_VAR
x := undeclared + 1;
END_PROGRAM
"""

WARNS = """\
PROGRAM Narrow
VAR
    big : DINT := 5;
    small : INT;
END_VAR
small := big;
END_PROGRAM
"""

DIV_ZERO = """\
PROGRAM Divide
VAR
    a : INT := 10;
    b : INT;
    c : INT;
END_VAR
c := a / b;
END_PROGRAM
"""

FUNC = """\
FUNCTION Twice : INT
VAR_INPUT
    x : INT := 21;
END_VAR
Twice := x * 2;
END_FUNCTION
"""

TWO_PROGRAMS = """\
PROGRAM First
VAR a : INT; END_VAR
a := 1;
END_PROGRAM
PROGRAM Second
VAR b : INT; END_VAR
b := 2;
END_PROGRAM
"""


def softplc(*args, cwd=None, timeout=120):
    """Run `python -m softplc.runtime.cli ARGS` (the same main() as the
    console script), without stdin, as CI does."""
    env = dict(os.environ, PYTHONIOENCODING="utf-8")
    env.pop("SOFTPLC_DEBUG", None)
    return subprocess.run(
        [sys.executable, "-m", "softplc.runtime.cli", *map(str, args)],
        capture_output=True,
        text=True,
        stdin=subprocess.DEVNULL,
        cwd=cwd,
        env=env,
        timeout=timeout,
    )


@pytest.fixture
def st(tmp_path):
    def write(name, text):
        path = tmp_path / name
        path.write_text(text, encoding="utf-8")
        return path

    return write


def no_traceback(proc):
    assert "Traceback" not in proc.stderr and "Traceback" not in proc.stdout


# ---------------------------------------------------------------- check


def test_check_ok(st):
    proc = softplc("check", st("good.st", GOOD))
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr.splitlines() == ["profile: codesys", "0 errors, 0 warnings"]


def test_check_leaves_with_every_line_of_its_output(tmp_path):
    # the console script's check ends with os._exit (cli._leave): nothing written is lost
    for k in range(10):
        body = "".join(f"x{i} := {i};\n" for i in range(40))
        (tmp_path / f"p{k}.st").write_text(f"PROGRAM p{k}\n{body}END_PROGRAM\n", encoding="utf-8")
    proc = softplc("check", tmp_path)
    assert proc.returncode == 1
    no_traceback(proc)
    lines = proc.stderr.splitlines()
    assert len([line for line in lines if ": error E010: unknown name" in line]) == 400
    assert lines[-2:] == ["400 errors, 0 warnings", "for more on a code: softplc check --explain E010"]


def test_check_broken_file(st):
    path = st("broken.st", BROKEN)
    proc = softplc("check", path)
    assert proc.returncode == 1
    no_traceback(proc)
    first = proc.stderr.splitlines()[0]
    assert first.startswith(f"{path}:5:6: error E")  # file:line:col: error CODE
    assert "undeclared" in proc.stderr
    assert "x := undeclared + 1;" in proc.stderr  # the source excerpt
    # the count, then where to read more on the code (softplc check --explain)
    assert "1 error" in proc.stderr.splitlines()[-2]
    assert proc.stderr.splitlines()[-1] == "for more on a code: softplc check --explain E010"


def test_check_reports_warnings_but_succeeds(st):
    proc = softplc("check", st("narrow.st", WARNS), "--profile", "codesys")
    assert proc.returncode == 0
    assert ": warning W" in proc.stderr
    assert proc.stderr.splitlines()[-2].startswith("0 errors, ")
    assert proc.stderr.splitlines()[-1] == "for more on a code: softplc check --explain W121"


@pytest.mark.parametrize("profile", ["iec", "matiec", "MatIEC"])
def test_check_profile_changes_severity(st, profile):
    proc = softplc("check", st("narrow.st", WARNS), "--profile", profile)
    assert proc.returncode == 1
    assert ": error E" in proc.stderr
    assert proc.stderr.splitlines()[-3:-1] == [f"profile: {profile.lower()}", "1 error, 0 warnings"]


def test_check_syntax_error(st):
    proc = softplc("check", st("syntax.st", "PROGRAM p\nVAR x : INT; END_VAR\nx := ;\nEND_PROGRAM\n"))
    assert proc.returncode == 1
    no_traceback(proc)
    assert "syntax.st:3:" in proc.stderr


def test_check_binary_garbage(st, tmp_path):
    path = tmp_path / "garbage.st"
    path.write_bytes(b"\xff\xfe\x00\x81PROGRAM\x00")
    proc = softplc("check", path)
    assert proc.returncode in (1, 2)
    no_traceback(proc)
    assert "garbage.st" in proc.stderr


def test_missing_file_is_a_usage_error(tmp_path):
    proc = softplc("check", tmp_path / "nope.st")
    assert proc.returncode == 2
    no_traceback(proc)
    assert "nope.st" in proc.stderr


def test_unknown_profile_is_a_usage_error(st):
    proc = softplc("check", st("good.st", GOOD), "--profile", "siemens")
    assert proc.returncode == 2
    assert "siemens" in proc.stderr


# ---------------------------------------------------------------- compile


def test_emit_python_to_stdout_compiles(st):
    proc = softplc("compile", st("good.st", GOOD), "--emit-python")
    assert proc.returncode == 0, proc.stderr
    compile(proc.stdout, "good.py", "exec")


def test_emit_python_to_directory(st, tmp_path):
    out = tmp_path / "out"
    proc = softplc("compile", st("good.st", GOOD), "--emit-python", "-o", out)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout == ""
    compile((out / "good.py").read_text(encoding="utf-8"), "good.py", "exec")


def test_compile_errors_exit_1(st):
    proc = softplc("compile", st("broken.st", BROKEN), "--emit-python")
    assert proc.returncode == 1
    no_traceback(proc)
    assert "broken.st:5:6" in proc.stderr
    assert proc.stdout == ""


def test_output_dir_needs_emit_python(st, tmp_path):
    proc = softplc("compile", st("good.st", GOOD), "-o", tmp_path)
    assert proc.returncode == 2


# ---------------------------------------------------------------- exec


def test_exec_program(st):
    proc = softplc("exec", st("good.st", GOOD), "--cycles", "4")
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert out["n"] == 4
    assert out["total"] == 1 + 2 + 3 + 4
    assert out["running"] is False
    assert out["ratio"] == 1.0
    assert out["up"].upper().startswith("T#")


def test_exec_default_is_one_cycle(st):
    out = json.loads(softplc("exec", st("good.st", GOOD)).stdout)
    assert out["n"] == 1


@pytest.mark.parametrize(
    "cycle_time, up",
    [
        (None, "T#20ms"),
        ("10ms", "T#20ms"),
        ("T#1s", "T#2s"),
        ("250", "T#500ms"),
        ("1m", "T#2m"),
        ("time#1s500ms", "T#3s"),
    ],
)
def test_exec_cycle_time(st, cycle_time, up):
    # Three cycles: the clock moves two cycle times from the first to the last.
    options = [] if cycle_time is None else ["--cycle-time", cycle_time]
    proc = softplc("exec", st("good.st", GOOD), "--cycles", "3", *options)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["up"] == up


@pytest.mark.parametrize("bad", ["fast", "500us", "0ms", "-5ms", "1.5ms"])
def test_exec_bad_cycle_time(st, bad):
    proc = softplc("exec", st("good.st", GOOD), "--cycle-time", bad)
    assert proc.returncode == 2, bad
    no_traceback(proc)
    assert "--cycle-time" in proc.stderr


def test_exec_function(st):
    proc = softplc("exec", st("twice.st", FUNC), "--entry", "twice")
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout) == {"return": 42}


def test_exec_needs_entry_without_single_program(st):
    proc = softplc("exec", st("twice.st", FUNC))
    assert proc.returncode == 2
    proc = softplc("exec", st("two.st", TWO_PROGRAMS))
    assert proc.returncode == 2
    assert "First" in proc.stderr and "Second" in proc.stderr
    proc = softplc("exec", st("two.st", TWO_PROGRAMS), "--entry", "SECOND")
    assert proc.returncode == 0
    assert json.loads(proc.stdout) == {"b": 2}


GLOBALS = """\
VAR_GLOBAL
    gCount : INT;
END_VAR
FUNCTION_BLOCK Blinker
VAR_OUTPUT on : BOOL; END_VAR
on := NOT on;
END_FUNCTION_BLOCK
PROGRAM Main
VAR_EXTERNAL gCount : INT; END_VAR
VAR b : Blinker; END_VAR
gCount := gCount + 1;
b();
END_PROGRAM
"""


def test_exec_shows_globals_and_nested_blocks(st):
    proc = softplc("exec", st("globals.st", GLOBALS), "--cycles", "3")
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout) == {"b": {"on": True}, "VAR_GLOBAL": {"gCount": 3}}


def test_exec_function_block_entry_is_a_usage_error(st):
    proc = softplc("exec", st("globals.st", GLOBALS), "--entry", "Blinker")
    assert proc.returncode == 2
    assert "FUNCTION_BLOCK" in proc.stderr


def test_exec_unknown_entry(st):
    proc = softplc("exec", st("good.st", GOOD), "--entry", "NoSuchThing")
    assert proc.returncode == 2
    no_traceback(proc)
    assert "NoSuchThing" in proc.stderr


def test_exec_runtime_fault_exits_3_with_st_location(st):
    path = st("divide.st", DIV_ZERO)
    proc = softplc("exec", path)
    assert proc.returncode == 3
    no_traceback(proc)
    assert f"{path}:7:" in proc.stderr
    assert "division by zero" in proc.stderr
    assert proc.stdout == ""


def test_exec_compile_error_exits_1(st):
    proc = softplc("exec", st("broken.st", BROKEN))
    assert proc.returncode == 1
    no_traceback(proc)


def test_exec_example_plant():
    proc = softplc("exec", CONVEYOR, "--cycles", "200", cwd=REPO)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert out["batches"] == 1
    assert out["state"] == "Idle"
    assert out["partCounter"]["CV"] == out["batchSize"] == 8
    assert out["motor"]["starts"] == 1
    assert out["motor"]["run"] is False
    assert all(t.upper().startswith("T#") for t in out["partAt"])


# ---------------------------------------------------------------- the command itself


def test_usage_errors():
    assert softplc().returncode in (0, 2)  # bare command: help
    proc = softplc("frobnicate")
    assert proc.returncode == 2
    proc = softplc("exec")  # no FILE
    assert proc.returncode == 2
    no_traceback(proc)


def test_help_and_version():
    proc = softplc("--help")
    assert proc.returncode == 0
    for command in ("check", "compile", "exec"):
        assert command in proc.stdout
    assert softplc("--version").returncode == 0


def test_console_script_is_installed():
    script = Path(sys.executable).with_name("softplc")
    if not script.exists():
        pytest.skip("console script not installed next to this Python")
    proc = subprocess.run([str(script), "--help"], capture_output=True, text=True, stdin=subprocess.DEVNULL, timeout=60)
    assert proc.returncode == 0 and "exec" in proc.stdout


# ---------------------------------------------------------------- check: another profile


def test_check_suggests_schneider_for_the_schneider_samples():
    proc = softplc("check", REPO / "st_programs" / "ltmr_read_sdo.st")
    assert proc.returncode == 1
    no_traceback(proc)
    assert proc.stderr.splitlines()[-4:-2] == [
        "profile: codesys",
        "reads like schneider (0x literals, %MW..:X bits and %MW..:n tables, ADR#); try --profile schneider",
    ]
    assert softplc("check", "--profile", "schneider", REPO / "st_programs" / "ltmr_read_sdo.st").returncode == 0


# MatIEC: comments do not nest, so '(* (*' closes at the first '*)'; with
# CODESYS nesting the rest of the file would be a comment.
MATIEC_FILE = """\
PROGRAM main
VAR x : INT; END_VAR
(* counts (* cycles *)
x := x + 1;
{{ printf("%d", 1); }}
END_PROGRAM
"""


def test_check_suggests_the_profile_a_file_reads_like(st):
    proc = softplc("check", st("beremiz.st", MATIEC_FILE))
    assert proc.returncode == 1
    assert proc.stderr.splitlines()[-3] == "reads like matiec ({{ }} embedded C); try --profile matiec"


def test_check_suggests_nothing_when_no_other_profile_does_better(st):
    # a MatIEC marker, but the error (an unknown name) is the same everywhere
    proc = softplc("check", st("bad.st", "PROGRAM p\nVAR x : INT; END_VAR\n{{ x++; }}\nx := y;\nEND_PROGRAM\n"))
    assert proc.returncode == 1
    assert "reads like" not in proc.stderr
    assert proc.stderr.splitlines()[-3] == "profile: codesys"


def test_check_explain_prints_the_page_of_a_code():
    # like rustc --explain: the page on stdout, no FILES needed, any case
    proc = softplc("check", "--explain", "e030")
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.startswith("# E030: ") and "```st" in proc.stdout and proc.stderr == ""


def test_check_explain_of_an_unknown_code_names_the_near_ones():
    proc = softplc("check", "--explain", "E034")
    assert proc.returncode == 2 and proc.stdout == ""
    assert "no diagnostic code 'E034'; near: E032, E031, E030" in proc.stderr
    no_traceback(proc)


def test_check_without_files_or_explain_is_a_usage_error():
    proc = softplc("check")
    assert proc.returncode == 2 and "Missing argument" in proc.stderr
