"""The generic simulated CANopen slave as the slave tests use it: a
RecordingSlave that writes its hooks down, on the LTMR's EDS (only its
object dictionary), at node 40 = 0x28 as in the LTMR manual's examples."""

from __future__ import annotations

import importlib.resources

import pytest

from softplc.runtime.io.canopen.slave import SimulatedCanopenSlave

NODE = 40


def eds_path(name: str):
    return importlib.resources.as_file(importlib.resources.files("softplc.io_config") / "eds" / name)


class RecordingSlave(SimulatedCanopenSlave):
    """The generic slave, with its hooks written down."""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self.events: list = []

    def on_state_change(self, old, new):
        self.events.append(("state", old, new))

    def on_reset_application(self):
        self.events.append(("reset application",))
        super().on_reset_application()

    def on_comm_error(self):
        self.events.append(("comm error",))

    def on_comm_restored(self):
        self.events.append(("comm restored",))

    def on_rpdo(self, number):
        self.events.append(("rpdo", number))


@pytest.fixture
def slave(bench):
    with eds_path("ltmr.eds") as path:
        made = RecordingSlave(NODE, eds=str(path), settings=bench.settings, clock=bench.clock, pump=bench.pump)
    return bench.add(made)
