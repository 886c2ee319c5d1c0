"""Dialect profiles: every difference between IEC, MatIEC (OpenPLC, Beremiz),
CODESYS/TwinCAT and Schneider Unity/Control Expert lives here, not in
scattered flags.

The parser (only for comments: it takes every dialect's syntax and notes it
in the AST), the checker, the code generator and the process image read the
profile; nothing else decides dialect behaviour. docs/guide/porting.md "Profiles" has
the switches per profile in a table.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace


@dataclass(frozen=True)
class Profile:
    name: str
    # 'iec': byte-offset areas (%MW1 = bytes 2-3, %MD1 = bytes 4-7).
    # 'schneider': word indices (%MD3200 overlaps %MW3200/%MW3201; %M are
    # separate bits; %MW3250:X0 bit 0; %MW3250:4 a 4-word table).
    addressing: str
    # AND / OR evaluate their right operand only when needed. CODESYS and
    # TwinCAT evaluate both (AND_THEN / OR_ELSE short-circuit); so does
    # strict IEC here. Only matters when the right side calls a function.
    short_circuit: bool
    # An implicit narrowing conversion (DINT -> INT, LREAL -> REAL,
    # signed <-> unsigned of the same size) is an 'error' or a 'warning'.
    narrowing: str
    # AND/OR/XOR/NOT on integer types act bit-wise (CODESYS allows it; IEC
    # wants ANY_BIT).
    bitwise_on_integers: bool
    # Integers and bit strings of the same size mix freely (INT := WORD).
    int_bits_mix: bool
    # C-style 0x literals (the Schneider manual's examples use them).
    c_hex_literals: bool
    # (* *) comments nest: (* a (* b *) c *) is one comment. CODESYS and
    # TwinCAT nest them (their static analysis has a rule, SA0163, against
    # nested comments); IEC 61131-3 ed.2 2.1.5 does not, nor does MatIEC
    # (unless run with -n): there the first '*)' ends the comment.
    nested_comments: bool
    # Assigning a VAR_INPUT inside its own POU is an 'error' (E030) or a
    # 'warning' (W130). IEC 61131-3 reads inputs only; CODESYS, TwinCAT and
    # MatIEC accept it (MatIEC's lvalue checks refuse writes to FOR
    # variables, constants and another block's outputs, not to the POU's
    # own inputs: OSCAT's port to Beremiz writes them in 39 places): the
    # input then holds the new value until the next call passes another.
    own_input_assignment: str
    # A comma may end a call's argument list, F(a := 1, b := 2,): TwinCAT 3
    # accepts it (blark, a parser of TwinCAT sources, does too), and so does
    # CODESYS V3: a CODESYS export that CODESYS compiles has calls ending
    # "MqttRetain := TRUE,\n);". The IEC 61131-3 grammar has no such comma
    # and MatIEC rejects it.
    trailing_comma_in_calls: bool
    # The untyped literals 0 and 1 go into a BOOL (assigned, passed, as an
    # initial value) as FALSE and TRUE: CODESYS, TwinCAT, Schneider and
    # MatIEC accept b := 1. The IEC 61131-3 grammar itself lets 0 and 1
    # spell a BOOL literal (ed.2 B.1.2 boolean_literal); the iec profile is stricter by
    # choice and wants TRUE/FALSE or BOOL#1, so that a number meant for an
    # INT does not pass silently. Any other number stays E020 everywhere.
    bool_from_0_1: bool
    # An untyped integer literal that does not fit its target but fits some
    # integer type (w : WORD := -1; i : INT := 40000) is an 'error' (E022)
    # or an implicit conversion with a 'warning' (W122): the value wraps to
    # the target as the conversion function would (-1 -> 16#FFFF, 40000 ->
    # -25536). CODESYS and TwinCAT type a literal as the smallest type that
    # holds it and convert it like a variable, with a warning (C0195 for
    # UINT := -1, shown in the CODESYS and TwinCAT help of the 'warning
    # disable' pragma); a literal too large for any integer type is C0001
    # there too (E022 everywhere). IEC 61131-3 and MatIEC take a literal
    # only where its value fits; schneider, which narrows nothing
    # implicitly, is as strict.
    literal_range: str = "error"
    # JMP and labels in ST: a CODESYS and TwinCAT extension (CODESYS "ST
    # Statement: JMP"); Schneider's ST has them too. IEC 61131-3 ed.3's ST
    # statements (7.3.3, Table 72) have no jump, only IL has JMP, and
    # MatIEC's ST grammar follows it: E159 there.
    jumps_in_st: bool = True
    # An enumeration without {attribute 'strict'} is its base integer type
    # in arithmetic, comparisons and assignments (CODESYS, TwinCAT: the
    # attribute makes those errors, "Attribute 'strict'"); IEC 61131-3
    # enumerated values are no numbers (ed.3 6.4.4.3), so elsewhere every
    # enumeration is strict.
    loose_enums: bool = False
    # Length of a STRING declared without one.
    default_string_length: int = 80
    # s[i] is the i-th byte of a STRING (from 0; a WSTRING's i-th WORD),
    # read and written: CODESYS V3 and TwinCAT 3. IEC strings are not indexed.
    string_index: bool = False
    # TIME and LTIME literals up to the unsigned maximum of their bits
    # (T#49d17h2m47s295ms, LTIME#213503d23h34m33s709ms551us615ns): TwinCAT's
    # TIME and LTIME are unsigned (Beckhoff Information System, "TIME",
    # "LTIME": 0 .. 2^32-1 ms, 0 .. 2^64-1 ns), and TcUnit's documentation
    # and tests use the largest LTIME. The value is kept in the type's bits.
    unsigned_durations: bool = False
    # The names IEC 61131-3 ed.3 gave its new elementary types (LTIME,
    # LDATE, LTOD, LDT, LTIME_OF_DAY, LDATE_AND_TIME, CHAR, WCHAR) name no
    # variable (E011; CODESYS and TwinCAT refuse them too). MatIEC reads
    # ed.2, where they are plain names: a POU's variable may take one (the
    # OSCAT port to Beremiz has a variable LTIME and one LDT); it hides the
    # clock function LTIME() in that POU only. A global still may not.
    ed3_type_names_reserved: bool = True
    # A FUNCTION_BLOCK's VAR_IN_OUT is a variable of the instance, copied
    # from the argument before the call and back into it after (MatIEC: the
    # FB's C structure holds the value, the call sets it and reads it back).
    # So inst.io is read and written from outside as an input is, and a call
    # may leave it out: the body then works on the value the instance holds.
    # Elsewhere a VAR_IN_OUT is a reference bound at each call: E042 when a
    # call leaves it out, E013 when named from outside.
    fb_in_out_copied: bool = False
    # TRUNC(x), the name without a type, gives the integer type its context
    # wants: the target of the assignment, the parameter, the other operand
    # (MatIEC declares TRUNC once per integer type, as IEC 61131-3 ed.2
    # Table 22 gives it ANY_REAL -> ANY_INT, and picks the one that fits),
    # DINT without one. Elsewhere TRUNC is DINT (CODESYS).
    trunc_from_context: bool = False
    # Two underscores in a row in a number (16#7f_ff__ff): TwinCAT 3 (and
    # CODESYS V3, whose compiler it is) skips every underscore between the
    # digits; IEC 61131-3 (ed.3 Table 5: digit {['_'] digit}) and MatIEC
    # take one between two digits only (E003).
    doubled_underscores: bool = False
    # F_TRIG's memory starts FALSE, so its first call with CLK FALSE is a
    # falling edge: MatIEC's standard library declares M without an initial
    # value. IEC 61131-3 ed.3 Table 44, CODESYS and TwinCAT start it TRUE
    # (no edge until CLK has been TRUE).
    f_trig_first_call_edge: bool = False
    # An FB instance's local VAR read from outside (x := inst.local) is an
    # 'error' (E013) or a 'warning' (W113): CODESYS and TwinCAT permit read
    # access (their static analysis flags it, rule SA0102); IEC 61131-3
    # shows an instance's inputs and outputs only. A write stays E013.
    internal_read: str = "error"
    # BIT, CODESYS's one-bit BOOL: consecutive BIT fields of a STRUCT share
    # a byte ("Data type: BIT"), so SIZEOF, ADR and MEMCPY see them packed.
    # IEC 61131-3 and the other dialects have no such type (E012).
    bit_type: bool = False
    # An initial value that is no constant (`nVal : INT := LowerLimit;`,
    # `topic : STRING := CONCAT(base, '/x');`) is computed when the
    # variable is initialised, in declaration order: CODESYS and TwinCAT
    # take "any valid ST expression" there ("Variable Initialization").
    # IEC 61131-3 and the other dialects want a constant (E024).
    initial_values_at_start: bool = False
    # p[i] of a POINTER TO: the i-th element from where p points, (p + i *
    # SIZEOF(p^))^ (CODESYS "Pointer": "index access [] to pointer
    # variables"). IEC REF_TO takes no index (E050).
    pointer_index: bool = False
    # (i := i + 1) as a value (IF (i := i + 1) = 10 THEN): CODESYS
    # "Assignment as expression" (an extension of IEC 61131-3, which has
    # assignment statements only: E032 there).
    assignment_expressions: bool = False
    # ADR('text'): a pointer to the literal's characters (CODESYS and
    # TwinCAT keep string literals in memory; real code passes
    # str2 := ADR('TRUE') to a POINTER TO STRING input). Here the pointer
    # is to a copy of the literal made each time ADR is evaluated, so a
    # write through it changes no later ADR('text'). IEC REF/ADR and
    # MatIEC want a variable (E031).
    adr_of_literal: bool = False
    # TO_<type>(e) of an enumeration, strict or not: its value converted
    # from the base type (TO_INT(e) = 5, TO_STRING(e) = '5'); TO_STRING
    # and TO_WSTRING give the value's name instead where its TYPE has
    # {attribute 'to_string'} (Beckhoff Infosys, TC3 PLC, "TO_STRING/
    # TO_WSTRING for enumeration variables"; CODESYS "Attribute:
    # to_string"). IEC enumerated values are no numbers and convert to
    # nothing (E020).
    enum_conversions: bool = False


IEC = Profile(
    name="iec",
    addressing="iec",
    short_circuit=False,
    narrowing="error",
    bitwise_on_integers=False,
    int_bits_mix=False,
    c_hex_literals=False,
    nested_comments=False,
    own_input_assignment="error",
    trailing_comma_in_calls=False,
    bool_from_0_1=False,
    jumps_in_st=False,
)

CODESYS = Profile(
    name="codesys",
    addressing="iec",
    short_circuit=False,
    narrowing="warning",
    bitwise_on_integers=True,
    int_bits_mix=True,
    c_hex_literals=False,
    nested_comments=True,
    own_input_assignment="warning",
    trailing_comma_in_calls=True,
    bool_from_0_1=True,
    literal_range="warning",
    loose_enums=True,
    string_index=True,
    doubled_underscores=True,
    internal_read="warning",
    bit_type=True,
    initial_values_at_start=True,
    pointer_index=True,
    assignment_expressions=True,
    adr_of_literal=True,
    enum_conversions=True,
)

TWINCAT = replace(CODESYS, name="twincat", unsigned_durations=True)

# MatIEC, the compiler of OpenPLC and Beremiz: strict IEC types (it converts
# nothing implicitly, bit operators want ANY_BIT). Its process image is the
# runtime's business (OpenPLC's per-size areas are not modelled): byte
# offsets as in IEC.
MATIEC = replace(
    IEC,
    name="matiec",
    bool_from_0_1=True,
    own_input_assignment="warning",
    ed3_type_names_reserved=False,
    fb_in_out_copied=True,
    trunc_from_context=True,
    f_trig_first_call_edge=True,
)

SCHNEIDER = Profile(
    name="schneider",
    addressing="schneider",
    short_circuit=False,
    narrowing="error",
    bitwise_on_integers=True,
    int_bits_mix=True,
    c_hex_literals=True,
    nested_comments=True,
    own_input_assignment="warning",
    trailing_comma_in_calls=False,
    bool_from_0_1=True,
)

PROFILES = {p.name: p for p in (IEC, MATIEC, CODESYS, TWINCAT, SCHNEIDER)}
DEFAULT = CODESYS


def get_profile(name: str) -> Profile:
    try:
        return PROFILES[name.lower()]
    except KeyError:
        raise KeyError(f"unknown profile {name!r}; choose one of {', '.join(PROFILES)}") from None


def names_where(test: Callable[[Profile], bool]) -> str:
    """The profiles that pass test, for a hint: 'codesys, twincat and schneider'."""
    names = [p.name for p in PROFILES.values() if test(p)]
    return ", ".join(names[:-1]) + " and " + names[-1] if len(names) > 1 else "".join(names)
