"""FC280_DRIVE and FC280_DSP402 (fblocks/vendor/fc280.st), driven cycle by
cycle in virtual time through a small ST program, with manual 003's
numbers and digest 003's vectors. FC280_PARAMETER and FC280_STORE:
test_fc280_parameter.py.

The test plays the drive and the CANopen master: it sets the status words
(what the TPDO brings) and CANOPEN_NODE[5] between cycles and reads the
words the RPDO would carry."""

from __future__ import annotations

import itertools

import pytest

from softplc.runtime.devices.fc280 import profile
from softplc.runtime.io.canopen import cia402
from softplc.runtime.st.profile import PROFILES

from .st_bench import CYCLE_MS, Bench

NODE = 5  # the digest's vectors are for node 5
MASTER = f"""
CANOPEN_NODE[{NODE}].Operational := operational;
CANOPEN_NODE[{NODE}].EmcyCode := emcyCode;
CANOPEN_NODE[{NODE}].EmcyData := emcyData;
"""
NODE_DECLS = "node : USINT; operational : BOOL; emcyCode : WORD; emcyData : DWORD;"

DRIVE_DECLS = f"""
    d : FC280_DRIVE;
    enable : BOOL; run : BOOL; reverse : BOOL; quickStop : BOOL; coast : BOOL; dcBrake : BOOL;
    freeze : BOOL; jog : BOOL; ramp2 : BOOL; reset : BOOL; relay01 : BOOL; relay04 : BOOL;
    preset : USINT; setup : USINT := 1; setpoint : REAL; sw : WORD; hiw : WORD;
    alarm : DWORD; alarm2 : DWORD; warning : DWORD; warning2 : DWORD;
    {NODE_DECLS}
"""
DRIVE_BODY = (
    MASTER
    + """
d(NODE := node, ENABLE := enable, RUN := run, REVERSE := reverse, QUICK_STOP := quickStop, COAST := coast,
  DC_BRAKE := dcBrake, FREEZE := freeze, JOG := jog, RAMP_2 := ramp2, FAULT_RESET := reset,
  RELAY_01 := relay01, RELAY_04 := relay04, PRESET := preset, SETUP := setup, SETPOINT := setpoint,
  STATUS_WORD := sw, ACTUAL_WORD := hiw, ALARM_WORD := alarm, ALARM_WORD_2 := alarm2,
  WARNING_WORD := warning, WARNING_WORD_2 := warning2);
"""
)

# the block's inputs and control_word()'s keywords
FLAGS = {
    "run": "run",
    "reverse": "reverse",
    "quickStop": "quick_stop",
    "coast": "coast",
    "dcBrake": "dc_brake",
    "freeze": "freeze",
    "jog": "jog",
    "ramp2": "ramp_2",
    "relay01": "relay_01",
    "relay04": "relay_04",
}


def drive() -> Bench:
    return Bench(DRIVE_DECLS, DRIVE_BODY)


def cw(b: Bench, fb: str = "d") -> int:
    return b[f"{fb}.CONTROL_WORD"]


# ---------------------------------------------------------------- FC280_DRIVE: the control word


def test_acceptance_vectors_of_digest_9_2():
    b = drive().step(enable=True, run=True)
    assert cw(b) == 0x047C  # defaults + run
    b.step(run=False)
    assert cw(b) == 0x043C  # ramp stop
    b.step(run=True, quickStop=True)
    assert cw(b) == 0x046C  # quick stop while running
    b.step(quickStop=False, reverse=True)
    assert cw(b) == 0x847C  # reverse
    b.step(reverse=False, coast=True)
    assert cw(b) == 0x0474  # coast: bit 3 cleared
    b.step(coast=False, setpoint=50.0)
    assert b["d.REFERENCE"] == 0x2000  # 50 %
    b.step(setpoint=-100.0)
    assert b["d.REFERENCE"] & 0xFFFF == 0xC000  # -100 % (§4.4.4)
    b.step(setpoint=100.0)
    assert b["d.REFERENCE"] == 0x4000  # 100 % (§4.4.4)


