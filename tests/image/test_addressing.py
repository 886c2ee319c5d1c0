"""The two addressing models of DESIGN.md at the byte level, and compiled ST
programs seen from the image: IEC/CODESYS byte offsets, and the Schneider
word indices of the LTMR manual's READ_VAR / WRITE_VAR examples."""

from __future__ import annotations

import struct
from pathlib import Path

import pytest

from softplc.runtime.image.address import parse_address
from softplc.runtime.image.memory import AddressError, ProcessImage
from softplc.runtime.program import ExecContext, compile_files
from softplc.runtime.st import types as T

REPO = Path(__file__).resolve().parents[2]
# DOCA0132DE-01, shared/manuals/000_97161f374cfc3d02.txt L997-L1014 (write)
# and L1020-L1036 (read); copied verbatim into st_programs/ (tests/st/test_parser.py
# checks the copies).
WRITE_SDO = REPO / "st_programs" / "ltmr_write_sdo.st"
READ_SDO = REPO / "st_programs" / "ltmr_read_sdo.st"


# ---------------------------------------------------------------- IEC: byte offsets


def test_iec_words_are_byte_offsets_and_little_endian():
    im = ProcessImage("iec")
    m = im.areas["M"]
    im.write("%MW1", 0x0201)
    assert m[2:4] == b"\x01\x02"  # %MW1 = bytes 2-3, low byte first
    im.write("%MD1", 0x07060504)
    assert m[4:8] == b"\x04\x05\x06\x07"  # %MD1 = bytes 4-7
    im.write("%ML1", 0x0F0E0D0C0B0A0908)
    assert m[8:16] == bytes(range(8, 16))  # %ML1 = bytes 8-15
    assert m[:2] == b"\0\0" and not any(m[16:64])


def test_iec_sizes_overlap_on_the_same_bytes():
    im = ProcessImage("iec")
    im.write("%MD0", 0x44332211)
    assert [im.read(a) for a in ("%MB0", "%MB1", "%MB2", "%MB3")] == [0x11, 0x22, 0x33, 0x44]
    assert (im.read("%MW0"), im.read("%MW1")) == (0x2211, 0x4433)  # low word, high word
    im.write("%MX2.3", True)  # bit 3 of byte 2
    assert im.areas["M"][2] == 0x33 | 0x08 and im.read("%MW1") == 0x443B


def test_iec_bits_and_bytes_of_each_area():
    im = ProcessImage("iec")
    im.write("%QB2", 0xA5)
    im.write("%QX0.0", True)
    im.write("%IX1.7", True)
    assert im.areas["Q"][:3] == b"\x01\x00\xa5"
    assert im.areas["I"][:2] == b"\x00\x80"
    assert not any(im.areas["M"][:8])  # the areas are separate


# ---------------------------------------------------------------- Schneider: word indices


def test_schneider_md_overlaps_two_words_low_word_first():
    # DOCA0132DE L1006: %MD3200 := 0x00032007 (<index> = 0x2007 ; <sub-index> = 3);
    # on a Premium %MD3200 is %MW3200 (low word) and %MW3201 (high word).
    im = ProcessImage("schneider")
    im.write("%MD3200", 0x00032007)
    assert (im.read("%MW3200"), im.read("%MW3201")) == (0x2007, 0x0003)
    assert im.areas["M"][6400:6404] == b"\x07\x20\x03\x00"  # word 3200 = byte 6400
    assert im.read("%MD3201") == 0x00000003  # %MD3201 starts at word 3201: no 4-byte stride


def test_schneider_word_bits_and_tables():
    im = ProcessImage("schneider")
    im.write("%MW3250", 0x8001)
    assert im.read("%MW3250:X0") and im.read("%MW3250:X15") and not im.read("%MW3250:X1")
    im.write("%MW3250:X0", False)  # the activity bit of the management table
    assert im.read("%MW3250") == 0x8000
    im.write("%MW3253", 2)
    assert im.read("%MW3250:4") == [0x8000, 0, 0, 2]  # words 3250..3253
    assert im.region(parse_address("%MW3250:4")) == ("M", 6500, 8)


def test_schneider_m_bits_are_apart_from_the_words():
    im = ProcessImage("schneider")
    im.write("%M100", True)
    assert im.mbits[100] == 1 and not any(im.areas["M"])
    im.write("%MW100", 0xFFFF)
    im.write("%M100", False)
    assert im.read("%MW100") == 0xFFFF and im.mbits[100] == 0


@pytest.mark.parametrize(
    "text, iec, schneider",
    [
        ("%MB3", ("M", 3, 1), ("M", 3, 1)),
        ("%MW1", ("M", 2, 2), ("M", 2, 2)),
        ("%MD1", ("M", 4, 4), ("M", 2, 4)),
        ("%ML1", ("M", 8, 8), ("M", 2, 8)),
        ("%QW4", ("Q", 8, 2), ("Q", 8, 2)),
        ("%ID3200", ("I", 12800, 4), ("I", 6400, 4)),
    ],
)
def test_the_models_differ_only_in_the_stride_of_d_and_l(text, iec, schneider):
    addr = parse_address(text)
    assert ProcessImage("iec").region(addr) == iec
    assert ProcessImage("schneider").region(addr) == schneider


