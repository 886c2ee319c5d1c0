"""parse_stack.py: the limits of a parse (errors, nesting), and feeding
tokens to the stacks."""

from __future__ import annotations

import pytest

from softplc.runtime.st import ast
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.syntax.lexer import Tok
from softplc.runtime.st.syntax.parse_stack import ParserCore, Rejected
from softplc.runtime.st.syntax.parser import MAX_ERRORS
from softplc.runtime.st.syntax.st_grammar import Reduce, grammar

from .parse_helpers import errors, ok, parse

# ---------------------------------------------------------------- limits


def test_too_many_errors_stop_the_parse():
    sf, diags = parse("x := ;\n" * (MAX_ERRORS + 50))
    assert len(diags) == MAX_ERRORS + 1 and "too many errors" in diags[-1].message
    assert sf.decls == []


def test_deep_nesting_is_refused_with_a_diagnostic():
    [d] = errors("x := " + "(" * 10000 + "1" + ")" * 10000 + ";")
    assert d.code == "E006" and d.message == "nested too deeply (more than 300 levels of the parser)"
    [d] = errors("x := " + " + ".join(["a"] * 10_002) + ";")
    assert d.code == "E006" and d.message == "expression too long (more than 10,000 operators)"
    ok("x := " + "(" * 50 + "1" + ")" * 50 + ";")  # but reasonable depth is fine
    ok("IF a THEN " * 30 + "x := 1;" + " END_IF" * 30)


# ---------------------------------------------------------------- feeding tokens


def test_a_rejected_token_leaves_the_stacks_as_they_were():
    g = grammar()
    text = "PROGRAM p x := 1; y := 2;"
    core = ParserCore(text, "t.st", DiagnosticBag(), g)
    for tok in g.lexer.tokens(text, lambda: g.rows[core.state_stack[-1]], None):
        core._feed(tok)
    states, values = list(core.state_stack), list(core.value_stack)
    [statements] = [v for v in values if isinstance(v, list)]
    assert len(statements) == 1
    # The table reduces y := 2; into the statement list before it sees that
    # END_IF does not fit here; the rejection takes that back.
    assert isinstance(g.rows[states[-1]]["END_IF"], Reduce)
    with pytest.raises(Rejected):
        core._feed(Tok("END_IF", "END_IF", len(text), 1, len(text) + 1))
    assert core.state_stack == states
    assert len(core.value_stack) == len(values) and all(a is b for a, b in zip(core.value_stack, values))
    assert len(statements) == 1
    # and the parse goes on as if the token had never come
    core._feed(Tok("END_PROGRAM", "END_PROGRAM", len(text), 1, len(text) + 1))
    sf = core._feed(core._end_token(), True)
    [pou] = sf.decls
    assert [s.target.name for s in pou.body] == ["x", "y"]


def test_chains_of_pass_through_reductions_leave_the_stack_the_table_gives():
    """Feeding takes a chain of ?rule pass-throughs (expression -> ... ->
    primary) in one step; the states must be those of the plain table."""
    g = grammar()
    text = "PROGRAM p x := (a + b * -c) MOD 3 > 2 OR d AND NOT e; IF x THEN y := x[1].f; END_IF END_PROGRAM"
    core = ParserCore(text, "t.st", DiagnosticBag(), g)
    chained = 0
    for tok in g.lexer.tokens(text, lambda: g.rows[core.state_stack[-1]], None):
        reduced: list = []
        expected = g.simulate(core.state_stack, tok.type, reduced)
        core._feed(tok)
        assert core.state_stack == expected, tok
        chained += len(reduced) > 1
    assert chained > 5 and g.unit_chains
    # reductions (some of them a pass-through chain) taken back on rejection
    text = "PROGRAM p x := a + b"
    core = ParserCore(text, "t.st", DiagnosticBag(), g)
    for tok in g.lexer.tokens(text, lambda: g.rows[core.state_stack[-1]], None):
        core._feed(tok)
    states, values = list(core.state_stack), list(core.value_stack)
    reduced: list = []
    assert g.simulate(states, "DO", reduced) is None and "primary" in reduced and "expr" in reduced
    with pytest.raises(Rejected):
        core._feed(Tok("DO", "DO", len(text), 1, len(text) + 1))
    assert core.state_stack == states and core.value_stack == values


def test_the_value_of_the_start_rule_ends_the_parse():
    g = grammar()
    core = ParserCore("", "t.st", DiagnosticBag(), g)
    sf = core._feed(core._end_token(), True)
    assert isinstance(sf, ast.SourceFile) and sf.decls == [] and core.state_stack[-1] == g.end_state


def test_too_many_stray_comment_ends_stop_the_parse_as_too_many_errors():
    sf, diags = parse("PROGRAM main\nEND_PROGRAM\n" + "*)" * (MAX_ERRORS + 1))
    assert [d.code for d in diags] == ["E001"] * (MAX_ERRORS + 1)
    assert diags[-1].message == f"too many errors; stopped after {MAX_ERRORS}"
