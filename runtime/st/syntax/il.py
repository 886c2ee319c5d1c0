"""IL, the instruction list of IEC 61131-3 ed.2, in an ST text: each IL body
is lowered to ST in place, before the parse (parser.py calls ``lower_il``
on the text whose comments are blanked, when it did not parse as ST).

    text, ranges = lower_il(text, path, diags, lexer)

A body is IL when it follows a POU's header or its VAR blocks (PROGRAM,
FUNCTION, FUNCTION_BLOCK, METHOD, ACTION, ACTION Pou.Name:) and its first
instruction, after optional labels, is an IL operator on a line of its own
with no ';': followed by an operand that does not start with ':=' (LD x,
JMP done, CAL fb), or alone where it takes none (RET, NOT). ``LD := 5;``,
``x := 1;``, ``L1: x := 1;`` and ``JMP L1;`` stay ST. The body ends before
the END_* keyword that closes it (or an ACTION of the POU that follows it).

il_parse.py reads the instructions, il_lower.py writes the ST on the same
lines (the text keeps its line count, so every position after a body is
unchanged, and the ST's positions are the IL's). ``ranges`` are the
(first, last) lines of each body: ``SourceFile.lowered`` (a JMP there is
IL's own, allowed in every profile). A body with a problem (E002, E004,
E190-E198) is left empty, so that only its own diagnostics are reported.

Looking for IL costs a few str.find passes over the text for END_VAR and
POU headers, and a look at what follows each; parser.py looks only in a
file that did not parse as ST.
"""

from __future__ import annotations

import re
from bisect import bisect_right
from dataclasses import fields

from ..ast import Binary, Node, Pos, SourceFile, Stmt
from ..diagnostics import DiagnosticBag
from .il_lower import Layout, Lowering
from .il_parse import BARE_OPS, OPS, PAREN_OPS, read_il
from .lexer import strip_comments

__all__ = ["has_il", "lower_il", "lowered_for_reading", "relocate"]

# What an IL body follows: the end of a VAR block (or of a method, before
# the body of its FB), or a header line (PROGRAM p, ACTION a:, ...)
_AFTER = ("END_VAR", "END_METHOD", "END_PROPERTY")
_HEADERS = ("PROGRAM", "FUNCTION", "METHOD", "ACTION", "TRANSITION")
_BLANK = re.compile(r"[ \t\f\r\v]*\n[ \t\f\r\n\v]*")
_LABEL = re.compile(r"([A-Za-z_]\w*)[ \t]*:(?!=)[ \t\f\r\n\v]*", re.A)
_WORD = re.compile(r"(&N?|[A-Za-z_]\w*)[ \t]*(\(?)[ \t]*", re.A)
_OPERAND_START = re.compile(r"[A-Za-z_0-9%'\"+\-]", re.A)
_END = re.compile(
    r"^[ \t]*(?:END_(?:PROGRAM|FUNCTION_BLOCK|FUNCTION|METHOD|ACTION|TRANSITION|PROPERTY|GET|SET)\b"
    r"|ACTION[ \t]+[A-Za-z_])",
    re.I | re.M,
)
_POU = re.compile(r"^[ \t]*(?:PROGRAM|FUNCTION_BLOCK|FUNCTION)\b", re.I | re.M)
_VARS = re.compile(r"\bVAR\w*\b(.*?)\bEND_VAR\b", re.I | re.S)
_DECL = re.compile(r"([A-Za-z_]\w*(?:\s*,\s*[A-Za-z_]\w*)*)\s*(?:AT\s+%\S+\s*)?:(?!=)\s*([A-Za-z_]\w*)", re.A)
_TYPES = re.compile(r"\bTYPE\b(.*?)\bEND_TYPE\b", re.I | re.S)
_TYPE_NAME = re.compile(r"([A-Za-z_]\w*)\s*:(?!=)", re.A)
ELEMENTARY = frozenset(
    """BOOL SINT INT DINT LINT USINT UINT UDINT ULINT BYTE WORD DWORD LWORD REAL LREAL TIME LTIME DATE
    LDATE TIME_OF_DAY TOD LTOD DATE_AND_TIME DT LDT STRING WSTRING CHAR WCHAR ARRAY POINTER REFERENCE
    REF_TO BIT""".split()
)
MAX_IL_ERRORS = 50  # per file
_NOT_CHILDREN = frozenset(("pos", "ty", "const", "sym", "pragmas", "qualifier"))


