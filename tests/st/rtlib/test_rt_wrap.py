"""rt_wrap.py: the normalisation of a value stored into its type."""

from __future__ import annotations

from softplc.runtime.st import types as T
from softplc.runtime.st.rtlib import rt_wrap as r


def test_wrap():
    assert r.wrap(T.INT, 32768) == -32768
    assert r.wrap(T.SINT, 300) == 44
    assert r.wrap(T.UINT, -1) == 65535
    assert r.wrap(T.BYTE, 256 + 7) == 7
    assert r.wrap(T.ULINT, -1) == 2**64 - 1
    assert r.wrap(T.REAL, 0.1) == 0.10000000149011612
    assert r.wrap(T.BOOL, 2) is True
    assert r.wrap(T.StringType(3), "abcdef") == "abc"
    assert r.wrapper(T.INT) is r.wrapper(T.INT)  # cached


def test_wrap_time():
    assert r.wrap_time(T.TIME, 2**31) == -(2**31)
    assert r.wrap_time(T.TIME, -5000) == -5000
    assert r.wrap_time(T.TOD, 86_400_000 + 5) == 5  # wraps at midnight
    assert r.wrap_time(T.TOD, -1) == 86_399_999
    assert r.wrap_time(T.DATE, 86_400 * 3 + 100) == 86_400 * 3  # kept at midnight
    assert r.wrap_time(T.DT, -1) == 2**32 - 1
