"""[[modbus]] and [[modbus.channel]] (runtime/io/modbus/config.py); simulated
devices on a Modbus line: test_config_sims.py."""

from __future__ import annotations

import pytest

from softplc.runtime.config import SimConfig, load_config
from softplc.runtime.io.modbus import ModbusChannelConfig, ModbusConnectionConfig, ModbusUnit
from softplc.runtime.sim.options import Registers

from ...config.support import EXAMPLES, MS, PLC, ST, addr, error, errors, load, pdo, plant
from .config_support import READ, RTU, TCP, channel

# ====================================================================== [[modbus]], [[modbus.channel]]
#
# Modbus over serial line / TCP: unit ids 1..247, 0 the broadcast (serial
# line 2.2); a PDU carries at most 2000 bits (01/02), 1968 bits (15),
# 125 registers (03/04/23 read), 123 registers (16), 121 registers (23
# write). The simulated Eaton drives of [[sim]] sit on an RTU line with
# device = "sim" or behind 127.0.0.1.


DEVICE = 'a serial port such as "/dev/ttyUSB0", or "sim" for the simulated drives of [[sim]]'
ONLY_TCP = "only for transport = 'tcp' (this connection is 'rtu')"
ONLY_RTU = "only for transport = 'rtu' (this connection is 'tcp')"
CH = "modbus[0].channel[0]"


def connection(
    name: str = "drives",
    transport: str = "rtu",
    device: str = "sim",
    host: str = "127.0.0.1",
    port: int = 502,
    baud: int = 19200,
    timeout_ms: int = 200,
    retries: int = 1,
    reconnect_ms: int = 1000,
    channels: tuple = (),
    key: str = "modbus[0]",
    **serial,
) -> ModbusConnectionConfig:
    """A ModbusConnectionConfig with the defaults of the file format."""
    settings = dict(parity="N", stop_bits=1, data_bits=8, frame_gap_us=None) | serial
    return ModbusConnectionConfig(
        name=name,
        transport=transport,
        device=device,
        baud=baud,
        host=host,
        port=port,
        timeout_ms=timeout_ms,
        retries=retries,
        reconnect_ms=reconnect_ms,
        reconnect_max_ms=10_000,
        channels=list(channels),
        key=key,
        **settings,
    )


def read_channel(
    name: str,
    connection: str = "drives",
    key: str = CH,
    unit: int = 1,
    function: int = 3,
    offset: int = 5,
    count: int = 5,
    read_to: str = "%IW200",
    **more,
) -> ModbusChannelConfig:
    values = (
        dict(write_offset=0, write_count=0, write_from=None, trigger="cyclic", period_ns=100 * MS, edge=None) | more
    )
    return ModbusChannelConfig(
        name=name,
        connection=connection,
        unit=unit,
        function=function,
        offset=offset,
        count=count,
        read_to=addr(read_to) if read_to else None,
        key=key,
        **values,
    )


def test_example_modbus_rtu():
    cfg = load_config(EXAMPLES / "modbus_rtu.toml")
    assert cfg.programs == [ST / "eaton_drive.st"]
    assert [(t.name, t.interval_ns, t.programs[0].instance) for t in cfg.tasks] == [("DriveTask", 10 * MS, "Drive")]
    assert cfg.modbus == [
        ModbusConnectionConfig(
            name="drives",
            transport="rtu",
            device="sim",
            baud=115200,
            parity="N",
            stop_bits=1,
            data_bits=8,
            frame_gap_us=None,
            host="127.0.0.1",
            port=502,
            timeout_ms=100,
            retries=1,
            reconnect_ms=1000,
            reconnect_max_ms=10_000,
            key="modbus[0]",
            channels=[
                ModbusChannelConfig(
                    name="drive_monitor",
                    connection="drives",
                    unit=1,
                    function=3,
                    offset=5,
                    count=5,
                    write_offset=0,
                    write_count=0,
                    read_to=addr("%IW200"),
                    write_from=None,
                    trigger="cyclic",
                    period_ns=100 * MS,
                    edge=None,
                    key="modbus[0].channel[0]",
                )
            ],
        )
    ]
    assert cfg.sims == [SimConfig("da1", "da1_1", "sim[0]", ModbusUnit("drives", 1), Registers({505: 20}))]
    assert (cfg.can, cfg.canopen) == ([], None)


