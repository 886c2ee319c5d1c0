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
    """A text of ``lines`` lines (or more, when text goes beyond them),
    written in order: each ``put`` goes at or after what is already on its
    line. Only the lines written take memory."""

    def __init__(self, lines: int) -> None:
        self.size = lines  # the original's lines (text() has at least these)
        self.lines: dict[int, str] = {}  # line (from 1) -> its text; a line not here is empty
        self.pad: dict[int, int] = {}  # blanks put before a line's first text (each line written has one)
        self.written: set[int] = set()  # lines some text went to (an empty body line too)
        self.indent: dict[int, int] = {}  # line -> its indentation in plain()
        self.lowered: list[tuple[int, int]] = []  # (first, last) lines of ST written from another language
        self.origins: list[tuple[int, int, int, int]] = []  # (line, col, orig_line, orig_col): see put
        # line -> (text, sep, own line in plain() with that indentation or None) of each put there
        self.segments: dict[int, list[tuple[str, str, int | None]]] = {}
        self.joins: set[int] = set()  # lines plain() joins to the line before (a declaration's value)

    @property
    def used(self) -> bool:
        return bool(self.written)

    def put(
        self,
        line: int,
        col: int,
        text: str,
        indent: int = 0,
        origin: tuple | None = None,
        sep: str = " ",
        *,
        join: bool = False,
        own_line: bool = False,
    ) -> None:
        """text at (line, col), one-based; a text of several lines goes on
        the following lines from column 1 on. Where the line already holds
        more than col - 1 characters, it goes after them and sep (a space).
        indent: the blanks before the first line in plain().
        origin: (line, column) of the original the text (one line) comes
        from when it is not placed there (a graphical body's ST, written in
        evaluation order): the parser gives its tokens positions from there
        on (StView.origins).
        join: in plain(), a line that starts with this text continues the
        one before (a declaration's value, written where the XML holds it);
        own_line: in plain(), the text starts a line of its own even after
        other text on its line."""
        if origin is not None:
            cur = self.lines.get(line, "")
            start = max(col, len(cur) + (1 + len(sep) if cur else 1))
            self.origins.append((line, start, *origin))
        for k, part in enumerate(text.split("\n")):
            n = line + k
            if join and k == 0 and n not in self.written:
                self.joins.add(n)
            self.segments.setdefault(n, []).append((part, sep, indent if own_line and k == 0 else None))
            self._place(n, col if k == 0 else 1, part, sep, indent if k == 0 else 0)

    def _place(self, n: int, start: int, part: str, sep: str, indent: int) -> None:
        cur = self.lines.get(n, "")
        if not cur:
            self.pad[n] = max(start - 1, 0)
        if len(cur) < start - 1:
            cur += " " * (start - 1 - len(cur))
        elif cur and part:
            cur += sep
        self.lines[n] = cur + part
        if n not in self.written and indent:
            self.indent[n] = indent
        self.written.add(n)

    def absorb(self, other: LineView, own_line: bool = False) -> None:
        """Put what other holds into this view, line by line (as if it had
        been put here in the first place, after what is here already).
        own_line: in plain(), what other holds starts a line of its own."""
        self.size = max(self.size, other.size)
        by_line: dict[int, list] = {}
        for o in other.origins:
            by_line.setdefault(o[0], []).append(o)
        for k, n in enumerate(sorted(other.written)):
            pad = other.pad.get(n, 0)
            cur, was = self.lines.get(n, ""), pad + 1
            shift = len(cur) + 2 - was if cur and len(cur) >= was - 1 else 0
            self.origins.extend((ln, c + shift, ol, oc) for ln, c, ol, oc in by_line.get(n, ()))
            if n in other.joins and n not in self.written:
                self.joins.add(n)
            segments = other.segments.get(n, [])
            if own_line and k == 0 and segments:
                segments = [(segments[0][0], segments[0][1], other.indent.get(n, 0)), *segments[1:]]
            self.segments.setdefault(n, []).extend(segments)
            self._place(n, was, other.lines.get(n, "")[pad:], " ", other.indent.get(n, 0))
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
            pad = self.pad.get(n, 0)
            lead = len(text) - len(text.lstrip())
            self.lines[n] = text
            self.pad[n] = min(pad, lead)
            self.segments[n] = [(text[self.pad[n] :], " ", None)]
            self.joins.discard(n)
            self.written.add(n)

    def view(self) -> StView:
        """What the parser reads: the text and its lowered lines."""
        return StView(self.text(), tuple(self.lowered), tuple(sorted(self.origins)))

    def text(self) -> str:
        """The view: the original's lines and columns."""
        last = max(self.size, max(self.lines, default=0))
        return "\n".join(self.lines.get(n, "") for n in range(1, last + 1)) + "\n"

    def plain(self) -> str:
        """The view as plain ST to read: the lines that hold ST, without the
        blanks that placed them in the original's columns."""
        return "".join(text + "\n" for _n, text in self.plain_lines())

    def plain_lines(self) -> list[tuple[int, str]]:
        """(line of the original, its text in plain()) of each line of
        plain(): a line's puts on one line, each after its sep (a line that
        starts with a declaration's value, placed at its own line, joined to
        the line before), a put that asks for it on a line of its own."""
        out: list[tuple[int, str]] = []
        for n in sorted(self.written):
            segments = self.segments.get(n, [])
            text = segments[0][0].rstrip() if segments else ""
            if n in self.joins and out:
                out[-1] = (out[-1][0], _glue(out[-1][1], text.strip()))
            else:
                out.append((n, " " * self.indent.get(n, 0) + text))
            for t, sep, own in segments[1:]:
                if own is not None:
                    out.append((n, " " * own + t.strip()))
                elif t.strip():
                    out[-1] = (out[-1][0], out[-1][1] + sep + t.strip())
        return out


def _glue(a: str, b: str) -> str:
    """a and b on one line of plain(): a blank between them, but after an
    opening and before a closing bracket, a comma or a semicolon."""
    if not b:
        return a
    if not a.strip() or a.endswith(("(", "[")) or b.startswith((")", "]", ",", ";")):
        return a + b
    return a + " " + b
