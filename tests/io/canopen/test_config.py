"""[canopen] and its nodes (runtime/io/canopen/config.py).

Numbers from the LTMR CANopen manual (001, English) where it sets them:
node ids 1..127 (L163), 0x1016:01 and 0x1017 in 16 bits of ms (L957,
L964), the TPDO inhibit time in 16 bits of 100 us (L1365), 8 bytes per PDO
(L117)."""

from __future__ import annotations

import pytest

from softplc.runtime.config import SafeOutput, SimConfig, load_config
from softplc.runtime.devices.ltmr.sim_options import LtmrPresets
from softplc.runtime.io.can import CanBusConfig, CanNode
from softplc.runtime.io.canopen.config import (
    CanopenConfig,
    CanopenNodeConfig,
    PdoConfig,
    PdoEntryConfig,
    SdoWriteConfig,
)

from ...config.support import CAN, EDS, EXAMPLES, NODE, PLC, ST, addr, error, errors, load, plant


def test_example_canopen():
    cfg = load_config(EXAMPLES / "canopen.toml")
    assert cfg.programs == [ST / "ltmr_motor.st"]
    assert cfg.can == [CanBusConfig("can0", "virtual", "softplc-example-canopen", 250_000, {}, "can[0]")]
    key = "canopen.node[0]"

    def entries(pdo: str, *pairs) -> list:
        return [
            PdoEntryConfig(index, sub, addr(text), f"{key}.{pdo}.map[{k}]")
            for k, (index, sub, text) in enumerate(pairs)
        ]

    assert cfg.canopen == CanopenConfig(
        bus="can0",
        node_id=127,
        heartbeat_ms=100,
        sync_us=50_000,
        sdo_timeout_ms=500,
        boot_timeout_ms=2000,
        retry_ms=1000,
        key="canopen",
        nodes=[
            CanopenNodeConfig(
                name="motor",
                node_id=40,
                eds=EDS / "ltmr.eds",
                mandatory=True,
                heartbeat_ms=100,
                heartbeat_timeout_ms=300,
                master_timeout_ms=500,
                master_timeout_explicit=True,
                device="ltmr",
                key=key,
                sdo=[
                    SdoWriteConfig(0x2007, 0x21, 2, None, f"{key}.sdo[0]"),
                    SdoWriteConfig(0x1029, 0x01, 0, 1, f"{key}.sdo[1]"),
                ],
                tpdo=[
                    PdoConfig(
                        1,
                        255,
                        0,
                        0,
                        False,
                        entries(
                            "tpdo[0]",
                            (0x2004, 0x06, "%IW100"),
                            (0x2004, 0x07, "%IW101"),
                            (0x2004, 0x08, "%IW102"),
                            (0x2004, 0x0A, "%IW103"),
                        ),
                        f"{key}.tpdo[0]",
                    ),
                    PdoConfig(
                        2,
                        255,
                        10_000,
                        1000,
                        True,
                        entries("tpdo[1]", (0x2004, 0x02, "%IW104"), (0x2004, 0x0B, "%IW105")),
                        f"{key}.tpdo[1]",
                    ),
                    PdoConfig(
                        3,
                        1,
                        0,
                        0,
                        True,
                        entries("tpdo[2]", (0x2004, 0x10, "%IW106"), (0x2004, 0x11, "%IW107")),
                        f"{key}.tpdo[2]",
                    ),
                ],
                rpdo=[
                    PdoConfig(
                        1,
                        255,
                        0,
                        0,
                        False,
                        entries(
                            "rpdo[0]", (0x2008, 0x05, "%QW100"), (0x2008, 0x04, "%QW101"), (0x2008, 0x01, "%QW102")
                        ),
                        f"{key}.rpdo[0]",
                    )
                ],
            )
        ],
    )
    assert cfg.sims == [SimConfig("ltmr", "ltmr40", "sim[0]", CanNode("can0", 40), LtmrPresets({682: 0}))]
    assert cfg.safe_outputs == [SafeOutput(addr("%QW100"), 0, 'outputs.safe."%QW100"')]