def test_example_modbus_tcp():
    cfg = load_config(EXAMPLES / "modbus_tcp.toml")
    assert cfg.programs == [ST / "eaton_drive.st"]
    # a TCP connection carries the serial defaults too; nothing uses them
    assert cfg.modbus == [
        ModbusConnectionConfig(
            name="drives",
            transport="tcp",
            device="",
            baud=19200,
            parity="N",
            stop_bits=1,
            data_bits=8,
            frame_gap_us=None,
            host="127.0.0.1",
            port=0,
            timeout_ms=200,
            retries=0,
            reconnect_ms=500,
            reconnect_max_ms=10_000,
            key="modbus[0]",
            channels=[
                ModbusChannelConfig(
                    name="drive_monitor",
                    connection="drives",
                    unit=1,
                    function=3,
                    offset=5,
                    count=5,
                    write_offset=0,
                    write_count=0,
                    read_to=addr("%IW200"),
                    write_from=None,
                    trigger="cyclic",
                    period_ns=100 * MS,
                    edge=None,
                    key="modbus[0].channel[0]",
                )
            ],
        )
    ]
    assert cfg.sims == [SimConfig("dc1", "dc1_1", "sim[0]", ModbusUnit("drives", 1), Registers({}))]


def test_file_without_modbus_sections(tmp_path):
    assert load(tmp_path, PLC).modbus == []


def test_modbus_rtu_defaults(tmp_path):
    cfg = load(tmp_path, PLC + '[[modbus]]\ntransport = "rtu"\ndevice = "/dev/ttyUSB0"\n')
    assert cfg.modbus == [connection("modbus0", device="/dev/ttyUSB0")]
    assert (cfg.modbus[0].baud, cfg.modbus[0].parity, cfg.modbus[0].stop_bits) == (19200, "N", 1)
    assert (cfg.modbus[0].timeout_ms, cfg.modbus[0].retries) == (200, 1)
    assert (cfg.modbus[0].reconnect_ms, cfg.modbus[0].reconnect_max_ms) == (1000, 10_000)


def test_modbus_tcp_defaults(tmp_path):
    cfg = load(tmp_path, PLC + '[[modbus]]\ntransport = "tcp"\n')
    assert cfg.modbus == [connection("modbus0", "tcp", device="")]
    assert (cfg.modbus[0].host, cfg.modbus[0].port) == ("127.0.0.1", 502)


def test_modbus_settings(tmp_path):
    cfg = load(
        tmp_path,
        PLC + '[[modbus]]\nname = "Line"\ntransport = "RTU"\ndevice = "/dev/ttyS1"\n'
        'baud = 9600\nparity = "e"\nstop_bits = 2\ndata_bits = 7\nframe_gap = "2ms"\n'
        'timeout = "T#1s"\nretries = 10\nreconnect = "250ms"\nreconnect_max = "1m"\n'
        '[[modbus]]\nname = "gw"\ntransport = "Tcp"\nhost = "192.168.0.20"\n'
        "port = 5020\nretries = 0\n",
    )
    assert cfg.modbus == [
        ModbusConnectionConfig(
            "Line", "rtu", "/dev/ttyS1", 9600, "E", 2, 7, 2000, "127.0.0.1", 502, 1000, 10, 250, 60_000, [], "modbus[0]"
        ),
        connection("gw", "tcp", device="", host="192.168.0.20", port=5020, retries=0, key="modbus[1]"),
    ]


