"""Simulated devices ([[sim]]) on a [[modbus]] line (runtime/io/modbus/config.py,
runtime/config/sims.py): their unit, their connection, their names and
registers, and the keys of the other bus."""

from __future__ import annotations

import pytest

from softplc.runtime.config import ConfigError, SimConfig, load_config
from softplc.runtime.devices.ltmr.sim_options import LtmrPresets
from softplc.runtime.io.can import CanNode
from softplc.runtime.io.modbus import ModbusUnit
from softplc.runtime.sim.options import Registers

from ...config.support import CAN, PLC, SIM, error, errors, load, write
from .config_support import DA1, ONLY_CAN, READ, RTU, TCP, channel


def test_modbus_sims(tmp_path):
    cfg = load(
        tmp_path,
        PLC
        + CAN
        + SIM
        + RTU
        + TCP.replace('"tcp"\n', '"tcp"\nhost = "localhost"\nport = 0\n')
        + '[[sim]]\ntype = "DA1"\nmodbus = "DRIVES"\nunit = 1\nregisters = { "505" = 20, "0017" = 3 }\n'
        + '[[sim]]\ntype = "de11"\nname = "pump"\nmodbus = "gateway"\nunit = 247\n'
        + '[[sim]]\ntype = "db1"\nmodbus = "gateway"\nunit = 1\n',
    )
    assert cfg.sims == [
        SimConfig("ltmr", "ltmr40", "sim[0]", CanNode("can0", 40), LtmrPresets({})),
        SimConfig("da1", "da1_1", "sim[1]", ModbusUnit("drives", 1), Registers({505: 20, 17: 3})),
        SimConfig("de11", "pump", "sim[2]", ModbusUnit("gateway", 247), Registers({})),
        SimConfig("db1", "db1_1", "sim[3]", ModbusUnit("gateway", 1), Registers({})),
    ]


def test_modbus_sim_on_the_only_connection(tmp_path):
    """Without modbus, a drive is on the file's only [[modbus]] connection."""
    cfg = load(tmp_path, PLC + '[[modbus]]\ntransport = "rtu"\ndevice = "sim"\n' + DA1)
    assert cfg.sims == [SimConfig("da1", "da1_1", "sim[0]", ModbusUnit("modbus0", 1), Registers({}))]
    cfg = load(tmp_path, PLC + TCP + DA1)  # host defaults to 127.0.0.1
    assert (cfg.sims[0].at.connection, cfg.sims[0].at.unit) == ("gateway", 1)


def test_modbus_sim_needs_a_unit(tmp_path):
    assert error(tmp_path, PLC + RTU + '[[sim]]\ntype = "da1"\n') == (
        "sim[0]",
        "required key missing: unit (the drive's Modbus address)",
    )
    assert error(tmp_path, PLC + RTU + '[[sim]]\ntype = "da1"\nunit = 0\n') == (
        "sim[0].unit",
        "expected an integer from 1 to 247 (got 0)",
    )


def test_modbus_sim_refuses_can_keys(tmp_path):
    assert error(tmp_path, PLC + RTU + DA1 + "node_id = 3\n") == ("sim[0].node_id", ONLY_CAN)
    assert errors(tmp_path, PLC + CAN + RTU + DA1 + 'bus = "can0"\nnode_id = 3\n') == [
        ("sim[0].bus", ONLY_CAN),
        ("sim[0].node_id", ONLY_CAN),
    ]


def test_can_sim_refuses_modbus_keys(tmp_path):
    only_modbus = "only for a Modbus device (da1, db1, dc1, de1, de11); a CAN device has bus and node_id"
    assert errors(tmp_path, PLC + CAN + RTU + SIM + 'modbus = "drives"\nunit = 1\n') == [
        ("sim[0].modbus", only_modbus),
        ("sim[0].unit", only_modbus),
    ]


def test_modbus_sim_needs_a_simulated_line(tmp_path):
    assert error(tmp_path, PLC + RTU.replace('"sim"', '"/dev/ttyUSB0"') + DA1) == (
        "sim[0].modbus",
        'modbus[0] is a serial line to real devices; a simulated drive needs device = "sim" there',
    )
    assert error(tmp_path, PLC + TCP + 'host = "192.168.0.20"\n' + DA1) == (
        "sim[0].modbus",
        "modbus[0] goes to 192.168.0.20; a simulated drive listens on 127.0.0.1 only",
    )


