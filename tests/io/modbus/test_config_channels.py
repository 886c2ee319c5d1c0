"""A [[modbus.channel]]: its function code and count limits, where it reads
to and writes from in the image (inside it, after the profile's
addressing), its triggers, and one writer per image byte (two channels, a
channel and a TPDO or a loopback target never write the same input)."""

from __future__ import annotations

import pytest

from ...config.support import PLC, addr, error, errors, load, pdo, plant
from .config_support import CH, READ, RTU, channel


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
