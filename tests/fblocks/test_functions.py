"""The standard function table: every entry is well formed and callable with
values of its parameter types, and the functions give the results the IEC
standard and the CODESYS documentation give."""

import math

import pytest

from softplc.fblocks.iec.functions import STANDARD_FUNCTIONS as F
from softplc.fblocks.iec.functions import StdFunc, parse_typespec
from softplc.runtime.st import types as T
from softplc.runtime.st.faults import RangeFault
from softplc.runtime.st.rtlib import rtlib

STRING = T.StringType(80)
WSTRING = T.StringType(80, wide=True)
DAY = 19724 * 86_400  # D#2024-01-02


def concrete(name: str) -> T.Type:
    if name == "STRING":
        return STRING
    if name == "WSTRING":
        return WSTRING
    return T.ELEMENTARY[name]


def call(name, *args, types=None):
    """Call a table entry like generated code does; types: the resolved
    (result, arg1, ...) types for a typed entry."""
    f = F[name]
    return f.impl(types, *args) if f.typed else f.impl(*args)


# ---------------------------------------------------------------- table-driven

# One concrete member per generic family, three different choices so that
# every entry runs with integers, reals, bit strings, strings and times.
CHOICES = [
    {
        "ANY": T.INT,
        "ANY_ELEMENTARY": T.INT,
        "ANY_MAGNITUDE": T.DINT,
        "ANY_NUM": T.INT,
        "ANY_REAL": T.REAL,
        "ANY_INT": T.INT,
        "ANY_SIGNED": T.SINT,
        "ANY_UNSIGNED": T.UINT,
        "ANY_BIT": T.BYTE,
        "ANY_STRING": STRING,
        "ANY_CHARS": STRING,
        "ANY_DATE": T.DATE,
        "ANY_DURATION": T.TIME,
    },
    {
        "ANY": T.LREAL,
        "ANY_ELEMENTARY": STRING,
        "ANY_MAGNITUDE": T.TIME,
        "ANY_NUM": T.LREAL,
        "ANY_REAL": T.LREAL,
        "ANY_INT": T.ULINT,
        "ANY_SIGNED": T.LINT,
        "ANY_UNSIGNED": T.USINT,
        "ANY_BIT": T.BOOL,
        "ANY_STRING": WSTRING,
        "ANY_CHARS": WSTRING,
        "ANY_DATE": T.DT,
        "ANY_DURATION": T.LTIME,
    },
    {
        "ANY": T.DT,
        "ANY_ELEMENTARY": T.TOD,
        "ANY_MAGNITUDE": T.LREAL,
        "ANY_NUM": T.SINT,
        "ANY_REAL": T.REAL,
        "ANY_INT": T.DINT,
        "ANY_SIGNED": T.DINT,
        "ANY_UNSIGNED": T.ULINT,
        "ANY_BIT": T.LWORD,
        "ANY_STRING": STRING,
        "ANY_CHARS": STRING,
        "ANY_DATE": T.LDT,
        "ANY_DURATION": T.TIME,
    },
]


def sample(t: T.Type, extreme: bool):
    """A typical value of type t, or an extreme one (range ends, NaN, '')."""
    if isinstance(t, T.StringType):
        return "" if extreme else ("SÜSI" if t.wide else "SUSI")
    c = t.category
    if c == T.BOOLCAT:
        return not extreme
    if c == T.REALCAT:
        return (math.nan if t is T.REAL else -math.inf) if extreme else -2.5
    if c in (T.SIGNED, T.DURATION):
        return t.lo if extreme else -7
    if c in (T.UNSIGNED, T.BITS, T.CHARCAT):
        return t.hi if extreme else 0x21
    day = 86_400 * 10**9 // t.unit_ns
    if c == T.TODCAT:
        return day - 1 if extreme else 45_015_500 * 10**6 // t.unit_ns
    if c == T.DATECAT:
        return t.hi - t.hi % day if extreme else DAY * 10**9 // t.unit_ns
    return t.hi if extreme else (DAY + 45_015) * 10**9 // t.unit_ns


