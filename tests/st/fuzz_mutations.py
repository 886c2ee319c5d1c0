"""Token-wise mutations of ST programs, shared by the fuzz tests of the
front end (test_fuzz.py) and the cross-cutting harness (tests/fuzz/): spans
deleted, duplicated, swapped; keywords, operators, literals inserted;
identifiers renamed; types flipped; truncated. Each mutation takes
hypothesis's draw and the token list (fuzz_support.tokenize) and changes the
list in place."""

from __future__ import annotations

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import strategies as st  # noqa: E402

from .fuzz_corpus import CORPUS  # noqa: E402
from .fuzz_support import IDENT_RE, IDENTS, LITERALS, TOKEN_POOL, TYPE_NAMES, TYPES, tokenize  # noqa: E402

ST_ALPHABET = st.sampled_from(
    list("abcxyzABC_019 \t\n\r\0\x0b\x0c\x1b\x7f\u00e9\u00a0\u2028\u202e\ufeff'\"$#%:;=<>()[]{}*/+-.,^&@!?\\`|~")
)


def _pos(draw, toks, extra: int = 0) -> int:
    return draw(st.integers(0, max(0, len(toks) - 1 + extra)))


def _m_delete(draw, toks):
    i = _pos(draw, toks)
    del toks[i : i + draw(st.integers(1, 12))]


def _m_duplicate(draw, toks):
    i = _pos(draw, toks)
    toks[i:i] = toks[i : i + draw(st.integers(1, 20))]


def _m_swap(draw, toks):
    i, j = sorted((_pos(draw, toks), _pos(draw, toks)))
    n = draw(st.integers(1, 8))
    if i + n <= j:
        toks[i : i + n], toks[j : j + n] = toks[j : j + n], toks[i : i + n]


def _m_insert(draw, toks):
    toks.insert(_pos(draw, toks, 1), " " + draw(st.sampled_from(TOKEN_POOL)) + " ")


def _m_truncate(draw, toks):
    del toks[_pos(draw, toks) :]


def _m_rename(draw, toks):
    names = sorted({t for t in toks if IDENT_RE.match(t)})
    if not names:
        return
    old = draw(st.sampled_from(names))
    new = draw(st.sampled_from(IDENTS) | st.from_regex(r"[A-Za-z_][A-Za-z0-9_]{0,12}", fullmatch=True))
    if draw(st.booleans()):  # every occurrence: the program often stays valid
        toks[:] = [new if t == old else t for t in toks]
    else:
        toks[draw(st.sampled_from([i for i, t in enumerate(toks) if t == old]))] = new


def _m_flip_type(draw, toks):
    at = [i for i, t in enumerate(toks) if t.upper() in TYPE_NAMES]
    if at:
        toks[draw(st.sampled_from(at))] = draw(st.sampled_from(TYPES))


def _m_literal(draw, toks):
    at = [i for i, t in enumerate(toks) if t[:1].isdigit() or t[:1] in "'\"%" or "#" in t]
    if at:
        toks[draw(st.sampled_from(at))] = draw(st.sampled_from(LITERALS))


def _m_char(draw, toks):
    i = _pos(draw, toks, 1)
    toks.insert(i, draw(st.text(ST_ALPHABET, min_size=1, max_size=3)))


def _m_case(draw, toks):
    i = _pos(draw, toks)
    if toks:
        toks[i] = toks[i].swapcase()


MUTATIONS = [
    _m_delete,
    _m_duplicate,
    _m_swap,
    _m_insert,
    _m_truncate,
    _m_rename,
    _m_flip_type,
    _m_literal,
    _m_char,
    _m_case,
]


@st.composite
def mutated_programs(draw):
    profile, src = CORPUS[draw(st.integers(0, len(CORPUS) - 1))]
    toks = tokenize(src)
    for _ in range(draw(st.integers(1, 4))):
        draw(st.sampled_from(MUTATIONS))(draw, toks)
    return profile, "".join(toks)


@st.composite
def gently_mutated_programs(draw):
    """Mutations that often keep the program valid, so the code generator
    and the runtime see unusual but legal programs too."""
    profile, src = CORPUS[draw(st.integers(0, len(CORPUS) - 1))]
    toks = tokenize(src)
    for _ in range(draw(st.integers(1, 3))):
        draw(st.sampled_from([_m_rename, _m_flip_type, _m_literal, _m_case]))(draw, toks)
    return profile, "".join(toks)
