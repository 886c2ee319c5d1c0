"""METHODs of FUNCTION_BLOCKs and THIS^ (runtime/st/check/checker_oop.py,
codegen_oop.py): IEC 61131-3 ed.3 6.6.5 and the CODESYS help "Object:
Method". A method's VAR, VAR_INPUT, VAR_OUTPUT and VAR_TEMP live in the call
(as a FUNCTION's); VAR_INST lives in the instance; the method's name is its
return value; inside the block a method is called as M() or THIS^.M()."""

from __future__ import annotations

from .conftest import diagnostics, run_st

COUNTER = """
FUNCTION_BLOCK FB_Counter
VAR_INPUT step : INT := 1; END_VAR
VAR_OUTPUT count : INT; END_VAR
VAR calls : INT; END_VAR
METHOD Add : INT
VAR_INPUT n : INT := 1; END_VAR
VAR_OUTPUT before : INT; END_VAR
VAR_INST made : INT; END_VAR
VAR local : INT; END_VAR
before := count;
local := local + 1;       (* a method VAR starts afresh at every call *)
made := made + local;     (* a VAR_INST keeps its value in the instance *)
count := count + n * step;
Add := count;
END_METHOD
METHOD Twice : INT
VAR_INPUT n : INT; END_VAR
Twice := Add(n) + THIS^.Add(n := n);
END_METHOD
METHOD Made : INT
VAR_INST made_here : INT; END_VAR
made_here := made_here + 100;
Made := made_here;
END_METHOD
METHOD Clear
count := 0;
THIS^.calls := 0;
END_METHOD
calls := calls + 1;
Add();
END_FUNCTION_BLOCK
"""


def test_methods_called_from_outside_as_statement_and_in_expressions():
    src = (
        COUNTER
        + """
PROGRAM main
VAR c : FB_Counter; r, b, t, m : INT; END_VAR
c();                                    (* the body: count + 1 *)
r := c.Add(n := 10, before => b);       (* formal call with an output *)
t := c.Twice(2);                        (* Add(2) + THIS^.Add(2) inside *)
c.Add(5);                               (* as a statement: the result is dropped *)
m := c.Made();
END_PROGRAM
"""
    )
    r = run_st(src, cycles=2)
    # cycle 1: body 1, Add(10) 11 (b = 1), Twice 13 + 15 = 28, Add(5) 20
    # cycle 2: body 21, Add(10) 31 (b = 21), Twice 33 + 35 = 68, Add(5) 40
    assert (r.get("r"), r.get("b"), r.get("t"), r.get("c.count")) == (31, 21, 68, 40)
    # Made's own VAR_INST is not Add's: 100 per call of Made, two calls
    assert r.get("m") == 200


def test_var_inst_keeps_its_value_and_method_vars_start_afresh():
    src = (
        COUNTER
        + """
PROGRAM main
VAR c : FB_Counter; END_VAR
c.Add(); c.Add(); c.Add();
END_PROGRAM
"""
    )
    r = run_st(src, cycles=2)
    # local is 1 at every call (a method's VAR is temporary, CODESYS), so made counts calls
    assert r.get("c.count") == 6
    [add] = [m for m in type(r.instance.v_c).__dict__ if m.startswith("i3_add")]
    assert getattr(r.instance.v_c, add) == 6


def test_method_without_result_and_this_inside_the_block():
    src = (
        COUNTER
        + """
PROGRAM main
VAR c : FB_Counter; n : INT; END_VAR
c(); c(); c.Clear(); c(); n := c.count;
END_PROGRAM
"""
    )
    r = run_st(src)
    assert r.get("n") == 1


def test_missing_inputs_take_their_initial_values_at_every_call():
    # CODESYS: the inputs of a method are initialised at each call, as a FUNCTION's
    src = """
FUNCTION_BLOCK FB
METHOD Scale : INT
VAR_INPUT x : INT := 7; k : INT := 2; END_VAR
Scale := x * k;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM main
VAR f : FB; a, b, c : INT; END_VAR
a := f.Scale(); b := f.Scale(x := 3); c := f.Scale(k := 10);
END_PROGRAM
"""
    r = run_st(src)
    assert (r.get("a"), r.get("b"), r.get("c")) == (14, 6, 70)


def test_method_after_end_function_block_belongs_to_it():
    # the TwinCAT/blark text export puts METHODs after END_FUNCTION_BLOCK
    src = """
FUNCTION_BLOCK FB
VAR x : INT; END_VAR
x := x + 1;
END_FUNCTION_BLOCK
METHOD Get : INT
Get := x * 10;
END_METHOD
PROGRAM main
VAR f : FB; v : INT; END_VAR
f(); v := f.Get();
END_PROGRAM
"""
    assert run_st(src, cycles=3).get("v") == 30


def test_methods_of_instances_in_an_array():
    src = (
        COUNTER
        + """
PROGRAM main
VAR cs : ARRAY[1..3] OF FB_Counter; i, sum : INT; END_VAR
sum := 0;
FOR i := 1 TO 3 DO sum := sum + cs[i].Add(n := i); END_FOR
END_PROGRAM
"""
    )
    assert run_st(src, cycles=2).get("sum") == 12  # 2 + 4 + 6 in the second cycle


def test_a_method_that_is_not_a_value_and_unknown_methods_are_coded_errors():
    src = """
FUNCTION_BLOCK FB
METHOD Go
END_METHOD
END_FUNCTION_BLOCK
PROGRAM main
VAR f : FB; x : INT; END_VAR
x := f.Go();
f.Gone();
END_PROGRAM
"""
    got = [(d.code, d.pos.line, d.pos.col) for d in diagnostics(src)]
    assert ("E148", 8, 6) in got  # METHOD Go has no return type
    assert ("E013", 9, 1) in got or ("E013", 9, 3) in got  # FB has no member 'Gone'


def test_this_outside_a_function_block_and_without_caret():
    src = """
FUNCTION_BLOCK FB
VAR x : INT; END_VAR
x := THIS.x;
END_FUNCTION_BLOCK
PROGRAM main
VAR y : INT; END_VAR
y := THIS^.y;
END_PROGRAM
"""
    got = [(d.code, d.pos.line) for d in diagnostics(src)]
    assert ("E146", 4) in got and ("E146", 8) in got


def test_a_method_named_like_a_variable_is_declared_twice():
    src = """
FUNCTION_BLOCK FB
VAR speed : INT; END_VAR
METHOD Speed : INT
END_METHOD
END_FUNCTION_BLOCK
"""
    [d] = diagnostics(src)
    assert (d.code, d.pos.line, d.pos.col) == ("E141", 4, 1)
