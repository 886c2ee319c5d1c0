"""[[modbus]] and [[modbus.channel]] (runtime/io/modbus/config.py); simulated
devices on a Modbus line: test_config_sims.py."""

from __future__ import annotations

from softplc.runtime.config import SimConfig, load_config
from softplc.runtime.io.modbus import ModbusChannelConfig, ModbusConnectionConfig, ModbusUnit
from softplc.runtime.sim.options import Registers

from ...config.support import EXAMPLES, MS, PLC, ST, addr, error, errors, load
from .config_support import CH, READ, RTU, TCP, channel

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
