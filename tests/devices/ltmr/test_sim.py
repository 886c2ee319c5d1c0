"""The simulated LTMR on the virtual bus, driven as a CANopen master drives
it: raw frames from the test's endpoint, byte-level checks against manual
001 and the vectors of digest 001 (§3.4 SDO, §2.5 PKW, §7.2 PDO frames;
node 40 = 0x28), virtual time only."""

from __future__ import annotations

import threading

import canopen
import pytest

from softplc.runtime.devices.ltmr import bits as ltmr_bits
from softplc.runtime.devices.ltmr import codes as ltmr_codes
from softplc.runtime.devices.ltmr import pkw
from softplc.runtime.devices.ltmr import registers as ltmr
from softplc.runtime.devices.ltmr.bits import Status1, Status2, TripEnable1, TripRegister1
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
    NMT_PRE_OPERATIONAL,
    NMT_START,
    NMT_STOP,
    STATE_OPERATIONAL,
    STATE_PRE_OPERATIONAL,
    STATE_STOPPED,
)
from softplc.runtime.io.canopen.eds import shipped_eds

from ...io.canopen.bench import MS, abort_frame, write_ok

NODE = 40
TPDO1, RPDO1, TPDO4, RPDO4, EMCY, HEARTBEAT = 0x1A8, 0x228, 0x4A8, 0x528, 0x0A8, 0x728


def _operational(bench, **kwargs):
    sim = bench.ltmr(NODE, **kwargs)
    bench.nmt(NMT_START, NODE)
    return sim


def _running_forward(bench, **kwargs):
    sim = _operational(bench, **kwargs)
    bench.send(RPDO1, "01 00 00 00 00 00")
    bench.run_ms(1500)  # past the 1 s start
    return sim


def _watched(bench, fallback, registers=None):
    """Operational, watching the master's heartbeat (0x1016:01 = 0x007F01F4, 500 ms:
    digest 001 §1.5) with 682 = fallback, the motor running forward."""
    sim = bench.ltmr(NODE, registers={ltmr.REG_NETWORK_FALLBACK: fallback, **(registers or {})})
    assert bench.sdo_write(NODE, 0x1016, 1, 0x007F01F4, 4) == write_ok(0x1016, 1)
    bench.master_heartbeat_ms = 100
    bench.run_ms(100)
    bench.nmt(NMT_START, NODE)
    bench.send(RPDO1, "01 00 00 00 00 00")
    bench.run_ms(1500)
    return sim


def _words(value: int) -> bytes:
    return value.to_bytes(2, "little")


def _tpdo1(sim) -> bytes:
    return b"".join(_words(sim.register(r)) for r in (455, 456, 457, 459))


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
    assert bench.frames_with(TPDO1) == [_tpdo1(sim)]
    bench.send(RPDO1, "01 00 00 00 00 00")
    bench.run_ms(1500)
    # digest 001 §7.2: 455 = 0x6083, 456 = 0, 457 = 0x0005, 459 = 0x1005 -> 83 60 00 00 05 00 05 10;
    # here 455 also has bit 6 "controller power" (A13) and word 4 is 459, not 458 (A1)
    assert bench.frames_with(TPDO1)[-1] == bytes.fromhex("C3 60 00 00 05 00 05 10")


# ---------------------------------------------------------------------------- SDO (digest 001 §3.4)


def test_sdo_read_of_status_register_1(bench):
    sim = _running_forward(bench)
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
    sim = _running_forward(bench)
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
    sim = _operational(bench)
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
    sim = _operational(bench)
    bench.send(RPDO1, "01 00 01 00 00 00")  # 703 must be 0: that entry is refused
    bench.run_ms(10)
    assert sim.lo1 and sim.register(703) == 0


# ---------------------------------------------------------------------------- PKW (digest 001 §2.5)


def _pkw(bench, words: pkw.PkwWords) -> list:
    bench.clear()
    bench.send(RPDO4, pkw.encode_frame(words))
    return [pkw.decode_frame(data) for data in bench.frames_with(TPDO4)]


