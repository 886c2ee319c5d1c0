"""[[plaincan]]: devices that speak their own protocol of raw 11-bit frames
on a [[can]] bus (not CANopen), one table per device:

    [[plaincan]]
    type = "mpu2s"            # a registered device with a plain-CAN kind
    name = "genset1"          # optional; default from the device's own keys
    bus = "can0"              # may be left out while there is only one [[can]] bus
    device = 1                # ... the device's own keys (its NodeOptions)

Pass 2 checks the bus, the device's keys, unique names, and the CAN-IDs the
device uses against the other plain-CAN devices and the CANopen nodes on
the same bus: an ID another device or a configured PDO uses is an error; an
ID of a CANopen node's predefined connection set that is not configured
(RPDO2 of node 33..63 is 0x321..0x33F, the MPU2-S's range) is a warning,
because the node may still take those frames.
"""

from __future__ import annotations

from typing import Annotated, Any

from pydantic import Field, create_model

from ...config.errors import key_text
from ...config.relations import Relations
from ...config.section import Section
from ...config.values import Model, choice, identifier, is_ident, optional_field
from ...plugin.registry import Registry
from ..can.config import bus_of, can_state
from .kind import PlainCanKind, PlainCanNodeConfig

# CiA 301 predefined connection set: the COB-IDs of node n (function code + n)
_PREDEFINED = {
    "EMCY": 0x080,
    "TPDO1": 0x180,
    "RPDO1": 0x200,
    "TPDO2": 0x280,
    "RPDO2": 0x300,
    "TPDO3": 0x380,
    "RPDO3": 0x400,
    "TPDO4": 0x480,
    "RPDO4": 0x500,
    "SDO tx": 0x580,
    "SDO rx": 0x600,
    "heartbeat": 0x700,
}
_PDO_BASE: dict[tuple[str, int], int] = {("tpdo", n): 0x180 + 0x100 * (n - 1) for n in range(1, 5)} | {
    ("rpdo", n): 0x200 + 0x100 * (n - 1) for n in range(1, 5)
}


def kinds(registry: Registry) -> dict[str, PlainCanKind]:
    """Device name -> its plain-CAN kind, for the devices that have one."""
    return {d.name: d.node_kind for d in registry.devices if isinstance(d.node_kind, PlainCanKind)}


