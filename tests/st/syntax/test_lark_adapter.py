"""What lark_adapter.py relies on in lark, checked against the installed lark.

Each test is one numbered assumption of lark_adapter.py's docstring; when a
lark release breaks one, the failure says which (and the lark version).
"""

from __future__ import annotations

import pickle
import re

import lark
import pytest
from lark.lexer import PatternRE, PatternStr
from lark.parsers.lalr_analysis import Shift

from softplc.runtime import cache
from softplc.runtime.st.syntax import lark_adapter
from softplc.runtime.st.syntax.lark_adapter import RuleInfo, Terminal, compile_grammar, load_st_grammar

VERSION = f"lark {lark.__version__}"

# A grammar with each feature the adapter reads: quoted (filtered) and named
# terminals, an inlined _rule, a ?rule, an alias, an optional [item] and a
# keyword with a flag.
TINY = r"""
start: item+
item: NAME "=" value [UNIT] ";"
    | "SKIP"i ";"            -> skip
?value: NUMBER | _pair
_pair: "(" NUMBER "," NUMBER ")"
NAME: /[a-z]+/
NUMBER: /[0-9]+/
UNIT: "KG"i
%ignore " "
"""


def tiny_lark() -> lark.Lark:
    return lark.Lark(TINY, parser="lalr", lexer="basic", maybe_placeholders=True)


def lark_rules(parser: lark.Lark) -> list:
    table = parser.parser.parser.parser.parse_table
    return [arg for actions in table.states.values() for kind, arg in actions.values() if kind is not Shift]


def test_1_the_lalr_table_is_at_parser_parser_parser_parse_table():
    parser = tiny_lark()
    try:
        table = parser.parser.parser.parser.parse_table
    except AttributeError as e:
        pytest.fail(f"assumption 1 broken in {VERSION}: Lark(...).parser.parser.parser.parse_table: {e}")
    assert isinstance(table.states, dict) and table.states, f"assumption 1 ({VERSION}): parse_table.states"
    for state, actions in table.states.items():
        assert isinstance(state, int), f"assumption 1 ({VERSION}): states are ints, got {state!r}"
        assert all(isinstance(str(symbol), str) and len(action) == 2 for symbol, action in actions.items()), (
            f"assumption 1 ({VERSION}): a row maps symbols to (action, argument)"
        )
    assert set(table.start_states) == {"start"} and set(table.end_states) == {"start"}, (
        f"assumption 1 ({VERSION}): start_states and end_states by start rule name"
    )
    assert table.start_states["start"] in table.states and table.end_states["start"] in table.states


def test_2_actions_are_shift_to_a_state_or_reduce_a_rule():
    parser = tiny_lark()
    table = parser.parser.parser.parser.parse_table
    kinds = {kind for actions in table.states.values() for kind, _ in actions.values()}
    assert Shift in kinds and len(kinds) == 2, f"assumption 2 ({VERSION}): two kinds of action, one of them Shift"
    for actions in table.states.values():
        for kind, arg in actions.values():
            if kind is Shift:
                assert isinstance(arg, int) and arg in table.states, (
                    f"assumption 2 ({VERSION}): Shift's argument is the next state"
                )
            else:
                assert isinstance(arg, lark.grammar.Rule), f"assumption 2 ({VERSION}): Reduce's argument is a Rule"


def test_3_rules_say_their_origin_expansion_alias_and_options():
    rules = {(str(r.origin.name), tuple(str(s.name) for s in r.expansion)): r for r in lark_rules(tiny_lark())}
    message = f"assumption 3 ({VERSION}): Rule fields"
    item = rules[("item", ("NAME", "EQUAL", "value", "UNIT", "SEMICOLON"))]
    assert [(s.is_term, s.filter_out if s.is_term else None) for s in item.expansion] == [
        (True, False),
        (True, True),
        (False, None),
        (True, False),
        (True, True),
    ], message
    assert item.alias is None and not item.options.expand1 and not item.options.keep_all_tokens, message
    # With the [UNIT] left out: a placeholder flag at its place.
    item_no_unit = rules[("item", ("NAME", "EQUAL", "value", "SEMICOLON"))]
    assert tuple(item_no_unit.options.empty_indices) == (False, False, False, True, False), message
    assert not any(item.options.empty_indices), message
    skip = rules[("item", ("SKIP", "SEMICOLON"))]
    assert skip.alias == "skip", message
    assert rules[("value", ("NUMBER",))].options.expand1, message
    assert rules[("_pair", ("LPAR", "NUMBER", "COMMA", "NUMBER", "RPAR"))].options.template_source is None, message


