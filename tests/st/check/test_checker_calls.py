"""The checker's calls (runtime/st/check/checker_calls.py): user FUNCTIONs, FB
instances, standard functions, builtins and native functions."""

from __future__ import annotations

import pytest

from softplc.runtime.st import types as T
from softplc.runtime.st.check.symbols import CallInfo
from softplc.runtime.st.native import ADDRESS, ANY_INT, STRING, WORDS, NativeFunction, Param

from ..conftest import check_st, codes, diagnostics, pou_body, run_st


def test_call_parameters_are_checked():
    src = """
FUNCTION f : INT
VAR_INPUT a : INT; END_VAR
VAR_IN_OUT io : INT; END_VAR
f := a;
END_FUNCTION
PROGRAM main
VAR t : TON; x : INT; q : BOOL; END_VAR
x := f(a := 1, nosuch := 2, io := x);
x := f(a := 1);
t(IN := TRUE, PT := 5);
t(IN := TRUE, Q := q);
x := f(1, x, 3);
END_PROGRAM
"""
    found = [(d.code, d.pos.line) for d in diagnostics(src) if d.is_error]
    assert ("E040", 9) in found  # unknown parameter
    assert ("E042", 10) in found  # VAR_IN_OUT not connected
    assert ("E020", 11) in found  # PT is TIME, not an integer
    assert ("E040", 12) in found  # output bound with :=
    assert ("E041", 13) in found  # too many arguments


def test_fb_called_as_a_value_and_program_called_directly():
    src = """
PROGRAM other
END_PROGRAM
PROGRAM main
VAR t : TON; b : BOOL; END_VAR
b := t(IN := TRUE);
other();
END_PROGRAM
"""
    assert codes(src) == ["E043", "E043"]


# ---------------------------------------------------------------- native functions


class _NoService:
    def request(self, name, *args):
        return False


PROBE = NativeFunction(
    "PROBE",
    (
        Param("address", ADDRESS),
        Param("label", STRING),
        Param("node", ANY_INT, "the node"),
        Param("table", WORDS, "the table", min_words=4),
    ),
    service="probe",
    fallback=_NoService(),
    usage="PROBE(ADR#0.1.SYS, 'x', <node>, %MW<table>:4)",
)

NATIVE_DECLS = (
    "ok : BOOL; n : INT; r : REAL; s : STRING; t4 : ARRAY[0..3] OF WORD; t2 : ARRAY[1..2] OF INT;"
    " b4 : ARRAY[0..3] OF BYTE;"
)


def native_call(args: str):
    """Check ok := PROBE(args) with PROBE declared as a native function;
    returns (the call expression, [(code, message, hint, line, column)])."""
    src = f"PROGRAM main\nVAR\n{NATIVE_DECLS}\nEND_VAR\nok := PROBE({args});\nEND_PROGRAM\n"
    checked, diags = check_st(src, profile="schneider", natives={PROBE.name: PROBE})
    return pou_body(checked)[0].value, [(d.code, d.message, d.hint, d.pos.line, d.pos.col) for d in diags]


@pytest.mark.parametrize("args", ["ADR#0.1.SYS, 'SDO', n, t4", "ADR#0.1.SYS, s, 40, %MW100:4"])
def test_a_native_call_is_typed_from_its_declaration(args):
    call, found = native_call(args)
    assert found == []
    assert isinstance(call.target, CallInfo) and call.target.kind == "native" and call.target.func is PROBE
    assert call.target.args == [a.value for a in call.args]
    assert call.target.rtypes == tuple(a.value.ty for a in call.args)
    assert call.ty is T.BOOL


@pytest.mark.parametrize(
    "args, message",
    [
        ("ADR#0.1.SYS, 'SDO', n", "PROBE takes 4 positional arguments"),
        ("ADR#0.1.SYS, 'SDO', n, t4, 1", "PROBE takes 4 positional arguments"),
        ("", "PROBE takes 4 positional arguments"),
        ("ADR#0.1.SYS, 'SDO', n, table := t4", "PROBE: name every argument or none"),
        ("address := ADR#0.1.SYS, label := 'SDO', node := n", "PROBE needs its input table"),
        ("address := ADR#0.1.SYS, label := 'SDO', node := n, table := t4, ok => ok", "PROBE has no outputs to connect"),
    ],
)
def test_a_native_call_with_the_wrong_arguments_shows_the_usage(args, message):
    _, found = native_call(args)
    assert found == [("E041", message, "PROBE(ADR#0.1.SYS, 'x', <node>, %MW<table>:4)", 5, 7)]


def test_a_native_call_may_name_its_arguments_in_any_order_and_case():
    call, found = native_call("NODE := n, table := t4, Label := 'SDO', address := ADR#0.1.SYS")
    assert found == []
    by_name = {a.name.upper(): a.value for a in call.args}
    assert call.target.args == [by_name[p.name.upper()] for p in PROBE.params]  # in the declaration's order


def test_a_named_native_argument_that_is_no_input_names_the_inputs():
    _, found = native_call("address := ADR#0.1.SYS, label := 'SDO', nod := n, table := t4")
    assert found == [("E041", "'nod' is not an input of PROBE (address, label, node, table)", PROBE.usage, 5, 53)]


def test_the_arguments_of_a_wrong_native_call_are_still_checked():
    _, found = native_call("nosuch")
    assert [(code, line, col) for code, _m, _h, line, col in found] == [("E041", 5, 7), ("E010", 5, 13)]


