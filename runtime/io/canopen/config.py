"""[canopen]: the CANopen master on a [[can]] bus and its nodes
([[canopen.node]] with the EDS, heartbeats, boot-time SDO writes and the
PDO maps to image addresses); io_config/examples/canopen.toml shows every
key. Limits come from the LTMR manual (001) and CiA 301."""

from __future__ import annotations

import difflib
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any

from pydantic import Field, PlainValidator, ValidationInfo
from pydantic_core import PydanticCustomError

from ...config.errors import key_text
from ...config.relations import Relations
from ...config.section import Section
from ...config.values import (
    U16_MAX,
    Model,
    area_name,
    bit_count,
    duration_in,
    existing_file,
    fail,
    got,
    identifier,
    in_range,
    int_range,
    is_ident,
    quiet,
)
from ...plugin.registry import registry
from ...st.ast import LocatedAddress
from ..can.config import NODE_ID_MAX, BusName, NodeId, bus_of, can_state, claim_node
from .config_node import (
    DEFAULT_HEARTBEAT_MS,
    DEFAULT_LIFE_TIME_FACTOR,
    GUARD_TIME,
    SdoWriteConfig,
    _SdoWrite,
    build_writes,
    check_guarding,
    check_writes,
    claim_safe_values,
    default_heartbeat,
    device_name,
    parse_object,
)

PDO_ENTRIES_MAX = 8  # manual 001 L117: a PDO carries 8 bytes
PDO_BITS_MAX = 64


@dataclass
class PdoEntryConfig:
    index: int
    subindex: int
    address: LocatedAddress  # %I (TPDO) or %Q (RPDO): a bit, byte, word, dword or lword
    key: str  # "canopen.node[0].tpdo[0].map[1]"


@dataclass
class PdoConfig:
    number: int  # 1..512
    transmission: int  # 0..240 (SYNC), 254, 255 (event-driven)
    inhibit_us: int  # 0: none
    event_ms: int  # 0: none
    configure: bool  # the master writes mapping and parameters at boot
    entries: list[PdoEntryConfig]
    key: str  # "canopen.node[0].tpdo[0]"


@dataclass
class CanopenNodeConfig:
    name: str
    node_id: int
    eds: Path  # absolute
    mandatory: bool
    heartbeat_ms: int  # the node's producer time, its 0x1017 (0: none)
    heartbeat_timeout_ms: int  # the master's consumer timeout for it (0: not watched)
    master_timeout_ms: int  # its 0x1016:01 consumer time for the master (0: none)
    sdo: list[SdoWriteConfig]  # boot-time writes, in order
    tpdo: list[PdoConfig]
    rpdo: list[PdoConfig]
    key: str  # "canopen.node[0]"
    guard_time_ms: int = 0  # node guarding: the master's request period, its 0x100C (0: no guarding)
    life_time_factor: int = 0  # its 0x100D: guard time x factor without a request is a lost master
    master_timeout_explicit: bool = False  # the file gives master_timeout (else it is the default)
    device: str = ""  # the registered device whose EDS the node names ("" for an EDS file of one's own)


@dataclass
class CanopenConfig:
    bus: str  # the name of a CanBusConfig
    node_id: int  # the master's own node id
    heartbeat_ms: int  # the master's producer period (0: none)
    sync_us: int  # SYNC period (0: no SYNC)
    sdo_timeout_ms: int
    boot_timeout_ms: int
    retry_ms: int
    nodes: list[CanopenNodeConfig]
    key: str = "canopen"


# ---------------------------------------------------------------- values

