"""PeriodicService (engine/clock.py): a bus's or a simulator's service thread
on the real clock runs each time the scan goes idle (the clock's
sleep_until), and on its own every period when no scan does. The waits below
are for a thread to be scheduled, never a measure of time: a service woken
by the scan answers in microseconds, its fallback period here is an hour."""

from __future__ import annotations

import queue

from softplc.runtime.engine.clock import PeriodicService, RealClock

HOUR_S = 3600.0


def test_the_service_runs_each_time_the_scan_goes_idle_not_at_its_period():
    clock = RealClock()
    calls: queue.Queue = queue.Queue()
    service = PeriodicService("test service", clock, calls.put, period_s=HOUR_S)
    service.start()
    try:
        first = calls.get(timeout=30)  # it runs once as it starts
        seen = [first]
        for _ in range(3):
            clock.sleep_until(clock.now_ns())  # a scan ends: the engine sleeps until its next release
            seen.append(calls.get(timeout=30))  # woken now, not an hour later
        assert seen == sorted(seen)  # each with the clock's time, never going back
    finally:
        service.stop()
    while not calls.empty():  # wakes that came while it ran
        calls.get_nowait()
    clock.sleep_until(clock.now_ns())  # stopped: the scan's idle no longer calls it
    assert calls.empty()


def test_without_scans_the_service_runs_every_period():
    clock = RealClock()
    calls: queue.Queue = queue.Queue()
    service = PeriodicService("test service", clock, calls.put, period_s=0.001)
    service.start()
    try:
        for _ in range(5):
            calls.get(timeout=30)
    finally:
        service.stop()


def test_a_failing_step_is_logged_and_the_service_goes_on(caplog):
    clock = RealClock()
    calls: queue.Queue = queue.Queue()
    steps = []

    def step(now_ns: int) -> None:
        steps.append(now_ns)
        calls.put(now_ns)
        if len(steps) == 1:
            raise RuntimeError("a bad frame")

    service = PeriodicService("test service", clock, step, period_s=HOUR_S)
    service.start()
    try:
        calls.get(timeout=30)
        clock.sleep_until(clock.now_ns())
        calls.get(timeout=30)  # the next idle still runs it
    finally:
        service.stop()
    assert "test service: service step failed" in caplog.text
