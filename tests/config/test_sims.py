"""[[sim]] (runtime/config/sims.py): simulated devices, their names and
registers, on a CAN bus (the Modbus ones: tests/io/modbus/test_config.py)."""

from __future__ import annotations

import pytest

from softplc.runtime.config import ConfigError, SimConfig, load_config
from softplc.runtime.devices.ltmr.sim_options import LtmrPresets
from softplc.runtime.io.can import CanNode

from .support import CAN, NODE, PLC, SIM, error, errors, load, pdo, plant, write

# ---------------------------------------------------------------- [[sim]]


def test_sims(tmp_path):
    cfg = load(
        tmp_path,
        PLC + CAN + '[[sim]]\ntype = "LTMR"\nnode_id = 40\n'
        'registers = { "682" = 2, "0652" = 50 }\n'
        '[[sim]]\ntype = "ltmr"\nname = "spare"\nbus = "can0"\nnode_id = 41\nload = 120\n',
    )
    assert cfg.sims == [
        SimConfig("ltmr", "ltmr40", "sim[0]", CanNode("can0", 40), LtmrPresets({682: 2, 652: 50}, 80.0)),
        SimConfig("ltmr", "spare", "sim[1]", CanNode("can0", 41), LtmrPresets({}, 120.0)),
    ]
    assert cfg.canopen is None  # a simulator needs no master in this PLC


def test_sim_is_the_canopen_node(tmp_path):
    """A simulator may have the node id of a [[canopen.node]]: it is that node."""
    cfg = load(tmp_path, plant("", "", SIM))
    assert cfg.sims[0].at.node_id == cfg.canopen.nodes[0].node_id == 40


def test_sim_node_ids(tmp_path):
    other = '[[can]]\nname = "can1"\ninterface = "virtual"\nchannel = "b"\n'
    assert error(tmp_path, PLC + CAN + SIM + SIM + 'name = "second"\n') == (
        "sim[1].node_id",
        "duplicate node id 40 on bus 'can0' (sim[0] has it)",
    )
    cfg = load(tmp_path, PLC + CAN + other + SIM + 'bus = "can0"\n' + SIM + 'bus = "can1"\nname = "other"\n')
    assert [(s.at.bus, s.at.node_id) for s in cfg.sims] == [("can0", 40), ("can1", 40)]
    assert error(tmp_path, plant("", "", SIM.replace("40", "127"))) == (
        "sim[0].node_id",
        "127 is the CANopen master's own node id on bus 'can0' (canopen.node_id)",
    )
    assert errors(tmp_path, PLC + CAN + '[[sim]]\ntype = "fc281"\nnode_id = 0\n[[sim]]\nnode_id = 2\n') == [
        (
            "sim[0].type",
            "expected one of 'ltmr', 'da1', 'db1', 'dc1', 'de1', 'de11', 'fc280', 'mpu2s' "
            "(got 'fc281'; did you mean 'fc280'?)",
        ),
        ("sim[0].node_id", "expected an integer from 1 to 127 (got 0)"),
        (
            "sim[1].type",
            "required key missing (expected 'ltmr', 'da1', 'db1', 'dc1', 'de1', 'de11', 'fc280' or 'mpu2s')",
        ),
    ]


def test_sim_names(tmp_path):
    other = '[[can]]\nname = "can1"\ninterface = "virtual"\nchannel = "b"\n'
    assert error(tmp_path, PLC + CAN + other + SIM + 'bus = "can0"\n' + SIM + 'bus = "can1"\n') == (
        "sim[1]",
        "duplicate simulator name 'ltmr40', the default <type><node_id> (sim[0] has it): give one a name",
    )
    assert error(tmp_path, PLC + CAN + SIM + 'name = "A"\n' + SIM.replace("40", "41") + 'name = "a"\n') == (
        "sim[1].name",
        "duplicate simulator name 'a' (sim[0] has it; names are case-insensitive)",
    )
    assert error(tmp_path, PLC + CAN + SIM + 'name = "ltmr 40"\n') == (
        "sim[0].name",
        "expected a simulator name: an IEC identifier (letters, digits, _; not starting with a digit) (got 'ltmr 40')",
    )


def test_sim_registers(tmp_path):
    assert errors(
        tmp_path, PLC + CAN + SIM + 'registers = { "682" = 70000, "abc" = 1, "70000" = 1, "7" = -1, "8" = true }\n'
    ) == [
        ("sim[0].registers.682", "expected an integer from 0 to 65535 (got 70000)"),
        ("sim[0].registers.7", "expected an integer from 0 to 65535 (got -1)"),
        ("sim[0].registers.8", "expected an integer from 0 to 65535 (got true)"),
        ("sim[0].registers.abc", "expected a register number from 0 to 65535 in decimal, such as \"682\" (got 'abc')"),
        (
            "sim[0].registers.70000",
            "expected a register number from 0 to 65535 in decimal, such as \"682\" (got '70000')",
        ),
    ]
    assert error(tmp_path, PLC + CAN + SIM + "registers = [682, 2]\n") == (
        "sim[0].registers",
        'expected a table of register = value, such as { "682" = 2 } (got an array)',
    )


def test_can_sections_errors_reported_together(tmp_path):
    path = write(
        tmp_path,
        PLC + '[[can]]\ninterface = "virtual"\nchannel = "a"\nbitrate = 1\n'
        '[canopen]\nnode_id = 40\nheartbeat = "0ms"\n'
        + NODE
        + 'master_timeout = "1s"\n'
        + pdo("tpdo", 1, ("2004:06", "%QW0"), ("20x4:06", "%IW0"))
        + SIM.replace("40", "0"),
    )
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert str(info.value).splitlines() == [
        f"{path}: can[0].bitrate: expected one of the CANopen bitrates 10000, 20000, 50000, 125000, 250000, "
        "500000, 800000, 1000000 (got 1)",
        f"{path}: canopen.node[0].id: 40 is the master's own node id (canopen.node_id): give the master another "
        "one (canopen.node_id = 1) or the node another (set its node-id parameter, and id here)",
        f"{path}: canopen.node[0].master_timeout: only meaningful when the master sends a heartbeat "
        "(canopen.heartbeat = '0ms')",
        f"{path}: canopen.node[0].tpdo[0].map[0].address: expected a %I address: a TPDO's entries go to %I "
        "inputs (got '%QW0', an output)",
        f'{path}: canopen.node[0].tpdo[0].map[1].object: expected an object "index:subindex" in hex, such as '
        "\"2004:06\" (got '20x4:06')",
        f"{path}: sim[0].node_id: expected an integer from 1 to 127 (got 0)",
    ]
