"""Structured Text source -> ``ast.SourceFile``: the parser's entry point.

    sf = parse_source(text, path, diags)

Never raises: every problem becomes a coded diagnostic in ``diags`` (E001
syntax, E002 invalid character, E003 invalid literal, E004 unterminated
comment/string/pragma, E005 structural, E009 internal; W101 ignored
EXTENDS/IMPLEMENTS) and the result holds whatever could be parsed.

How it works:
  1. lexer.strip_comments blanks out comments and pragmas, keeping every
     line and column; lexer.Lexer cuts the rest into tokens.
  2. The LALR(1) table comes from lark (grammar.lark, analysed once per
     process, on first use, through lark_adapter.py; st_grammar.py). The
     token loop is ours (``ParserCore``): it runs the table and calls the
     builder's rule methods (build_*.py), which build the ``ast`` nodes
     directly (no parse tree).
  3. A syntax error does not end the parse: ``Recovery`` inserts a missing
     token, handles a known mistake, or skips to a synchronising token
     (';', END_*, THEN, ...) and pops the stack until it fits.
  4. Pragmas are attached to the item that follows them (here).

Each parse has its own state (``_Parse``, its builder); the grammar is
shared and never changes, so files can be parsed in several threads.
"""
from __future__ import annotations

import difflib
import re
from bisect import bisect_left
from collections.abc import Iterator
from typing import Any, Optional

from . import ast
from .diagnostics import DiagnosticBag
from .lexer import INVALID_RUN, Tok, line_col, strip_comments
from .st_grammar import COLON, COMMA, SEMI, Grammar, grammar

__all__ = ["MAX_ERRORS", "parse_source"]

MAX_ERRORS = 100
# Nesting beyond this is refused (E005): later stages walk the tree
# recursively, and generated Python has limits of its own (100 levels of
# indentation, 200 nested parentheses). The parser stack grows by 1-4
# entries per nesting level (a parenthesis, a unary operator, IF in IF).
MAX_STACK = 300


class TooDeep(Exception):
    """The nesting limit (MAX_STACK) is reached; args: the token."""


class GiveUp(Exception):
    """MAX_ERRORS reported: the rest of the file is not worth reading."""


class Rejected(Exception):
    """The parser does not accept this token here."""