class PlainCanSection(Section):
    key = "plaincan"
    many = True
    description = "[[plaincan]] tables"

    def __init__(self) -> None:
        self.kinds: dict[str, PlainCanKind] = {}
        self.model = self._model()

    def bind(self, registry: Registry) -> None:
        self.kinds = kinds(registry)
        self.model = self._model()

    def _model(self) -> type[Model]:
        types = tuple(self.kinds) or ("",)
        fields: dict[str, Any] = {
            "type": (Annotated[str, choice(types)], Field(description=" or ".join(f"'{t}'" for t in types))),
            "name": (Annotated[str, identifier("a device name")] | None, Field(None, description="a device name")),
            "bus": (Annotated[str, identifier("a bus name")] | None, Field(None, description="a [[can]] bus name")),
        }
        for kind in self.kinds.values():
            for name, info in kind.options.model_fields.items():
                if name not in fields:
                    fields[name] = optional_field(info)
        return create_model("PlainCan", __base__=Model, **fields)

    # ---------------------------------------------------------------- pass 2

    def check(self, value: Any, ctx: Relations) -> None:
        if not isinstance(value, list):
            return
        names: dict = {}
        used: dict = {}  # (bus, CAN-ID) -> (loc, what)
        for i, table in enumerate(value):
            if not isinstance(table, dict) or not isinstance(table.get("type"), str):
                continue
            kind = self.kinds.get(table["type"].lower())
            if kind is None:
                continue  # pass 1 reports it
            here = ("plaincan", i)
            self._foreign_keys(here, table, kind, ctx)
            bus = bus_of(here, table, ctx, "a [[plaincan]] device")
            ctx.required(here, table, kind.options)
            kind.options.check(here, table, ctx)
            name = table.get("name") or kind.options.default_name(table["type"].lower(), table)
            if isinstance(name, str) and is_ident(name):
                first = names.setdefault(name.upper(), here)
                if first != here:
                    loc = here + (("name",) if "name" in table else ())
                    ctx.error(loc, f"duplicate device name '{name}' ({key_text(first)} has it)")
            if bus is None:
                continue
            receives, sends = kind.options.ids(table)
            # two devices that send on one ID (a request ID every device of a kind
            # listens to) are fine; two that are told apart by one received ID are not
            for can_id in sorted(receives):
                first = used.setdefault((bus, can_id), (here, f"{key_text(here)} ({table['type']})"))
                if first[0] != here:
                    ctx.error(here, f"CAN-ID 0x{can_id:03X} on bus '{bus}' is also {first[1]}'s")
            self._against_canopen(here, bus, receives | sends, ctx)

    def _foreign_keys(self, here: tuple, table: dict, kind: PlainCanKind, ctx: Relations) -> None:
        mine = set(kind.options.model_fields) | {"type", "name", "bus"}
        for other, other_kind in self.kinds.items():
            if other_kind is kind:
                continue
            for key in other_kind.options.model_fields:
                if key in table and key not in mine:
                    ctx.error(here + (key,), f"only for {other}; type {table['type']!r} does not take it")

    @staticmethod
    def _against_canopen(here: tuple, bus: str, ids: set[int], ctx: Relations) -> None:
        """The device's CAN-IDs against the CANopen nodes on the same bus."""
        canopen = ctx.data.get("canopen")
        if not isinstance(canopen, dict):
            return
        if canopen.get("bus", bus) != bus and len(ctx.data.get("can", [])) > 1:
            return
        nodes = canopen.get("node")
        for j, node in enumerate(nodes if isinstance(nodes, list) else []):
            n = node.get("id") if isinstance(node, dict) else None
            if not isinstance(n, int) or isinstance(n, bool) or not 1 <= n <= 127:
                continue
            configured = {}
            for direction in ("tpdo", "rpdo"):
                for pdo in node.get(direction) or []:
                    number = pdo.get("number") if isinstance(pdo, dict) else None
                    base = _PDO_BASE.get((direction, number)) if isinstance(number, int) else None
                    if base is not None:
                        configured[base + n] = f"{direction.upper()}{number}"
            for what, base in _PREDEFINED.items():
                can_id = base + n
                if can_id not in ids:
                    continue
                node_key = key_text(("canopen", "node", j))
                if can_id in configured:
                    ctx.error(
                        here,
                        f"CAN-ID 0x{can_id:03X} on bus '{bus}' is {configured[can_id]} of CANopen node {n} "
                        f"({node_key}): give the node another id or the device another number",
                    )
                else:
                    ctx.warning(
                        here,
                        f"CAN-ID 0x{can_id:03X} on bus '{bus}' is the default {what} of CANopen node {n} "
                        f"({node_key}): if that PDO is valid in the node, it takes this device's frames; "
                        "invalidate it or use another node id",
                    )

    # ---------------------------------------------------------------- build

    def build(self, model: Any, ctx: Relations) -> list[PlainCanNodeConfig]:
        out = []
        resolved = can_state(ctx).bus_of  # pass 2 found each table's bus
        for i, table in enumerate(model):
            kind = self.kinds[table.type]
            here = ("plaincan", i)
            own = {k: getattr(table, k) for k in kind.options.model_fields if getattr(table, k) is not None}
            options = kind.options.model_construct(**own).build()  # values validated: the table's
            raw = ctx.data["plaincan"][i]
            bus = resolved[here]
            name = table.name or kind.options.default_name(table.type, raw) or f"{table.type}{i}"
            out.append(PlainCanNodeConfig(type=table.type, name=name, key=key_text(here), bus=bus, options=options))
        return out
