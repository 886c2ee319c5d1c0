"""Polymorphism through parameters (runtime/st/check/oop.py extends_fb, used by
checker_calls.py, checker_refs.py and conversions.py).

CODESYS "Extension of a Function Block" / TwinCAT "EXTENDS": an instance of
a derived FUNCTION_BLOCK may be used wherever a reference to an instance of
its base is expected (VAR_IN_OUT, REFERENCE TO, REF_TO, POINTER TO) and
methods called through that reference run the derived block's overrides
(late binding, IEC 61131-3 ed.3 6.6.5.5). A block that does not EXTEND the
parameter's type stays an error (E020) whose hint says so."""

from __future__ import annotations

from .conftest import diagnostics, run_st

MOTORS = """
INTERFACE I_Speed
METHOD Speed : INT END_METHOD
END_INTERFACE
FUNCTION_BLOCK FB_Motor IMPLEMENTS I_Speed
VAR_INPUT boost : INT; END_VAR
VAR_OUTPUT starts : INT; END_VAR
METHOD Speed : INT
Speed := 1;
END_METHOD
METHOD Start
starts := starts + 1;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_FastMotor EXTENDS FB_Motor
METHOD Speed : INT
Speed := 10 + boost;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Turbo EXTENDS FB_FastMotor
METHOD Speed : INT
Speed := SUPER^.Speed() * 10;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Pump
END_FUNCTION_BLOCK
"""


def test_derived_instances_through_in_out_and_references_dispatch_to_overrides():
    src = (
        MOTORS
        + """
FUNCTION ViaInOut : INT
VAR_IN_OUT m : FB_Motor; END_VAR
m.Start();
ViaInOut := m.Speed();
END_FUNCTION
FUNCTION ViaReference : INT
VAR_INPUT m : REFERENCE TO FB_Motor; END_VAR
ViaReference := m.Speed();
END_FUNCTION
FUNCTION ViaRefTo : INT
VAR_INPUT m : REF_TO FB_Motor; END_VAR
ViaRefTo := m^.Speed();
END_FUNCTION
FUNCTION ViaPointer : INT
VAR_INPUT m : POINTER TO FB_Motor; END_VAR
ViaPointer := m^.Speed();
END_FUNCTION
PROGRAM main
VAR plain : FB_Motor; fast : FB_FastMotor := (boost := 2); turbo : FB_Turbo;
    a, b, c, d, e, f : INT; r : REF_TO FB_Motor; END_VAR
a := ViaInOut(plain);           (* the base's own: 1 *)
b := ViaInOut(fast);            (* the override: 10 + 2 *)
c := ViaReference(turbo);       (* two levels down: (10 + 0) * 10 *)
d := ViaRefTo(REF(fast));
e := ViaPointer(ADR(turbo));
r := REF(turbo);                (* a REF_TO the base designates a derived instance *)
f := r^.Speed();
END_PROGRAM
"""
    )
    r = run_st(src, cycles=2)
    assert [r.get(n) for n in "abcdef"] == [1, 12, 100, 12, 100, 100]
    # the instance itself was passed, not a copy: Start() counted on it
    assert (r.get("plain.starts"), r.get("fast.starts")) == (2, 2)


def test_block_parameters_in_out_reference_and_interface_input():
    src = (
        MOTORS
        + """
FUNCTION_BLOCK FB_Driver
VAR_INPUT itf : I_Speed; END_VAR
VAR_IN_OUT motor : FB_Motor; END_VAR
VAR_OUTPUT total : DINT; END_VAR
VAR last : REFERENCE TO FB_Motor; END_VAR
last REF= motor;
motor.boost := motor.boost + 1;   (* writes the caller's instance *)
total := INT_TO_DINT(itf.Speed()) * 1000 + last.Speed();
END_FUNCTION_BLOCK
PROGRAM main
VAR fast : FB_FastMotor; turbo : FB_Turbo; drv : FB_Driver; t1, t2 : DINT; END_VAR
drv(itf := turbo, motor := fast);
t1 := drv.total;                  (* each call adds 1 to the boost of the block passed *)
drv(itf := fast, motor := turbo);
t2 := drv.total;
END_PROGRAM
"""
    )
    r = run_st(src, cycles=3)
    # cycle 3, first call: turbo (boost 2) gives (10 + 2) * 10 through the
    # interface, fast (boost now 3) 13 through the reference; second call:
    # fast 13 through the interface, turbo (boost now 3) 130
    assert (r.get("t1"), r.get("t2")) == (120 * 1000 + 13, 13 * 1000 + 130)
    assert (r.get("fast.boost"), r.get("turbo.boost")) == (3, 3)


def test_a_block_that_does_not_extend_the_type_is_e020_with_a_hint():
    src = (
        MOTORS
        + """
FUNCTION Use : INT
VAR_IN_OUT m : FB_Motor; END_VAR
VAR_INPUT r : REFERENCE TO FB_Motor; p : POINTER TO FB_FastMotor; END_VAR
END_FUNCTION
PROGRAM main
VAR pump : FB_Pump; plain : FB_Motor; i : INT; END_VAR
i := Use(m := pump, r := pump, p := ADR(plain));   (* a base is not a derived one *)
END_PROGRAM
"""
    )
    got = [(d.code, d.pos.line, d.hint) for d in diagnostics(src)]
    assert got == [
        ("E020", 34, "FB_Pump does not EXTEND FB_Motor: pass an instance of FB_Motor or of a block that EXTENDS it"),
        ("E020", 34, "FB_Pump does not EXTEND FB_Motor: pass an instance of FB_Motor or of a block that EXTENDS it"),
        (
            "E020",
            34,
            "FB_Motor does not EXTEND FB_FastMotor: pass an instance of FB_FastMotor or of a block that EXTENDS it",
        ),
    ]
