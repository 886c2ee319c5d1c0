"""Direct addresses from config files and the command line: parse_address,
default_type, region, ProcessImage.read / write and outputs_view."""

from __future__ import annotations

import pytest

from softplc.runtime.image import address, memory
from softplc.runtime.image.address import AddressError, default_type, parse_address, region
from softplc.runtime.image.memory import ProcessImage
from softplc.runtime.st import types as T
from softplc.runtime.st.syntax.literals import parse_located

# ---------------------------------------------------------------- parse_address


@pytest.mark.parametrize(
    "text, fields",
    [
        ("%QX0.0", ("Q", "X", (0, 0), None, None)),
        ("%IW4", ("I", "W", (4,), None, None)),
        ("%MD3200", ("M", "D", (3200,), None, None)),
        ("%MW3250:X0", ("M", "W", (3250,), 0, None)),
        ("%MW3250:4", ("M", "W", (3250,), None, 4)),
        ("%QB2", ("Q", "B", (2,), None, None)),
        ("%M100", ("M", "", (100,), None, None)),
        ("%ML1", ("M", "L", (1,), None, None)),
        ("  %mw3250:x15\t", ("M", "W", (3250,), 15, None)),
    ],
)
def test_parse_address(text, fields):
    a = parse_address(text)
    assert (a.area, a.size, a.indices, a.bit, a.table) == fields


def test_parse_address_is_case_insensitive_and_canonical():
    a = parse_address(" %qw0 ")
    assert a.text == "%QW0" and a == parse_address("%QW0") == parse_located("%QW0")


@pytest.mark.parametrize(
    "text, message",
    [
        ("%QZ1", "'%QZ1' is not a direct address (examples: %QX0.0, %IW2, %MD3200, %MW3250:X0)"),
        ("", "'' is not a direct address"),
        ("QW0", "'QW0' is not a direct address"),
        ("%QW", "'%QW' is not a direct address"),
        ("%QX0..3", "'%QX0..3' is not a direct address"),
        ("%QX0.", "'%QX0.' is not a direct address"),
        ("%QW0 junk", "'%QW0 junk' is not a direct address"),
        ("%I*", "'%I*' is an unconfigured placeholder; give the full address"),
        ("%QW0.1", "%QW0.1: a %QW address has one number, e.g. %QW4"),
        ("%QX0.8", "%QX0.8: bit number 8 is not 0..7"),
        ("%QX0.1.2", "%QX0.1.2: a bit address is <byte>.<bit>, e.g. %QX0.3"),
        ("%MW3250:X16", "%MW3250:X16: a word has bits 0..15"),
        ("%MD3200:X0", "%MD3200:X0: :X0 follows a word address, e.g. %MW3250:X0"),
        ("%MB7:4", "%MB7:4: :4 follows a word address"),
        ("%MW1:0", "%MW1:0: a word table has at least 1 word"),
        ("%MW" + "9" * 19, "number too long"),
    ],
)
def test_bad_addresses_say_what_was_expected(text, message):
    with pytest.raises(AddressError) as exc:
        parse_address(text)
    assert message in str(exc.value)


def test_an_address_is_a_string():
    with pytest.raises(AddressError, match="a direct address is a string like '%QW0', not int"):
        parse_address(12)


def test_the_model_refuses_what_it_lacks():
    for text in ("%MW3250:X0", "%MW3250:4", "%M100"):
        assert parse_address(text, "schneider").text == text
    with pytest.raises(AddressError, match="Schneider addressing; use the schneider profile"):
        parse_address("%MW3250:X0", "iec")
    with pytest.raises(AddressError, match=r"%M100: a bit address needs <byte>.<bit>, e.g. %MX0.3"):
        parse_address("%M100", "iec")


def test_one_address_error_class():
    assert memory.AddressError is address.AddressError and issubclass(AddressError, ValueError)


@pytest.mark.parametrize(
    "text, ty",
    [
        ("%QX0.0", T.BOOL),
        ("%M100", T.BOOL),
        ("%MW3250:X3", T.BOOL),
        ("%QB0", T.BYTE),
        ("%IW2", T.WORD),
        ("%MD3200", T.DWORD),
        ("%ML0", T.LWORD),
        ("%MW3250:4", T.WORD),
    ],
)
def test_default_type(text, ty):
    assert default_type(parse_address(text)) is ty


# ---------------------------------------------------------------- region


def test_region_of_bytes_words_and_tables():
    iec, sch = ProcessImage("iec"), ProcessImage("schneider")
    assert region(iec, parse_address("%QB7")) == ("Q", 7, 1)
    assert region(iec, parse_address("%IW3")) == ("I", 6, 2)
    assert region(sch, parse_address("%MW3260:4")) == ("M", 6520, 8)
    assert region(sch, parse_address("%QD10")) == ("Q", 20, 4)
    assert region(iec, parse_address("%QL8191")) == ("Q", 65528, 8)  # the last whole LWORD