# The checks are kept as functions too: _Relations compares the values.
_master_heartbeat = duration_in("ms", off="no heartbeat")
# CiA 301 takes SYNC periods in us; this master sends SYNC from its service
# thread, which wakes every millisecond: a shorter period is sent no faster
_sync_period = duration_in(
    "us",
    off="no SYNC",
    most=(0xFFFF_FFFF, "0x1006 holds microseconds in 32 bits"),
    least=(1_000_000, "1ms", "the master's service runs every millisecond"),
)
_timeout_ms = duration_in("ms")
# manual 001 L964: 0x1017 Producer Heartbeat Time, Unsigned 16, unit 1 ms.
_node_heartbeat = duration_in("ms", off="no heartbeat", most=(U16_MAX, "0x1017 holds ms in 16 bits"))
_heartbeat_timeout = duration_in("ms", off="not watching it")
# manual 001 L957: 0x1016:01 bits 0-15 = heartbeat time, unit 1 ms.
_master_timeout = duration_in(
    "ms", off="the node not watching the master", most=(U16_MAX, "0x1016:01 holds ms in 16 bits")
)
# manual 001 L1365: TPDO inhibit time, Unsigned 16, unit 0.1 ms.
_inhibit = duration_in("us", off="none", most=(U16_MAX * 100, "the inhibit time is 16 bits of 100us"))
# Event timer: Unsigned 16 in ms, as CiA 301 says; manual 001 L1379 says
# 0.1 ms, which digest 001 A7 resolves for CiA (ms).
_event = duration_in("ms", off="none", most=(U16_MAX, "the event timer is 16 bits of ms"))


def _transmission(value) -> int:
    # manual 001 L1114: asynchronous (255), synchronously cyclic (1-240),
    # synchronously acyclic (0); CiA 301 adds 254 (event-driven, manufacturer).
    if isinstance(value, int) and not isinstance(value, bool) and (0 <= value <= 240 or value in (254, 255)):
        return value
    raise fail("a transmission type 0..240, 254 or 255", value)


def _eds_file(value, info: ValidationInfo) -> Path:
    """A shipped EDS by name ("ltmr": io_config/eds/ltmr.eds, installed with
    the package) or the path of an EDS file relative to the config file."""
    shipped = dict(sorted(registry().files("eds").items()))
    names = ", ".join(f"'{n}'" for n in shipped)
    if not isinstance(value, str) or not value.strip():
        raise fail(f"a shipped EDS name ({names}) or the path of an .eds file", value)
    text = value.strip()
    if re.fullmatch(r"[A-Za-z0-9_-]+", text):  # a name, not a path
        if text.lower() in shipped:
            return shipped[text.lower()].path
        close = difflib.get_close_matches(text.lower(), list(shipped), n=1)
        hint = f"; did you mean '{close[0]}'?" if close else ""
        raise PydanticCustomError(
            "config",
            "expected a shipped EDS name ({names}) or the path of an .eds file (got {got}{hint})",
            {"names": names, "got": got(value), "hint": hint},
        )
    return existing_file(text, info)


def _clash(node_id: int, master_given: bool) -> str:
    """A node on the master's own node id, and how to part them (an FC 280
    and the master both come with 127: manual 003 §1.9, 10-02)."""
    where = "canopen.node_id" if master_given else f"canopen.node_id, {NODE_ID_MAX} unless the file says"
    other = 1 if node_id != 1 else 2
    return (
        f"{node_id} is the master's own node id ({where}): give the master another one "
        f"(canopen.node_id = {other}) or the node another (set its node-id parameter, and id here)"
    )


def _default_master_timeout(master_heartbeat_ms: int) -> int:
    """5 heartbeats of the master, within what 0x1016:01 holds."""
    return min(5 * master_heartbeat_ms, U16_MAX)


# ---------------------------------------------------------------- pass 1


class _PdoEntry(Model):
    object: Annotated[tuple, PlainValidator(parse_object)] = Field(
        description='an object "index:subindex" in hex, such as "2004:06"'
    )
    address: Any = Field(description='an image address such as "%IW0" for a TPDO, "%QW0" for an RPDO')


class _Pdo(Model):
    number: Annotated[int, int_range(1, 512)] = Field(description="a PDO number from 1 to 512")
    transmission: Annotated[int, PlainValidator(_transmission)] = Field(255, description="0..240, 254 or 255")
    inhibit: Annotated[int, PlainValidator(_inhibit)] = Field(0, description="a duration such as 10ms")
    event: Annotated[int, PlainValidator(_event)] = Field(0, description="a duration such as 500ms")
    configure: bool = Field(True, description="true or false")
    map: list[_PdoEntry] = Field(
        min_length=1,
        max_length=PDO_ENTRIES_MAX,
        description=f'an array of 1 to {PDO_ENTRIES_MAX} {{ object = "2004:06", address = "%IW0" }} tables; '
        "a PDO carries 8 bytes",
    )


