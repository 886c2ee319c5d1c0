"""The MPU2-S's frames as `softplc log` prints them (devices/mpu2s/words.py):
frames.py's worked examples of manual 004 §1.3-1.5 (a read of ID 500, a
write of 12800 = 50.00 Hz to ID 11), a telegram frame of ch. 3, and the
genset example's wire recorded with --bus-log."""

from __future__ import annotations

from types import SimpleNamespace

from softplc.runtime.devices.mpu2s import frames
from softplc.runtime.devices.mpu2s.words import frame_text

from ...test_cli import softplc

DEVICE_1 = SimpleNamespace(device=1)


def test_requests_on_33f_name_the_parameter():
    assert frame_text(DEVICE_1, frames.REQUEST_ID, frames.read_request(1, 500)) == (
        "read ID 500 Password for code level 2"
    )
    assert frames.write_request(1, 11, 12800) == bytes.fromhex("EE 01 00 0B 32 00 DC 0A")
    assert frame_text(DEVICE_1, frames.REQUEST_ID, frames.write_request(1, 11, 12800)) == (
        "write ID 11 Generator set-point frequency = 12800"
    )


def test_another_device_s_frames_are_not_its():
    assert frame_text(DEVICE_1, frames.REQUEST_ID, frames.read_request(2, 500)) is None
    assert frame_text(DEVICE_1, frames.device_can_id(2), frames.reply(frames.KIND_READ, 2, 26, 51)) is None


def test_replies_and_telegram_frames_on_320h_plus_the_device():
    reply = frames.reply(frames.KIND_READ, 1, 26, 51)
    assert frame_text(DEVICE_1, 0x321, reply) == "read ID 26 Synchronising +df max = 51"
    telegram = frames.telegram_frame(0, (1301, 5030, 0))  # Nr 1 identifier, Nr 2 f_gen in 1/100 Hz
    assert frame_text(DEVICE_1, 0x321, telegram) == (
        "telegram mux 0: Nr 1 identifier (telegram type) = 1301 | Nr 2 generator frequency L1/L2 = 5030 (50.30 Hz)"
        " | Nr 3 generator active power = 0"
    )


def test_a_malformed_reply_says_why():
    bad = bytearray(frames.reply(frames.KIND_READ, 1, 26, 51))
    bad[7] ^= 0xFF
    assert frame_text(DEVICE_1, 0x321, bytes(bad)).startswith("malformed reply: ")


def test_the_genset_example_s_wire_in_words(tmp_path):
    from softplc.runtime.config import default_config_path

    config = default_config_path().parent / "examples" / "genset.toml"
    done = softplc("run", config, "--virtual-time", "--duration", "1s", "--bus-log", tmp_path / "gs.log", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    done = softplc("log", tmp_path / "gs.log", config)
    assert done.returncode == 0, done.stderr
    assert "Rx 321 [8] DD 00 05 15" in done.stdout  # the identifier 1301 = 0515h first
    assert "mpu2s_1: telegram mux 0: Nr 1 identifier (telegram type) = 1301" in done.stdout
    assert "mpu2s_1: read ID 26 Synchronising +df max" in done.stdout
