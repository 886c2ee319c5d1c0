"""`softplc sweep`: the genset example's sweep file from the command line,
its table as CSV and as Parquet (read back with pyarrow), its plot, and
the exit codes: 0 all passed, 3 one failed, 2 a bad file or option, 1 a
program that does not compile."""

from __future__ import annotations

import csv

import pytest

from softplc.runtime.config import default_config_path

from .test_cli import softplc

GENSET = default_config_path().parent / "examples" / "genset.toml"
SLIP_SWEEP = default_config_path().parent / "sweeps" / "genset_slip.toml"


def test_the_genset_sweep_writes_a_row_per_scenario_and_the_plot(tmp_path):
    done = softplc("sweep", GENSET, "--matrix", SLIP_SWEEP, "-o", tmp_path / "slip.csv", "--plot", tmp_path / "s.svg")
    assert done.returncode == 0, done.stderr
    assert "12 passed, 0 failed" in done.stderr
    rows = list(csv.DictReader((tmp_path / "slip.csv").open(encoding="utf-8")))
    assert [r["scenario"] for r in rows] == [str(i) for i in range(12)]
    assert list(rows[0])[:4] == ["scenario", "sim.mpu2s1.slip", "sim.mpu2s1.closing_time", "passed"]
    assert {(r["sim.mpu2s1.slip"], r["sim.mpu2s1.closing_time"]) for r in rows} == {
        (s, t) for s in ("0.1", "0.2", "0.3", "-0.15") for t in ("40ms", "80ms", "150ms")
    }
    assert all(r["passed"] == "True" and abs(float(r["records.mpu2s1.closes[0].phase_deg"])) < 10 for r in rows)
    svg = (tmp_path / "s.svg").read_text(encoding="utf-8")
    assert "genset_slip.toml: 12 scenarios, 0 failed" in svg


def test_a_parquet_table_holds_the_same_rows(tmp_path):
    pq = pytest.importorskip("pyarrow.parquet", reason="the test extra installs pyarrow")
    assert softplc("sweep", GENSET, "--matrix", SLIP_SWEEP, "-o", tmp_path / "a.csv", "-j", "1").returncode == 0
    assert softplc("sweep", GENSET, "--matrix", SLIP_SWEEP, "-o", tmp_path / "a.parquet", "-j", "2").returncode == 0
    table = pq.read_table(tmp_path / "a.parquet").to_pylist()
    rows = list(csv.DictReader((tmp_path / "a.csv").open(encoding="utf-8")))
    assert len(table) == len(rows) == 12
    for parquet_row, csv_row in zip(table, rows):
        assert {k: "" if v is None else str(v) for k, v in parquet_row.items()} == csv_row


def write(tmp_path, text: str):
    path = tmp_path / "sweep.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_a_scenario_whose_expectation_fails_exits_3_and_says_why(tmp_path):
    sweep = write(
        tmp_path,
        'duration = "20s"\n[matrix]\n"sim.mpu2s1.slip" = [0.1, 0.3]\n'
        '[result]\nexpect = ["records.mpu2s1.closes[0].t_s < 11"]\n',
    )
    done = softplc("sweep", GENSET, "--matrix", sweep, "-j", "1")
    assert done.returncode == 3, done.stderr
    assert "1 passed, 1 failed" in done.stderr
    assert "scenario 1: records.mpu2s1.closes[0].t_s < 11: false" in done.stderr
    rows = list(csv.DictReader((tmp_path / "sweep.csv").open(encoding="utf-8")))  # beside the sweep file
    assert [r["passed"] for r in rows] == ["True", "False"]


@pytest.mark.parametrize(
    ("text", "args", "message"),
    [
        ('[matrix]\n"sim.gen.slip" = [0.1]\n', (), "sim.gen.slip: no simulated device 'gen'"),
        ('[matrix]\n"sim.mpu2s1.slip" = ["x"]\n', (), "scenario 0 (slip=x)"),
        ('[matrix]\n"sim.mpu2s1.slip" = [0.1]\n', ("-o", "out.xlsx"), "the ending says the table's form"),
        ('[matrix]\n"sim.mpu2s1.slip" = [0.1]\n', ("--plot", "p.svg"), "has no [result] plot"),
        ('[matrix]\n"sim.mpu2s1.slip" = [0.1]\n', ("-j", "2", "--scheduler", "tcp://127.0.0.1:1"), "--workers and"),
        ("[matrix\n", (), "not TOML"),
    ],
)
def test_a_bad_sweep_or_option_exits_2_with_the_key(tmp_path, text, args, message):
    done = softplc("sweep", GENSET, "--matrix", write(tmp_path, text), *args, cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    assert message in done.stderr
    assert "Traceback" not in done.stderr


def test_a_program_that_does_not_compile_exits_1_once(tmp_path):
    st = tmp_path / "bad.st"
    st.write_text("PROGRAM Main\nx := ;\nEND_PROGRAM\n", encoding="utf-8")
    config = tmp_path / "plc.toml"
    tasks = '[[task]]\nname = "Main"\ninterval = "10ms"\nprograms = ["Main"]\n'
    config.write_text(f'[plc]\nprograms = ["{st.name}"]\n{tasks}', encoding="utf-8")
    sweep = write(tmp_path, '[matrix]\n"init.Main.x" = [1, 2]\n')
    done = softplc("sweep", config, "--matrix", sweep)
    assert done.returncode == 1, done.stderr
    assert "bad.st:2:" in done.stderr


def test_a_configuration_that_is_not_toml_exits_2_naming_it(tmp_path):
    config = tmp_path / "plant.toml"
    config.write_text("[plc\n", encoding="utf-8")
    done = softplc("sweep", config, "--matrix", write(tmp_path, '[matrix]\n"init.Main.x" = [1]\n'))
    assert done.returncode == 2, done.stderr
    assert "plant.toml" in done.stderr and "Traceback" not in done.stderr


def test_the_program_s_own_assertions_from_the_command_line(tmp_path):
    # the first scenario is built before the workers start: with the assertions softplc test has
    (tmp_path / "p.st").write_text(
        "PROGRAM Main\nVAR limit : INT := 10; level : INT; END_VAR\nlevel := level + 1;\n"
        "ASSERT_TRUE(level < limit, 'below the limit');\nEND_PROGRAM\n",
        encoding="utf-8",
    )
    config = tmp_path / "plant.toml"
    config.write_text('[plc]\nprograms = ["p.st"]\n[[task]]\nname = "Main"\ninterval = "10ms"\nprograms = ["Main"]\n')
    sweep = write(tmp_path, 'duration = "1s"\n[matrix]\n"init.Main.limit" = [1000, 50]\n')
    done = softplc("sweep", config, "--matrix", sweep, "-j", "1")
    assert done.returncode == 3, done.stderr
    assert "1 passed, 1 failed" in done.stderr
    assert "ASSERT_TRUE failed: below the limit" in done.stderr
