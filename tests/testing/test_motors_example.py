"""The object-oriented example (st_programs/motors_oop.st, an interface,
an abstract block, two derived ones and properties) passes its ST tests
against io_config/examples/motors_oop.toml, as `softplc test` runs them."""

from __future__ import annotations

from pathlib import Path

from .test_command import softplc

REPO = Path(__file__).resolve().parents[2]


def test_the_motor_line_passes_its_st_tests(tmp_path):
    proc = softplc(
        REPO / "io_config" / "examples" / "motors_oop.toml",
        REPO / "st_programs" / "tests" / "test_motors_oop.st",
        cwd=tmp_path,
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "PASS  TEST_StaggeredStartAndRamps" in proc.stdout
    assert "PASS  TEST_StopThroughTheInterface" in proc.stdout
    assert "2 passed, 0 failed" in proc.stdout
