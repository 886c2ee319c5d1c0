"""SFC steps where a user looks at a running PLC: a step is a variable of
its POU instance (X, T), so the testing API's watch and trace, the
engine's --watch (runtime/engine/monitor.py) and --final-json
(st/valuejson.py) show it like any struct."""

from __future__ import annotations

import json

from softplc.runtime.engine.monitor import Watch
from softplc.runtime.st.valuejson import encode_value
from softplc.testing import PLC

SEQUENCE = """
PROGRAM Main
VAR go : BOOL; END_VAR
INITIAL_STEP wait: END_STEP
STEP work: END_STEP
TRANSITION FROM wait TO work := go; END_TRANSITION
TRANSITION FROM work TO wait := work.T >= T#30ms; END_TRANSITION
END_PROGRAM
"""


def test_the_testing_api_traces_step_flags():
    with PLC.from_st(SEQUENCE) as plc:
        plc.watch("Main.wait.X", "Main.work.X")
        plc.step(2)
        plc["Main.go"] = True
        plc.step(1)
        plc["Main.go"] = False
        plc.step(5)
        ms = 1_000_000
        # work is active from the cycle at t = 20 ms until its 30 ms are up (t = 50 ms)
        assert plc.trace.changes("Main.work.X") == [(0, False), (20 * ms, True), (50 * ms, False)]
        assert plc.trace.changes("Main.wait.X") == [(0, True), (20 * ms, False), (50 * ms, True)]


def test_watch_and_final_json_show_a_step_as_x_and_t():
    with PLC.from_st(SEQUENCE) as plc:
        plc["Main.go"] = True
        plc.step(3)  # t = 0: to work; t = 10, 20: work.T = 10, 20 ms
        watch = Watch(plc.engine, ["Main.work.X", "Main.work.T", "Main.work"])
        assert [s.kind for s in watch.signals()] == ["bool", "int", "text"]
        assert watch.raw()[:2] == [1, 20]
        assert json.loads(watch.raw()[2]) == {"X": True, "T": "T#20ms"}
        shown = dict(watch.shown())
        assert shown["Main.work.X"] == "true" and shown["Main.work.T"] == '"T#20ms"'  # as exec writes a TIME
        # --final-json encodes the instance, steps included
        _name, info, instance = next(iter(plc.engine.instances.values()))
        encoded = encode_value(info.fbtype, instance)
        assert encoded["wait"] == {"X": False, "T": "T#0ms"} and encoded["work"]["X"] is True


PUMPING = """
PROGRAM Main
VAR go : BOOL; END_VAR
INITIAL_STEP idle: END_STEP
STEP fill: pump(N); END_STEP
TRANSITION FROM idle TO fill := go; END_TRANSITION
TRANSITION FROM fill TO idle := NOT go; END_TRANSITION
ACTION pump: ; END_ACTION
END_PROGRAM
"""


def test_an_actions_q_and_a_are_watched_and_traced_like_a_steps_flags():
    # Main.pump.Q / Main.pump.A (ed.3 6.7.4; CODESYS and TwinCAT watch _pump.x)
    with PLC.from_st(PUMPING) as plc:
        plc.watch("Main.pump.Q", "Main.pump.A", "Main.fill.X")
        plc.step(1)
        plc["Main.go"] = True
        plc.step(2)
        plc["Main.go"] = False
        plc.step(2)
        ms = 1_000_000
        # fill is active at t = 10, 20 ms; pump's final scan (A, not Q) at t = 30 ms
        assert plc.trace.changes("Main.fill.X") == [(0, False), (10 * ms, True), (30 * ms, False)]
        assert plc.trace.changes("Main.pump.Q") == [(0, False), (10 * ms, True), (30 * ms, False)]
        assert plc.trace.changes("Main.pump.A") == [(0, False), (10 * ms, True), (40 * ms, False)]
        watch = Watch(plc.engine, ["Main.pump.Q", "Main.pump"])
        assert [s.kind for s in watch.signals()] == ["bool", "text"]
        assert json.loads(watch.raw()[1]) == {"Q": False, "A": False}
        _name, info, instance = next(iter(plc.engine.instances.values()))
        assert encode_value(info.fbtype, instance)["pump"] == {"Q": False, "A": False}
