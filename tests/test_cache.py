"""softplc's cache on disk (runtime/cache.py): an entry is used again, a
changed text or another softplc version misses, a damaged entry is ignored
and written again, concurrent writers leave a whole entry, and --no-cache
(SOFTPLC_NO_CACHE) neither reads nor writes."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from click.testing import CliRunner

from softplc.runtime import cache
from softplc.runtime.cli import cli
from softplc.runtime.program import libraries
from softplc.runtime.st.profile import DEFAULT

pytestmark = pytest.mark.usefixtures("own_cache")  # tests/conftest.py

TEXT = "FUNCTION_BLOCK FB_Count\nVAR_INPUT x : INT; END_VAR\nVAR n : INT; END_VAR\nn := n + x;\nEND_FUNCTION_BLOCK\n"


def _entries(tmp_path: Path) -> list[str]:
    folder = tmp_path / "cache" / "st"
    return sorted(p.name for p in folder.iterdir()) if folder.exists() else []


def test_an_entry_is_used_by_the_next_run(tmp_path, monkeypatch, parses):
    [sf], _ = libraries.parse_cached("lib.st", TEXT, DEFAULT)
    assert parses == ["lib.st"] and len(_entries(tmp_path)) == 1
    monkeypatch.setattr(libraries, "_PARSES", {})  # a new process
    [again], _ = libraries.parse_cached("lib.st", TEXT, DEFAULT)
    assert parses == ["lib.st"]  # not parsed again: read from the cache
    assert [d.name for d in again.decls] == [d.name for d in sf.decls] == ["FB_Count"]


def test_a_changed_text_or_another_version_misses(tmp_path, monkeypatch, parses):
    libraries.parse_cached("lib.st", TEXT, DEFAULT)
    monkeypatch.setattr(libraries, "_PARSES", {})
    [sf], _ = libraries.parse_cached("lib.st", TEXT.replace("FB_Count", "FB_Sum"), DEFAULT)
    assert [d.name for d in sf.decls] == ["FB_Sum"] and len(parses) == 2
    monkeypatch.setattr(libraries, "_PARSES", {})
    monkeypatch.setattr(cache, "_version", "99.0.0")  # an upgrade
    libraries.parse_cached("lib.st", TEXT, DEFAULT)
    assert len(parses) == 3 and len(_entries(tmp_path)) == 3


def test_a_module_moved_to_another_package_changes_the_code_hash(tmp_path, monkeypatch):
    """The pickles name classes by module: a module of the same name and text
    in another package (runtime/st/ split into stages) must not meet the old
    entries, so the code's hash knows where each file is inside softplc."""
    root = tmp_path / "softplc"
    monkeypatch.setattr(cache, "_ROOT", root)
    before, after = root / "st" / "parser.py", root / "st" / "syntax" / "parser.py"
    for f in (before, after):
        f.parent.mkdir(parents=True, exist_ok=True)
        f.write_text("class Parser: pass\n")
    assert cache.code_hash(before) != cache.code_hash(after)
    outside = [tmp_path / f"plugin{n}" / "tables.py" for n in (1, 2)]  # not softplc's: name and text
    for f in outside:
        f.parent.mkdir(exist_ok=True)
        f.write_text("x = 1\n")
    assert cache.code_hash(outside[0]) == cache.code_hash(outside[1])


def test_a_damaged_entry_is_ignored_and_written_again(tmp_path, monkeypatch, parses):
    libraries.parse_cached("lib.st", TEXT, DEFAULT)
    [name] = _entries(tmp_path)
    entry = tmp_path / "cache" / "st" / name
    whole = entry.read_bytes()
    for damaged in (whole[: len(whole) // 2], b"", b"not a pickle"):
        entry.write_bytes(damaged)
        monkeypatch.setattr(libraries, "_PARSES", {})
        [sf], _ = libraries.parse_cached("lib.st", TEXT, DEFAULT)
        assert [d.name for d in sf.decls] == ["FB_Count"]
        assert entry.read_bytes() == whole  # written again, whole
    assert len(parses) == 4


def test_load_ignores_what_does_not_read(tmp_path):
    key = cache.key("t", "x")
    cache.store("t", key, {"a": 1})
    assert cache.load("t", key) == {"a": 1}
    cache.path("t", key).write_bytes(b"\x80\x05garbage")
    assert cache.load("t", key) is None
    assert cache.key("t", "x") != cache.key("t", "y") and cache.key("t", "ab", "c") != cache.key("t", "a", "bc")


WRITER = """
import sys
from softplc.runtime import cache
value = [bytes([int(sys.argv[1])]) * 50_000 for _ in range(40)]
key = cache.key("race", "one entry")
for _ in range(60):
    cache.store("race", key, value)
"""


def test_two_processes_writing_one_entry_leave_a_readable_one(tmp_path):
    writers = [subprocess.Popen([sys.executable, "-c", textwrap.dedent(WRITER), str(n)]) for n in (1, 2)]
    key = cache.key("race", "one entry")
    seen = 0
    while any(w.poll() is None for w in writers):
        value = cache.load("race", key)  # read while they write: the old entry or a new one, whole
        if value is not None:
            assert len(value) == 40 and value[0] in (b"\x01" * 50_000, b"\x02" * 50_000)
            seen += 1
    assert [w.wait() for w in writers] == [0, 0]
    value = cache.load("race", key)
    assert value is not None and len(set(value)) == 1
    assert [p.name for p in (tmp_path / "cache" / "race").iterdir()] == [f"{key}.pickle"]  # no temporary file left


def _check(args: list, tmp_path: Path):
    libraries._PARSES.clear()  # (as a new process)
    (tmp_path / "main.st").write_text("PROGRAM Main\nVAR t : TON; END_VAR\nt(IN := TRUE, PT := T#1s);\nEND_PROGRAM\n")
    return CliRunner().invoke(cli, [*args, "check", str(tmp_path / "main.st")])


def _written(tmp_path: Path) -> dict:
    folder = tmp_path / "cache"
    return {p: p.stat().st_mtime_ns for p in folder.rglob("*")} if folder.exists() else {}


def test_no_cache_neither_reads_nor_writes(tmp_path, monkeypatch):
    assert _check(["--no-cache"], tmp_path).exit_code == 0
    assert _written(tmp_path) == {}  # nothing written
    assert _check([], tmp_path).exit_code == 0 and _written(tmp_path)  # (written without it)
    before, loads = _written(tmp_path), +cache.stats
    assert _check(["--no-cache"], tmp_path).exit_code == 0
    assert _written(tmp_path) == before
    assert +cache.stats == loads  # nothing read (no hit, no miss)
    assert cache.enabled()  # on again after the command
    monkeypatch.setenv("SOFTPLC_NO_CACHE", "1")  # the pytest plugin's way
    assert _check([], tmp_path).exit_code == 0
    assert _written(tmp_path) == before and +cache.stats == loads
