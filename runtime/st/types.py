"""ST types and how their values are represented in Python.

Value representation (the contract between checker, code generator, the
runtime library and the JSON encoder):

  BOOL                                  bool
  SINT..LINT, USINT..ULINT, BYTE..LWORD int, wrapped to the type on store
  REAL                                  float, rounded to IEEE-754 binary32 on store
  LREAL                                 float
  TIME                                  int milliseconds, signed 32 bit (CODESYS TIME
                                        resolution; IEC allows negative durations)
  LTIME                                 int nanoseconds, signed 64 bit
  DATE, DT                              int seconds since 1970-01-01 (DATE at midnight)
  TOD                                   int milliseconds since midnight
  LDATE, LDT                            int nanoseconds since 1970-01-01
  LTOD                                  int nanoseconds since midnight
  STRING[n] / WSTRING[n]                str, truncated to n characters on store
  CHAR / WCHAR                           int, the character's code (0..255 / 0..65535)
  enumeration                           int (the enumerator's value)
  subrange                              int, checked on store
  ARRAY                                 list (nested list per dimension), bounds kept here
  STRUCT, FUNCTION_BLOCK                an instance of the generated class
  REF_TO / POINTER TO                   None (NULL) or a reference object
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any


class Type:
    # every subclass provides ``name`` (a field or a property)

    # classification helpers; overridden where true
    is_elementary = False
    is_array = False
    is_struct = False
    is_fb = False
    is_enum = False
    is_ref = False
    is_string = False

    @property
    def is_aggregate(self) -> bool:
        """Values that are Python objects mutated in place (value semantics
        are kept by copying into the target on assignment)."""
        return self.is_array or self.is_struct or self.is_fb

    if TYPE_CHECKING:

        @property
        def name(self) -> str: ...

    def __str__(self) -> str:
        return self.name


# ---------------------------------------------------------------- elementary

# categories
BOOLCAT = "bool"
SIGNED = "signed"
UNSIGNED = "unsigned"
BITS = "bits"
REALCAT = "real"
DURATION = "duration"
DATECAT = "date"
TODCAT = "tod"
DTCAT = "dt"
CHARCAT = "char"  # CHAR, WCHAR: the character's code (IEC 61131-3 ed.3 6.4.2, Table 10)


@dataclass(frozen=True, eq=False)
class ElementaryType(Type):
    name: str
    category: str
    bits: int
    # integer range (ints and bit strings); for time types the raw int range
    lo: int | None = None
    hi: int | None = None
    # unit of the int representation of time/date types, in nanoseconds
    unit_ns: int = 0

    is_elementary = True

    @property
    def is_integer(self) -> bool:
        return self.category in (SIGNED, UNSIGNED)

    @property
    def is_bits(self) -> bool:
        return self.category == BITS

    @property
    def is_intlike(self) -> bool:
        """Stored as a wrapped int: integers and bit strings (not BOOL)."""
        return self.category in (SIGNED, UNSIGNED, BITS)

    @property
    def is_real(self) -> bool:
        return self.category == REALCAT

    @property
    def is_bool(self) -> bool:
        return self.category == BOOLCAT

    @property
    def is_time(self) -> bool:
        return self.category in (DURATION, DATECAT, TODCAT, DTCAT)

    @property
    def is_char(self) -> bool:
        return self.category == CHARCAT


def _signed(name: str, bits: int) -> ElementaryType:
    return ElementaryType(name, SIGNED, bits, -(1 << (bits - 1)), (1 << (bits - 1)) - 1)


def _unsigned(name: str, bits: int, cat: str = UNSIGNED) -> ElementaryType:
    return ElementaryType(name, cat, bits, 0, (1 << bits) - 1)


BOOL = ElementaryType("BOOL", BOOLCAT, 1, 0, 1)
SINT = _signed("SINT", 8)
INT = _signed("INT", 16)
DINT = _signed("DINT", 32)
LINT = _signed("LINT", 64)
USINT = _unsigned("USINT", 8)
UINT = _unsigned("UINT", 16)
UDINT = _unsigned("UDINT", 32)
ULINT = _unsigned("ULINT", 64)
BYTE = _unsigned("BYTE", 8, BITS)
WORD = _unsigned("WORD", 16, BITS)
DWORD = _unsigned("DWORD", 32, BITS)
LWORD = _unsigned("LWORD", 64, BITS)
REAL = ElementaryType("REAL", REALCAT, 32)
LREAL = ElementaryType("LREAL", REALCAT, 64)
TIME = ElementaryType("TIME", DURATION, 32, -(1 << 31), (1 << 31) - 1, unit_ns=1_000_000)
LTIME = ElementaryType("LTIME", DURATION, 64, -(1 << 63), (1 << 63) - 1, unit_ns=1)
DATE = ElementaryType("DATE", DATECAT, 32, 0, (1 << 32) - 1, unit_ns=1_000_000_000)
TOD = ElementaryType("TIME_OF_DAY", TODCAT, 32, 0, (1 << 32) - 1, unit_ns=1_000_000)
DT = ElementaryType("DATE_AND_TIME", DTCAT, 32, 0, (1 << 32) - 1, unit_ns=1_000_000_000)
LDATE = ElementaryType("LDATE", DATECAT, 64, 0, (1 << 64) - 1, unit_ns=1)
LTOD = ElementaryType("LTIME_OF_DAY", TODCAT, 64, 0, (1 << 64) - 1, unit_ns=1)
LDT = ElementaryType("LDATE_AND_TIME", DTCAT, 64, 0, (1 << 64) - 1, unit_ns=1)
CHAR = ElementaryType("CHAR", CHARCAT, 8, 0, 255)
WCHAR = ElementaryType("WCHAR", CHARCAT, 16, 0, 65535)

ELEMENTARY: dict[str, ElementaryType] = {
    t.name: t
    for t in (
        BOOL,
        SINT,
        INT,
        DINT,
        LINT,
        USINT,
        UINT,
        UDINT,
        ULINT,
        BYTE,
        WORD,
        DWORD,
        LWORD,
        REAL,
        LREAL,
        TIME,
        LTIME,
        DATE,
        TOD,
        DT,
        LDATE,
        LTOD,
        LDT,
        CHAR,
        WCHAR,
    )
}
# Short spellings.
ELEMENTARY["TOD"] = TOD
ELEMENTARY["DT"] = DT
ELEMENTARY["LTOD"] = LTOD
ELEMENTARY["LDT"] = LDT
# The names IEC 61131-3 ed.3 added (ed.2 and MatIEC have none of these
# types): plain names in ed.2 code (Profile.ed3_type_names_reserved).
ED3_NAMES = frozenset(("LTIME", "LDATE", "LTIME_OF_DAY", "LTOD", "LDATE_AND_TIME", "LDT", "CHAR", "WCHAR"))


# ---------------------------------------------------------------- strings


@dataclass(frozen=True, eq=False)
class StringType(Type):
    length: int
    wide: bool = False

    is_string = True

    @property
    def name(self) -> str:
        base = "WSTRING" if self.wide else "STRING"
        return f"{base}[{self.length}]"

    def same(self, other: Type) -> bool:
        return isinstance(other, StringType) and other.wide == self.wide


# ---------------------------------------------------------------- derived


@dataclass(eq=False)
class EnumType(Type):
    name: str
    values: dict  # UPPER name -> int, in declaration order
    spelled: dict  # UPPER name -> name as declared
    base: ElementaryType = INT
    default: int | None = None  # TYPE E : (a, b) := b; -- else the first value
    # CODESYS/TwinCAT attributes before its TYPE (st/syntax/pragmas.py)
    qualified_only: bool = False  # its values only as E.a (or E#a)
    strict: bool = False  # no arithmetic, no integer assigned (where the profile allows them)
    to_string: bool = False  # TO_STRING/TO_WSTRING give a value's name, not its number
    is_enum = True

    def name_of(self, value: int) -> str | None:
        for k, v in self.values.items():
            if v == value:
                return self.spelled[k]
        return None


@dataclass(eq=False)
class SubrangeType(Type):
    base: ElementaryType
    lo: int
    hi: int

    @property
    def name(self) -> str:
        return f"{self.base.name}({self.lo}..{self.hi})"


@dataclass(eq=False)
class AliasType(Type):
    """TYPE Speed : REAL := 1.5; END_TYPE -- resolved away by ``resolve``;
    init_value is the type's own initial value plan, if declared."""

    name: str
    target: Type
    init_value: Any = None