# ---------------------------------------------------------------- [canopen] durations


@pytest.mark.parametrize(
    "written, field, value",
    [
        ('heartbeat = "250ms"', "heartbeat_ms", 250),
        ("heartbeat = false", "heartbeat_ms", 0),
        ('heartbeat = "0ms"', "heartbeat_ms", 0),
        ('heartbeat = "1.4ms"', "heartbeat_ms", 1),  # rounded to whole ms
        ('heartbeat = "1.6ms"', "heartbeat_ms", 2),
        ('sync = "2.5ms"', "sync_us", 2500),  # SYNC in microseconds
        ('sync = "T#1ms"', "sync_us", 1000),
        ("sync = false", "sync_us", 0),
        ('sdo_timeout = "1s"', "sdo_timeout_ms", 1000),
        ('boot_timeout = "3000ms"', "boot_timeout_ms", 3000),
        ('retry = "1.5s"', "retry_ms", 1500),
    ],
)
def test_master_durations(tmp_path, written, field, value):
    cfg = load(tmp_path, PLC + CAN + f"[canopen]\n{written}\n")
    assert getattr(cfg.canopen, field) == value


@pytest.mark.parametrize(
    "written, message",
    [
        ('sdo_timeout = "0ms"', "expected a duration > 0 such as 10ms, 1s, T#250ms (got '0ms')"),
        ("sdo_timeout = false", "expected a duration > 0 such as 10ms, 1s, T#250ms (got false)"),
        ('retry = "0.4ms"', "expected a duration of at least 1ms (got '0.4ms')"),
        ("heartbeat = true", "expected a duration such as 10ms, 1s, T#250ms, or false for no heartbeat (got true)"),
        ('heartbeat = "-5ms"', "expected a duration such as 10ms, 1s, T#250ms, or false for no heartbeat (got '-5ms')"),
        ('heartbeat = "0.4ms"', "expected a duration of at least 1ms, or false for no heartbeat (got '0.4ms')"),
        ('sync = "soon"', "expected a duration such as 10ms, 1s, T#250ms, or false for no SYNC (got 'soon')"),
        ("sync = 10", "expected a duration with its unit, such as 10ms or 10s (got 10: a number alone has none)"),
        (
            'sync = "1us"',
            "expected a duration of at least 1ms (the master's service runs every millisecond), or false for no "
            "SYNC (got '1us')",
        ),
    ],
)
def test_master_durations_refused(tmp_path, written, message):
    assert error(tmp_path, PLC + CAN + f"[canopen]\n{written}\n") == (f"canopen.{written.split()[0]}", message)


# ---------------------------------------------------------------- heartbeats


def test_node_heartbeat_defaults(tmp_path):
    def times(master: str, node: str) -> tuple:
        n = load(tmp_path, plant(master, node)).canopen.nodes[0]
        return n.heartbeat_ms, n.heartbeat_timeout_ms, n.master_timeout_ms

    assert times("", "") == (100, 300, 500)  # 3 x 100, 5 x 100
    assert times('heartbeat = "50ms"\n', 'heartbeat = "200ms"\n') == (200, 600, 250)
    assert times("", 'heartbeat = "1s"\nheartbeat_timeout = "1.5s"\nmaster_timeout = "150ms"\n') == (1000, 1500, 150)
    assert times("", "heartbeat = false\n") == (0, 0, 500)  # nothing to watch
    assert times("", 'heartbeat = "0ms"\n') == (0, 0, 500)
    assert times("", "heartbeat_timeout = false\n") == (100, 0, 500)  # sent, not watched
    assert times("heartbeat = false\n", "") == (100, 300, 0)  # no master heartbeat to watch
    assert times("", "master_timeout = false\n") == (100, 300, 0)
    assert times('heartbeat = "20s"\n', "") == (100, 300, 65535)  # not 5 x 20 s: 0x1016:01 holds 65.535 s