def test_every_combination_is_profile_control_word():
    b = drive().step(enable=True)
    for values in itertools.product((False, True), repeat=len(FLAGS)):
        asked = dict(zip(FLAGS, values))
        b.step(**asked)
        expected = profile.control_word(**{FLAGS[k]: v for k, v in asked.items()})
        assert cw(b) == expected, asked


def test_preset_and_setup_bits():
    b = drive().step(enable=True, run=True)
    for preset, setup in itertools.product(range(4), range(1, 5)):
        b.step(preset=preset, setup=setup)
        assert cw(b) == profile.control_word(run=True, preset=preset, setup=setup)
    assert cw(b.step(preset=3, setup=2)) == 0x247F  # preset 4 (3-10[3]), set-up 2
    assert cw(b.step(preset=9, setup=9)) == profile.control_word(run=True, preset=3, setup=4)  # limited
    assert cw(b.step(preset=0, setup=0)) == profile.control_word(run=True)  # set-up 1


def test_enable_false_is_a_valid_stop_word_never_0000():
    b = drive()
    for values in itertools.product((False, True), repeat=len(FLAGS)):
        asked = dict(zip(FLAGS, values))
        b.step(enable=False, **asked)
        kw = {FLAGS[k]: v for k, v in asked.items()}
        assert cw(b) == profile.control_word(**{**kw, "run": False, "jog": False}), asked
        assert cw(b) & profile.ControlWord.DATA_VALID
    b.step(**{**dict.fromkeys(FLAGS, False), "run": True})
    assert cw(b) == 0x043C  # ENABLE FALSE with RUN: 043C, not 047C (nor 0000)


def test_fault_reset_bit_7_held_until_the_trip_clears():
    b = drive().step(enable=True, run=True, sw=0x0208)  # tripped, bus control
    assert cw(b) == 0x047C and b["d.FAULT"]
    b.step(reset=True)
    assert cw(b) == profile.control_word(run=True, reset=True) == 0x04FC  # digest 4.5: 047C -> 04FC
    b.step(3, reset=False)
    assert cw(b) == 0x04FC and b["d.RESETTING"]  # the drive has not taken it yet
    b.step(sw=0x0607)  # the trip is gone
    assert cw(b) == 0x047C and not b["d.RESETTING"]


def test_a_reset_without_a_trip_is_one_cycle():
    # one cycle is one transmitted word when the RPDO goes out every scan
    b = drive().step(sw=0x0607)
    b.step(reset=True)
    assert cw(b) == 0x04BC  # digest 4.5: 043C -> 04BC -> 043C
    b.step()
    assert cw(b) == 0x043C
    b.step(reset=False).step(reset=True)
    assert cw(b) == 0x04BC  # a new edge, a new pulse


