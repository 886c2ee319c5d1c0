"""LTMR_PKW (fblocks/vendor/ltmr.st): register access over the PKW words of
PDO4, driven cycle by cycle in virtual time through a small ST program.

The test plays the LTMR: it reads the request words Out1..Out4 (what RPDO4
would carry) and writes the response words In1..In4 (what TPDO4 would
bring). The request words are digest 001 section 2.5's DERIVED table
(word 2 = toggle << 15 | function code << 8 | sub-index); the function codes
are manual 001 L404-413 and L424-430, the error response L579, the abort
codes L720-754.

At the end: SDO_READ / SDO_WRITE (fblocks/comm/sdo.st), the other way to a
register, as far as a test without a CANopen master can take them; the
lead's end-to-end tests run them against the simulated LTMR.
"""

from __future__ import annotations

import pytest

from softplc.runtime.st.profile import PROFILES

from .st_bench import Bench

PKW_DECLS = """
    p : LTMR_PKW;
    execute : BOOL; write : BOOL; byObject : BOOL; double : BOOL;
    register : UINT; index : WORD; subindex : BYTE; value : UDINT; timeout : TIME := T#1s;
    in1 : WORD; in2 : WORD; in3 : WORD; in4 : WORD;
"""
PKW_BODY = """
p(Execute := execute, Write := write, ByObject := byObject, Register := register, Index := index,
  Subindex := subindex, Double := double, Value := value, Timeout := timeout,
  In1 := in1, In2 := in2, In3 := in3, In4 := in4);
"""


def bench() -> Bench:
    return Bench(PKW_DECLS, PKW_BODY)


def request(b: Bench) -> tuple:
    """The request words the block puts in RPDO4."""
    return tuple(b[f"p.Out{i}"] for i in range(1, 5))


def state(b: Bench) -> tuple:
    return b["p.Busy"], b["p.Done"], b["p.Error"]


REQUEST_DEFAULTS = dict(write=False, byObject=False, double=False, register=0, index=0, subindex=0, value=0)


def send(b: Bench, **inputs) -> tuple:
    """A rising edge of Execute for the request these inputs describe (the
    others at their defaults: a one-register read); returns the request words."""
    b.step(execute=False)
    b.step(execute=True, **{**REQUEST_DEFAULTS, **inputs})
    return request(b)


def answer(b: Bench, w1: int, w2: int, w3: int = 0, w4: int = 0) -> Bench:
    """The LTMR's response words arrive in TPDO4."""
    return b.step(in1=w1, in2=w2, in3=w3, in4=w4)


def echo(b: Bench, w3: int = 0, w4: int = 0) -> Bench:
    """The LTMR answers the request: word 1 and word 2 echoed, data in words 3-4."""
    w1, w2, _w3, _w4 = request(b)
    return answer(b, w1, w2, w3, w4)


# ---------------------------------------------------------------- request words (digest 001 section 2.5)


def test_r_reg_16_of_register_455_and_its_toggle():
    b = bench()
    assert send(b, register=455) == (0x01C7, 0xA500, 0, 0)  # T=1: the LTMR's last response had T=0
    assert state(b) == (True, False, False)
    echo(b, w3=0x6083)
    assert state(b) == (False, True, False)
    assert b["p.ReadValue"] == 0x6083
    assert send(b, register=455) == (0x01C7, 0x2500, 0, 0)  # the next request flips the toggle
    assert echo(b, w3=0x6003)["p.ReadValue"] == 0x6003


@pytest.mark.parametrize(
    "inputs, words",
    [
        # digest 001 section 2.5, DERIVED table, T=1 column (the first request after start)
        (dict(register=500, double=True), (0x01F4, 0xA600, 0, 0)),  # R_REG_32 500
        (dict(register=704, write=True, value=0x0008), (0x02C0, 0xAA00, 0x0008, 0)),  # W_REG_16 704 := 8
        (dict(register=652, write=True, value=50), (0x028C, 0xAA00, 0x0032, 0)),  # W_REG_16 652 := 50
        (dict(byObject=True, index=0x2004, subindex=0x06), (0x2004, 0xB506, 0, 0)),  # R_CO_16 2004:06
        (
            dict(byObject=True, index=0x2008, subindex=0x05, write=True, value=1),
            (0x2008, 0xBA05, 0x0001, 0),
        ),  # W_CO_16 2008:05 := 1
    ],
)
def test_request_words_of_the_digest_table(inputs, words):
    assert send(bench(), **inputs) == words


