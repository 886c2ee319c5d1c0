"""The request vectors V1-V19 of digest 004 §5.2, built byte for byte from
the parameter table (parameters.py) and the frame encoder (frames.py):
what a driver does to write a value in its unit."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.mpu2s import frames
from softplc.runtime.devices.mpu2s.codewords import RelayEvent
from softplc.runtime.devices.mpu2s.parameters import KWUGNSEK_ID, decode, encode, encode_words, merge, parameter


def write(device: int, key: str, value) -> bytes:
    p = parameter(key)
    return frames.write_request(device, p.id, encode(p, value))


VECTORS = [
    ("V1", lambda: frames.read_request(1, parameter("password").id), "FF 01 01 F4 00 00 FE F5"),
    ("V2", lambda: frames.read_request(1, KWUGNSEK_ID), "FF 01 01 FB 00 00 FE FA"),
    ("V3", lambda: frames.read_request(1, parameter("f_controller_on").id), "FF 01 00 13 00 00 FF 12"),
    ("V4", lambda: write(1, "password", 1234), "EE 01 01 F4 04 D2 EB 27"),
    ("V5", lambda: write(1, "gen_setpoint_frequency", 50.00), "EE 01 00 0B 32 00 DC 0A"),
    ("V6", lambda: write(3, "gen_setpoint_frequency", 50.00), "EE 03 00 0B 32 00 DC 08"),
    ("V8", lambda: write(1, "sync_df_max", 0.20), "EE 01 00 1A 00 33 EE 28"),
    ("V9", lambda: write(1, "sync_df_min", 0.10), "EE 01 00 1B 00 1A EE 00"),
    ("V10", lambda: write(1, "sync_du_max", 5.0), "EE 01 00 1C 00 C8 EE D5"),
    ("V11", lambda: write(1, "sync_du_min", 5.0), "EE 01 01 35 00 C8 EF FC"),
    ("V12", lambda: write(1, "sync_pulse", 0.20), "EE 01 00 1F 00 0A EE 14"),
    ("V13", lambda: write(1, "gcb_closing_time", 80), "EE 01 00 20 00 50 EE 71"),
    ("V14", lambda: write(1, "sync_time_monitoring_delay", 60), "EE 01 00 22 00 3C EE 1F"),
    ("V15", lambda: write(1, "power_setpoint_1", -100), "EE 01 00 45 FF 9C 11 D8"),
    ("V16", lambda: write(1, "pf_controller_setpoint", -0.95), "EE 01 00 0D FF A1 11 AD"),
]


@pytest.mark.parametrize("frame, expected", [pytest.param(f, e, id=name) for name, f, e in VECTORS])
def test_request_vectors(frame, expected):
    assert frame() == bytes.fromhex(expected)


def test_v7_read_reply():
    # device 1 answers ID 11 = 12800 = 50.00 Hz on 321h
    p = parameter("gen_setpoint_frequency")
    reply = frames.decode_reply(frames.device_can_id(1), bytes.fromhex("FF 01 00 0B 32 00 CD 0A"))
    assert (reply.kind, reply.device, reply.param_id) == (frames.KIND_READ, 1, p.id)
    assert decode(p, reply.raw) == 50.0


def test_v17_frequency_controller_alone():
    # ID 19 = C000h: only the frequency controller on, built from a word of zeros
    word = merge(parameter("f_controller_on"), 0x0000, True)
    assert frames.write_request(1, 19, word) == bytes.fromhex("EE 01 00 13 C0 00 2E 12")


def test_v18_all_controllers_and_black_start():
    # ID 19 = FF30h: f, P, U, cos φ controllers and black start on, bits 7..6 and 3..0 zero
    word = 0x0000
    for key in ("f_controller_on", "p_controller_on", "u_controller_on", "pf_controller_on", "black_start"):
        word = merge(parameter(key), word, True)
    assert frames.write_request(1, 19, word) == bytes.fromhex("EE 01 00 13 FF 30 11 22")


def test_v19_relay_1_gcb_closed():
    # relay 1 = event 68 "GLS EIN" alone, end of chain: 4404h to ID 436
    (param_id, word), *_ = encode_words(parameter("relay_1"), [RelayEvent(68, end=True)]).items()
    assert frames.write_request(1, param_id, word) == bytes.fromhex("EE 01 01 B4 44 04 AB B1")


# E9: the limit examples of the analog-output list (ch. 5, "Eingabe der beiden Grenzwerte"):
# source, the value at 0 % and at 100 % as printed (-0050 kW / 0200 kW ...)
E9 = [
    (1, -50, 200),  # generator active power, kW
    (2, -30, 30),  # cos phi: distance to 1.00, -0030 = 0.70 capacitive
    (3, 0, 7000),  # generator frequency, Hz*100: 7000 = 70.00 Hz
    (4, -100, 100),  # reactive power, kvar
    (7, 0, 500),  # current L1, A
    (10, 0, 3000),  # speed, 1/min
    (11, 0, 255),  # T1 temperature, 0255 = 255 degC
    (13, 0, 100),  # T3, 0100 = 10.0 bar oil pressure
    (19, -800, 800),  # mains active power, kW
]


@pytest.mark.parametrize("source, at_0, at_100", E9)
def test_e9_analog_output_limits(source, at_0, at_100):
    for n in (1, 2):
        src, lo, hi = (parameter(f"ao{n}_{key}") for key in ("source", "value_0", "value_100"))
        assert encode(src, source) == source
        # 4.2.154/155: words -9999..9999, the number as printed, negative in two's complement
        assert encode(lo, at_0) == at_0 & 0xFFFF and decode(lo, at_0 & 0xFFFF) == at_0
        assert encode(hi, at_100) == at_100 & 0xFFFF and decode(hi, at_100 & 0xFFFF) == at_100
    frame = frames.write_request(1, parameter("ao1_value_0").id, encode(parameter("ao1_value_0"), at_0))
    assert frame[:6] == bytes([0xEE, 0x01, 0x00, 193]) + (at_0 & 0xFFFF).to_bytes(2, "big")
