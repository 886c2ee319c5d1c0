"""A [[plaincan]] table of type "mpu2s" (runtime/devices/mpu2s/node.py,
Mpu2sOptions): its keys, the 69 telegram words in %I, and its CAN-IDs
(digest 004 §1.2: 320h + device number, requests on 33Fh) against the
CANopen nodes on the same bus."""

from __future__ import annotations

from ...config.support import CAN, PLC, errors, load

MPU2S = '[[plaincan]]\ntype = "mpu2s"\ndevice = 1\ntelegram = "%IW300"\npassword = 1234\n'


def test_a_device_with_its_defaults(tmp_path):
    cfg = load(tmp_path, PLC + CAN + MPU2S)
    [node] = cfg.plaincan
    s = node.options
    assert (node.name, node.bus) == ("mpu2s_1", "can0")
    assert (s.device, s.telegram, s.password) == (1, "%IW300", 1234)
    # a reply within three message slots of 100 ms (§1.1, §1.7), two retries, frames 100 ms apart
    assert (s.timeout_ms, s.retries, s.pace_ms, s.stale_ms, s.variant) == (300, 2, 100, 1000, None)


def test_its_keys_are_checked(tmp_path):
    bad = (
        '[[plaincan]]\ntype = "mpu2s"\ndevice = 31\npassword = 10000\nvariant = 230\ntimeout = "soon"\n'
        '[[plaincan]]\ntype = "mpu2s"\ndevice = 2\ntelegram = "%QW300"\n'
        '[[plaincan]]\ntype = "mpu2s"\ndevice = 3\ntelegram = "%IW32700"\n'
    )
    found = errors(tmp_path, PLC + CAN + bad)
    assert ("plaincan[0].device", "expected an integer from 1 to 30 (got 31)") in found
    assert ("plaincan[0].password", "expected an integer from 0 to 9999 (got 10000)") in found
    assert ("plaincan[0].variant", "expected 100 or 400 (got 230)") in found
    assert any(key == "plaincan[0].timeout" for key, _ in found)
    assert ("plaincan[1].telegram", "expected the first input word of the 69, such as %IW300 (got '%QW300')") in found
    assert any(key == "plaincan[2].telegram" and "do not fit" in message for key, message in found)


def test_the_telegram_words_are_claimed(tmp_path):
    other = '[[plaincan]]\ntype = "mpu2s"\ndevice = 2\ntelegram = "%IW360"\n'
    found = errors(tmp_path, PLC + CAN + MPU2S + other)
    assert len(found) == 1 and found[0][0] == "plaincan[1].telegram"
    assert "overlap %IW300 and the 68 words after it" in found[0][1]


def test_its_ids_against_canopen_rpdo2_of_node_33(tmp_path):
    # device 1 sends on 321h, the default RPDO2 of CANopen node 33 (0x300 + 33)
    canopen = '[canopen]\n[[canopen.node]]\nname = "drive"\nid = 33\neds = "fc280"\n'
    cfg = load(tmp_path, PLC + CAN + MPU2S + canopen)
    [warning] = cfg.warnings
    assert "CAN-ID 0x321 on bus 'can0' is the default RPDO2 of CANopen node 33" in warning