def test_r_co_16_2004_06_with_toggle_0():
    b = bench()
    send(b, register=455)
    echo(b, w3=0x6083)  # the LTMR now shows T=1
    assert send(b, byObject=True, index=0x2004, subindex=0x06) == (0x2004, 0x3506, 0, 0)


def test_32_bit_codes_and_word_order():
    # manual 001 L365-366: word 3 = 1st word MSW, word 4 = 2nd word LSW
    b = bench()
    assert send(b, register=117, double=True, write=True, value=0x00012345) == (0x0075, 0xAB00, 0x0001, 0x2345)
    echo(b)
    assert send(b, byObject=True, index=0x2007, subindex=0x03, double=True, write=True, value=0xCAFE0032) == (
        0x2007,
        0x3B03,
        0xCAFE,
        0x0032,
    )  # W_CO_32
    echo(b)
    assert send(b, byObject=True, index=0x2004, subindex=0x33, double=True) == (0x2004, 0xB633, 0, 0)  # R_CO_32


def test_one_register_write_sends_the_low_16_bits():
    assert send(bench(), register=704, write=True, value=0x00070001) == (0x02C0, 0xAA00, 0x0001, 0)


def test_r_reg_32_of_average_current_reads_word_3_as_msw():
    # digest 001 section 7.2: 500/501 = 0x0000/0x04D2 -> 1234 (12.34 A)
    b = bench()
    send(b, register=500, double=True)
    assert echo(b, w3=0x0000, w4=0x04D2)["p.ReadValue"] == 1234


# ---------------------------------------------------------------- when the response is ready (A23)


def test_a_response_with_the_other_toggle_does_not_complete():
    b = bench()
    send(b, register=455)  # 0x01C7, 0xA500
    answer(b, 0x01C7, 0x2500, 0x1111)  # same register and code, toggle 0: stale
    assert state(b) == (True, False, False)
    answer(b, 0x01C7, 0xA500, 0x6083)
    assert state(b) == (False, True, False) and b["p.ReadValue"] == 0x6083


@pytest.mark.parametrize(
    "w1, w2",
    [
        (0x01C8, 0xA500),  # another register
        (0x01C7, 0xAA00),  # another function code (W_REG_16)
        (0x01C7, 0xA501),  # another sub-index byte
        (0x01C7, 0x8000),  # function code 0: no request
    ],
)
def test_a_response_to_another_request_does_not_complete(w1, w2):
    b = bench()
    send(b, register=455)
    answer(b, w1, w2, 0x1234)
    assert state(b) == (True, False, False)
    assert b["p.ReadValue"] == 0


def test_error_response_gives_the_abort_code_from_words_3_and_4():
    # digest 001 section 2.5: error response to a register request (T=1), abort 0x06090030
    b = bench()
    assert send(b, register=652, write=True, value=500) == (0x028C, 0xAA00, 0x01F4, 0)
    answer(b, 0x028C, 0xCE00, 0x0609, 0x0030)
    assert state(b) == (False, False, True)
    assert b["p.ErrorCode"] == 0x06090030  # value range of parameter exceeded (L741)


def test_error_response_to_an_object_request_echoes_the_sub_index():
    b = bench()
    send(b, register=455)
    echo(b)
    send(b, byObject=True, index=0x2004, subindex=0x06)  # T=0
    answer(b, 0x2004, 0x4E06, 0x0602, 0x0000)  # 0x06020000: no such object (L733)
    assert state(b) == (False, False, True) and b["p.ErrorCode"] == 0x06020000


def test_no_response_times_out_after_the_timeout():
    b = bench()
    send(b, register=455)
    start = b.runner.now_ms
    b.step(98)
    assert b.runner.now_ms - start == 980 and state(b) == (True, False, False)
    b.step(3)  # 1 s has passed
    assert state(b) == (False, False, True)
    assert b["p.ErrorCode"] == 0x05040000  # L727: the SDO protocol timed out


def test_a_request_right_after_a_slow_answer_gets_the_whole_timeout():
    b = bench()
    send(b, register=455)
    b.step(execute=False)
    b.step(89)  # 0.9 s
    echo(b, w3=1)  # answered in the last call Execute was FALSE
    b.step(execute=True, register=456)  # and the next request in the very next call
    b.step(95)
    assert state(b) == (True, False, False)  # 0.95 s later: still waiting
    assert echo(b, w3=2)["p.ReadValue"] == 2


def test_timeout_zero_waits_for_ever():
    b = bench()
    send(b, register=455, timeout=0)
    b.step(6000)  # a minute
    assert state(b) == (True, False, False)
    assert echo(b, w3=1)["p.Done"] is True


