"""The STRING/WSTRING length oracle's inputs (test_strings.py): variables
of random declared lengths, and assignments of random string functions
(CONCAT, INSERT, REPLACE, LEFT, RIGHT, MID, DELETE, nested two deep) into
them, then LEN of each; and the reference: the same functions written as
Python slicing from IEC 61131-3 ed.3 Table 29 (positions from 1,
out-of-range arguments as CODESYS takes them), each store cut at the
declared length (6.4.2).

A WSTRING counts UTF-16 code units (6.3.3), and its alphabet holds
characters beyond U+FFFF (2 units each): its reference slices the UTF-16
units themselves (len(s.encode('utf-16-le')) // 2 of them). softplc's rule
for a position inside a surrogate pair (runtime/st/rtlib/rt_strings.py): a part
taken (LEFT, RIGHT, MID, what DELETE and REPLACE keep, a store's cut) leaves
out a character it holds half of; an insertion point (INSERT, REPLACE of 0
units) inside a pair goes before it."""

from __future__ import annotations

import struct
from dataclasses import dataclass

from hypothesis import strategies as st

NAMES = ("a", "b", "c", "d")
TARGETS = NAMES + ("r.s", "arr[2]")  # a variable, a STRUCT field, an array element
_INTS = st.integers(min_value=-2, max_value=14)


def _left(s: str, n: int) -> str:
    return s[:n] if n > 0 else ""


def _right(s: str, n: int) -> str:
    return s[max(len(s) - n, 0) :] if n > 0 else ""


def _mid(s: str, n: int, p: int) -> str:
    return s[p - 1 : p - 1 + n] if p >= 1 and n > 0 else ""


def _insert(s1: str, s2: str, p: int) -> str:
    p = max(p, 0)
    return s1[:p] + s2 + s1[p:]


def _delete(s: str, n: int, p: int) -> str:
    return s if p < 1 or n <= 0 or p > len(s) else s[: p - 1] + s[p - 1 + n :]


def _replace(s1: str, s2: str, n: int, p: int) -> str:
    p = min(max(p, 1), len(s1) + 1)
    return s1[: p - 1] + s2 + s1[p - 1 + max(n, 0) :]


# ---- WSTRING: the same on UTF-16 code units


def _units(s: str) -> list:
    data = s.encode("utf-16-le")
    return list(struct.unpack(f"<{len(data) // 2}H", data))


def _low(unit: int) -> bool:
    return 0xDC00 <= unit <= 0xDFFF


def _text_of(units: list) -> str:
    """A part taken of a WSTRING: a half character at either end left out."""
    if units and _low(units[0]):
        units = units[1:]
    if units and 0xD800 <= units[-1] <= 0xDBFF:
        units = units[:-1]
    return struct.pack(f"<{len(units)}H", *units).decode("utf-16-le")


def _before_pair(units: list, p: int) -> int:
    """An insertion point inside a surrogate pair goes before it."""
    return p - 1 if 0 < p < len(units) and _low(units[p]) else p


def wcut(s: str, n: int) -> str:
    return _text_of(_units(s)[:n])


def _wleft(s: str, n: int) -> str:
    return _text_of(_units(s)[:n]) if n > 0 else ""


def _wright(s: str, n: int) -> str:
    u = _units(s)
    return _text_of(u[max(len(u) - n, 0) :]) if n > 0 else ""


def _wmid(s: str, n: int, p: int) -> str:
    return _text_of(_units(s)[p - 1 : p - 1 + n]) if p >= 1 and n > 0 else ""


def _winsert(s1: str, s2: str, p: int) -> str:
    u = _units(s1)
    p = _before_pair(u, max(p, 0))
    return _text_of(u[:p]) + s2 + _text_of(u[p:])


def _wdelete(s: str, n: int, p: int) -> str:
    u = _units(s)
    return s if p < 1 or n <= 0 or p > len(u) else _text_of(u[: p - 1]) + _text_of(u[p - 1 + n :])


def _wreplace(s1: str, s2: str, n: int, p: int) -> str:
    u = _units(s1)
    p = min(max(p, 1), len(u) + 1)
    if n <= 0:
        return _winsert(s1, s2, p - 1)
    return _text_of(u[: p - 1]) + s2 + _text_of(u[p - 1 + n :])


#: function -> (the number of string arguments, of integer arguments, the reference)
FUNCTIONS = {
    "CONCAT": (2, 0, lambda s, i: s[0] + s[1]),
    "INSERT": (2, 1, lambda s, i: _insert(s[0], s[1], i[0])),
    "REPLACE": (2, 2, lambda s, i: _replace(s[0], s[1], i[0], i[1])),
    "LEFT": (1, 1, lambda s, i: _left(s[0], i[0])),
    "RIGHT": (1, 1, lambda s, i: _right(s[0], i[0])),
    "MID": (1, 2, lambda s, i: _mid(s[0], i[0], i[1])),
    "DELETE": (1, 2, lambda s, i: _delete(s[0], i[0], i[1])),
}
#: the same for WSTRING arguments
WIDE_REFERENCE = {
    "CONCAT": lambda s, i: s[0] + s[1],
    "INSERT": lambda s, i: _winsert(s[0], s[1], i[0]),
    "REPLACE": lambda s, i: _wreplace(s[0], s[1], i[0], i[1]),
    "LEFT": lambda s, i: _wleft(s[0], i[0]),
    "RIGHT": lambda s, i: _wright(s[0], i[0]),
    "MID": lambda s, i: _wmid(s[0], i[0], i[1]),
    "DELETE": lambda s, i: _wdelete(s[0], i[0], i[1]),
}