def lower_il(text: str, path: str, diags: DiagnosticBag, lexer, plain: dict | None = None) -> tuple:
    """(text with its IL bodies lowered to ST, [(first, last) line of each],
    where the pieces of ST come from: line -> [(column, column after, IL
    line, IL column)], for relocate). plain: gets line -> the ST of the
    line with one blank between its pieces (for a reader)."""
    bodies = _find_bodies(text)
    if not bodies:
        return text, [], {}
    lines = text.split("\n")
    starts = _line_starts(text)
    ranges, errors, where = [], [0], {}

    def report(code: str, message: str, line: int, col: int, end_col: int, hint: str) -> None:
        errors[0] += 1
        if errors[0] <= MAX_IL_ERRORS:
            diags.error(code, message, Pos(path, line, col, line, end_col), hint or None)

    types = {m.upper() for block in _TYPES.findall(text) for m in _TYPE_NAME.findall(block)}
    heads = [m.start() for m in _POU.finditer(text)]
    for start, end, colon in bodies:
        first = bisect_right(starts, start)
        last = bisect_right(starts, end - 1) if end > start else first
        texts = {n: lines[n - 1] for n in range(first, last + 1)}
        before = errors[0]
        items = read_il(texts, first, last, lexer, report)
        out = Layout(first, last)
        if errors[0] == before:  # (IL that does not read is not lowered: what would follow is noise)
            indent = {n: len(t) - len(t.lstrip()) + 1 for n, t in texts.items() if t.strip()}
            lowering = Lowering(items, out, report, _fb_names(text, start, types, heads), indent)
            lowering.condition = colon >= 0
            lowering.run()
        failed = errors[0] > before
        for n in range(first, last + 1):
            lines[n - 1] = "" if failed else out.lines[n]
        if colon >= 0:  # TRANSITION ... : IL  ->  TRANSITION ... := condition;
            at = bisect_right(starts, colon)
            col = colon - starts[at - 1]
            lines[at - 1] = lines[at - 1][:col] + ":=" + lines[at - 1][col + 1 :]
            if failed:
                lines[first - 1] = "FALSE;"  # (its problem is reported: no other)
        ranges.append((first, last))
        if not failed:
            where.update(out.where)
            if plain is not None:
                plain.update(out.plain)
    return "\n".join(lines), ranges, where


def relocate(sf: SourceFile, where: dict) -> None:
    """Give the expressions of lowered IL the positions of the IL they come
    from (a target written before its value, an operand that did not fit in
    its column). Statements keep theirs: a statement starts where a fault
    in it is likeliest (il_lower.py), which is where runtime faults point."""
    if where:
        _Relocate(sf.path, where).value(sf.decls)