def python_kind(t: T.Type):
    if isinstance(t, T.StringType):
        return str
    if t.category == T.BOOLCAT:
        return bool
    if t.category == T.REALCAT:
        return float
    return int


def bind(f: StdFunc, choice: dict):
    """The argument types (the last one repeated for an extensible entry)
    and the result type, as the checker would resolve them."""
    bindings: dict = {}

    def resolve(spec):
        var, name = parse_typespec(spec)
        if var is not None:
            return bindings.setdefault(var, choice[name])
        return choice[name] if name in T.GENERICS else concrete(name)

    specs = [p[1] for p in f.params]
    if f.extensible:
        specs.append(specs[-1])
    args = [resolve(s) for s in specs]
    ret = bindings[f.ret] if f.ret in bindings else concrete(f.ret)
    return ret, args


MAY_DIVIDE_BY_ZERO = {"DIV", "MOD", "DIV_TIME", "DIV_LTIME"}
# a sample year, month ... that is no date or time of day is a range fault
MAY_BE_NO_DATE = {"CONCAT_DATE", "CONCAT_LDATE", "CONCAT_TOD", "CONCAT_LTOD", "CONCAT_DT", "CONCAT_LDT"}


def test_table_is_well_formed():
    for name, f in F.items():
        assert name == f.name == name.upper()
        assert f.params and all(isinstance(p, tuple) and len(p) == 2 for p in f.params)
        for _, spec in f.params:
            var, fam = parse_typespec(spec)
            assert fam in T.GENERICS or concrete(fam), (name, spec)
        # the result is a concrete type or a type variable of a parameter
        assert f.ret in {parse_typespec(s)[0] for _, s in f.params} or concrete(f.ret), name
        assert callable(f.impl)


def run_entry(name: str, choice: dict, extreme: bool) -> None:
    f = F[name]
    ret, arg_types = bind(f, choice)
    args = [sample(t, extreme) for t in arg_types]
    try:
        result = f.impl((ret, *arg_types), *args) if f.typed else f.impl(*args)
    except ZeroDivisionError:
        assert name in MAY_DIVIDE_BY_ZERO and extreme, (name, args)
        return
    except RangeFault:
        assert name in MAY_BE_NO_DATE, (name, args)
        return
    assert isinstance(result, python_kind(ret)), (name, args, result)
    if "_TO_" in name or name.startswith(("TO_", "TRUNC")):  # conversions wrap
        e = T.base_elementary(ret)
        if e is not None and e.lo is not None and e.category != T.TODCAT:
            assert e.lo <= result <= e.hi, (name, args, result)


@pytest.mark.parametrize("extreme", [False, True], ids=["typical", "extreme"])
@pytest.mark.parametrize("choice", range(len(CHOICES)))
def test_every_function_runs_on_its_types(choice, extreme):
    """Each entry, called with values of its parameter types (generic
    families bound per CHOICES), returns a value of its result type."""
    failures = []
    for name in sorted(F):
        try:
            run_entry(name, CHOICES[choice], extreme)
        except Exception as exc:  # collect all, report together
            failures.append(f"{name}: {type(exc).__name__}: {exc}")
    assert not failures, "\n".join(failures)


def test_all_conversion_pairs_exist():
    names = list(T.ELEMENTARY) + ["STRING", "WSTRING"]
    for s in names:
        for d in names:
            if concrete(s) is concrete(d):
                continue
            if "CHAR" in (s, d) or "WCHAR" in (s, d):  # with integers, bit strings, strings (ed.3 Table 23, 27)
                assert (f"{s}_TO_{d}" in F) == rtlib.converts_char(concrete(s), concrete(d)), (s, d)
            else:
                assert f"{s}_TO_{d}" in F
        assert (f"TO_{s}" in F) == (s not in ("CHAR", "WCHAR"))
    assert "INT_TO_INT" not in F
    assert "TOD_TO_TIME_OF_DAY" not in F  # one type, two spellings