def test_4_terminals_have_a_name_and_a_pattern():
    terminals = {t.name: t for t in tiny_lark().terminals}
    message = f"assumption 4 ({VERSION}): Lark.terminals, TerminalDef.pattern"
    assert isinstance(terminals["UNIT"].pattern, PatternStr) and terminals["UNIT"].pattern.value == "KG", message
    assert isinstance(terminals["SEMICOLON"].pattern, PatternStr) and terminals["SEMICOLON"].pattern.value == ";"
    assert isinstance(terminals["NAME"].pattern, PatternRE), message
    unit = re.compile(terminals["UNIT"].pattern.to_regexp())
    assert unit.fullmatch("kg") and unit.fullmatch("KG"), f"{message}: to_regexp() keeps the flags"
    assert re.compile(terminals["NAME"].pattern.to_regexp()).fullmatch("abc"), message


def test_the_adapter_turns_it_into_plain_data():
    compiled = compile_grammar(TINY, lexer="basic", maybe_placeholders=True)
    assert compiled.start_state in compiled.states and compiled.end_state in compiled.states
    actions = [a for row in compiled.states.values() for a in row.values()]
    assert all(isinstance(a, (int, RuleInfo)) for a in actions)
    rules = {(r.origin, tuple(s.name for s in r.expansion)): r for r in actions if isinstance(r, RuleInfo)}
    # One RuleInfo per rule, shared by the rows that reduce it.
    assert len(rules) == len({id(a) for a in actions if isinstance(a, RuleInfo)})
    item = rules[("item", ("NAME", "EQUAL", "value", "SEMICOLON"))]
    assert [s.filter_out for s in item.expansion] == [False, True, False, True]
    assert item.empty_indices == (False, False, False, True, False) and item.alias is None
    assert rules[("item", ("SKIP", "SEMICOLON"))].alias == "skip"
    assert rules[("value", ("NUMBER",))].expand1
    assert compiled.terminals["UNIT"] == Terminal("UNIT", "KG", compiled.terminals["UNIT"].regexp)
    assert compiled.terminals["NAME"].literal is None and re.fullmatch(compiled.terminals["NAME"].regexp, "abc")


def _table(compiled):
    return {
        s: {k: (v if isinstance(v, int) else (v.origin, v.expansion)) for k, v in row.items()}
        for s, row in compiled.states.items()
    }


def test_the_st_grammar_loads_and_uses_the_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("SOFTPLC_CACHE", str(tmp_path))
    first = load_st_grammar()
    [entry] = (tmp_path / "grammar").iterdir()
    before = cache.stats["hit", "grammar"]
    again = load_st_grammar()  # from the cache
    assert cache.stats["hit", "grammar"] == before + 1
    assert again.states.keys() == first.states.keys() and again.terminals == first.terminals
    assert _table(again) == _table(first)
    # a rule reduced in several states is one object there, as in the analysis (st_grammar keys on it)
    ids = {id(v) for row in again.states.values() for v in row.values() if not isinstance(v, int)}
    assert len(ids) == len(
        {(v.origin, v.expansion) for row in again.states.values() for v in row.values() if not isinstance(v, int)}
    )
    assert [p.name for p in (tmp_path / "grammar").iterdir()] == [entry.name]


def test_a_broken_cache_is_rebuilt(tmp_path, monkeypatch):
    monkeypatch.setenv("SOFTPLC_CACHE", str(tmp_path))
    first = load_st_grammar()
    [entry] = (tmp_path / "grammar").iterdir()
    entry.write_bytes(entry.read_bytes()[:1000])  # truncated, as by a crash of another writer
    rebuilt = load_st_grammar()  # (lark may number the states otherwise: the same table)
    assert len(rebuilt.states) == len(first.states) and rebuilt.terminals == first.terminals
    assert _table(pickle.loads(entry.read_bytes())) == _table(rebuilt)  # written again, whole


# ---------------------------------------------------------------- 5: tree shaping

