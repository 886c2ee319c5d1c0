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

Every native function is a statement-like call with positional arguments.
The service is called as ``service.request(NAME, *args, *signed)``, where
``signed`` holds, for each word-table argument in order, whether its
elements are signed (INT) or not (WORD, UINT): the service stores words into
the tables and must keep their type's representation.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol

# Parameter kinds: what the checker accepts for an argument.
ANY_INT = "ANY_INT"  # an integer of any width, signed or not
STRING = "STRING"  # a STRING of any length
ADDRESS = "ADDRESS"  # a Schneider ADR#r.m.c address
WORDS = "WORDS"  # a one-dimensional table of 16-bit words: ARRAY OF WORD/INT/UINT, %MW100:4

_EXPECTED = {
    ANY_INT: "an integer",
    STRING: "a STRING",
    ADDRESS: "an ADR#... address",
    WORDS: "a word table such as %MW3250:4 or an ARRAY OF WORD",
}


class Service(Protocol):
    def request(self, name: str, *args: Any) -> Any: ...


@dataclass(frozen=True)
class Param:
    """One positional parameter. what: how a message names it ('the node';
    '' for 'argument n' alone); expect: what a wrong argument is told it
    must be (default: from the kind); min_words: a word table's least size."""

    name: str
    kind: str
    what: str = ""
    expect: str = ""
    min_words: int = 0

    def __post_init__(self) -> None:
        if self.kind not in _EXPECTED:
            raise ValueError(f"{self.name}: unknown parameter kind {self.kind!r}")

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

    def __post_init__(self) -> None:
        if self.name != self.name.upper():
            raise ValueError(f"native function names are upper case: {self.name!r}")