class _Node(Model):
    name: Annotated[str, identifier("a node name")] = Field(description='a node name such as "motor1"')
    id: NodeId = Field(description=f"a node id from 1 to {NODE_ID_MAX}")
    eds: Annotated[Path, PlainValidator(_eds_file)] = Field(
        description='a shipped EDS name such as "ltmr" or the path of an .eds file'
    )
    mandatory: bool = Field(True, description="true or false")
    heartbeat: Annotated[int, PlainValidator(_node_heartbeat)] | None = Field(
        None, description="a duration such as 100ms, or false"
    )
    guard_time: Annotated[int, PlainValidator(GUARD_TIME)] | None = Field(
        None, description="a duration such as 100ms, or false"
    )
    life_time_factor: Annotated[int, int_range(1, 255)] | None = Field(None, description="an integer from 1 to 255")
    heartbeat_timeout: Annotated[int, PlainValidator(_heartbeat_timeout)] | None = Field(
        None, description="a duration such as 300ms, or false"
    )
    master_timeout: Annotated[int, PlainValidator(_master_timeout)] | None = Field(
        None, description="a duration such as 500ms, or false"
    )
    sdo: list[_SdoWrite] = Field(
        default_factory=list,
        description='an array of { object = "2007:21", value = 2 } or { parameter = "8-03", value = 1.0 } tables',
    )
    tpdo: list[_Pdo] = Field(default_factory=list, description="[[canopen.node.tpdo]] tables")
    rpdo: list[_Pdo] = Field(default_factory=list, description="[[canopen.node.rpdo]] tables")


class _Canopen(Model):
    bus: BusName | None = Field(None, description="the name of a [[can]] bus")
    node_id: NodeId = Field(NODE_ID_MAX, description=f"a node id from 1 to {NODE_ID_MAX}")
    heartbeat: Annotated[int, PlainValidator(_master_heartbeat)] = Field(
        DEFAULT_HEARTBEAT_MS, description="a duration such as 100ms, or false"
    )
    sync: Annotated[int, PlainValidator(_sync_period)] = Field(0, description="a duration such as 10ms, or false")
    sdo_timeout: Annotated[int, PlainValidator(_timeout_ms)] = Field(500, description="a duration such as 500ms")
    boot_timeout: Annotated[int, PlainValidator(_timeout_ms)] = Field(2000, description="a duration such as 2s")
    retry: Annotated[int, PlainValidator(_timeout_ms)] = Field(1000, description="a duration such as 1s")
    node: list[_Node] = Field(default_factory=list, description="[[canopen.node]] tables")


# ---------------------------------------------------------------- pass 2


