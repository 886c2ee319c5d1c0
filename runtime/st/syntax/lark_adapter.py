"""The one module that reads lark: grammar.lark compiled into plain data.

lark does the grammar analysis (EBNF to BNF, the LALR(1) table); softplc
runs the table itself (parse_stack.py), with its own lexer (lexer.py) and
error recovery (parse_recovery.py), because lark's public parsing interface
cannot do what they need fast enough: lark's InteractiveParser copies its
whole state to tell whether a token fits (``accepts``), and recovery asks
that for many tokens and stack depths, and undoes reductions. So this module
takes from lark what its public interface does not give, and hands it on as
plain data (``CompiledGrammar``) that no other module needs lark to read.

What is relied on, each checked by tests/st/test_lark_adapter.py against the
installed lark (a lark upgrade that breaks one fails there, naming it):

  1. ``Lark(..., parser="lalr")`` keeps its table at
     ``.parser.parser.parser.parse_table`` (frontend, LALR_Parser, _Parser),
     with ``states`` {state: {symbol name: (action, argument)}},
     ``start_states`` and ``end_states`` ({start rule name: state}).
  2. An action is ``lark.parsers.lalr_analysis.Shift`` (the argument is the
     next state) or Reduce (the argument is a ``lark.grammar.Rule``).
  3. A Rule has ``origin.name``, ``expansion`` (symbols with ``name``,
     ``is_term``, and for terminals ``filter_out``: a quoted string, left
     out of the children), ``alias`` (``-> name``) and ``options`` with
     ``expand1`` (``?rule``), ``keep_all_tokens`` (``!rule``),
     ``template_source`` and ``empty_indices`` (with maybe_placeholders:
     one flag per position of the written expansion, True where an omitted
     ``[item]`` stood).
  4. ``Lark.terminals`` holds TerminalDefs with ``name`` and ``pattern``; a
     quoted terminal's pattern is a ``lark.lexer.PatternStr`` whose
     ``value`` is the string; ``pattern.to_regexp()`` is a Python regular
     expression with the terminal's flags.
  5. The children a rule's callback gets are shaped the way grammar.lark's
     comments and lark's documentation say (quoted tokens dropped, _rules
     inlined, ?rules with one child passed through, [item] -> None);
     st_grammar.py shapes them itself from the data of 3, and the test
     compares that with lark's own parser on ST programs.

The analysis takes half a second; its result, plain data, is kept in
softplc's cache (runtime/cache.py) by the hash of grammar.lark, this
module's code and lark's, so a run with the cache warm does not import lark.
"""

from __future__ import annotations

import importlib.util
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ... import cache

__all__ = ["CompiledGrammar", "RuleInfo", "SymbolInfo", "Terminal", "compile_grammar", "load_st_grammar"]


@dataclass(frozen=True, slots=True)
class SymbolInfo:
    """One symbol of a rule's expansion."""

    name: str
    is_term: bool
    filter_out: bool  # a quoted terminal: not among the children

    def __reduce__(self) -> tuple:  # (a cached grammar: faster than the dataclass's __setstate__)
        return SymbolInfo, (self.name, self.is_term, self.filter_out)


@dataclass(frozen=True, slots=True)
class RuleInfo:
    """One alternative of a rule, after lark's EBNF expansion."""

    origin: str  # the rule's name (goto symbol)
    expansion: tuple[SymbolInfo, ...]  # what the parser stack holds when it is reduced
    alias: str | None  # ``-> name``
    expand1: bool  # ``?rule``
    keep_all_tokens: bool  # ``!rule``
    empty_indices: tuple[bool, ...]  # placeholders of omitted [items] (see 3 above)
    template_source: str | None

    def __reduce__(self) -> tuple:
        return RuleInfo, (
            self.origin,
            self.expansion,
            self.alias,
            self.expand1,
            self.keep_all_tokens,
            self.empty_indices,
            self.template_source,
        )


@dataclass(frozen=True, slots=True)
class Terminal:
    """A terminal of the grammar: its literal text (quoted terminals) and
    its regular expression (flags included)."""

    name: str
    literal: str | None
    regexp: str

    def __reduce__(self) -> tuple:
        return Terminal, (self.name, self.literal, self.regexp)


# An action of the table: the next state (shift) or the rule to reduce.
Action = int | RuleInfo


@dataclass(frozen=True, slots=True)
class CompiledGrammar:
    states: dict[int, dict[str, Action]]
    start_state: int
    end_state: int
    terminals: dict[str, Terminal]


def compile_grammar(text: str, start: str = "start", **options: Any) -> CompiledGrammar:
    """Analyse a lark grammar for LALR(1) parsing; ``options`` go to Lark."""
    import lark  # (only when the grammar is analysed: not with a warm cache)
    from lark.parsers.lalr_analysis import Shift

    parser = lark.Lark(text, parser="lalr", start=start, **options)
    table = parser.parser.parser.parser.parse_table  # assumption 1
    rules: dict[tuple, RuleInfo] = {}
    states: dict[int, dict[str, Action]] = {}
    for state, actions in table.states.items():
        row = states[state] = {}
        for symbol, (kind, arg) in actions.items():
            if kind is Shift:  # assumption 2
                row[str(symbol)] = arg
            else:
                key = (str(arg.origin.name), tuple(str(s.name) for s in arg.expansion))
                info = rules.get(key)
                if info is None:
                    info = rules[key] = _rule_info(arg)
                row[str(symbol)] = info
    terminals = {t.name: _terminal(t) for t in parser.terminals}
    return CompiledGrammar(states, table.start_states[start], table.end_states[start], terminals)


def _rule_info(rule: Any) -> RuleInfo:
    """assumption 3"""
    options = rule.options
    return RuleInfo(
        str(rule.origin.name),
        tuple(SymbolInfo(str(s.name), bool(s.is_term), bool(s.is_term and s.filter_out)) for s in rule.expansion),
        rule.alias,
        bool(options.expand1),
        bool(options.keep_all_tokens),
        tuple(options.empty_indices or ()),
        options.template_source,
    )


def _terminal(t: Any) -> Terminal:
    """assumption 4"""
    from lark.lexer import PatternStr

    pattern = t.pattern
    literal = pattern.value if isinstance(pattern, PatternStr) else None
    return Terminal(t.name, literal, pattern.to_regexp())


# ---------------------------------------------------------------- grammar.lark

GRAMMAR_FILE = Path(__file__).with_name("grammar.lark")
# lark's lexer is never run (lexer.py's is); 'basic' is the cheapest to set up.
ST_OPTIONS: dict[str, Any] = dict(lexer="basic", maybe_placeholders=True, g_regex_flags=re.ASCII)


def _lark_code() -> bytes:
    """A hash of the installed lark's top module (it holds lark's version),
    found without importing lark."""
    spec = importlib.util.find_spec("lark")
    origin = spec.origin if spec is not None else None
    return cache.code_hash(Path(origin)) if origin else b"?"


def load_st_grammar() -> CompiledGrammar:
    """grammar.lark, analysed (or loaded from softplc's cache)."""
    text = GRAMMAR_FILE.read_text(encoding="utf-8")
    key = cache.key("grammar", text, repr(sorted(ST_OPTIONS.items())), cache.code_hash(Path(__file__)), _lark_code())
    compiled = cache.load("grammar", key)
    if not isinstance(compiled, CompiledGrammar):
        compiled = compile_grammar(text, **ST_OPTIONS)
        cache.store("grammar", key, compiled)
    return compiled