def test_heartbeat_words_of_the_manual(tmp_path):
    """Digest 001 §7.2 (derived from manual 001 L957/L964): the master 0x7F
    watched at 500 ms is 0x1016:01 = 0x007F01F4; a producer time of 1000 ms
    is 0x1017 = 0x03E8."""
    node = load(tmp_path, plant("node_id = 127\n", 'heartbeat = "1s"\nmaster_timeout = "500ms"\n')).canopen
    assert (node.node_id << 16) | node.nodes[0].master_timeout_ms == 0x007F01F4
    assert node.nodes[0].heartbeat_ms == 0x03E8


def test_heartbeat_fields_of_16_bits(tmp_path):
    n = load(tmp_path, plant("", 'heartbeat = "65535ms"\nheartbeat_timeout = "70s"\nmaster_timeout = "65535ms"\n'))
    assert (n.canopen.nodes[0].heartbeat_ms, n.canopen.nodes[0].master_timeout_ms) == (65535, 65535)
    assert errors(tmp_path, plant("", 'heartbeat = "65.536s"\nmaster_timeout = "1min"\n')) == [
        (
            "canopen.node[0].heartbeat",
            "expected a duration of at most 65535ms (0x1017 holds ms in 16 bits), or "
            "false for no heartbeat (got '65.536s')",
        ),
        (
            "canopen.node[0].master_timeout",
            "expected a duration such as 10ms, 1s, T#250ms, or false for the node not watching the master (got '1min')",
        ),
    ]
    assert error(tmp_path, plant("", 'master_timeout = "66s"\n')) == (
        "canopen.node[0].master_timeout",
        "expected a duration of at most 65535ms (0x1016:01 holds ms in 16 "
        "bits), or false for the node not watching the master (got '66s')",
    )


def test_heartbeat_timeout_must_outlast_the_heartbeat(tmp_path):
    assert error(tmp_path, plant("", 'heartbeat = "100ms"\nheartbeat_timeout = "100ms"\n')) == (
        "canopen.node[0].heartbeat_timeout",
        "expected a duration longer than the node's heartbeat (100ms), or false for not watching it (got '100ms')",
    )
    assert error(tmp_path, plant("", 'heartbeat = false\nheartbeat_timeout = "300ms"\n')) == (
        "canopen.node[0].heartbeat_timeout",
        "only meaningful with a heartbeat (this node has heartbeat = false)",
    )


def test_master_timeout_must_outlast_the_masters_heartbeat(tmp_path):
    assert error(tmp_path, plant('heartbeat = "200ms"\n', 'master_timeout = "150ms"\n')) == (
        "canopen.node[0].master_timeout",
        "expected a duration longer than canopen.heartbeat (200ms), or "
        "false for the node not watching the master (got '150ms')",
    )
    assert error(tmp_path, plant('heartbeat = "0ms"\n', 'master_timeout = "500ms"\n')) == (
        "canopen.node[0].master_timeout",
        "only meaningful when the master sends a heartbeat (canopen.heartbeat = '0ms')",
    )
    assert error(tmp_path, plant('heartbeat = "65535ms"\n')) == (
        "canopen.node[0]",
        "the default master_timeout, 5 x canopen.heartbeat at most 65535ms, is not longer "
        "than canopen.heartbeat (65535ms): give master_timeout, or false",
    )


# ---------------------------------------------------------------- nodes


def test_node_ids(tmp_path):
    assert load(tmp_path, plant("node_id = 1\n").replace("id = 40", "id = 127")).canopen.nodes[0].node_id == 127
    assert errors(tmp_path, plant("node_id = 0\n").replace("id = 40", "id = 128")) == [
        ("canopen.node_id", "expected an integer from 1 to 127 (got 0)"),
        ("canopen.node[0].id", "expected an integer from 1 to 127 (got 128)"),
    ]
    assert error(tmp_path, plant("node_id = 40\n")) == (
        "canopen.node[0].id",
        "40 is the master's own node id (canopen.node_id): give the master another one (canopen.node_id = 1) or "
        "the node another (set its node-id parameter, and id here)",
    )
    assert errors(tmp_path, plant("", "", NODE.replace('"motor"', '"Pump"'), NODE.replace("40", "41"))) == [
        ("canopen.node[1].id", "duplicate node id 40 (canopen.node[0] has it)"),
        ("canopen.node[2].name", "duplicate node name 'motor' (canopen.node[0] has it; names are case-insensitive)"),
    ]


