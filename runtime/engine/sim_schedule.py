"""The faults of [[sim]] faults = [...] (config/sim_faults.py), fired at
their times: simulator.inject(fault, value, True) at `at`, and
inject(fault, value, False) `for` later.

A driver that exchanges no image data, placed after the simulators and
before the bus drivers: in virtual time it fires at each tick, once the
simulators have moved to the tick's time and before the drivers read the
bus, so a fault at 20 s is on the bus of the scan released at 20 s, the same
way every run; in real time it fires at the start of each scan. The
simulators are the ones the buses built (BuildContext.simulators); it knows
no device, only that a simulator takes inject().
"""

from __future__ import annotations

import heapq
import logging
from typing import Any

from ..image.memory import ProcessImage
from ..plugin.driver import Driver, DriverStatus

log = logging.getLogger("softplc")


class SimSchedule(Driver):
    name = "sim faults"

    def __init__(self, clock, sims, simulators: dict[str, Any]) -> None:
        """sims: the configuration's SimConfigs; simulators: [[sim]] name -> simulator."""
        self.clock = clock
        self._due: list[tuple[int, int, str, Any, bool]] = []  # (time, order, sim name, event, on)
        self.simulators = simulators
        self.fired = 0
        order = 0
        for sim in sims:
            for event in sim.faults:
                heapq.heappush(self._due, (event.at_ns, order, sim.name, event, True))
                order += 1
                if event.for_ns is not None:
                    heapq.heappush(self._due, (event.at_ns + event.for_ns, order, sim.name, event, False))
                    order += 1

    def advance_to(self, now_ns: int) -> None:
        self._fire(now_ns)

    def read_inputs(self, image: ProcessImage) -> None:
        if not self.clock.virtual:
            self._fire(self.clock.now_ns())

    def write_outputs(self, image: ProcessImage) -> None:
        pass

    def _fire(self, now_ns: int) -> None:
        while self._due and self._due[0][0] <= now_ns:
            at, _order, name, event, on = heapq.heappop(self._due)
            value = "" if event.value is None else f" {event.value}"
            log.warning("sim %s: fault %s%s %s at %.3f s", name, event.fault, value, "on" if on else "off", at / 1e9)
            self.simulators[name].inject(event.fault, event.value, on)
            self.fired += 1

    def status(self) -> DriverStatus:
        left = len(self._due)
        return DriverStatus(True, f"sim faults: {self.fired} fired, {left} to come" if left else "")