class ParserCore:
    """The state of one parse: stacks, tokens, reports."""

    def __init__(self, text: str, path: str, diags: DiagnosticBag, g: Grammar) -> None:
        self.g = g
        self.raw = text
        self.text = text             # with comments blanked (set by the driver)
        self.path = path
        self.diags = diags
        self.items: list = []        # nodes a pragma can attach to
        self.pou_headers: list = []  # (POU, start, header end)
        self.errors = 0
        self.calm = 0                # tokens to shift before the next error is reported
        self.comment_trouble = False
        self.skipping = False        # recovery is reading tokens: no parser context
        self.strays: dict = {}       # END_* whose block recovery dropped -> how many
        self.last: Tok | None = None
        self.state_stack = [g.start_state]
        self.value_stack: list = []
        self.tokens: Iterator[Tok] = iter(())
        self.builder: Any = g.builder(self)  # the AST builder (build_decls.AstBuilder)

    # -- diagnostics
    def report(self, code: str, message: str, pos: ast.Pos, hint: str | None = None,
               always: bool = False, calm: int = 0) -> None:
        """Add an error, unless it is an echo of the previous one (``always``
        overrides). ``calm``: errors at that many next tokens are echoes."""
        quiet = self.calm and not always
        self.calm = max(self.calm, calm)
        if quiet:
            return
        self.errors += 1
        if self.errors > MAX_ERRORS:
            raise GiveUp
        self.diags.error(code, message, pos, hint)

    def _pos_at(self, line: int, col: int, end_col: int = 0) -> ast.Pos:
        return ast.Pos(self.path, line, col, line, end_col or col + 1)

    def _tok_pos(self, t: Tok) -> ast.Pos:
        if t.type == "$END":
            return self._eof_pos()
        return ast.Pos(self.path, t.line, t.column, t.line, t.end_column)

    def _eof_pos(self) -> ast.Pos:
        line, col = line_col(self.raw, len(self.raw))
        return ast.Pos(self.path, line, col, line, col)

    # -- the stacks
    def _feed(self, token: Tok, is_end: bool = False) -> Any:
        """Shift the token, after the reductions it calls for (building their
        values), and return the value of the start rule if it ended the
        parse. LALR may reduce before it notices that the token does not fit
        (a statement list into a body, say); on rejection (``Rejected``)
        those reductions are taken back, so that recovery sees the stack as
        it was."""
        states, values = self.state_stack, self.value_stack
        rows, builder, end_state = self.g.rows, self.builder, self.g.end_state
        ttype = token.type
        undo = None
        while True:
            action: Any = rows[states[-1]].get(ttype)  # a state (int), a Reduce or None
            if action.__class__ is int:  # (the fastest test)
                states.append(action)
                values.append(token)
                return None
            if action is None:
                if undo:
                    self._undo(undo)
                raise Rejected
            size = action.size
            if size:
                children = values[-size:]
                del states[-size:]
                del values[-size:]
            else:
                children = []
            if undo is None:
                undo = []
            alias = action.alias
            undo.append((action, children) if alias is None else (action, children, len(children[alias])))
            build = action.build
            value = children[0] if build is None else build(builder, children)
            goto = rows[states[-1]][action.origin]
            states.append(goto)
            values.append(value)
            if is_end and goto == end_state:
                return value

    def _undo(self, undo: list) -> None:
        states, values, rows = self.state_stack, self.value_stack, self.g.rows
        for entry in reversed(undo):
            action, children = entry[0], entry[1]
            states.pop()
            values.pop()
            if len(entry) == 3:
                del children[action.alias][entry[2]:]
            for symbol in action.symbols:  # the states the children were shifted with
                states.append(rows[states[-1]][symbol])
            values.extend(children)

    def _synthetic(self, ttype: str, at: Tok, after: bool = True) -> Tok:
        """A token the parser is given by recovery, placed just after (or on) at."""
        t = Tok(ttype, self.g.spelling(ttype), at.end_pos if after else at.start_pos, at.line,
                at.end_column if after else at.column)
        t.end_column = t.column  # it takes no room in the text
        return t

    # -- tokens
    def _end_token(self) -> Tok:
        line, col = line_col(self.text, len(self.text))
        return Tok("$END", "", len(self.text), line, col)

    def _next_token(self) -> Tok:
        """The next token, read without parser context (while skipping)."""
        self.skipping = True
        try:
            tok = next(self.tokens, None)
        finally:
            self.skipping = False
        if tok is None:
            return self._end_token()
        self.last = tok
        return tok


# ---------------------------------------------------------------- error recovery

_FRIENDLY = {"NAME": "a name", "LABEL_NAME": "a name", "INT": "a number", "REAL": "a number",
             "BASED_INT": "a number", "C_HEX": "a number", "HASH_LIT": "a typed literal",
             "STRING_LIT": "a string", "WSTRING_LIT": "a string", "LOCATED": "a direct address",
             "BIT_REF": "a bit number", "S_ASSIGN": "S=", "R_ASSIGN": "R=", "REF_ASSIGN": "REF=",
             "$END": "end of file"}
# Block openers -> their closer, for "END_IF expected to close the IF at line 3".
_CLOSERS = {"IF": "END_IF", "CASE": "END_CASE", "FOR": "END_FOR", "WHILE": "END_WHILE",
            "REPEAT": "END_REPEAT", "PROGRAM": "END_PROGRAM", "FUNCTION": "END_FUNCTION",
            "FUNCTION_BLOCK": "END_FUNCTION_BLOCK", "TYPE": "END_TYPE", "STRUCT": "END_STRUCT",
            "CONFIGURATION": "END_CONFIGURATION", "RESOURCE": "END_RESOURCE",
            **{k: "END_VAR" for k in ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_GLOBAL",
                                      "VAR_EXTERNAL", "VAR_TEMP", "VAR_STAT", "VAR_CONFIG")}}
_CLOSER_TYPES = frozenset(_CLOSERS.values())
_VAR_KINDS = frozenset(k for k, v in _CLOSERS.items() if v == "END_VAR")
# Tokens a broken region is skipped to before parsing resumes.
_SYNC = frozenset([SEMI, "_ELSE", "ELSIF", "UNTIL", "THEN", "DO", "OF", "IF", "CASE", "FOR", "WHILE",
                   "REPEAT", "EXIT", "CONTINUE", "RETURN", *_CLOSERS, *_CLOSERS.values()])
