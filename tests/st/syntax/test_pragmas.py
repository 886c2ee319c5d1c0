"""pragmas.py: what softplc makes of pragmas, as a user sees it: MatIEC's
embedded C {{ }} (W102) and the CODESYS/TwinCAT {attribute '...'} pragmas."""

from __future__ import annotations

import pytest

from softplc.runtime.st.profile import PROFILES

from ..conftest import diagnostics, run_st

# ---------------------------------------------------------------- MatIEC {{ }}

# A Beremiz/OpenPLC POU with C pasted into it (MatIEC copies the text
# between {{ and }} into the generated C; it may hold braces and span lines).
EMBEDDED_C = """PROGRAM main
VAR
    count : INT;
END_VAR
{{
    if (data__->COUNT.value > 3) { printf("%d\\n", 1); }
}}
count := count + 1;
{{ fflush(stdout); }}
END_PROGRAM
"""


@pytest.mark.parametrize("profile", sorted(PROFILES))
def test_embedded_c_is_ignored_with_a_warning_naming_it_in_every_profile(profile):
    found = [(d.code, d.pos.line, d.pos.col, d.message) for d in diagnostics(EMBEDDED_C, profile)]
    assert found == [
        (
            "W102",
            5,
            1,
            "embedded C code {{ if (data__->COUNT.value > 3) { printf... }} is ignored: softplc runs no C",
        ),
        ("W102", 9, 1, "embedded C code {{ fflush(stdout); }} is ignored: softplc runs no C"),
    ]
    # the ST around it runs as written
    assert run_st(EMBEDDED_C, cycles=3, profile=profile).get("count") == 3


def test_an_unclosed_embedded_c_block_is_e004_at_its_start():
    src = "PROGRAM main\nVAR x : INT; END_VAR\n{{ int y; }\nx := 1;\nEND_PROGRAM\n"
    [d] = [d for d in diagnostics(src) if d.code == "E004"]
    assert (d.pos.line, d.pos.col, d.message) == (3, 1, "unterminated pragma: '{{' is never closed")
    assert d.hint == "close it with '}}'"


# ---------------------------------------------------------------- {attribute '...'}

ATTRIBUTES = """{attribute 'call_after_init'}
FUNCTION_BLOCK Fb
VAR_OUTPUT
    {attribute 'monitoring' := 'call'} shown : INT;
    {attribute 'monitoring' := 'variable'} plain : INT;
END_VAR
{attribute 'pack_mode' := '1'}
VAR
    {attribute 'no_check'} n : INT;
END_VAR
n := n + 1;
shown := n;
END_FUNCTION_BLOCK
{attribute 'linkalways'}
PROGRAM main
VAR f : Fb; x : INT; END_VAR
{region 'cycle'}
f();
x := f.shown;
{endregion}
END_PROGRAM
"""


def test_attributes_softplc_does_not_honour_are_accepted_with_a_warning():
    # call_after_init (CODESYS: a method called after FB_init) and monitoring
    # := 'call' (a property read by calling it) change what runs or what is
    # shown; the others here change nothing softplc computes: no message.
    found = [(d.code, d.pos.line, d.pos.col, d.message) for d in diagnostics(ATTRIBUTES)]
    assert found == [
        ("W103", 1, 1, "{attribute 'call_after_init'} is ignored"),
        ("W103", 4, 5, "{attribute 'monitoring' := 'call'} is ignored"),
    ]
    assert run_st(ATTRIBUTES, cycles=3).get("x") == 3
