"""The ST grammar made ready to parse with: the LALR table bound to the AST
builder, the terminals and the lexer; built once per process, on first use.

``grammar()`` gives the shared instance (``Grammar`` is immutable once made,
so parses in several threads can share it). It comes from grammar.lark
through lark_adapter.py; the first call takes about 0.03 s (ten times that when
lark's cache of the analysis is missing or stale).

The table's reduce actions are ``Reduce`` objects that say how to make the
value of the rule from the values on the parser stack: the children are
shaped as lark shapes them (quoted tokens dropped, ``_rule``s inlined into
their parent, a ``?rule`` with one child passes it through, an omitted
``[item]`` gives None) and handed to the builder's method named after the
rule (or its ``-> alias``).
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from .build_decls import AstBuilder
from .lark_adapter import CompiledGrammar, RuleInfo, Terminal, load_st_grammar
from .lexer import Lexer

__all__ = ["COLON", "COMMA", "Grammar", "RESERVED", "Reduce", "SEMI", "grammar"]

# Keywords reserved everywhere: never names, so a misplaced END_IF is
# reported as such. The others (SET, RESET, AT, ON, WITH, TASK, RETAIN,
# CONSTANT, POINTER, ...) are keywords only where the grammar expects them.
RESERVED = frozenset(
    """
    PROGRAM END_PROGRAM FUNCTION END_FUNCTION FUNCTION_BLOCK END_FUNCTION_BLOCK TYPE END_TYPE
    STRUCT END_STRUCT ARRAY STRING WSTRING REF_TO VAR VAR_INPUT VAR_OUTPUT VAR_IN_OUT VAR_GLOBAL
    VAR_EXTERNAL VAR_TEMP VAR_STAT VAR_CONFIG END_VAR END_CONFIGURATION END_RESOURCE
    IF THEN ELSIF ELSE END_IF CASE OF END_CASE FOR TO BY DO END_FOR WHILE END_WHILE REPEAT UNTIL
    END_REPEAT EXIT CONTINUE RETURN AND AND_THEN OR OR_ELSE XOR NOT MOD TRUE FALSE
    END_METHOD END_PROPERTY END_INTERFACE
