"""The servers' process's side of the pipe to the PLC (surfaces/child.py)."""

from __future__ import annotations

import multiprocessing

import pytest

from softplc.runtime.surfaces.child import _Link
from softplc.runtime.surfaces.process import PlcBusy


def test_a_call_the_plc_does_not_answer_in_time_says_so():
    """The web page's online change waited 30 s for a PLC busy compiling on
    a loaded host: a bare TimeoutError reached the page as a 500 with
    "TimeoutError: " and nothing after it. Now a PlcBusy (a TimeoutError:
    the page answers 504) that says what happened; the call is forgotten."""
    plc_end, servers_end = multiprocessing.Pipe()
    link = _Link(servers_end)
    with pytest.raises(PlcBusy, match=r"^the PLC did not answer within 0.2 s: busy, or stopping$"):
        link.call("request", timeout=0.2)
    assert plc_end.recv()[:3] == ("call", 1, "request")  # it was asked, and nobody answered
    assert not link._waiting and not link._done
    plc_end.close()
    servers_end.close()
