"""Abstract syntax tree of Structured Text.

The parser builds these nodes; the checker annotates expressions (``ty``) and
symbols (``sym``); the code generator reads the annotated tree. Every node
keeps the source position it came from so that diagnostics and runtime faults
can point at ST, never at Python.

Names are kept as written (``name``); lookups are case-insensitive, so the
checker compares ``name.upper()``.
"""

from __future__ import annotations

import reprlib
from collections.abc import Iterable
from dataclasses import dataclass, field, fields
from typing import Any


@dataclass(frozen=True, slots=True)
class Pos:
    """A source span: 1-based line and column of the first character, and of
    the character after the last one (``end_*`` may equal start for a point)."""

    file: str
    line: int
    col: int
    end_line: int = 0
    end_col: int = 0

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}"

    def __reduce__(self) -> tuple:  # (cached parses: faster than the dataclass's __setstate__)
        return Pos, (self.file, self.line, self.col, self.end_line, self.end_col)


NOPOS = Pos("<builtin>", 0, 0)


@dataclass(slots=True, eq=False, repr=False)
class Node:
    """Every node of the tree: where it was written."""

    pos: Pos = field(default=NOPOS, kw_only=True)

    @reprlib.recursive_repr()
    def __repr__(self) -> str:
        # one for every node, as the dataclass would write it: a __repr__
        # generated per class cost each start 55 exec calls
        shown = ", ".join(f"{f.name}={getattr(self, f.name)!r}" for f in fields(self) if f.repr)
        return f"{type(self).__qualname__}({shown})"


# ---------------------------------------------------------------- expressions


@dataclass(slots=True, eq=False, repr=False)
class Expr(Node):
    # Set by the checker: the resolved type (runtime.st.types.Type).
    ty: Any = field(default=None, kw_only=True, repr=False)
    # Set by the checker when the value is known at compile time.
    const: Any = field(default=None, kw_only=True, repr=False)
    # Set by the checker on a REFERENCE TO used as its target (CODESYS:
    # dereferenced implicitly): the reference's type; ty is the target's.
    implicit_ref: Any = field(default=None, kw_only=True, repr=False)


@dataclass(slots=True, eq=False, repr=False)
class Literal(Expr):
    """A literal with its parsed Python value.

    kind is one of: 'int', 'real', 'bool', 'string', 'wstring', 'time',
    'ltime', 'date', 'tod', 'dt', 'ldate', 'ltod', 'ldt'.
    Values: int/real/bool as Python int/float/bool; strings decoded ($ escapes
    resolved); every time and date kind as an int of NANOSECONDS (durations
    for time/ltime; since midnight for tod/ltod; since 1970-01-01T00:00:00 for
    date/dt/ldate/ldt). type_name is the explicit prefix of a typed literal
    (``INT#5`` -> 'INT', ``T#5s`` -> None), upper-cased.
    """

    kind: str
    value: Any
    type_name: str | None = None
    c_hex: bool = False  # written C-style (0x1F); allowed by profile only
    doubled_underscore: bool = False  # a number with '__' (16#7f__ff); by profile only


@dataclass(slots=True, eq=False, repr=False)
class EnumLiteral(Expr):
    """``Color#Red`` (type_name='Color') or a bare enumerator resolved later."""

    type_name: str | None
    value_name: str


@dataclass(slots=True, eq=False, repr=False)
class SchneiderAddress(Expr):
    """Schneider exchange address ``ADR#0.1.SYS`` -> parts ('0', '1', 'SYS')."""

    parts: tuple


@dataclass(frozen=True, slots=True)
class LocatedAddress:
    """A direct address such as ``%IX0.3``, ``%MW3250``, ``%MW3250:X0``,
    ``%MW3250:4``.

    area: 'I', 'Q' or 'M'. size: 'X', 'B', 'W', 'D', 'L' or '' (no size
    letter: a bit, ``%M100`` / ``%I0.1``). indices: the dotted numbers
    (``%IX0.3`` -> (0, 3)). bit: the Schneider ``:Xn`` bit of a word.
    table: the Schneider ``:n`` table length. text: the address as written,
    for messages only (never pasted into generated code).
    """

    area: str
    size: str
    indices: tuple
    bit: int | None = None
    table: int | None = None
    text: str = ""


@dataclass(slots=True, eq=False, repr=False)
class Located(Expr):
    addr: LocatedAddress


@dataclass(slots=True, eq=False, repr=False)
class Name(Expr):
    name: str
    sym: Any = field(default=None, kw_only=True, repr=False)
    # The global variable list it was written with (GVL.x -> 'GVL'): only
    # globals are then looked up (namespaces.py).
    qualifier: str | None = field(default=None, kw_only=True)


