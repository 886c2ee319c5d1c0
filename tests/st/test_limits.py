"""The compiler's limits (runtime/st/limits.py): each one passed is its
own coded error at the place where it is passed, from the command line
too, and the README's "Limits" list states the values the code has."""

from __future__ import annotations

import re

import pytest

from softplc.runtime.st import limits

from ..test_cli import REPO, softplc


def _prog(decls: str = "x : INT;", body: str = "") -> str:
    return f"PROGRAM main\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"


_COMMENT_LINE = "(* " + "c" * 93 + " *)\n"  # 100 characters

# name: (source, the start of the error line: line, column, code)
BEYOND = {
    "file too large": (
        _COMMENT_LINE * (limits.MAX_SOURCE_CHARS // 100 + 1) + _prog(),
        f"{limits.MAX_SOURCE_CHARS // 100 + 1}:{limits.MAX_SOURCE_CHARS % 100 + 1}: error E007",
    ),
    "comments nested too deeply": (
        _prog() + "(*" * (limits.MAX_COMMENT_DEPTH + 1) + "*)" * (limits.MAX_COMMENT_DEPTH + 1),
        f"7:{2 * limits.MAX_COMMENT_DEPTH + 1}: error E008",
    ),
    # the parser stops after 100 (E001 'too many errors'); the command line shows 50 a file
    "101 stray comment ends": (_prog() + "*)" * 101, " ... 51 more errors"),
    "parentheses nested too deeply": (_prog(body="x := " + "(" * 400 + "1" + ")" * 400 + ";"), "5:"),
    "too many operators": (_prog(body="x := " + " + ".join(["1"] * 1001) + ";"), "5:6: error E006"),
    "array type too large": (_prog("a : ARRAY[0..9999, 0..9999, 0..99] OF INT;"), "3:5: error E054"),
    "variables too large together": (
        _prog("a : ARRAY[1..10000000] OF BYTE;\nb : ARRAY[1..10000000] OF BYTE;"),
        "4:1: error E055",
    ),
    "huge repetition count": (_prog("a : ARRAY[0..9] OF INT := [1000000000(0)];"), "3:27: error E052"),
}


@pytest.mark.parametrize("name", list(BEYOND))
def test_beyond_a_limit_the_command_line_reports_a_coded_error_not_a_crash(name, tmp_path):
    source, where = BEYOND[name]
    path = tmp_path / "limit.st"
    path.write_text(source, encoding="utf-8")
    for command in ("check", "compile"):
        proc = softplc(command, path)
        assert proc.returncode == 1, proc.stderr[-2000:]
        assert "Traceback" not in proc.stderr and "E009" not in proc.stderr
        assert f"{path}:{where}" in proc.stderr, proc.stderr[:2000]
        if name == "parentheses nested too deeply":
            assert "error E006: nested too deeply" in proc.stderr
        # a long source line is shown cut around the column
        assert all(len(line) < 200 for line in proc.stderr.splitlines())


def test_the_manual_lists_each_limit_with_the_value_in_limits_py():
    page = (REPO / "docs" / "reference" / "language.md").read_text(encoding="utf-8")
    section = page.split("\n## Limits\n", 1)[1].split("\n## ", 1)[0]
    numbers = {int(n.replace(",", "")) for n in re.findall(r"\d[\d,]*", section)}
    for name in (
        "MAX_SOURCE_CHARS",
        "MAX_COMMENT_DEPTH",
        "MAX_NESTING",
        "MAX_OPERATORS",
        "MAX_VAR_ELEMENTS",
        "MAX_TOTAL_ELEMENTS",
        "MAX_STRING_LENGTH",
        "MAX_ERRORS",
    ):
        assert getattr(limits, name) in numbers, name
    for code in ("E006", "E007", "E008", "E054", "E055"):
        assert f"**{code}**" in section