class _Relocate:
    def __init__(self, path: str, where: dict) -> None:
        self.path = path
        self.where = where
        self.fields: dict = {}

    def _at(self, line: int, col: int) -> tuple | None:
        for first, after, il_line, il_col in self.where.get(line, ()):
            if first <= col < after:
                return il_line, il_col + col - first
        return None

    def value(self, value) -> None:
        """Every node in value, each before its children (an explicit stack:
        a chain of a thousand IL operators is a tree that deep)."""
        stack = [value]
        while stack:
            item = stack.pop()
            if isinstance(item, Node):
                self.node(item)
                stack.extend(getattr(item, name) for name in self._children(item))
            elif isinstance(item, (list, tuple)):
                stack.extend(item)

    def _children(self, node: Node) -> tuple:
        names = self.fields.get(type(node))
        if names is None:
            names = self.fields[type(node)] = tuple(f.name for f in fields(node) if f.name not in _NOT_CHILDREN)
        return names

    def _operator(self, node: Binary) -> tuple | None:
        """The IL position of a binary operation's operator: of the first
        piece between its operands (it says more than the left operand,
        where the ST node starts: AND b, not the LD three lines above)."""
        after = (node.left.pos.end_line, node.left.pos.end_col)
        before = (node.right.pos.line, node.right.pos.col)
        for line in range(after[0], before[0] + 1):
            for first, _after, il_line, il_col in self.where.get(line, ()):
                if after <= (line, first) < before:
                    return il_line, il_col
        return None

    def node(self, node: Node) -> None:
        pos = node.pos
        if pos.line in self.where and pos.file == self.path and not isinstance(node, Stmt):
            start = self._operator(node) if isinstance(node, Binary) else None
            start = start or self._at(pos.line, pos.col)
            if start is not None:
                end = self._at(pos.end_line, pos.end_col - 1)
                end = (end[0], end[1] + 1) if end is not None and end >= start else (start[0], start[1] + 1)
                node.pos = Pos(pos.file, start[0], start[1], end[0], end[1])


def has_il(text: str) -> bool:
    """Whether text (comments blanked) holds an IL body."""
    return bool(_find_bodies(text))


def _line_starts(text: str) -> list:
    starts, i = [0], text.find("\n")
    while i >= 0:
        starts.append(i + 1)
        i = text.find("\n", i + 1)
    return starts


def _find_bodies(text: str) -> list:
    """(start, end, colon) offsets of the IL bodies: start at the line of
    the first label or instruction, end before the line that closes the
    body; colon: of a transition's ':' (-1: the body is no transition's)."""
    bodies: list = []
    pos = 0
    for after, colon in _contexts(text):
        if after < pos:
            continue
        start = _il_start(text, after)
        if start < 0:
            continue
        e = _END.search(text, start)
        end = e.start() if e is not None else len(text)
        bodies.append((text.rfind("\n", 0, start) + 1, end, colon))
        pos = end
    return bodies


def _contexts(text: str) -> list:
    """(offset, colon) after which an IL body may start: after END_VAR,
    END_METHOD, END_PROPERTY, and at the end of a header line (one with no
    ';' that starts with PROGRAM, FUNCTION, FUNCTION_BLOCK, METHOD, ACTION,
    or TRANSITION and ends with ':', whose offset is colon; -1 for the
    others)."""
    up, found = text.upper(), []
    n = len(up)
    for kw in (*_AFTER, *_HEADERS):
        p = up.find(kw)
        while p >= 0:
            q = p + len(kw)
            if (p == 0 or not _wordy(up[p - 1])) and (q == n or not _wordy(up[q]) or up.startswith("_BLOCK", q)):
                if kw in _AFTER:
                    found.append((q, -1))
                elif not up[up.rfind("\n", 0, p) + 1 : p].strip():  # first on its line
                    eol = up.find("\n", q)
                    eol = n if eol < 0 else eol
                    if ";" in up[q:eol]:
                        pass
                    elif kw != "TRANSITION":
                        found.append((eol, -1))
                    elif up[q:eol].rstrip().endswith(":"):  # TRANSITION FROM s1 TO s2 :
                        found.append((eol, q + len(up[q:eol].rstrip()) - 1))
            p = up.find(kw, q)
    return sorted(found)


def _wordy(c: str) -> bool:
    return c.isalnum() or c == "_"