def test_schneider_forms_are_refused_in_the_iec_model():
    for text in ("%MW3250:X0", "%MW3250:4", "%M100"):
        with pytest.raises(AddressError):
            ProcessImage("iec").read(text)


# ---------------------------------------------------------------- compiled ST, IEC / CODESYS

IEC_PROGRAM = """
PROGRAM main
VAR
  start AT %IX0.3 : BOOL;
  speed_in AT %IW2 : INT;     (* bytes 4-5 of %I *)
  out_b AT %QB0 : BYTE;
  lamp AT %QX1.7 : BOOL;
  out_w AT %QW1 : WORD;       (* bytes 2-3 *)
  setpoint AT %QD1 : REAL;    (* bytes 4-7 *)
  total AT %MD2 : DINT;       (* bytes 8-11 *)
  big AT %ML2 : LINT;         (* bytes 16-23 *)
  low_of_total AT %MW4 : INT; (* bytes 8-9: the low word of total *)
  copy : INT;
END_VAR
lamp := start;
out_b := 16#A5;
out_w := 16#1234;
setpoint := 1.5;
total := speed_in;
total := total * 1000;
big := -2;
copy := low_of_total;
END_PROGRAM
"""


def test_iec_located_variables_of_every_size_land_on_their_bytes():
    prog = compile_files([], profile="codesys", texts={"main.st": IEC_PROGRAM})
    image = ProcessImage("iec")
    image.write("%IX0.3", True)
    image.write("%IW2", -7)
    assert image.areas["I"][:6] == b"\x08\x00\x00\x00\xf9\xff"
    runner = prog.runner("main", cycle_time_ms=10, ctx=ExecContext(image))
    runner.run(1)
    q, m = image.areas["Q"], image.areas["M"]
    assert q[0] == 0xA5 and q[1] == 0x80  # %QB0, %QX1.7
    assert q[2:4] == b"\x34\x12"  # %QW1
    assert q[4:8] == struct.pack("<f", 1.5)  # %QD1 as REAL
    assert m[8:12] == struct.pack("<i", -7000)  # %MD2
    assert m[16:24] == struct.pack("<q", -2)  # %ML2
    assert runner.get("copy") == struct.unpack("<h", struct.pack("<i", -7000)[:2])[0]
    assert image.read("%QD1", T.REAL) == 1.5 and image.read("%MD2") == (-7000) & 0xFFFFFFFF
    # An input changed between cycles is what the next cycle reads.
    image.write("%IX0.3", False)
    runner.run(1)
    assert q[1] == 0


# ---------------------------------------------------------------- compiled ST, the LTMR manual


def _ltmr_image():
    prog = compile_files([WRITE_SDO, READ_SDO], profile="schneider")
    image = ProcessImage("schneider")
    ctx = ExecContext(image)  # no bus: READ_VAR / WRITE_VAR end at once (NoCommunication)
    return (
        image,
        prog.runner("ltmr_write_sdo", cycle_time_ms=10, ctx=ctx),
        prog.runner("ltmr_read_sdo", cycle_time_ms=10, ctx=ctx),
    )


def test_ltmr_examples_share_one_memory_without_overlap():
    image, write, read = _ltmr_image()
    write.run(1)
    read.run(1)
    # Write example: %MD3200 = index 0x2007 / subindex 3 (register 652, FLC1),
    # value %MW3202 = 50 (% of FLCmax), just after the %MD with no overlap.
    assert image.read("%MW3200:3") == [0x2007, 0x0003, 50]
    assert image.areas["M"][6400:6406] == b"\x07\x20\x03\x00\x32\x00"
    # Read example: %MD3220 = index 0x2004 / subindex 3 (register 452).
    assert image.read("%MW3220:2") == [0x2004, 0x0003]
    assert image.read("%MD3220") == 0x00032004
    # No request bit set: the management tables are untouched.
    assert image.read("%MW3250:4") == [0, 0, 0, 0] and image.read("%MW3260:4") == [0, 0, 0, 0]


def test_ltmr_request_bit_and_activity_bit_through_the_image():
    image, write, _read = _ltmr_image()
    # An exchange still in progress (activity bit %MW3250:X0 set): no new request.
    image.write("%M100", True)
    image.write("%MW3250:X0", True)
    write.run(1)
    assert image.read("%M100") and image.read("%MW3253") == 0
    # Previous exchange finished: the request starts, with the timeout in the
    # 4th management word (L1010: %MW3253:=2, 200 ms), and %M100 is reset.
    image.write("%MW3250:X0", False)
    write.run(1)
    assert image.read("%MW3253") == 2 and image.read("%MW3250:4")[3] == 2
    assert not image.read("%M100") and image.mbits[100] == 0
    assert not image.read("%MW3250:X0")  # without a bus the exchange is over at once
