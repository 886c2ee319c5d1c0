"""Plain CAN: devices with a protocol of their own on raw 11-bit frames (no
CANopen), on the [[can]] buses ([[plaincan]] tables, config.py). A device
declares how it is driven with a PlainCanKind (kind.py) in its Device's
`node_kind`; the driver (driver.py) shares the PLC's CanPort with the
CANopen master on the same bus.

Public names: BUS, MalformedFrame, NodeContext, NodeOptions, PlainCanDriver,
PlainCanKind, PlainCanNode, PlainCanNodeConfig.
"""

from __future__ import annotations

from ...plugin.registry import registry
from ...plugin.seams import BuildContext, Bus, Contribution
from ..can import port_of
from .config import PlainCanSection, kinds
from .driver import PlainCanDriver
from .kind import MalformedFrame, NodeContext, NodeOptions, PlainCanKind, PlainCanNode, PlainCanNodeConfig


def _build(config, ctx: BuildContext) -> Contribution:
    nodes = config.sections.get("plaincan") or []
    if not nodes:
        return Contribution()
    by_kind = kinds(registry())
    drivers: dict[str, PlainCanDriver] = {}
    for cfg in nodes:
        driver = drivers.get(cfg.bus)
        if driver is None:
            bus = next(b for b in config.can if b.name == cfg.bus)
            driver = drivers[cfg.bus] = PlainCanDriver(cfg.bus, port_of(ctx, bus), clock=ctx.clock)
        node_ctx = NodeContext(ctx.clock, ctx.addressing, ctx.where, driver.send, driver.lock, ctx.shared, driver.lines)
        driver.add(by_kind[cfg.type].build(cfg, node_ctx))
    return Contribution(drivers=list(drivers.values()))


def frame_text(config):
    """`softplc log`: each [[plaincan]] node's words for the frames of its bus (PlainCanKind.frame_text)."""
    nodes = config.sections.get("plaincan") or []
    by_kind = kinds(registry()) if nodes else {}

    def words(bus: str, msg) -> str | None:
        if msg.is_extended_id or msg.is_remote_frame:
            return None
        for cfg in nodes:
            text = by_kind[cfg.type].frame_text if cfg.bus == bus else None
            found = text(cfg.options, msg.arbitration_id, bytes(msg.data)) if text is not None else None
            if found:
                return f"{cfg.name}: {found}"
        return None

    return words


BUS = Bus(name="plaincan", order=35, sections=(PlainCanSection(),), build=_build, frame_text=frame_text)

__all__ = [
    "BUS",
    "MalformedFrame",
    "NodeContext",
    "NodeOptions",
    "PlainCanDriver",
    "PlainCanKind",
    "PlainCanNode",
    "PlainCanNodeConfig",
]