# Between them, these use every rule of grammar.lark that has a builder method.
SAMPLES = [
    """
TYPE
    Color : (Red, Green := 5, Blue);
    Small : INT (0..100) := 1;
    Level : BYTE (Low, High) := Low;
    Mode : (Off, On) INT;
    Pair : STRUCT a : INT; b : ARRAY[1..2, *] OF REAL; END_STRUCT;
    Name : STRING[20];
    Wide : WSTRING(10);
    Ptr : REF_TO INT;
    Old : POINTER TO INT;
END_TYPE
VAR_GLOBAL CONSTANT RETAIN
    g1, g2 : INT := 3;
    AT %QW1 : WORD;
    lamp AT %QX0.1 : BOOL;
    arr : ARRAY[0..9] OF INT := [2(1), 3, 4(), 0];
    st : Pair := (a := 1, b := [1.0, 2.0]);
END_VAR
FUNCTION f : INT
VAR_INPUT x : INT; END_VAR
f := x;
END_FUNCTION
FUNCTION_BLOCK ABSTRACT fb EXTENDS base.one IMPLEMENTS i1, i2
VAR_OUTPUT q : BOOL; END_VAR
METHOD PUBLIC m : INT VAR_INPUT a : INT; END_VAR VAR_INST n : INT; END_VAR m := a; END_METHOD
PROPERTY p : INT GET p := 1; END_GET SET VAR t : INT; END_VAR t := p; END_SET END_PROPERTY
q := NOT q; THIS^.q := SUPER^.m(1) > 0; SUPER^();
END_FUNCTION_BLOCK
METHOD late END_METHOD
INTERFACE i1 EXTENDS i0, i3 METHOD m : INT END_METHOD PROPERTY p : INT GET END_GET END_PROPERTY END_INTERFACE
PROGRAM main
VAR a, b : INT; s : STRING; t : fb; p : REF_TO INT; w : WORD; d : ARRAY[1..3] OF INT; END_VAR
a := -b + 16#FF * 2#101 - 0x1F / 1.5E3 MOD 7 ** 2;
s := 'x'; s := "w"; a := INT#5; w := w OR w AND w XOR w;
IF a > 1 AND_THEN b < 2 OR_ELSE a = 3 THEN a := 1; ELSIF a <> 2 THEN a := 2; ELSE a := 3; END_IF;
CASE a OF
    1, 2..3: b := 1;
    -4: b := 2;
    (5): b := 3;
    Color.Red, Red..Blue: b := 4;
ELSE b := 5;
END_CASE;
FOR a := 1 TO 10 BY 2 DO b := b + 1; CONTINUE; END_FOR;
WHILE TRUE DO EXIT; END_WHILE;
REPEAT a := a - 1; UNTIL a < 0 END_REPEAT;
t(q => b, NOT q => a, x := 1);
t(2, 3);
t.q := w.3 AND w.%X4 AND d[1] > 0 AND p^ = 1 AND %IX0.1 AND a <= 1 AND a >= 1 AND FALSE & TRUE;
p REF= a;
SET t.q; RESET t.q;
t.q S= TRUE; t.q R= FALSE;
f(x := 1);
f(x := 1, y := 2,);
;
RETURN;
END_PROGRAM
CONFIGURATION cfg
    VAR_GLOBAL x : INT; END_VAR
    RESOURCE r ON cpu
        TASK fast (INTERVAL := T#10ms, PRIORITY := 1);
        PROGRAM RETAIN inst WITH fast : main (a := 1);
    END_RESOURCE
END_CONFIGURATION
CONFIGURATION c2
    VAR_CONFIG inst.a : INT := 1; END_VAR
    TASK t (INTERVAL := T#1s);
    PROGRAM NON_RETAIN i2 : main;
END_CONFIGURATION
""",
    "x := 1; y(z := 2);",
    "FUNCTION_BLOCK fb2\n;\nACTION A: ; END_ACTION\nEND_FUNCTION_BLOCK\nACTION fb2.B x := 1; END_ACTION;",
    "top: x := 1;\nJMP top;",
    "PROGRAM pm\nMETHOD m : INT m := 1; END_METHOD\nPROPERTY p : INT GET p := 2; END_GET END_PROPERTY\n;\nEND_PROGRAM",
    "VAR_GLOBAL fbs : ARRAY[1..2] OF FB_X[(n := 1), (n := 2)]; f : FB_X(n := 3); END_VAR",
    "PROGRAM p VAR t : Tc2_Standard.TON; END_VAR END_PROGRAM",
    """
FUNCTION_BLOCK seq
VAR go : BOOL; lamp : BOOL; n : INT; END_VAR
INITIAL_STEP s1: lamp(N); act(L, T#1s, lamp); END_STEP
STEP s2: END_STEP;
STEP s3: END_STEP
TRANSITION t1 (PRIORITY := 1) FROM s1 TO (s2, s3) := go; END_TRANSITION
TRANSITION t2 FROM (s2, s3) TO s1 : t2 := TRUE; END_TRANSITION;
ACTION act: n := n + 1; END_ACTION
ACTION other n := 0; END_ACTION;
END_FUNCTION_BLOCK
""",
    # actions before the network; an action (and an SFC one) written in SFC
    """
PROGRAM p
ACTION first: ; END_ACTION
INITIAL_STEP s1: first(N); END_STEP
ACTION inner: INITIAL_STEP x: END_STEP END_ACTION
END_PROGRAM
ACTION p.seq: STEP y: END_STEP END_ACTION
""",
    "x := (p + 2)^ + (ps)^.a + (pa)^[1, 2] + (pp)^^ + (pf)^.m(1);",
    "TYPE Sub EXTENDS Base : STRUCT c : INT; END_STRUCT END_TYPE",
    "PROGRAM p x := 1; END_PROGRAM ACTIONS ACTION a x := 2; END_ACTION END_ACTIONS ACTIONS p END_ACTIONS",
    "a := b := c + 9; IF (i := i + 1) = 10 THEN ; ELSIF f := g THEN ; END_IF",
]


