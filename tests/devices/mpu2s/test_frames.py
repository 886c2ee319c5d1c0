"""MPU2-S frames: identifiers, checksum, requests, replies and telegram
frames, against the bytes of digest 004 (§1, E3, V1-V7, D1) and every way a
frame can be malformed."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from softplc.runtime.devices.mpu2s import frames
from softplc.runtime.devices.mpu2s.frames import MalformedFrame, Reply


def hexbytes(text: str) -> bytes:
    return bytes.fromhex(text)


def test_identifiers_and_kinds():
    # §1.2, §1.3: 320h + device number, 33Fh for requests; DD, FF, EE
    assert frames.TELEGRAM_ID_BASE == 0x320 and frames.REQUEST_ID == 0x33F
    assert (frames.KIND_TELEGRAM, frames.KIND_READ, frames.KIND_WRITE) == (0xDD, 0xFF, 0xEE)
    assert frames.device_can_id(1) == 0x321
    assert frames.device_can_id(30) == 0x33E  # §1.2: device 30 -> 33Eh
    assert frames.device_of(0x321) == 1


@pytest.mark.parametrize("device", [0, 31, -1, 255])
def test_device_numbers_are_1_to_30(device):
    # A9: 31 would send on 33Fh, the request ID
    with pytest.raises(ValueError, match="A9"):
        frames.device_can_id(device)
    with pytest.raises(ValueError):
        frames.read_request(device, 500)
    with pytest.raises(MalformedFrame):
        frames.device_of(0x320 + device)


def test_checksum_is_the_bytewise_xor_of_e3():
    # E3: Byte6 = B0^B2^B4, Byte7 = B1^B3^B5; V1 FF 01 01 F4 00 00 -> FE F5
    assert frames.checksum(hexbytes("FF 01 01 F4 00 00")) == hexbytes("FE F5")
    # the 16-bit form of E3: Wort1 ^ Wort2 ^ Wort3
    head = hexbytes("EE 01 00 0B 32 00")
    word = 0xEE01 ^ 0x000B ^ 0x3200
    assert frames.checksum(head) == word.to_bytes(2, "big")


@pytest.mark.parametrize(
    "device, param_id, expected",
    [
        (1, 500, "FF 01 01 F4 00 00 FE F5"),  # V1 read password ID 500
        (1, 507, "FF 01 01 FB 00 00 FE FA"),  # V2 read KWUGNSEK ID 507
        (1, 19, "FF 01 00 13 00 00 FF 12"),  # V3 read controller word ID 19
    ],
)
def test_read_requests_v1_to_v3(device, param_id, expected):
    assert frames.read_request(device, param_id) == hexbytes(expected)
    assert frames.decode_request(0x33F, hexbytes(expected)) == Reply(0xFF, device, param_id, 0)


@pytest.mark.parametrize(
    "device, param_id, raw, expected",
    [
        (1, 500, 0x04D2, "EE 01 01 F4 04 D2 EB 27"),  # V4 password 1234
        (1, 11, 0x3200, "EE 01 00 0B 32 00 DC 0A"),  # V5 12800 to ID 11
        (3, 11, 0x3200, "EE 03 00 0B 32 00 DC 08"),  # V6 the same to device 3
        (1, 69, 0xFF9C, "EE 01 00 45 FF 9C 11 D8"),  # V15 -100 kW as FF9Ch
    ],
)
def test_write_requests(device, param_id, raw, expected):
    assert frames.write_request(device, param_id, raw) == hexbytes(expected)
    assert frames.decode_request(0x33F, hexbytes(expected)) == Reply(0xEE, device, param_id, raw)


def test_read_reply_v7():
    # V7: device 1 answers ID 11 = 12800 on 321h
    data = hexbytes("FF 01 00 0B 32 00 CD 0A")
    assert frames.decode_reply(0x321, data) == Reply(kind=0xFF, device=1, param_id=11, raw=12800)
    assert frames.reply(frames.KIND_READ, 1, 11, 12800) == data


def test_write_reply_round_trip():
    data = frames.reply(frames.KIND_WRITE, 7, 26, 51)
    assert data[:6] == hexbytes("EE 07 00 1A 00 33")
    assert frames.decode_reply(0x327, data) == Reply(0xEE, 7, 26, 51)


def test_twos_complement():
    # §1.6, E4: FF9E = -98, FF9D = -99; V15 -100 = FF9C; V16 -95 = FFA1
    assert frames.to_word(-98) == 0xFF9E and frames.to_word(-99) == 0xFF9D
    assert frames.to_word(-100) == 0xFF9C and frames.to_word(-95) == 0xFFA1
    assert frames.to_word(100) == 0x0064 and frames.to_word(65000) == 65000
    assert frames.from_word(0xFF9E) == -98 and frames.from_word(0x0064) == 100
    for bad in (-0x8001, 0x10000):
        with pytest.raises(ValueError):
            frames.to_word(bad)


@given(st.integers(-0x8000, 0x7FFF))
def test_twos_complement_round_trip(value):
    assert frames.from_word(frames.to_word(value)) == value


def test_telegram_frame_d1():
    # D1: DD 00 05 15 13 88 00 C8 on 321h: mux 0, Kennung 0515h, f 1388h, P 00C8h
    data = hexbytes("DD 00 05 15 13 88 00 C8")
    assert frames.decode_telegram(0x321, data) == (1, 0, (0x0515, 0x1388, 0x00C8))
    assert frames.telegram_frame(0, (0x0515, 0x1388, 0x00C8)) == data


def test_telegram_mux_22_is_the_last():
    data = hexbytes("DD 16 00 01 00 02 00 03")
    assert frames.decode_telegram(0x33E, data) == (30, 22, (1, 2, 3))
    with pytest.raises(MalformedFrame, match="mux 23"):
        frames.decode_telegram(0x321, hexbytes("DD 17 00 01 00 02 00 03"))
    with pytest.raises(ValueError):
        frames.telegram_frame(23, (0, 0, 0))


@pytest.mark.parametrize(
    "can_id, data, why",
    [
        (0x321, "FF 01 00 0B 32 00 CD", "DLC 7"),
        (0x321, "FF 01 00 0B 32 00 CD 0A 00", "DLC 9"),
        (0x321, "FF 01 00 0B 32 00 CD 0B", "checksum"),
        (0x321, "FF 01 00 0B 32 01 CD 0A", "checksum"),
        (0x321, "AA 01 00 0B 32 00 37 0A", "byte 0 is AAh"),
        (0x321, "DD 01 00 0B 32 00 DD 0A", "byte 0 is DDh"),
        (0x322, "FF 01 00 0B 32 00 CD 0A", "device 1, the CAN-ID 322h device 2"),
        (0x33F, "FF 01 00 0B 32 00 CD 0A", "no MPU2-S device"),
        (0x320, "FF 00 00 0B 32 00 CD 0B", "no MPU2-S device"),
        (0x300, "FF 01 00 0B 32 00 CD 0A", "no MPU2-S device"),
    ],
)
def test_malformed_replies(can_id, data, why):
    with pytest.raises(MalformedFrame, match=why) as caught:
        frames.decode_reply(can_id, hexbytes(data))
    assert isinstance(caught.value, ValueError) and why.split()[0] in caught.value.reason


@pytest.mark.parametrize(
    "can_id, data, why",
    [
        (0x321, "DD 00 05 15 13 88 00", "DLC 7"),
        (0x321, "FF 00 05 15 13 88 00 C8", "byte 0 is FFh"),
        (0x321, "DD 17 05 15 13 88 00 C8", "mux 23"),
        (0x33F, "DD 00 05 15 13 88 00 C8", "no MPU2-S device"),
    ],
)
def test_malformed_telegram_frames(can_id, data, why):
    with pytest.raises(MalformedFrame, match=why):
        frames.decode_telegram(can_id, hexbytes(data))


@pytest.mark.parametrize(
    "can_id, data, why",
    [
        (0x321, "FF 01 01 F4 00 00 FE F5", "requests come on 33Fh"),
        (0x33F, "FF 1F 01 F4 00 00 FE EB", "device 31"),
        (0x33F, "FF 00 01 F4 00 00 FE F4", "device 0"),
        (0x33F, "FF 01 01 F4 00 00 FE F4", "checksum"),
    ],
)
def test_malformed_requests(can_id, data, why):
    with pytest.raises(MalformedFrame, match=why):
        frames.decode_request(can_id, hexbytes(data))


@given(
    st.integers(1, 30),
    st.sampled_from([frames.KIND_READ, frames.KIND_WRITE]),
    st.integers(0, 0xFFFF),
    st.integers(0, 0xFFFF),
)
def test_every_reply_decodes_to_what_was_encoded(device, kind, param_id, raw):
    data = frames.reply(kind, device, param_id, raw)
    assert len(data) == 8
    assert frames.decode_reply(frames.device_can_id(device), data) == Reply(kind, device, param_id, raw)


@given(st.integers(1, 30), st.integers(0, 0xFFFF), st.integers(0, 0xFFFF), st.integers(0, 7), st.integers(0, 7))
def test_any_single_bit_error_in_the_data_is_caught(device, param_id, raw, byte, bit):
    data = bytearray(frames.reply(frames.KIND_WRITE, device, param_id, raw))
    data[byte] ^= 1 << bit  # byte 1 is checked twice: the checksum and the CAN-ID's device
    with pytest.raises(MalformedFrame):
        frames.decode_reply(frames.device_can_id(device), bytes(data))


def test_range_checks_of_the_encoders():
    with pytest.raises(ValueError):
        frames.write_request(1, 11, 0x10000)
    with pytest.raises(ValueError):
        frames.write_request(1, 11, -1)  # a signed value goes through to_word()
    with pytest.raises(ValueError):
        frames.read_request(1, 0x10000)
    with pytest.raises(ValueError):
        frames.reply(frames.KIND_TELEGRAM, 1, 11, 0)