def test_node_required_keys(tmp_path):
    assert errors(tmp_path, PLC + CAN + "[canopen]\n[[canopen.node]]\nmandatory = 1\n") == [
        ("canopen.node[0].name", 'required key missing (expected a node name such as "motor1")'),
        ("canopen.node[0].id", "required key missing (expected a node id from 1 to 127)"),
        (
            "canopen.node[0].eds",
            'required key missing (expected a shipped EDS name such as "ltmr" or the path of an .eds file)',
        ),
        ("canopen.node[0].mandatory", "expected true or false (got 1)"),
    ]


def test_node_mandatory(tmp_path):
    assert load(tmp_path, plant("", "mandatory = false\n")).canopen.nodes[0].mandatory is False


@pytest.mark.parametrize(
    "written, path", [('"ltmr"', EDS / "ltmr.eds"), ('"LTMR"', EDS / "ltmr.eds"), ('"fc280"', EDS / "fc280.eds")]
)
def test_shipped_eds(tmp_path, written, path):
    text = plant("", "").replace('eds = "ltmr"', f"eds = {written}")
    assert load(tmp_path, text).canopen.nodes[0].eds == path


def test_eds_files(tmp_path):
    (tmp_path / "devices").mkdir()
    (tmp_path / "devices" / "motor.eds").write_text((EDS / "ltmr.eds").read_text())
    text = plant("", "").replace('eds = "ltmr"', 'eds = "devices/motor.eds"')
    assert load(tmp_path, text).canopen.nodes[0].eds == tmp_path / "devices" / "motor.eds"
    for written, message in [
        (
            '"ltmx"',
            "expected a shipped EDS name ('fc280', 'ltmr') or the path of an .eds file (got 'ltmx'; did "
            "you mean 'ltmr'?)",
        ),
        ('"vfd"', "expected a shipped EDS name ('fc280', 'ltmr') or the path of an .eds file (got 'vfd')"),
        ("7", "expected a shipped EDS name ('fc280', 'ltmr') or the path of an .eds file (got 7)"),
        (
            '"devices/pump.eds"',
            f"no such file: {tmp_path / 'devices' / 'pump.eds'} (relative paths start at the config file's directory)",
        ),
        ('"devices/"', f"not a file: {tmp_path / 'devices'}"),
    ]:
        assert error(tmp_path, plant("", "").replace('eds = "ltmr"', f"eds = {written}")) == (
            "canopen.node[0].eds",
            message,
        )


# ---------------------------------------------------------------- boot-time SDO writes


def test_sdo_writes(tmp_path):
    cfg = load(
        tmp_path,
        plant(
            "",
            'sdo = [{ object = "2007:21", value = 2 }, { object = "0x1017:0", '
            'value = 1000, size = 2 }, { object = "1:1", value = -1, size = 4 }, '
            '{ object = "2004:6a", value = 4294967295, size = 4 }]\n',
        ),
    )
    assert cfg.canopen.nodes[0].sdo == [
        SdoWriteConfig(0x2007, 0x21, 2, None, "canopen.node[0].sdo[0]"),
        SdoWriteConfig(0x1017, 0x00, 1000, 2, "canopen.node[0].sdo[1]"),
        SdoWriteConfig(0x0001, 0x01, -1, 4, "canopen.node[0].sdo[2]"),
        SdoWriteConfig(0x2004, 0x6A, 4294967295, 4, "canopen.node[0].sdo[3]"),
    ]


@pytest.mark.parametrize(
    "written", ['"2004.06"', '"12004:06"', '"2004:123"', '"2004:"', '":06"', '"x2004:06"', '"2004:0G"', '""', "0x2004"]
)
def test_bad_objects(tmp_path, written):
    got = written.replace('"', "'") if written.startswith('"') else "8196"
    assert error(tmp_path, plant("", f"sdo = [{{ object = {written}, value = 1 }}]\n")) == (
        "canopen.node[0].sdo[0].object",
        f'expected an object "index:subindex" in hex, such as "2004:06" (got {got})',
    )


