"""The [result] expressions (sweep/expr.py): ST paths, records, parameters
and the fault, evaluated without eval(); what is not there is None."""

from __future__ import annotations

import pytest

from softplc.runtime.sweep.expr import ExpressionError, Scope, check, evaluate, parse_expression

VALUES = {"Genset.State": "Running", "Line.parts[2].weight": 1.5, "CANOPEN_NODE[40].State": 5, "Main.n": 0}
RECORDS = {"gen": {"closes": [{"phase_deg": -3.5, "tripped": False}]}}


def scope(fault: str = "") -> Scope:
    def read(path: str):
        if path not in VALUES:
            raise KeyError(f"no variable {path!r}")
        return VALUES[path]

    return Scope(read, RECORDS, {"sim.gen.slip": 0.2}, fault)


@pytest.mark.parametrize(
    ("text", "value"),
    [
        ("Genset.State", "Running"),
        ("Genset.State == 'Running'", True),
        ("Line.parts[2].weight * 2", 3.0),
        ("CANOPEN_NODE[40].State in_range", None),
        ("records.gen.closes[0].phase_deg", -3.5),
        ("abs(records.gen.closes[0].phase_deg) < 10", True),
        ("len(records.gen.closes)", 1),
        ("records.gen.closes[1].phase_deg", None),  # no second close
        ("records.nobody", None),
        ("param('sim.gen.slip') * 10", 2.0),
        ("0 < CANOPEN_NODE[40].State <= 5", True),
        ("not records.gen.closes[0].tripped and Main.n == 0", True),
        ("1 / Main.n", None),
        ("Main.nothing + 1", None),
        ("fault", ""),
        ("max(1, 4) - min(2, 3) % 2", 4),
    ],
)
def test_values(text, value):
    if text.endswith("in_range"):  # not an expression: refused before any run
        with pytest.raises(ExpressionError):
            parse_expression(text)
        return
    assert evaluate(text, scope()) == value


def test_an_expectation_says_why_it_failed():
    assert check("abs(records.gen.closes[0].phase_deg) < 10", scope()) is None
    assert check("records.gen.closes[0].phase_deg > 0", scope()) == "records.gen.closes[0].phase_deg > 0: false"
    why = check("records.gen.closes[3].phase_deg < 10", scope())
    assert why is not None and "no 3 in the records" in why
    assert "no variable 'Main.gone'" in (check("Main.gone == 1", scope()) or "")
    assert check("fault == ''", scope("task Main: division by zero")) == "fault == '': false"


@pytest.mark.parametrize(
    "text",
    [
        "__import__('os').system('true')",
        "(lambda: 1)()",
        "Main.n.__class__",  # an attribute is a path part: read as an ST path, not Python's
        "[x for x in range(3)]",
        "open('/etc/passwd')",
        "Main.n if True else 2",
        "x" * 501,
    ],
)
def test_what_is_not_an_expression_of_the_list_is_refused_or_inert(text):
    try:
        tree = parse_expression(text)
    except ExpressionError:
        return
    # what parses (a dotted name) only ever reads a path
    assert tree is not None and evaluate(text, scope()) is None
