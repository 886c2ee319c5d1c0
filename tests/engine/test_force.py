"""Engine.force / unforce (a value held against the program and the
drivers) and Engine.load (variables set before the first scan)."""

from __future__ import annotations

from softplc.runtime.engine.scan import Engine
from softplc.runtime.plugin.driver import Driver, DriverStatus

from .conftest import compile_st, task

SOURCE = """
PROGRAM Main
VAR count : INT; seen : INT; inp AT %IW0 : INT; out AT %QW0 : INT; END_VAR
seen := inp;
count := count + 1;
out := count;
END_PROGRAM
"""


class Wire(Driver):
    """A driver that writes %IW0 from its own counter and records the %QW0 it is handed."""

    name = "wire"

    def __init__(self) -> None:
        self.sent: list = []
        self.value = 100

    def read_inputs(self, image) -> None:
        self.value += 1
        image.write("%IW0", self.value)

    def write_outputs(self, image) -> None:
        self.sent.append(image.read("%QW0"))

    def status(self) -> DriverStatus:
        return DriverStatus(True, "")


def test_set_before_start_is_an_initial_value():
    engine = Engine(compile_st(SOURCE), [task("T", 10, "Main")])
    engine.set("Main.count", 41)  # no KeyError '_G': the program is loaded first
    assert engine.get("Main.count") == 41 and not engine.started
    engine.run(cycles=1)
    assert engine.get("Main.count") == 42
    engine.stop()


def test_a_force_holds_over_the_program_and_the_drivers(engines):
    wire = Wire()
    engine = engines(SOURCE, [task("T", 10, "Main")], drivers=[wire])
    holder, attr, _ty = engine.variable("Main.count")
    engine.force("MAIN.COUNT", lambda: setattr(holder, attr, 7))
    engine.force("%IW0", lambda: engine.image.write("%IW0", -5))
    engine.run(cycles=3)
    assert engine.get("Main.count") == 7  # count := count + 1 ran, the force came after
    assert engine.get("Main.seen") == -5  # the program saw the forced input, not the driver's
    assert wire.sent == [8, 8, 8]  # computed from the forced value in each scan
    assert engine.unforce("MAIN.COUNT") and not engine.unforce("MAIN.COUNT")
    engine.unforce("%IW0")
    engine.run(cycles=1)
    assert engine.get("Main.count") == 8 and engine.get("Main.seen") == 104