@dataclass(slots=True, eq=False, repr=False)
class Member(Expr):
    """``base.name`` (struct field, FB instance variable, enum ``Type.Value``)."""

    base: Expr
    name: str
    sym: Any = field(default=None, kw_only=True, repr=False)


@dataclass(slots=True, eq=False, repr=False)
class BitAccess(Expr):
    """``w.3`` or ``w.%X3``: bit 3 of a bit-string or integer variable;
    size "B", "W", "D" or "L" for the partial access ``d.%B0``, ``d.%W1``
    (IEC 61131-3 ed.3 6.5.3): byte 0, word 1 (bit is then the part's number)."""

    base: Expr
    bit: Expr
    size: str = "X"


@dataclass(slots=True, eq=False, repr=False)
class Index(Expr):
    """``a[i]`` or ``a[i, j]`` (one expression per dimension)."""

    base: Expr
    indices: list
    # Set by the checker on a pointer's index p[i] (CODESYS): the Deref of
    # p moved by i elements it stands for (checker_pointers.py)
    via: Any = field(default=None, kw_only=True, repr=False)


@dataclass(slots=True, eq=False, repr=False)
class AssignExpr(Expr):
    """``(target := value)`` used as a value (CODESYS): the value stored."""

    target: Expr
    value: Expr


@dataclass(slots=True, eq=False, repr=False)
class Deref(Expr):
    """``r^``"""

    base: Expr


@dataclass(slots=True, eq=False, repr=False)
class Unary(Expr):
    op: str  # 'NOT', '-', '+'
    operand: Expr


@dataclass(slots=True, eq=False, repr=False)
class Binary(Expr):
    """op: 'OR', 'OR_ELSE', 'XOR', 'AND', 'AND_THEN' ('&' is 'AND'), '=', '<>',
    '<', '>', '<=', '>=', '+', '-', '*', '/', 'MOD', '**'."""

    op: str
    left: Expr
    right: Expr
    # Set by the checker when the operator is a library function (time and
    # date arithmetic: TOD + TIME is ADD_TOD_TIME).
    impl: Any = field(default=None, kw_only=True, repr=False)
    # The function the operation was written as (ADD for ADD(a, b)), for
    # diagnostics; None for the operator form.
    spelling: str | None = field(default=None, kw_only=True, repr=False)
    # Set by conversions.is_flexible the first time it is asked (a chain of
    # 10,000 operators is asked at every level).
    flexible: bool | None = field(default=None, kw_only=True, repr=False)


@dataclass(slots=True, eq=False, repr=False)
class Arg(Node):
    """One call argument. name is None for a positional argument.
    output=True for ``name => target`` (value is then the target expression,
    or None for an output left unconnected). negated for ``NOT name => x``."""

    name: str | None
    value: Expr | None
    output: bool = False
    negated: bool = False


class ArgList(list):
    """A call's arguments (Arg) as written; trailing_comma: where a comma
    ends the list, F(a := 1,) (TwinCAT accepts it; the profile decides)."""

    __slots__ = ("trailing_comma",)

    def __init__(self, args: Iterable = (), trailing_comma: Pos | None = None) -> None:
        super().__init__(args)
        self.trailing_comma = trailing_comma


@dataclass(slots=True, eq=False, repr=False)
class Call(Expr):
    """A function call, or an FB instance call (as a statement)."""

    callee: Expr  # Name, or Member for an instance inside a struct/FB
    args: list
    # Where a comma ends the argument list (None: it does not).
    trailing_comma: Pos | None = field(default=None, kw_only=True)
    # Set by the checker: what is called (a Symbol/POU/builtin descriptor).
    target: Any = field(default=None, kw_only=True, repr=False)


# ---------------------------------------------------------------- types (syntax)


@dataclass(slots=True, eq=False, repr=False)
class TypeSpec(Node):
    pass


@dataclass(slots=True, eq=False, repr=False)
class NamedType(TypeSpec):
    name: str


@dataclass(slots=True, eq=False, repr=False)
class StringTypeSpec(TypeSpec):
    wide: bool
    length: Expr | None = None  # STRING[80] / STRING(80); None = default


@dataclass(slots=True, eq=False, repr=False)
class ArrayTypeSpec(TypeSpec):
    """ranges: list of (lo, hi) expression pairs, or None for ``*``
    (variable-length array in VAR_IN_OUT)."""

    ranges: list
    elem: TypeSpec
    fb_inits: list | None = None  # CODESYS OF FB_X[(n := 1), ...]: a StructInit per element