@pytest.mark.parametrize(
    "size, value, fits",
    [
        (1, 255, True),
        (1, -128, True),
        (1, 256, False),
        (1, -129, False),
        (2, 65535, True),
        (2, -32768, True),
        (2, 65536, False),
        (4, 4294967295, True),
        (4, -2147483648, True),
        (4, 4294967296, False),
    ],
)
def test_sdo_value_must_fit_its_size(tmp_path, size, value, fits):
    text = plant("", f'sdo = [{{ object = "2007:21", value = {value}, size = {size} }}]\n')
    if fits:
        assert load(tmp_path, text).canopen.nodes[0].sdo[0].value == value
    else:
        lo, hi = -(1 << (8 * size - 1)), (1 << (8 * size)) - 1
        assert error(tmp_path, text) == (
            "canopen.node[0].sdo[0].value",
            f"expected an integer from {lo} to {hi} for size = {size} (got {value})",
        )


def test_sdo_write_errors(tmp_path):
    assert errors(
        tmp_path,
        plant(
            "",
            'sdo = [{ object = "2007:21" }, { object = "2007:21", value = "2", '
            'size = 3 }, { object = "2007:21", value = 1.5, bytes = 2 }]\n',
        ),
    ) == [
        ("canopen.node[0].sdo[0].value", "required key missing (expected an integer)"),
        ("canopen.node[0].sdo[1].value", "expected an integer (got '2')"),
        ("canopen.node[0].sdo[1].size", "expected a size in bytes: 1, 2 or 4 (got 3)"),
        ("canopen.node[0].sdo[2].value", "expected an integer (got 1.5)"),
        ("canopen.node[0].sdo[2].bytes", "unknown key (expected one of object, parameter, value, size)"),
    ]


# ---------------------------------------------------------------- node guarding


def test_node_guarding_instead_of_a_heartbeat(tmp_path):
    node = load(tmp_path, plant("", 'guard_time = "100ms"\n')).canopen.nodes[0]
    # no heartbeat by default, none watched, no 0x1016 default: the node watches the master by guarding
    assert (node.guard_time_ms, node.life_time_factor) == (100, 3)
    assert (node.heartbeat_ms, node.heartbeat_timeout_ms, node.master_timeout_ms) == (0, 0, 0)
    node = load(tmp_path, plant("", 'guard_time = "50ms"\nlife_time_factor = 5\n')).canopen.nodes[0]
    assert (node.guard_time_ms, node.life_time_factor) == (50, 5)
    assert load(tmp_path, plant("", "")).canopen.nodes[0].guard_time_ms == 0


def test_node_guarding_errors(tmp_path):
    assert errors(tmp_path, plant("", 'guard_time = "100ms"\nheartbeat = "100ms"\n')) == [
        (
            "canopen.node[0].heartbeat",
            "a node is watched by its heartbeat or by node guarding, not both (this node has guard_time = "
            "'100ms'): remove one; a node that sends heartbeats does not answer guarding",
        )
    ]
    assert error(tmp_path, plant("", "life_time_factor = 3\n")) == (
        "canopen.node[0].life_time_factor",
        "only with guard_time (node guarding)",
    )
    assert errors(tmp_path, plant("", 'guard_time = "70s"\nlife_time_factor = 0\n')) == [
        (
            "canopen.node[0].guard_time",
            "expected a duration of at most 65535ms (0x100C holds ms in 16 bits), or false for no node "
            "guarding (got '70s')",
        ),
        ("canopen.node[0].life_time_factor", "expected an integer from 1 to 255 (got 0)"),
    ]
    # heartbeat = false with guarding is what the default says anyway
    assert load(tmp_path, plant("", 'guard_time = "100ms"\nheartbeat = false\n')).canopen.nodes[0].heartbeat_ms == 0


# ---------------------------------------------------------------- writes by parameter number

FC280 = NODE.replace('eds = "ltmr"', 'eds = "fc280"')