# ---------------------------------------------------------------- conversions


def test_conversion_entries():
    assert call("INT_TO_SINT", 300) == 44
    assert call("DINT_TO_UINT", -1) == 65535
    assert call("REAL_TO_INT", 1.5) == 2
    assert call("REAL_TO_INT", -1.5) == -2
    assert call("LREAL_TO_REAL", 0.1) == 0.10000000149011612
    assert call("BOOL_TO_STRING", True) == "TRUE"
    assert call("TIME_TO_STRING", 1500) == "T#1s500ms"
    assert call("STRING_TO_INT", "  42 ") == 42
    assert call("STRING_TO_WORD", "abc34") == 0
    assert call("TIME_TO_LTIME", 1500) == 1_500_000_000
    assert call("DT_TO_TOD", DAY + 45_015) == 45_015_000
    assert call("DATE_AND_TIME_TO_TIME_OF_DAY", DAY + 45_015) == 45_015_000
    assert call("DT_TO_DATE", DAY + 45_015) == DAY
    assert call("DATE_TO_DT", DAY) == DAY
    assert call("TIME_TO_DINT", 1000) == 1000
    assert F["TOD_TO_TIME"].params == (("IN", "TIME_OF_DAY"),)
    assert F["INT_TO_TOD"].ret == "TIME_OF_DAY"


def test_generic_to():
    assert call("TO_INT", 2.5, types=(T.INT, T.REAL)) == 3
    assert call("TO_SINT", 300, types=(T.SINT, T.INT)) == 44
    assert call("TO_STRING", 1500, types=(STRING, T.TIME)) == "T#1s500ms"
    assert call("TO_LREAL", "1.25", types=(T.LREAL, STRING)) == 1.25
    assert call("TO_TOD", DAY + 45_015, types=(T.TOD, T.DT)) == 45_015_000
    assert F["TO_INT"].typed and F["TO_INT"].params == (("IN", "ANY_ELEMENTARY"),)


def test_trunc():
    assert call("TRUNC", -2.7) == -2
    assert call("TRUNC", 2.7) == 2
    assert call("TRUNC", math.nan) == 0
    assert call("TRUNC", 3e9) == 3_000_000_000 - 2**32  # DINT wraps
    assert call("TRUNC_INT", 40000.5) == 40000 - 65536
    assert call("LREAL_TRUNC_SINT", -1.9) == -1
    assert F["TRUNC"].ret == "DINT"


def test_bcd():
    assert call("WORD_BCD_TO_UINT", 0x1234) == 1234
    assert call("UINT_TO_BCD_WORD", 1234) == 0x1234
    assert call("BYTE_BCD_TO_USINT", 0x1A) == 255  # invalid: -1 wrapped
    assert call("BYTE_BCD_TO_SINT", 0x1A) == -1
    assert call("USINT_TO_BCD_BYTE", 100) == 0xFF
    assert call("BCD_TO_INT", 0x27, types=(T.INT, T.BYTE)) == 27  # CODESYS
    assert call("INT_TO_BCD", 81) == 0x81  # CODESYS
    assert call("TO_BCD_WORD", 9999) == 0x9999
    assert call("BCD_TO_UDINT", 0x12345678, types=(T.UDINT, T.DWORD)) == 12345678


# ---------------------------------------------------------------- numeric and arithmetic


def test_numeric():
    assert call("ABS", -5) == 5
    assert call("ABS", -32768) == 32768  # wraps on store into INT
    assert call("ABS", -2.5) == 2.5
    assert call("SQRT", 16.0) == 4.0
    assert math.isnan(call("SQRT", -1.0))
    assert call("LN", 0.0) == -math.inf
    assert call("LOG", 100.0) == 2.0
    assert call("EXP", 0.0) == 1.0
    assert call("EXPT", 2.0, 7) == 128.0
    assert call("SIN", 0.0) == 0.0
    assert call("COS", 0.0) == 1.0
    assert call("ATAN2", 1.0, 1.0) == pytest.approx(math.pi / 4)
    assert math.isnan(call("ASIN", 2.0))


