"""Literal values: token text -> the Python value the AST carries."""

import pytest

from softplc.runtime.st import ast
from softplc.runtime.st.syntax.literals import (
    LiteralError,
    parse_based,
    parse_c_hex,
    parse_date,
    parse_dt,
    parse_duration,
    parse_hash_literal,
    parse_int,
    parse_real,
    parse_string,
    parse_tod,
)

S = 10**9
MS = 10**6


@pytest.mark.parametrize("text, value", [("0", 0), ("42", 42), ("1_000", 1000), ("007", 7)])
def test_integers(text, value):
    assert parse_int(text) == value


@pytest.mark.parametrize(
    "text, value",
    [
        ("16#FF", 255),
        ("16#ff", 255),
        ("2#1010_1010", 170),
        ("8#17", 15),
        ("16#FFFF_FFFF", 0xFFFFFFFF),
    ],
)
def test_based_integers(text, value):
    assert parse_based(text) == value


def test_c_hex():
    assert parse_c_hex("0x00032007") == 0x32007
    assert parse_c_hex("0X1f") == 31


@pytest.mark.parametrize(
    "text, value",
    [
        ("1.5", 1.5),
        ("1.0E-3", 0.001),
        ("1.5e3", 1500.0),
        ("1e5", 1e5),
        ("1_000.5", 1000.5),
        ("0.25", 0.25),
    ],
)
def test_reals(text, value):
    assert parse_real(text) == value


@pytest.mark.parametrize(
    "text, problem",
    [
        ("2#102", "digit '2' is not valid in base 2"),
        ("8#9", "digit '9' is not valid in base 8"),
        ("16#FG", "digit 'G' is not valid in base 16"),
        ("3#12", "invalid base '3'"),
        ("16x#1", "invalid base '16x'"),
        ("16#3#Z", "digit '#' is not valid"),
        ("16#_FF", "invalid number"),
    ],
)
def test_bad_based_integers(text, problem):
    with pytest.raises(LiteralError) as e:
        parse_based(text)
    assert problem in e.value.message


def test_bad_underscores_and_absurd_lengths():
    with pytest.raises(LiteralError):
        parse_int("10_")
    with pytest.raises(LiteralError):
        parse_based("16#_FF")
    assert parse_int("1__0") == 10  # the checker refuses it where the profile does
    with pytest.raises(LiteralError) as e:
        parse_int("9" * 200)  # Python's int() would refuse past 4300 digits; we stop far earlier
    assert "too long" in e.value.message
    with pytest.raises(LiteralError):
        parse_real("1e999")


@pytest.mark.parametrize(
    "text, value",
    [
        ("'abc'", "abc"),
        ("''", ""),
        ("'$''", "'"),
        ("'$$'", "$"),
        ("'a$Nb'", "a\nb"),
        ("'$L$R$T$P'", "\n\r\t\f"),
        ("'$41$42'", "AB"),
        ("'$n'", "\n"),
        ('"$00C4"', "Ä"),
        ('"say $"hi$""', 'say "hi"'),
        ('"x$0041"', "xA"),
        ("'it$'s'", "it's"),
    ],
)
def test_strings(text, value):
    assert parse_string(text) == value


@pytest.mark.parametrize("text", ["'$Q'", "'$4'", '"$00G1"', "'$'"])
def test_bad_string_escapes(text):
    with pytest.raises(LiteralError) as e:
        parse_string(text)
    assert "escape" in e.value.message and e.value.hint


@pytest.mark.parametrize(
    "body, ns",
    [
        ("1h2m3s4ms", 3_723_004_000_000),
        ("1.5s", 1500 * MS),
        ("-5s", -5 * S),
        ("+5s", 5 * S),
        ("100us", 100_000),
        ("250ns", 250),
        ("1d", 86_400 * S),
        ("1d_2h", 93_600 * S),
        ("1_000ms", S),
        ("2m", 120 * S),
        ("2m30s", 150 * S),
        ("1H30M", 5400 * S),
        ("0.5ms", 500_000),
        ("1.5h", 5400 * S),
        ("25h", 90_000 * S),  # the leading unit may overflow
    ],
)
def test_durations(body, ns):
    assert parse_duration(body) == ns


@pytest.mark.parametrize(
    "body, problem",
    [
        ("5", "invalid time literal"),
        ("5x", "invalid time literal"),
        ("1s2m", "out of order"),
        ("1s1s", "out of order"),
        ("1.5h30m", "only the last unit"),
    ],
)
def test_bad_durations(body, problem):
    with pytest.raises(LiteralError) as e:
        parse_duration(body)
    assert problem in e.value.message