def test_modbus_channels(tmp_path):
    cfg = load(
        tmp_path,
        PLC
        + RTU
        + READ
        + channel(
            16,
            'name = "Setpoints"\ncount = 2\nwrite_from = "%QW10"\ntrigger = "CHANGE"\nperiod = "1s"\n',
            unit=0,
            offset=1,
        )
        + channel(
            23,
            'write_offset = 0\nwrite_count = 2\nread_to = "%MW4"\nwrite_from = "%MW0"\n'
            'count = 6\ntrigger = "edge"\nedge = "%QX0.0"\n',
            unit=247,
        )
        + channel(1, 'count = 16\nread_to = "%IB0"\n', unit=2)
        + channel(5, 'write_from = "%QB7"\ntrigger = "edge"\nedge = "%MX1.7"\n')
        + TCP
        + READ.replace("%IW200", "%IW300"),  # each input byte has one writer
    )
    assert cfg.modbus == [
        connection(
            channels=[
                read_channel("drives_0"),
                ModbusChannelConfig(
                    "Setpoints",
                    "drives",
                    0,
                    16,
                    1,
                    2,
                    0,
                    0,
                    None,
                    addr("%QW10"),
                    "change",
                    1000 * MS,
                    None,
                    "modbus[0].channel[1]",
                ),
                ModbusChannelConfig(
                    "drives_2",
                    "drives",
                    247,
                    23,
                    0,
                    6,
                    0,
                    2,
                    addr("%MW4"),
                    addr("%MW0"),
                    "edge",
                    100 * MS,
                    addr("%QX0.0"),
                    "modbus[0].channel[2]",
                ),
                read_channel(
                    "drives_3", key="modbus[0].channel[3]", unit=2, function=1, offset=0, count=16, read_to="%IB0"
                ),
                ModbusChannelConfig(
                    "drives_4",
                    "drives",
                    1,
                    5,
                    0,
                    1,
                    0,
                    0,
                    None,
                    addr("%QB7"),
                    "edge",
                    100 * MS,
                    addr("%MX1.7"),
                    "modbus[0].channel[4]",
                ),
            ]
        ),
        connection(
            "gateway",
            "tcp",
            device="",
            key="modbus[1]",
            channels=[read_channel("gateway_0", "gateway", "modbus[1].channel[0]", read_to="%IW300")],
        ),
    ]


def test_a_tcp_host_is_checked_as_a_host(tmp_path):
    """A 1 MB host went to the socket: an idna UnicodeError of Python's."""
    assert error(tmp_path, PLC + TCP + f'host = "{"h" * 1_000_000}"\n') == (
        "modbus[0].host",
        f"expected a host name or address such as \"192.168.0.20\" (got '{'h' * 60}…' (1000000 characters))",
    )
    assert load(tmp_path, PLC + TCP + 'host = "drive-3.plant"\n').modbus[0].host == "drive-3.plant"


def test_modbus_section_shapes(tmp_path):
    assert error(tmp_path, PLC + '[modbus]\ntransport = "tcp"\n') == (
        "modbus",
        "expected [[modbus]] tables (got a table)",
    )
    assert error(tmp_path, PLC + TCP + 'hots = "x"\n') == ("modbus[0].hots", "unknown key (did you mean 'host'?)")
    assert errors(tmp_path, PLC + TCP + '[[modbus.channel]]\nname = "1st"\nperiod = "0ms"\ncount = 0\n') == [
        (
            f"{CH}.name",
            "expected a channel name: an IEC identifier (letters, digits, _; not starting with a digit) (got '1st')",
        ),
        (f"{CH}.unit", "required key missing (expected a unit id from 1 to 247 (0: broadcast write))"),
        (f"{CH}.function", "required key missing (expected a function code: 1, 2, 3, 4, 5, 6, 15, 16, 23)"),
        (f"{CH}.offset", "required key missing (expected a PDU address from 0 to 65535 (Eaton ID n is offset n-1))"),
        (f"{CH}.count", "expected an integer from 1 to 2000 (got 0)"),
        (f"{CH}.period", "expected a duration > 0 such as 10ms, 1s, T#250ms (got '0ms')"),
    ]


