"""On the real clock the snapshot hub copies between two scans, in a thread
of its own (engine/snapshot.py): every snapshot is still the state at the
end of one scan, and a scan never runs while a copy is under way."""

from __future__ import annotations

import threading

from softplc.runtime.engine.clock import RealClock
from softplc.runtime.engine.places import Resolver
from softplc.runtime.engine.snapshot import SnapshotHub

from .conftest import Scanning, task, wait_until

SRC = """
VAR_GLOBAL seen AT %QD2 : DINT; END_VAR
PROGRAM Main
VAR
    n : DINT;
    copies : ARRAY[1..500] OF DINT;
    i : INT;
END_VAR
n := n + 1;
FOR i := 1 TO 500 DO copies[i] := n; END_FOR
seen := n;
END_PROGRAM
"""


def test_every_snapshot_on_the_real_clock_is_the_end_of_one_scan(engines):
    e = engines(SRC, [task("Main", 2, "Main")], clock=RealClock(spin_ns=0))
    hub = SnapshotHub(e, period_s=0)  # a copy after every scan: the copier is always busy
    paths = ["Main.n", "seen", *(f"Main.copies[{i}]" for i in range(1, 501))]
    hub.watch("test", paths)
    scan = threading.Thread(target=e.run, kwargs={"cycles": 150}, name="test-scan")
    scan.start()
    snaps = []
    seen = 0
    while scan.is_alive() or (hub.latest is not None and hub.latest.sequence > seen):
        snap = hub.next_after(seen, timeout=1.0)
        if snap is not None:
            snaps.append(snap)
            seen = snap.sequence
    scan.join()
    assert len(snaps) >= 20, len(snaps)
    for snap in snaps:  # the scan's n everywhere: an element, the located global, the counter
        n = snap.values["Main.n"]
        assert n == snap.cycle, (snap.sequence, n, snap.cycle)
        assert snap.values["seen"] == n and {snap.values[p] for p in paths[2:]} == {n}, snap.sequence
    assert [s.values["Main.n"] for s in snaps] == sorted({s.values["Main.n"] for s in snaps})


RESTARTED = """
VAR_GLOBAL zero : DINT; faulted : BOOL; END_VAR
PROGRAM Main
VAR n : DINT; d : DINT; END_VAR
n := n + 1;
IF n = 20 AND NOT faulted THEN
    faulted := TRUE;
    d := n / zero;
END_IF
END_PROGRAM
"""


def test_after_a_restart_the_scans_go_on_while_the_paths_are_resolved_again(engines, monkeypatch):
    """New program instances (a restart, an online change): the watched
    paths are resolved again by the copier while the scans go on; the
    scan used to wait for it (20-30 ms for the default plant's 860 paths,
    two periods of a 10 ms task). Here the copier's resolving is held at
    its first path, its resolver already the new program's (a scan that
    saw that resolver asked for a copy and waited for the copier behind
    the whole resolving: a live soak's 100 ms ticks), until the engine
    has scanned 20 more times; then the snapshots follow the new
    instance. The new instance is told from the stopped one by its
    counting: n goes on with every scan (the stopped one's n stays at 20)
    and counts no scan from before the restart."""
    e = engines(RESTARTED, [task("Main", 2, "Main")], clock=RealClock(spin_ns=0))
    hub = SnapshotHub(e, period_s=0)
    hub.watch("test", ["Main.n", "faulted"])
    held, resolving = threading.Event(), threading.Event()
    place = Resolver.place

    def held_place(resolver, path):  # the copier's own resolving, once the test lets it
        if threading.current_thread().name == "softplc-snapshot":
            resolving.set()
            assert held.wait(20), "never let go"
        return place(resolver, path)

    monkeypatch.setattr(Resolver, "place", held_place)
    scanning = Scanning(e, pause_s=0).start()
    try:
        wait_until(lambda: e.faulted_tasks(), "the fault at n = 20")
        before = e.cycle
        e.request_restart()
        assert resolving.wait(20), "the copier did not resolve the paths again"
        at = e.cycle
        wait_until(lambda: e.cycle >= at + 20, "20 scans while the paths are being resolved")
        held.set()
        first = wait_until(lambda: (s := hub.wait_fresh(5)).generation == 1 and s, "a snapshot after the restart")
        later = wait_until(lambda: (s := hub.wait_fresh(5)).cycle > first.cycle and s, "a later snapshot")
        assert e.generation == 1 and later.generation == 1
        assert first.values["faulted"] and later.values["faulted"]  # a global: kept by the restart
        assert later.values["Main.n"] - first.values["Main.n"] == later.cycle - first.cycle
        assert 20 <= first.values["Main.n"] <= first.cycle - before
    finally:
        held.set()
        scanning.stop()


def test_paths_that_fail_to_resolve_after_a_restart_are_resolved_at_the_next_scan(engines, monkeypatch, caplog):
    """The copier's resolving after a restart fails once (an unforeseen
    error, injected at its first path): it is logged, the snapshots keep
    the old places for a scan, and the next scan has the copier resolve
    them again. It used to take the new program's resolver before the
    resolving and never try again: the snapshots went on reading the
    stopped instance (n frozen at 20) for good."""
    e = engines(RESTARTED, [task("Main", 2, "Main")], clock=RealClock(spin_ns=0))
    hub = SnapshotHub(e, period_s=0)
    hub.watch("test", ["Main.n", "faulted"])
    failures = []
    place = Resolver.place

    def failing_once(resolver, path):
        if threading.current_thread().name == "softplc-snapshot" and not failures:
            failures.append(path)
            raise RuntimeError("injected: resolving failed")
        return place(resolver, path)

    monkeypatch.setattr(Resolver, "place", failing_once)
    scanning = Scanning(e, pause_s=0).start()
    try:
        wait_until(lambda: e.faulted_tasks(), "the fault at n = 20")
        e.request_restart()
        wait_until(lambda: failures, "the copier's first resolving after the restart")
        first = wait_until(lambda: (s := hub.wait_fresh(5)).generation == 1 and s, "a snapshot after the restart")
        later = wait_until(
            lambda: (s := hub.wait_fresh(5)).cycle > first.cycle + 5 and s, "a snapshot five scans later"
        )
        assert later.values["Main.n"] - first.values["Main.n"] == later.cycle - first.cycle  # the new instance
    finally:
        scanning.stop()
    assert "injected: resolving failed" in caplog.text
