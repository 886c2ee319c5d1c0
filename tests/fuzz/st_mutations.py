"""Mutations of ST programs beyond the token-wise ones of
tests/st/fuzz_mutations.py: bytes deleted, inserted and duplicated inside
tokens, numbers made huge, constructs nested deep. `mutants(base)` applies a
few of either kind to programs drawn from base."""

from __future__ import annotations

from hypothesis import strategies as st

from ..st.fuzz_corpus import CORPUS
from ..st.fuzz_mutations import MUTATIONS, ST_ALPHABET
from ..st.fuzz_support import tokenize

HUGE = [
    "99999999999999999999999999999999",
    "2147483648",
    "4294967296",
    "18446744073709551616",
    "-9223372036854775809",
    "1.0E309",
    "1.0E-400",
    "16#FFFFFFFFFFFFFFFFFFFFFFFF",
    "2#" + "1" * 200,
    "9" * 400,
    "T#99999999999999d",
    "LTIME#9999999999999999999999ns",
    "INT#99999",
    "DINT#-2147483649",
]


def _m_bytes(draw, toks):
    """Delete, insert or duplicate a few characters anywhere, even inside a token."""
    text = "".join(toks)
    i = draw(st.integers(0, len(text)))
    n = draw(st.integers(1, 4))
    how = draw(st.sampled_from(["delete", "insert", "duplicate"]))
    if how == "delete":
        text = text[:i] + text[i + n :]
    elif how == "insert":
        text = text[:i] + draw(st.text(ST_ALPHABET, min_size=1, max_size=n)) + text[i:]
    else:
        text = text[:i] + text[i : i + n] + text[i:]
    toks[:] = tokenize(text)


def _next_code(toks, i: int, step: int) -> str:
    """The nearest token that is not white space, before (-1) or after (1) i."""
    j = i + step
    while 0 <= j < len(toks) and not toks[j].strip():
        j += step
    return toks[j] if 0 <= j < len(toks) else ""


def _m_huge(draw, toks):
    """A number made huge (or tiny, or too long).

    Repeat counts and array bounds too (issue 16, "a huge repeat count in an
    array initialiser raises MemoryError in the checker; a huge
    multi-dimensional array makes the code generator run for minutes")."""
    at = [i for i, t in enumerate(toks) if t[:1].isdigit()]
    if at:
        toks[draw(st.sampled_from(at))] = draw(st.sampled_from(HUGE))


def _m_nest(draw, toks):
    """A construct nested deep around a span of tokens or at a place."""
    depth = draw(st.sampled_from([8, 40, 120, 400, 2000]))
    i = draw(st.integers(0, max(0, len(toks) - 1)))
    j = min(len(toks), i + draw(st.integers(0, 12)))
    shape = draw(st.sampled_from(["parens", "if", "not", "minus", "array", "comment", "brackets"]))
    if shape == "parens":
        toks[i:j] = ["(" * depth, *toks[i:j], ")" * depth]
    elif shape == "if":
        toks[i:j] = ["IF TRUE THEN " * depth, *toks[i:j], " END_IF;" * depth]
    elif shape == "not":
        toks.insert(i, "NOT " * depth)
    elif shape == "minus":
        toks.insert(i, "- " * depth)
    elif shape == "array":
        toks.insert(i, " ARRAY[0..0] OF" * depth + " INT")
    elif shape == "brackets":
        toks.insert(i, "[" * depth + "1" + "]" * depth)
    else:
        toks[i:j] = ["(* " * depth, *toks[i:j], " *)" * depth]


NEW_MUTATIONS = [_m_bytes, _m_huge, _m_nest]


@st.composite
def mutants(draw, base):
    """(profile, source): a program of base (a strategy of sources, or None
    for the corpus of tests/st) with one to four mutations, old and new."""
    if base is None:
        profile, src = draw(st.sampled_from(CORPUS))
    else:
        profile, src = "codesys", draw(base)
    toks = tokenize(src)
    for _ in range(draw(st.integers(1, 4))):
        draw(st.sampled_from(MUTATIONS + NEW_MUTATIONS * 2))(draw, toks)
    return profile, "".join(toks)