def test_pkw_read_of_455_byte_by_byte(bench):
    sim = _running_forward(bench)
    sim.set_load(100)
    bench.run_ms(10)
    # R_REG_16 reg 455, toggle 0: words 0x01C7 0x2500 (digest §2.5), A6 little-endian placement
    bench.clear()
    bench.send(RPDO4, "C7 01 00 25 00 00 00 00")
    assert bench.frames_with(TPDO4) == [bytes.fromhex("C7 01 00 25 C3 60 00 00")]


def test_pkw_toggle_rule(bench):
    sim = _operational(bench)
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
    sim = _operational(bench)
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
    sim = _running_forward(bench)
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
    _operational(bench)
    [response] = _pkw(bench, request_words)
    assert response == pkw.error_response(request_words, abort)
    assert response.w2 >> 8 == 0xCE  # toggle + 0x4E


def test_pkw_write_error_leaves_the_register_alone(bench):
    sim = _operational(bench)
    request = pkw.request(682, pkw.W_REG_16, 0, data=(FallbackStrategy.BOTH_ON, 0))  # not in reverser mode
    [response] = _pkw(bench, request)
    # digest §2.5: "Error response to register request, abort 0x06090030": words 3-4 = 0x0609 0x0030
    assert (response.function, response.w3, response.w4) == (pkw.ERROR, 0x0609, 0x0030)
    assert sim.register(682) == ltmr_codes.FallbackStrategy.OFF


def test_pkw_is_read_only_on_the_local_configuration_variant(bench):
    sim = _operational(bench, product_code=0x130)  # TeSys T MMC L (L343)
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


# ---------------------------------------------------------------------------- communication loss


@pytest.mark.parametrize(
    "strategy, mode, outputs",
    [
        (FallbackStrategy.HOLD, OperatingMode.REVERSER_2W, (True, False)),
        (FallbackStrategy.RUN, OperatingMode.TWO_STEP_2W, (False, True)),
        (FallbackStrategy.OFF, OperatingMode.REVERSER_2W, (False, False)),
        (FallbackStrategy.BOTH_ON, OperatingMode.OVERLOAD_2W, (True, True)),
        (FallbackStrategy.LO1_ON, OperatingMode.REVERSER_2W, (True, False)),
        (FallbackStrategy.LO2_ON, OperatingMode.REVERSER_2W, (False, True)),
    ],
)
def test_heartbeat_loss_applies_the_fallback_of_682(bench, strategy, mode, outputs):
    sim = _watched(bench, strategy, {ltmr.REG_OPERATING_MODE: mode, ltmr.REG_CONTROL_SETTING: 1 << 9})
    assert sim.lo1 or sim.lo2
    bench.master_heartbeat_ms = 0  # the PLC is gone
    bench.run_ms(600)
    assert sim.nmt_state == STATE_PRE_OPERATIONAL  # 0x1029:01 = 0
    assert (sim.lo1, sim.lo2) == outputs
    assert sim.register(ltmr.REG_STATUS_2) & Status2.NETWORK_COMM_LOSS  # 456 bit 8
    assert sim.register(ltmr.REG_ALARM_CODE) == ltmr_codes.ALARM_NETWORK_COMM  # 632 bit 15 (default on)
    assert not sim.register(ltmr.REG_NETWORK_PORT_STATUS) & ltmr_bits.NetworkPortStatus.COMMUNICATING


def test_communication_comes_back_then_the_next_rpdo_ends_the_fallback(bench):
    sim = _watched(bench, FallbackStrategy.OFF)
    sim.unplug()  # the cable is cut
    bench.run_ms(700)
    assert not sim.lo1
    sim.plug()
    bench.run_ms(200)
    assert sim.register(ltmr.REG_STATUS_2) & Status2.NETWORK_COMM_LOSS  # not Operational yet
    bench.nmt(NMT_START, NODE)
    bench.run_ms(10)
    assert not sim.register(ltmr.REG_STATUS_2) & Status2.NETWORK_COMM_LOSS
    assert sim.register(ltmr.REG_ALARM_CODE) == 0
    assert (
        sim.register(ltmr.REG_NETWORK_PORT_STATUS)
        == ltmr_bits.NetworkPortStatus.CONNECTED | ltmr_bits.NetworkPortStatus.COMMUNICATING
    )
    assert not sim.lo1  # the fallback holds until an RPDO
    status2 = int.from_bytes(bench.frames_with(TPDO1)[-1][2:4], "little")
    assert not status2 & Status2.NETWORK_COMM_LOSS  # TPDO1 on entering Operational
    bench.send(RPDO1, "01 00 00 00 00 00")
    bench.run_ms(10)
    assert sim.lo1