# Tokens tried as "the one that is missing", in this order.
_INSERTABLE = [SEMI, COMMA, "THEN", "DO", "OF", "RPAR", "RSQB", "END_IF", "END_CASE", "END_FOR",
               "END_WHILE", "END_VAR", "END_STRUCT", "END_TYPE", "END_FUNCTION_BLOCK", "END_FUNCTION",
               "END_PROGRAM", "END_RESOURCE", "END_CONFIGURATION"]
# At the end of the file: closers first; ';' only when nothing else fits.
_CLOSING = [c for c in _INSERTABLE if c.startswith("END_")] + ["RPAR", "RSQB", SEMI, "THEN", "DO", "OF"]
_UNSUPPORTED = {"METHOD": "methods", "END_METHOD": "methods", "PROPERTY": "properties",
                "END_PROPERTY": "properties", "INTERFACE": "interfaces", "END_INTERFACE": "interfaces",
                "ACTION": "actions", "END_ACTION": "actions", "NAMESPACE": "namespaces",
                "END_NAMESPACE": "namespaces", "VAR_ACCESS": "VAR_ACCESS blocks"}

def _is_bare(value) -> bool:
    """A parser stack value that is a name or expression but not a call:
    followed by ';' it would make a bogus call statement."""
    return isinstance(value, Tok) or (isinstance(value, ast.Expr) and not isinstance(value, ast.Call))