def test_native_arguments_of_the_wrong_kind():
    _, found = native_call("n, 5, r, b4")
    assert found == [
        ("E020", "PROBE: argument 1 must be an ADR#... address", None, 5, 13),
        ("E020", "PROBE: argument 2 must be a STRING", None, 5, 16),
        ("E020", "PROBE: the node (argument 3) must be an integer", None, 5, 19),
        (
            "E020",
            "PROBE: the table (argument 4) must be a word table such as %MW3250:4 or an ARRAY OF WORD",
            None,
            5,
            22,
        ),
    ]


@pytest.mark.parametrize("table", ["t2", "%MW100:2"])
def test_a_native_management_table_too_small(table):
    _, found = native_call(f"ADR#0.1.SYS, 'SDO', n, {table}")
    assert found == [("E020", "PROBE: the table (argument 4) needs 4 words", None, 5, 36)]


def test_a_native_argument_in_error_is_reported_once():
    _, found = native_call("ADR#0.1.SYS, 'SDO', nosuch, t4")
    assert [code for code, *_ in found] == ["E010"]


# ---------------------------------------------------------------- generic native parameters

from softplc.runtime.st.native import ANY_ELEMENTARY, ANY_REAL  # noqa: E402
from softplc.runtime.st.native import BOOL as BOOL_KIND  # noqa: E402

SAME = NativeFunction(
    "SAME",
    (Param("a", ANY_ELEMENTARY, same="T"), Param("b", ANY_ELEMENTARY, same="T"), Param("c", BOOL_KIND)),
    service="same",
    fallback=_NoService(),
    usage="SAME(a, b, cond)",
    site=True,
)
NEAR = NativeFunction(
    "NEAR",
    (Param("a", ANY_REAL, same="R"), Param("b", ANY_REAL, same="R")),
    service="near",
    fallback=_NoService(),
    usage="NEAR(x, y)",
)
GENERIC_DECLS = (
    "TYPE E_Light : (Off, Green, Red); END_TYPE\n"
    "PROGRAM main\nVAR\nok : BOOL; i : INT; d : DINT; r : REAL; s : STRING; t : TIME; e : E_Light;"
    " a : ARRAY[0..1] OF INT;\nEND_VAR\n"
)


def generic_call(call: str):
    """Check ok := <call>; returns (the call, [(code, message, line, column)])."""
    src = f"{GENERIC_DECLS}ok := {call};\nEND_PROGRAM\n"
    checked, diags = check_st(src, natives={SAME.name: SAME, NEAR.name: NEAR})
    return pou_body(checked)[0].value, [(d.code, d.message, d.pos.line, d.pos.col) for d in diags]


@pytest.mark.parametrize(
    "call, common",
    [
        ("SAME(5, i, TRUE)", T.INT),  # the literal takes the variable's type
        ("SAME(i, 5, TRUE)", T.INT),
        ("SAME(i, d, i > 0)", T.DINT),  # integers meet in the wider one
        ("SAME(1.5, r, TRUE)", T.REAL),
        ("SAME(T#2s, t, TRUE)", T.TIME),
        ("SAME(E_Light#Red, e, TRUE)", "E_Light"),
        ("SAME('abc', s, TRUE)", "STRING"),
        ("NEAR(2, r)", T.REAL),  # an integer literal is a real here
    ],
)
def test_parameters_that_share_a_type_variable_get_one_common_type(call, common):
    node, found = generic_call(call)
    assert found == []
    types = node.target.rtypes[:2]
    if isinstance(common, str):
        assert all(str(t).startswith(common) for t in types), types
    else:
        assert types == (common, common)


@pytest.mark.parametrize(
    "call, message",
    [
        ("SAME(e, i, TRUE)", "arguments of types E_Light and INT do not match"),
        (
            "SAME(a, a, TRUE)",
            "SAME: argument 1 must be an elementary value (a number, BOOL, STRING, time or enumeration)",
        ),
        ("SAME(i, i, 5)", "SAME: argument 3 must be a BOOL"),
        ("NEAR(t, t)", "NEAR: argument 1 must be a REAL or LREAL"),
    ],
)
def test_generic_native_arguments_that_do_not_fit(call, message):
    _, found = generic_call(call)
    assert message in [m for _c, m, _l, _col in found], found


def test_a_native_declared_with_site_is_not_mistaken_for_a_plain_one():
    node, found = generic_call("SAME(5, i, TRUE)")
    assert found == [] and node.target.func.site
    with pytest.raises(ValueError, match="share a type"):
        Param("x", ANY_INT, same="T")


# ---------------------------------------------------------------- a trailing comma

TRAILING = """
FUNCTION add : INT
VAR_INPUT a : INT; b : INT; END_VAR
add := a + b;
END_FUNCTION
PROGRAM main
VAR r : INT; t : TON; END_VAR
r := add(a := 1, b := 2,);
r := add(1, 2 ,);
t(IN := TRUE, PT := T#1s,);
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["iec", "matiec", "schneider"])
def test_a_trailing_comma_is_e044_but_in_codesys_and_twincat(profile):
    ds = diagnostics(TRAILING, profile)
    assert [(d.code, d.pos.line, d.pos.col) for d in ds] == [("E044", 8, 24), ("E044", 9, 15), ("E044", 10, 25)]
    assert ds[0].message == "a comma ends the argument list"
    assert ds[0].hint == "remove it (the codesys and twincat profiles accept it)"


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_codesys_and_twincat_accept_a_trailing_comma(profile):
    # TwinCAT 3 compiles F(a := 1, b := 2,) (blark, a parser of TwinCAT
    # sources, reads it too), and a CODESYS V3 export CODESYS compiles has
    # such calls; the call runs as without the comma
    assert codes(TRAILING, profile) == []
    r = run_st(TRAILING, profile=profile)
    assert r.get("r") == 3