def test_entering_pre_operational_by_nmt_applies_the_fallback(bench):
    # manual 001 L75-90: "(4) (7) Enter_Pre-Operational_State and apply fallback"
    sim = _running_forward(bench, registers={ltmr.REG_NETWORK_FALLBACK: FallbackStrategy.OFF})
    bench.nmt(NMT_PRE_OPERATIONAL, NODE)
    bench.run_ms(10)
    assert not sim.lo1
    assert sim.register(ltmr.REG_STATUS_2) & Status2.NETWORK_COMM_LOSS
    bench.send(RPDO1, "01 00 00 00 00 00")  # not Operational: ignored
    bench.run_ms(10)
    assert not sim.lo1
    bench.nmt(NMT_START, NODE)
    bench.send(RPDO1, "01 00 00 00 00 00")
    bench.run_ms(10)
    assert sim.lo1


def test_stop_by_nmt_holds_when_682_says_hold(bench):
    sim = _running_forward(bench, registers={ltmr.REG_NETWORK_FALLBACK: FallbackStrategy.HOLD})
    bench.nmt(NMT_STOP, NODE)
    bench.run_ms(1000)
    assert sim.nmt_state == STATE_STOPPED
    assert sim.lo1
    assert sim.register(ltmr.REG_STATUS_2) & Status2.NETWORK_COMM_LOSS


def test_network_port_trip_109_stays_until_reset_and_sends_an_emcy(bench):
    sim = _watched(
        bench, FallbackStrategy.OFF, {ltmr.REG_TRIP_ENABLE_1: TripEnable1.NETWORK_PORT | TripEnable1.THERMAL_OVERLOAD}
    )
    bench.master_heartbeat_ms = 0
    bench.run_ms(600)
    assert sim.register(ltmr.REG_TRIP_CODE) == ltmr_codes.TRIP_NETWORK_COMM
    assert sim.register(ltmr.REG_TRIP_REGISTER_1) & TripRegister1.NETWORK_PORT
    assert bench.frames_with(EMCY)[-1] == bytes.fromhex("00 10 01 6D 00 00 00 00")  # A22: 0x1000, 109
    bench.master_heartbeat_ms = 100
    bench.nmt(NMT_START, NODE)
    bench.run_ms(200)
    assert sim.register(ltmr.REG_TRIP_CODE) == ltmr_codes.TRIP_NETWORK_COMM
    bench.send(RPDO1, "08 00 00 00 00 00")  # remote reset
    bench.run_ms(10)
    assert sim.register(ltmr.REG_TRIP_CODE) == 0
    assert bench.frames_with(EMCY)[-1] == bytes(8)  # error reset


# ---------------------------------------------------------------------------- overload, reset, self test