def test_dates_and_times_of_day():
    assert parse_date("1970-01-01") == 0
    assert parse_date("1970-01-02") == 86_400 * S
    assert parse_date("2024-01-02") == 1_704_153_600 * S
    assert parse_tod("00:00:00") == 0
    assert parse_tod("12:30:15.5") == (12 * 3600 + 30 * 60 + 15) * S + 500 * MS
    assert parse_tod("23:59") == (23 * 3600 + 59 * 60) * S
    assert parse_dt("2008-09-04-07:50:32") == 1_220_514_632 * S
    assert parse_dt("2024-01-02-12:30:15.25") == (1_704_153_600 + 12 * 3600 + 30 * 60 + 15) * S + 250 * MS
    assert parse_date("1969-12-31") == -86_400 * S  # before the epoch: the checker judges the range


@pytest.mark.parametrize(
    "fn, text",
    [
        (parse_date, "2024-13-01"),
        (parse_date, "2023-02-29"),
        (parse_date, "0000-01-01"),
        (parse_date, "2024-1"),
        (parse_tod, "24:00:00"),
        (parse_tod, "12:60:00"),
        (parse_tod, "12"),
        (parse_dt, "2024-01-02"),
    ],
)
def test_bad_dates(fn, text):
    with pytest.raises(LiteralError):
        fn(text)


@pytest.mark.parametrize(
    "text, kind, value, type_name",
    [
        ("T#1h2m3s4ms", "time", 3_723_004_000_000, None),
        ("TIME#5s", "time", 5 * S, None),
        ("t#-5s", "time", -5 * S, None),
        ("LT#100ns", "ltime", 100, None),
        ("LTIME#1.5s", "ltime", 1500 * MS, None),
        ("D#2024-01-02", "date", 1_704_153_600 * S, None),
        ("DATE#1970-01-01", "date", 0, None),
        ("LDATE#1970-01-02", "ldate", 86_400 * S, None),
        ("TOD#12:30:15.5", "tod", 45_015_500 * MS, None),
        ("TIME_OF_DAY#00:00:01", "tod", S, None),
        ("LTOD#00:00:00.000000001", "ltod", 1, None),
        ("DT#2008-09-04-07:50:32", "dt", 1_220_514_632 * S, None),
        ("DATE_AND_TIME#1970-01-01-00:00:01", "dt", S, None),
        ("LDT#1970-01-01-00:00:00.5", "ldt", 500 * MS, None),
        ("INT#5", "int", 5, "INT"),
        ("int#-5", "int", -5, "INT"),
        ("INT#16#FF", "int", 255, "INT"),
        ("DWORD#2#1010", "int", 10, "DWORD"),
        ("UDINT#1_000", "int", 1000, "UDINT"),
        ("REAL#1.5", "real", 1.5, "REAL"),
        ("LREAL#1.0E-3", "real", 0.001, "LREAL"),
        ("REAL#1", "int", 1, "REAL"),  # kept as written; the checker converts
        ("BOOL#1", "bool", True, "BOOL"),
        ("BOOL#0", "bool", False, "BOOL"),
        ("BOOL#TRUE", "bool", True, "BOOL"),
        ("bool#false", "bool", False, "BOOL"),
        ("STRING#'hi$N'", "string", "hi\n", "STRING"),
        ('WSTRING#"$00C4"', "wstring", "Ä", "WSTRING"),
        ("Speed#5", "int", 5, "SPEED"),  # a derived type: the checker resolves it
    ],
)
def test_prefixed_literals(text, kind, value, type_name):
    lit = parse_hash_literal(text)
    assert isinstance(lit, ast.Literal)
    assert (lit.kind, lit.value, lit.type_name) == (kind, value, type_name)
    assert type(lit.value) is type(value)


def test_enumeration_values_and_schneider_addresses():
    e = parse_hash_literal("Color#Red")
    assert isinstance(e, ast.EnumLiteral) and (e.type_name, e.value_name) == ("Color", "Red")
    a = parse_hash_literal("ADR#0.1.SYS")
    assert isinstance(a, ast.SchneiderAddress) and a.parts == ("0", "1", "SYS")


@pytest.mark.parametrize(
    "text",
    [
        "BOOL#2",
        "BOOL#yes",
        "INT#Red",
        "T#5",
        "D#2024-13-01",
        "TOD#25:00:00",
        'STRING#"x"',
        "WSTRING#'x'",
        "INT#16#XY",
        "STRING#5",
        "ADR#0..SYS",
    ],
)
def test_bad_prefixed_literals(text):
    with pytest.raises(LiteralError):
        parse_hash_literal(text)
