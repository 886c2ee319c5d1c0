"""A user's file parsed once per way of reading it, in one process.

`softplc check` of files with errors checks them again under every other
profile (check_summary.note_other_profiles) and for a dialect hint: five
parses of the same text. The parse depends on the profile only through
whether (* *) comments nest (st/syntax/parser.py), so a file is parsed once for
each answer and every later check gets a fresh copy (the checker annotates
the AST) from the pickle kept here, in memory only, at most _MAX_BYTES of
them, the oldest dropped first. Only checks keep them (check_files).
"""

from __future__ import annotations

import hashlib
import pickle
from collections import OrderedDict
from collections.abc import Callable

from ..st.diagnostics import DiagnosticBag
from ..st.importers import st_views
from ..st.profile import Profile
from ..st.syntax.parser import parse_source

_MAX_BYTES = 64 * 1024 * 1024
_KEPT: OrderedDict[tuple, bytes] = OrderedDict()
_size = 0


def parse_views(
    name: str, text: str, profile: Profile, words: Callable[[str], set], keep: bool
) -> tuple[list, list, set]:
    """(SourceFiles of the file's ST views, their diagnostics, words(view
    text) of them all), new objects each call; keep: kept for the next call
    (a check; compiling to run keeps nothing)."""
    global _size
    key = (name, hashlib.sha256(text.encode()).digest(), profile.nested_comments)
    data = _KEPT.get(key) if keep else None
    if data is not None:
        _KEPT.move_to_end(key)
        return pickle.loads(data)
    diags = DiagnosticBag()
    files: list = []
    found: set = set()
    for view in st_views(name, text, diags):  # st/importers: PLCopen XML, TwinCAT as ST
        files.append(parse_source(view.text, name, diags, profile, view.lowered, view.origins))
        found |= words(view.text)
    parsed = (files, diags.items, found)
    if not keep:
        return parsed
    try:
        data = pickle.dumps(parsed, protocol=pickle.HIGHEST_PROTOCOL)
    except RecursionError:  # an expression hundreds of operators long: parsed, not kept
        return parsed
    _KEPT[key] = data
    _size += len(data)
    while _size > _MAX_BYTES and len(_KEPT) > 1:
        _size -= len(_KEPT.popitem(last=False)[1])
    return pickle.loads(data)  # (a copy: the objects above would be annotated by this check)