def test_a_trip_that_stays_ends_the_reset_after_a_second():
    b = drive().step(sw=0x0248)  # trip lock: only a power cycle clears it
    b.step(reset=True)
    b.step(1000 // CYCLE_MS - 1)
    assert cw(b) == 0x04BC
    b.step()
    assert cw(b) == 0x043C and not b["d.RESETTING"]


@pytest.mark.parametrize(
    "percent",
    [0.0, 25.0, -25.0, 33.333, -12.345, 0.003, 0.0031, 150.0, 199.99, 200.0, 250.0, -199.99, -200.0, -1e9, 1e9],
)
def test_reference_is_profile_reference_raw(percent):
    b = drive().step(setpoint=percent)
    f32 = b["setpoint"]  # REAL: the value as the block sees it
    assert b["d.REFERENCE"] & 0xFFFF == profile.reference_raw(f32)


def test_reference_of_nan_is_zero():
    assert drive().step(setpoint=float("nan"))["d.REFERENCE"] == 0


# ---------------------------------------------------------------- FC280_DRIVE: status and diagnostics


def status(b: Bench, fb: str = "d") -> set:
    names = ("READY", "ENABLED", "RUNNING", "AT_SETPOINT", "WARNING", "FAULT", "TRIP_LOCK", "BUS_CONTROL")
    return {n for n in names if b[f"{fb}.{n}"]}


@pytest.mark.parametrize(
    "word, flags",
    [
        # digest 003 §4.6 decodes
        (0x0F07, {"READY", "ENABLED", "AT_SETPOINT", "BUS_CONTROL", "RUNNING"}),
        (0x0607, {"READY", "ENABLED", "BUS_CONTROL"}),
        (0x0208, {"FAULT", "BUS_CONTROL"}),
        (0x0248, {"FAULT", "TRIP_LOCK", "BUS_CONTROL"}),
        (0x0087, {"READY", "ENABLED", "WARNING"}),
        (0x0001, set()),  # control ready only: not READY
    ],
)
def test_status_word_2643h(word, flags):
    assert status(drive().step(sw=word)) == flags


@pytest.mark.parametrize("word, percent", [(0x4000, 100.0), (0x2000, 50.0), (0xC000, -100.0), (0x0000, 0.0)])
def test_actual_value_is_scaled_as_the_reference(word, percent):
    b = drive().step(hiw=word)
    assert b["d.ACTUAL"] == percent == profile.reference_percent(word)


def test_node_supervision():
    b = drive().step(node=NODE, operational=False, sw=0x0F07, hiw=0x4000, enable=True, run=True)
    assert not b["d.NODE_OK"] and status(b) == set() and b["d.ACTUAL"] == 0.0  # stale: read as 0
    assert cw(b) == 0x047C  # still computed
    b.step(operational=True)
    assert b["d.NODE_OK"] and "RUNNING" in status(b) and b["d.ACTUAL"] == 100.0
    b.step(node=0, operational=False)
    assert not b["d.NODE_OK"] and "RUNNING" in status(b)  # NODE 0: not watched, taken as it is
    b.step(node=200)
    assert not b["d.NODE_OK"] and not b["d.RUNNING"]  # no such node id: no fault, nothing trusted


def test_fault_text_from_the_alarm_words_before_the_emcy():
    b = drive().step(node=NODE, operational=True, sw=0x0208)
    assert b["d.FAULT_TEXT"] == "" and b["d.WARNING_TEXT"] == ""
    b.step(emcyCode=0x8130, emcyData=0x01)  # D29: life guard error, byte 3 = alarm word 1
    assert b["d.EMCY_CODE"] == 0x8130
    assert b["d.FAULT_TEXT"] == "Life guard error or heartbeat error" and b["d.WARNING_TEXT"] == ""
    b.step(alarm=0x00400010)  # 16-90: control word timeout and fieldbus fault
    assert b["d.FAULT_TEXT"] == "Control word timeout"  # the lowest bit
    b.step(alarm=0, alarm2=0x00000800)
    assert b["d.FAULT_TEXT"] == "Speed limit"
    b.step(alarm2=0, emcyCode=0, emcyData=0)  # D30: the alarm is gone
    assert b["d.FAULT_TEXT"] == "" and b["d.EMCY_CODE"] == 0


def test_warning_text_from_the_warning_words_or_a_warning_emcy():
    b = drive().step(node=NODE, operational=True, sw=0x0287)
    b.step(emcyCode=0x8120, emcyData=0x08)  # error passive, reported as a warning (8-07 = [2])
    assert b["d.WARNING_TEXT"] == "CAN in error passive mode" and b["d.FAULT_TEXT"] == ""
    b.step(warning=0x00400000)
    assert b["d.WARNING_TEXT"] == "Fieldbus fault"  # warning 34
    b.step(warning=0, warning2=0x00040000)
    assert b["d.WARNING_TEXT"] == "Fan warning"
    b.step(operational=False)  # stale words; the EMCY is the last one heard
    assert b["d.WARNING_TEXT"] == "CAN in error passive mode"


# ---------------------------------------------------------------- FC280_DSP402

DSP_DECLS = f"""
    e : FC280_DSP402;
    enable : BOOL; run : BOOL; reverse : BOOL; quickStop : BOOL; reset : BOOL; jog : BOOL;
    rpm : INT; sw : WORD; actualRpm : INT; alarm : DWORD;
    {NODE_DECLS}
"""
DSP_BODY = (
    MASTER
    + """
e(NODE := node, ENABLE := enable, RUN := run, REVERSE := reverse, QUICK_STOP := quickStop,
  FAULT_RESET := reset, JOG := jog, SETPOINT_RPM := rpm, STATUS_WORD := sw, ACTUAL_RPM := actualRpm,
  ALARM_WORD := alarm);
"""
)


def dsp() -> Bench:
    return Bench(DSP_DECLS, DSP_BODY)


def test_dsp402_switch_on_and_run_tabelle_4_3():
    b = dsp().step(sw=0x0240, enable=True, run=True, rpm=1500)
    assert cw(b, "e") == 0x0006 and b["e.STATE"] == cia402.State.SWITCH_ON_DISABLED
    b.step(sw=0x0231)
    assert cw(b, "e") == 0x0007
    b.step(sw=0x0233)
    assert cw(b, "e") == 0x007F  # 000F + vl bits 4-6 (A22)
    b.step(sw=0x0237)
    assert cw(b, "e") == 0x007F and b["e.ENABLED"] and b["e.READY"]
    assert b["e.REFERENCE"] == 1500  # D26: 6042h = 05DCh
    b.step(run=False)
    assert cw(b, "e") == 0x000F  # enabled, stopped (D26's word)
    b.step(enable=False)
    assert cw(b, "e") == 0x0007  # transition 5: ramp down


def test_dsp402_jog_reverse_and_quick_stop():
    b = dsp().step(sw=0x0237, enable=True, jog=True)
    assert cw(b, "e") == 0x080F  # §4.3.3: bits 0-3, bit 4 = 0
    b.step(run=True)
    assert cw(b, "e") == 0x007F  # RUN wins
    b.step(reverse=True)
    assert cw(b, "e") == 0x807F
    b.step(reverse=False, jog=False, quickStop=True)
    assert cw(b, "e") == 0x0002  # transition 11
    b.step(sw=0x0207)
    assert b["e.QUICK_STOP_ACTIVE"] and cw(b, "e") == 0x0002


def test_dsp402_fault_reset_023f_0080_0240():
    b = dsp().step(sw=0x0237, enable=True, run=True)
    b.step(sw=0x023F)
    assert b["e.FAULT"] and cw(b, "e") == 0x0000  # A20: bit 3
    b.step(reset=True)
    assert cw(b, "e") == 0x0080 and b["e.RESETTING"]  # A21
    b.step(sw=0x0240, reset=False)
    assert not b["e.FAULT"] and cw(b, "e") == 0x0006


def test_dsp402_status_bits_and_texts():
    b = dsp().step(sw=0x4637, actualRpm=-750, alarm=0x20000000)
    assert b["e.RUNNING"] and b["e.AT_SETPOINT"] and b["e.BUS_CONTROL"]  # bits 14 (A19), 10, 9
    assert b["e.ACTUAL"] == -750.0
    assert b["e.FAULT_TEXT"] == "Drive initialised"
    b.step(sw=0x0237)
    assert not b["e.RUNNING"] and not b["e.AT_SETPOINT"]


def test_dsp402_with_the_node_lost_falls_back_to_0000():
    b = dsp().step(node=NODE, operational=True, sw=0x0237, enable=True, run=True)
    assert cw(b, "e") == 0x007F and b["e.NODE_OK"]
    b.step(operational=False)
    assert cw(b, "e") == 0x0000 and not b["e.NODE_OK"] and b["e.STATE"] == 0


# ---------------------------------------------------------------- every profile


@pytest.mark.parametrize("profile_name", list(PROFILES))
def test_the_blocks_compile_in_every_profile_without_warnings(profile_name):
    decls = "d : FC280_DRIVE; e : FC280_DSP402; p : FC280_PARAMETER; s : FC280_STORE; i : UINT;"
    body = "d(ENABLE := TRUE, RUN := TRUE); e(); p(); s(); i := FC280_PARAMETER_INDEX('8-03', 0, 0);"
    b = Bench(decls, body, profile_name).step()
    assert b.runner.program.warnings == []
    assert b["d.CONTROL_WORD"] == 0x047C and b["i"] == 0x2323
