"""Helpers of the runtime library's tests (test_rt_*.py)."""

from __future__ import annotations

from softplc.runtime.st import types as T
from softplc.runtime.st.rtlib import rtlib as r

STRING = T.StringType(80)
WSTRING = T.StringType(80, wide=True)
NAN = float("nan")
INF = float("inf")


def conv(src, dst, v):
    return r.make_converter(src, dst)(v)


def ns(text, cat):
    return r.parse_temporal(text, cat)
