"""The benchmarks (benchmarks/) measure speed and are not run by the suite;
this only keeps them from rotting: each imports everything it uses and
understands its command line."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

BENCHMARKS = sorted((Path(__file__).resolve().parents[1] / "benchmarks").glob("bench_*.py"))


def test_there_are_benchmarks():
    assert [b.name for b in BENCHMARKS] == [
        "bench_canopen.py",
        "bench_canopen_flood.py",
        "bench_check.py",
        "bench_engine.py",
        "bench_examples.py",
        "bench_genset.py",
        "bench_language.py",
        "bench_language_limits.py",
        "bench_loops.py",
        "bench_modbus.py",
        "bench_modbus_server.py",
        "bench_native.py",
        "bench_online_change.py",
        "bench_soak.py",
        "bench_soak_live.py",
        "bench_spin.py",
        "bench_split.py",
        "bench_startup.py",
        "bench_surfaces.py",
        "bench_sweep.py",
    ]


@pytest.mark.parametrize("script", BENCHMARKS, ids=lambda p: p.name)
def test_benchmark_starts(script):
    done = subprocess.run([sys.executable, str(script), "--help"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("usage:")


REAL_PROJECTS = BENCHMARKS[0].parent / "real_projects.py"


def test_real_projects_reads_projects_of_each_kind():
    """benchmarks/real_projects.py on the tests' own small projects: one row each."""
    here = Path(__file__).resolve().parent / "project"
    args = [str(here / name) for name in ("twincat", "codesys/Line.xml", "beremiz", "folder")]
    done = subprocess.run(
        [sys.executable, str(REAL_PROJECTS), *args, "--cycles", "5"], capture_output=True, text=True, timeout=300
    )
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0].startswith("host: timeit factor ")
    assert lines[1].split()[:3] == ["project", "kind", "files"]
    rows = {line.split()[0]: line.split()[1:] for line in lines[2:6]}
    assert rows["Plc"][:6] == ["twincat", "4", "2", "2", "(100", "%)"] and rows["Plc"][6] == "1/1"
    assert rows["Line"][0] == "codesys" and rows["beremiz"][0] == "beremiz" and rows["folder"][0] == "folder"
    assert lines[-1].startswith("all: 4 projects, 7 POUs, 7 compiled (100 %), 4/4 PROGRAMs ran, 0 errors")


TCUNIT_VERIFIER = BENCHMARKS[0].parent / "tcunit_verifier.py"
TCUNIT_DEMO = Path(__file__).resolve().parent / "testing" / "data" / "tcunit" / "TcUnitDemo"
VERIFIER_CLASS = """\
using System.Collections.Generic;

namespace TcUnit.Verifier
{
    class FB_Lamp_Test : TestFunctionBlockAssert
    {
        public FB_Lamp_Test(IEnumerable<ErrorList.Error> errors, string testFunctionBlockInstance = null)
            : base(errors, testFunctionBlockInstance)
        {
            Presses();
            Counts();
        }

        private void Presses()
        {
            string testMessage = CreateFailedTestMessage("ExpectsTooManyPresses", "5", "4", "five presses");
            AssertContainsMessage(testMessage, EnvDTE80.vsBuildErrorLevel.vsBuildErrorLevelHigh);
            AssertContainsMessage("no such message", EnvDTE80.vsBuildErrorLevel.vsBuildErrorLevelHigh);
        }

        private void Counts()
        {
            string testMessage = CreateFailedTestMessage("CountsEachPress", "2", "2", "two presses");
            AssertDoesNotContainMessage(testMessage, EnvDTE80.vsBuildErrorLevel.vsBuildErrorLevelHigh);
            AssertMessageCount("Test name=CountsEachPress", 1, EnvDTE80.vsBuildErrorLevel.vsBuildErrorLevelLow);
        }
    }
}
"""


def test_tcunit_verifier_counts_the_expectations_that_hold(tmp_path):
    """benchmarks/tcunit_verifier.py on a small verifier of its own: the
    tests' TcUnit project and one class of expectations in the verifier's C#."""
    verifier = tmp_path / "TcUnit-Verifier"
    project = verifier / "TcUnit-Verifier_TwinCAT" / "TcUnitDemo"
    shutil.copytree(TCUNIT_DEMO, project)
    prg = project / "Test" / "PRG_TEST.TcPOU"
    prg.write_text(prg.read_text().replace("fbLamp_Test", "Lamp_Test"))
    dotnet = verifier / "TcUnit-Verifier_DotNet" / "TcUnit-Verifier"
    dotnet.mkdir(parents=True)
    (dotnet / "FB_Lamp_Test.cs").write_text(VERIFIER_CLASS)
    done = subprocess.run(
        [sys.executable, str(TCUNIT_VERIFIER), str(verifier)], capture_output=True, text=True, timeout=300
    )
    assert done.returncode == 0, done.stderr
    out = done.stdout
    assert "ran 1 test suites, 4 tests: {'passed': 2, 'failed': 1, 'skipped': 1, 'error': 0}" in out
    assert "  FB_Lamp_Test: 3/4\n      FAIL contains 'no such message'" in out
    assert out.rstrip().endswith("total: 3/4 checks hold")


