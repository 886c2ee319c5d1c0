"""[[sim]] type = "fc280": its bus keys and its own, parameters = { ... } in
the parameters' units, checked in pass 2 with messages naming the key; the
simulator the device's factory builds from it."""

from __future__ import annotations

from softplc.runtime.devices.fc280 import DEVICE
from softplc.runtime.devices.fc280.options import Fc280Presets
from softplc.runtime.io.can import CanNode, CanSimContext

from ...config.support import CAN, PLC, error, errors, load

FC280 = '[[sim]]\ntype = "fc280"\nnode_id = 5\n'


def test_parameters_in_their_units_become_raw_values(tmp_path):
    cfg = load(tmp_path, PLC + CAN + FC280 + 'parameters = { "8-03" = 1.5, "10-01" = 21, "03-10" = [25.0, -12.5] }\n')
    sim = cfg.sims[0]
    assert (sim.type, sim.name, sim.at) == ("fc280", "fc2805", CanNode("can0", 5))
    # 8-03 conversion index -1: 1.5 s = 15; 3-10 index -2: 25 % = 2500 (Tabelle 6.2)
    assert sim.options == Fc280Presets({"8-03": 15, "10-01": 21, "3-10": [2500, -1250]})
    assert load(tmp_path, PLC + CAN + FC280).sims[0].options == Fc280Presets({})


def test_bad_parameters_are_named(tmp_path):
    text = (
        "parameters = { "
        '"8-3x" = 1, "9-99" = 1, "16-90" = 0, "8-03" = 0.0, "8-04" = 6, "8-10" = 5, '
        '"8-01" = [1], "3-10" = [1, 2, 3, 4, 5, 6, 7, 8, 9], "10-02" = 128 }\n'
    )
    found = errors(tmp_path, PLC + CAN + FC280 + text)
    assert found == [
        ("sim[0].parameters.8-3x", "expected an FC 280 parameter number such as \"8-03\" (got '8-3x')"),
        ("sim[0].parameters.9-99", "parameter 9-99 is not one the FC 280 simulator knows"),
        ("sim[0].parameters.16-90", "16-90 Alarmwort is a readout of the drive, not a setting"),
        ("sim[0].parameters.8-03", "8-03 Steuerwort Timeout-Zeit: 0.0 s is too low (8-03: 0 is below 1)"),
        ("sim[0].parameters.8-04", "8-04 Steuerwort Timeout-Funktion: 6 is too high (8-04: 6 is above 5)"),
        ("sim[0].parameters.8-10", "8-10 Steuerwortprofil: 5 is not an allowed value (8-10: 5 is none of [0, 7])"),
        ("sim[0].parameters.8-01", "8-01 Führungshoheit takes one value, not an array"),
        ("sim[0].parameters.3-10", "3-10 Festsollwert has 8 elements, not 9"),
        ("sim[0].parameters.10-02", "10-02 Node-ID: 128 is too high (10-02: 128 is above 127)"),
    ]
    assert error(tmp_path, PLC + CAN + FC280 + 'parameters = { "8-10" = 0.5 }\n') == (
        "sim[0].parameters.8-10",
        "8-10 Steuerwortprofil takes an option number such as 1 (got 0.5)",
    )
    assert error(tmp_path, PLC + CAN + FC280 + 'parameters = { "3-10" = 1.0 }\n') == (
        "sim[0].parameters.3-10",
        "3-10 Festsollwert takes an array of up to 8 values",
    )
    assert error(tmp_path, PLC + CAN + FC280 + 'parameters = { "8-03" = true }\n') == (
        "sim[0].parameters.8-03",
        "expected a number in the parameter's unit, or an array of numbers for an array parameter (got true)",
    )
    assert error(tmp_path, PLC + CAN + FC280 + 'parameters = { "8-03" = 100000.0 }\n')[1].startswith(
        "8-03 Steuerwort Timeout-Zeit: 100000.0 s is raw 1000000, outside 0..65535"
    )
    # found by the fuzz harness (tests/fuzz): inf or nan crashed the check (OverflowError, exit 4);
    # the configuration's check of every value (config/errors.py not_finite) names the key
    for value in ("inf", "-inf", "nan"):
        assert error(tmp_path, PLC + CAN + FC280 + f'parameters = {{ "3-41" = {value} }}\n') == (
            "sim[0].parameters.3-41",
            f"expected a finite number (got {value})",
        )


def test_the_ltmr_keys_are_not_the_fc280s(tmp_path):
    assert errors(tmp_path, PLC + CAN + FC280 + 'registers = { "682" = 2 }\n') == [
        ("sim[0].registers", "only for ltmr; type 'fc280' does not take it"),
        ("sim[0].registers", "only for da1, db1, dc1, de1, de11; type 'fc280' does not take it"),
    ]


def test_the_device_builds_its_simulator(tmp_path, bench):
    cfg = load(tmp_path, PLC + CAN + FC280 + 'name = "drive"\nparameters = { "8-04" = 2 }\n')
    sim = DEVICE.simulator(cfg.sims[0], CanSimContext(bench.settings, bench.clock, bench.pump))
    bench.add(sim)
    assert (sim.name, sim.node_id, sim.parameter("8-04")) == ("drive", 5, 2)
    assert bench.frames == [(0, 0x705, b"\x00")]