def test_boot_time_writes_by_parameter_number(tmp_path):
    # manual 003 §5.1: 2000h + g*100 + nn; Tabelle 6.2: 8-03 has conversion index -1 (1.0 s -> 10)
    cfg = load(
        tmp_path,
        PLC + CAN + "[canopen]\nnode_id = 1\n" + FC280 + 'sdo = [{ parameter = "8-03", value = 1.0 }, '
        '{ parameter = "8-04", value = 5 }, { parameter = "3-10[1]", value = 25.0 }, '
        '{ object = "2007:21", value = 2 }]\n',
    )
    node = cfg.canopen.nodes[0]
    assert node.device == "fc280"
    assert node.sdo == [
        SdoWriteConfig(0x2323, 0, 10, 2, "canopen.node[0].sdo[0]"),
        SdoWriteConfig(0x2324, 0, 5, 1, "canopen.node[0].sdo[1]"),
        SdoWriteConfig(0x2136, 2, 2500, 2, "canopen.node[0].sdo[2]"),  # element [1]: sub-index 2 (A35)
        SdoWriteConfig(0x2007, 0x21, 2, None, "canopen.node[0].sdo[3]"),
    ]


def test_writes_by_parameter_number_errors(tmp_path):
    sdo = (
        'sdo = [{ parameter = "8-3x", value = 1 }, { parameter = "9-99", value = 1 }, '
        '{ parameter = "8-03", value = 7000.0 }, { parameter = "3-10", value = 1 }, '
        '{ parameter = "8-03", object = "2323:00", value = 1 }, { value = 1 }, '
        '{ parameter = "8-03", value = 1.0, size = 2 }]\n'
    )
    assert errors(tmp_path, PLC + CAN + "[canopen]\nnode_id = 1\n" + FC280 + sdo) == [
        (
            "canopen.node[0].sdo[0].parameter",
            "a parameter number is written g-nn, or g-nn[i] for an array element (got '8-3x')",
        ),
        ("canopen.node[0].sdo[1].parameter", "parameter 9-99 is not one the softplc FC 280 support knows"),
        (  # the parameter is known; its value is what is wrong
            "canopen.node[0].sdo[2].value",
            "8-03 Steuerwort Timeout-Zeit: 7000.0 s is raw 70000, outside 0..65535 (UInt16, conversion index -1)",
        ),
        ("canopen.node[0].sdo[3].parameter", "3-10 Festsollwert is an array: write one element, such as 3-10[0]"),
        ("canopen.node[0].sdo[4].parameter", "object or parameter, not both"),
        ("canopen.node[0].sdo[5]", 'required key missing: object (such as "2007:21") or parameter (such as "8-03")'),
        ("canopen.node[0].sdo[6].size", "only with object (a parameter's size is its device's)"),
    ]
    # found by the fuzz harness (tests/fuzz): inf (TOML has it) crashed the check with OverflowError;
    # the configuration's check of every value (config/errors.py not_finite) now names the value's key
    assert error(
        tmp_path, PLC + CAN + "[canopen]\nnode_id = 1\n" + FC280 + 'sdo = [{ parameter = "8-07", value = inf }]\n'
    ) == ("canopen.node[0].sdo[0].value", "expected an integer (got inf)")
    # an LTMR names no parameters by number
    assert error(tmp_path, plant("", 'sdo = [{ parameter = "8-03", value = 1 }]\n')) == (
        "canopen.node[0].sdo[0].parameter",
        "the node's EDS ('ltmr') is no registered device's that names its parameters: write the object "
        'instead (object = "index:subindex")',
    )


def test_an_fc280_on_the_factory_node_id_clashes_with_the_master(tmp_path):
    # both come with 127 (manual 003 §1.9, 10-02; canopen.node_id's default)
    text = PLC + CAN + "[canopen]\n" + FC280.replace("id = 40", "id = 127")
    assert error(tmp_path, text) == (
        "canopen.node[0].id",
        "127 is the master's own node id (canopen.node_id, 127 unless the file says): give the master another "
        "one (canopen.node_id = 1) or the node another (set its node-id parameter, and id here)",
    )
