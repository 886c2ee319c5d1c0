"""The MPU2-S send telegram: the 69-word table of digest 004 §2.1, the bit
maps of §2.2, the decode vectors D1-D10 fed as frames, the cos φ table
(E4), the state bytes (E10), and the assembler's completeness and age."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.mpu2s import frames, telegram
from softplc.runtime.devices.mpu2s.telegram import (
    Coding,
    ControlRegister1,
    ControlRegister2,
    FaultClass,
    TelegramAssembler,
    double_bit,
)

S = 1_000_000_000  # ns


def feed(t: TelegramAssembler, frame: str, now_ns: int = 0) -> None:
    device, mux, words = frames.decode_telegram(0x321, bytes.fromhex(frame))
    assert device == 1
    t.feed(mux, words, now_ns)


def test_the_table_has_69_words_in_23_frames():
    assert len(telegram.WORD_TABLE) == 69
    for i, w in enumerate(telegram.WORD_TABLE):
        assert w.nr == i + 1
        assert w.nr == 3 * w.mux + w.word  # §2: Nr = 3·Mux + Wort
    assert {w.mux for w in telegram.WORD_TABLE} == set(range(23))
    assert len({w.key for w in telegram.WORD_TABLE}) == 69


@pytest.mark.parametrize(
    "nr, mux, word, german, unit",
    [
        (1, 0, 1, "Kennung", "1301"),
        (2, 0, 2, "Gen-Frequenz L1/L2", "1/100 Hz"),
        (3, 0, 3, "Gen-Wirkleistung", "(10^PGNEXPO) W"),
        (9, 2, 3, "Anliegende Fehlerklassen", "Doppelbits"),
        (10, 3, 1, "Interne Steuerregister 2", "Doppelbits"),
        (26, 8, 2, "Gen.-cosϕ", "1/100"),
        (32, 10, 2, "Sammelschienenfrequenz", "1/100 Hz"),
        (39, 12, 3, "Netzfrequenz aus L1 L2 L3", "1/100 Hz"),
        (45, 14, 3, "Betriebsstunden Highwort", "2^16 h"),
        (52, 17, 1, "Batteriespannung", "1/10 V"),
        (58, 19, 1, "Fehler DI's 1-8", "Doppelbits"),
        (68, 22, 2, "Analogeingang 8", "Skalierbar"),
        (69, 22, 3, "Intern", "Intern"),
    ],
)
def test_rows_of_section_2_1(nr, mux, word, german, unit):
    w = telegram.WORD_TABLE[nr - 1]
    assert (w.mux, w.word, w.german, w.unit) == (mux, word, german, unit)


def test_exponents_of_the_values():
    by_nr = {w.nr: w for w in telegram.WORD_TABLE}
    assert {nr for nr, w in by_nr.items() if w.exponent == "PGNEXPO"} == {3, 5, 25}  # 25: A5
    assert {nr for nr, w in by_nr.items() if w.exponent == "UGNEXPO"} == {15, 16, 17, 18, 19, 20}
    assert {nr for nr, w in by_nr.items() if w.exponent == "IGNEXPO"} == {22, 23, 24}  # A6
    assert {nr for nr, w in by_nr.items() if w.exponent == "UNTEXPO"} == {8, 34, 35, 36, 37, 38}
    assert {nr for nr, w in by_nr.items() if w.exponent == "USSEXPO"} == {7}
    # §2.1 summary: PGNEXPO/UGNEXPO Mux 1 W1 high/low, IGNEXPO Mux 10 W1 high,
    # UNTEXPO Mux 14 W1 low, USSEXPO Mux 14 W2 low
    assert telegram.EXPONENTS == {
        "PGNEXPO": (4, 8),
        "UGNEXPO": (4, 0),
        "IGNEXPO": (31, 8),
        "UNTEXPO": (43, 0),
        "USSEXPO": (44, 0),
    }


def test_signed_words_a4():
    signed = {w.nr for w in telegram.WORD_TABLE if w.signed}
    assert signed == {3, 5, 25, 26, *range(61, 69)}


def test_d1_d2_d3_power_frequency_and_generator_voltage():
    t = TelegramAssembler()
    feed(t, "DD 01 03 FF 00 96 0A F0")  # D2: PGNEXPO 3, UGNEXPO FFh = -1, P_set 150, PGNWWD 2800
    assert t.exponents == {"PGNEXPO": 3, "UGNEXPO": -1}
    assert t.value("p_set") == 150_000.0  # 150·(2800/2800)·10³ W (A7 literal)
    feed(t, "DD 00 05 15 13 88 00 C8")  # D1
    assert t.value("ident") == 1301 and t.value("ident") in telegram.IDENTS
    assert t.value("f_gen") == 50.0
    assert t.value("p_gen") == 200_000.0  # 200·10³ W = 200 kW
    feed(t, "DD 06 0F A0 0F A0 00 00")  # D3
    assert t.value("u_gen_l3n") == 400.0  # 4000·10⁻¹
    assert t.value("u_gen_l12") == 400.0


def test_d4_cos_phi_and_reactive_power():
    t = TelegramAssembler()
    feed(t, "DD 08 00 32 FF 9E 00 00")  # D4
    assert t.value("cos_phi") == -0.98  # capacitive
    assert t.value("q_gen") is None  # no exponent yet
    # D4 leaves Q's exponent open (A5); decided: PGNEXPO, here 3 -> 50·10³ var
    feed(t, "DD 01 03 FF 00 96 0A F0")
    assert t.value("q_gen") == 50_000.0


def test_d5_participants_and_states():
    t = TelegramAssembler()
    feed(t, "DD 09 00 00 00 01 FF FF")  # D5
    assert t.value("participants") == 1
    assert t.value("mains_present") is True and t.value("generator_present") is True


def test_d6_busbar_frequency_and_state():
    t = TelegramAssembler()
    feed(t, "DD 0A 00 00 13 92 FF 00")  # D6
    assert t.exponents == {"IGNEXPO": 0}
    assert t.value("f_bus") == 50.10
    assert t.value("busbar_present") is True
    feed(t, "DD 00 05 15 13 88 00 C8")  # with D1: df = 50.00 - 50.10 = -0.10 Hz
    assert round(t.value("f_gen") - t.value("f_bus"), 9) == -0.10


def test_d7_control_register_2():
    t = TelegramAssembler()
    feed(t, "DD 03 F0 30 00 00 00 00")  # D7: Nr 10 = F030h
    assert t.words[10] == 0xF030
    bits = telegram.decode_bits(10, t.words[10])
    assert bits == {
        "T3_GCB_RELEASE": True,
        "T5_GCB_CLOSED": True,
        "T4_BREAKER_OPEN": False,
        "T54_MAINS_PARALLEL": True,
        "T6_SYNC_ON": False,
    }
    assert double_bit(0xF030, ControlRegister2.T54_MAINS_PARALLEL) is True


def test_d8_busbar_and_mains_voltage_and_fault_class():
    t = TelegramAssembler()
    feed(t, "DD 0E 00 FF 00 FF 00 01")  # mux 14: UNTEXPO = USSEXPO = FFh = -1 (and D9's high word)
    feed(t, "DD 02 0F A0 0F A0 00 30")  # D8
    assert t.exponents == {"UNTEXPO": -1, "USSEXPO": -1}
    assert t.value("u_bus_l12") == 400.0 and t.value("u_mains_l12") == 400.0
    assert telegram.decode_bits(9, t.words[9]) == {"F3": False, "F2": True, "F1": False, "F0": False}


def test_d9_hours_and_d10_battery():
    t = TelegramAssembler()
    feed(t, "DD 0E 00 FF 00 FF 00 01")  # Nr 45 = 0001h
    assert t.value("hours") is None  # the low word has not come
    feed(t, "DD 0F 86 A0 00 00 00 00")  # Nr 46 = 86A0h
    assert t.value("hours") == 100_000  # 1·65536 + 34464 (D9)
    feed(t, "DD 11 00 F0 00 00 00 00")  # Nr 52 = 00F0h
    assert t.value("battery") == 24.0  # D10


@pytest.mark.parametrize(
    "word, value",
    [(0xFF9E, -0.98), (0xFF9D, -0.99), (0x0064, 1.00), (0x0063, 0.99), (0x0062, 0.98)],
)
def test_cos_phi_table_e4(word, value):
    t = TelegramAssembler()
    t.feed(8, (0, word, 0), 0)
    assert t.value("cos_phi") == value


@pytest.mark.parametrize("byte, present", [(0xFF, True), (0x00, False), (0x80, None), (0x01, None)])
def test_state_bytes_e10(byte, present):
    t = TelegramAssembler()
    t.feed(9, (0, 0, byte << 8 | byte), 0)
    t.feed(10, (0, 0, byte << 8), 0)
    assert t.value("mains_present") is present
    assert t.value("generator_present") is present
    assert t.value("busbar_present") is present


@pytest.mark.parametrize("pair, value", [(0b11, True), (0b00, False), (0b01, None), (0b10, None)])
def test_double_bits_a8(pair, value):
    for high in range(1, 16, 2):
        others = 0xFFFF & ~(0b11 << (high - 1))  # every other bit set: ignored
        assert double_bit(pair << (high - 1), high) is value
        assert double_bit(others | pair << (high - 1), high) is value


def test_double_bit_needs_an_odd_high_bit():
    for bad in (0, 2, 16, -1):
        with pytest.raises(ValueError):
            double_bit(0, bad)


def test_bit_maps_of_section_2_2():
    assert {m.name: m.value for m in FaultClass} == {"F3": 7, "F2": 5, "F1": 3, "F0": 1}
    assert {m.name: m.value for m in ControlRegister2} == {
        "T3_GCB_RELEASE": 15,
        "T5_GCB_CLOSED": 13,
        "T4_BREAKER_OPEN": 7,
        "T54_MAINS_PARALLEL": 5,
        "T6_SYNC_ON": 3,
    }
    assert {m.name: m.value for m in ControlRegister1} == {"ACK_F2_F3": 11, "ACK_F1": 9}
    assert telegram.Faults8.GEN_OVERFREQUENCY_2 == 15 and telegram.Faults8.REACTIVE_CAPACITIVE == 10
    assert telegram.Faults6.AI1_WIRE_BREAK == 0 and telegram.Faults6.AI8_WIRE_BREAK == 7
    assert telegram.Faults1.GEN_OVERFREQUENCY_1 == 15 and telegram.Faults1.REVERSE_POWER == 1
    assert telegram.Faults2.INTERFACE_X1_X5 == 7 and telegram.Faults2.PHASE_JUMP == 1
    assert telegram.Faults3.OVERCURRENT_1 == 15 and telegram.Faults3.MAINTENANCE_CALL == 3
    assert telegram.Faults4.AI1_STAGE_1 == 15 and telegram.Faults4.AI4_STAGE_2 == 1
    assert telegram.Faults5.AI5_STAGE_1 == 15 and telegram.Faults5.AI8_STAGE_2 == 1
    assert telegram.DiFaults1To8.DI1 == 15 and telegram.DiFaults1To8.DI8 == 1
    assert telegram.DiFaults9To16.DI9 == 15 and telegram.DiFaults9To16.DI16 == 1
    assert telegram.Faults7.EARTH_FAULT == 13 and telegram.Faults7.OVERCURRENT_IEC255 == 12
    # the words of §2.2 with bits, and their codings
    for nr, (_names, double) in telegram.BIT_WORDS.items():
        coding = telegram.WORD_TABLE[nr - 1].coding
        assert coding is (Coding.DOUBLE_BITS if double else Coding.BITS), nr
    assert sorted(telegram.BIT_WORDS) == [9, 10, 12, 13, 14, *range(53, 61)]


def test_single_bit_words():
    bits = telegram.decode_bits(60, 1 << 13)
    assert bits == {"EARTH_FAULT": True, "OVERCURRENT_IEC255": False}
    assert telegram.decode_bits(14, 0x0081)["AI8_WIRE_BREAK"] is True
    with pytest.raises(ValueError):
        telegram.decode_bits(11, 0)


def test_complete_and_stale():
    t = TelegramAssembler()
    assert not t.complete and t.stale(0, 10 * S)
    for mux in range(23):
        t.feed(mux, (0, 0, 0), mux * S // 10)  # about 100 ms apart (§1.1)
        assert t.complete == (mux == 22)
    now = 23 * S // 10
    assert not t.stale(now, 5 * S)
    assert t.age_ns(1, now) == now  # mux 0 came at 0
    assert t.age_ns(69, now) == now - 22 * S // 10
    assert t.stale(now + 3 * S, 5 * S)  # mux 0 is now 5.3 s old
    t.feed(0, (0, 0, 0), now + 3 * S)
    assert t.stale(now + 3 * S, 5 * S)  # mux 1 is 5.2 s old
    t.clear()
    assert not t.complete and t.age_ns(1, now) is None and t.words[1] is None


def test_values_before_anything_came():
    t = TelegramAssembler()
    values = t.values()
    assert set(values) == set(telegram.VALUE_KEYS)
    assert all(v is None for v in values.values())
    for key in ("f_gen", "f_bus", "f_mains", "u_gen_l12", "i_gen_l1", "p_gen", "q_gen", "cos_phi", "hours"):
        assert key in values
    for key in ("energy_kwh", "battery", "participants", "generator_present", "mains_present", "busbar_present"):
        assert key in values


def test_signed_values_and_unsigned_values():
    t = TelegramAssembler()
    t.feed(1, (0x00FE, 0, 0), 0)  # PGNEXPO 0, UGNEXPO -2
    t.feed(0, (0, 0, 0xFF9C), 0)  # P = -100 W
    t.feed(6, (0, 0xFFFF, 0), 0)  # U L1-L2 unsigned 65535·10⁻²
    assert t.value("p_gen") == -100.0
    assert t.value("u_gen_l12") == 655.35
    t.feed(20, (0xFFFF, 0, 0), 0)
    assert t.value("analog_1") == -1  # A4: analog inputs signed


def test_energy_is_high_and_low_word():
    t = TelegramAssembler()
    t.feed(16, (0, 0x0002, 0x0003), 0)
    assert t.value("energy_kwh") == 2 * 65536 + 3


def test_feed_checks_its_arguments():
    t = TelegramAssembler()
    with pytest.raises(ValueError):
        t.feed(23, (0, 0, 0), 0)
    with pytest.raises(ValueError):
        t.feed(0, (0, 0), 0)
    with pytest.raises(ValueError):
        t.feed(0, (0, 0, 0x10000), 0)
    with pytest.raises(KeyError):
        t.value("internal_11")
