"""What a hostile or careless ST file broke (issue 31, "The language"),
each through the command line as the user met it: a coded diagnostic and
exit 1, or the value kept, never a traceback and exit 4."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest


def softplc(*args):
    env = dict(os.environ, PYTHONIOENCODING="utf-8")
    env.pop("SOFTPLC_DEBUG", None)
    return subprocess.run(
        [sys.executable, "-m", "softplc.runtime.cli", *map(str, args)],
        capture_output=True,
        text=True,
        stdin=subprocess.DEVNULL,
        env=env,
        timeout=300,
    )


def no_traceback(proc):
    assert "Traceback" not in proc.stderr and "internal error" not in proc.stderr


# ---------------------------------------------------------------- WSTRING surrogates


@pytest.mark.parametrize(
    ("literal", "column"), [('"$D800"', 6), ('"ab$DC00"', 6), ('"$DE00$D83D"', 6), ('"x$D83Dy"', 6)]
)
def test_a_lone_surrogate_in_a_wstring_literal_is_an_error(tmp_path, literal, column):
    path = tmp_path / "w.st"
    path.write_text(f"PROGRAM Main\nVAR\n  w : WSTRING;\nEND_VAR\nw := {literal};\nEND_PROGRAM\n")
    proc = softplc("exec", path)
    no_traceback(proc)
    assert proc.returncode == 1
    assert f"w.st:5:{column}: error E003:" in proc.stderr and "lone UTF-16 surrogate" in proc.stderr


def test_a_surrogate_pair_in_a_wstring_literal_is_its_character(tmp_path):
    path = tmp_path / "w.st"
    path.write_text('PROGRAM Main\nVAR\n  w : WSTRING := "a$D83D$DE00b";\nEND_VAR\nEND_PROGRAM\n')
    proc = softplc("exec", path)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["w"] == "a\U0001f600b"


def test_a_surrogate_made_at_run_time_is_printed_as_its_json_escape(tmp_path):
    """CODESYS keeps WORD_TO_WCHAR(16#D800) as one WORD: exec keeps it too
    and prints it as \\ud800, valid JSON, not a UnicodeEncodeError."""
    path = tmp_path / "w.st"
    path.write_text(
        "PROGRAM Main\nVAR\n  w : WSTRING;\n  c : WCHAR;\nEND_VAR\n"
        "c := WORD_TO_WCHAR(16#D800);\nw := WCHAR_TO_WSTRING(c);\nEND_PROGRAM\n"
    )
    proc = softplc("exec", path)
    no_traceback(proc)
    assert proc.returncode == 0
    assert '"w": "\\ud800"' in proc.stdout
    assert json.loads(proc.stdout)["w"] == "\ud800"