class CanopenSection(Section):
    key = "canopen"
    model = _Canopen
    description = "a [canopen] table"

    def check(self, value: Any, ctx: Relations) -> None:
        ctx.state[self.key] = {"pdo_addresses": {}}
        if not isinstance(value, dict):
            return
        bus = bus_of(("canopen",), value, ctx, "the CANopen master")
        node_id = value.get("node_id", NODE_ID_MAX)
        master_id = node_id if in_range(node_id, 1, NODE_ID_MAX) else None
        if bus is not None and master_id is not None:
            claim_node(
                ctx,
                bus,
                master_id,
                ("canopen", "node_id"),
                f"the CANopen master's own node id on bus '{bus}' (canopen.node_id)",
            )
        self._nodes(value, master_id, ctx)

    def _nodes(self, canopen: dict, master_id: int | None, ctx: Relations) -> None:
        nodes = canopen.get("node")
        if not isinstance(nodes, list):
            return
        master_heartbeat = quiet(_master_heartbeat, canopen.get("heartbeat", DEFAULT_HEARTBEAT_MS))
        ids: dict = {}
        names: dict = {}
        for i, node in enumerate(nodes):
            if not isinstance(node, dict):
                continue
            here = ("canopen", "node", i)
            node_id, name = node.get("id"), node.get("name")
            if in_range(node_id, 1, NODE_ID_MAX):
                if node_id == master_id:
                    ctx.error(here + ("id",), _clash(node_id, "node_id" in canopen))
                elif node_id in ids:
                    ctx.error(here + ("id",), f"duplicate node id {node_id} ({key_text(ids[node_id])} has it)")
                else:
                    ids[node_id] = here
            if is_ident(name):
                first = names.setdefault(name.upper(), here)
                if first != here:
                    ctx.error(
                        here + ("name",),
                        f"duplicate node name '{name}' ({key_text(first)} has it; names are case-insensitive)",
                    )
            self._heartbeats(here, node, canopen, master_heartbeat, ctx)
            check_guarding(here, node, ctx)
            for direction in ("tpdo", "rpdo"):
                if isinstance(node.get(direction), list):
                    self._pdos(here, direction, node[direction], ctx)
            if isinstance(node.get("sdo"), list):
                check_writes(here, node, ctx)

    @staticmethod
    def _heartbeats(here: tuple, node: dict, canopen: dict, master_heartbeat: int | None, ctx: Relations) -> None:
        """The node's heartbeat against the master's timeout for it, and the
        master's heartbeat against the node's timeout for the master."""
        heartbeat = quiet(_node_heartbeat, node.get("heartbeat", default_heartbeat(node)))
        timeout = quiet(_heartbeat_timeout, node.get("heartbeat_timeout"))
        if heartbeat is not None and timeout:  # given and not off
            if heartbeat == 0:
                which = (
                    f"this node has heartbeat = {got(node['heartbeat'])}"
                    if "heartbeat" in node
                    else "this node sends none, it is guarded by guard_time"
                )
                ctx.error(here + ("heartbeat_timeout",), f"only meaningful with a heartbeat ({which})")
            elif timeout <= heartbeat:
                ctx.error(
                    here + ("heartbeat_timeout",),
                    f"expected a duration longer than the node's heartbeat ({heartbeat}ms), or false "
                    f"for not watching it (got {got(node['heartbeat_timeout'])})",
                )
        if master_heartbeat is None:
            return
        if "master_timeout" in node:
            timeout = quiet(_master_timeout, node["master_timeout"])
            if not timeout:
                return  # off, or refused by pass 1
            if master_heartbeat == 0:
                ctx.error(
                    here + ("master_timeout",),
                    "only meaningful when the master sends a heartbeat "
                    f"(canopen.heartbeat = {got(canopen['heartbeat'])})",
                )
            elif timeout <= master_heartbeat:
                ctx.error(
                    here + ("master_timeout",),
                    f"expected a duration longer than canopen.heartbeat ({master_heartbeat}ms), or "
                    f"false for the node not watching the master (got {got(node['master_timeout'])})",
                )
        elif master_heartbeat and _default_master_timeout(master_heartbeat) <= master_heartbeat:
            ctx.error(
                here,
                f"the default master_timeout, 5 x canopen.heartbeat at most {U16_MAX}ms, is not "
                f"longer than canopen.heartbeat ({master_heartbeat}ms): give master_timeout, or "
                "false",
            )

    def _pdos(self, here: tuple, direction: str, pdos: list, ctx: Relations) -> None:
        """PDO numbers unique per direction, and the image addresses of the
        entries: %I for a TPDO, %Q for an RPDO, no two overlapping."""
        numbers: dict = {}
        area = "I" if direction == "tpdo" else "Q"
        for j, pdo in enumerate(pdos):
            if not isinstance(pdo, dict):
                continue
            at = here + (direction, j)
            number = pdo.get("number")
            if in_range(number, 1, 512):
                first = numbers.setdefault(number, at)
                if first != at:
                    ctx.error(
                        at + ("number",), f"duplicate {direction.upper()} number {number} ({key_text(first)} has it)"
                    )
            entries = pdo.get("map")
            if not isinstance(entries, list):
                continue
            bits = 0
            for k, entry in enumerate(entries):
                if isinstance(entry, dict) and "address" in entry:
                    addr = self._pdo_address(at + ("map", k, "address"), entry["address"], area, ctx)
                    if addr is not None:
                        ctx.state[self.key]["pdo_addresses"][at + ("map", k)] = addr
                        bits += bit_count(addr)
            if bits > PDO_BITS_MAX and len(entries) <= PDO_ENTRIES_MAX:  # else pass 1 says too many
                ctx.error(
                    at + ("map",), f"the addresses hold {bits} bits; a PDO carries at most {PDO_BITS_MAX} (8 bytes)"
                )

    @staticmethod
    def _pdo_address(loc: tuple, text, area: str, ctx: Relations) -> LocatedAddress | None:
        addr = ctx.address(loc, text, f"%{area}W0, %{area}X0.0")
        if addr is None:
            return None
        kind = "a TPDO's entries go to %I inputs" if area == "I" else "an RPDO's entries come from %Q outputs"
        if addr.area != area:
            ctx.error(loc, f"expected a %{area} address: {kind} (got {area_name(addr)})")
            return None
        if addr.table is not None:
            ctx.error(
                loc,
                f"expected a bit, byte, word, dword or lword address (got '{addr.text}', a word "
                "table): map one object per address",
            )
            return None
        span = ctx.image_bits(loc, addr)
        if span is None:
            return None
        first, last = span
        overlap = ctx.claim(area, first, last, loc, f"'{addr.text}'")
        if overlap is not None:
            ctx.error(loc, f"'{addr.text}' overlaps {key_text(overlap[0])} ({overlap[1]})")
        return addr

    def build(self, model: Any, ctx: Relations) -> CanopenConfig | None:
        if model is None:
            return None
        return _build_canopen(model, ctx)


