"""Syntax errors: the report, and the recovery that gets the parser going
again, so that one parse finds all the errors of a file.

At a token the table rejects (``_recover``), in this order:
  * the END_* of a block an earlier recovery dropped: skipped silently;
  * a known mistake (``_special_case``: '=' for ':=', ELSE after ELSE, a
    VAR block after the statements, a misplaced label or ACTION, METHOD ...): a tailored
    message and recovery;
  * one missing token (';', ',', THEN, END_IF, ...) that would let it fit:
    reported and inserted;
  * else panic mode (``_resync``): skip to a synchronising token (';',
    END_*, THEN, ...) and pop the stack until it fits.
Errors right after another one are its echoes and are not reported
(``calm``). At the end of the file, what is open is closed (``_finish``).
"""

from __future__ import annotations

import difflib
import re

from .. import ast
from ..limits import MAX_NESTING
from .lexer import Tok
from .parse_stack import ParserCore, Rejected
from .st_grammar import COLON, COMMA, SEMI

_FRIENDLY = {
    "NAME": "a name",
    "LABEL_NAME": "a name",
    "INT": "a number",
    "REAL": "a number",
    "BASED_INT": "a number",
    "C_HEX": "a number",
    "HASH_LIT": "a typed literal",
    "STRING_LIT": "a string",
    "WSTRING_LIT": "a string",
    "LOCATED": "a direct address",
    "BIT_REF": "a bit number",
    "S_ASSIGN": "S=",
    "R_ASSIGN": "R=",
    "REF_ASSIGN": "REF=",
    "QUERY_ASSIGN": "?=",
    "$END": "end of file",
}
# Block openers -> their closer, for "END_IF expected to close the IF at line 3".
_CLOSERS = {
    "IF": "END_IF",
    "CASE": "END_CASE",
    "FOR": "END_FOR",
    "WHILE": "END_WHILE",
    "REPEAT": "END_REPEAT",
    "PROGRAM": "END_PROGRAM",
    "FUNCTION": "END_FUNCTION",
    "FUNCTION_BLOCK": "END_FUNCTION_BLOCK",
    "TYPE": "END_TYPE",
    "STRUCT": "END_STRUCT",
    "CONFIGURATION": "END_CONFIGURATION",
    "RESOURCE": "END_RESOURCE",
    "METHOD": "END_METHOD",
    "PROPERTY": "END_PROPERTY",
    "INTERFACE": "END_INTERFACE",
    **dict.fromkeys(
        (
            "VAR",
            "VAR_INPUT",
            "VAR_OUTPUT",
            "VAR_IN_OUT",
            "VAR_GLOBAL",
            "VAR_EXTERNAL",
            "VAR_TEMP",
            "VAR_STAT",
            "VAR_CONFIG",
            "VAR_INST",
        ),
        "END_VAR",
    ),
}
_CLOSER_TYPES = frozenset(_CLOSERS.values())
_VAR_KINDS = frozenset(k for k, v in _CLOSERS.items() if v == "END_VAR")
# Tokens a broken region is skipped to before parsing resumes.
_SYNC = frozenset(
    [
        SEMI,
        "_ELSE",
        "ELSIF",
        "UNTIL",
        "THEN",
        "DO",
        "OF",
        "IF",
        "CASE",
        "FOR",
        "WHILE",
        "REPEAT",
        "EXIT",
        "CONTINUE",
        "RETURN",
        *_CLOSERS,
        *_CLOSERS.values(),
    ]
)
# Tokens tried as "the one that is missing", in this order.
_INSERTABLE = [
    SEMI,
    COMMA,
    "THEN",
    "DO",
    "OF",
    "RPAR",
    "RSQB",
    "END_IF",
    "END_CASE",
    "END_FOR",
    "END_WHILE",
    "END_VAR",
    "END_STRUCT",
    "END_TYPE",
    "END_FUNCTION_BLOCK",
    "END_FUNCTION",
    "END_PROGRAM",
    "END_RESOURCE",
    "END_CONFIGURATION",
]
# At the end of the file: closers first; ';' only when nothing else fits.
_CLOSING = [c for c in _INSERTABLE if c.startswith("END_")] + ["RPAR", "RSQB", SEMI, "THEN", "DO", "OF"]
_UNSUPPORTED = {
    "ACTION": "actions",  # ACTION where no action can stand: its own message below
    "END_ACTION": "actions",
    "NAMESPACE": "namespaces",
    "END_NAMESPACE": "namespaces",
    "VAR_ACCESS": "VAR_ACCESS blocks",
}


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

    def _special_case(self, tok: Tok, prev: Tok | None):
        """Errors with a known cause and a tailored recovery. Returns False
        when tok is not one of them, else what _recover returns."""
        value = tok.value.upper()
        if tok.type in ("_ELSE", "ELSIF"):
            for v in reversed(self.value_stack):
                if isinstance(v, Tok) and v.type in ("IF", "CASE", "_ELSE"):
                    if v.type != "_ELSE":
                        break
                    what = "duplicate ELSE" if tok.type == "_ELSE" else "ELSIF after ELSE"
                    self.report(
                        "E005", what, self._tok_pos(tok), f"the ELSE at line {v.line} must be the last branch", calm=1
                    )
                    # Drop it (and an ELSIF's condition): what follows joins the ELSE branch.
                    return self._skip_through("THEN") if tok.type == "ELSIF" else None
        if tok.type in _VAR_KINDS:
            opener = next(self._open_blocks(), None)
            if opener is not None and opener.type in ("PROGRAM", "FUNCTION", "FUNCTION_BLOCK"):
                self.report(
                    "E005",
                    f"{self.g.spelling(tok.type)} block after the statements",
                    self._tok_pos(tok),
                    "declare variables before the first statement of the POU",
                    calm=1,
                )
                return self._skip_through("END_VAR")
        if tok.type == "EQ" and "ASSIGN" in self._expected():
            self.report(
                "E001", "'=' compares; use ':=' to assign", self._tok_pos(tok), "':=' assigns, '=' compares", calm=1
            )
            assign = Tok("ASSIGN", ":=", tok.start_pos, tok.line, tok.column)
            assign.end_column = tok.end_column
            return self._feed_or_recover(assign)
        word = value if value in _UNSUPPORTED else None
        if word is None and prev is not None and prev.type == "NAME" and prev.value.upper() in _UNSUPPORTED:
            word = prev.value.upper()
        if word is not None:
            at = tok if word == value or prev is None else prev
            message, hint = (
                f"{word}: {_UNSUPPORTED[word]} are not supported",
                "write the logic as a FUNCTION or FUNCTION_BLOCK",
            )
            if word in ("ACTION", "END_ACTION"):
                message = f"{word} here: only a PROGRAM or FUNCTION_BLOCK has actions"
                hint = "write ACTION Name: ... END_ACTION after the POU's statements, or outside it as ACTION Pou.Name:"
            self.report("E001", message, self._tok_pos(at), hint, calm=1)
            self._unshift(prev if word != value else None)
            end = word if word.startswith("END_") else "END_" + word
            if word == end:
                return None
            return self._skip_through(end) if end in self.g.terminals else self._skip_through("NAME", end)
        if tok.type == "LABEL_NAME" and re.compile(r"\s*:").match(self.text, tok.end_pos):
            # In a statement list the lexer offers LABEL_NAME (a case label
            # could follow a statement), so 'lbl:' arrives as one.
            self.report(
                "E001",
                f"a label '{tok.value}:' cannot stand here",
                self._tok_pos(tok),
                "a jump label goes before a statement of a POU or ACTION",
                calm=1,
            )
            return self._skip_through(COLON)
        if prev is not None and prev.type == "NAME" and "ASSIGN" in self._expected():
            if prev.value.upper() == "JMP":
                self.report(
                    "E001", "JMP needs a label", self._tok_pos(prev), "write JMP name; to go on at 'name:'", calm=1
                )
                self._unshift(prev)
                return self._skip_through(SEMI)
            if tok.type == COLON:
                self.report(
                    "E001",
                    f"a label '{prev.value}:' cannot stand here",
                    self._tok_pos(prev),
                    "a jump label goes before a statement of a POU or ACTION",
                    calm=1,
                )
                self._unshift(prev)
                return None
        return False

    def _unshift(self, tok: Tok | None) -> None:
        """Take tok (just shifted) back off the stack."""
        values = self.value_stack
        if tok is not None and values and values[-1] is tok:
            values.pop()
            self.state_stack.pop()

    def _skip_through(self, ttype: str, value: str | None = None):
        """Drop tokens up to and including the first of type ttype (and
        value, upper-cased), then let parsing go on."""
        while True:
            t = self._next_token()
            if t.type == "$END":
                return self._finish(t)
            if t.type == ttype and (value is None or t.value.upper() == value):
                self.calm = 0  # a clean cut: what follows is new
                return None

    def _missing(self, cand: str, tok: Tok, prev: Tok | None) -> None:
        text = self.g.spelling(cand)
        if cand in _CLOSERS.values():
            opener = next((b for b in self._open_blocks() if _CLOSERS[b.type] == cand), None)
            where = f" to close the {opener.type} at line {opener.line}" if opener else ""
            self.report(
                "E001",
                f"{text} expected{where}, found {self._describe(tok)}",
                self._tok_pos(tok),
                f"add {text} before {self._describe(tok)}",
                calm=1,
            )
            return
        # Point at where the token is missing: just after the previous one.
        pos = self._pos_at(prev.end_line, prev.end_column) if prev is not None else self._tok_pos(tok)
        opener = next(self._open_blocks(), None)
        item = "declaration" if opener is not None and opener.type in ("TYPE", "STRUCT", *_VAR_KINDS) else "statement"
        hint = {SEMI: f"missing ';' after the {item}?", COMMA: "separate arguments, names and values with ','"}.get(
            cand
        )
        self.report("E001", f"missing '{text}' before {self._describe(tok)}", pos, hint, calm=1)

    def _eof_error(self) -> None:
        if self.comment_trouble:
            return  # the unterminated comment already explains it
        opener = next(self._open_blocks(), None)
        hint = (
            f"{_CLOSERS[opener.type]} expected to close the {opener.type} at line {opener.line}"
            if opener is not None
            else "the last statement is incomplete"
        )
        self.report("E001", "unexpected end of file", self._eof_pos(), hint)

    def _generic_error(self, tok: Tok, prev: Tok | None) -> None:
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
            shown = sorted(
                {
                    _FRIENDLY.get(t, self.g.spelling(t))
                    for t in expected
                    if t != "DOTDOT" and (not t.startswith("END_") or t == closer)
                }
            )
            if 0 < len(shown) <= 6:
                hint = "expected " + ", ".join(s if s.startswith("a ") else f"'{s}'" for s in shown)
        self.report("E001", f"unexpected {self._describe(tok)}", self._tok_pos(tok), hint, calm=3)

    def _did_you_mean(self, tok: Tok, prev: Tok | None) -> str | None:
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
        for lowest in (floor,) if bounded else (floor, 1):
            for depth in range(len(stack), lowest - 1, -1):
                if fits(depth):
                    for v in values[depth - 1 :]:
                        self._lost_opener(v)
                    del stack[depth:]
                    del values[depth - 1 :]
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
        for _ in range(MAX_NESTING):
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