def test_modbus_transport(tmp_path):
    assert error(tmp_path, PLC + '[[modbus]]\ndevice = "sim"\n') == (
        "modbus[0].transport",
        "required key missing (expected 'rtu' or 'tcp')",
    )
    assert error(tmp_path, PLC + '[[modbus]]\ntransport = "udp"\n') == (
        "modbus[0].transport",
        "expected one of 'rtu', 'tcp' (got 'udp')",
    )
    assert error(tmp_path, PLC + '[[modbus]]\ntransport = "tpc"\n') == (
        "modbus[0].transport",
        "expected one of 'rtu', 'tcp' (got 'tpc'; did you mean 'tcp'?)",
    )
    assert error(tmp_path, PLC + "[[modbus]]\ntransport = 1\n") == (
        "modbus[0].transport",
        "expected one of 'rtu', 'tcp' (got 1)",
    )


def test_modbus_rtu_needs_a_device(tmp_path):
    assert error(tmp_path, PLC + '[[modbus]]\ntransport = "rtu"\n') == (
        "modbus[0]",
        f"required key missing: device ({DEVICE})",
    )
    assert error(tmp_path, PLC + '[[modbus]]\ntransport = "rtu"\ndevice = ""\n') == (
        "modbus[0].device",
        f"expected {DEVICE} (got '')",
    )


def test_modbus_keys_of_the_other_transport(tmp_path):
    assert errors(tmp_path, PLC + RTU + 'host = "192.168.0.20"\nport = 502\n') == [
        ("modbus[0].host", ONLY_TCP),
        ("modbus[0].port", ONLY_TCP),
    ]
    assert errors(
        tmp_path,
        PLC + TCP + 'device = "sim"\nbaud = 9600\nparity = "E"\nstop_bits = 1\ndata_bits = 8\nframe_gap = "2ms"\n',
    ) == [
        ("modbus[0].device", ONLY_RTU),
        ("modbus[0].baud", ONLY_RTU),
        ("modbus[0].parity", ONLY_RTU),
        ("modbus[0].stop_bits", ONLY_RTU),
        ("modbus[0].data_bits", ONLY_RTU),
        ("modbus[0].frame_gap", ONLY_RTU),
    ]


def test_modbus_serial_values_refused(tmp_path):
    assert errors(
        tmp_path, PLC + RTU + 'baud = 12345\nparity = "X"\nstop_bits = 3\ndata_bits = 9\nframe_gap = "2s"\n'
    ) == [
        ("modbus[0].baud", "expected one of 1200, 2400, 4800, 9600, 19200, 38400, 57600, 115200 (got 12345)"),
        ("modbus[0].parity", "expected one of 'N', 'E', 'O' (got 'X')"),
        ("modbus[0].stop_bits", "expected one of 1, 2 (got 3)"),
        ("modbus[0].data_bits", "expected one of 7, 8 (got 9)"),
        ("modbus[0].frame_gap", "expected a duration of at most 1000000us (at most 1s) (got '2s')"),
    ]
    assert errors(tmp_path, PLC + TCP + 'port = 70000\nretries = 11\nhost = ""\n') == [
        ("modbus[0].host", "expected a host name or address such as \"192.168.0.20\" (got '')"),
        ("modbus[0].port", "expected an integer from 0 to 65535 (got 70000)"),
        ("modbus[0].retries", "expected an integer from 0 to 10 (got 11)"),
    ]


def test_duplicate_connection_names(tmp_path):
    assert error(tmp_path, PLC + RTU + TCP.replace('"gateway"', '"DRIVES"')) == (
        "modbus[1].name",
        "duplicate connection name 'DRIVES' (modbus[0] has it; names are case-insensitive)",
    )
    assert error(tmp_path, PLC + '[[modbus]]\ntransport = "tcp"\n[[modbus]]\ntransport = "tcp"\n') == (
        "modbus[1]",
        "duplicate connection name 'modbus0' (modbus[0] has it; names are case-insensitive): "
        "give each [[modbus]] a name",
    )