def test_modbus_sim_units(tmp_path):
    assert error(tmp_path, PLC + RTU + DA1 + '[[sim]]\ntype = "dc1"\nunit = 1\n') == (
        "sim[1].unit",
        "duplicate unit 1 on modbus[0] (sim[0] has it)",
    )
    # one unit per connection: the same unit on another connection is another drive
    cfg = load(tmp_path, PLC + RTU + TCP + DA1 + 'modbus = "drives"\n' + DA1 + 'modbus = "gateway"\nname = "b"\n')
    assert [(s.name, s.at.connection, s.at.unit) for s in cfg.sims] == [("da1_1", "drives", 1), ("b", "gateway", 1)]


def test_modbus_sim_connection(tmp_path):
    assert error(tmp_path, PLC + RTU + TCP + DA1 + 'modbus = "pumps"\n') == (
        "sim[0].modbus",
        "expected one of 'drives', 'gateway', the [[modbus]] connections (got 'pumps')",
    )
    assert error(tmp_path, PLC + DA1) == (
        "sim[0]",
        "a simulated drive needs a [[modbus]] connection (the file has none)",
    )
    assert error(tmp_path, PLC + RTU + TCP + DA1) == (
        "sim[0]",
        "required key missing: modbus (the [[modbus]] connection the drive is on)",
    )
    assert errors(tmp_path, PLC + CAN + DA1 + 'bus = "can0"\n') == [  # a [[can]] bus is no home for a drive
        ("sim[0].bus", ONLY_CAN),
        ("sim[0]", "a simulated drive needs a [[modbus]] connection (the file has none)"),
    ]
    assert error(tmp_path, PLC + RTU + DA1 + 'modbus = "2drives"\n') == (
        "sim[0].modbus",
        "expected a connection name: an IEC identifier (letters, digits, _; not starting with a digit) (got '2drives')",
    )


def test_modbus_sim_names(tmp_path):
    assert error(tmp_path, PLC + RTU + TCP + DA1 + 'modbus = "drives"\n' + DA1 + 'modbus = "gateway"\n') == (
        "sim[1]",
        "duplicate simulator name 'da1_1', the default <type>_<unit> (sim[0] has it): give one a name",
    )
    assert error(tmp_path, PLC + CAN + SIM + RTU + DA1 + 'name = "LTMR40"\n') == (
        "sim[1].name",
        "duplicate simulator name 'LTMR40' (sim[0] has it; names are case-insensitive)",
    )
    cfg = load(tmp_path, PLC + RTU + DA1 + '[[sim]]\ntype = "da1"\nunit = 2\n')
    assert [s.name for s in cfg.sims] == ["da1_1", "da1_2"]


def test_modbus_sim_registers(tmp_path):
    assert errors(tmp_path, PLC + RTU + DA1 + 'registers = { "505" = 70000, "abc" = 1, "70000" = 1 }\n') == [
        ("sim[0].registers.505", "expected an integer from 0 to 65535 (got 70000)"),
        ("sim[0].registers.abc", "expected a register number from 0 to 65535 in decimal, such as \"682\" (got 'abc')"),
        (
            "sim[0].registers.70000",
            "expected a register number from 0 to 65535 in decimal, such as \"682\" (got '70000')",
        ),
    ]


def test_modbus_errors_reported_together(tmp_path):
    path = write(
        tmp_path,
        PLC
        + DA1
        + 'bus = "can0"\n'
        + '[[modbus]]\nname = "drives"\ntransport = "rtu"\ndevice = "sim"\nbaud = 12345\n'
        + READ
        + 'trigger = "change"\n'
        + channel(6, 'write_from = "%IW0"\n')
        + TCP
        + 'device = "sim"\n',
    )
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert str(info.value).splitlines() == [
        f"{path}: sim[0].bus: {ONLY_CAN}",
        f"{path}: sim[0]: required key missing: modbus (the [[modbus]] connection the drive is on)",
        f"{path}: modbus[0].baud: expected one of 1200, 2400, 4800, 9600, 19200, 38400, 57600, 115200 (got 12345)",
        f"{path}: modbus[0].channel[0].trigger: 'change' watches the data to write; function 3 only reads "
        "(use 'cyclic' or 'edge')",
        f"{path}: modbus[0].channel[1].write_from: expected an address in %Q or %M (got '%IW0', an input)",
        f"{path}: modbus[1].device: only for transport = 'rtu' (this connection is 'tcp')",
    ]