def test_an_overload_trips_with_code_4_and_an_emcy_then_a_remote_reset(bench):
    sim = _running_forward(bench)
    bench.clear()
    sim.set_load(400)
    bench.run_until(lambda: sim.register(ltmr.REG_TRIP_CODE) != 0, 60_000, "thermal trip")
    assert sim.register(ltmr.REG_TRIP_CODE) == ltmr_codes.TRIP_THERMAL_OVERLOAD
    assert sim.register(ltmr.REG_TRIP_REGISTER_1) & TripRegister1.THERMAL_OVERLOAD
    assert not sim.lo1
    assert bench.frames_with(EMCY) == [bytes.fromhex("00 10 01 04 00 00 00 00")]  # A22 choice
    status = int.from_bytes(bench.frames_with(TPDO1)[-1][:2], "little")
    assert status & Status1.TRIP and status & Status1.TRIPPED and not status & Status1.RUNNING
    assert bench.sdo_read(NODE, 0x1001, 0) == bytes.fromhex("4F 01 10 00 01 00 00 00")
    assert bench.sdo_read(NODE, 0x1003, 1) == bytes.fromhex("43 03 10 01 00 10 00 00")
    sim.set_load(80)
    bench.send(RPDO1, "00 00 00 00 00 00")
    bench.run_until(lambda: sim.register(455) & Status1.RESET_AUTHORIZED, 300_000, "reset authorized")
    assert sim.register(ltmr.REG_THERMAL_CAPACITY) < 75  # 608
    bench.send(RPDO1, "08 00 00 00 00 00")  # 704 bit 3, digest §7.2
    bench.run_ms(10)
    assert sim.register(ltmr.REG_TRIP_CODE) == 0
    assert bench.frames_with(EMCY)[-1] == bytes(8)
    bench.send(RPDO1, "01 00 00 00 00 00")
    bench.run_ms(10)
    assert sim.lo1


def test_manual_reset_mode_needs_the_button(bench):
    sim = _running_forward(bench, registers={ltmr.REG_GENERAL_CONFIG_2: ResetMode.MANUAL})
    sim.set_load(720)
    bench.run_until(lambda: sim.register(ltmr.REG_TRIP_CODE) != 0, 20_000, "thermal trip")
    bench.send(RPDO1, "00 00 00 00 00 00")
    bench.run_until(lambda: sim.register(455) & Status1.RESET_AUTHORIZED, 300_000, "reset authorized")
    bench.send(RPDO1, "08 00 00 00 00 00")
    bench.run_ms(10)
    assert sim.register(ltmr.REG_TRIP_CODE) == ltmr_codes.TRIP_THERMAL_OVERLOAD
    sim.press_reset()
    bench.run_ms(10)
    assert sim.register(ltmr.REG_TRIP_CODE) == 0


def test_self_test_by_rpdo(bench):
    sim = _operational(bench)
    bench.send(RPDO1, "20 00 00 00 00 00")  # 704 bit 5
    bench.run_ms(10)
    assert sim.register(ltmr.REG_TRIP_CODE) == ltmr_codes.TRIP_TEST  # 10
    assert sim.register(ltmr.REG_TRIP_REGISTER_1) & TripRegister1.TEST  # 452 bit 9
    assert bench.frames_with(EMCY)[-1] == bytes.fromhex("00 10 01 0A 00 00 00 00")


# ---------------------------------------------------------------------------- power


def test_a_power_cycle_forgets_the_commands_and_keeps_the_settings(bench):
    sim = _running_forward(bench)
    assert bench.sdo_write(NODE, 0x2007, 0x03, 60, 2) == write_ok(0x2007, 0x03)
    bench.clear()
    sim.power_cycle()
    bench.run_ms(10)
    assert bench.frames_with(HEARTBEAT) == [b"\x00"]
    assert sim.nmt_state == STATE_PRE_OPERATIONAL
    assert not sim.lo1 and sim.register(ltmr.REG_CONTROL_1) == 0
    assert sim.register(ltmr.REG_FLC1) == 60


def test_a_trip_outlives_a_reset_communication_and_is_reported_again(bench):
    sim = _operational(bench)
    bench.send(RPDO1, "20 00 00 00 00 00")  # self test: trip 10
    bench.run_ms(10)
    bench.clear()
    bench.send(0x000, "82 28")  # NMT reset communication
    bench.run_ms(10)
    assert bench.frames_with(HEARTBEAT) == [b"\x00"]
    assert sim.register(ltmr.REG_TRIP_CODE) == ltmr_codes.TRIP_TEST
    assert bench.frames_with(EMCY) == [bytes.fromhex("00 10 01 0A 00 00 00 00")]
    assert sim.read(0x1001) == 0x01