def test_duplicate_channel_names(tmp_path):
    other = READ.replace("%IW200", "%IW300")
    assert error(tmp_path, PLC + RTU + READ + 'name = "monitor"\n' + other + 'name = "Monitor"\n') == (
        "modbus[0].channel[1].name",
        "duplicate channel name 'Monitor' (channel[0] has it; names are case-insensitive)",
    )
    # channel names are per connection
    cfg = load(tmp_path, PLC + RTU + READ + 'name = "monitor"\n' + TCP + other + 'name = "monitor"\n')
    assert [[c.name for c in m.channels] for m in cfg.modbus] == [["monitor"], ["monitor"]]


def test_modbus_function_codes(tmp_path):
    assert error(tmp_path, PLC + RTU + channel(7)) == (
        f"{CH}.function",
        "expected one of 1, 2, 3, 4, 5, 6, 15, 16, 23 (got 7)",
    )
    assert error(tmp_path, PLC + RTU + channel("true")) == (
        f"{CH}.function",
        "expected one of 1, 2, 3, 4, 5, 6, 15, 16, 23 (got true)",
    )


@pytest.mark.parametrize(
    "function, body, message",
    [
        (3, 'count = 126\nread_to = "%IW0"\n', "function 3 carries at most 125 registers (got 126)"),
        (4, 'count = 126\nread_to = "%IW0"\n', "function 4 carries at most 125 registers (got 126)"),
        (16, 'count = 124\nwrite_from = "%QW0"\n', "function 16 carries at most 123 registers (got 124)"),
        (15, 'count = 1969\nwrite_from = "%QB0"\n', "function 15 carries at most 1968 bits (got 1969)"),
        (6, 'count = 2\nwrite_from = "%QW0"\n', "function 6 carries at most 1 register (got 2)"),
        (5, 'count = 2\nwrite_from = "%QB0"\n', "function 5 carries at most 1 bit (got 2)"),
        (
            23,
            'count = 126\nread_to = "%IW0"\nwrite_from = "%QW0"\nwrite_offset = 0\nwrite_count = 1\n',
            "function 23 carries at most 125 registers (got 126)",
        ),
        # beyond what any function carries: pass 1 says so, once
        (1, 'count = 2001\nread_to = "%IB0"\n', "expected an integer from 1 to 2000 (got 2001)"),
    ],
)
def test_modbus_count_limits(tmp_path, function, body, message):
    assert error(tmp_path, PLC + RTU + channel(function, body)) == (f"{CH}.count", message)


@pytest.mark.parametrize(
    "function, body",
    [
        (3, 'count = 125\nread_to = "%IW0"\n'),
        (1, 'count = 2000\nread_to = "%IB0"\n'),
        (16, 'count = 123\nwrite_from = "%QW0"\n'),
        (15, 'count = 1968\nwrite_from = "%QB0"\n'),
        (23, 'count = 125\nread_to = "%IW0"\nwrite_from = "%QW0"\nwrite_offset = 0\nwrite_count = 121\n'),
    ],
)
def test_modbus_count_limits_accepted(tmp_path, function, body):
    assert load(tmp_path, PLC + RTU + channel(function, body)).modbus[0].channels[0].function == function


def test_a_count_of_the_wrong_type_is_one_error(tmp_path):
    """Pass 2 sizes the block only with an integer count (a string once crashed it)."""
    assert error(tmp_path, PLC + RTU + READ.replace("count = 5", 'count = "5"')) == (
        f"{CH}.count",
        "expected an integer from 1 to 2000 (got '5')",
    )
    body = 'read_to = "%IW0"\nwrite_from = "%QW0"\nwrite_offset = 0\nwrite_count = "2"\n'
    assert error(tmp_path, PLC + RTU + channel(23, body)) == (
        f"{CH}.write_count",
        "expected an integer from 1 to 121 (got '2')",
    )