@dataclass(eq=False)
class ArrayType(Type):
    dims: list  # [(lo, hi)], or [None] per '*' dimension
    elem: Type
    is_array = True

    @property
    def name(self) -> str:
        rng = ", ".join("*" if d is None else f"{d[0]}..{d[1]}" for d in self.dims)
        return f"ARRAY[{rng}] OF {self.elem.name}"

    @property
    def variable_length(self) -> bool:
        return any(d is None for d in self.dims)


@dataclass(eq=False)
class StructField:
    name: str  # as declared
    type: Type
    init: Any = None  # AST initialiser or None
    pyname: str = ""
    init_value: Any = None  # evaluated by the checker (see Checker.init_value)


@dataclass(eq=False)
class StructType(Type):
    name: str
    fields: dict = field(default_factory=dict)  # UPPER -> StructField (a base's first)
    pyclass: str = ""  # name of the generated class
    base: StructType | None = None  # CODESYS STRUCT EXTENDS: the base's fields come first
    is_struct = True


@dataclass(eq=False)
class RefType(Type):
    target: Type
    pointer: bool = False
    reference: bool = False  # CODESYS REFERENCE TO: dereferenced implicitly
    is_ref = True

    @property
    def name(self) -> str:
        kind = "REFERENCE TO " if self.reference else "POINTER TO " if self.pointer else "REF_TO "
        return kind + self.target.name


@dataclass(eq=False)
class FBType(Type):
    """A FUNCTION_BLOCK (or PROGRAM) type; pou is the checker's POU info."""

    name: str
    pou: Any = None
    is_fb = True


