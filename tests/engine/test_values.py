"""A value from outside checked as the ST type it goes into, in the one
write API every surface uses (engine/access.py, engine/values.py): a
string with a lone surrogate, NaN and infinities from a server, a number
too big for a REAL; what a refusal echoes is cut (issue 31)."""

from __future__ import annotations

import json
import math
import pickle

import pytest

from softplc.runtime.engine.access import Access, Permission
from softplc.runtime.engine.places import PathError
from softplc.runtime.engine.retain_file import RetainStore, read_file, write_file
from softplc.runtime.engine.values import EnumValue

from .conftest import MS, compile_st, make_engine, task

SRC = """
PROGRAM Main
VAR
    name : STRING[10];
    wide : WSTRING[10];
    speed : REAL;
    total : LREAL;
    speeds : ARRAY[1..2] OF REAL;
END_VAR
END_PROGRAM
"""


def access(engines) -> Access:
    e = engines(SRC, [task("Main", 10, "Main")])
    # the web page, as surfaces/host.py makes it, and the test API, as softplc.testing.PLC does
    return Access(e, {"web": Permission(("*",), where="[web] writable"), "test": Permission(("*",), non_finite=True)})


@pytest.mark.parametrize("path", ["Main.name", "Main.wide"])
def test_a_string_with_a_lone_surrogate_is_refused(engines, path):
    a = access(engines)
    with pytest.raises(ValueError, match=r"U\+D800 at index 1 is a lone surrogate") as refused:
        a.write(path, "a\ud800b", surface="web")
    assert path in str(refused.value)
    with pytest.raises(ValueError, match="lone surrogate"):
        a.write(path, "\udfff", surface="test")  # the test API too: no STRING holds one
    a.write(path, "é€😀", surface="web")  # a pair is a character, and so are these
    assert a.engine.get(path) == "é€😀"


@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf, json.loads("1e999"), json.loads("-1e999")])
def test_a_server_cannot_write_nan_or_infinity_into_a_real(engines, value):
    a = access(engines)
    for path in ("Main.speed", "Main.total"):
        with pytest.raises(ValueError, match="a finite number"):
            a.write(path, value, surface="web")
    with pytest.raises(ValueError, match="a finite number"):
        a.write("Main.speeds", [1.0, value], surface="web")  # an element of an array too
    assert a.engine.get("Main.speed") == 0.0 and a.engine.get("Main.speeds") == [0.0, 0.0]
    a.write("Main.speed", value, surface="test")  # a test may check how the program takes a NaN
    got = a.engine.get("Main.speed")
    assert got == value or (math.isnan(got) and math.isnan(value))


def test_a_number_beyond_the_real_range_is_refused_not_made_infinite(engines):
    a = access(engines)
    with pytest.raises(ValueError, match=r"within the REAL range \(about ±3.4e38\)"):
        a.write("Main.speed", 1e39, surface="test")
    with pytest.raises(ValueError, match="within the LREAL range"):
        a.write("Main.total", 10**400, surface="test")  # float() of it would overflow
    a.write("Main.total", 1e300, surface="web")
    assert a.engine.get("Main.total") == 1e300


INTEGERS = """
PROGRAM Main
VAR
    count : DINT;
    mask : WORD;
    small : INT (0..100);
END_VAR
END_PROGRAM
"""


@pytest.mark.parametrize("literal", ["T#2s", "TIME#1s", "LTIME#5ms", "TOD#00:00:01", "BOOL#1"])
def test_an_integer_takes_no_time_or_date_literal(engines, literal):
    """The live soak's web client wrote 'T#2s' into a DINT: accepted as
    2,000,000,000 (the literal's nanoseconds). In ST `count := T#2s` is a
    type error; only an integer literal, typed or not, is an integer."""
    e = engines(INTEGERS, [task("Main", 10, "Main")])
    a = Access(e, {"web": Permission(("*",), where="[web] writable")})
    for path in ("Main.count", "Main.mask", "Main.small"):
        with pytest.raises(ValueError, match="an integer"):
            a.write(path, literal, surface="web")
    a.write("Main.count", "DINT#16#7F", surface="web")
    a.write("Main.mask", "WORD#2#101", surface="web")
    a.write("Main.small", "INT#42", surface="web")
    assert (e.get("Main.count"), e.get("Main.mask"), e.get("Main.small")) == (127, 5, 42)


def test_a_refusal_echoes_a_long_value_or_path_cut(engines):
    a = access(engines)
    with pytest.raises(ValueError) as long_value:
        a.write("Main.name", "x" * 1_000_000, surface="web")
    message = str(long_value.value)
    assert len(message) < 200 and "(1000000 characters)" in message, message
    with pytest.raises(PathError) as long_path:
        a.write("Main." + "p" * 1_000_000, 1, surface="web")
    assert len(str(long_path.value)) < 200 and "(1000005 characters)" in str(long_path.value)
    with pytest.raises(ValueError) as long_list:
        a.write("Main.speed", list(range(100_000)), surface="web")
    assert len(str(long_list.value)) <= 1000


RETAINED = """
PROGRAM Main
VAR RETAIN
    label : WSTRING[20] := "init";
    names : ARRAY[1..2] OF STRING[8];
    count : INT;
END_VAR
count := count + 1;
END_PROGRAM
"""


def test_a_retained_string_with_a_lone_surrogate_from_an_older_version_is_repaired(tmp_path, caplog):
    """An older softplc let a client write "\\ud800" and saved it ("\\ud800" in the JSON of the
    retain file): the warm start keeps the text with U+FFFD in its place and says so, and the
    engine's dump (softplc run --final-json) is JSON that UTF-8 takes."""
    path = tmp_path / "plant.retain"

    def engine():
        return make_engine(
            compile_st(RETAINED),
            [task("Main", 10, "Main")],
            retain_store=RetainStore(path),
            retain_period_ns=100 * MS,
            start_mode="warm",
        )

    first = engine()
    first.run(cycles=3)
    first.stop()
    saved = read_file(path)
    assert saved is not None
    saved.vars["Main.label"]["value"] = "ok\ud800ay"
    saved.vars["Main.names"]["value"] = ["fine", "\udc00"]
    write_file(path, saved)
    assert b"\\ud800" in path.read_bytes()  # what the older version wrote

    e = engine()
    assert e.get("Main.label") == "ok\ufffday" and e.get("Main.names") == ["fine", "\ufffd"]
    assert e.get("Main.count") == 3  # the rest as saved
    assert e.restore_report.repaired == [("Main.label", ["Main.label"]), ("Main.names", ["Main.names[2]"])]
    warnings = [r.getMessage() for r in caplog.records if "lone surrogate" in r.getMessage()]
    assert warnings == [
        "warm start: Main.label restored, U+FFFD for a lone surrogate: Main.label",
        "warm start: Main.names restored, U+FFFD for a lone surrogate: Main.names[2]",
    ]
    json.dumps(e.dump(), ensure_ascii=False).encode("utf-8")
    e.stop()


def test_an_enumerator_read_from_the_plc_pickles_with_its_type_and_number():
    # what a sweep's worker process, or a pytest-xdist worker, sends back
    running = EnumValue("Running", "E_State", 3)
    back = pickle.loads(pickle.dumps(running))
    assert (back.name, back.type_name, back.value) == ("Running", "E_State", 3)
    assert back == running and back == "running" and back == 3 and str(back) == "Running"
