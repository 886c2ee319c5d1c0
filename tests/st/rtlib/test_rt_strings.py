"""rt_strings.py: the IEC string functions, with the CODESYS examples."""

from __future__ import annotations

from softplc.runtime.st.rtlib import rt_strings as r

# ---------------------------------------------------------------- strings


def test_string_functions_codesys_examples():
    assert r.LEN("SUSI") == 4
    assert r.LEFT("SUSI", 3) == "SUS"
    assert r.RIGHT("SUSI", 3) == "USI"
    assert r.MID("SUSI", 2, 2) == "US"
    assert r.CONCAT("SUSI", "WILLI") == "SUSIWILLI"
    assert r.CONCAT("a", "b", "c") == "abc"
    assert r.INSERT("SUSI", "XY", 2) == "SUXYSI"
    assert r.DELETE("SUXYSI", 2, 3) == "SUSI"
    assert r.REPLACE("SUXYSI", "K", 2, 2) == "SKYSI"
    assert r.FIND("abcdef", "de") == 4
    assert r.FIND("abcdef", "x") == 0


def test_string_edge_cases_never_raise():
    assert r.LEFT("SUSI", 0) == ""
    assert r.LEFT("SUSI", -1) == ""
    assert r.LEFT("SUSI", 10) == "SUSI"
    assert r.RIGHT("SUSI", 0) == ""
    assert r.RIGHT("SUSI", 10) == "SUSI"
    assert r.MID("SUSI", 2, 0) == ""
    assert r.MID("SUSI", 2, 5) == ""
    assert r.MID("SUSI", 10, 3) == "SI"
    assert r.MID("SUSI", 2, -1) == ""
    assert r.INSERT("SUSI", "XY", 0) == "XYSUSI"
    assert r.INSERT("SUSI", "XY", -3) == "XYSUSI"
    assert r.INSERT("SUSI", "XY", 9) == "SUSIXY"
    assert r.DELETE("SUSI", 2, 0) == "SUSI"
    assert r.DELETE("SUSI", 2, 5) == "SUSI"
    assert r.DELETE("SUSI", 10, 2) == "S"
    assert r.DELETE("SUSI", -1, 2) == "SUSI"
    assert r.REPLACE("SUSI", "XY", 1, 9) == "SUSIXY"
    assert r.REPLACE("SUSI", "XY", 1, 0) == "XYUSI"
    assert r.REPLACE("SUSI", "XY", -2, 2) == "SXYUSI"
    assert r.FIND("abc", "") == 0
    assert r.FIND("", "a") == 0
