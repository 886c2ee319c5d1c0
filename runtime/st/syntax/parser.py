"""Structured Text source -> ``ast.SourceFile``: the parser's entry point.

    sf = parse_source(text, path, diags)               # as the default profile
    sf = parse_source(text, path, diags, profile)      # as another one

Never raises: every problem becomes a coded diagnostic in ``diags`` (E001
syntax, E002 invalid character, E003 invalid literal, E004 unterminated
comment/string/pragma, E005 structural, E006 nested too deeply, E007 file
too large, E008 comments nested too deeply, E009 internal, E047 an
ACTION named Pou.Name inside a POU; W102
ignored MatIEC embedded C {{ }}, W103 an attribute accepted but not
honoured: pragmas.py) and
the result holds whatever could be parsed.

How it works:
  1. lexer.strip_comments blanks out comments and pragmas, keeping every
     line and column (whether (* *) comments nest is the profile's
     choice); lexer.Lexer cuts the rest into tokens. Where that
     text does not parse and holds IL bodies, it is read again with
     them lowered to ST on their own lines first (il.py).
  2. The LALR(1) table comes from lark (grammar.lark, analysed once per
     process, on first use, through lark_adapter.py; st_grammar.py). The
     token loop is ours (parse_stack.py): it runs the table and calls the
     builder's rule methods (build_*.py), which build the ``ast`` nodes
     directly (no parse tree).
  3. A syntax error does not end the parse: parse_recovery.py inserts a
     missing token, handles a known mistake, or skips to a synchronising
     token (';', END_*, THEN, ...) and pops the stack until it fits.
  4. Pragmas are attached to the item that follows them (here).

Each parse has its own state (``_Parse``, its builder); the grammar is
shared and never changes, so files can be parsed in several threads.
"""

from __future__ import annotations

from bisect import bisect_left

from .. import ast
from ..diagnostics import DiagnosticBag
from ..limits import MAX_ERRORS, MAX_NESTING, MAX_SOURCE_CHARS
from ..profile import DEFAULT, Profile
from .lexer import INVALID_RUN, Tok, line_col, strip_comments
from .parse_recovery import Recovery
from .parse_stack import GiveUp, Rejected, TooDeep
from .pragmas import warn_ignored
from .st_grammar import Grammar, grammar

__all__ = ["MAX_ERRORS", "parse_source"]


