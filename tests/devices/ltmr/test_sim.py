"""The simulated LTMR on the virtual bus, driven as a CANopen master drives
it: raw frames from the test's endpoint, byte-level checks against manual
001 and the vectors of digest 001 (§3.4 SDO, §2.5 PKW, §7.2 PDO frames;
node 40 = 0x28), virtual time only."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.ltmr import codes as ltmr_codes
from softplc.runtime.devices.ltmr import pkw
from softplc.runtime.devices.ltmr import registers as ltmr
from softplc.runtime.devices.ltmr.bits import Status1
from softplc.runtime.devices.ltmr.codes import FallbackStrategy, OperatingMode, ResetMode
from softplc.runtime.io.canopen.cia301 import (
    ABORT_ACCESS,
    ABORT_BAD_COMMAND,
    ABORT_DEVICE_STATE,
    ABORT_NO_OBJECT,
    ABORT_NO_SUBINDEX,
    ABORT_NOT_MAPPABLE,
    ABORT_READ_ONLY,
    ABORT_VALUE_RANGE,
    NMT_START,
    STATE_OPERATIONAL,
    STATE_PRE_OPERATIONAL,
)

from ...io.canopen.bench import MS, abort_frame, write_ok
from .sim_support import (
    HEARTBEAT,
    NODE,
    RPDO1,
    RPDO4,
    TPDO1,
    TPDO4,
    operational,
    running_forward,
    tpdo1,
)

# ---------------------------------------------------------------------------- boot and NMT


def test_boot_up_frame_and_product_code(bench):
    sim = bench.ltmr(NODE, product_code=0x31)
    assert bench.frames == [(0, HEARTBEAT, b"\x00")]  # 0x728 [00]
    assert sim.nmt_state == STATE_PRE_OPERATIONAL
    # digest 001 §3.4: 0x1018:02 product code 0x31 (remote configuration, LTMEV40)
    assert bench.sdo(NODE, "40 18 10 02 00 00 00 00") == bytes.fromhex("43 18 10 02 31 00 00 00")


def test_an_unknown_product_code_is_refused(bench):
    with pytest.raises(ValueError):
        bench.ltmr(NODE, product_code=0x32)


def test_nmt_start_then_tpdo1_carries_455_456_457_459(bench):
    sim = bench.ltmr(NODE, registers={ltmr.REG_LOGIC_INPUTS: 0x0005})
    sim.set_load(100)
    bench.clear()
    bench.send(0x000, "01 28")  # NMT start node 40
    assert sim.nmt_state == STATE_OPERATIONAL
    assert bench.frames_with(TPDO1) == [tpdo1(sim)]
    bench.send(RPDO1, "01 00 00 00 00 00")
    bench.run_ms(1500)
    # digest 001 §7.2: 455 = 0x6083, 456 = 0, 457 = 0x0005, 459 = 0x1005 -> 83 60 00 00 05 00 05 10;
    # here 455 also has bit 6 "controller power" (A13) and word 4 is 459, not 458 (A1)
    assert bench.frames_with(TPDO1)[-1] == bytes.fromhex("C3 60 00 00 05 00 05 10")


# ---------------------------------------------------------------------------- SDO (digest 001 §3.4)


def test_sdo_read_of_status_register_1(bench):
    sim = running_forward(bench)
    sim.set_load(100)
    bench.run_ms(10)
    assert bench.sdo(NODE, "40 04 20 06 00 00 00 00") == bytes.fromhex("4B 04 20 06 C3 60 00 00")


def test_sdo_write_flc1_50_percent(bench):
    sim = bench.ltmr(NODE, registers={ltmr.REG_FLC1: 40})
    assert bench.sdo(NODE, "2B 07 20 03 32 00 00 00") == bytes.fromhex("60 07 20 03 00 00 00 00")
    assert sim.register(ltmr.REG_FLC1) == 50
    assert sim.read(0x2007, 0x03) == 50


def test_sdo_read_of_trip_register_1(bench):
    sim = bench.ltmr(NODE)
    sim.set_register(ltmr.REG_TRIP_REGISTER_1, 0x0008)  # the manual's "Read SDO Example" object
    assert bench.sdo(NODE, "40 04 20 03 00 00 00 00") == bytes.fromhex("4B 04 20 03 08 00 00 00")


def test_sdo_run_forward_and_trip_reset_words(bench):
    sim = bench.ltmr(NODE)
    assert bench.sdo(NODE, "2B 08 20 05 01 00 00 00") == write_ok(0x2008, 0x05)  # 704 := 0x0001
    bench.run_ms(10)
    assert sim.lo1
    assert bench.sdo(NODE, "2B 08 20 05 08 00 00 00") == write_ok(0x2008, 0x05)  # 704 := 0x0008
    bench.run_ms(10)
    assert not sim.lo1


def test_read_only_reserved_and_forbidden_registers(bench):
    sim = bench.ltmr(NODE)
    assert bench.sdo(NODE, "2B 04 20 06 01 00 00 00") == abort_frame(0x2004, 0x06, ABORT_READ_ONLY)
    assert sim.register(ltmr.REG_STATUS_1) != 1
    # 703 (2008:04) is Reserved: "you must write 0"
    assert bench.sdo_write(NODE, 0x2008, 0x04, 1, 2) == abort_frame(0x2008, 0x04, ABORT_VALUE_RANGE)
    assert bench.sdo_write(NODE, 0x2008, 0x04, 0, 2) == write_ok(0x2008, 0x04)
    # Forbidden: 710 (2008:0B) and 97 (2000:62) are not in the OD; a whole index: no object (A21)
    assert bench.sdo_read(NODE, 0x2008, 0x0B) == abort_frame(0x2008, 0x0B, ABORT_NO_SUBINDEX)
    assert bench.sdo_read(NODE, 0x2000, 0x62) == abort_frame(0x2000, 0x62, ABORT_NO_SUBINDEX)
    assert bench.sdo_read(NODE, 0x2009, 0x01) == abort_frame(0x2009, 0x01, ABORT_NO_OBJECT)


def test_note_a_motor_off_note_b_configuration_mode_note_c_no_trip(bench):
    sim = running_forward(bench)
    # 540 (note B) outside configuration mode
    assert bench.sdo_write(NODE, 0x2005, 0x01, 2, 2) == abort_frame(0x2005, 0x01, ABORT_DEVICE_STATE)
    # 601 bit 0, "go to the configuration menu" (note A), while the motor runs
    config = sim.register(ltmr.REG_GENERAL_CONFIG_1)
    assert bench.sdo_write(NODE, 0x2006, 0x02, config | 1, 2) == abort_frame(0x2006, 0x02, ABORT_DEVICE_STATE)
    bench.send(RPDO1, "00 00 00 00 00 00")
    bench.run_ms(10)
    assert bench.sdo_write(NODE, 0x2006, 0x02, config | 1, 2) == write_ok(0x2006, 0x02)
    assert bench.sdo_write(NODE, 0x2005, 0x01, OperatingMode.OVERLOAD_2W, 2) == write_ok(0x2005, 0x01)
    assert sim.register(ltmr.REG_OPERATING_MODE) == OperatingMode.OVERLOAD_2W
    # 602 bits 0-2 reset mode (note C) while tripped; its other bits are free
    sim.set_register(ltmr.REG_TRIP_CODE, ltmr_codes.TRIP_TEST)
    general2 = sim.register(ltmr.REG_GENERAL_CONFIG_2)
    manual = (general2 & ~0x7) | ResetMode.MANUAL
    assert bench.sdo_write(NODE, 0x2006, 0x03, manual, 2) == abort_frame(0x2006, 0x03, ABORT_DEVICE_STATE)
    assert bench.sdo_write(NODE, 0x2006, 0x03, general2 ^ (1 << 3), 2) == write_ok(0x2006, 0x03)


def test_values_the_manual_lists(bench):
    bench.ltmr(NODE)
    # 682 = 3 "LO1, LO2 On": only for overload, independent and custom modes, not the reverser
    assert bench.sdo_write(NODE, 0x2007, 0x21, 3, 2) == abort_frame(0x2007, 0x21, ABORT_VALUE_RANGE)
    assert bench.sdo_write(NODE, 0x2007, 0x21, 2, 2) == write_ok(0x2007, 0x21)
    # 602 bits 0-2 is one of 1, 2, 4 (DT_ResetMode)
    assert bench.sdo_write(NODE, 0x2006, 0x03, 3, 2) == abort_frame(0x2006, 0x03, ABORT_VALUE_RANGE)


def test_configuration_over_the_network_only_when_enabled(bench):
    sim = bench.ltmr(NODE)
    sim.set_register(ltmr.REG_GENERAL_CONFIG_1, sim.register(ltmr.REG_GENERAL_CONFIG_1) & ~(1 << 10))
    assert bench.sdo_write(NODE, 0x2007, 0x03, 50, 2) == abort_frame(0x2007, 0x03, ABORT_ACCESS)
    assert bench.sdo_write(NODE, 0x2008, 0x05, 1, 2) == write_ok(0x2008, 0x05)  # commands still count


def test_pdo_mapping_follows_the_manuals_groups(bench):
    bench.ltmr(NODE)
    assert bench.sdo_write(NODE, 0x1801, 2, 255, 1) == write_ok(0x1801, 2)  # TPDO2 is invalid already
    # 0x2004 (monitoring) into a TPDO; a command (0x2008) is not monitoring
    assert bench.sdo_write(NODE, 0x1A01, 1, 0x20040210, 4) == write_ok(0x1A01, 1)
    assert bench.sdo_write(NODE, 0x1A01, 2, 0x20080510, 4) == abort_frame(0x1A01, 2, ABORT_NOT_MAPPABLE)
    # settings 0x2007 and commands 0x2008 into an RPDO
    assert bench.sdo_write(NODE, 0x1601, 1, 0x20072110, 4) == write_ok(0x1601, 1)
    assert bench.sdo_write(NODE, 0x1601, 2, 0x30000320, 4) == abort_frame(0x1601, 2, ABORT_NOT_MAPPABLE)


def test_tpdo2_mapped_by_the_master_with_an_event_timer(bench):
    sim = bench.ltmr(NODE)
    for index, sub, value, size in (
        (0x1801, 1, 0x800002A8, 4),
        (0x1A01, 0, 0, 1),
        (0x1A01, 1, 0x20040210, 4),
        (0x1A01, 2, 0x20040B10, 4),
        (0x1A01, 3, 0x20041010, 4),
        (0x1A01, 4, 0x20041110, 4),
        (0x1A01, 0, 4, 1),
        (0x1801, 2, 255, 1),
        (0x1801, 5, 500, 2),
        (0x1801, 1, 0x2A8, 4),
    ):
        assert bench.sdo_write(NODE, index, sub, value, size) == write_ok(index, sub)
    bench.nmt(NMT_START, NODE)
    bench.run_ms(1000)
    assert len(bench.times_of(0x2A8)) == 3  # at 0, 500 and 1000 ms (A7: ms)
    sim.set_register(ltmr.REG_TRIP_CODE, 4)
    bench.run_ms(10)
    frame = bench.frames_with(0x2A8)[-1]
    assert frame[:2] == b"\x04\x00"  # 451 trip code, on change


# ---------------------------------------------------------------------------- RPDO1 (digest 001 §7.2)


def test_rpdo1_runs_the_motor_forward_stops_and_reverses(bench):
    sim = operational(bench)
    bench.send(RPDO1, "01 00 00 00 00 00")  # 704 bit 0
    bench.run_ms(10)
    assert sim.lo1 and not sim.lo2
    status = int.from_bytes(bench.frames_with(TPDO1)[-1][:2], "little")
    assert status & Status1.ON and status & Status1.STARTING
    bench.run_ms(1500)
    assert sim.motor_running
    bench.send(RPDO1, "00 00 00 00 00 00")
    bench.run_ms(10)
    assert not sim.lo1 and not sim.motor_running
    bench.send(RPDO1, "02 00 00 00 00 00")  # 704 bit 1: reverse
    bench.run_ms(10)
    assert sim.lo2 and not sim.lo1


def test_rpdos_are_ignored_outside_operational(bench):
    sim = bench.ltmr(NODE)
    bench.send(RPDO1, "01 00 00 00 00 00")
    bench.run_ms(100)
    assert not sim.lo1 and sim.register(ltmr.REG_CONTROL_1) == 0


def test_an_rpdo_with_a_non_zero_reserved_word_still_sets_704(bench):
    sim = operational(bench)
    bench.send(RPDO1, "01 00 01 00 00 00")  # 703 must be 0: that entry is refused
    bench.run_ms(10)
    assert sim.lo1 and sim.register(703) == 0


# ---------------------------------------------------------------------------- PKW (digest 001 §2.5)


def _pkw(bench, words: pkw.PkwWords) -> list:
    bench.clear()
    bench.send(RPDO4, pkw.encode_frame(words))
    return [pkw.decode_frame(data) for data in bench.frames_with(TPDO4)]


def test_pkw_read_of_455_byte_by_byte(bench):
    sim = running_forward(bench)
    sim.set_load(100)
    bench.run_ms(10)
    # R_REG_16 reg 455, toggle 0: words 0x01C7 0x2500 (digest §2.5), A6 little-endian placement
    bench.clear()
    bench.send(RPDO4, "C7 01 00 25 00 00 00 00")
    assert bench.frames_with(TPDO4) == [bytes.fromhex("C7 01 00 25 C3 60 00 00")]


def test_pkw_toggle_rule(bench):
    sim = operational(bench)
    read_455 = pkw.request(455, pkw.R_REG_16, 0)
    assert _pkw(bench, read_455) == [pkw.response(read_455, (sim.register(455), 0))]
    assert _pkw(bench, read_455) == []  # same function byte: no new request
    again = pkw.request(455, pkw.R_REG_16, 1)  # the toggle inverted: a new request
    assert _pkw(bench, again) == [pkw.response(again, (sim.register(455), 0))]
    # the HMI way: function code 0, answered with 0, then the request again
    idle = pkw.request(455, pkw.NONE, 1)
    assert [r.function for r in _pkw(bench, idle)] == [pkw.NONE]
    assert _pkw(bench, again) == [pkw.response(again, (sim.register(455), 0))]


def test_pkw_writes_by_register_and_by_object(bench):
    sim = operational(bench)
    # W_REG_16 reg 652 := 50 (0x028C, 0x2A00, 0x0032)
    # the response echoes words 1-2; words 3-4 are "-" for a write (digest §2.5): 0 here
    assert _pkw(bench, pkw.PkwWords(0x028C, 0x2A00, 0x0032, 0)) == [pkw.PkwWords(0x028C, 0x2A00, 0, 0)]
    assert sim.register(ltmr.REG_FLC1) == 50
    # W_CO_16 2008:05 := 0x0001 run forward (0x2008, 0xBA05, 0x0001)
    assert _pkw(bench, pkw.PkwWords(0x2008, 0xBA05, 0x0001, 0)) == [pkw.PkwWords(0x2008, 0xBA05, 0, 0)]
    bench.run_ms(10)
    assert sim.lo1
    # R_CO_16 2004:06 (0x2004, 0x3506)
    status = pkw.PkwWords(0x2004, 0x3506)
    [response] = _pkw(bench, status)
    assert (response.w1, response.w2, response.w3) == (0x2004, 0x3506, sim.register(455))


def test_pkw_32_bit_read_is_msw_then_lsw(bench):
    sim = running_forward(bench)
    # R_REG_32 reg 500 average current (0x01F4, 0x2600): 80 % of 4.0 A = 320 x 0.01 A
    [response] = _pkw(bench, pkw.PkwWords(0x01F4, 0x2600))
    assert (response.function, response.w3, response.w4) == (pkw.R_REG_32, 0, 320)
    assert sim.register(501) == 320


@pytest.mark.parametrize(
    "request_words, abort",
    [
        (pkw.request(97, pkw.R_REG_16, 1), ABORT_NO_SUBINDEX),  # Forbidden register
        (pkw.request(900, pkw.R_REG_16, 1), ABORT_NO_OBJECT),  # no register 800-1199
        (pkw.request(455, pkw.W_REG_16, 1, data=(1, 0)), ABORT_READ_ONLY),
        (pkw.request(0x2009, pkw.R_CO_16, 1, 1), ABORT_NO_OBJECT),
        (pkw.PkwWords(455, 0xA700), ABORT_BAD_COMMAND),  # function code 0x27 is not defined
    ],
)
def test_pkw_errors_carry_the_sdo_abort_code_in_words_3_and_4(bench, request_words, abort):
    operational(bench)
    [response] = _pkw(bench, request_words)
    assert response == pkw.error_response(request_words, abort)
    assert response.w2 >> 8 == 0xCE  # toggle + 0x4E


def test_pkw_write_error_leaves_the_register_alone(bench):
    sim = operational(bench)
    request = pkw.request(682, pkw.W_REG_16, 0, data=(FallbackStrategy.BOTH_ON, 0))  # not in reverser mode
    [response] = _pkw(bench, request)
    # digest §2.5: "Error response to register request, abort 0x06090030": words 3-4 = 0x0609 0x0030
    assert (response.function, response.w3, response.w4) == (pkw.ERROR, 0x0609, 0x0030)
    assert sim.register(682) == ltmr_codes.FallbackStrategy.OFF


def test_pkw_is_read_only_on_the_local_configuration_variant(bench):
    sim = operational(bench, product_code=0x130)  # TeSys T MMC L (L343)
    write = pkw.request(652, pkw.W_REG_16, 0, data=(60, 0))
    assert _pkw(bench, write) == [pkw.error_response(write, ABORT_READ_ONLY)]
    assert sim.register(652) != 60
    read = pkw.request(652, pkw.R_REG_16, 1)
    assert _pkw(bench, read) == [pkw.response(read, (sim.register(652), 0))]


# ---------------------------------------------------------------------------- heartbeat


def test_heartbeat_producer_in_virtual_time(bench):
    sim = bench.ltmr(NODE)
    assert bench.sdo_write(NODE, 0x1017, 0, 1000, 2) == write_ok(0x1017, 0)  # 0x03E8 (digest §7.2)
    start = bench.clock.now_ns()
    bench.clear()
    bench.run_ms(3000)
    assert [t - start for t in bench.times_of(HEARTBEAT)] == [1000 * MS, 2000 * MS, 3000 * MS]
    bench.nmt(NMT_START, NODE)
    bench.run_ms(1000)
    assert bench.frames_with(HEARTBEAT)[-1] == b"\x05"
    assert sim.nmt_state == STATE_OPERATIONAL