def test_arithmetic_typed():
    ii = (T.INT, T.INT, T.INT)
    rr = (T.REAL, T.REAL, T.REAL)
    assert call("ADD", 1, 2, 3, types=(T.INT,) * 4) == 6
    assert call("ADD", 1000, 500, types=(T.TIME,) * 3) == 1500
    assert call("MUL", 2, 3, 4, types=(T.INT,) * 4) == 24
    assert call("SUB", 3, 5, types=ii) == -2
    assert call("DIV", -7, 2, types=ii) == -3
    assert call("DIV", 7, -2, types=ii) == -3
    assert call("DIV", -7.0, 2.0, types=rr) == -3.5
    assert call("DIV", 1.0, 0.0, types=rr) == math.inf
    assert call("MOD", -7, 2, types=ii) == -1
    assert call("MOD", 7, -2, types=ii) == 1
    with pytest.raises(ZeroDivisionError):
        call("DIV", 1, 0, types=ii)
    with pytest.raises(ZeroDivisionError):
        call("MOD", 1, 0, types=ii)
    assert call("MOVE", 42, types=(T.INT, T.INT)) == 42
    assert F["ADD"].extensible and F["MUL"].extensible and not F["SUB"].extensible


# ---------------------------------------------------------------- bit strings


def test_shifts_use_the_width_of_in():
    bb = (T.BYTE, T.BYTE, T.INT)
    ww = (T.WORD, T.WORD, T.INT)
    assert call("SHL", 0x81, 1, types=bb) == 0x02
    assert call("ROL", 0x81, 1, types=bb) == 0x03
    assert call("ROR", 0x81, 1, types=bb) == 0xC0
    assert call("SHR", 0x81, 1, types=bb) == 0x40
    assert call("SHL", 0x45, 2, types=bb) == 0x14  # CODESYS example
    assert call("SHL", 0x45, 2, types=ww) == 0x0114
    assert call("SHL", 0xFF, 8, types=bb) == 0
    assert call("ROL", 0x81, 9, types=bb) == 0x03
    assert call("SHL", -1, 1, types=(T.INT, T.INT, T.INT)) == -2  # re-signed
    assert call("ROL", True, 3, types=(T.BOOL, T.BOOL, T.INT)) is True


def test_bitwise():
    assert call("AND", 0xF0, 0x3C, 0xFF) == 0x30
    assert call("OR", 0xF0, 0x0F) == 0xFF
    assert call("XOR", 0xFF, 0x0F, 0x01) == 0xF1
    assert call("AND", True, False) is False
    assert call("NOT", 0x0F, types=(T.BYTE, T.BYTE)) == 0xF0
    assert call("NOT", 0, types=(T.LWORD, T.LWORD)) == 2**64 - 1
    assert call("NOT", True, types=(T.BOOL, T.BOOL)) is False
    assert call("NOT", 0, types=(T.INT, T.INT)) == -1


# ---------------------------------------------------------------- selection and comparison


def test_selection():
    assert call("SEL", True, 3, 4) == 4
    assert call("SEL", False, 3, 4) == 3
    assert call("MAX", 1, 5, 3) == 5
    assert call("MIN", 1, 5, -3) == -3
    assert call("MAX", "abc", "abd") == "abd"
    assert call("LIMIT", 0, 150, 100) == 100
    assert call("LIMIT", 0, -5, 100) == 0
    assert call("LIMIT", 0, 50, 100) == 50
    assert call("LIMIT", 10, 5, 0) == 0  # MN > MX: MIN(MAX(IN, MN), MX)
    assert call("MUX", 1, 10, 20, 30) == 20
    assert call("MUX", 0, 30, 40, 50, 60, 70, 80) == 30  # CODESYS example
    assert call("MUX", 7, 10, 20, 30) == 30  # beyond: the last input (CODESYS)
    assert call("MUX", -1, 10, 20, 30) == 10
    assert F["MUX"].params[0] == ("K", "ANY_INT") and F["MUX"].extensible