def test_after_a_timeout_the_next_request_differs_from_the_last_answer():
    # The LTMR handles a request when word 2's upper byte changes (L494):
    # the block sets the toggle opposite to the last response's.
    b = bench()
    send(b, register=455)  # T=1, never answered
    b.step(101)
    assert b["p.Error"] is True
    assert send(b, register=455)[1] == 0xA500  # the LTMR still shows T=0: T=1 again
    answer(b, 0x01C7, 0x2500)  # an old answer does not complete it
    assert state(b) == (True, False, False)


def test_a_stale_answer_from_before_a_plc_restart_is_not_taken():
    b = bench()
    b.step(in1=0x01C7, in2=0xA500, in3=0x6083)  # TPDO4 still holds an answer from before
    assert send(b, register=455) == (0x01C7, 0x2500, 0, 0)
    assert state(b) == (True, False, False)
    assert echo(b, w3=0x4003)["p.ReadValue"] == 0x4003


# ---------------------------------------------------------------- PLCopen outputs


def test_done_stays_while_execute_stays_and_clears_with_it():
    b = bench()
    send(b, register=455)
    echo(b, w3=7)
    b.step(5)
    assert state(b) == (False, True, False) and b["p.ReadValue"] == 7
    b.step(execute=False)
    assert state(b) == (False, False, False)


def test_done_shows_for_one_call_when_execute_already_fell():
    b = bench()
    send(b, register=455)
    b.step(execute=False)
    echo(b, w3=7)
    assert state(b) == (False, True, False)
    b.step()
    assert state(b) == (False, False, False)


def test_a_new_edge_while_busy_is_ignored():
    b = bench()
    words = send(b, register=455)
    b.step(execute=False)
    b.step(execute=True, register=704, write=True, value=8)
    assert request(b) == words and state(b) == (True, False, False)
    echo(b, w3=0x6083)
    assert b["p.ReadValue"] == 0x6083  # the first request's answer


def test_error_stays_while_execute_stays_and_a_new_request_clears_it():
    b = bench()
    send(b, register=652, write=True, value=500)
    answer(b, 0x028C, 0xCE00, 0x0609, 0x0030)
    b.step(3)
    assert b["p.Error"] is True and b["p.ErrorCode"] == 0x06090030
    send(b, register=652, write=True, value=50)
    assert state(b) == (True, False, False) and b["p.ErrorCode"] == 0


# ---------------------------------------------------------------- SDO_READ / SDO_WRITE

SDO_DECLS = """
    rd : SDO_READ; wr : SDO_WRITE; node : USINT := 40;
    bytes : ARRAY[0..SDO_MAX_BYTES - 1] OF BYTE;
"""
SDO_BODY = """
(* the manual's two examples (manual 000 L993-1036): read 2004:03, write 2007:03 := 50 *)
rd(EXECUTE := execute, NODE := node, INDEX := 16#2004, SUBINDEX := 3, TIMEOUT := T#200ms);
bytes[0] := 50;
wr(EXECUTE := execute, NODE := node, INDEX := 16#2007, SUBINDEX := 3, DATA := bytes, LENGTH := 2);
"""


@pytest.mark.parametrize("profile", list(PROFILES))
def test_the_libraries_compile_in_every_profile_without_warnings(profile):
    b = Bench(SDO_DECLS + PKW_DECLS + "m : LTMR_CONTROL;", SDO_BODY + PKW_BODY + "m();", profile)
    b.step(execute=True)
    assert b.runner.program.warnings == []


def test_sdo_blocks_without_a_canopen_master_end_in_error_with_the_report():
    # No bus configured: READ_VAR / WRITE_VAR end at once with communication
    # report 16#FF, network exchange error (NoCommunication, the fallback of READ_VAR without a bus).
    b = Bench(SDO_DECLS + "execute : BOOL;", SDO_BODY).step(execute=True)
    for fb in ("rd", "wr"):
        assert (b[f"{fb}.BUSY"], b[f"{fb}.DONE"], b[f"{fb}.ERROR"]) == (False, False, True)
        assert b[f"{fb}.ERRORINFO"] == 0x08000000  # L753: general detected error
        assert b[f"{fb}.REPORT"] == 0x00FF
    assert b["rd.LENGTH"] == 0
    b.step(execute=False)
    assert b["rd.ERROR"] is False and b["rd.ERRORINFO"] == 0 and b["rd.REPORT"] == 0x00FF