# ---------------------------------------------------------------------------- canopen's own master side


class _MasterNetwork(canopen.Network):
    """canopen's Network on the bench's master endpoint."""

    def __init__(self, endpoint) -> None:
        super().__init__(bus=None)
        self.endpoint = endpoint
        endpoint.add_handler(lambda msg: self.notify(msg.arbitration_id, bytes(msg.data), msg.timestamp))

    def send_message(self, can_id: int, data: bytes, remote: bool = False) -> None:
        self.endpoint.send(can_id, bytes(data), remote=remote)


def _blocking(bench, work):
    """Run canopen's blocking SDO client in a thread while the pump delivers the frames."""
    outcome = {}

    def run():
        try:
            outcome["value"] = work()
        except BaseException as exc:  # handed to the test thread
            outcome["error"] = exc

    thread = threading.Thread(target=run)
    bench.pump.add_busy(thread.is_alive)
    thread.start()
    bench.pump.settle()
    thread.join()
    bench.pump.remove_busy(thread.is_alive)
    if "error" in outcome:
        raise outcome["error"]
    return outcome.get("value")


def test_canopens_sdo_client_works_against_the_simulator(bench):
    """A real master's client: expedited and segmented SDO, a CiA 301 remap of
    TPDO2 and canopen's own read-back of it. (canopen's Map.save() cannot remap
    here: it sizes an ARRAY from sub-index 0, which the procedure has just set
    to 0, and the manual declares 0x1A0x as ARRAY, manual 001 §4.)"""
    sim = bench.ltmr(NODE)
    network = _MasterNetwork(bench.master)
    with shipped_eds("ltmr.eds") as path:
        remote = canopen.RemoteNode(NODE, str(path))
    network.add_node(remote)

    def configure():
        hardware = remote.sdo.upload(0x1009, 0)  # segmented: "M1.0-ES1.0" (manual 001 §4)
        remote.sdo[0x2007][0x03].raw = 50  # FLC1 := 50 %
        remote.sdo[0x1801][1].raw = 0x800002A8  # 1. invalidate TPDO2
        remote.sdo[0x1A01][0].raw = 0  # 2. no entries
        remote.sdo[0x1A01][1].raw = 0x20040210  # 3. 451 trip code
        remote.sdo[0x1A01][2].raw = 0x20041010  #    465 thermal capacity
        remote.sdo[0x1A01][0].raw = 2  # 4. two entries
        remote.sdo[0x1801][1].raw = 0x2A8  # 5. valid
        remote.tpdo.read()
        return hardware, [(var.index, var.subindex) for var in remote.tpdo[2].map]

    hardware, mapped = _blocking(bench, configure)
    assert hardware == b"M1.0-ES1.0"
    assert mapped == [(0x2004, 0x02), (0x2004, 0x10)]
    assert sim.register(ltmr.REG_FLC1) == 50
    sim.set_register(ltmr.REG_TRIP_CODE, ltmr_codes.TRIP_THERMAL_OVERLOAD)
    bench.clear()
    bench.nmt(NMT_START, NODE)
    assert bench.frames_with(0x2A8) == [bytes.fromhex("04 00 00 00")]


# ---------------------------------------------------------------------------- injected faults


def test_injected_faults_load_and_unplug(bench):
    # what [[sim]] faults = [{ fault = "load", value = 400, for = ... }] and "unplug" do
    sim = _running_forward(bench)
    assert sim.register(466) == 80  # 466 average current ratio, % FLC: the model's default load
    sim.inject("load", 400.0, True)
    bench.run_ms(100)
    assert sim.register(466) == 400  # a jam draws 400 % FLC
    sim.inject("load", 400.0, False)
    bench.run_ms(100)
    assert sim.register(466) == 80  # back to the load before
    sim.inject("unplug", None, True)
    bench.clear()
    bench.run_ms(300)
    assert bench.frames == [] and not sim.plugged
    sim.inject("unplug", None, False)
    assert sim.plugged
    with pytest.raises(ValueError, match="no fault 'over_current'"):
        sim.inject("over_current", None, True)
