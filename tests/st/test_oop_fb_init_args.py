"""FB_init inputs set where an instance is declared (runtime/st/
checker_fbinit.py, codegen_oop.py).

CODESYS "Method FB_init" / TwinCAT "FB_init": FB_init may declare inputs
after bInitRetains and bInCopyCode; each instance's declaration sets them,
`fb : FB_X(nStart := 5);`, and for an array one list per element,
`fbs : ARRAY[1..3] OF FB_X[(nStart := 1), (nStart := 2), (nStart := 3)];`
("Any additional variables specified there must be set when declaring a
function block instance", TwinCAT; one without an initial value is E170
when not set). FB_init runs before the initial values of the declaration
(`:= (in1 := 99)`), as CODESYS's call_after_init help spells out: FB_Init,
then the declared values."""

from __future__ import annotations

from .conftest import diagnostics, run_st

FB_X = """
FUNCTION_BLOCK FB_X
VAR_INPUT step : INT; END_VAR
VAR_OUTPUT n : INT; inits : INT; END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; nStart : INT; nStep : INT := 1; END_VAR
n := nStart;
step := nStep;
inits := inits + 1;
END_METHOD
n := n + step;
END_FUNCTION_BLOCK
"""


def test_declared_inputs_reach_fb_init_once():
    src = (
        FB_X
        + """
PROGRAM main
VAR base : INT := 40;
    f : FB_X(nStart := 5);
    g : FB_X(nStart := base + 2, nStep := 10);
    h : FB_X(nStep := 3, nStart := -1) := (step := 7);   (* FB_init first, then step := 7 *)
END_VAR
f(); g(); h();
END_PROGRAM
"""
    )
    r = run_st(src, cycles=2)
    assert (r.get("f.n"), r.get("f.step"), r.get("f.inits")) == (5 + 2 * 1, 1, 1)
    assert (r.get("g.n"), r.get("g.step")) == (42 + 2 * 10, 10)
    assert (r.get("h.n"), r.get("h.step")) == (-1 + 2 * 7, 7)


def test_an_array_sets_each_elements_inputs():
    src = (
        FB_X
        + """
PROGRAM main
VAR fbs : ARRAY[1..3] OF FB_X[(nStart := 1), (nStart := 2), (nStart := 3, nStep := 0)];
    i : INT; sum : INT; END_VAR
sum := 0;
FOR i := 1 TO 3 DO fbs[i](); sum := sum * 100 + fbs[i].n; END_FOR
END_PROGRAM
"""
    )
    assert run_st(src).get("sum") == 2 * 10000 + 3 * 100 + 3  # 1 + 1, 2 + 1, 3 + 0


def test_derived_blocks_pass_each_fb_init_its_own_inputs_and_a_variable_positionally():
    # TwinCAT's test framework declares fbTestCase : FB_TestCase1(fbPreparation);
    # the base's FB_init runs first, with the inputs it declares
    src = """
INTERFACE I_Source
METHOD Get : INT END_METHOD
END_INTERFACE
FUNCTION_BLOCK FB_Src IMPLEMENTS I_Source
METHOD Get : INT
Get := 11;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Base
VAR src : I_Source; got : INT; END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; source : I_Source; END_VAR
src := source;
END_METHOD
got := src.Get();
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Derived EXTENDS FB_Base
VAR scale : INT; END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; source : I_Source; k : INT := 3; END_VAR
scale := k;
END_METHOD
SUPER^();
got := got * scale;
END_FUNCTION_BLOCK
PROGRAM main
VAR s : FB_Src; b : FB_Base(s); d : FB_Derived(source := s, k := 2); e : FB_Derived(s); END_VAR
b(); d(); e();
END_PROGRAM
"""
    r = run_st(src)
    assert (r.get("b.got"), r.get("d.got"), r.get("e.got")) == (11, 22, 33)


def test_missing_unknown_and_misplaced_inputs_are_e170():
    src = (
        FB_X
        + """
FUNCTION_BLOCK FB_Plain
END_FUNCTION_BLOCK
FUNCTION Use : INT
VAR_IN_OUT r : FB_X(nStart := 1); END_VAR
END_FUNCTION
PROGRAM main
VAR a : FB_X;                              (* nStart has no initial value: it must be set *)
    b : FB_X(nStep := 2);
    c : FB_X(nStrat := 2);
    d : FB_Plain(x := 1);
    e : ARRAY[1..3] OF FB_X[(nStart := 1)];  (* the other two are not set *)
    f : FB_X(nStart := 'text');
END_VAR
END_PROGRAM
"""
    )
    got = [(d.code, d.pos.line) for d in diagnostics(src)]
    assert got == [
        ("E170", 17),  # VAR_IN_OUT r : FB_X(...)
        ("E170", 20),  # a
        ("E170", 21),  # b: nStart not set
        ("E170", 22),  # c: nStart not set, and no input nStrat
        ("E170", 22),
        ("E170", 23),  # FB_Plain has no FB_init inputs
        ("E170", 24),  # e: elements 2 and 3
        ("E020", 25),  # f: a STRING for an INT
    ]