class _Parse(Recovery):
    """One run of the parser over one file."""

    def __init__(
        self,
        text: str,
        path: str,
        diags: DiagnosticBag,
        g: Grammar,
        profile: Profile = DEFAULT,
        origins: tuple = (),
        il: bool = False,
    ) -> None:
        super().__init__(text, path, diags, g)
        self.profile = profile
        self.origins = origins
        self.il = il  # lower IL bodies first (il.py)
        self.text = ""  # the text the tokens come from: comments blanked (IL lowered)

    def run(self) -> ast.SourceFile:
        if self.raw.startswith("\ufeff"):
            self.raw = self.raw[1:]  # a BOM: editors do not show it as a column
        text = self.raw

        def comment_error(code, message, start, end, hint):
            self.comment_trouble = self.comment_trouble or code == "E004"
            self.report(
                code, message, ast.Pos(self.path, *line_col(text, start), *line_col(text, end)), hint, always=True
            )

        if len(text) > MAX_SOURCE_CHARS:
            where = ast.Pos(self.path, *line_col(text, MAX_SOURCE_CHARS))
            self.diags.error(
                "E007",
                f"the file is too large: more than {MAX_SOURCE_CHARS:,} characters",
                where,
                "split it into several files; the part past this point is not read",
            )
            return ast.SourceFile(self.path, [], pos=ast.Pos(self.path, 1, 1))
        pragmas: list = []
        il_ranges: list = []
        il_where: dict = {}
        try:
            self.text, pragmas = strip_comments(text, comment_error, self.profile.nested_comments)
            if self.il:
                from .il import lower_il  # (IL's modules only for a file that has it: 11 ms of every start)

                self.text, il_ranges, il_where = lower_il(self.text, self.path, self.diags, self.g.lexer)
            self.tokens = self.g.lexer.tokens(self.text, self._accepts, self._bad_characters, self._fits)
            if self.origins:
                self.tokens = _relocated(self.tokens, self.origins)
            result = self._drive()
        except GiveUp:
            self.diags.error("E001", f"too many errors; stopped after {MAX_ERRORS}", self._eof_pos())
            result = None
        except TooDeep as e:
            self.report(
                "E006",
                f"nested too deeply (more than {MAX_NESTING} levels of the parser)",
                self._tok_pos(e.args[0]),
                "split the expression or statement into smaller parts, with intermediate variables",
                always=True,
            )
            result = None
        if not isinstance(result, ast.SourceFile):
            result = ast.SourceFile(self.path, [], pos=ast.Pos(self.path, 1, 1))
        result.lowered.extend(il_ranges)
        if il_where:
            from .il import relocate

            relocate(result, il_where)
        if pragmas:
            warn_ignored(pragmas, self.path, self.diags)
            self._attach(pragmas)
        return result

    def _accepts(self) -> dict | None:
        return None if self.skipping else self.g.rows[self.state_stack[-1]]

    def _fits(self, ttype: str) -> bool:
        return self.g.simulate(self.state_stack, ttype) is not None

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
            if len(stack) > MAX_NESTING:
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
            rest = text[offset : len(text) if nl < 0 else nl].rstrip()
            if rest.endswith(";") and len(rest) > 1:
                rest = rest[:-1].rstrip()
            self.report(
                "E004",
                "unterminated string",
                self._pos_at(line, col, col + len(rest)),
                f"close it with {ch} on the same line; inside a string write {ch} as ${ch}",
                always=True,
                calm=2,
            )  # the rest of the line is guesswork
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
            hint = (
                "identifiers may only use ASCII letters, digits and '_'"
                if run[0].isalpha()
                else "only ASCII is allowed outside strings and comments"
            )
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


def _has_il(text: str) -> bool:
    from .il import has_il

    return has_il(text)


def _relocated(tokens, origins: tuple):
    """The tokens, those an importer placed apart from where they come from
    at their origin (StView.origins: (line, column, orig_line, orig_column),
    sorted: a token at or after (line, column) and before the next is at
    orig_column + its offset from column on orig_line)."""
    starts = [(o[0], o[1]) for o in origins]
    for tok in tokens:
        i = bisect_left(starts, (tok.line, tok.column + 1)) - 1
        if i >= 0 and origins[i][0] == tok.line:
            _, col, oline, ocol = origins[i]
            tok.line, tok.column = oline, ocol + tok.column - col
            tok.end_column = tok.column + len(tok.value)
        yield tok


def parse_source(
    text: str, path: str, diags: DiagnosticBag, profile: Profile = DEFAULT, lowered: tuple | list = (), origins=()
) -> ast.SourceFile:
    """Parse one ST file into an ``ast.SourceFile`` as the profile reads ST
    (its comments). Never raises; every problem goes into diags.
    lowered: (first, last) line ranges whose ST an importer wrote from
    another language (``SourceFile.lowered``); origins: where pieces of
    such ST come from (StView.origins), for the tokens' positions."""
    try:
        if "\r" in text:  # CR, LF and CRLF each end one line (a CR-only file, a mixed one)
            text = text.replace("\r\n", "\n").replace("\r", "\n")
        # A file is read as ST first: IL (il.py) is looked for only when
        # that fails, for IL is never valid ST, so a file without IL costs
        # nothing more; one with IL is read twice.
        g, attempt = grammar(), DiagnosticBag()
        first = _Parse(text, path, attempt, g, profile, tuple(origins))
        sf = first.run()
        if attempt.has_errors and _has_il(first.text):
            sf = _Parse(text, path, diags, g, profile, tuple(origins), il=True).run()
        else:
            diags.extend(attempt.items)
        sf.lowered.extend(lowered)
        return sf
    except Exception as e:  # a bug here must not become a traceback for the user
        diags.error(
            "E009",
            f"internal parser error: {type(e).__name__}: {e}",
            ast.Pos(str(path), 1, 1),
            "please report this with the source file",
        )
        return ast.SourceFile(str(path), [], pos=ast.Pos(str(path), 1, 1))
