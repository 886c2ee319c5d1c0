"""[[plaincan]] (runtime/io/plaincan/config.py) with a device that plugs in
through the seam (beacon.py): its keys, its bus, names, and the CAN-IDs
against other plain-CAN devices and CANopen nodes on the bus."""

from __future__ import annotations

from ...config.support import CAN, PLC, error, errors, load

BEACON = '[[plaincan]]\ntype = "beacon"\nnumber = 5\ninput = "%IW10"\n'
CANOPEN = '[canopen]\n[[canopen.node]]\nname = "drive"\nid = 5\neds = "fc280"\n'


def test_a_device_its_bus_and_its_default_name(tmp_path):
    cfg = load(tmp_path, PLC + CAN + BEACON)
    [node] = cfg.plaincan
    assert (node.type, node.name, node.key, node.bus) == ("beacon", "beacon5", "plaincan[0]", "can0")
    assert (node.options.number, node.options.input) == (5, "%IW10")
    assert cfg.warnings == []


def test_the_devices_keys_and_the_bus_are_checked(tmp_path):
    found = errors(
        tmp_path,
        PLC
        + CAN
        + '[[plaincan]]\ntype = "beacon"\nnumber = 16\ninput = "%IW10"\nbus = "can9"\n'
        + '[[plaincan]]\ntype = "lamp"\n',
    )
    assert found == [
        ("plaincan[0].number", "expected an integer from 1 to 15 (got 16)"),
        ("plaincan[0].bus", "expected one of 'can0', the [[can]] buses (got 'can9')"),
        ("plaincan[1].type", "expected one of 'mpu2s', 'beacon' (got 'lamp')"),
    ]
    assert error(tmp_path, PLC + BEACON) == (
        "plaincan[0]",
        "a [[plaincan]] device needs a [[can]] bus (the file has none): add a [[can]] table with interface and channel",
    )


def test_a_required_key_of_the_device_missing_is_an_error_not_a_crash(tmp_path):
    """Found by the fuzz harness (tests/fuzz): without its device's required
    key (the beacon's number, the MPU2-S's device), a [[plaincan]] table
    passed both passes and loading crashed with pydantic's ValidationError."""
    assert errors(tmp_path, PLC + CAN + '[[plaincan]]\ntype = "beacon"\ninput = "%IW10"\n') == [
        ("plaincan[0]", "required key missing: number (the beacon's number, 1 to 15)")
    ]
    assert errors(tmp_path, PLC + CAN + '[[plaincan]]\ntype = "mpu2s"\n') == [
        ("plaincan[0]", "required key missing: device (the device number (Gerätenummer), 1 to 30)")
    ]


def test_two_devices_on_one_id_or_one_name(tmp_path):
    assert errors(tmp_path, PLC + CAN + BEACON + BEACON) == [
        ("plaincan[1]", "duplicate device name 'beacon5' (plaincan[0] has it)"),
        ("plaincan[1]", "CAN-ID 0x185 on bus 'can0' is also plaincan[0] (beacon)'s"),
    ]


def test_an_id_of_a_canopen_node(tmp_path):
    # 0x185 is TPDO1 of node 5 in the predefined connection set (CiA 301)
    cfg = load(tmp_path, PLC + CAN + BEACON + CANOPEN)
    assert cfg.warnings == [
        f"{tmp_path / 'plant.toml'}: plaincan[0]: CAN-ID 0x185 on bus 'can0' is the default TPDO1 of CANopen node 5 "
        "(canopen.node[0]): if that PDO is valid in the node, it takes this device's frames; invalidate it or use "
        "another node id"
    ]
    mapped = CANOPEN + '[[canopen.node.tpdo]]\nnumber = 1\nmap = [{ object = "2643:00", address = "%IW20" }]\n'
    assert error(tmp_path, PLC + CAN + BEACON + mapped) == (
        "plaincan[0]",
        "CAN-ID 0x185 on bus 'can0' is TPDO1 of CANopen node 5 (canopen.node[0]): give the node another id or "
        "the device another number",
    )