NATIVE = BENCHMARKS[0].parent / "bench_native.py"
NATIVE_C = BENCHMARKS[0].parent / "native" / "scan.c"
WORKLOADS = ("numeric", "bits", "timers", "methods")
no_cc = pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler (cc) on PATH to build benchmarks/native")


def run_native(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(NATIVE), *args], capture_output=True, text=True, timeout=300)


@no_cc
def test_native_twins_end_in_the_generated_programs_state():
    """benchmarks/native/scan.c, the C version of bench_language.py's four
    programs, ends in the generated Python's state, every variable."""
    done = run_native("--check", "30")
    assert done.returncode == 0, done.stdout + done.stderr
    for name in WORKLOADS:
        assert f"   {name:<8} C and generated Python: same state after 30 cycles (" in done.stdout


@no_cc
def test_native_check_reports_a_real_rounded_differently(tmp_path):
    """A C twin that multiplies in double and rounds once to float (not IEC's
    REAL * REAL) is caught: the first differing element, exit 1."""
    source = NATIVE_C.read_text()
    assert source.count("* 0.01f;") == 1
    wrong = tmp_path / "scan.c"
    wrong.write_text(source.replace("* 0.01f;", "* 0.01;"))
    done = run_native("--check", "5", "--source", str(wrong))
    assert done.returncode == 1, done.stdout + done.stderr
    assert "!!! numeric: C AND GENERATED PYTHON DIFFER after 5 cycles" in done.stdout
    assert "!!!   samples[element " in done.stdout
    assert "   bits     C and generated Python: same state after 5 cycles" in done.stdout


def test_native_is_skipped_without_a_compiler():
    done = run_native("--cc", "no-such-cc-softplc")
    assert done.returncode == 0, done.stderr
    assert (
        done.stdout == "bench_native: skipped: no C compiler 'no-such-cc-softplc' on PATH (the C reference needs one)\n"
    )


def _bench_split():
    import importlib.util

    spec = importlib.util.spec_from_file_location("bench_split", BENCHMARKS[0].parent / "bench_split.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_TICK = "_scan (runtime/engine/scan.py:310);Engine.tick (runtime/engine/scan.py:340)"


def test_split_puts_each_sample_in_its_kind():
    """benchmarks/bench_split.py sorts py-spy's raw stacks (frames as py-spy
    writes them) by the innermost frame of ours or of a library: the
    standard library and the image's accessors count for their caller."""
    stacks = [
        # a REAL rounded for a program: the runtime library, called from the generated code
        (
            _TICK + ";Engine._run_task (runtime/engine/scan.py:394);P_conveyor.__call__ (<softplc-1>:3139)"
            ";f32 (runtime/st/rtlib/rt_numeric.py:33)",
            7,
            "ST programs",
        ),
        # the DA1's ramp in exact fractions, under the Modbus line's service
        (
            _TICK + ";SimulatedDevice.advance_to (runtime/sim/base.py:73);SimulatedModbusLine.service "
            "(runtime/io/modbus/line.py:136);EatonDriveModel.advance (runtime/devices/eaton/model.py:280)"
            ";EatonDriveModel._integrate (runtime/devices/eaton/model.py:412);Fraction.__eq__ (fractions.py:682)",
            5,
            "device models",
        ),
        # pymodbus's CRC, under our Modbus link
        (
            _TICK + ";ModbusDriver.advance_to (runtime/io/modbus/master.py:268);ModbusLink.transact "
            "(runtime/io/modbus/link.py:190);FramerRTU.compute_CRC (pymodbus/framer/rtu.py:130)",
            3,
            "protocol libraries",
        ),
        # the LTMR's simulated slave (its sim.py is the bus side), in an installed package
        (
            _TICK + ";SimulatedDevice.advance_to (softplc/runtime/sim/base.py:73);LtmrSimulator.run_device "
            "(softplc/runtime/devices/ltmr/sim.py:187)",
            2,
            "our bus plumbing",
        ),
        # an image accessor called by the CANopen master: the master's
        (
            _TICK + ";CanopenDriver.write_outputs (runtime/io/canopen/master.py:581);PdoBinding.pack "
            "(runtime/io/canopen/pdo.py:188);ProcessImage.accessor.<locals>.get_int (runtime/image/memory.py:152)",
            4,
            "our bus plumbing",
        ),
        (
            _TICK + ";Engine._run_task (runtime/engine/scan.py:382);TaskStats.record (runtime/engine/stats.py:37)",
            6,
            "engine",
        ),
        (_TICK, 1, "engine"),
        # outside the ticks (the start-up): not counted
        ("<module> (bench_split.py:1);build_engine (runtime/engine/build.py:80)", 50, None),
    ]
    module = _bench_split()
    for stack, _count, kind in stacks:
        assert module.kind_of(stack.split(";")) == kind, stack
    raw = "\n".join(f"{stack} {count}" for stack, count, _kind in stacks) + "\n"
    assert module.split(raw) == {
        "ST programs": 7,
        "device models": 5,
        "protocol libraries": 3,
        "our bus plumbing": 6,
        "engine": 7,
    }