class Recovery(ParserCore):
    """Error reports and recovery, on the parser's stacks."""

    def _feed_or_recover(self, tok: Tok):
        """Feed one token outside the main loop; returns the parse result
        if tok ended the file."""
        try:
            result = self._feed(tok, tok.type == "$END")
        except Rejected:
            return self._recover(tok)
        self.last = tok
        if self.calm:
            self.calm -= 1
        return result

    def _open_blocks(self, with_index: bool = False):
        """Unclosed block keywords on the parser stack, innermost first (with
        their index in the value stack if asked). A block whose END_* is
        already there (END_PROGRAM waiting for an optional ';') is closed."""
        values = self.value_stack
        closed = []
        for i in range(len(values) - 1, -1, -1):
            v = values[i]
            if isinstance(v, Tok):
                if v.type in _CLOSER_TYPES:
                    closed.append(v.type)
                elif v.type in _CLOSERS:
                    if closed and closed[-1] == _CLOSERS[v.type]:
                        closed.pop()
                    else:
                        yield (i, v) if with_index else v

    def _expected(self) -> set:
        """The token types that fit here. Not just the row's keys: LALR
        merges states, so a row may offer tokens a later state refuses."""
        stack = self.state_stack
        return {t for t in self.g.rows[stack[-1]] if t.isupper() and self.g.simulate(stack, t) is not None}

    def _describe(self, tok: Tok) -> str:
        if tok.type == "$END":
            return "end of file"
        if tok.type in self.g.keyword_terminals:
            return tok.value.upper()
        return f"'{tok.value}'"

    def _recover(self, tok: Tok):
        """Report the error at tok and get the parser going again: a special
        case, one inserted token, or skipping to a synchronising token.
        Returns the parse result when recovery reached the end of the file."""
        prev = self.last
        if tok.type == "$END":
            self._eof_error()
            return self._finish(tok)
        if self.strays.get(tok.type):
            self.strays[tok.type] -= 1  # the END_* of a block lost in an earlier error
            return None
        special = self._special_case(tok, prev)
        if special is not False:
            return special
        for cand in self._insertable(tok):
            self._missing(cand, tok, prev)
            self._feed(self._synthetic(cand, prev) if prev is not None else self._synthetic(cand, tok, after=False))
            return self._feed_or_recover(tok)
        self._generic_error(tok, prev)
        return self._resync(tok)

    def _insertable(self, tok: Tok):
        """The token types whose insertion before tok would let it fit."""
        stack = self.state_stack
        for cand in _INSERTABLE:
            after = self.g.simulate(stack, cand)
            reduced: list = []
            if after is None or self.g.simulate(after, tok.type, reduced) is None:
                continue
            # 'x y := 1': not "missing ';'" after a name that cannot be a statement.
            if cand == SEMI and "call_stmt" in reduced and self.value_stack and _is_bare(self.value_stack[-1]):
                continue
            yield cand
            return

    def _special_case(self, tok: Tok, prev: Optional[Tok]):
        """Errors with a known cause and a tailored recovery. Returns False
        when tok is not one of them, else what _recover returns."""
        value = tok.value.upper()
        if tok.type in ("_ELSE", "ELSIF"):
            for v in reversed(self.value_stack):
                if isinstance(v, Tok) and v.type in ("IF", "CASE", "_ELSE"):
                    if v.type != "_ELSE":
                        break
                    what = "duplicate ELSE" if tok.type == "_ELSE" else "ELSIF after ELSE"
                    self.report("E005", what, self._tok_pos(tok), f"the ELSE at line {v.line} must be the last branch", calm=1)
                    # Drop it (and an ELSIF's condition): what follows joins the ELSE branch.
                    return self._skip_through("THEN") if tok.type == "ELSIF" else None
        if tok.type in _VAR_KINDS:
            opener = next(self._open_blocks(), None)
            if opener is not None and opener.type in ("PROGRAM", "FUNCTION", "FUNCTION_BLOCK"):
                self.report("E005", f"{self.g.spelling(tok.type)} block after the statements", self._tok_pos(tok),
                            "declare variables before the first statement of the POU", calm=1)
                return self._skip_through("END_VAR")
        if tok.type == "EQ" and "ASSIGN" in self._expected():
            self.report("E001", "'=' compares; use ':=' to assign", self._tok_pos(tok), "':=' assigns, '=' compares", calm=1)
            assign = Tok("ASSIGN", ":=", tok.start_pos, tok.line, tok.column)
            assign.end_column = tok.end_column
            return self._feed_or_recover(assign)
        word = value if value in _UNSUPPORTED else None
        if word is None and prev is not None and prev.type == "NAME" and prev.value.upper() in _UNSUPPORTED:
            word = prev.value.upper()
        if word is not None:
            at = tok if word == value else prev
            self.report("E001", f"{word}: {_UNSUPPORTED[word]} are not supported", self._tok_pos(at),
                        "write the logic as a FUNCTION or FUNCTION_BLOCK", calm=1)
            self._unshift(prev if word != value else None)
            end = word if word.startswith("END_") else "END_" + word
            return self._skip_through("NAME", end) if word != end else None
        if tok.type == "LABEL_NAME" and re.compile(r"\s*:").match(self.text, tok.end_pos):
            # In a statement list the lexer offers LABEL_NAME (a case label
            # could follow a statement), so 'lbl:' arrives as one.
            self.report("E001", f"label '{tok.value}:' is not supported", self._tok_pos(tok),
                        "JMP and labels are not supported; use a loop or CASE", calm=1)
            return self._skip_through(COLON)
        if prev is not None and prev.type == "NAME" and "ASSIGN" in self._expected():
            if prev.value.upper() == "JMP":
                self.report("E001", "JMP is not supported", self._tok_pos(prev),
                            "JMP and labels are not supported; use a loop or CASE", calm=1)
                self._unshift(prev)
                return self._skip_through(SEMI)
            if tok.type == COLON:
                self.report("E001", f"label '{prev.value}:' is not supported", self._tok_pos(prev),
                            "JMP and labels are not supported; use a loop or CASE", calm=1)
                self._unshift(prev)
                return None
        return False

    def _unshift(self, tok: Optional[Tok]) -> None:
        """Take tok (just shifted) back off the stack."""
        values = self.value_stack
        if tok is not None and values and values[-1] is tok:
            values.pop()
            self.state_stack.pop()

    def _skip_through(self, ttype: str, value: Optional[str] = None):
        """Drop tokens up to and including the first of type ttype (and
        value, upper-cased), then let parsing go on."""
        while True:
            t = self._next_token()
            if t.type == "$END":
                return self._finish(t)
            if t.type == ttype and (value is None or t.value.upper() == value):
                self.calm = 0  # a clean cut: what follows is new
                return None

    def _missing(self, cand: str, tok: Tok, prev: Optional[Tok]) -> None:
        text = self.g.spelling(cand)
        if cand in _CLOSERS.values():
            opener = next((b for b in self._open_blocks() if _CLOSERS[b.type] == cand), None)
            where = f" to close the {opener.type} at line {opener.line}" if opener else ""
            self.report("E001", f"{text} expected{where}, found {self._describe(tok)}", self._tok_pos(tok),
                        f"add {text} before {self._describe(tok)}", calm=1)
            return
        # Point at where the token is missing: just after the previous one.
        pos = self._pos_at(prev.end_line, prev.end_column) if prev is not None else self._tok_pos(tok)
        opener = next(self._open_blocks(), None)
        item = "declaration" if opener is not None and opener.type in ("TYPE", "STRUCT", *_VAR_KINDS) else "statement"
        hint = {SEMI: f"missing ';' after the {item}?",
                COMMA: "separate arguments, names and values with ','"}.get(cand)
        self.report("E001", f"missing '{text}' before {self._describe(tok)}", pos, hint, calm=1)

    def _eof_error(self) -> None:
        if self.comment_trouble:
            return  # the unterminated comment already explains it
        opener = next(self._open_blocks(), None)
        hint = (f"{_CLOSERS[opener.type]} expected to close the {opener.type} at line {opener.line}"
                if opener is not None else "the last statement is incomplete")
        self.report("E001", "unexpected end of file", self._eof_pos(), hint)

    def _generic_error(self, tok: Tok, prev: Optional[Tok]) -> None:
        expected = self._expected()
        hint = None
        if tok.type in _CLOSERS.values() or tok.type in ("_ELSE", "ELSIF"):
            opener = next(self._open_blocks(), None)
            if opener is not None:
                hint = f"{_CLOSERS[opener.type]} expected to close the {opener.type} at line {opener.line}"
        if hint is None:
            hint = self._did_you_mean(tok, prev)
        if hint is None and self._between_pous():
            hint = "outside a POU: PROGRAM, FUNCTION, FUNCTION_BLOCK, TYPE, VAR_GLOBAL or CONFIGURATION"
        if hint is None and {"INT", "NAME", "LPAR", "NOT"} <= expected:
            hint = "an expression (a value or a variable) is missing here"
        if hint is None and {"ARRAY", "STRING", "NAME"} <= expected:
            hint = "a type (INT, STRING[20], ARRAY[1..3] OF REAL, a type name, ...) is missing here"
        if hint is None:
            # Only the closer of the innermost block (the table merges states
            # of VAR and STRUCT, say, and offers both END_VAR and END_STRUCT).
            opener = next(self._open_blocks(), None)
            closer = _CLOSERS[opener.type] if opener is not None else None
            # ('..' is not listed: the hints never offered it.)
            shown = sorted({_FRIENDLY.get(t, self.g.spelling(t)) for t in expected
                            if t != "DOTDOT" and (not t.startswith("END_") or t == closer)})
            if 0 < len(shown) <= 6:
                hint = "expected " + ", ".join(s if s.startswith("a ") else f"'{s}'" for s in shown)
        self.report("E001", f"unexpected {self._describe(tok)}", self._tok_pos(tok), hint, calm=3)

    def _did_you_mean(self, tok: Tok, prev: Optional[Tok]) -> Optional[str]:
        """A misspelt keyword (ELSEIF, ENDIF, VAR_INPUTS) lexes as a name."""
        for t in (tok, prev):
            if t is not None and t.type == "NAME" and len(t.value) > 2:
                close = difflib.get_close_matches(t.value.upper(), self.g.keywords, n=1, cutoff=0.8)
                if close and close[0] != t.value.upper():
                    # A misspelt FOR leaves its END_FOR without a block.
                    self._lost_opener(Tok(self.g.lexer.keywords[close[0]], close[0], 0, 0, 0))
                    return f"did you mean {close[0]}?"
        return None

    def _resync(self, tok: Tok):
        """Panic mode: skip to a synchronising token, pop the parser stack
        until that token fits, feed it. tok is the offending token.
        Errors on the next tokens are echoes of this one: ``calm``."""
        while True:
            if tok.type == "$END":
                return self._finish(tok)
            if tok.type == SEMI and not self._between_pous():
                # The end of the broken statement or declaration: recover
                # within the innermost open block, where the ';' ends what
                # was parsed, or else by dropping the broken item with it.
                if self._pop_for(tok, bounded=True, fits=self._semicolon_ends_item):
                    self.calm = 0  # a clean cut: what follows is new
                    return self._feed_or_recover(tok)
                if self._pop_to_item_boundary():
                    self.calm = 0
                    return None
            elif tok.type in _SYNC and self._pop_for(tok):
                self.calm = 3
                return self._feed_or_recover(tok)
            self._lost_opener(tok)
            tok = self._next_token()

    def _between_pous(self) -> bool:
        """Is the broken part outside any POU, where ';' ends nothing (in a
        file of POUs, not of bare statements)? Then recovery waits for the
        next PROGRAM, FUNCTION, TYPE, VAR_GLOBAL ..."""
        if next(self._open_blocks(), None) is not None:
            return False
        stack = self.state_stack
        for depth in range(len(stack), 0, -1):
            if self.g.simulate(stack[:depth], "$END") is not None:
                return self.g.simulate(stack[:depth], "PROGRAM") is not None
        return False

    def _semicolon_ends_item(self, depth: int) -> bool:
        """Would ';' at this stack depth end a statement or declaration, not
        make an empty statement, nor a lone name into a call statement?"""
        after = self.g.simulate(self.state_stack[:depth], SEMI)
        if after is None:
            return False
        reduced: list = []
        self.g.simulate(after, "NAME", reduced)  # a statement may follow: what does ';' complete?
        if "empty_stmt" in reduced:
            return False
        return not ("call_stmt" in reduced and depth >= 2 and _is_bare(self.value_stack[depth - 2]))

    def _pop_to_item_boundary(self) -> bool:
        """Pop what was parsed of the current item (declaration, statement)
        of the innermost block: to where the block's closer would fit."""
        opener = next(self._open_blocks(), None)
        if opener is None:  # top level, or a file of bare statements
            closer = "$END"
        else:
            closer = "UNTIL" if opener.type == "REPEAT" else _CLOSERS[opener.type]
        return self._pop_for(Tok(closer, closer, 0, 0, 0), bounded=True)

    def _pop_for(self, tok: Tok, bounded: bool = False, fits=None) -> bool:
        """Pop the fewest states so that tok is accepted (or fits(depth)
        says yes), first without leaving the innermost open block, then
        (unless bounded) anywhere. False if it fits nowhere (the stack is
        then unchanged)."""
        stack, values = self.state_stack, self.value_stack
        if fits is None:
            def fits(depth):
                return self.g.simulate(stack[:depth], tok.type) is not None
        innermost = next(self._open_blocks(with_index=True), None)
        # stack[i + 1] is the state after the opener values[i]: keep it.
        floor = innermost[0] + 2 if innermost is not None else 1
        for lowest in ((floor,) if bounded else (floor, 1)):
            for depth in range(len(stack), lowest - 1, -1):
                if fits(depth):
                    for v in values[depth - 1:]:
                        self._lost_opener(v)
                    del stack[depth:]
                    del values[depth - 1:]
                    return True
        return False

    def _lost_opener(self, tok) -> None:
        """A block keyword dropped by recovery: its END_* will come without
        it and is then not worth another error."""
        if isinstance(tok, Tok) and tok.type in _CLOSERS:
            closer = _CLOSERS[tok.type]
            self.strays[closer] = self.strays.get(closer, 0) + 1

    def _finish(self, end: Tok):
        """At the end of the file: close what is open by inserting the
        missing closers (already reported), or else drop the unfinished
        part; then accept."""
        stack = self.state_stack
        previous = None
        for _ in range(MAX_STACK):
            if self.g.simulate(stack, "$END") is not None:
                break
            # Closers first; ';' (always welcome in a statement list) only
            # when nothing else fits, and never twice in a row.
            cand = next((c for c in _CLOSING if c != previous and self.g.simulate(stack, c) is not None), None)
            if cand is None:
                break
            self._feed(self._synthetic(cand, end, after=False))
            previous = cand
        if self.g.simulate(stack, "$END") is None:
            self._pop_for(end)
        return self._feed(end, True)


