"""[[can]]: the CAN buses of a configuration, and how a simulated device sits
on one ([[sim]] keys bus and node_id).

    [[can]]
    name = "can0"              # what [canopen] and [[sim]] tables name
    interface = "socketcan"    # any python-can interface
    channel = "can0"
    bitrate = 250000
    options = { ... }          # more python-can keyword arguments
    missing_adapter = "retry"  # the adapter cannot be opened at the start: "retry" (wait for
                               # it, with back-off) or "fail" (stop: softplc run exits with 2)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated, Any

from pydantic import Field, PlainValidator

from ...config.errors import key_text
from ...config.relations import Relations
from ...config.section import Attachment, Section
from ...config.values import (
    Model,
    choice,
    fail,
    identifier,
    in_range,
    int_range,
    is_ident,
    nonempty,
    text_value,
)

# manual 001 L183-205 (Network Port Baud Rate Setting): the CANopen rates.
CAN_BITRATES = (10_000, 20_000, 50_000, 125_000, 250_000, 500_000, 800_000, 1_000_000)
# A [[can]] table without bitrate: 250 kbit/s, the LTMR's factory setting (manual 001 L206).
DEFAULT_BITRATE = 250_000
NODE_ID_MAX = 127  # manual 001 L163: "an address from 1 to 127"
# An adapter that cannot be opened when the PLC starts: wait for it (plant PCs bring USB
# adapters up late), or stop with a configuration error.
MISSING_ADAPTER = ("retry", "fail")

_INTERFACE = 'a python-can interface such as "socketcan", "pcan" or "virtual"'

NodeId = Annotated[int, int_range(1, NODE_ID_MAX)]
BusName = Annotated[str, identifier("a bus name")]


@dataclass
class CanBusConfig:
    name: str
    interface: str  # a python-can interface name: socketcan, pcan, virtual ...
    channel: str
    bitrate: int  # bit/s
    options: dict  # more keyword arguments for python-can
    key: str  # "can[0]"
    missing_adapter: str = "retry"  # "retry" | "fail": an adapter that cannot be opened at the start


@dataclass
class CanNode:
    """Where a simulated CAN device sits: a [[can]] bus and its node id."""

    bus: str
    node_id: int


def _bitrate(value) -> int:
    if isinstance(value, int) and not isinstance(value, bool) and value in CAN_BITRATES:
        return value
    raise fail("one of the CANopen bitrates " + ", ".join(str(b) for b in CAN_BITRATES), value)


class _Can(Model):
    name: BusName = Field("can0", description='a bus name such as "can0"')
    interface: Annotated[str, nonempty(_INTERFACE)] = Field(description=_INTERFACE)
    channel: Annotated[str, text_value('a channel such as "can0" or "PCAN_USBBUS1"')] = Field(
        description='a channel such as "can0" or "PCAN_USBBUS1"'
    )
    bitrate: Annotated[int, PlainValidator(_bitrate)] = Field(DEFAULT_BITRATE, description="a CANopen bitrate")
    options: dict[str, Any] = Field(
        default_factory=dict, description="a table of python-can options, such as { fd = false }"
    )
    missing_adapter: Annotated[str, choice(MISSING_ADAPTER)] = Field(
        "retry", description='"retry" (wait for the adapter, with back-off) or "fail" (stop at the start)'
    )


class _State:
    """What pass 2 learns of the CAN side, for [canopen] and [[sim]]."""

    def __init__(self) -> None:
        self.names: dict = {}  # NAME (upper) -> the name as written, of buses with a valid name
        self.count = 0  # [[can]] tables
        self.bus_of: dict = {}  # loc of a table that names a bus -> the bus
        self.nodes: dict = {}  # (bus, node id) -> (loc, what holds it, or None for a simulator)


def can_state(ctx: Relations) -> _State:
    state = ctx.state.get("can")
    if state is None:
        state = ctx.state["can"] = _State()
    return state


def bus_of(here: tuple, table: dict, ctx: Relations, what: str) -> str | None:
    """The [[can]] bus a table uses ([canopen], [[sim]]): its bus key, or the
    only bus. None (and perhaps an error) when there is none."""
    state = can_state(ctx)
    names, count = state.names, state.count
    bus = table.get("bus")
    listed = ", ".join(f"'{n}'" for n in names.values())
    if count == 0:
        ctx.error(
            here, f"{what} needs a [[can]] bus (the file has none): add a [[can]] table with interface and channel"
        )
        return None
    if bus is None:
        if count == 1 and len(names) == 1:
            bus = next(iter(names.values()))
        elif count > 1:
            ctx.error(
                here + ("bus",), f"required key missing: the file has several [[can]] buses (expected one of {listed})"
            )
            return None
        else:
            return None  # the only bus has a bad name: pass 1 reports it
    elif not is_ident(bus):
        return None  # pass 1 reports it
    elif bus.upper() in names:
        bus = names[bus.upper()]
    else:
        if len(names) == count:  # every bus has a valid name, so this one is unknown
            ctx.error(here + ("bus",), f"expected one of {listed}, the [[can]] buses (got '{bus}')")
        return None
    state.bus_of[here] = bus
    return bus


def claim_node(ctx: Relations, bus: str, node_id: int, loc: tuple, what: str) -> None:
    """A node id on a bus taken by something other than a simulated device
    (a CANopen master): a simulator given it is told that it is what."""
    can_state(ctx).nodes.setdefault((bus, node_id), (loc, what))


class CanSection(Section):
    key = "can"
    many = True
    model = _Can
    description = "[[can]] tables"

    def check(self, value: Any, ctx: Relations) -> None:
        state = can_state(ctx)
        buses = value if isinstance(value, list) else []
        state.count = len(buses)
        names: dict = {}
        for i, bus in enumerate(buses):
            if not isinstance(bus, dict):
                continue
            name = bus.get("name", "can0")
            if not is_ident(name):
                continue  # pass 1 reports it
            first = names.get(name.upper())
            if first is None:
                names[name.upper()] = (name, i)
            elif "name" in bus:
                ctx.error(
                    ("can", i, "name"),
                    f"duplicate bus name '{name}' (can[{first[1]}] has it; names are case-insensitive)",
                )
            else:
                ctx.error(
                    ("can", i),
                    f"duplicate bus name '{name}' (the default; can[{first[1]}] has it): "
                    "give each [[can]] its own name",
                )
        state.names = {upper: name for upper, (name, _i) in names.items()}

    def build(self, model: Any, ctx: Relations) -> list[CanBusConfig]:
        return [
            CanBusConfig(b.name, b.interface, b.channel, b.bitrate, dict(b.options), f"can[{i}]", b.missing_adapter)
            for i, b in enumerate(model)
        ]


class _CanNodeKeys(Model):
    bus: BusName | None = Field(None, description="the name of a [[can]] bus")
    node_id: NodeId | None = Field(None, description=f"a node id from 1 to {NODE_ID_MAX}")


class CanAttachment(Attachment):
    """A simulated device on a [[can]] bus, at a node id."""

    kind = "CAN"
    model = _CanNodeKeys
    default_name = "<type><node_id>"

    def check(self, here: tuple, sim: dict, ctx: Relations) -> None:
        if "node_id" not in sim:
            ctx.error(here, "required key missing: node_id (a CAN device's node id)")
        bus = bus_of(here, sim, ctx, "a simulated device")
        node_id = sim.get("node_id")
        if bus is None or not in_range(node_id, 1, NODE_ID_MAX):
            return
        nodes = can_state(ctx).nodes
        taken = nodes.get((bus, node_id))
        if taken is None:
            nodes[bus, node_id] = (here, None)
        elif taken[1] is not None:
            ctx.error(here + ("node_id",), f"{node_id} is {taken[1]}")
        else:
            ctx.error(here + ("node_id",), f"duplicate node id {node_id} on bus '{bus}' ({key_text(taken[0])} has it)")

    def name(self, sim_type: str, sim: dict) -> str | None:
        node_id = sim.get("node_id")
        return f"{sim_type}{node_id}" if in_range(node_id, 1, NODE_ID_MAX) else None

    def build(self, values: dict, here: tuple, ctx: Relations) -> CanNode:
        return CanNode(can_state(ctx).bus_of[here], values["node_id"])