@dataclass(eq=False)
class InterfaceType(Type):
    """An INTERFACE (IEC 61131-3 ed.3 6.6.6): a variable of it designates
    an FB instance that implements it, or none (0, NULL: None in Python).
    methods: UPPER -> POUInfo (signatures), properties: UPPER ->
    PropertyInfo, bases: the InterfaceTypes it EXTENDS (checker_oop.py)."""

    name: str
    node: Any = None
    methods: dict = field(default_factory=dict)
    properties: dict = field(default_factory=dict)
    bases: list = field(default_factory=list)
    library: bool = False


@dataclass(frozen=True, eq=False)
class SchneiderAddrType(Type):
    name: str = "ADR#"


@dataclass(frozen=True, eq=False)
class NullType(Type):
    name: str = "NULL"


ADDR = SchneiderAddrType()
NULL = NullType()

#: CODESYS's BIT (profiles codesys, twincat): a BOOL in every use, but a run of
#: BIT fields of a STRUCT shares bytes, one bit each (st/sizes.py)
BIT = AliasType("BIT", BOOL)


def resolve(t: Type) -> Type:
    """Follow aliases."""
    while isinstance(t, AliasType):
        t = t.target
    return t


def is_reference(t: Type | None) -> bool:
    """Whether t is a CODESYS REFERENCE TO (dereferenced implicitly)."""
    if t is None:
        return False
    r = resolve(t)
    return isinstance(r, RefType) and r.reference


def declared_default(t: Type) -> Any:
    """The initial value plan a derived type declares for itself (the
    nearest alias with one, or an enumeration's default), else None."""
    while isinstance(t, AliasType):
        if t.init_value is not None:
            return t.init_value
        t = t.target
    if isinstance(t, EnumType):
        return t.default
    return None


def base_elementary(t: Type) -> ElementaryType | None:
    """The elementary type a value of t is stored as (enum -> its base,
    subrange -> its base), or None for strings and aggregates."""
    t = resolve(t)
    if isinstance(t, ElementaryType):
        return t
    if isinstance(t, SubrangeType):
        return t.base
    if isinstance(t, EnumType):
        return t.base
    return None


# ---------------------------------------------------------------- generics

INTEGERS = (SINT, INT, DINT, LINT, USINT, UINT, UDINT, ULINT)
BITSTRINGS = (BOOL, BYTE, WORD, DWORD, LWORD)
REALS = (REAL, LREAL)


def is_generic_member(t: Type, generic: str) -> bool:
    """Whether type t belongs to the IEC generic type ``generic``
    (ANY, ANY_DERIVED, ANY_ELEMENTARY, ANY_MAGNITUDE, ANY_NUM, ANY_REAL,
    ANY_INT, ANY_SIGNED, ANY_UNSIGNED, ANY_BIT, ANY_STRING, ANY_DATE,
    ANY_DURATION, ANY_CHARS)."""
    t = resolve(t)
    g = generic.upper()
    if g == "ANY":
        return True
    if isinstance(t, SubrangeType):
        t = t.base
    if g == "ANY_DERIVED":
        return not t.is_elementary and not t.is_string
    if g == "ANY_STRING":
        return t.is_string
    if g == "ANY_CHARS":  # ed.3 Figure 5: ANY_CHARS is ANY_STRING and ANY_CHAR
        return t.is_string or isinstance(t, ElementaryType) and t.category == CHARCAT
    if g == "ANY_ELEMENTARY":
        return t.is_elementary or t.is_string
    if not isinstance(t, ElementaryType):
        return False
    c = t.category
    if g == "ANY_MAGNITUDE":
        return c in (SIGNED, UNSIGNED, REALCAT, DURATION)
    if g == "ANY_NUM":
        return c in (SIGNED, UNSIGNED, REALCAT)
    if g == "ANY_REAL":
        return c == REALCAT
    if g == "ANY_INT":
        return c in (SIGNED, UNSIGNED)
    if g == "ANY_SIGNED":
        return c == SIGNED
    if g == "ANY_UNSIGNED":
        return c == UNSIGNED
    if g == "ANY_BIT":
        return c in (BOOLCAT, BITS)
    if g == "ANY_DATE":
        return c in (DATECAT, TODCAT, DTCAT)
    if g == "ANY_DURATION":
        return c == DURATION
    if g == "ANY_CHAR":
        return c == CHARCAT
    raise ValueError(f"unknown generic type {generic}")


GENERICS = (
    "ANY",
    "ANY_DERIVED",
    "ANY_ELEMENTARY",
    "ANY_MAGNITUDE",
    "ANY_NUM",
    "ANY_REAL",
    "ANY_INT",
    "ANY_SIGNED",
    "ANY_UNSIGNED",
    "ANY_BIT",
    "ANY_STRING",
    "ANY_DATE",
    "ANY_DURATION",
    "ANY_CHARS",
    "ANY_CHAR",
)


def int_fits(t: ElementaryType, value: int) -> bool:
    """Whether value is one of integer type t's values."""
    return t.lo is not None and t.hi is not None and t.lo <= value <= t.hi