# ---------------------------------------------------------------- one parse

class _Parse(Recovery):
    """One run of the parser over one file."""

    def run(self) -> ast.SourceFile:
        if self.raw.startswith("\ufeff"):
            self.raw = self.raw[1:]  # a BOM: editors do not show it as a column
        text = self.raw

        def comment_error(code, message, start, end, hint):
            self.comment_trouble = self.comment_trouble or code == "E004"
            self.report(code, message, ast.Pos(self.path, *line_col(text, start), *line_col(text, end)),
                        hint, always=True)

        self.text, pragmas = strip_comments(text, comment_error)
        self.tokens = self.g.lexer.tokens(self.text, self._accepts, self._bad_characters)
        try:
            result = self._drive()
        except GiveUp:
            self.diags.error("E001", f"too many errors; stopped after {MAX_ERRORS}", self._eof_pos())
            result = None
        except TooDeep as e:
            self.report("E005", "nesting too deep", self._tok_pos(e.args[0]),
                        "split the expression or statement into smaller parts", always=True)
            result = None
        if not isinstance(result, ast.SourceFile):
            result = ast.SourceFile(self.path, [], pos=ast.Pos(self.path, 1, 1))
        if pragmas:
            self._attach(pragmas)
        return result

    def _accepts(self) -> Optional[dict]:
        return None if self.skipping else self.g.rows[self.state_stack[-1]]

    def _drive(self):
        feed, stack = self._feed, self.state_stack
        for tok in self.tokens:
            try:
                feed(tok)
            except Rejected:
                result = self._recover(tok)
                if result is not None:
                    return result
                continue
            self.last = tok
            if self.calm:
                self.calm -= 1
            if len(stack) > MAX_STACK:
                raise TooDeep(tok)
        return self._feed_or_recover(self._end_token())

    def _bad_characters(self, offset: int, line: int, col: int) -> tuple:
        """The lexer is stuck at offset: an unterminated string, or characters
        no token starts with. Returns (offset to go on from, token or None)."""
        text = self.text
        ch = text[offset]
        if ch in "'\"":
            # Take the string to the end of the line (but leave a final ';'
            # alone) and go on as if it were closed.
            nl = text.find("\n", offset)
            rest = text[offset:len(text) if nl < 0 else nl].rstrip()
            if rest.endswith(";") and len(rest) > 1:
                rest = rest[:-1].rstrip()
            self.report("E004", "unterminated string", self._pos_at(line, col, col + len(rest)),
                        f"close it with {ch} on the same line; inside a string write {ch} as ${ch}",
                        always=True, calm=2)  # the rest of the line is guesswork
            kind = "WSTRING_LIT" if ch == '"' else "STRING_LIT"
            tok = Tok(kind, rest + ch, offset, line, col)
            tok.end_column = col + len(rest)
            return offset + len(rest), tok
        m = INVALID_RUN.match(text, offset)
        run = m.group() if m else ch
        if ch == "%":
            message, hint = "invalid direct address", "direct addresses look like %IX0.1, %QW4, %MD3200, %MW3250:X0"
        elif ch == "#":
            message, hint = "unexpected '#'", "typed literals are written without spaces: INT#5, T#1s, Color#Red"
        elif not run[0].isascii():
            message = f"invalid character '{run[0]}'"
            hint = ("identifiers may only use ASCII letters, digits and '_'" if run[0].isalpha()
                    else "only ASCII is allowed outside strings and comments")
        else:
            message, hint = f"invalid character {run[0]!r}", None
        if not self.skipping:
            self.report("E002", message, self._pos_at(line, col, col + len(run)), hint, calm=3)
        return offset + len(run), None

    # -- pragmas
    def _attach(self, pragmas: list) -> None:
        """Each pragma goes to the item (POU, type, variable block or
        declaration, statement) that follows it; one between a POU's name
        and its first declaration goes to the POU ({external}, attributes)."""
        items = sorted(self.items, key=lambda n: (n.pos.line, n.pos.col))
        starts = [(n.pos.line, n.pos.col) for n in items]
        for p in pragmas:
            end = (p.end_line, p.end_col)
            target = None
            for pou, start, header_end in self.pou_headers:
                if start < end <= header_end:
                    target = pou
                    break
            if target is None:
                i = bisect_left(starts, end)
                if i == len(items):
                    continue  # nothing follows: a trailing pragma has no item
                target = items[i]
            target.pragmas.append(p.text)
            if isinstance(target, ast.POU) and p.text.lower() == "external":
                target.external = True


def parse_source(text: str, path: str, diags: DiagnosticBag) -> ast.SourceFile:
    """Parse one ST file into an ``ast.SourceFile``. Never raises; every
    problem goes into diags."""
    try:
        return _Parse(text, path, diags, grammar()).run()
    except Exception as e:  # a bug here must not become a traceback for the user
        diags.error("E009", f"internal parser error: {type(e).__name__}: {e}", ast.Pos(str(path), 1, 1),
                    "please report this with the source file")
        return ast.SourceFile(str(path), [], pos=ast.Pos(str(path), 1, 1))
