"""background(): the switch interval lowered while any background work runs,
Python's again when the last one ends, whatever the order they end in."""

import sys
import threading

from softplc.runtime.engine.lock_share import SWITCH_S, background


def test_the_interval_is_lowered_inside_and_put_back_after():
    before = sys.getswitchinterval()
    with background():
        assert sys.getswitchinterval() == min(before, SWITCH_S)
    assert sys.getswitchinterval() == before


def test_two_threads_overlapping_leave_the_interval_as_it_was():
    # thread a enters, b enters, a leaves while b still works, then b:
    # two plain save-and-restore blocks left it at 0.5 ms for good
    before = sys.getswitchinterval()
    a_in, b_in, a_out = threading.Event(), threading.Event(), threading.Event()
    seen = {}

    def a() -> None:
        with background():
            a_in.set()
            b_in.wait(5)
        a_out.set()

    def b() -> None:
        a_in.wait(5)
        with background():
            b_in.set()
            a_out.wait(5)
            seen["after a left"] = sys.getswitchinterval()

    threads = [threading.Thread(target=a), threading.Thread(target=b)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(10)
    assert seen["after a left"] == min(before, SWITCH_S)
    assert sys.getswitchinterval() == before


def test_an_exception_inside_puts_the_interval_back():
    before = sys.getswitchinterval()
    try:
        with background():
            raise ValueError("boom")
    except ValueError:
        pass
    assert sys.getswitchinterval() == before
