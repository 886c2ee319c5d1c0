"""An ST text laid out on the lines of another file (an XML export): what
the importer writes at (line, column) of the original lands at that line and
column of the view, so the parser's and the checker's positions are those of
the original file with no mapping (diagnostics, runtime faults, watch).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class StView:
    """One ST text to parse for a source file, as ``parse_source(text, path,
    diags, profile, lowered)`` takes it."""

    text: str
    lowered: tuple = ()  # (first, last) line ranges written from another language
    origins: tuple = ()  # (line, column, orig_line, orig_column): text placed apart from where it comes from


class LineView:
    """A text of ``lines`` lines, written in order: each ``put`` goes at or
    after what is already on its line."""

    def __init__(self, lines: int) -> None:
        self.lines: list[str] = [""] * (lines + 1)  # index 0 unused: lines count from 1
        self.pad: list[int] = [0] * (lines + 1)  # blanks put before a line's first text
        self.written: set[int] = set()  # lines some text went to (an empty body line too)
        self.indent: dict[int, int] = {}  # line -> its indentation in plain()
        self.lowered: list[tuple[int, int]] = []  # (first, last) lines of ST written from another language
        self.origins: list[tuple[int, int, int, int]] = []  # (line, col, orig_line, orig_col): see put

    @property
    def used(self) -> bool:
        return bool(self.written)

    def put(self, line: int, col: int, text: str, indent: int = 0, origin: tuple | None = None, sep: str = " ") -> None:
        """text at (line, col), one-based; a text of several lines goes on
        the following lines from column 1 on. Where the line already holds
        more than col - 1 characters, it goes after them and a space.
        indent: the blanks before the first line in plain().
        origin: (line, column) of the original the text (one line) comes
        from when it is not placed there (a graphical body's ST, written in
        evaluation order): the parser gives its tokens positions from there
        on (StView.origins). sep: what goes between the line's text and
        text when it goes after it."""
        if origin is not None:
            cur = self.lines[line] if line < len(self.lines) else ""
            start = max(col, len(cur) + (1 + len(sep) if cur else 1))
            self.origins.append((line, start, *origin))
        for k, part in enumerate(text.split("\n")):
            n = line + k
            while n >= len(self.lines):
                self.lines.append("")
                self.pad.append(0)
            cur = self.lines[n]
            start = col if k == 0 else 1
            if len(cur) < start - 1:
                if not cur:
                    self.pad[n] = start - 1
                cur += " " * (start - 1 - len(cur))
            elif cur and part:
                cur += sep
            self.lines[n] = cur + part
            if n not in self.written and k == 0 and indent:
                self.indent[n] = indent
            self.written.add(n)

    def absorb(self, other: LineView) -> None:
        """Put what other holds into this view, line by line (as if it had
        been put here in the first place, after what is here already)."""
        by_line: dict[int, list] = {}
        for o in other.origins:
            by_line.setdefault(o[0], []).append(o)
        for n in sorted(other.written):
            cur, was = self.lines[n] if n < len(self.lines) else "", other.pad[n] + 1
            shift = len(cur) + 2 - was if cur and len(cur) >= was - 1 else 0
            self.origins.extend((ln, c + shift, ol, oc) for ln, c, ol, oc in by_line.get(n, ()))
            self.put(n, other.pad[n] + 1, other.lines[n][other.pad[n] :], other.indent.get(n, 0))
        self.lowered.extend(other.lowered)

    def mark_lowered(self, first: int, last: int) -> None:
        """Lines first..last hold ST written from IL or a graphical body
        (``SourceFile.lowered``: a JMP there is allowed in every profile)."""
        self.lowered.append((first, last))

    def replace(self, lines: dict) -> None:
        """Put other text on some lines (line -> text; "" empties a line):
        for plain(), the ST of an IL body instead of the IL."""
        for n, text in lines.items():
            if not text:
                self.written.discard(n)
                continue
            lead = len(text) - len(text.lstrip())
            self.lines[n] = " " * min(self.pad[n], lead) + text.lstrip() if self.pad[n] else text
            self.pad[n] = min(self.pad[n], lead)
            self.written.add(n)

    def view(self) -> StView:
        """What the parser reads: the text and its lowered lines."""
        return StView(self.text(), tuple(self.lowered), tuple(sorted(self.origins)))

    def text(self) -> str:
        """The view: the original's lines and columns."""
        return "\n".join(self.lines[1:]) + "\n"

    def plain(self) -> str:
        """The view as plain ST to read: the lines that hold ST, without the
        blanks that placed them in the original's columns."""
        return "".join(text + "\n" for _n, text in self.plain_lines())

    def plain_lines(self) -> list[tuple[int, str]]:
        """(line of the original, its text in plain()) of each line that holds ST."""
        return [(n, " " * self.indent.get(n, 0) + self.lines[n][self.pad[n] :].rstrip()) for n in sorted(self.written)]