""".split()
)

# Terminal names of punctuation (defined in grammar.lark).
SEMI = "SEMICOLON"
COMMA = "COMMA"
COLON = "COLON"

# build(builder, children) -> the value of the rule
Build = Callable[[Any, list], Any]


class Reduce:
    """A reduce action, prepared for the parser's feed loop: how many values
    it takes, ``build`` (None: the value passes through, a ?rule with one
    child), the rule's name (for the goto), its symbols (to redo the states
    when a reduction is undone) and ``alias``: the child whose list the
    shaping reuses and extends in place (undo cuts it back). ``unit``: a
    ?rule's pass-through of its one child (the value stays, only the state
    changes: expression -> or_expr -> ... -> primary is a chain of them)."""

    __slots__ = ("size", "build", "origin", "symbols", "alias", "unit")

    def __init__(self, rule: RuleInfo, builder: type) -> None:
        self.size = len(rule.expansion)
        self.symbols = tuple(sym.name for sym in rule.expansion)
        self.origin = rule.origin
        self.build, self.alias = _shape(rule, builder)
        self.unit = self.size == 1 and self.build is None and self.alias is None


def _shape(rule: RuleInfo, builder: type) -> tuple[Build | None, int | None]:
    """(build, alias) for a rule: lark's tree shaping, with the builder's
    method for the rule at the end (or, for an inlined _rule, nothing: its
    value is the list of its children, spliced into its parent's)."""
    if rule.template_source is not None:
        raise ValueError(f"rule {rule.origin}: templates are not supported")
    size = len(rule.expansion)
    # How many None placeholders (omitted [items]) go before each position.
    nones = [0] * (size + 1)
    if rule.empty_indices:
        nones = [len(ones) for ones in "".join("1" if e else "0" for e in rule.empty_indices).split("0")]
        if len(nones) != size + 1:
            raise ValueError(f"rule {rule.origin}: empty_indices do not fit the expansion")
    plan: list[tuple[int, bool, int]] = []  # (child index, inline it, Nones before it)
    pending = 0
    for i, sym in enumerate(rule.expansion):
        pending += nones[i]
        if rule.keep_all_tokens or not sym.filter_out:
            plan.append((i, not sym.is_term and sym.name.startswith("_"), pending))
            pending = 0
    trailing = pending + nones[size]
    trivial = not trailing and len(plan) == size and not any(inline or n for _, inline, n in plan)
    alias = plan[0][0] if plan and plan[0][1] and not plan[0][2] else None

    name = rule.alias or rule.origin
    expand1 = rule.expand1 and not rule.alias
    if name.startswith("_"):
        if expand1:
            raise ValueError(f"rule {name}: an inlined rule cannot be a ?rule")
        method: Build | None = None
    else:
        method = getattr(builder, name, None)
        if method is None and not (expand1 and size == 1 and len(plan) == 1 and trivial):
            raise ValueError(f"rule {name}: the AST builder has no method {name}()")

    if trivial:
        if expand1 and size == 1:
            return None, alias  # always its one child
        if method is None:
            return _itself, alias
        if expand1:
            return _single_or(method), alias
        return method, alias
    shape = _filter(tuple(plan), trailing)
    if method is None:
        return (lambda builder, children: shape(children)), alias
    if expand1:
        single = _single_or(method)
        return (lambda builder, children: single(builder, shape(children))), alias
    return (lambda builder, children: method(builder, shape(children))), alias


def _itself(builder: Any, children: list) -> list:
    return children


def _single_or(method: Build) -> Build:
    def build(builder: Any, children: list) -> Any:
        return children[0] if len(children) == 1 else method(builder, children)

    return build


def _filter(plan: tuple[tuple[int, bool, int], ...], trailing: int) -> Callable[[list], list]:
    """The children a rule keeps. An inlined child's list is reused when it
    comes first (a left-recursive list grows in place, not by copying)."""

    def shape(children: list) -> list:
        kept: list = []
        for i, inline, nones in plan:
            if nones:
                kept += [None] * nones
            if inline:
                if kept:
                    kept += children[i]
                else:
                    kept = children[i]
            else:
                kept.append(children[i])
        if trailing:
            kept += [None] * trailing
        return kept

    return shape


class Grammar:
    """grammar.lark ready to parse with. The LALR table is in two parts:
    ``rows`` {state: {terminal: next state (int) | Reduce}}, what to do with
    a token, and ``goto`` {state: {symbol: next state}}, where a shift or a
    reduction to a rule leads. The reductions call the methods of
    ``builder`` (a parse makes one instance of it)."""

    def __init__(self, compiled: CompiledGrammar, builder: type = AstBuilder) -> None:
        terminals = {*compiled.terminals, "$END"}
        reduces: dict[int, Reduce] = {}
        rows: dict[int, dict[str, int | Reduce]] = {}
        goto: dict[int, dict[str, int]] = {}
        for state, actions in compiled.states.items():
            row: dict[str, int | Reduce] = {}
            after: dict[str, int] = {}
            rows[state], goto[state] = row, after
            for symbol, action in actions.items():
                if isinstance(action, int):
                    after[symbol] = action
                    if symbol in terminals:
                        row[symbol] = action
                else:
                    reduce = reduces.get(id(action))
                    if reduce is None:
                        reduce = reduces[id(action)] = Reduce(action, builder)
                    row[symbol] = reduce
        self.rows = rows
        self.goto = goto
        self.builder = builder  # the class whose methods the reductions call
        self.start_state = compiled.start_state
        self.end_state = compiled.end_state
        self.terminals: dict[str, Terminal] = compiled.terminals
        self.lexer = Lexer(self.terminals, RESERVED)
        for text, name in ((";", SEMI), (",", COMMA), (":", COLON)):
            if self.lexer.punct.get(text) != name:
                raise ValueError(f"grammar.lark must name the terminal {text!r} {name}")
        self.keyword_terminals = frozenset(
            n for n, t in self.terminals.items() if t.literal is not None and t.literal.isidentifier()
        )
        self.keywords = sorted(self.spelling(n) for n in self.keyword_terminals)
        # (state below, state on top, token type) -> the state on top after
        # every pass-through reduction the token calls for there (unit_chain)
        self.unit_chains: dict[tuple[int, int, str], int] = {}

    def unit_chain(self, below: int, top: int, ttype: str) -> int:
        """The state on top of the stack after the chain of pass-through
        reductions (``Reduce.unit``) that a token of type ttype calls for
        with ``top`` on ``below``: each replaces the top state only, so the
        chain depends on these two states and the token, and is remembered
        (the parser takes 10 of them after a typical operand)."""
        key = (below, top, ttype)
        found = self.unit_chains.get(key)
        if found is None:
            rows, gotos, found = self.rows, self.goto[below], top
            action = rows[found].get(ttype)
            while action is not None and action.__class__ is not int and action.unit:  # type: ignore[union-attr]
                found = gotos[action.origin]  # type: ignore[union-attr]
                if found == self.end_state:
                    break
                action = rows[found].get(ttype)
            self.unit_chains[key] = found  # (a race writes the same value)
        return found

    def spelling(self, name: str) -> str:
        """Terminal name -> how it is written ('SEMICOLON' -> ';', '_ELSE' -> 'ELSE')."""
        t = self.terminals.get(name)
        if t is not None and t.literal is not None:
            return t.literal.upper()
        return name

    def simulate(self, stack: list, ttype: str, reduced: list | None = None) -> list | None:
        """The state stack after feeding a token of type ttype (reductions and
        the shift), or None if the parser would reject it. Nothing is built;
        the names of the rules reduced on the way go into ``reduced``."""
        rows, gotos, end_state = self.rows, self.goto, self.end_state
        stack = list(stack)
        while True:
            action = rows[stack[-1]].get(ttype)
            if action is None:
                return None
            if isinstance(action, int):
                stack.append(action)
                return stack
            if action.size:
                del stack[-action.size :]
            if reduced is not None:
                reduced.append(action.origin)
            goto = gotos[stack[-1]][action.origin]
            stack.append(goto)
            if ttype == "$END" and goto == end_state:
                return stack


# ---------------------------------------------------------------- the shared instance

_grammar: Grammar | None = None
_lock = threading.Lock()


def grammar() -> Grammar:
    """The Grammar of grammar.lark with the AST builder, made on the first
    call and shared from then on (a cache: it never changes)."""
    global _grammar
    if _grammar is None:
        with _lock:
            if _grammar is None:
                _grammar = Grammar(load_st_grammar())
    return _grammar
