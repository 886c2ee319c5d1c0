"""The corpus of valid ST programs the fuzz tests mutate (test_fuzz.py)."""

from __future__ import annotations

# ---------------------------------------------------------------- corpus

CORPUS = [
    # 0: elementary types, operators, strings, bit access, typed literals
    (
        "codesys",
        """
PROGRAM main
VAR
    a : INT := 7; b : DINT := -3; c : REAL := 1.5; d : LREAL; ok : BOOL;
    w : WORD := 16#00FF; bt : BYTE := 2#1010; s : STRING[20] := 'hi $'there$''; u : UINT;
    n : DINT;
END_VAR
n := n + 1;
d := c * 2.0E1 + INT_TO_LREAL(a);
b := b + a MOD 4 - (a / 2) * 3;
ok := (a > 3) AND NOT (b = 0) OR w.3 XOR FALSE;
w := SHL(w, 1) OR WORD#16#0001;
bt := bt AND 16#0F;
s := CONCAT(s, '!');
u := UINT#5 + 2;
a := -a;
END_PROGRAM
""",
    ),
    # 1: arrays (initialiser with repetition, 2-D), FOR with BY
    (
        "codesys",
        """
PROGRAM main
VAR
    arr : ARRAY[1..5] OF INT := [1, 2, 3(7)];
    grid : ARRAY[0..2, 0..2] OF DINT;
    i : INT; j : INT; total : DINT;
END_VAR
total := 0;
FOR i := 1 TO 5 DO
    arr[i] := arr[i] + i;
    total := total + arr[i];
END_FOR
FOR i := 0 TO 2 DO
    FOR j := 2 TO 0 BY -1 DO
        grid[i, j] := i * 3 + j;
    END_FOR
END_FOR
END_PROGRAM
""",
    ),
    # 2: enums, structs, struct initialisers, CASE with lists, ranges, ELSE
    (
        "codesys",
        """
TYPE Color : (Red, Green := 5, Blue); END_TYPE
TYPE Point :
STRUCT
    x : INT := 1;
    y : INT;
    tag : Color := Color#Blue;
END_STRUCT
END_TYPE
PROGRAM main
VAR p : Point; q : Point := (x := 3, y := 4); c : Color; out : INT; k : INT; END_VAR
k := k + 1;
p.x := q.x + q.y;
CASE k OF
    1: c := Red;
    2, 3: c := Green;
    4..10: c := Blue;
ELSE
    k := 0;
END_CASE
CASE c OF
    Red: out := 1;
    Green: out := 2;
    Blue: out := 3;
END_CASE
p := q;
END_PROGRAM
""",
    ),
    # 3: a user FB, standard FBs, named inputs and outputs
    (
        "codesys",
        """
FUNCTION_BLOCK Counter
VAR_INPUT inc : BOOL; step : INT := 1; END_VAR
VAR_OUTPUT count : INT; done : BOOL; END_VAR
VAR prev : BOOL; END_VAR
IF inc AND NOT prev THEN
    count := count + step;
END_IF
prev := inc;
done := count >= 3;
END_FUNCTION_BLOCK
PROGRAM main
VAR c1 : Counter; t : TON; edge : R_TRIG; pulse : BOOL; fin : BOOL; n : INT; END_VAR
pulse := NOT pulse;
c1(inc := pulse, step := 1, done => fin);
t(IN := TRUE, PT := T#30ms);
edge(CLK := t.Q);
n := c1.count;
END_PROGRAM
""",
    ),
    # 4: a FUNCTION with outputs and in-outs, WHILE, REPEAT, EXIT, CONTINUE
    (
        "codesys",
        """
FUNCTION Collatz : INT
VAR_INPUT start : DINT; END_VAR
VAR_OUTPUT peak : DINT; END_VAR
VAR_IN_OUT calls : INT; END_VAR
VAR n : DINT; steps : INT; END_VAR
n := start; peak := n; calls := calls + 1;
WHILE n > 1 DO
    IF n MOD 2 = 0 THEN n := n / 2; ELSE n := 3 * n + 1; END_IF
    IF n > peak THEN peak := n; END_IF
    steps := steps + 1;
    IF steps > 500 THEN EXIT; END_IF
END_WHILE
Collatz := steps;
END_FUNCTION
PROGRAM main
VAR steps : INT; peak : DINT; calls : INT; k : INT; acc : INT; END_VAR
steps := Collatz(start := 27, peak => peak, calls := calls);
k := 0;
REPEAT
    k := k + 1;
    IF k = 2 THEN CONTINUE; END_IF
    acc := acc + k;
UNTIL k >= 5
END_REPEAT
END_PROGRAM
""",
    ),
    # 5: references and pointers
    (
        "codesys",
        """
PROGRAM main
VAR
    x : INT := 5; r : REF_TO INT; p : POINTER TO INT; y : INT;
    arr : ARRAY[1..3] OF INT; isnull : BOOL;
END_VAR
r := REF(x);
r^ := r^ + 1;
p := ADR(arr[2]);
p^ := 42;
y := x + p^;
isnull := r = 0;
END_PROGRAM
""",
    ),
    # 6: time and date literals, globals, constants, subranges
    (
        "codesys",
        """
VAR_GLOBAL CONSTANT LIMIT : INT := 4; END_VAR
VAR_GLOBAL g_total : DINT; END_VAR
PROGRAM main
VAR
    t : TIME := T#1s250ms; u : TIME; tod1 : TOD := TOD#12:30:00; d : DATE := D#2024-02-29;
    dt1 : DT := DT#2024-01-01-00:00:00; pct : INT(0..100) := 50; lt : LTIME := LTIME#5us;
    buf : ARRAY[1..LIMIT] OF INT; i : INT; now : TIME;
END_VAR
u := t * 2 + T#250ms - T#1m;
tod1 := tod1 + T#1h;
now := TIME();
FOR i := 1 TO LIMIT DO
    buf[i] := i * pct;
    g_total := g_total + buf[i];
END_FOR
pct := LIMIT * 10;
END_PROGRAM
""",
    ),
    # 7: Schneider located variables, bit and table addresses, C hex, SET/RESET
    (
        "schneider",
        """
PROGRAM main
VAR
    level AT %MW100 : INT;
    flag AT %M10 : BOOL;
    big : DINT;
    w : WORD;
    cnt : INT;
END_VAR
cnt := cnt + 1;
%MW3250 := 0x00FF;
%MD3220 := 16#00032004;
flag := %MW3250:X0;
IF flag AND NOT %M101 THEN
    level := level + 1;
    SET %M101;
END_IF
big := %MD3220;
w := INT_TO_WORD(%MW3250);
RESET %M101;
END_PROGRAM
""",
    ),
    # 8: a bare statement list (a pasted Schneider section), READ_VAR
    (
        "schneider",
        """
%MD3220 := 0x00032004; (* index/sub-index *)
IF %M101 AND NOT %MW3260:X0 THEN
  %MW3263 := 2;
  READ_VAR(ADR#0.1.SYS, 'SDO', %MD3220, 40, %MW3222:1, %MW3260:4);
  RESET %M101;
END_IF;
""",
    ),
    # CODESYS REFERENCE TO and pointer arithmetic (tests/st/test_refs.py, test_pointers.py)
    (
        "codesys",
        """
TYPE Pair : STRUCT a : INT; r : REFERENCE TO INT; END_STRUCT END_TYPE
FUNCTION_BLOCK Bump
VAR_INPUT target : REFERENCE TO INT; END_VAR
IF __ISVALIDREF(target) THEN target := target + 1; END_IF
END_FUNCTION_BLOCK
PROGRAM main
VAR
    arr : ARRAY[0..3] OF INT := [1, 2, 3, 4]; p : POINTER TO INT; q : POINTER TO INT;
    r : REFERENCE TO INT; pr : Pair; b : Bump; s : INT; d : DINT; n : UDINT;
END_VAR
r REF= arr[1]; r := r * 10; pr.r REF= s; b(target := s);
p := ADR(arr); q := ADR(arr) + 3 * SIZEOF(INT);
WHILE p <= q DO s := s + p^; p := p + SIZEOF(INT); END_WHILE
d := q - ADR(arr); n := SIZEOF(Pair);
END_PROGRAM
""",
    ),
    # IL bodies (st/syntax/il.py): operators with modifiers, parentheses, calls,
    # jumps across labels with the current result, an IL action
    (
        "matiec",
        """
FUNCTION Mean2 : INT
VAR_INPUT a, b : INT; END_VAR
    LD a
    ADD b
    DIV 2
    ST Mean2
END_FUNCTION

FUNCTION_BLOCK Tally
VAR_INPUT clear : BOOL; step : INT; END_VAR
VAR_OUTPUT total : INT; full : BOOL; END_VAR
VAR latch : SR; END_VAR
    LD clear
    JMPC zero
    LD total
    ADD step
    JMP keep
zero: LD 0
keep: ST total
    GE 50
    S1 latch
    LD clear
    R latch
    LD latch.Q1
    ST full
END_FUNCTION_BLOCK

PROGRAM main
VAR
    n, m, k : INT; t : Tally; trig : R_TRIG; ton1 : TON;
    a, b, x, y : BOOL; w : WORD := 16#00F0; r : REAL;
END_VAR
    LD n
    ADD 1
    ST n
    MOD 4
    EQ 0
    ST a
    LD n
    GT 2
    ST b
    LD a
    AND( b
    ORN x
    )
    XOR y
    ST x
    LDN x
    S y
    LD b
    R y
    LD n
    MOD 9
    EQ 0
    ST t.clear
    CAL t(step := n)
    LD t.full
    CLK trig
    LD b
    IN ton1
    LD T#20ms
    PT ton1
    LD n
    Mean2 t.total
    MAX 3, 4
    ST m
    LD w
    AND 16#FF00
    OR 2#1
    ST w
    LD n
    INT_TO_REAL
    MUL 1.5
    ST r
    LD 0
    ST k
again: LD k
    ADD 1
    ST k
    LT 3
    JMPC again
    LD a
    RETC
    CAL Bump
ACTION Bump:
    LD m
    ADD 1
    ST m
END_ACTION
END_PROGRAM
""",
    ),
]