def test_comparison():
    assert call("GT", 3, 2) is True
    assert call("GT", 3, 2, 1) is True
    assert call("GT", 3, 2, 2) is False  # GT(a, b, c) = a > b AND b > c
    assert call("GE", 3, 3, 2) is True
    assert call("EQ", 2, 2, 2) is True
    assert call("EQ", 2, 2, 3) is False
    assert call("LE", 1, 2, 2) is True
    assert call("LT", 1, 2, 2) is False
    assert call("NE", 1, 2) is True
    assert call("LT", "abc", "abd") is True
    assert not F["NE"].extensible and F["GT"].extensible


# ---------------------------------------------------------------- strings


def test_string_entries():
    assert call("LEN", "SUSI") == 4
    assert call("LEFT", "SUSI", 3) == "SUS"
    assert call("RIGHT", "SUSI", 3) == "USI"
    assert call("MID", "SUSI", 2, 2) == "US"
    assert call("CONCAT", "AB", "CD", "E") == "ABCDE"
    assert call("INSERT", "SUSI", "XY", 2) == "SUXYSI"
    assert call("DELETE", "SUXYSI", 2, 3) == "SUSI"
    assert call("REPLACE", "SUXYSI", "K", 2, 2) == "SKYSI"
    assert call("FIND", "abcdef", "de") == 4
    assert call("WCONCAT", "Ü", "€") == "Ü€"
    assert F["MID"].params == (("IN", "T:ANY_STRING"), ("L", "ANY_INT"), ("P", "ANY_INT"))
    assert F["LEN"].ret == "INT" and F["CONCAT"].extensible


# ---------------------------------------------------------------- time and date


def test_time_entries():
    assert call("ADD_TIME", 1000, 500) == 1500
    assert call("SUB_TIME", 1000, 1500) == -500
    assert call("MUL_TIME", 1000, 1.5) == 1500
    assert call("DIV_TIME", 10, 4) == 2
    # ed.2's names of the last two (MatIEC has them; OSCAT's port calls MULTIME)
    assert call("MULTIME", 1000, 1.5) == 1500 and call("DIVTIME", 10, 4) == 2
    assert call("ADD_TOD_TIME", 86_399_999, 1) == 0
    assert call("ADD_DT_TIME", DAY, 1500) == DAY + 1
    assert call("SUB_DATE_DATE", DAY + 86_400, DAY) == 86_400_000
    assert call("SUB_TOD_TOD", 7_200_000, 3_600_000) == 3_600_000
    assert call("SUB_DT_DT", DAY + 60, DAY) == 60_000
    assert call("SUB_TOD_TIME", 0, 1) == 86_399_999
    assert call("SUB_DT_TIME", DAY, 1000) == DAY - 1
    assert call("CONCAT_DATE_TOD", DAY, 45_015_500) == DAY + 45_015
    assert call("ADD_LTOD_LTIME", 86_400 * 10**9 - 1, 1) == 0
    assert call("SUB_LDT_LDT", 10, 3) == 7
    assert call("CONCAT_DATE", 2024, 1, 2) == DAY
    assert call("CONCAT_DT", 2024, 1, 2, 12, 30, 15, 0) == DAY + 45_015
    assert call("CONCAT_TOD", 12, 30, 15, 500) == 45_015_500
    assert call("DAY_OF_WEEK", DAY) == 2
    assert F["ADD_TOD_TIME"].params == (("IN1", "TIME_OF_DAY"), ("IN2", "TIME"))
    assert F["SUB_DT_DT"].ret == "TIME"