def _callback_names(compiled) -> set:
    from softplc.runtime.st.syntax.build_decls import AstBuilder

    names = {r.alias or r.origin for row in compiled.states.values() for r in row.values() if isinstance(r, RuleInfo)}
    return {n for n in names if hasattr(AstBuilder, n)}


def _recorder(names: set) -> type:
    """A builder whose rule methods return (rule, children): the shapes."""

    def method(name):
        return lambda self, children: (name, [_norm(c) for c in children])

    def init(self, ctx=None):
        self.result = None

    def top(name):
        def record(self, children):
            self.result = (name, [_norm(c) for c in children])
            return self.result

        return record

    body = {n: method(n) for n in names}
    body.update(source=top("source"), bare_source=top("bare_source"), __init__=init)
    return type("Recorder", (), body)


def _norm(x):
    if isinstance(x, (lark.Token,)):
        return (x.type, str(x))
    if hasattr(x, "type") and hasattr(x, "value") and not isinstance(x, tuple):  # our Tok
        return (x.type, x.value)
    return x


def test_5_children_are_shaped_as_lark_shapes_them():
    """st_grammar.py shapes the children itself; lark's own parser, fed the
    same tokens, must hand its transformer the same children."""
    from softplc.runtime.st.diagnostics import DiagnosticBag
    from softplc.runtime.st.syntax.parser import _Parse
    from softplc.runtime.st.syntax.st_grammar import Grammar

    compiled = load_st_grammar()
    names = _callback_names(compiled)
    recorder = _recorder(names)
    ours = Grammar(compiled, builder=recorder)
    theirs = lark.Lark(
        lark_adapter.GRAMMAR_FILE.read_text(encoding="utf-8"),
        parser="lalr",
        transformer=recorder(),
        **lark_adapter.ST_OPTIONS,
    )
    seen: list = []
    lex = ours.lexer.tokens

    def tokens(text, accepts, bad, *more):
        for t in lex(text, accepts, bad, *more):
            seen.append(t)
            yield t

    ours.lexer.tokens = tokens
    used: set = set()
    for text in SAMPLES:
        seen.clear()
        diags = DiagnosticBag()
        parse = _Parse(text, "t.st", diags, ours)
        parse.run()
        assert not diags.items, [d.format() for d in diags.items]
        mine = parse.builder.result
        interactive = theirs.parse_interactive()
        for t in seen:
            interactive.feed_token(lark.Token(t.type, t.value))
        reference = interactive.feed_eof()
        assert mine == reference, f"assumption 5 ({VERSION}): lark shapes the children of some rule differently"

        def collect(node):
            if isinstance(node, tuple) and len(node) == 2 and isinstance(node[1], list):
                used.add(node[0])
                for c in node[1]:
                    collect(c)

        collect(mine)
    assert names <= used, f"samples to add, for: {sorted(names - used)}"
