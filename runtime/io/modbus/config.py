"""[[modbus]]: Modbus connections (RTU on a serial port, TCP), their
channels ([[modbus.channel]]: function code, block, image address,
trigger), and how a simulated device sits on one ([[sim]] with modbus and
unit); io_config/examples/modbus_rtu.toml and modbus_tcp.toml show every key.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated, Any

from pydantic import Field, PlainValidator

from ...config.errors import key_text
from ...config.relations import Relations
from ...config.section import Attachment, Section
from ...config.values import (
    U16_MAX,
    Model,
    area_name,
    choice,
    choice_int,
    choice_upper,
    duration_in,
    host_value,
    identifier,
    in_range,
    int_range,
    is_ident,
    nonempty,
)
from ...st.ast import LocatedAddress
from .functions import FUNCTIONS as MODBUS_FUNCTION_KINDS
from .functions import READ_LIMIT as MODBUS_READ_LIMIT
from .functions import WRITE_LIMIT as MODBUS_WRITE_LIMIT

MODBUS_FUNCTIONS = tuple(MODBUS_FUNCTION_KINDS)
MODBUS_BAUDS = (1200, 2400, 4800, 9600, 19200, 38400, 57600, 115200)
MODBUS_SIM_DEVICE = "sim"
MODBUS_UNIT_MAX = 247  # Modbus over serial line 2.2: 1..247 (0 = broadcast)
_timeout_ms = duration_in("ms")
_frame_gap = duration_in("us", most=(1_000_000, "at most 1s"))
_DEVICE = 'a serial port such as "/dev/ttyUSB0", or "sim" for the simulated drives of [[sim]]'


@dataclass
class ModbusChannelConfig:
    name: str
    connection: str  # the name of its ModbusConnectionConfig
    unit: int  # the slave's unit id
    function: int  # 1, 2, 3, 4, 5, 6, 15, 16, 23
    offset: int  # PDU address: the read, or the write of a write-only function
    count: int  # registers or bits read (or written by a write-only function)
    write_offset: int  # function 23: the write
    write_count: int  # function 23
    read_to: LocatedAddress | None  # %I / %M: where read data lands
    write_from: LocatedAddress | None  # %Q / %M: what is written
    trigger: str  # "cyclic" | "change" | "edge"
    period_ns: int  # cyclic period; the wait after a failure for the others
    edge: LocatedAddress | None  # trigger "edge": a BOOL address
    key: str  # "modbus[0].channel[1]"


@dataclass
class ModbusConnectionConfig:
    name: str
    transport: str  # "rtu" | "tcp"
    device: str  # rtu: serial port, or "sim" (a NullModem to the [[sim]] drives)
    baud: int
    parity: str  # "N" | "E" | "O"
    stop_bits: int
    data_bits: int
    frame_gap_us: int | None  # None: 3.5 characters (link.frame_gap)
    host: str  # tcp
    port: int  # tcp; 0 with simulated slaves: any free port
    timeout_ms: int
    retries: int
    reconnect_ms: int
    reconnect_max_ms: int
    channels: list[ModbusChannelConfig]
    key: str  # "modbus[0]"
    sim_wire: str | None = None  # to [[sim]] units: "memory" | "port"; None: memory in virtual time


class _State:
    """What pass 2 learns of the Modbus side, for the simulated devices and the build."""

    def __init__(self) -> None:
        self.names: dict = {}  # NAME (upper) -> (index, the [[modbus]] table), of valid names
        self.addresses: dict = {}  # loc of a channel address key -> LocatedAddress
        self.sim_connection: dict = {}  # loc of a [[sim]] -> the connection it is on
        self.units: dict = {}  # (connection index, unit) -> loc of the [[sim]] there


def modbus_state(ctx: Relations) -> _State:
    state = ctx.state.get("modbus")
    if state is None:
        state = ctx.state["modbus"] = _State()
    return state


@dataclass
class ModbusUnit:
    """Where a simulated Modbus device sits: a [[modbus]] connection and its unit id."""

    connection: str
    unit: int


class _ModbusChannel(Model):
    name: Annotated[str, identifier("a channel name")] | None = Field(
        None, description='a channel name such as "drive_status"'
    )
    unit: Annotated[int, int_range(0, MODBUS_UNIT_MAX)] = Field(
        description=f"a unit id from 1 to {MODBUS_UNIT_MAX} (0: broadcast write)"
    )
    function: Annotated[int, choice_int(MODBUS_FUNCTIONS)] = Field(
        description="a function code: " + ", ".join(map(str, MODBUS_FUNCTIONS))
    )
    offset: Annotated[int, int_range(0, U16_MAX)] = Field(
        description="a PDU address from 0 to 65535 (Eaton ID n is offset n-1)"
    )
    count: Annotated[int, int_range(1, 2000)] = Field(1, description="an integer from 1 to 2000")
    write_offset: Annotated[int, int_range(0, U16_MAX)] | None = Field(
        None, description="a PDU address from 0 to 65535"
    )
    write_count: Annotated[int, int_range(1, 121)] | None = Field(None, description="an integer from 1 to 121")
    read_to: Any = Field(None, description='an %I or %M address such as "%IW100"')
    write_from: Any = Field(None, description='a %Q or %M address such as "%QW100"')
    trigger: Annotated[str, choice(("cyclic", "change", "edge"))] = Field(
        "cyclic", description="'cyclic', 'change' or 'edge'"
    )
    period: Annotated[int, PlainValidator(_timeout_ms)] = Field(100, description="a duration such as 100ms")
    edge: Any = Field(None, description='a BOOL address such as "%QX10.0"')


class _Modbus(Model):
    name: Annotated[str, identifier("a connection name")] = Field(
        "modbus0", description='a connection name such as "drives"'
    )
    transport: Annotated[str, choice(("rtu", "tcp"))] = Field(description="'rtu' or 'tcp'")
    device: Annotated[str, nonempty(_DEVICE)] | None = Field(None, description=_DEVICE)
    baud: Annotated[int, choice_int(MODBUS_BAUDS)] = Field(
        19200, description="a baud rate: " + ", ".join(map(str, MODBUS_BAUDS))
    )
    parity: Annotated[str, choice_upper(("N", "E", "O"))] = Field("N", description="'N', 'E' or 'O'")
    stop_bits: Annotated[int, choice_int((1, 2))] = Field(1, description="1 or 2")
    data_bits: Annotated[int, choice_int((7, 8))] = Field(8, description="7 or 8")
    frame_gap: Annotated[int, PlainValidator(_frame_gap)] | None = Field(
        None, description="a duration such as 2ms (default: 3.5 characters)"
    )
    host: Annotated[str, host_value('a host name or address such as "192.168.0.20"')] | None = Field(
        None, description='a host such as "192.168.0.20"'
    )
    port: Annotated[int, int_range(0, U16_MAX)] | None = Field(None, description="a TCP port such as 502")
    timeout: Annotated[int, PlainValidator(_timeout_ms)] = Field(200, description="a duration such as 200ms")
    retries: Annotated[int, int_range(0, 10)] = Field(1, description="an integer from 0 to 10")
    reconnect: Annotated[int, PlainValidator(_timeout_ms)] = Field(1000, description="a duration such as 1s")
    reconnect_max: Annotated[int, PlainValidator(_timeout_ms)] = Field(10_000, description="a duration such as 10s")
    sim_wire: Annotated[str, choice(("memory", "port"))] | None = Field(
        None, description="'memory' or 'port' (default: memory in virtual time, the port in real time)"
    )
    channel: list[_ModbusChannel] = Field(default_factory=list, description="[[modbus.channel]] tables")


# ---------------------------------------------------------------- pass 2


def _check_connections(conns, ctx: Relations, state: _State) -> None:
    if not isinstance(conns, list):
        return
    for i, conn in enumerate(conns):
        if not isinstance(conn, dict):
            continue
        here = ("modbus", i)
        name = conn.get("name", "modbus0")
        if is_ident(name):
            first = state.names.get(name.upper())
            if first is None:
                state.names[name.upper()] = (i, conn)
            else:
                ctx.error(
                    here + (("name",) if "name" in conn else ()),
                    f"duplicate connection name '{name}' (modbus[{first[0]}] has it; names are "
                    "case-insensitive)" + ("" if "name" in conn else ": give each [[modbus]] a name"),
                )
        transport = conn.get("transport")
        transport = transport.lower() if isinstance(transport, str) else None
        if transport == "rtu":
            if "device" not in conn:
                ctx.error(here, f"required key missing: device ({_DEVICE})")
            for key in ("host", "port"):
                if key in conn:
                    ctx.error(here + (key,), "only for transport = 'tcp' (this connection is 'rtu')")
        elif transport == "tcp":
            for key in ("device", "baud", "parity", "stop_bits", "data_bits", "frame_gap"):
                if key in conn:
                    ctx.error(here + (key,), "only for transport = 'rtu' (this connection is 'tcp')")
        channels = conn.get("channel")
        if isinstance(channels, list):
            _check_channels(here, channels, ctx, state)


def _check_channels(here: tuple, channels: list, ctx: Relations, state: _State) -> None:
    names: dict = {}
    for j, ch in enumerate(channels):
        if not isinstance(ch, dict):
            continue
        at = here + ("channel", j)
        name = ch.get("name")
        if is_ident(name):
            first = names.setdefault(name.upper(), j)
            if first != j:
                ctx.error(
                    at + ("name",),
                    f"duplicate channel name '{name}' (channel[{first}] has it; names are case-insensitive)",
                )
        fc = ch.get("function")
        if fc not in MODBUS_FUNCTIONS or isinstance(fc, bool):
            continue  # pass 1 reports it
        reads, writes, bits = MODBUS_FUNCTION_KINDS[fc]
        count = ch.get("count", 1)
        limit = MODBUS_READ_LIMIT[fc] if reads else MODBUS_WRITE_LIMIT[fc]
        if in_range(count, 1, 2000) and count > limit:  # above 2000: pass 1 reports it
            what = ("bit" if bits else "register") + ("s" if limit > 1 else "")
            ctx.error(at + ("count",), f"function {fc} carries at most {limit} {what} (got {count})")
        if fc == 23:
            for key in ("write_offset", "write_count"):
                if key not in ch:
                    ctx.error(at, f"required key missing: {key} (function 23 writes and reads)")
        else:
            for key in ("write_offset", "write_count"):
                if key in ch:
                    ctx.error(at + (key,), "only for function 23 (offset and count give the block)")
        wc = ch.get("write_count", count) if fc == 23 else count
        _channel_address(at, ch, "read_to", reads, ("I", "M"), _size(count) if reads else 0, bits, ctx, state)
        _channel_address(at, ch, "write_from", writes, ("Q", "M"), _size(wc) if writes else 0, bits, ctx, state)
        trigger = ch.get("trigger", "cyclic")
        trigger = trigger.lower() if isinstance(trigger, str) else None
        if trigger == "change" and not writes:
            ctx.error(
                at + ("trigger",),
                f"'change' watches the data to write; function {fc} only reads (use 'cyclic' or 'edge')",
            )
        if trigger == "edge":
            if "edge" not in ch:
                ctx.error(at, 'required key missing: edge (the BOOL whose rising edge triggers, such as "%QX10.0")')
            else:
                addr = ctx.address(at + ("edge",), ch["edge"], "%QX10.0, %MX2.0")
                if addr is not None and addr.bit is None and addr.size not in ("", "X"):
                    ctx.error(at + ("edge",), f"expected a BOOL (bit) address such as %QX10.0 (got '{addr.text}')")
                elif addr is not None:
                    state.addresses[at + ("edge",)] = addr
        elif "edge" in ch:
            ctx.error(at + ("edge",), "only for trigger = 'edge'")
        if ch.get("unit") == 0 and reads:
            ctx.error(at + ("unit",), "unit 0 is the broadcast address: nobody answers, so only writes can go to it")


def _size(value: object) -> int | None:
    """A block size of the raw table, or None when it is no integer (pass 1 reports it)."""
    return value if in_range(value, None, None) else None


def _channel_address(
    at: tuple,
    ch: dict,
    key: str,
    needed: bool,
    areas: tuple,
    count: int | None,
    bits: bool,
    ctx: Relations,
    state: _State,
) -> None:
    """The image address of a block of count bits or registers (None: a count pass 1 refuses)."""
    what = "reads into" if key == "read_to" else "writes from"
    if not needed:
        if key in ch:
            ctx.error(at + (key,), f"function {ch.get('function')} does not use {key}")
        return
    if key not in ch:
        ctx.error(at, f"required key missing: {key} (the image address the channel {what})")
        return
    examples = f"%{areas[0]}W100, %MW20"
    addr = ctx.address(at + (key,), ch[key], examples)
    if addr is None:
        return
    if addr.area not in areas:
        ctx.error(at + (key,), f"expected an address in {' or '.join('%' + a for a in areas)} (got {area_name(addr)})")
        return
    try:
        _area, offset, _n = ctx.probe().region(addr)
    except ValueError as exc:
        ctx.error(at + (key,), str(exc))
        return
    if count is None:
        return  # no valid count (pass 1 reports it): no block to fit
    nbytes = (count + 7) // 8 if bits else 2 * count
    if offset + nbytes > ctx.probe().size:
        ctx.error(
            at + (key,),
            f"{count} {'bits' if bits else 'registers'} from {addr.text} run past the end of the %{addr.area} area",
        )
        return
    what = f"{count} {'bit' if bits else 'register'}{'s' if count > 1 else ''} from '{addr.text}'"
    if key == "read_to" and not ctx.writes(at + (key,), addr.area, offset, nbytes, what):
        return  # another channel or bus writes these bytes
    state.addresses[at + (key,)] = addr


class ModbusSection(Section):
    key = "modbus"
    many = True
    model = _Modbus
    description = "[[modbus]] tables"

    def check(self, value: Any, ctx: Relations) -> None:
        state = modbus_state(ctx)
        if isinstance(value, list):
            _check_connections(value, ctx, state)

    def build(self, model: Any, ctx: Relations) -> list[ModbusConnectionConfig]:
        return [_build_modbus(i, m, modbus_state(ctx)) for i, m in enumerate(model)]


class _ModbusUnitKeys(Model):
    modbus: Annotated[str, identifier("a connection name")] | None = Field(
        None, description="the name of a [[modbus]] connection"
    )
    unit: Annotated[int, int_range(1, MODBUS_UNIT_MAX)] | None = Field(
        None, description=f"a unit id from 1 to {MODBUS_UNIT_MAX}"
    )


class ModbusAttachment(Attachment):
    """A simulated device on a [[modbus]] connection, at a unit id: RTU with
    device = "sim" (a pseudo-terminal cable) or TCP on 127.0.0.1."""

    kind = "Modbus"
    model = _ModbusUnitKeys
    default_name = "<type>_<unit>"

    def check(self, here: tuple, sim: dict, ctx: Relations) -> None:
        """An Eaton drive on a [[modbus]] connection: RTU with device = "sim"
        or TCP on 127.0.0.1; one drive per unit id."""
        state = modbus_state(ctx)
        units = state.units
        if "unit" not in sim:
            ctx.error(here, "required key missing: unit (the drive's Modbus address)")
        conn = sim.get("modbus")
        if conn is None:
            if len(state.names) == 1:
                conn = next(iter(state.names.values()))[1].get("name", "modbus0")
            else:
                ctx.error(
                    here,
                    "required key missing: modbus (the [[modbus]] connection the drive is on)"
                    if state.names
                    else "a simulated drive needs a [[modbus]] connection (the file has none)",
                )
                return
        elif not is_ident(conn):
            return
        entry = state.names.get(conn.upper())
        if entry is None:
            listed = ", ".join(repr(t.get("name", "modbus0")) for _i, t in state.names.values())
            ctx.error(here + ("modbus",), f"expected one of {listed}, the [[modbus]] connections (got '{conn}')")
            return
        index, table = entry
        state.sim_connection[here] = table.get("name", "modbus0")
        transport = str(table.get("transport", "")).lower()
        if transport == "rtu" and table.get("device") != MODBUS_SIM_DEVICE:
            ctx.error(
                here + ("modbus",),
                f"modbus[{index}] is a serial line to real devices; a simulated "
                f'drive needs device = "{MODBUS_SIM_DEVICE}" there',
            )
        if transport == "tcp" and table.get("host", "127.0.0.1") not in ("127.0.0.1", "localhost"):
            ctx.error(
                here + ("modbus",),
                f"modbus[{index}] goes to {table.get('host')}; a simulated drive listens on 127.0.0.1 only",
            )
        unit = sim.get("unit")
        if in_range(unit, 1, None):
            first = units.setdefault((index, unit), here)
            if first != here:
                ctx.error(here + ("unit",), f"duplicate unit {unit} on modbus[{index}] ({key_text(first)} has it)")

    def name(self, sim_type: str, sim: dict) -> str | None:
        unit = sim.get("unit")
        return f"{sim_type}_{unit}" if in_range(unit, 1, None) else None

    def build(self, values: dict, here: tuple, ctx: Relations) -> ModbusUnit:
        return ModbusUnit(modbus_state(ctx).sim_connection[here], values["unit"])


def _build_modbus(i: int, m: _Modbus, state: _State) -> ModbusConnectionConfig:
    key = f"modbus[{i}]"
    channels = []
    for j, c in enumerate(m.channel):
        at = ("modbus", i, "channel", j)
        channels.append(
            ModbusChannelConfig(
                name=c.name or f"{m.name}_{j}",
                connection=m.name,
                unit=c.unit,
                function=c.function,
                offset=c.offset,
                count=c.count,
                write_offset=c.write_offset or 0,
                write_count=c.write_count or 0,
                read_to=state.addresses.get(at + ("read_to",)),
                write_from=state.addresses.get(at + ("write_from",)),
                trigger=c.trigger,
                period_ns=c.period * 1_000_000,
                edge=state.addresses.get(at + ("edge",)),
                key=key_text(at),
            )
        )
    return ModbusConnectionConfig(
        name=m.name,
        transport=m.transport,
        device=m.device or "",
        baud=m.baud,
        parity=m.parity,
        stop_bits=m.stop_bits,
        data_bits=m.data_bits,
        frame_gap_us=m.frame_gap,
        host=m.host or "127.0.0.1",
        port=m.port if m.port is not None else 502,
        timeout_ms=m.timeout,
        retries=m.retries,
        reconnect_ms=m.reconnect,
        reconnect_max_ms=m.reconnect_max,
        channels=channels,
        key=key,
        sim_wire=m.sim_wire,
    )
