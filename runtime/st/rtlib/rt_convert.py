"""Runtime library, conversions: the <src>_TO_<dst> functions, as closures
built once per pair of types (``make_converter``), and time/date units."""

from __future__ import annotations

from collections.abc import Callable

from ..types import (
    BITS,
    BOOLCAT,
    CHARCAT,
    DATECAT,
    DURATION,
    LREAL,
    REALCAT,
    SIGNED,
    TODCAT,
    UNSIGNED,
    ElementaryType,
    EnumType,
    StringType,
    Type,
    base_elementary,
    resolve,
)
from .rt_numeric import f32, idiv, int_to_f32, round_half_away
from .rt_text import (
    bool_to_string,
    parse_bool,
    parse_int,
    parse_real,
    parse_temporal,
    real32_to_string,
    real64_to_string,
    temporal_formatter,
)
from .rt_timedate import DAY_NS
from .rt_wrap import identity, int_wrapper, time_wrapper

# ---------------------------------------------------------------- conversion


def _time_from_ns_unit(src_unit: int, d: ElementaryType) -> Callable[[int], int]:
    """Convert a time/date raw value in units of src_unit ns to type d by
    its physical meaning: durations keep their length (truncated toward zero
    to d's resolution: LTIME_TO_TIME drops sub-ms), DATE takes the day
    (floor, DT_TO_DATE), TOD the time of day (DT_TO_TOD), DT the instant
    (floor to d's resolution). A duration meets a date as time since
    1970-01-01 (CODESYS: TIME_TO_DT(T#5d4h3m2s1ms) = DT#1970-01-06-04:03:02)
    or since midnight; TOD_TO_DT gives that time on 1970-01-01."""
    du = d.unit_ns
    w = time_wrapper(d)
    c = d.category
    if c == DURATION:
        if src_unit == du:
            return w
        if src_unit > du:
            f = src_unit // du

            def scale_up(v: int) -> int:
                return w(v * f)

            return scale_up
        f = du // src_unit

        def scale_down(v: int) -> int:
            return w(idiv(v, f))  # toward zero

        return scale_down
    if c == DATECAT:
        per_day = DAY_NS // du

        def to_date(v: int) -> int:
            return w((v * src_unit // DAY_NS) * per_day)

        return to_date
    if c == TODCAT:

        def to_tod(v: int) -> int:
            return (v * src_unit % DAY_NS) // du

        return to_tod

    def to_dt(v: int) -> int:
        return w(v * src_unit // du)

    return to_dt


def _narrow_string(v: str) -> str:
    """WSTRING -> STRING: STRING holds 8-bit characters (Latin-1 here);
    others become '?'."""
    try:
        v.encode("latin-1")
        return v
    except UnicodeEncodeError:
        return v.encode("latin-1", "replace").decode("latin-1")


def _enum_namer(t: EnumType) -> Callable:
    """TO_STRING of an enumeration with {attribute 'to_string'}: the name
    of the value (the first declared, if several share it); a value
    without a name as its number."""
    names: dict = {}
    for key, value in t.values.items():
        names.setdefault(value, t.spelled[key])

    def name(v):
        return names.get(v, str(v))

    return name


def _classify(t: Type) -> tuple:
    r = resolve(t)
    if isinstance(r, StringType):
        return "str", r
    e = base_elementary(r)
    if e is None:
        raise TypeError(f"no conversion for type {t.name}")
    c = e.category
    if c == BOOLCAT:
        return "bool", e
    if c in (SIGNED, UNSIGNED, BITS):
        return "int", e
    if c == REALCAT:
        return "real", e
    return "time", e


def _is_char(t: Type) -> bool:
    e = base_elementary(t)
    return e is not None and e.category == CHARCAT


def char_converter(src: Type, dst: Type) -> Callable:
    """Conversions of CHAR and WCHAR (IEC 61131-3 ed.3 Table 23, 27): with
    an integer or bit string by the character's code (BYTE_TO_CHAR(65) is
    CHAR#'A', wrapped to 8/16 bits), with a string as its first character
    (CHAR_TO_STRING gives a one-character string, STRING_TO_CHAR('') is
    CHAR#'$00'). A code the destination cannot hold (WCHAR_TO_CHAR of
    a character beyond Latin-1) becomes '?', as WSTRING_TO_STRING does."""
    s, d = resolve(src), resolve(dst)
    if isinstance(d, StringType):
        limit = 0xFFFF if d.wide else 0xFF

        def char_to_string(v: int) -> str:
            return chr(v) if v <= limit else "?"

        return char_to_string
    de = base_elementary(d)
    if de is None:
        raise TypeError(f"no conversion to {dst.name}")
    if de.category == CHARCAT:
        top = de.hi if de.hi is not None else 0xFF
        if isinstance(s, StringType):

            def string_to_char(v: str) -> int:
                code = ord(v[0]) if v else 0
                return code if code <= top else 63

            return string_to_char
        se = base_elementary(s)
        if se is not None and se.category == CHARCAT:

            def char_to_char(v: int) -> int:
                return v if v <= top else 63

            return char_to_char
        if se is not None and se.category in (SIGNED, UNSIGNED, BITS):
            return int_wrapper(de)
    elif de.category in (SIGNED, UNSIGNED, BITS):
        return int_wrapper(de)
    raise TypeError(f"no conversion from {src.name} to {dst.name}")


def converts_char(src: Type, dst: Type) -> bool:
    """Whether <src>_TO_<dst> exists, where either is CHAR or WCHAR."""
    try:
        char_converter(src, dst)
    except TypeError:
        return False
    return True


def make_converter(src: Type, dst: Type) -> Callable:
    """A closure converting a value of type src to type dst, with IEC /
    CODESYS semantics (the <src>_TO_<dst> function). Bind it once, call it
    often. Enumerations and subranges convert through their base type.

      integer -> integer/bit string   wraps (INT_TO_SINT(300) = 44,
                                      DINT_TO_UINT(-1) = 65535)
      REAL -> integer/time            rounds half away from zero, then wraps;
                                      NaN and inf give 0
      integer -> REAL                 rounds to binary32
      any -> BOOL                     value <> 0; BOOL -> number 0/1
      time/date <-> number            the raw value: TIME ms, LTIME ns, DATE
                                      and DT s, TOD ms, L-dates ns
                                      (TIME_TO_DINT(T#1s) = 1000)
      time/date -> time/date          by meaning (see _time_from_ns_unit):
                                      TIME_TO_LTIME * 1e6, DT_TO_DATE,
                                      DT_TO_TOD, DATE_TO_DT
      number -> STRING                decimal ('42'); reals per
                                      real_to_string; BOOL 'TRUE'/'FALSE';
                                      time/date as literal ('T#1s500ms')
      STRING -> x                     parses the literal forms of x (blanks
                                      around allowed, 'INT#5', '16#FF',
                                      'T#1s'); invalid text gives 0 / FALSE
      WSTRING -> STRING               characters beyond Latin-1 -> '?'
    """
    if _is_char(src) or _is_char(dst):
        return char_converter(src, dst)
    named = resolve(src)
    if isinstance(named, EnumType) and named.to_string and isinstance(resolve(dst), StringType):
        return _enum_namer(named)
    sk, s = _classify(src)
    dk, d = _classify(dst)
    if s is d and sk != "str":
        return identity

    if dk == "str":
        if sk == "str":
            return _narrow_string if (s.wide and not d.wide) else identity
        if sk == "bool":
            return bool_to_string
        if sk == "int":
            return str
        if sk == "real":
            return real64_to_string if s is LREAL else real32_to_string
        return temporal_formatter(s)

    if dk == "bool":
        if sk == "str":

            def str_to_bool(v: str) -> bool:
                return parse_bool(v) or False

            return str_to_bool
        return bool  # <> 0; NaN is <> 0 as well

    if dk == "real":
        if sk == "str":
            if d is LREAL:

                def str_to_lreal(v: str) -> float:
                    x = parse_real(v)
                    return 0.0 if x is None else x

                return str_to_lreal

            def str_to_real(v: str) -> float:
                x = parse_real(v)
                return 0.0 if x is None else f32(x)

            return str_to_real
        if d is LREAL:
            return float
        return f32 if sk == "real" else int_to_f32

    # integer, bit string or time/date destination
    w = int_wrapper(d) if dk == "int" else time_wrapper(d)
    if sk in ("int", "bool"):  # the wrappers turn a bool into 0/1
        return w
    if sk == "real":

        def real_to_int(v: float) -> int:
            return w(round_half_away(v))

        return real_to_int
    if sk == "time":
        if dk == "int":
            return w
        return _time_from_ns_unit(s.unit_ns, d)
    # from text
    if dk == "int":

        def str_to_int(v: str) -> int:
            x = parse_int(v)
            return 0 if x is None else w(x)

        return str_to_int
    from_ns_ = _time_from_ns_unit(1, d)
    cat = d.category

    def str_to_time(v: str) -> int:
        ns = parse_temporal(v, cat)
        return 0 if ns is None else from_ns_(ns)

    return str_to_time


_CONVERTERS: dict = {}


def convert(value, src: Type, dst: Type):
    """Convert one value from src to dst (see make_converter); converters
    are cached per (src, dst) pair."""
    key = (src, dst)
    f = _CONVERTERS.get(key)
    if f is None:
        f = _CONVERTERS[key] = make_converter(src, dst)
    return f(value)


def from_ns(t: ElementaryType, ns: int) -> int:
    """The raw value of time/date type t for a parser literal in ns
    (T#1.5ms -> TIME 1: truncated toward zero to t's resolution)."""
    return _time_from_ns_unit(1, t)(ns)


def to_ns(t: ElementaryType, raw: int) -> int:
    """Nanoseconds of a raw time/date value of type t."""
    return raw * t.unit_ns