def test_function_23_write_block(tmp_path):
    rw = 'read_to = "%IW0"\nwrite_from = "%QW0"\n'
    assert errors(tmp_path, PLC + RTU + channel(23, rw)) == [
        (CH, "required key missing: write_offset (function 23 writes and reads)"),
        (CH, "required key missing: write_count (function 23 writes and reads)"),
    ]
    assert error(tmp_path, PLC + RTU + channel(23, rw + "write_offset = 0\nwrite_count = 122\n")) == (
        f"{CH}.write_count",
        "expected an integer from 1 to 121 (got 122)",
    )
    assert errors(tmp_path, PLC + RTU + READ + "write_offset = 1\nwrite_count = 1\n") == [
        (f"{CH}.write_offset", "only for function 23 (offset and count give the block)"),
        (f"{CH}.write_count", "only for function 23 (offset and count give the block)"),
    ]


def test_channel_read_to(tmp_path):
    assert error(tmp_path, PLC + RTU + channel(3)) == (
        CH,
        "required key missing: read_to (the image address the channel reads into)",
    )
    assert error(tmp_path, PLC + RTU + channel(3, 'read_to = "%QW0"\n')) == (
        f"{CH}.read_to",
        "expected an address in %I or %M (got '%QW0', an output)",
    )
    assert error(tmp_path, PLC + RTU + channel(3, 'read_to = "IW0"\n')) == (
        f"{CH}.read_to",
        "expected a direct address such as %IW100, %MW20 (got 'IW0')",
    )
    assert error(tmp_path, PLC + RTU + channel(3, "read_to = 200\n")) == (
        f"{CH}.read_to",
        "expected a direct address such as %IW100, %MW20 (got 200)",
    )
    assert error(tmp_path, PLC + RTU + READ + 'write_from = "%QW0"\n') == (
        f"{CH}.write_from",
        "function 3 does not use write_from",
    )


def test_channel_write_from(tmp_path):
    assert error(tmp_path, PLC + RTU + channel(6)) == (
        CH,
        "required key missing: write_from (the image address the channel writes from)",
    )
    assert error(tmp_path, PLC + RTU + channel(6, 'write_from = "%IW0"\n')) == (
        f"{CH}.write_from",
        "expected an address in %Q or %M (got '%IW0', an input)",
    )
    assert error(tmp_path, PLC + RTU + channel(16, 'write_from = "%QW0"\nread_to = "%IW0"\n')) == (
        f"{CH}.read_to",
        "function 16 does not use read_to",
    )


def test_channel_triggers(tmp_path):
    assert error(tmp_path, PLC + RTU + READ + 'trigger = "change"\n') == (
        f"{CH}.trigger",
        "'change' watches the data to write; function 3 only reads (use 'cyclic' or 'edge')",
    )
    assert error(tmp_path, PLC + RTU + READ + 'trigger = "edge"\n') == (
        CH,
        'required key missing: edge (the BOOL whose rising edge triggers, such as "%QX10.0")',
    )
    assert error(tmp_path, PLC + RTU + READ + 'trigger = "edge"\nedge = "%QW10"\n') == (
        f"{CH}.edge",
        "expected a BOOL (bit) address such as %QX10.0 (got '%QW10')",
    )
    assert error(tmp_path, PLC + RTU + READ + 'trigger = "edge"\nedge = true\n') == (
        f"{CH}.edge",
        "expected a direct address such as %QX10.0, %MX2.0 (got true)",
    )
    assert error(tmp_path, PLC + RTU + READ + 'edge = "%QX10.0"\n') == (f"{CH}.edge", "only for trigger = 'edge'")
    assert error(tmp_path, PLC + RTU + READ + 'trigger = "cyclic"\nedge = "%QX10.0"\n') == (
        f"{CH}.edge",
        "only for trigger = 'edge'",
    )
    assert error(tmp_path, PLC + RTU + READ + 'trigger = "rising"\n') == (
        f"{CH}.trigger",
        "expected one of 'cyclic', 'change', 'edge' (got 'rising')",
    )
    cfg = load(tmp_path, PLC + RTU + READ + 'trigger = "edge"\nedge = "%IX3.1"\n')
    assert (cfg.modbus[0].channels[0].trigger, cfg.modbus[0].channels[0].edge) == ("edge", addr("%IX3.1"))


