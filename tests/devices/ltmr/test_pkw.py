"""The PKW codec: word 2 of every request in digest 001 §2.5 (DERIVED table,
from the manual's function codes and word layout, L337-591), the handshake
rules quoted from the manual, and the frame layout (A6)."""

from __future__ import annotations

import canopen
import pytest

from softplc.runtime.devices.ltmr import pkw
from softplc.runtime.devices.ltmr.eds import ltmr_eds
from softplc.runtime.devices.ltmr.pkw import PkwWords
from softplc.runtime.io.canopen.cia301 import ABORT_VALUE_RANGE
from softplc.runtime.io.canopen.eds import render

# (description, word 1, function, sub-index, (word 3, word 4), word 2 with T=0, word 2 with T=1)
WORD2_TABLE = [
    ("R_REG_16 reg 455", 0x01C7, pkw.R_REG_16, 0, (0, 0), 0x2500, 0xA500),
    ("R_REG_32 reg 500 (Average current)", 0x01F4, pkw.R_REG_32, 0, (0, 0), 0x2600, 0xA600),
    ("W_REG_16 reg 704 := 0x0008 (trip reset)", 0x02C0, pkw.W_REG_16, 0, (0x0008, 0), 0x2A00, 0xAA00),
    ("W_REG_16 reg 652 := 50 (FLC1 50 %)", 0x028C, pkw.W_REG_16, 0, (0x0032, 0), 0x2A00, 0xAA00),
    ("R_CO_16 2004:06 (reg 455)", 0x2004, pkw.R_CO_16, 0x06, (0, 0), 0x3506, 0xB506),
    ("W_CO_16 2008:05 := 0x0001 (run fwd)", 0x2008, pkw.W_CO_16, 0x05, (0x0001, 0), 0x3A05, 0xBA05),
]


@pytest.mark.parametrize("row", WORD2_TABLE, ids=lambda r: r[0])
@pytest.mark.parametrize("toggle", [0, 1])
def test_request_words(row, toggle):
    _what, w1, function, sub, data, w2_t0, w2_t1 = row
    words = pkw.request(w1, function, toggle, subindex=sub, data=data)
    assert words == PkwWords(w1, w2_t1 if toggle else w2_t0, *data)
    assert (words.toggle, words.function, words.subindex) == (toggle, function, sub)


def test_register_numbers_of_the_table():
    # word 1 is the register number in decimal: 455 = 0x01C7, 500 = 0x01F4, 704 = 0x02C0, 652 = 0x028C
    assert [pkw.request(n, pkw.R_REG_16, 0).w1 for n in (455, 500, 704, 652)] == [0x01C7, 0x01F4, 0x02C0, 0x028C]


def test_error_response_to_an_object_request():
    # "Error response to R_CO_16 2004:06": word 2 = 0x4E06 (T=0) / 0xCE06 (T=1), abort code MSW, LSW
    for toggle, w2 in ((0, 0x4E06), (1, 0xCE06)):
        req = pkw.request(0x2004, pkw.R_CO_16, toggle, subindex=0x06)
        assert pkw.error_response(req, ABORT_VALUE_RANGE) == PkwWords(0x2004, w2, 0x0609, 0x0030)


def test_error_response_to_a_register_request():
    # "Error response to register request (T=1), abort 0x06090030": 0xCE00, 0x0609, 0x0030
    req = pkw.request(652, pkw.W_REG_16, 1, data=(5000, 0))
    resp = pkw.error_response(req, 0x06090030)
    assert (resp.w1, resp.w2, resp.w3, resp.w4) == (652, 0xCE00, 0x0609, 0x0030)
    assert resp.is_error and resp.value32 == 0x06090030


def test_function_code_sets():
    # codes of L404-577; 0x55 in the CANopen response table is a typo for 0x35 (A10)
    assert (pkw.R_REG_16, pkw.R_REG_32, pkw.W_REG_16, pkw.W_REG_32) == (0x25, 0x26, 0x2A, 0x2B)
    assert (pkw.R_CO_16, pkw.R_CO_32, pkw.W_CO_16, pkw.W_CO_32, pkw.ERROR) == (0x35, 0x36, 0x3A, 0x3B, 0x4E)
    assert pkw.READS == {0x25, 0x26, 0x35, 0x36} and pkw.WRITES == {0x2A, 0x2B, 0x3A, 0x3B}
    assert pkw.IS_32BIT == {0x26, 0x2B, 0x36, 0x3B} and pkw.BY_OBJECT == {0x35, 0x36, 0x3A, 0x3B}
    assert 0x55 not in pkw.READS
    with pytest.raises(ValueError):
        pkw.request(0x2004, 0x55, 0, subindex=6)


def test_register_addressing_has_no_sub_index():
    # "LSB = 0x00" for R_REG/W_REG
    with pytest.raises(ValueError):
        pkw.request(455, pkw.R_REG_16, 0, subindex=1)


