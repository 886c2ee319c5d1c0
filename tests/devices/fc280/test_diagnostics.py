"""runtime/devices/fc280/diagnostics.py: the FC 280's EMCY (manual 003
§3.1.4, Tabellen 3.3/3.4, Tabelle 8.9) and its alarm and warning words
(Tabellen 8.1-8.4), with digest 003's vectors D29/D30."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.fc280 import diagnostics as d
from softplc.runtime.devices.fc280.diagnostics import EmcyFlags

# ---------------------------------------------------------------- EMCY


def test_d29_life_guard_error_of_node_5():
    # digest 003 D29: 085  30 81 01 01 xx xx xx xx
    emcy = d.decode_emcy(bytes.fromhex("3081010112345678"))
    assert emcy.code == 0x8130 == d.EMCY_LIFE_GUARD
    assert emcy.register == d.ERROR_REGISTER_GENERIC
    assert emcy.flags == EmcyFlags.ALARM_WORD
    assert emcy.alarm and not emcy.warning
    assert emcy.vendor == bytes.fromhex("12345678")  # undocumented, kept as they came (A5)
    assert emcy.text == "Life guard error or heartbeat error"
    assert emcy.cleared is False


def test_d30_all_zero_is_the_alarm_gone():
    # §3.1.4: "ein weiteres Notfalltelegramm mit dem Inhalt 0"
    emcy = d.decode_emcy(bytes(8))
    assert emcy.cleared is True
    assert (emcy.code, emcy.register, emcy.flags, emcy.text) == (0, 0, EmcyFlags(0), "No error")
    assert d.emcy_text(0, 0, bytes(5)) == "EMCY 0000h no error: the alarm is gone"


def test_a_short_frame_is_padded_and_a_long_one_refused():
    assert d.decode_emcy(bytes.fromhex("3081")).code == 0x8130
    assert d.decode_emcy(b"").cleared is True
    with pytest.raises(ValueError, match="8 bytes"):
        d.decode_emcy(bytes(9))


def test_code_zero_with_a_warning_flag_is_not_cleared():
    emcy = d.decode_emcy(bytes.fromhex("0000000800000000"))
    assert not emcy.cleared and emcy.warning and not emcy.alarm


@pytest.mark.parametrize(
    "bit, flag",
    [
        (0x01, EmcyFlags.ALARM_WORD),  # 16-90
        (0x02, EmcyFlags.ALARM_WORD_2),  # 16-91
        (0x04, EmcyFlags.ALARM_WORD_3),  # 16-97
        (0x08, EmcyFlags.WARNING_WORD),  # 16-92
        (0x10, EmcyFlags.WARNING_WORD_2),  # 16-93
    ],
)
def test_byte_3_flags_of_tabelle_3_4(bit, flag):
    emcy = d.decode_emcy(bytes([0x00, 0x10, 0x01, bit]))
    assert emcy.flags == flag
    assert emcy.alarm == (bit <= 0x04) and emcy.warning == (bit >= 0x08)


# Tabelle 8.9, every row: code -> text
TABELLE_8_9 = {
    0x0000: "No error",
    0x1000: "Generic error",
    0x2130: "Short circuit",
    0x2213: "Over-current at switch-on",
    0x2240: "Earth fault",  # printed "Kurzschluss" like 2130h: decided (A5)
    0x2310: "Continuous over-current",
    0x2311: "Current inside the device",
    0x3100: "Mains voltage",
    0x3130: "Phase failure",
    0x3210: "Over-voltage inside the device",
    0x3220: "Under-voltage inside the device",
    0x3300: "Output voltage",
    0x4210: "Excess device temperature",
    0x4310: "Excess drive temperature",
    0x5110: "Low supply voltage",
    0x5112: "24 V supply",
    0x5210: "Measurement circuit",
    0x6100: "Internal software error",
    0x7110: "Brake chopper",
    0x8100: "Communication",
    0x8110: "CAN overrun (objects lost)",
    0x8120: "CAN in error passive mode",
    0x8130: "Life guard error or heartbeat error",
    0x8140: "Recovered from bus off",
    0x8150: "COB-ID collision on transmit",
    0x8210: "PDO not processed due to length error",
    0x8220: "PDO length exceeded",
    0x8302: "Torque limited",
}


def test_every_code_of_tabelle_8_9():
    assert d.EMCY_CODES == TABELLE_8_9
    for code, text in TABELLE_8_9.items():
        assert d.decode_emcy(code.to_bytes(2, "little") + b"\x01\x01").text == text


@pytest.mark.parametrize("code", [0xFF00, 0xFF42, 0xFFFF])
def test_ffxx_is_manufacturer_specific(code):
    assert d.emcy_code_text(code) == "Manufacturer-specific"


@pytest.mark.parametrize("code", [0x1001, 0x8300, 0xFE00])
def test_other_codes_are_unknown(code):
    assert d.emcy_code_text(code) == "Unknown EMCY code"


def test_emcy_text_is_one_line_for_a_log():
    # D29 as the CANopen master keeps it: code, error register, bytes 3-7
    assert d.emcy_text(0x8130, 0x01, bytes.fromhex("0100000000")) == (
        "EMCY 8130h Life guard error or heartbeat error, error register 01h (generic error); active: alarm word 16-90"
    )
    assert d.emcy_text(0x8120, 0x00, bytes.fromhex("18DEADBEEF")) == (
        "EMCY 8120h CAN in error passive mode, error register 00h; "
        "active: warning word 16-92, warning word 2 16-93; vendor bytes DE AD BE EF"
    )
    assert d.emcy_text(0xFF01, 0x01, b"\xe1") == (
        "EMCY FF01h Manufacturer-specific, error register 01h (generic error); "
        "active: alarm word 16-90; reserved byte-3 bits E0h"
    )
    assert d.emcy_text(0x1000, 0x01) == "EMCY 1000h Generic error, error register 01h (generic error)"
    assert "\n" not in d.emcy_text(0x8130, 0xFF, bytes(range(1, 6)))


# ---------------------------------------------------------------- alarm and warning words


def test_alarm_word_16_90_every_bit_of_tabelle_8_1():
    assert len(d.ALARM_WORD) == 32
    assert d.alarm_texts(0x00000001) == ["Brake resistor test"]
    assert d.alarm_texts(0x00000010) == ["Control word timeout"]  # Steuerwort-Timeout
    assert d.alarm_texts(0x00400000) == ["Fieldbus fault"]  # Feldbus-Fehl.
    assert d.alarm_texts(0x20000000) == ["Drive initialised"]  # alarm 80 after 1011h restore
    assert d.alarm_texts(0x80000000) == ["Mechanical brake low"]
    assert d.alarm_texts(0xFFFFFFFF) == list(d.ALARM_WORD.values())


def test_several_bits_lowest_first_and_zero_none():
    assert d.alarm_texts(0x00400010) == ["Control word timeout", "Fieldbus fault"]
    assert d.alarm_texts(0) == [] and d.warning_texts(0) == []


def test_alarm_word_2_16_91_tabelle_8_2_and_its_reserved_bits():
    assert d.alarm2_texts(0x00000001) == ["Service trip, read/write"]
    assert d.alarm2_texts(0x00000800) == ["Speed limit"]
    assert d.alarm2_texts(0x80000000) == ["Dangerous failure"]
    assert d.alarm2_texts(0x00000002) == ["Reserved (00000002h)"]
    reserved = [1 << n for n in range(32) if (1 << n) not in d.ALARM_WORD_2]
    assert len(reserved) == 18  # 02h, 08h, 10h, 1000h-10000h, 100000h-20000000h
    assert 0x00001000 in reserved and 0x00010000 in reserved and 0x20000000 in reserved


def test_warning_word_16_92_every_bit_of_tabelle_8_3():
    assert len(d.WARNING_WORD) == 32
    assert d.warning_texts(0x00000010) == ["Control word timeout"]
    assert d.warning_texts(0x00001000) == ["DC-link voltage low"]
    assert d.warning_texts(0x00400000) == ["Fieldbus fault"]  # warning 34
    assert d.warning_texts(0x80000000) == ["Extended status word"]


def test_warning_word_2_16_93_tabelle_8_4():
    assert d.warning2_texts(0x00000001) == ["Start delayed"]
    assert d.warning2_texts(0x00040000) == ["Fan warning"]
    assert d.warning2_texts(0x40000000) == ["PTC thermistor"]
    assert d.warning2_texts(0x80000000) == ["Reserved (80000000h)"]  # reserved in 16-93, unlike 16-91
    assert len(d.WARNING_WORD_2) == 13


def test_every_table_has_single_bits_and_short_texts():
    for table in d.WORDS.values():
        for bit, text in table.items():
            assert bit & (bit - 1) == 0 and 0 < bit <= 0x80000000
            assert 0 < len(text) <= 80
    assert all(len(text) <= 80 for text in d.EMCY_CODES.values())
