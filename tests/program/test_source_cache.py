"""A project's own sources in softplc's cache (libraries.parse_cached with
slot=True, what `softplc check` and the project analysis use): a re-check
of an unchanged file reads its parse instead of parsing it, an edited file
(another profile, another parser) never meets its old parse, a file keeps
one entry however often it is edited, a damaged entry is parsed again, and
--no-cache (SOFTPLC_NO_CACHE) neither reads nor writes."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from softplc.runtime import cache
from softplc.runtime.cli import cli
from softplc.runtime.program import libraries
from softplc.runtime.st.profile import DEFAULT, get_profile

pytestmark = pytest.mark.usefixtures("own_cache")  # tests/conftest.py

GOOD = "PROGRAM main\nVAR x : INT; END_VAR\nx := x + 1;\nEND_PROGRAM\n"
BAD = "PROGRAM main\nVAR x : INT; END_VAR\nx := y + 1;\nEND_PROGRAM\n"


def _entries(tmp_path: Path) -> list[Path]:
    folder = tmp_path / "cache" / libraries.SLOT
    return sorted(folder.iterdir()) if folder.exists() else []


def _new_process(monkeypatch) -> None:
    monkeypatch.setattr(libraries, "_PARSES", {})


def _names(text: str, profile=DEFAULT) -> list:
    [sf], _ = libraries.parse_cached("main.st", text, profile, slot=True)
    return [d.name for d in sf.decls]


def test_an_unchanged_source_is_read_from_its_entry(tmp_path, monkeypatch, parses):
    assert _names(GOOD) == ["main"] and parses == ["main.st"]
    _new_process(monkeypatch)
    assert _names(GOOD) == ["main"] and parses == ["main.st"]  # not parsed again


def test_an_edited_source_is_parsed_again_and_keeps_one_entry(tmp_path, monkeypatch, parses):
    _names(GOOD)
    _new_process(monkeypatch)
    edited = GOOD.replace("main", "edited")
    assert _names(edited) == ["edited"]  # never the old parse
    assert len(parses) == 2 and len(_entries(tmp_path)) == 1
    _new_process(monkeypatch)
    assert _names(GOOD) == ["main"] and len(parses) == 3  # the entry holds the edited text's parse


def test_another_profile_or_parser_misses(tmp_path, monkeypatch, parses):
    _names(GOOD)
    _new_process(monkeypatch)
    _names(GOOD, get_profile("iec"))
    assert len(parses) == 2
    _new_process(monkeypatch)
    monkeypatch.setattr(libraries, "_SALT", b"another parser")
    _names(GOOD)
    assert len(parses) == 3


def test_a_damaged_entry_is_parsed_again(tmp_path, monkeypatch, parses):
    _names(GOOD)
    [entry] = _entries(tmp_path)
    data = entry.read_bytes()
    entry.write_bytes(data[:64] + data[64 : len(data) // 2])  # the key, half a pickle
    _new_process(monkeypatch)
    assert _names(GOOD) == ["main"] and len(parses) == 2
    _new_process(monkeypatch)
    assert _names(GOOD) == ["main"] and len(parses) == 2  # (written again whole)


def _check(tmp_path: Path, text: str, *args: str):
    source = tmp_path / "main.st"
    source.write_text(text, encoding="utf-8")
    return CliRunner().invoke(cli, [*args, "check", str(source)])


def test_check_reads_the_parse_of_an_unchanged_file_and_reports_an_edit(tmp_path, monkeypatch, parses):
    assert _check(tmp_path, GOOD).exit_code == 0
    _new_process(monkeypatch)
    assert _check(tmp_path, GOOD).exit_code == 0
    assert parses.count(str(tmp_path / "main.st")) == 1
    _new_process(monkeypatch)
    result = _check(tmp_path, BAD)
    assert result.exit_code == 1 and "E" in result.output and "'y'" in result.output
    assert parses.count(str(tmp_path / "main.st")) == 2


@pytest.mark.parametrize("how", ["--no-cache", "SOFTPLC_NO_CACHE"])
def test_no_cache_neither_reads_nor_writes_a_source_s_entry(tmp_path, monkeypatch, parses, how):
    assert _check(tmp_path, GOOD).exit_code == 0  # an entry written
    [entry] = _entries(tmp_path)
    before = entry.read_bytes()
    _new_process(monkeypatch)
    if how == "SOFTPLC_NO_CACHE":
        monkeypatch.setenv("SOFTPLC_NO_CACHE", "1")
    args = ("--no-cache",) if how == "--no-cache" else ()
    assert _check(tmp_path, BAD, *args).exit_code == 1
    assert parses.count(str(tmp_path / "main.st")) == 2  # parsed, not read
    assert _entries(tmp_path) == [entry] and entry.read_bytes() == before  # nothing written
    _new_process(monkeypatch)
    assert _check(tmp_path, GOOD, *args).exit_code == 0
    assert parses.count(str(tmp_path / "main.st")) == 3  # the entry not read either
    assert cache.enabled() is (how == "--no-cache")