@pytest.mark.parametrize(
    "model, text, message",
    [
        ("iec", "%QX0.3", "%QX0.3 is a bit; drivers copy whole bytes"),
        ("schneider", "%MW3250:X0", "%MW3250:X0 is a bit; drivers copy whole bytes"),
        ("schneider", "%M100", "%M100 is a bit"),
        ("iec", "%MW3250:4", "Schneider addressing"),
        ("iec", "%QW32768", "%QW32768 (bytes 65536..65537) is outside the 65536-byte %Q area"),
        ("schneider", "%MW32767:2", "%MW32767:2 (bytes 65534..65537) is outside"),
        ("schneider", "%MD32767", "%MD32767 (bytes 65534..65537) is outside"),
    ],
)
def test_region_errors(model, text, message):
    with pytest.raises(AddressError) as exc:
        ProcessImage(model).region(parse_address(text))
    assert message in str(exc.value)


def test_region_refuses_a_placeholder_from_the_parser():
    with pytest.raises(AddressError, match="%I\\* is an unconfigured address"):
        ProcessImage().region(parse_located("%I*"))


def test_a_smaller_image_says_its_size():
    with pytest.raises(AddressError, match=r"%QW8 \(bytes 16..17\) is outside the 16-byte %Q area"):
        ProcessImage("iec", 16).write("%QW8", 1)


# ---------------------------------------------------------------- read / write


def test_read_and_write_by_address_string_or_located_address():
    im = ProcessImage("iec")
    im.write("%QW0", 0xBEEF)
    assert im.read("%qw0") == 0xBEEF == im.read(parse_address("%QW0"))
    im.write(parse_address("%QX3.1"), True)
    assert im.read("%QB3") == 2 and im.read("%QX3.1") is True


def test_words_take_signed_or_unsigned_values_but_nothing_wider():
    im = ProcessImage("iec")
    im.write("%MW0", -1)
    assert im.read("%MW0") == 0xFFFF and im.read("%MW0", T.INT) == -1
    im.write("%MB2", -128)
    assert im.read("%MB2") == 0x80
    im.write("%ML1", (1 << 64) - 1)
    assert im.read("%ML1", T.LINT) == -1
    for text, value in (("%MW0", 0x10000), ("%MW0", -0x8001), ("%MB0", 256), ("%MD0", 1 << 32)):
        with pytest.raises(ValueError, match=f"{text}: {value} does not fit"):
            im.write(text, value)
    with pytest.raises(ValueError, match="%MW0 holds a WORD: write an integer, not 1.5"):
        im.write("%MW0", 1.5)
    with pytest.raises(ValueError, match="%QX0.0 is a BOOL: write TRUE/FALSE or 1/0, not 2"):
        im.write("%QX0.0", 2)


def test_reals_need_their_type():
    im = ProcessImage("schneider")
    im.write("%MD10", 1.5, T.REAL)
    im.write("%ML20", -0.25, T.LREAL)
    assert im.read("%MD10", T.REAL) == 1.5 and im.read("%ML20", T.LREAL) == -0.25
    assert im.read("%MD10") == 0x3FC00000  # without a type: the DWORD bits
    with pytest.raises(AddressError, match="%MW0 holds 16 bits; REAL does not fit"):
        im.read("%MW0", T.REAL)
    with pytest.raises(AddressError, match="%MD0 holds 32 bits; INT does not fit"):
        im.write("%MD0", 1, T.INT)
    with pytest.raises(AddressError, match="%MW3250:X0 is a bit; it holds a BOOL, not WORD"):
        im.read("%MW3250:X0", T.WORD)


def test_tables_read_and_write_as_lists():
    im = ProcessImage("schneider")
    im.write("%MW3260:4", [1, -1, 0xFFFF, 2])
    assert im.read("%MW3260:4") == [1, 0xFFFF, 0xFFFF, 2]
    assert im.read("%MW3260:4", T.INT) == [1, -1, -1, 2]
    with pytest.raises(ValueError, match="%MW3260:4 is a table of 4 words, not 3"):
        im.write("%MW3260:4", [1, 2, 3])
    with pytest.raises(ValueError, match="write a list of 4 integers"):
        im.write("%MW3260:4", 7)


# ---------------------------------------------------------------- outputs_view


def test_outputs_view_shares_inputs_and_memory_but_not_outputs():
    im = ProcessImage("schneider", 64)
    safe = bytearray(64)
    safe[0] = 0x5A
    view = im.outputs_view(safe)
    assert view.areas["Q"] is safe and view.areas["I"] is im.areas["I"] and view.mbits is im.mbits
    assert (view.addressing, view.size) == ("schneider", 64)
    assert view.held_safe and not im.held_safe  # what a driver that sends no %Q acts on
    im.write("%QW0", 0x1111)
    assert view.read("%QB0") == 0x5A and im.read("%QB0") == 0x11  # its own %Q
    im.write("%IW1", 7)
    im.write("%MW2", 8)
    im.write("%M3", True)
    assert (view.read("%IW1"), view.read("%MW2"), view.read("%M3")) == (7, 8, True)
    view.write("%MW2", 9)  # one memory, whichever image writes it
    assert im.read("%MW2") == 9


def test_outputs_view_needs_a_q_area_of_the_image_size():
    with pytest.raises(ValueError, match="the %Q area of a view must have 64 bytes, not 8"):
        ProcessImage("iec", 64).outputs_view(bytearray(8))
