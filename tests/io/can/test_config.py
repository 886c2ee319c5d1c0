"""[[can]] buses and CAN nodes of simulated devices (runtime/io/can/config.py).

Numbers from the LTMR CANopen manual (001, English) where it sets them:
node ids 1..127 (L163), the bitrates (L183-205, 250 kBaud the factory
setting, L206)."""

from __future__ import annotations

import pytest

from softplc.runtime.config import SimConfig
from softplc.runtime.devices.ltmr.sim_options import LtmrPresets
from softplc.runtime.io.can import CanBusConfig, CanNode
from softplc.runtime.io.canopen.config import CanopenConfig, CanopenNodeConfig, PdoConfig, PdoEntryConfig

from ...config.support import CAN, CANOPEN_BITRATES, EDS, PLC, SIM, addr, error, errors, load, pdo, plant


def test_canopen_defaults(tmp_path):
    cfg = load(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IW0")), pdo("rpdo", 1, ("2008:05", "%QW0")), SIM))
    assert cfg.can == [CanBusConfig("can0", "virtual", "plant", 250_000, {}, "can[0]")]
    key = "canopen.node[0]"
    assert cfg.canopen == CanopenConfig(
        bus="can0",
        node_id=127,
        heartbeat_ms=100,
        sync_us=0,
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
                sdo=[],
                key=key,
                device="ltmr",
                tpdo=[
                    PdoConfig(
                        1,
                        255,
                        0,
                        0,
                        True,
                        [PdoEntryConfig(0x2004, 0x06, addr("%IW0"), f"{key}.tpdo[0].map[0]")],
                        f"{key}.tpdo[0]",
                    )
                ],
                rpdo=[
                    PdoConfig(
                        1,
                        255,
                        0,
                        0,
                        True,
                        [PdoEntryConfig(0x2008, 0x05, addr("%QW0"), f"{key}.rpdo[0].map[0]")],
                        f"{key}.rpdo[0]",
                    )
                ],
            )
        ],
    )
    assert cfg.sims == [SimConfig("ltmr", "ltmr40", "sim[0]", CanNode("can0", 40), LtmrPresets({}))]


def test_file_without_can_sections(tmp_path):
    cfg = load(tmp_path, PLC)
    assert (cfg.can, cfg.canopen, cfg.sims) == ([], None, [])


def test_can_buses(tmp_path):
    cfg = load(
        tmp_path,
        PLC + CAN + '[[can]]\nname = "Line2"\ninterface = "socketcan"\nchannel = 1\n'
        "bitrate = 1000000\noptions = { fd = false, receive_own_messages = true }\n"
        '[canopen]\nbus = "LINE2"\n'
        '[[sim]]\ntype = "ltmr"\nnode_id = 3\nbus = "can0"\n'
        '[[sim]]\ntype = "LTMR"\nname = "spare"\nnode_id = 3\nbus = "line2"\n',
    )
    assert cfg.can == [
        CanBusConfig("can0", "virtual", "plant", 250_000, {}, "can[0]"),
        CanBusConfig("Line2", "socketcan", "1", 1_000_000, {"fd": False, "receive_own_messages": True}, "can[1]"),
    ]
    # bus names are case-insensitive; the configuration carries the name as the [[can]] writes it
    assert cfg.canopen.bus == "Line2" and cfg.canopen.nodes == []
    assert [(s.name, s.at.bus, s.at.node_id) for s in cfg.sims] == [("ltmr3", "can0", 3), ("spare", "Line2", 3)]


@pytest.mark.parametrize("written, meant", [('"retry"', "retry"), ('"fail"', "fail"), ('"Fail"', "fail")])
def test_missing_adapter(tmp_path, written, meant):
    cfg = load(tmp_path, PLC + CAN + f"missing_adapter = {written}\n")
    assert cfg.can[0].missing_adapter == meant
    assert load(tmp_path, PLC + CAN).can[0].missing_adapter == "retry"  # a plant PC's adapter may come up late


