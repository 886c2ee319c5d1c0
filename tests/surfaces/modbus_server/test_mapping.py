"""OpenPLC's mapping of the four Modbus tables onto the process image, and
the [modbus_server] keys."""

from __future__ import annotations

import pytest

from softplc.runtime.image.memory import ProcessImage
from softplc.runtime.surfaces.modbus_server.mapping import (
    COILS,
    DISCRETE_INPUTS,
    HOLDING_REGISTERS,
    INPUT_REGISTERS,
    Mapping,
    OutOfRange,
)

from ...config.support import PLC, error, load


@pytest.mark.parametrize("addressing", ["iec", "schneider"])
def test_registers_and_bits_are_the_image_words_and_bits_in_either_addressing(addressing):
    image = ProcessImage(addressing)
    image.write("%QW3", 0x1234)
    image.write("%MW0", 7)
    image.write("%MW32767", 65535)
    image.write("%IW1", 0xBEEF)
    image.write("%QX0.3", True)
    image.write("%QX1.0", True)
    image.write("%IX8191.7", True)
    snap = {area: bytes(data) for area, data in image.areas.items()}
    m = Mapping(image.size)
    assert m.read(snap, HOLDING_REGISTERS, 2, 3) == [0, 0x1234, 0]
    assert m.read(snap, HOLDING_REGISTERS, 1023, 2) == [0, 7]  # %QW1023, then %MW0
    assert m.read(snap, HOLDING_REGISTERS, 1024 + 32767, 1) == [65535]
    assert m.read(snap, INPUT_REGISTERS, 1, 1) == [0xBEEF]
    assert m.read(snap, COILS, 0, 10) == [False, False, False, True, False, False, False, False, True, False]
    assert m.read(snap, DISCRETE_INPUTS, 65535, 1) == [True]


def test_writes_go_to_the_addresses_access_writes():
    m = Mapping(1 << 16)
    assert m.paths(COILS, 7, 3) == ["%QX0.7", "%QX1.0", "%QX1.1"]
    assert m.paths(HOLDING_REGISTERS, 1022, 4) == ["%QW1022", "%QW1023", "%MW0", "%MW1"]
    assert m.paths(DISCRETE_INPUTS, 10, 1) == ["%IX1.2"]


def test_an_address_past_a_table_names_the_table_and_its_range():
    m = Mapping(1 << 16)
    with pytest.raises(OutOfRange, match=r"holding registers 33791\.\.33792: outside 0\.\.1023 \(%QW\), 1024\.\.33791"):
        m.segments(HOLDING_REGISTERS, 33791, 2)
    with pytest.raises(OutOfRange, match=r"input registers 32768: outside 0\.\.32767 \(%IW\)"):
        m.segments(INPUT_REGISTERS, 32768, 1)
    small = Mapping(256)  # a 256-byte image: 128 words an area
    assert small.ranges() == {
        COILS: "0..2047 (%QX)",
        DISCRETE_INPUTS: "0..2047 (%IX)",
        INPUT_REGISTERS: "0..127 (%IW)",
        HOLDING_REGISTERS: "0..127 (%QW), 1024..1151 (%MW)",
    }
    with pytest.raises(OutOfRange):
        small.segments(HOLDING_REGISTERS, 127, 2)  # %QW128 is past the area


def test_the_unit_key_defaults_to_any_and_takes_a_modbus_unit_id(tmp_path):
    assert load(tmp_path, PLC + "[modbus_server]\n").sections["modbus_server"].options == {
        "unit": 0,
        "max_connections": 32,
    }
    assert load(tmp_path, PLC + "[modbus_server]\nunit = 7\n").sections["modbus_server"].options["unit"] == 7
    assert error(tmp_path, PLC + "[modbus_server]\nunit = 300\n") == (
        "modbus_server.unit",
        "expected an integer from 0 to 255 (got 300)",
    )
