"""Value semantics of aggregates (runtime/st/values.py): ST assigns and
passes function block instances by value (IEC 61131-3 ed.3 6.5.2.2; CODESYS
accepts fb1 := fb2 of one type), their inner instances, arrays and strings
included; a derived block's copy has the inherited variables too."""

from __future__ import annotations

from .conftest import run_st

BLOCKS = """
FUNCTION_BLOCK Inner
VAR_INPUT k : INT; END_VAR
VAR_OUTPUT n : INT; last : ARRAY[1..2] OF INT; END_VAR
n := n + k; last[2] := last[1]; last[1] := k;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Outer
VAR_INPUT step : INT; END_VAR
VAR_OUTPUT total : DINT; name : STRING := 'a'; hist : ARRAY[1..2] OF INT; END_VAR
VAR inner : Inner; END_VAR
total := total + step; name := CONCAT(name, 'b'); inner(k := step); hist := inner.last;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Derived EXTENDS Outer
VAR_OUTPUT extra : INT; END_VAR
extra := extra + 1; SUPER^();
END_FUNCTION_BLOCK
FUNCTION Peek : DINT
VAR_INPUT f : Outer; END_VAR
f(step := 100);
Peek := f.total;
END_FUNCTION
"""


def test_an_fb_instance_is_assigned_and_passed_by_value():
    r = run_st(
        BLOCKS
        + """
PROGRAM main
VAR a, b : Outer; seen, after : DINT; last_a, last_b : INT; name_b : STRING; END_VAR
a(step := 5);
b := a;             (* a copy: calling b leaves a alone *)
b(step := 1);
seen := Peek(a);    (* the function works on its own copy *)
after := a.total;
last_a := a.hist[2]; last_b := b.hist[2];
name_b := b.name;
END_PROGRAM
""",
        cycles=1,
    )
    assert (r.get("a.total"), r.get("b.total"), r.get("seen"), r.get("after")) == (5, 6, 105, 5)
    assert (r.get("a.inner.n"), r.get("b.inner.n")) == (5, 6)  # the inner instance is copied
    assert (r.get("last_a"), r.get("last_b")) == (0, 5)  # and the arrays, deep
    assert (r.get("a.name"), r.get("name_b")) == ("ab", "abb")


def test_a_derived_instance_copies_its_inherited_variables():
    r = run_st(
        BLOCKS
        + """
PROGRAM main
VAR d1, d2 : Derived; END_VAR
d1(step := 2);
d2 := d1;
d2(step := 3);
END_PROGRAM
""",
        cycles=2,
    )
    # cycle 2: d2 := d1 again overwrites what d2 did in cycle 1
    assert (r.get("d1.total"), r.get("d1.extra")) == (4, 2)
    assert (r.get("d2.total"), r.get("d2.extra")) == (7, 3)
