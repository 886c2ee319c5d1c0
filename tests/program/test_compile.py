"""program/compile.py: the libraries compiled with every program."""

from __future__ import annotations

from softplc.runtime.program.compile import _library_sources
from softplc.runtime.st.lexer import strip_comments


def test_the_libraries_read_alike_whether_comments_nest_or_not():
    # The library files are parsed once for every profile, so none may hold
    # a comment that nesting (CODESYS) and not nesting (IEC, MatIEC) read
    # differently: '(*' inside a (* *) comment.
    sources = _library_sources()
    assert len(sources) > 10
    problems: list = []
    for name, text in sources:
        nested, _ = strip_comments(text, lambda *a: problems.append(a), nested=True)
        flat, _ = strip_comments(text, lambda *a: problems.append(a), nested=False)
        assert problems == [] and nested == flat, name
