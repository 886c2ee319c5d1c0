"""What the checker knows about declared things, shared with the code
generator: variables, POUs and resolved calls. Python names are derived here
from validated identifiers only (``pyname``), never from raw source text."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

from .. import types as T
from ..types import FBType, Type

_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


def pyname(prefix: str, st_name: str) -> str:
    """A Python identifier for an ST name: a fixed prefix plus the lower-cased
    name (ST names are case-insensitive). Refuses anything that is not a plain
    identifier, so no source text can reach generated code unchecked."""
    if not _IDENT.match(st_name):
        raise ValueError(f"not an identifier: {st_name!r}")
    return f"{prefix}{st_name.lower()}"


@dataclass(eq=False)
class VarSymbol:
    name: str
    section: str  # VAR, VAR_INPUT, VAR_OUTPUT, VAR_IN_OUT, VAR_TEMP, VAR_GLOBAL, VAR_EXTERNAL, VAR_STAT, RETURN
    type: Type
    pos: Any
    pyname: str
    owner: POUInfo | None = None  # None for a global
    constant: bool = False
    retain: bool = False
    persistent: bool = False
    location: Any = None  # ast.LocatedAddress
    placeholder: Any = None  # AT %QX*: the incomplete address (VAR_CONFIG completes it per instance)
    init: Any = None  # AST initialiser
    init_value: Any = None  # evaluated initial value plan (see checker.init_value)
    const_value: Any = None  # compile-time value of a CONSTANT
    boxed: bool = False  # FUNCTION local whose reference is taken: kept in a CellRef
    address_taken: bool = False  # REF/ADR, VAR_IN_OUT or => reaches it: others may read it
    hidden: bool = False  # {attribute 'hide'}: left out of listings (namespaces.py)
    generic: str | None = None  # ANY_NUM ... of a FUNCTION's input (st/check/checker_generics.py)
    fb_init: Any = None  # CODESYS FB_init inputs set in the declaration (st/check/checker_fbinit.py)

    @property
    def is_global(self) -> bool:
        return self.owner is None


@dataclass(eq=False)
class POUInfo:
    name: str
    kind: str  # PROGRAM, FUNCTION, FUNCTION_BLOCK
    node: Any  # ast.POU
    pyname: str
    vars: dict = field(default_factory=dict)  # UPPER -> VarSymbol, declaration order
    return_type: Type | None = None
    result: VarSymbol | None = None  # the FUNCTION's result variable
    fbtype: FBType | None = None
    library: bool = False  # from fblocks (not the user's files)
    native: Any = None  # Python implementation of an external POU
    actions: dict = field(default_factory=dict)  # UPPER -> ActionInfo (PROGRAM, FUNCTION_BLOCK)
    sfc: Any = None  # checker_sfc.SfcInfo of an SFC body
    # Object-oriented ST (checker_oop.py). A METHOD or PROPERTY accessor is a
    # POUInfo of kind FUNCTION (its variables live in the call, as a
    # FUNCTION's) whose fb is the FUNCTION_BLOCK it belongs to.
    fb: POUInfo | None = None
    base: POUInfo | None = None  # the FUNCTION_BLOCK this one EXTENDS
    methods: dict = field(default_factory=dict)  # UPPER -> POUInfo, declared here
    properties: dict = field(default_factory=dict)  # UPPER -> PropertyInfo, declared here
    interfaces: list = field(default_factory=list)  # InterfaceType, IMPLEMENTS here
    modifiers: tuple = ()  # ABSTRACT, FINAL, PUBLIC, PRIVATE, PROTECTED, INTERNAL

    def params(self, *sections: str) -> list:
        return [v for v in self.vars.values() if v.section in sections]


@dataclass(eq=False)
class ActionInfo:
    """An ACTION of a PROGRAM or FUNCTION_BLOCK: a method of its class."""

    name: str
    node: Any  # ast.Action
    pou: POUInfo
    pyname: str


@dataclass(eq=False)
class PropertyInfo:
    """A PROPERTY (CODESYS, TwinCAT): reading it calls getter, assigning it
    calls setter (POUInfos of kind FUNCTION; None where it has none)."""

    name: str
    type: Type
    pos: Any
    owner: Any  # the POUInfo of its FUNCTION_BLOCK, or the InterfaceType
    getter: POUInfo | None = None
    setter: POUInfo | None = None
    modifiers: tuple = ()


@dataclass(eq=False)
class CallInfo:
    """A checked call. kind: 'function' (user FUNCTION), 'fb' (instance
    call), 'action' (an ACTION of pou: func is its ActionInfo, instance the
    FB instance or None inside the POU), 'method' (pou: the METHOD;
    instance: the FB or interface expression, None for THIS; func: 'super'
    for SUPER^.M(), 'body' for SUPER^()), 'std' (standard library function), 'builtin' (TIME, LTIME, REF,
    ADR, SIZEOF), 'native' (a native function, st/native.py), 'operator'
    (the function form of an operator, ADD(a, b, c): args is [the operator
    expression it stands for, (a + b) + c])."""

    kind: str
    pou: POUInfo | None = None
    func: Any = None  # StdFunc for 'std'; builtin name for 'builtin'; NativeFunction for 'native'
    instance: Any = None  # the instance expression for 'fb'
    inputs: list = field(default_factory=list)  # (VarSymbol, Expr) in call order
    inouts: list = field(default_factory=list)  # (VarSymbol, Expr lvalue)
    outputs: list = field(default_factory=list)  # (VarSymbol, Expr lvalue, negated)
    args: list = field(default_factory=list)  # std/builtin: argument Exprs in parameter order
    rtypes: tuple = ()  # std typed: (result type, arg types...)
    param_types: list = field(default_factory=list)  # std: the type each arg is converted to
    en: Any = None  # the EN argument (IEC 61131-3 ed.3 6.6.1.6): the call runs only when it is TRUE
    eno: Any = None  # std/operator: the ENO => target (a POU's own ENO is one of its outputs)


def copied_in_out(sym: VarSymbol, profile: Any) -> bool:
    """Whether sym is a FUNCTION_BLOCK's VAR_IN_OUT that the profile keeps
    as the instance's own copy (Profile.fb_in_out_copied, MatIEC): a value
    of its type, not a reference to the caller's variable. An ARRAY[*], a
    REFERENCE TO and an FB instance stay references."""
    if not profile.fb_in_out_copied or sym.section != "VAR_IN_OUT":
        return False
    if sym.owner is None or sym.owner.kind != "FUNCTION_BLOCK" or T.is_reference(sym.type):
        return False
    t = T.resolve(sym.type)
    return not (t.is_fb or (isinstance(t, T.ArrayType) and t.variable_length))
