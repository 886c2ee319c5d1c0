""" "Did you mean" for an unknown name, from an index of the known names.

``NameIndex(names).closest(key, cutoff)`` is the name that
``difflib.get_close_matches(key, names, n=1, cutoff=cutoff)`` picks (the
same score, SequenceMatcher's ratio, and the same tie-break, the larger
name), spelled as first declared; but a name is scored only when it can
reach the cutoff: its length (the bound difflib's real_quick_ratio checks),
then which characters it shares with the key (a bit mask each, an upper
bound of quick_ratio), then quick_ratio itself, count against count. The
answer is kept per key: a name unknown a thousand times is looked up once.
A project with thousands of references to a missing library spent most of
its check in difflib, which scores every name for every error.
"""

from __future__ import annotations

import collections
from collections.abc import Iterable
from difflib import SequenceMatcher

#: how many searches were computed (not answered from the memo): for tests
SEARCHES = 0


def _mask(text: str) -> int:
    m = 0
    for ch in text:
        m |= 1 << (ord(ch) & 63)  # A-Z, 0-9 and _ fall on different bits
    return m


def _ratio(matches: int, length: int) -> float:
    return 2.0 * matches / length if length else 1.0  # difflib's _calculate_ratio


class NameIndex:
    """The known names of one kind (variables in scope, functions, fields),
    by length; UPPER keys are looked up, the spelling declared first is
    returned."""

    def __init__(self, names: Iterable[str]) -> None:
        self.spelled: dict[str, str] = {}
        for n in names:
            self.spelled.setdefault(n.upper(), n)
        self._by_length: dict[int, list] = {}
        for u in self.spelled:
            self._by_length.setdefault(len(u), []).append((u, _mask(u)))
        self._memo: dict[tuple[str, float], str | None] = {}

    def closest(self, key: str, cutoff: float) -> str | None:
        """The known name closest to the UPPER key, as declared; None
        under the cutoff."""
        try:
            return self._memo[key, cutoff]
        except KeyError:
            pass
        best = self._search(key, cutoff)
        found = self.spelled[best] if best is not None else None
        self._memo[key, cutoff] = found
        return found

    def _search(self, key: str, cutoff: float) -> str | None:
        global SEARCHES
        SEARCHES += 1
        lb = len(key)
        kmask = _mask(key)
        kcount: collections.Counter | None = None
        matcher = SequenceMatcher()
        matcher.set_seq2(key)
        best: tuple[float, str] | None = None
        for la, bucket in self._by_length.items():
            length = la + lb
            if _ratio(min(la, lb), length) < cutoff:  # real_quick_ratio
                continue
            for name, mask in bucket:
                # at most la - (x's letters the key lacks) characters match,
                # and at most lb - (the key's letters x lacks)
                bound = min(la - (mask & ~kmask).bit_count(), lb - (kmask & ~mask).bit_count())
                if _ratio(bound, length) < cutoff:
                    continue
                if kcount is None:
                    kcount = collections.Counter(key)
                theirs = collections.Counter(name)
                if _ratio(sum(min(n, kcount[c]) for c, n in theirs.items()), length) < cutoff:  # quick_ratio
                    continue
                matcher.set_seq1(name)
                score = matcher.ratio()
                if score >= cutoff and (best is None or (score, name) > best):
                    best = (score, name)
        return best[1] if best is not None else None