def _il_start(text: str, pos: int) -> int:
    """Where the IL body after a header or END_VAR ending at pos starts
    (its first label or instruction), or -1 when what follows is no IL."""
    gap = _BLANK.match(text, pos)
    if gap is None:
        return -1  # IL starts on a new line
    start = p = gap.end()
    while True:
        label = _LABEL.match(text, p)
        if label is None or label.group(1).upper() in OPS:
            break
        p = label.end()
    w = _WORD.match(text, p)
    if w is None:
        return -1
    word, paren = w.group(1).upper(), w.group(2)
    base = "AND" if word.startswith("&") else OPS.get(word, ("",))[0]
    if not base:
        return -1
    eol = text.find("\n", p)
    rest = text[w.end() : len(text) if eol < 0 else eol].rstrip()
    if ";" in rest:
        return -1
    if paren:
        return start if base in PAREN_OPS else -1
    if base in BARE_OPS:
        return start if not rest else -1
    return start if rest and _OPERAND_START.match(rest) and not rest.startswith(":=") else -1


def _fb_names(text: str, start: int, types: set, heads: list) -> set:
    """The upper names the POU around offset start declares with a type that
    is not elementary and not a TYPE of this text: its function block
    instances (S and R on them call them). heads: where the POUs start."""
    k = bisect_right(heads, start)
    head = heads[k - 1] if k else 0
    names: set = set()
    for block in _VARS.findall(text, head, start):
        for decl in _DECL.finditer(block):
            ty = decl.group(2).upper()
            if ty not in ELEMENTARY and ty not in types:
                names.update(n.strip().upper() for n in decl.group(1).split(","))
    return names


def lowered_for_reading(text: str, lexer) -> dict:
    """For ``softplc export-st``: line -> the ST of the IL bodies of text
    (comments not blanked yet), one statement a line where it took several
    (n := n + 1; not n := n / + 1;), with the comments of its lines; ""
    where nothing is left of an IL line. Only the lines that hold
    something in the IL. {} when text has no IL, or IL with errors (then
    the IL is shown as it is)."""
    blank, _ = strip_comments(text, lambda *_: None)
    diags = DiagnosticBag()
    plain: dict = {}
    _lowered, ranges, _where = lower_il(blank, "", diags, lexer, plain)
    if not ranges or diags.has_errors:
        return {}
    origs, blanks = text.split("\n"), blank.split("\n")
    out: dict = {}
    for first, last in ranges:
        group: list = []  # lines of one statement: (line, code, comments after)
        for n in range(first, last + 1):
            if not origs[n - 1].strip():
                continue
            before, after = _comments(origs[n - 1], blanks[n - 1])
            code = plain[n]
            if not code and not group:  # a line of comments
                out[n] = after
                continue
            if before or after.count("(*") != after.count("*)") or after.count("/*") != after.count("*/"):
                _flush(group, out)  # a comment of several lines: the line stays as it is
                out[n] = " ".join(part for part in (before, code, after) if part)
                continue
            group.append((n, code, after))
            if code.endswith((";", ":")):
                _flush(group, out)
        _flush(group, out)
    return out


def _flush(group: list, out: dict) -> None:
    """The lines of group as one: the code on the first line that has some,
    the comments after it; the other lines empty, but for their comments."""
    if not group:
        return
    code = " ".join(c for _n, c, _a in group if c)
    at = next((n for n, c, _a in group if c), group[0][0])
    for n, _c, _a in group:
        out[n] = ""
    out[at] = " ".join(part for part in (code, *(a for _n, _c, a in group if a)) if part)
    group.clear()


def _comments(orig: str, blank: str) -> tuple:
    """(the end of a comment that began on an earlier line, the comments
    that begin on this line) of one line: what strip_comments blanked."""
    spans, i, n = [], 0, min(len(orig), len(blank))
    while i < n:
        if orig[i] == blank[i]:
            i += 1
            continue
        k = last = i
        while k < n and blank[k] == " ":
            if orig[k] != " ":
                last = k
            k += 1
        spans.append(orig[i : last + 1])
        i = k
    if spans and not spans[0].startswith(("(*", "/*", "//", "{")):
        return spans[0], " ".join(spans[1:])
    return "", " ".join(spans)