@pytest.mark.parametrize(
    "written, got",
    [('"wait"', "'wait'"), ("true", "true"), ('"fial"', "'fial'; did you mean 'fail'?")],
)
def test_missing_adapter_takes_retry_or_fail(tmp_path, written, got):
    assert error(tmp_path, PLC + CAN + f"missing_adapter = {written}\n") == (
        "can[0].missing_adapter",
        f"expected one of 'retry', 'fail' (got {got})",
    )


@pytest.mark.parametrize("bitrate", CANOPEN_BITRATES)
def test_canopen_bitrates(tmp_path, bitrate):
    assert load(tmp_path, PLC + CAN + f"bitrate = {bitrate}\n").can[0].bitrate == bitrate


@pytest.mark.parametrize(
    "written, got", [("100000", "100000"), ('"250k"', "'250k'"), ("true", "true"), ("250000.0", "250000.0")]
)
def test_other_bitrates_are_refused(tmp_path, written, got):
    assert error(tmp_path, PLC + CAN + f"bitrate = {written}\n") == (
        "can[0].bitrate",
        "expected one of the CANopen bitrates 10000, 20000, 50000, 125000, 250000, 500000, "
        f"800000, 1000000 (got {got})",
    )


def test_can_required_keys_and_types(tmp_path):
    assert errors(tmp_path, PLC + '[[can]]\nname = "can0"\n') == [
        (
            "can[0].interface",
            'required key missing (expected a python-can interface such as "socketcan", "pcan" or "virtual")',
        ),
        ("can[0].channel", 'required key missing (expected a channel such as "can0" or "PCAN_USBBUS1")'),
    ]
    assert errors(
        tmp_path, PLC + '[[can]]\nname = "0can"\ninterface = " "\nchannel = true\noptions = 3\nbitrat = 1\n'
    ) == [
        (
            "can[0].name",
            "expected a bus name: an IEC identifier (letters, digits, _; not starting with a digit) (got '0can')",
        ),
        ("can[0].interface", 'expected a python-can interface such as "socketcan", "pcan" or "virtual" (got \' \')'),
        ("can[0].channel", 'expected a channel such as "can0" or "PCAN_USBBUS1" (got true)'),
        ("can[0].options", "expected a table of python-can options, such as { fd = false } (got 3)"),
        ("can[0].bitrat", "unknown key (did you mean 'bitrate'?)"),
    ]
    assert error(tmp_path, PLC + '[can]\ninterface = "virtual"\nchannel = "x"\n') == (
        "can",
        "expected [[can]] tables (got a table)",
    )


def test_duplicate_bus_names(tmp_path):
    assert error(tmp_path, PLC + CAN + '[[can]]\nname = "CAN0"\ninterface = "virtual"\nchannel = "b"\n') == (
        "can[1].name",
        "duplicate bus name 'CAN0' (can[0] has it; names are case-insensitive)",
    )
    assert error(tmp_path, PLC + CAN + CAN) == (
        "can[1]",
        "duplicate bus name 'can0' (the default; can[0] has it): give each [[can]] its own name",
    )


def test_canopen_and_sims_need_a_bus(tmp_path):
    assert errors(tmp_path, PLC + "[canopen]\n" + SIM) == [
        (
            "canopen",
            "the CANopen master needs a [[can]] bus (the file has none): add a [[can]] table with "
            "interface and channel",
        ),
        (
            "sim[0]",
            "a simulated device needs a [[can]] bus (the file has none): add a [[can]] table with "
            "interface and channel",
        ),
    ]


def test_several_buses_need_a_bus_key(tmp_path):
    two = CAN + '[[can]]\nname = "can1"\ninterface = "virtual"\nchannel = "b"\n'
    assert errors(tmp_path, PLC + two + "[canopen]\n" + SIM) == [
        ("canopen.bus", "required key missing: the file has several [[can]] buses (expected one of 'can0', 'can1')"),
        ("sim[0].bus", "required key missing: the file has several [[can]] buses (expected one of 'can0', 'can1')"),
    ]
    assert errors(tmp_path, PLC + two + '[canopen]\nbus = "can2"\n' + SIM + 'bus = "can_1"\n') == [
        ("canopen.bus", "expected one of 'can0', 'can1', the [[can]] buses (got 'can2')"),
        ("sim[0].bus", "expected one of 'can0', 'can1', the [[can]] buses (got 'can_1')"),
    ]
