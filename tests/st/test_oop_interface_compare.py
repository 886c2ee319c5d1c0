"""Comparing interface variables (checker_operators.py, codegen_exprs.py).

CODESYS "Interface": a variable of an interface type designates an
instance or is 0 (unassigned); `itf = 0` / `itf <> 0` test it, `itf1 =
itf2` is TRUE when both designate the same instance (or both are 0), and
`itf = inst` when itf designates that instance (an instance of a block
implementing the interface, derived ones included, or one reached through
a REFERENCE TO). Other comparisons stay E020; __ISVALIDREF is for
REFERENCE TO (E160), its hint says how to test an interface."""

from __future__ import annotations

from .conftest import diagnostics, run_st

DECLS = """
INTERFACE I_A
METHOD Go : INT END_METHOD
END_INTERFACE
INTERFACE I_B
METHOD Go : INT END_METHOD
END_INTERFACE
FUNCTION_BLOCK FB_A IMPLEMENTS I_A, I_B
METHOD Go : INT
Go := 1;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_D EXTENDS FB_A
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_None
END_FUNCTION_BLOCK
"""


def test_interfaces_compare_by_the_instance_they_designate():
    src = (
        DECLS
        + """
PROGRAM main
VAR a1, a2 : FB_A; d : FB_D; i, j, u1, u2 : I_A; k : I_B; ra : REFERENCE TO FB_A;
    unset, isA1, a1IsI, isA2, notA2, sameIJ, sameIK, bothUnset, setJ, isD, isRef, notRef : BOOL; END_VAR
unset := i = 0;
i := a1; j := a1; k := a1;
isA1 := i = a1;
a1IsI := a1 = i;
isA2 := i = a2;
notA2 := i <> a2;
sameIJ := i = j;
sameIK := i = k;                 (* two interfaces, one instance *)
bothUnset := u1 = u2;            (* both 0 *)
setJ := j <> 0;
ra REF= a1;
isRef := i = ra;                 (* the instance a REFERENCE TO designates *)
i := d;
isD := i = d;                    (* an instance of a derived block *)
notRef := i = ra;
END_PROGRAM
"""
    )
    r = run_st(src)
    names = "unset isA1 a1IsI isA2 notA2 sameIJ sameIK bothUnset setJ isRef isD notRef".split()
    assert {n: r.get(n) for n in names} == {
        "unset": True,
        "isA1": True,
        "a1IsI": True,
        "isA2": False,
        "notA2": True,
        "sameIJ": True,
        "sameIK": True,
        "bothUnset": True,
        "setJ": True,
        "isRef": True,
        "isD": True,
        "notRef": False,
    }


def test_what_an_interface_does_not_compare_with():
    src = (
        DECLS
        + """
PROGRAM main
VAR i : I_A; n : FB_None; a1 : FB_A; b : BOOL; x : INT; END_VAR
b := i = n;                      (* FB_None does not implement I_A *)
b := i < a1;                     (* only = and <> *)
b := i = x;
b := __ISVALIDREF(i);
END_PROGRAM
"""
    )
    got = [(d.code, d.pos.line, d.hint) for d in diagnostics(src)]
    assert [g[:2] for g in got] == [("E020", 20), ("E020", 21), ("E020", 22), ("E160", 23)]
    assert got[3][2] == "an interface is 0 until assigned: test it with itf <> 0"