def test_channel_unit_0_is_for_writes(tmp_path):
    assert error(tmp_path, PLC + RTU + READ.replace("unit = 1", "unit = 0")) == (
        f"{CH}.unit",
        "unit 0 is the broadcast address: nobody answers, so only writes can go to it",
    )
    assert error(
        tmp_path,
        PLC + RTU + channel(23, 'read_to = "%IW0"\nwrite_from = "%QW0"\nwrite_offset = 0\nwrite_count = 1\n', unit=0),
    ) == (f"{CH}.unit", "unit 0 is the broadcast address: nobody answers, so only writes can go to it")
    assert error(tmp_path, PLC + RTU + READ.replace("unit = 1", "unit = 248")) == (
        f"{CH}.unit",
        "expected an integer from 0 to 247 (got 248)",
    )
    cfg = load(tmp_path, PLC + RTU + channel(6, 'write_from = "%QW0"\n', unit=0))
    assert cfg.modbus[0].channels[0].unit == 0


def test_channel_inside_the_image(tmp_path):
    assert error(tmp_path, PLC + RTU + READ.replace("%IW200", "%IW32767").replace("count = 5", "count = 10")) == (
        f"{CH}.read_to",
        "10 registers from %IW32767 run past the end of the %I area",
    )
    assert error(tmp_path, PLC + RTU + channel(15, 'count = 16\nwrite_from = "%QB65535"\n')) == (
        f"{CH}.write_from",
        "16 bits from %QB65535 run past the end of the %Q area",
    )
    assert error(tmp_path, PLC + RTU + READ.replace("%IW200", "%IW40000")) == (
        f"{CH}.read_to",
        "%IW40000 (bytes 80000..80001) is outside the 65536-byte %I area",
    )
    assert error(tmp_path, PLC + RTU + channel(1, 'count = 8\nread_to = "%IX0.0"\n')) == (
        f"{CH}.read_to",
        "%IX0.0 is a bit; drivers copy whole bytes: give the byte or word that holds it (e.g. %IB0, %IW0)",
    )
    cfg = load(
        tmp_path, PLC + RTU + READ.replace("%IW200", "%IW32763") + channel(15, 'count = 8\nwrite_from = "%QB65535"\n')
    )
    assert [c.read_to or c.write_from for c in cfg.modbus[0].channels] == [addr("%IW32763"), addr("%QB65535")]


def test_modbus_addresses_follow_the_profile(tmp_path):
    from softplc.runtime.image.address import parse_address

    schneider = '[plc]\nprograms = ["main.st"]\nprofile = "schneider"\n'
    cfg = load(
        tmp_path,
        schneider
        + RTU
        + READ.replace('"%IW200"', '"%MW100"')
        + channel(
            23,
            'count = 2\nread_to = "%MW10:2"\nwrite_from = "%MW20:4"\nwrite_offset = 0\n'
            'write_count = 4\ntrigger = "edge"\nedge = "%MW30:X3"\n',
        ),
    )
    assert cfg.profile == "schneider"
    first, second = cfg.modbus[0].channels
    assert first.read_to == parse_address("%MW100", "schneider")
    assert (second.read_to, second.write_from, second.edge) == (
        parse_address("%MW10:2", "schneider"),
        parse_address("%MW20:4", "schneider"),
        parse_address("%MW30:X3", "schneider"),
    )
    # the same Schneider forms under an IEC profile
    assert errors(
        tmp_path,
        PLC
        + RTU
        + channel(
            23,
            'count = 2\nread_to = "%MW10:2"\nwrite_from = "%MW20:4"\n'
            'write_offset = 0\nwrite_count = 4\ntrigger = "edge"\n'
            'edge = "%MW30:X3"\n',
        ),
    ) == [
        (
            f"{CH}.read_to",
            "%MW10:2 is Schneider addressing; use the schneider profile (IEC addresses a bit as %MX<byte>.<bit>)",
        ),
        (
            f"{CH}.write_from",
            "%MW20:4 is Schneider addressing; use the schneider profile (IEC addresses a bit as %MX<byte>.<bit>)",
        ),
        (
            f"{CH}.edge",
            "%MW30:X3 is Schneider addressing; use the schneider profile (IEC addresses a bit as %MX<byte>.<bit>)",
        ),
    ]