@dataclass(frozen=True)
class Call:
    func: str
    strings: tuple  # of Call, a variable's name, or ("lit", text)
    ints: tuple


@dataclass(frozen=True)
class Case:
    wide: bool
    lengths: dict  # target -> declared length
    inits: dict  # variable -> initial text
    stores: tuple  # (target, Call)


def _text(wide: bool, max_size: int):
    alphabet = "abcXYZ01\u00e9\u4e2d\U0001f600\U00010348" if wide else "abcXYZ01"
    return st.text(alphabet, max_size=max_size)


def _arg(wide: bool, depth: int):
    leaf = st.one_of(st.sampled_from(TARGETS), st.tuples(st.just("lit"), _text(wide, 8)))
    return leaf if depth == 0 else st.one_of(leaf, _call(wide, depth - 1))


def _call(wide: bool, depth: int):
    def build(func):
        n_str, n_int, _ref = FUNCTIONS[func]
        return st.builds(
            Call,
            st.just(func),
            st.tuples(*[_arg(wide, depth) for _ in range(n_str)]),
            st.tuples(*[_INTS for _ in range(n_int)]),
        )

    return st.sampled_from(sorted(FUNCTIONS)).flatmap(build)


@st.composite
def cases(draw) -> Case:
    wide = draw(st.booleans())
    lengths = {t: draw(st.integers(min_value=1, max_value=12)) for t in TARGETS}
    inits = {n: draw(_text(wide, lengths[n])) for n in NAMES}
    stores = tuple(draw(st.lists(st.tuples(st.sampled_from(TARGETS), _call(wide, 2)), min_size=1, max_size=12)))
    return Case(wide, lengths, inits, stores)


def _quote(text: str, wide: bool) -> str:
    q = '"' if wide else "'"
    return q + text + q  # the alphabets hold nothing to escape


def _st_expr(arg, wide: bool) -> str:
    if isinstance(arg, str):
        return arg
    if isinstance(arg, tuple):
        return _quote(arg[1], wide)
    args = [_st_expr(a, wide) for a in arg.strings] + [str(i) for i in arg.ints]
    return f"{arg.func}({', '.join(args)})"


def source(case: Case) -> str:
    """The case as a PROGRAM Main (one cycle does every store in order)."""
    s = "WSTRING" if case.wide else "STRING"
    decls = [f"{n} : {s}[{case.lengths[n]}] := {_quote(case.inits[n], case.wide)};" for n in NAMES]
    decls.append(f"r : R; arr : ARRAY[1..3] OF {s}[{case.lengths['arr[2]']}];")
    decls.append(", ".join(f"len_{n}" for n in NAMES) + " : INT;")
    body = "\n".join(f"{t} := {_st_expr(call, case.wide)};" for t, call in case.stores)
    body += "\n" + "\n".join(f"len_{n} := LEN({n});" for n in NAMES)
    return (
        f"TYPE R : STRUCT s : {s}[{case.lengths['r.s']}]; END_STRUCT END_TYPE\n"
        f"PROGRAM Main\nVAR\n" + "\n".join(decls) + f"\nEND_VAR\n{body}\nEND_PROGRAM\n"
    )


def _value(arg, env: dict, wide: bool) -> str:
    if isinstance(arg, str):
        return env[arg]
    if isinstance(arg, tuple):
        return arg[1]
    ref = WIDE_REFERENCE[arg.func] if wide else FUNCTIONS[arg.func][2]
    return ref([_value(a, env, wide) for a in arg.strings], list(arg.ints))


def length(text: str, wide: bool) -> int:
    """LEN: characters of a STRING, UTF-16 code units of a WSTRING."""
    return len(text.encode("utf-16-le")) // 2 if wide else len(text)


def expected(case: Case) -> dict:
    """Every target's value after one cycle, by the reference, and len_<name>
    the LEN of each variable."""

    def cut(text: str, target: str) -> str:
        return wcut(text, case.lengths[target]) if case.wide else text[: case.lengths[target]]

    env = {n: cut(text, n) for n, text in case.inits.items()}
    env.update({"r.s": "", "arr[2]": ""})
    for target, call in case.stores:
        env[target] = cut(_value(call, env, case.wide), target)
    env.update({f"len_{n}": length(env[n], case.wide) for n in NAMES})
    return env
