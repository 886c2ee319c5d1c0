"""dialects.py: the markers that make a source read like another dialect
(softplc check's hint; the command itself is tested in tests/test_cli.py)."""

from __future__ import annotations

from pathlib import Path

from softplc.runtime.st.dialects import candidates, hint, markers

REPO = Path(__file__).resolve().parents[2]


def test_the_schneider_samples_read_like_schneider():
    text = (REPO / "st_programs" / "ltmr_read_sdo.st").read_text(encoding="utf-8")
    assert markers(text) == {"schneider": ["0x literals", "%MW..:X bits and %MW..:n tables", "ADR#"]}


def test_twincat_outranks_codesys_when_a_twincat_only_marker_is_there():
    text = (
        "{attribute 'qualified_only'}\nVAR_GLOBAL x : INT; END_VAR\n"
        "PROGRAM p\nTc2_Standard.CONCAT(a,\n);\nEND_PROGRAM\n"
    )
    assert candidates([text], "codesys") == [
        ("twincat", ["Tc2_/Tc3_ libraries", "a comma ending an argument list", "{attribute} pragmas"])
    ]
    assert [p for p, _ in candidates([text], "iec")] == ["twincat", "codesys"]


def test_comments_and_strings_are_no_markers():
    text = "PROGRAM p\n(* 0x1F, ADR#0.1 and f(a,) *)\ns := '{{ 0x12 }}, ADR#';\nEND_PROGRAM\n"
    assert markers(text) == {}


def test_matiec_embedded_c_and_the_hint_line():
    assert markers("{{ int x; }}\nPROGRAM p END_PROGRAM") == {"matiec": ["{{ }} embedded C"]}
    assert hint("matiec", ["{{ }} embedded C"]) == "reads like matiec ({{ }} embedded C); try --profile matiec"