# ---------------------------------------------------------------- build


def _build_canopen(c: _Canopen, ctx: Relations) -> CanopenConfig:
    nodes = []
    for i, n in enumerate(c.node):
        key = f"canopen.node[{i}]"
        guard_time = n.guard_time or 0
        heartbeat = n.heartbeat if n.heartbeat is not None else (0 if guard_time else DEFAULT_HEARTBEAT_MS)
        if n.heartbeat_timeout is not None:
            heartbeat_timeout = n.heartbeat_timeout
        else:
            heartbeat_timeout = 3 * heartbeat  # 0 when the node sends none
        if n.master_timeout is not None:
            master_timeout = n.master_timeout
        else:  # a guarded node watches the master through guarding
            master_timeout = _default_master_timeout(c.heartbeat) if c.heartbeat and not guard_time else 0
        rpdo = _build_pdos(n.rpdo, ("canopen", "node", i, "rpdo"), ctx)
        claim_safe_values(("canopen", "node", i), ctx.data["canopen"]["node"][i], rpdo, ctx)
        nodes.append(
            CanopenNodeConfig(
                name=n.name,
                node_id=n.id,
                eds=n.eds,
                mandatory=n.mandatory,
                heartbeat_ms=heartbeat,
                heartbeat_timeout_ms=heartbeat_timeout,
                master_timeout_ms=master_timeout,
                sdo=build_writes(n.sdo, ("canopen", "node", i), ctx),
                tpdo=_build_pdos(n.tpdo, ("canopen", "node", i, "tpdo"), ctx),
                rpdo=rpdo,
                key=key,
                guard_time_ms=guard_time,
                life_time_factor=(n.life_time_factor or DEFAULT_LIFE_TIME_FACTOR) if guard_time else 0,
                master_timeout_explicit=n.master_timeout is not None,
                device=device_name(ctx.data, i),
            )
        )
    return CanopenConfig(
        bus=can_state(ctx).bus_of["canopen",],
        node_id=c.node_id,
        heartbeat_ms=c.heartbeat,
        sync_us=c.sync,
        sdo_timeout_ms=c.sdo_timeout,
        boot_timeout_ms=c.boot_timeout,
        retry_ms=c.retry,
        nodes=nodes,
    )


def _build_pdos(pdos: list, here: tuple, ctx: Relations) -> list:
    out = []
    for j, p in enumerate(pdos):
        at = here + (j,)
        entries = [
            PdoEntryConfig(
                e.object[0],
                e.object[1],
                ctx.state["canopen"]["pdo_addresses"][at + ("map", k)],
                key_text(at + ("map", k)),
            )
            for k, e in enumerate(p.map)
        ]
        out.append(
            PdoConfig(
                number=p.number,
                transmission=p.transmission,
                inhibit_us=p.inhibit,
                event_ms=p.event,
                configure=p.configure,
                entries=entries,
                key=key_text(at),
            )
        )
    return out
