"""CAN: the [[can]] buses every CAN protocol shares (bus.py: python-can
endpoints, the virtual-time BusPump), and the simulated devices that sit
on them as CAN nodes ([[sim]] with bus and node_id).

A device that simulates a CAN node gets ``simulator(sim, CanSimContext)``
called: sim.at is its CanNode, the context has the bus settings, the clock
and (virtual time) the pump its endpoint must use.

The PLC side of a bus is one CanPort (port.py) that every protocol driver
on it shares: port_of(ctx, bus).

Public names: BUS, BusPump, BusSettings, CanEndpoint, CanNode, CanBusConfig,
CanPort, CanSimContext, open_bus, port_of, pump_of, settings_of.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ...plugin.registry import registry
from ...plugin.seams import BuildContext, Bus, Contribution
from .bus import BusPump, BusSettings, CanEndpoint, open_bus
from .config import CanAttachment, CanBusConfig, CanNode, CanSection
from .port import CanPort, shared_port
from .readlog import read_log
from .wire import CanWireLog, wire_log_of


@dataclass
class CanSimContext:
    settings: BusSettings
    clock: Any
    pump: BusPump | None


def settings_of(bus: CanBusConfig) -> BusSettings:
    return BusSettings(bus.interface, str(bus.channel), bus.bitrate, dict(bus.options))


def pump_of(ctx: BuildContext) -> BusPump | None:
    """The BusPump every CAN endpoint of one engine shares in virtual time
    (None in real time: each endpoint has its receive thread)."""
    if "can.pump" not in ctx.shared:
        ctx.shared["can.pump"] = BusPump() if ctx.virtual else None
    return ctx.shared["can.pump"]


def port_of(ctx: BuildContext, bus: CanBusConfig) -> CanPort:
    """The PLC's one connection to the [[can]] bus, shared by every protocol
    driver of the engine on it (port.py); its frames recorded when the run
    records its wire (wire.py)."""
    port = shared_port(
        ctx.shared,
        bus.name,
        settings_of(bus),
        pump_of(ctx),
        clock=ctx.clock,
        fail_fast=bus.missing_adapter == "fail",
    )
    wire = wire_log_of(ctx, [bus.name])
    if wire is not None and port.wire is None:
        port.wire = wire.channel(bus.name)
    return port


def _build(config, ctx: BuildContext) -> Contribution:
    buses = {bus.name: bus for bus in config.can}
    # made before the protocols' drivers ask for their ports: channels in the file's order,
    # and the log first among the drivers, so it is closed after them
    wire = wire_log_of(ctx, list(buses)) if buses else None
    devices = registry().sim_types()
    sims = []
    for sim in config.sims:
        device = devices[sim.type]
        if device.bus != BUS.name:
            continue
        context = CanSimContext(settings_of(buses[sim.at.bus]), ctx.clock, pump_of(ctx))
        assert device.simulator is not None  # the registry has no simulating device without one
        sims.append(ctx.simulated(sim, device.simulator(sim, context)))
    return Contribution(simulators=sims, drivers=[wire] if wire is not None else [])


BUS = Bus(
    name="can",
    order=20,
    sections=(CanSection(),),
    attachment=CanAttachment(),
    build=_build,
    read_log=read_log,
)

__all__ = [
    "BUS",
    "BusPump",
    "BusSettings",
    "CanBusConfig",
    "CanEndpoint",
    "CanNode",
    "CanPort",
    "CanSimContext",
    "CanWireLog",
    "open_bus",
    "port_of",
    "pump_of",
    "settings_of",
]