@dataclass(slots=True, eq=False, repr=False)
class StructTypeSpec(TypeSpec):
    members: list  # VarDecl
    extends: TypeSpec | None = None  # CODESYS: TYPE B EXTENDS A : STRUCT ... (A's fields first)


@dataclass(slots=True, eq=False, repr=False)
class EnumTypeSpec(TypeSpec):
    """values: list of (name, Expr|None, Pos); base: explicit base type of a
    typed enumeration ``(a, b) INT`` or ``INT (a := 1, b := 2)``."""

    values: list
    base: TypeSpec | None = None


@dataclass(slots=True, eq=False, repr=False)
class SubrangeTypeSpec(TypeSpec):
    base: TypeSpec
    lo: Expr
    hi: Expr


@dataclass(slots=True, eq=False, repr=False)
class RefTypeSpec(TypeSpec):
    """REF_TO T (pointer=False), POINTER TO T (pointer=True) or the CODESYS
    REFERENCE TO T (reference=True)."""

    target: TypeSpec
    pointer: bool = False
    reference: bool = False


# ---------------------------------------------------------------- initialisers


@dataclass(slots=True, eq=False, repr=False)
class ArrayInit(Node):
    """``[1, 2, 3(0)]`` -> items of (count Expr|None, initialiser)."""

    items: list


@dataclass(slots=True, eq=False, repr=False)
class StructInit(Node):
    """``(a := 1, b := [1, 2])`` -> fields of (name, initialiser, Pos)."""

    fields: list


Initializer = Expr | ArrayInit | StructInit


# ---------------------------------------------------------------- declarations


@dataclass(slots=True, eq=False, repr=False)
class VarDecl(Node):
    name: str
    type: TypeSpec
    init: Any = None  # Initializer or None
    location: LocatedAddress | None = None  # AT %...
    pragmas: list = field(default_factory=list)


@dataclass(slots=True, eq=False, repr=False)
class VarBlock(Node):
    """kind: 'VAR', 'VAR_INPUT', 'VAR_OUTPUT', 'VAR_IN_OUT', 'VAR_GLOBAL',
    'VAR_EXTERNAL', 'VAR_TEMP', 'VAR_STAT', 'VAR_CONFIG'."""

    kind: str
    decls: list
    constant: bool = False
    retain: bool = False
    persistent: bool = False
    # {attribute 'qualified_only'} before a VAR_GLOBAL block (CODESYS GVL).
    pragmas: list = field(default_factory=list)


@dataclass(slots=True, eq=False, repr=False)
class TypeDecl(Node):
    name: str
    spec: TypeSpec
    init: Any = None  # default initial value for the type
    pragmas: list = field(default_factory=list)


@dataclass(slots=True, eq=False, repr=False)
class POU(Node):
    """kind: 'PROGRAM', 'FUNCTION', 'FUNCTION_BLOCK'."""

    kind: str
    name: str
    var_blocks: list
    body: list  # statements
    return_type: TypeSpec | None = None
    pragmas: list = field(default_factory=list)
    external: bool = False  # declared only (body provided natively)
    actions: list = field(default_factory=list)  # Action, written inside the POU or given to it
    # an ast_sfc.SfcNetwork when the body is SFC (then body is []); Any: ast_sfc builds on this module
    sfc: Any = None
    # Object-oriented ST (FUNCTION_BLOCK only; checker_oop.py): ABSTRACT,
    # FINAL, PUBLIC ... as written (upper-case), EXTENDS (the base's name
    # and position), IMPLEMENTS (names and positions), METHODs, PROPERTYs.
    modifiers: tuple = ()
    extends: tuple | None = None
    implements: list = field(default_factory=list)
    methods: list = field(default_factory=list)
    properties: list = field(default_factory=list)


@dataclass(slots=True, eq=False, repr=False)
class Action(Node):
    """``ACTION Name: ... END_ACTION``: more code of a PROGRAM or
    FUNCTION_BLOCK, on its variables. pou_name: the POU a top-level
    ``ACTION Pou.Name:`` names (None inside a POU); name_pos: where the
    name is."""

    name: str
    body: list
    pou_name: str | None = None
    name_pos: Pos = NOPOS


@dataclass(slots=True, eq=False, repr=False)
class Method(Node):
    """A METHOD of a FUNCTION_BLOCK or INTERFACE (an interface's has no
    body; body is then None). modifiers: upper-case ABSTRACT, FINAL, PUBLIC ..."""

    name: str
    var_blocks: list
    body: list | None
    return_type: TypeSpec | None = None
    modifiers: tuple = ()


