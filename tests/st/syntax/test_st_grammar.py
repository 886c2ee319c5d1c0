"""st_grammar.py: the grammar bound to the AST builder, built on first use."""

from __future__ import annotations

import subprocess
import sys

import pytest

from softplc.runtime.st.syntax import st_grammar
from softplc.runtime.st.syntax.lark_adapter import compile_grammar
from softplc.runtime.st.syntax.st_grammar import COLON, COMMA, RESERVED, SEMI, grammar


def test_reserved_words_are_grammar_keywords():
    assert RESERVED <= set(grammar().lexer.keywords)


def test_the_grammar_is_built_on_first_use_and_then_shared():
    code = (
        "import softplc.runtime.st.syntax.parser, softplc.runtime.st.syntax.st_grammar as g\n"
        "assert g._grammar is None, 'built at import'\n"
        "from softplc.runtime.st.diagnostics import DiagnosticBag\n"
        "softplc.runtime.st.syntax.parser.parse_source('x := 1;', 'a.st', DiagnosticBag())\n"
        "assert g._grammar is g.grammar()\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)
    assert grammar() is grammar()


def test_punctuation_and_keywords():
    g = grammar()
    assert (g.lexer.punct[";"], g.lexer.punct[","], g.lexer.punct[":"]) == (SEMI, COMMA, COLON)
    assert [g.spelling(n) for n in (SEMI, "_ELSE", "END_IF", "THEN", "NAME")] == [";", "ELSE", "END_IF", "THEN", "NAME"]
    assert {"IF", "ELSE", "THEN", "END_VAR", "SET"} <= set(g.keywords) and "NAME" not in g.keyword_terminals
    assert g.keywords == sorted(g.keywords)


def test_simulate_feeds_a_token_without_building():
    g = grammar()
    start = [g.start_state]
    assert g.simulate(start, "END_IF") is None
    reduced: list = []
    after = g.simulate(start, "PROGRAM", reduced)
    assert after is not None and len(after) == 2 and reduced == []
    end = g.simulate(start, "$END", reduced)  # an empty file
    assert end is not None and end[-1] == g.end_state and reduced == ["start"]  # rule names, not aliases


# ---------------------------------------------------------------- shaping the children

TINY = r"""
start: item+
item: NAME "=" value [UNIT] ";"
    | "SKIP"i ";"            -> skip
    | "TWICE"i value ";"     -> twice
?value: NUMBER | _pair | "(" value ")"
_pair: "(" NUMBER "," NUMBER ")"
NAME: /[a-z]+/
NUMBER: /[0-9]+/
UNIT: "KG"i
%ignore " "
"""


class Builder:
    """Rule methods that return what they were given."""

    def __init__(self, ctx=None) -> None:
        pass

    def start(self, c):
        return ("start", list(c))

    def item(self, c):
        return ("item", list(c))

    def skip(self, c):
        return ("skip", list(c))

    def twice(self, c):
        return ("twice", list(c))

    def value(self, c):
        return ("value", list(c))


def reductions(builder: type) -> dict:
    """{(rule or alias, symbols): Reduce} of TINY (a Grammar needs the ST terminals for its lexer)."""
    out = {}
    for row in compile_grammar(TINY, lexer="basic", maybe_placeholders=True).states.values():
        for action in row.values():
            if not isinstance(action, int):
                out[(action.alias or action.origin, tuple(s.name for s in action.expansion))] = st_grammar.Reduce(
                    action, builder
                )
    return out


def tiny() -> dict:
    return reductions(Builder)


def run(reduce, children):
    return children[0] if reduce.build is None else reduce.build(Builder(), children)


def test_quoted_tokens_are_dropped_and_omitted_items_are_none():
    r = tiny()
    item = r[("item", ("NAME", "EQUAL", "value", "UNIT", "SEMICOLON"))]
    assert item.size == 5 and item.origin == "item" and item.alias is None
    assert run(item, ["a", "=", "1", "kg", ";"]) == ("item", ["a", "1", "kg"])
    no_unit = r[("item", ("NAME", "EQUAL", "value", "SEMICOLON"))]
    assert run(no_unit, ["a", "=", "1", ";"]) == ("item", ["a", "1", None])
    assert run(r[("skip", ("SKIP", "SEMICOLON"))], ["skip", ";"]) == ("skip", [])


def test_a_question_mark_rule_passes_one_child_through():
    r = tiny()
    assert r[("value", ("NUMBER",))].build is None  # always its one child
    assert run(r[("value", ("LPAR", "value", "RPAR"))], ["(", "7", ")"]) == "7"


def test_an_underscore_rule_is_spliced_into_its_parent():
    r = tiny()
    pair = r[("_pair", ("LPAR", "NUMBER", "COMMA", "NUMBER", "RPAR"))]
    inner = run(pair, ["(", "1", ",", "2", ")"])
    assert inner == ["1", "2"]
    # ?value with the _pair inlined: two children, so the method is called.
    assert run(r[("value", ("_pair",))], [inner]) == ("value", ["1", "2"])


def test_a_growing_list_is_extended_in_place_and_can_be_cut_back():
    r = tiny()
    [(key, grow)] = [(k, v) for k, v in r.items() if k[0].startswith("__") and len(k[1]) == 2]
    first = run(r[(key[0], ("item",))], ["i1"])
    assert first == ["i1"]
    assert grow.alias == 0  # the list of child 0 is reused: undo cuts it back
    grown = run(grow, [first, "i2"])
    assert grown is first and first == ["i1", "i2"]
    assert run(r[("start", (key[0],))], [grown]) == ("start", ["i1", "i2"])


def test_a_rule_without_a_builder_method_is_refused():
    without = type("WithoutTwice", (), {k: v for k, v in vars(Builder).items() if k != "twice"})
    with pytest.raises(ValueError, match=r"no method twice\(\)"):
        reductions(without)
