"""The one snapshot API and the one write/force API every surface uses
(engine/snapshot.py, engine/access.py): what a reader sees is a whole scan,
a write lands at the start of the next scan, a refused write names the
variable and where to allow it."""

from __future__ import annotations

import pytest

from softplc.runtime.engine.access import Access, AccessDenied, Permission
from softplc.runtime.engine.places import PathError
from softplc.runtime.engine.snapshot import SnapshotHub

from .conftest import Scanning, task

SRC = """
TYPE E_Mode : (Idle, Run, Fault); END_TYPE
TYPE S_Pair : STRUCT a : INT; b : BOOL; END_STRUCT END_TYPE
VAR_GLOBAL total : DINT; END_VAR
PROGRAM Main
VAR
    n : INT;
    setpoint : REAL := 12.5;
    mode : E_Mode := Run;
    pair : S_Pair;
    out AT %QW2 : INT;
    t : TON;
END_VAR
n := n + 1;
total := total + 1;
out := n * 10;
pair.a := n;
t(IN := TRUE, PT := T#1S);
END_PROGRAM
"""


def test_a_snapshot_holds_the_watched_values_of_one_scan_with_their_types(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    hub = SnapshotHub(e, attach=False)
    assert hub.watch("web", ["main.N", "total", "Main.mode", "Main.pair", "%QW2", "Main.t.ET"]) == [
        "Main.n",
        "total",
        "Main.mode",
        "Main.pair",
        "%QW2",
        "Main.t.ET",
    ]
    e.run(cycles=3)
    snap = hub.capture()
    assert snap.cycle == 3 and snap.time_ns == 20_000_000
    assert snap.values["Main.n"] == 3 and snap.values["total"] == 3 and snap.values["%QW2"] == 30
    assert snap.json("Main.mode") == "Run" and snap.json("Main.pair") == {"a": 3, "b": False}
    assert snap.json("Main.t.ET") == "T#20ms"
    assert [t.name for t in snap.tasks] == ["Main"] and snap.tasks[0].cycles == 3
    assert snap.image["Q"][4:6] == (30).to_bytes(2, "little")
    e.run(cycles=1)
    assert snap.values["Main.n"] == 3  # a snapshot does not change after it was taken
    assert snap.json("Main.pair") == {"a": 3, "b": False}


def test_a_wrong_path_is_refused_naming_it(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    hub = SnapshotHub(e, attach=False)
    with pytest.raises(PathError, match="Main.nn"):
        hub.watch("web", ["Main.nn"])


def test_snapshots_are_taken_at_the_end_of_a_scan_while_the_engine_runs_in_its_thread(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    hub = SnapshotHub(e, period_s=3600)  # only when asked
    hub.watch("test", ["Main.n"])
    e.run(cycles=2)
    assert hub.latest is not None and hub.latest.values["Main.n"] == 1  # the first scan's, then the period
    scan = Scanning(e, pause_s=0).start()
    try:
        first = hub.wait_fresh(timeout=30)
        second = hub.wait_fresh(timeout=30)
    finally:
        scan.stop()
    assert second.sequence > first.sequence and second.values["Main.n"] > first.values["Main.n"] >= 2


def test_writes_and_forces_are_checked_against_the_surface_permission(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    access = Access(
        e, {"opcua": Permission(("Main.setpoint", "%QW*"), where="[opcua] writable"), "web": Permission(("*",))}
    )
    assert access.write("MAIN.SETPOINT", 40.0, surface="opcua") == "Main.setpoint"
    assert e.get("Main.setpoint") == 40.0
    with pytest.raises(AccessDenied, match=r"Main\.n: opcua may not write it \(allow it in \[opcua\] writable\)"):
        access.write("Main.n", 5, surface="opcua")
    with pytest.raises(AccessDenied, match="modbus_server may not force"):
        access.force("Main.n", 5, surface="modbus_server")
    with pytest.raises(ValueError, match="Main.mode"):
        access.write("Main.mode", "Walk", surface="web")  # no such enumerator
    access.write("Main.mode", "Fault", surface="web")
    assert e.get("Main.mode") == 2


def test_a_force_holds_against_the_program_until_unforced(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    access = Access(e, {"web": Permission(("Main.*",))})
    access.force("Main.n", 100, surface="web")
    e.run(cycles=3)
    assert e.get("Main.n") == 100 and e.get("%QW2") == 1010  # the program saw 100, wrote 101 * 10
    assert access.forced == {"Main.n": 100}
    hub = SnapshotHub(e, attach=False)
    assert hub.capture().forced == {"Main.n": 100}
    access.unforce("Main.n", surface="web")
    e.run(cycles=2)
    assert e.get("Main.n") == 102 and access.forced == {}
    with pytest.raises(KeyError, match="Main.n is not forced"):
        access.unforce("Main.n", surface="web")


def test_a_write_from_another_thread_lands_at_the_start_of_the_next_scan(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    access = Access(e, {"web": Permission(("*",))})
    hub = SnapshotHub(e, period_s=3600)
    hub.watch("test", ["Main.n", "%QW2"])
    holder, attr, _ty = e.variable("Main.n")
    ends: list = []  # Main.n at the end of every scan (in the scan's thread)
    e.after_tick.append(lambda _e: ends.append(getattr(holder, attr)))
    scan = Scanning(e, pause_s=0).start()
    try:
        hub.wait_fresh(timeout=30)
        access.write("Main.n", -1000, surface="web")  # waits for the scan that applies it
        snap = hub.wait_fresh(timeout=30)
    finally:
        scan.stop()
    # the scan that applied the write ran the program after it: that scan ended
    # with -999, the one before with what counting alone gave (however many
    # scans the busy host ran before and after)
    k = ends.index(-999)
    assert k > 0 and ends[k - 1] > 0 and ends[k + 1 : k + 3] == [-998, -997][: len(ends) - k - 1]
    # the snapshot is one scan's end: n and %QW2 (n * 10 as a WORD) agree
    n = snap.values["Main.n"]
    assert n in ends[k:] and snap.values["%QW2"] == (n * 10) & 0xFFFF
