"""A [[canopen.node]]'s error control and boot-time writes: heartbeat or
node guarding, and the `sdo = [...]` list, by object or by a parameter the
node's device names.

    [[canopen.node]]
    name = "pump"
    id = 20
    eds = "fc280"
    guard_time = "100ms"            # node guarding (0x100C): the master asks every 100 ms
    life_time_factor = 3            # (0x100D) the node's life time: 300 ms without a request
    sdo = [{ object = "2007:21", value = 2 },
           { parameter = "8-03", value = 0.5 }]   # a parameter as the device's manual writes it

A node is watched by its heartbeat (heartbeat > 0, the default 100 ms) or by
node guarding (guard_time), not both: CiA 301 has a node that produces a
heartbeat leave guarding requests unanswered.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Annotated, Any

from pydantic import Field, PlainValidator, ValidationInfo

from ...config.errors import key_text
from ...config.relations import Relations
from ...config.values import U16_MAX, Model, bit_count, duration_in, fail, got, in_range, nonempty, quiet
from ...plugin.registry import registry
from ...plugin.seams import ParameterValueError

DEFAULT_HEARTBEAT_MS = 100  # the master's and a node's, unless the file says
DEFAULT_LIFE_TIME_FACTOR = 3  # guarding: three requests may go unanswered

# CiA 301: 0x100C guard time, Unsigned 16 in ms
GUARD_TIME = duration_in("ms", off="no node guarding", most=(U16_MAX, "0x100C holds ms in 16 bits"))


@dataclass
class SdoWriteConfig:
    index: int
    subindex: int
    value: int  # raw, as the bus carries it
    size: int | None  # bytes (1, 2, 4); None: the EDS says
    key: str  # "canopen.node[0].sdo[0]"


def _sdo_value(value, info: ValidationInfo):
    """An integer; a number (in the parameter's unit) for a parameter write."""
    if isinstance(value, int) and not isinstance(value, bool):
        return value
    if isinstance(value, float) and info.data.get("parameter") is not None:
        return value
    raise fail("an integer", value)


_OBJECT = re.compile(r"(?:0x)?([0-9A-F]{1,4}):(?:0x)?([0-9A-F]{1,2})", re.A | re.I)


def parse_object(value) -> tuple:
    """'2004:06' or '0x2004:06' (hex index : hex sub-index) -> (0x2004, 0x06)."""
    m = _OBJECT.fullmatch(value.strip()) if isinstance(value, str) else None
    if m is None:
        raise fail('an object "index:subindex" in hex, such as "2004:06"', value)
    return int(m.group(1), 16), int(m.group(2), 16)


def _sdo_size(value) -> int:
    if isinstance(value, int) and not isinstance(value, bool) and value in (1, 2, 4):
        return value
    raise fail("a size in bytes: 1, 2 or 4", value)


class _SdoWrite(Model):
    object: Annotated[tuple, PlainValidator(parse_object)] | None = Field(
        None, description='an object "index:subindex" in hex, such as "2007:21"'
    )
    parameter: Annotated[str, nonempty('a parameter number such as "8-03"')] | None = Field(
        None, description='a parameter number such as "8-03"'
    )
    value: Annotated[Any, PlainValidator(_sdo_value)] = Field(description="an integer")
    size: Annotated[int, PlainValidator(_sdo_size)] | None = Field(None, description="1, 2 or 4")


def default_heartbeat(node: dict) -> int:
    """The node's heartbeat when the file gives none: none for a guarded node."""
    return 0 if node.get("guard_time") not in (None, False, 0) else DEFAULT_HEARTBEAT_MS


def check_guarding(here: tuple, node: dict, ctx: Relations) -> None:
    guard = quiet(GUARD_TIME, node.get("guard_time", False))  # None: refused by pass 1
    if guard and "heartbeat" in node and node["heartbeat"] not in (False, 0, "0ms"):
        ctx.error(
            here + ("heartbeat",),
            f"a node is watched by its heartbeat or by node guarding, not both (this node has guard_time = "
            f"{got(node['guard_time'])}): remove one; a node that sends heartbeats does not answer guarding",
        )
    if "life_time_factor" in node and guard == 0:
        ctx.error(here + ("life_time_factor",), "only with guard_time (node guarding)")


def _device_of(node: dict):
    """The registered device whose shipped EDS the node names, or None."""
    eds = node.get("eds")
    if not isinstance(eds, str):
        return None
    return registry().device_with_file("eds", eds.strip().lower())


def device_name(data: dict, i: int) -> str:
    node = data["canopen"]["node"][i]
    device = _device_of(node)
    return device.name if device is not None else ""


def claim_safe_values(here: tuple, node: dict, rpdos: list, ctx: Relations) -> None:
    """The safe values of the node's device (Device.safe_objects) for the %Q
    addresses its RPDOs map to the device's objects: the engine holds them
    there while outputs are safe, unless [outputs] safe says otherwise. A
    value that does not fit the address (a mapping the master refuses) is
    left out."""
    device = _device_of(node)
    if device is None or not device.safe_objects:
        return
    for j, pdo in enumerate(rpdos):
        for k, entry in enumerate(pdo.entries):
            value = device.safe_objects.get((entry.index, entry.subindex))
            addr = entry.address
            if value is None or addr.bit is not None or addr.size in ("", "X"):
                continue
            if 0 <= value < 1 << bit_count(addr):
                ctx.safe_defaults.append((here + ("rpdo", j, "map", k, "address"), addr, int(value)))


def check_writes(here: tuple, node: dict, ctx: Relations) -> None:
    """Object or parameter (not both, one of them), values that fit; a
    parameter write resolved by the node's device (kept for the build)."""
    resolved: dict = ctx.state.setdefault("canopen.parameters", {})
    for k, write in enumerate(node["sdo"]):
        if not isinstance(write, dict):
            continue
        at = here + ("sdo", k)
        if "object" in write and "parameter" in write:
            ctx.error(at + ("parameter",), "object or parameter, not both")
            continue
        if "parameter" in write:
            _check_parameter(at, node, write, ctx, resolved)
            continue
        if "object" not in write:
            ctx.error(at, 'required key missing: object (such as "2007:21") or parameter (such as "8-03")')
            continue
        value, size = write.get("value"), write.get("size")
        if in_range(value, None, None) and size in (1, 2, 4) and not isinstance(size, bool):
            lo, hi = -(1 << (8 * size - 1)), (1 << (8 * size)) - 1
            if not lo <= value <= hi:
                ctx.error(at + ("value",), f"expected an integer from {lo} to {hi} for size = {size} (got {value})")


def _check_parameter(at: tuple, node: dict, write: dict, ctx: Relations, resolved: dict) -> None:
    if "size" in write:
        ctx.error(at + ("size",), "only with object (a parameter's size is its device's)")
    device = _device_of(node)
    if device is None or device.parameter_object is None:
        ctx.error(
            at + ("parameter",),
            f"the node's EDS ({got(node.get('eds'))}) is no registered device's that names its parameters: "
            'write the object instead (object = "index:subindex")',
        )
        return
    name, value = write.get("parameter"), write.get("value")
    if not isinstance(name, str) or not isinstance(value, (int, float)) or isinstance(value, bool):
        return  # pass 1 reports it
    try:
        resolved[at] = device.parameter_object(name, value)
    except ParameterValueError as exc:
        ctx.error(at + ("value",), str(exc.args[0] if exc.args else exc))
    except (ValueError, KeyError) as exc:
        ctx.error(at + ("parameter",), str(exc.args[0] if exc.args else exc))


def build_writes(writes: list, here: tuple, ctx: Relations) -> list[SdoWriteConfig]:
    resolved = ctx.state.get("canopen.parameters", {})
    out = []
    for k, w in enumerate(writes):
        at = here + ("sdo", k)
        if w.parameter is not None:
            index, sub, size, raw = resolved[at]
            out.append(SdoWriteConfig(index, sub, raw, size, key_text(at)))
        else:
            out.append(SdoWriteConfig(w.object[0], w.object[1], w.value, w.size, key_text(at)))
    return out
