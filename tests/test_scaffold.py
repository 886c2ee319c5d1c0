"""softplc new (runtime/scaffold.py): a project that runs at once on the
simulated plant, tests green and checks clean."""

from __future__ import annotations

from tests.test_cli import softplc


def test_a_new_project_runs_tests_and_checks_clean(tmp_path):
    r = softplc("new", "pumps", "--dir", tmp_path)
    assert r.returncode == 0, r.stderr
    root = tmp_path / "pumps"
    assert sorted(p.name for p in root.iterdir()) == ["README.md", "plant", "plc.toml", "src", "tests"]
    r = softplc("test", "plc.toml", "tests/test_main.st", cwd=root)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "PASS  TEST_MotorStartsAreCounted" in r.stdout + r.stderr
    r = softplc("run", "plc.toml", "--virtual-time", "--duration", "6s", "--watch", "motorStarts", cwd=root)
    assert r.returncode == 0, r.stderr
    assert "motorStarts=2" in r.stdout + r.stderr  # forward, then reverse within 6 s
    r = softplc("check", ".", cwd=root)
    assert r.returncode == 0, r.stderr
    assert "src/main.st" in r.stderr and "7 files" in r.stderr and "0 errors, 0 warnings" in r.stderr


def test_new_refuses_an_existing_folder_and_a_bad_name(tmp_path):
    (tmp_path / "taken").mkdir()
    r = softplc("new", "taken", "--dir", tmp_path)
    assert r.returncode == 2 and "exists already" in r.stderr
    r = softplc("new", "../escape", "--dir", tmp_path)
    assert r.returncode == 2 and "is not a project name" in r.stderr