# ====================================================================== one writer per image byte


def test_two_channels_reading_into_overlapping_inputs_are_refused(tmp_path):
    """Two channels wrote %IW200.. and %IW203..: which value a program saw
    depended on the order of their answers."""
    text = PLC + RTU + channel(3, 'count = 4\nread_to = "%IW200"\n') + channel(4, 'count = 2\nread_to = "%IW203"\n', 2)
    assert error(tmp_path, text) == (
        "modbus[0].channel[1].read_to",
        "2 registers from '%IW203' overlaps modbus[0].channel[0].read_to (4 registers from '%IW200'): "
        "each image byte has one writer",
    )


def test_channels_of_two_connections_share_no_input_byte_either(tmp_path):
    other = '[[modbus]]\nname = "gateway"\ntransport = "tcp"\nhost = "10.0.0.2"\n'
    text = PLC + RTU + channel(1, 'count = 16\nread_to = "%IB10"\n') + other + channel(3, 'read_to = "%IW5"\n')
    assert error(tmp_path, text) == (
        "modbus[1].channel[0].read_to",
        "1 register from '%IW5' overlaps modbus[0].channel[0].read_to (16 bits from '%IB10'): "
        "each image byte has one writer",
    )


def test_a_read_into_memory_has_one_writer_too(tmp_path):
    text = PLC + RTU + channel(3, 'count = 2\nread_to = "%MW0"\n') + channel(3, 'read_to = "%MB3"\n', 2)
    assert error(tmp_path, text)[0] == "modbus[0].channel[1].read_to"


def test_a_read_overlapping_a_tpdo_is_refused(tmp_path):
    """A Modbus read_to over a TPDO's %IW100 passed; each wrote in turn."""
    text = plant("", "", pdo("tpdo", 1, ("2004:06", "%IW100"))) + RTU + channel(3, 'count = 8\nread_to = "%IW96"\n')
    assert error(tmp_path, text) == (
        "modbus[0].channel[0].read_to",
        "8 registers from '%IW96' overlaps canopen.node[0].tpdo[0].map[0].address ('%IW100'): "
        "each image byte has one writer",
    )


def test_a_read_overlapping_a_loopback_target_is_refused(tmp_path):
    loopback = '[[loopback]]\nfrom = "%QB0"\nto = "%IB10"\nbytes = 4\n'
    assert error(tmp_path, PLC + loopback + RTU + channel(3, 'read_to = "%IW6"\n')) == (
        "modbus[0].channel[0].read_to",
        "1 register from '%IW6' overlaps loopback[0].to ('%IB10', 4 bytes): each image byte has one writer",
    )


def test_adjacent_reads_and_shared_writes_are_fine(tmp_path):
    cfg = load(
        tmp_path,
        plant("", "", pdo("tpdo", 1, ("2004:06", "%IW100")))
        + RTU
        + channel(3, 'count = 4\nread_to = "%IW96"\n')  # bytes 192..199, the TPDO's 200..201
        + channel(3, 'count = 2\nread_to = "%IW101"\n', 2)
        + channel(16, 'count = 2\nwrite_from = "%QW0"\n')  # two channels may send the same outputs
        + channel(6, 'write_from = "%QW0"\n', 2),
    )
    assert [ch.read_to.text if ch.read_to else ch.write_from.text for ch in cfg.modbus[0].channels] == [
        "%IW96",
        "%IW101",
        "%QW0",
        "%QW0",
    ]
