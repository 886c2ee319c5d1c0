"""Coded compiler diagnostics: file:line:column, message, source excerpt with a
caret, and a hint. Every stage collects them instead of raising, so all the
errors of a file are reported in one run.

Code ranges (keep them stable, users search for them):
  E000       a file that cannot be read
  E001-E005  lexical and syntax (parser)
  E006-E008  limits (limits.py): E006 expressions and statements nested too
             deeply (parser, checker, or the Python compiler), E007 a source
             file too large, E008 comments nested too deeply
  E009       internal error (a bug in softplc; the input is reported, not lost)
  E010-E019  names and declarations (E014: a STRUCT or FUNCTION_BLOCK that
             contains itself; E018 a qualified_only list's variable without
             its list, E019 a namespace or list problem: namespaces.py)
  E020-E029  types and conversions
  E030-E039  assignment targets (E032: an assignment used as a value)
  E040-E049  calls (E044: a comma ending an argument list, where the profile
             does not take it)
  E050-E059  arrays, indices, bit access (E054, E055: the element limits of
             one variable and of all, limits.py)
  E060-E069  CASE
  E070-E079  control flow
  E080-E089  direct (located) addresses
  E090-E099  configuration, resources, tasks (E094: a VAR_CONFIG path)
  E140-E149  object-oriented ST (checker_oop.py): EXTENDS/IMPLEMENTS, members,
             ABSTRACT, FINAL, access, interfaces, THIS/SUPER, PROPERTY, FB_init
  E150-E159  SFC (st/check/checker_sfc.py); W150 a step no transition reaches
  E160-E162  references and pointers (checker_refs.py, checker_pointers.py,
             sizes.py): E160 a reference to a REFERENCE TO, E161 pointer
             arithmetic not supported, E162 SIZEOF without a size
  E170-E174  object-oriented ST, continued: E170 FB_init inputs set where an
             instance is declared (checker_fbinit.py)
  E180-E189  imported files (st/importers/): E180 XML not well-formed, E181
             refused XML, E182 a language or object not imported, E183 an
             element that cannot become ST, E184-E189 the project's structure
  E190-E199  IL, instruction list (st/syntax/il.py)
  E200-E209  FBD and LD networks (st/importers/: graphical bodies)
  E210-E219  graphical SFC (st/importers/sfc*.py); W210, W212 what CODESYS
             writes beside TC6 about an SFC and softplc does not honour
             (step time limits, SFC flags)
  E220-E229  projects as a whole (check of a project: libraries, entries)
  E230-E239  the libraries softplc ships (program/shipped.py, fblocks/libs):
             W230 one that cannot do its work here (hardware, a service)
  W1xx       warnings (same tens as the error they soften: W113 ~ E013,
             W121 ~ E021, W122 ~ E022, W130 ~ E030 where the profile allows what IEC
             forbids; W102-W103 the parser: W102 MatIEC embedded C, W103 an
             attribute not honoured, pragmas.py)
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass, field

from .ast import Pos

ERROR = "error"
WARNING = "warning"


@dataclass(slots=True)
class Diagnostic:
    code: str
    message: str
    pos: Pos
    hint: str | None = None
    severity: str = ERROR

    @property
    def is_error(self) -> bool:
        return self.severity == ERROR

    def format(self, sources: SourceSet | None = None) -> str:
        head = f"{self.pos.file}:{self.pos.line}:{self.pos.col}: {self.severity} {self.code}: {self.message}"
        lines = [head]
        text = sources.line(self.pos.file, self.pos.line) if sources else None
        if text is not None:
            shown = text.expandtabs(1).rstrip("\n")
            start = max(self.pos.col, 1)
            if self.pos.end_line == self.pos.line and self.pos.end_col > start:
                width = self.pos.end_col - start
            else:
                width = 1
            width = max(1, min(width, max(1, len(shown) - start + 1)))
            shown, start, width = _excerpt(shown, start, width)
            lines.append(f"    {shown}")
            lines.append("    " + " " * (start - 1) + "^" * width)
        if self.hint:
            lines.append(f"    hint: {self.hint}")
        return "\n".join(lines)


EXCERPT = 120  # characters of a long source line shown around the column
#: the errors of one file a message shows (a configuration's, the command's
#: diagnostics); the rest are counted ("... 120 more errors")
SHOWN = 50


def _excerpt(line: str, start: int, width: int) -> tuple:
    """(line, caret column, caret width): a long line cut to EXCERPT
    characters around the caret, with '...' where it is cut."""
    if len(line) <= EXCERPT:
        return line, start, width
    width = min(width, EXCERPT // 2)
    first = max(0, min(start - 1 - EXCERPT // 3, len(line) - EXCERPT))
    cut = line[first : first + EXCERPT]
    head = "..." if first > 0 else ""
    tail = "..." if first + EXCERPT < len(line) else ""
    return head + cut + tail, start - first + len(head), width


_LINE_END = re.compile(r"\r\n|\r|\n")


class SourceSet:
    """The texts of the files being compiled, for excerpts in messages."""

    def __init__(self) -> None:
        self._texts: dict[str, list[str]] = {}

    def add(self, path: str, text: str) -> None:
        # the lines as the lexer counts them (parser.parse_source): CR, LF and CRLF
        # end one, a form feed or U+2028 does not (str.splitlines would split there)
        lines = _LINE_END.split(text)
        if lines and lines[-1] == "":
            lines.pop()
        self._texts[path] = lines

    def text(self, path: str) -> str | None:
        """The whole text of a source, None if it is not there."""
        lines = self._texts.get(path)
        return None if lines is None else "\n".join(lines) + "\n"

    def line(self, path: str, line: int) -> str | None:
        lines = self._texts.get(path)
        if lines is None or not (1 <= line <= len(lines)):
            return None
        return lines[line - 1]


@dataclass
class DiagnosticBag:
    """Collects diagnostics of one compilation."""

    items: list = field(default_factory=list)

    def error(self, code: str, message: str, pos: Pos, hint: str | None = None) -> None:
        self.items.append(Diagnostic(code, message, pos, hint, ERROR))

    def warning(self, code: str, message: str, pos: Pos, hint: str | None = None) -> None:
        self.items.append(Diagnostic(code, message, pos, hint, WARNING))

    def extend(self, diags: Iterable[Diagnostic]) -> None:
        self.items.extend(diags)

    @property
    def has_errors(self) -> bool:
        return any(d.is_error for d in self.items)

    def sorted(self) -> list:
        return sorted(self.items, key=lambda d: (d.pos.file, d.pos.line, d.pos.col, d.code))


class CompileError(Exception):
    """Raised by the high-level API when a compilation has errors; carries
    every diagnostic (errors and warnings) and the sources for formatting."""

    def __init__(self, diagnostics: list, sources: SourceSet | None = None) -> None:
        self.diagnostics = diagnostics
        self.sources = sources
        super().__init__(self.format())

    def format(self) -> str:
        return "\n".join(d.format(self.sources) for d in self.diagnostics)