@dataclass(slots=True, eq=False, repr=False)
class Property(Node):
    """A PROPERTY (CODESYS, TwinCAT): its GET and SET accessors are Methods
    (None where it has none; in an INTERFACE they have no body)."""

    name: str
    type: TypeSpec
    getter: Method | None
    setter: Method | None
    modifiers: tuple = ()


@dataclass(slots=True, eq=False, repr=False)
class Interface(Node):
    """INTERFACE name EXTENDS bases: methods and properties without bodies."""

    name: str
    bases: list  # (name, Pos)
    methods: list
    properties: list


@dataclass(slots=True, eq=False, repr=False)
class TaskDecl(Node):
    """TASK name (INTERVAL := T#10ms, PRIORITY := 1, SINGLE := x)."""

    name: str
    params: dict  # upper-cased param name -> Expr


@dataclass(slots=True, eq=False, repr=False)
class ProgramConfig(Node):
    """PROGRAM inst WITH task : Type (args);"""

    name: str
    type_name: str
    task: str | None = None
    args: list = field(default_factory=list)  # Arg
    retain: bool = False
    trailing_comma: Pos | None = None  # as in Call


@dataclass(slots=True, eq=False, repr=False)
class Resource(Node):
    name: str
    on: str | None
    var_blocks: list
    tasks: list
    programs: list


@dataclass(slots=True, eq=False, repr=False)
class Configuration(Node):
    name: str
    var_blocks: list
    resources: list


@dataclass(slots=True, eq=False, repr=False)
class SourceFile(Node):
    """One parsed file. decls: POU, TypeDecl, VarBlock (top-level VAR_GLOBAL,
    as a CODESYS GVL), Configuration."""

    path: str
    decls: list
    # The names a '.' follows (UPPER): 'GVL' of GVL.x, 'Tc2_Standard' of
    # Tc2_Standard.TON, 'motor' of motor.speed. namespaces.py reads a file
    # only when one of them may be a namespace.
    qualified_bases: set = field(default_factory=set)
    # (first line, last line) of each part whose ST softplc wrote from another
    # language (IL, FBD, LD, graphical SFC): a JMP there is the language's own
    # and allowed in every profile (checker_jumps.py).
    lowered: list = field(default_factory=list)
    # Statements outside any POU (a Schneider section pasted as is): wrapped
    # by the parser into a PROGRAM named after the file.


# ---------------------------------------------------------------- statements


@dataclass(slots=True, eq=False, repr=False)
class Stmt(Node):
    pragmas: list = field(default_factory=list, kw_only=True)


@dataclass(slots=True, eq=False, repr=False)
class Assign(Stmt):
    target: Expr
    value: Expr
    op: str = ":="  # ':=', 'S=', 'R=', 'REF='


@dataclass(slots=True, eq=False, repr=False)
class CallStmt(Stmt):
    call: Call


@dataclass(slots=True, eq=False, repr=False)
class If(Stmt):
    branches: list  # (cond Expr, body list)
    else_body: list | None = None


@dataclass(slots=True, eq=False, repr=False)
class CaseRange(Node):
    lo: Expr
    hi: Expr


@dataclass(slots=True, eq=False, repr=False)
class CaseBranch(Node):
    labels: list  # Expr or CaseRange
    body: list


@dataclass(slots=True, eq=False, repr=False)
class Case(Stmt):
    selector: Expr
    branches: list  # CaseBranch
    else_body: list | None = None


@dataclass(slots=True, eq=False, repr=False)
class For(Stmt):
    var: Name
    start: Expr
    end: Expr
    step: Expr | None
    body: list


@dataclass(slots=True, eq=False, repr=False)
class While(Stmt):
    cond: Expr
    body: list


@dataclass(slots=True, eq=False, repr=False)
class Repeat(Stmt):
    body: list
    cond: Expr


@dataclass(slots=True, eq=False, repr=False)
class Exit(Stmt):
    pass


@dataclass(slots=True, eq=False, repr=False)
class Continue(Stmt):
    pass


@dataclass(slots=True, eq=False, repr=False)
class Return(Stmt):
    pass


@dataclass(slots=True, eq=False, repr=False)
class SetReset(Stmt):
    """Schneider ``SET x;`` / ``RESET x;`` (kind 'SET' or 'RESET')."""

    kind: str
    target: Expr


@dataclass(slots=True, eq=False, repr=False)
class Label(Stmt):
    """``name:`` before a statement (CODESYS/TwinCAT ST). jumped_to: set by
    the checker when a JMP names it."""

    name: str
    jumped_to: bool = False


@dataclass(slots=True, eq=False, repr=False)
class Jump(Stmt):
    """``JMP name;``. target: the Label, set by the checker."""

    label: str
    target: Label | None = field(default=None, repr=False)