def test_32_bit_data_is_msw_first():
    # W_REG_32: word 3 = data for register 1 (MSW), word 4 = register 2 (LSW)
    req = pkw.request(500, pkw.W_REG_32, 0, data=(0x0001, 0x0002))
    assert req.value32 == 0x00010002
    resp = pkw.response(pkw.request(500, pkw.R_REG_32, 1), data=(0x0000, 0x04D2))
    assert resp.value32 == 1234 and resp.w2 == 0xA600


# ---------------------------------------------------------------------------
# Handshake (manual L337-591, A23)
# ---------------------------------------------------------------------------


def test_response_with_the_same_toggle_and_function_is_ready():
    req = pkw.request(455, pkw.R_REG_16, 1)
    assert pkw.response_ready(req, pkw.response(req, data=(0x6083, 0)))
    assert pkw.response_ready(req, pkw.error_response(req, 0x06020000))


def test_previous_response_is_not_ready_for_the_next_request():
    # "Another way of re-triggering exactly the same command is to invert the toggle bit"
    first = pkw.request(455, pkw.R_REG_16, 0)
    old_response = pkw.response(first, data=(0x6083, 0))
    again = pkw.request(455, pkw.R_REG_16, 1)
    assert not pkw.response_ready(again, old_response)
    assert pkw.response_ready(again, pkw.response(again, data=(0x6083, 0)))


def test_response_for_another_register_or_function_is_not_ready():
    req = pkw.request(455, pkw.R_REG_16, 0)
    assert not pkw.response_ready(req, pkw.response(pkw.request(456, pkw.R_REG_16, 0)))
    assert not pkw.response_ready(req, pkw.response(pkw.request(455, pkw.R_REG_32, 0)))
    obj = pkw.request(0x2004, pkw.R_CO_16, 0, subindex=6)
    assert not pkw.response_ready(obj, pkw.response(pkw.request(0x2004, pkw.R_CO_16, 0, subindex=7)))


def test_retrigger_through_function_code_zero():
    # "Reset the function code to 0x00, wait for the response frame with the function code equal to 0x00,
    #  reset it to its previous value."
    req = pkw.request(704, pkw.W_REG_16, 0, data=(0x0008, 0))
    done = pkw.response(req)
    idle = pkw.request(704, pkw.NONE, 0)
    assert not pkw.response_ready(idle, done)  # still the old answer
    idle_echo = pkw.response(idle)
    assert pkw.response_ready(idle, idle_echo)
    assert not pkw.response_ready(req, idle_echo)  # the repeated request is not answered yet
    assert pkw.response_ready(req, pkw.response(req))


# ---------------------------------------------------------------------------
# Frame layout (A6)
# ---------------------------------------------------------------------------


def test_frame_bytes_default_layout():
    # each object = (second word << 16) | first word, little-endian: w1lo w1hi w2lo w2hi w3lo w3hi w4lo w4hi
    req = pkw.request(704, pkw.W_REG_16, 1, data=(0x0008, 0))
    assert pkw.encode_frame(req) == bytes([0xC0, 0x02, 0x00, 0xAA, 0x08, 0x00, 0x00, 0x00])
    assert pkw.to_objects(req) == (0xAA0002C0, 0x00000008)
    assert pkw.decode_frame(pkw.encode_frame(req)) == req
    assert pkw.from_objects(*pkw.to_objects(req)) == req


def test_frame_bytes_big_endian_alternative():
    req = pkw.request(0x2004, pkw.R_CO_16, 1, subindex=6)
    assert pkw.encode_frame(req, "big") == bytes([0x20, 0x04, 0xB5, 0x06, 0, 0, 0, 0])
    assert pkw.decode_frame(pkw.encode_frame(req, "big"), "big") == req
    with pytest.raises(ValueError):
        pkw.encode_frame(req, "middle")


def test_frame_length_and_word_range():
    with pytest.raises(ValueError):
        pkw.decode_frame(bytes(6))
    with pytest.raises(ValueError):
        PkwWords(0x10000, 0)


def test_default_layout_is_what_canopen_stores_in_the_pkw_objects(tmp_path):
    # The RPDO4 bytes land in 0x3000:01/02 (UNSIGNED32, little-endian on the wire, CiA 301);
    # the canopen stack's own decoding of those bytes gives the object values of to_objects.
    eds = tmp_path / "ltmr.eds"
    eds.write_text(render(ltmr_eds()))
    node = canopen.LocalNode(40, canopen.import_od(str(eds), node_id=40))
    req = pkw.request(0x2008, pkw.W_CO_16, 1, subindex=5, data=(0x0001, 0))
    frame = pkw.encode_frame(req)
    node.set_data(0x3000, 1, frame[:4], check_writable=True)
    node.set_data(0x3000, 2, frame[4:], check_writable=True)
    assert (node.sdo[0x3000][1].raw, node.sdo[0x3000][2].raw) == pkw.to_objects(req)
