"""Native functions: ST functions implemented in Python by a service of the
runtime (a bus driver's SDO or Modbus transfers), declared once.

A declaration names the function, its parameters, its result and the
service that executes it. The checker types a call from it, the code
generator emits the call from it, and at run time the call goes to the
service a driver bound under that name (runtime/program ExecContext), or to
the declaration's fallback when no driver offers it (a program that calls
READ_VAR runs without a bus: the exchange ends with an error report, as on a
PLC without the network module).

    READ_VAR = NativeFunction(
        "READ_VAR", (Param("address", ADDRESS), ...), service="sdo",
        fallback=NoBus(), usage="READ_VAR(ADR#0.1.SYS, 'SDO', ...)")

A native function is called with positional arguments, or with every
argument named (``AssertEquals(Expected := a, Actual := b, Message := 'm')``,
the parameters' names, any case); a parameter with a default may then be
left out. The service is called as ``service.request(NAME, *args, *signed)``, where
``signed`` holds, for each word-table argument in order, whether its
elements are signed (INT) or not (WORD, UINT): the service stores words into
the tables and must keep their type's representation. A declaration with
``site=True`` gets one more argument last: a CallSite, where the call is in
the ST source (file:line:column, from the compiler) and the types of its
arguments, so that the service can name the call and write the values as ST
literals (an assertion of a test, runtime/testing).

Parameters of the generic kinds (BOOL, ANY_ELEMENTARY, ANY_REAL) may share a
type variable (``same="T"``): their arguments are brought to one common type,
as the standard functions' ``T:ANY_NUM`` are, so that ASSERT_EQUAL(5, x)
compares 5 as x's type. Parameters of kind ANY sharing one keep their own
types (AssertEquals(ANY) tells an INT from a UINT); only an untyped literal
takes the type of the others (AssertEquals(5, myUint) passes 5 as a UINT).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol

# Parameter kinds: what the checker accepts for an argument.
ANY_INT = "ANY_INT"  # an integer of any width, signed or not
STRING = "STRING"  # a STRING of any length
ADDRESS = "ADDRESS"  # a Schneider ADR#r.m.c address
WORDS = "WORDS"  # a one-dimensional table of 16-bit words: ARRAY OF WORD/INT/UINT, %MW100:4
BOOL = "BOOL"  # a BOOL
ANY_ELEMENTARY = "ANY_ELEMENTARY"  # any elementary value: number, bit string, BOOL, time, STRING, enumeration
ANY_REAL = "ANY_REAL"  # a REAL or LREAL (an integer literal too)
ANY = "ANY"  # a value of any type: elementary, STRING, ARRAY (ARRAY[*] too), STRUCT; passed as stored

GENERIC_KINDS = (BOOL, ANY_ELEMENTARY, ANY_REAL, ANY)

_EXPECTED = {
    ANY_INT: "an integer",
    STRING: "a STRING",
    ADDRESS: "an ADR#... address",
    WORDS: "a word table such as %MW3250:4 or an ARRAY OF WORD",
    BOOL: "a BOOL",
    ANY_ELEMENTARY: "an elementary value (a number, BOOL, STRING, time or enumeration)",
    ANY_REAL: "a REAL or LREAL",
    ANY: "a value",
}


class Service(Protocol):
    def request(self, name: str, *args: Any) -> Any: ...


@dataclass(frozen=True)
class Param:
    """One positional parameter. what: how a message names it ('the node';
    '' for 'argument n' alone); expect: what a wrong argument is told it
    must be (default: from the kind); min_words: a word table's least size;
    same: a type variable shared with other parameters of a generic kind;
    default: the value of a STRING or BOOL parameter a call by name leaves
    out (None: it must be given)."""

    name: str
    kind: str
    what: str = ""
    expect: str = ""
    min_words: int = 0
    same: str = ""
    default: Any = None

    def __post_init__(self) -> None:
        if self.kind not in _EXPECTED:
            raise ValueError(f"{self.name}: unknown parameter kind {self.kind!r}")
        if self.same and self.kind not in GENERIC_KINDS:
            raise ValueError(f"{self.name}: only {', '.join(GENERIC_KINDS)} parameters share a type")
        if self.default is not None and not (
            (self.kind == STRING and isinstance(self.default, str))
            or (self.kind == BOOL and isinstance(self.default, bool))
        ):
            raise ValueError(f"{self.name}: a default is a str for STRING, a bool for BOOL")

    @property
    def expected(self) -> str:
        return self.expect or _EXPECTED[self.kind]

    def label(self, position: int) -> str:
        """'the node (argument 4)' or 'argument 1'."""
        return f"{self.what} (argument {position})" if self.what else f"argument {position}"


@dataclass(frozen=True, eq=False)
class NativeFunction:
    name: str  # the ST name, upper case
    params: tuple[Param, ...]
    service: str  # the key a driver binds its implementation under
    fallback: Service  # the implementation when no driver offers the service
    usage: str  # the call as written, for the hint of a wrong call
    result: str = "BOOL"  # an elementary type name
    site: bool = False  # the service gets a CallSite after the arguments

    def __post_init__(self) -> None:
        if self.name != self.name.upper():
            raise ValueError(f"native function names are upper case: {self.name!r}")


@dataclass(frozen=True)
class CallSite:
    """Where a native call is in the ST source and the types of its
    arguments (after their common type is found): what a ``site=True``
    service gets last. types are st.types.Type objects."""

    file: str
    line: int
    col: int
    types: tuple = ()

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}"


#: The service of the runtime's own clock, which every ExecContext serves
#: (runtime/program/context.py): ``request(name)`` answers the date of the
#: task clock as milliseconds since 1970-01-01 00:00 UTC. The date of the
#: wall clock when the engine runs in real time; in virtual time (a test,
#: ``exec``, a simulation) the epoch plus the virtual clock, so that a run
#: is the same every time.
CLOCK = "clock"


class NoClock:
    """The clock service's fallback (a context always serves it): the epoch."""

    def request(self, name: str, *args: Any) -> int:
        return 0
