"""The simulated FC 280 on the virtual bus, driven as a CANopen master drives
it: raw frames from the test's endpoint, byte for byte against manual 003
and the vectors of digest 003 (§8.1 M1-M16 from the manual, §8.2 D1-D30
derived; node 5 unless stated), in virtual time only."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.fc280 import DEVICE as FC280
from softplc.runtime.devices.fc280.model import CONTROL_WORD_TIMEOUT, DRIVE_INITIALISED, FIELDBUS_FAULT
from softplc.runtime.devices.fc280.sim import LOAD_SIGNATURE, SAVE_SIGNATURE, Fc280Simulator
from softplc.runtime.io.canopen.cia301 import (
    ABORT_DEVICE_STATE,
    ABORT_NO_OBJECT,
    ABORT_NO_SUBINDEX,
    ABORT_READ_ONLY,
    ABORT_VALUE_HIGH,
    ABORT_VALUE_LOW,
    ABORT_VALUE_RANGE,
    NMT_RESET_NODE,
    NMT_START,
    STATE_OPERATIONAL,
    STATE_PRE_OPERATIONAL,
)

from ...io.canopen.bench import MS, abort_frame, write_ok
from .test_model import TABELLE_4_3

NODE = 5
TPDO1, TPDO3, RPDO1, EMCY, HEARTBEAT, SDO_TX = 0x185, 0x385, 0x205, 0x085, 0x705, 0x585
ABORT_NOT_STORED = 0x08000020


def fc280(bench, node: int = NODE, **parameters) -> Fc280Simulator:
    params = {number.replace("_", "-"): value for number, value in parameters.items()}
    return bench.add(
        Fc280Simulator(node, settings=bench.settings, clock=bench.clock, pump=bench.pump, parameters=params)
    )


def remap(bench, pdo: int, cob: int, entries, node: int = NODE) -> None:
    """CiA 301 remapping as a master does it (digest 003 §2.2): invalidate,
    sub 0 := 0, the entries, sub 0 := n, validate; every step confirmed."""
    comm, mapping = pdo, pdo + 0x200
    steps = [(comm, 1, 0x80000000 | cob, 4), (mapping, 0, 0, 1)]
    steps += [(mapping, sub, entry, 4) for sub, entry in enumerate(entries, start=1)]
    steps += [(mapping, 0, len(entries), 1), (comm, 1, cob, 4)]
    for index, sub, value, size in steps:
        assert bench.sdo_write(node, index, sub, value, size) == write_ok(index, sub), (hex(index), sub)


def fc_pdos(bench) -> None:
    """RPDO1 = 2690h + 2692h, TPDO1 = 2643h + 2645h (D28)."""
    remap(bench, 0x1400, RPDO1, [0x26900010, 0x26920010])
    remap(bench, 0x1800, TPDO1, [0x26430010, 0x26450010])


def operational(bench, **parameters) -> Fc280Simulator:
    sim = fc280(bench, **parameters)
    fc_pdos(bench)
    bench.send(0x000, "01 05")  # D1
    assert sim.nmt_state == STATE_OPERATIONAL
    return sim


def sending(bench, data: str, ms: int, every_ms: int = 100) -> None:
    """The master's RPDO1, cyclic."""
    for _ in range(ms // every_ms):
        bench.send(RPDO1, data)
        bench.run_ms(every_ms)


# ---------------------------------------------------------------------------- NMT, heartbeat, COB-IDs


def test_boot_up_and_heartbeat(bench):
    sim = fc280(bench)
    assert bench.frames == [(0, HEARTBEAT, b"\x00")]  # D4
    assert sim.nmt_state == STATE_PRE_OPERATIONAL
    assert bench.sdo(NODE, "2B 17 10 00 E8 03 00 00") == bytes.fromhex("60 17 10 00 00 00 00 00")  # D15
    bench.send(0x000, "01 05")  # D1
    bench.clear()
    bench.run_ms(3000)
    assert bench.frames_with(HEARTBEAT) == [b"\x05"] * 3  # D5: 1000 ms
    assert bench.times_of(HEARTBEAT) == [1000 * MS, 2000 * MS, 3000 * MS]
    bench.send(0x000, "80 00")  # D2
    assert sim.nmt_state == STATE_PRE_OPERATIONAL
    bench.clear()
    bench.send(0x000, "82 05")  # D3: reset communication
    assert bench.frames == [(3000 * MS, HEARTBEAT, b"\x00")] and sim.read(0x1017) == 0


@pytest.mark.parametrize("node, tpdo, cob", [(3, 0x1802, 0x383), (5, 0x1800, 0x185)])
def test_tpdo_cob_ids(bench, node, tpdo, cob):
    # M1: 383h is TPDO3 of node 3; M2: 185h is TPDO1 of node 5 (§3.1.2)
    fc280(bench, node)
    remap(bench, tpdo, cob, [0x26430010], node)
    bench.clear()
    bench.nmt(NMT_START, node)
    assert bench.frames_with(cob) == [bytes.fromhex("03 06")]


def test_sdo_cob_ids(bench):
    # M3: 604h is an SDO received by node 4; it answers on 584h
    fc280(bench, 4)
    bench.clear()
    bench.send(0x604, "40 00 10 00 00 00 00 00")
    assert bench.frames_with(0x584) == [bytes.fromhex("43 00 10 00 92 01 01 00")]


# ---------------------------------------------------------------------------- SDO (D6-D24)


def test_sdo_requests_and_responses(bench):
    sim = fc280(bench)
    # M4 / D6: read 0-01 Sprache, index 2001h sub 0; a 1-byte answer
    assert bench.sdo(NODE, "40 01 20 00 00 00 00 00") == bytes.fromhex("4F 01 20 00 00 00 00 00")
    assert bench.sdo(NODE, "2B 23 23 00 0A 00 00 00") == bytes.fromhex("60 23 23 00 00 00 00 00")  # D7, D8
    assert bench.sdo(NODE, "2F 24 23 00 05 00 00 00") == write_ok(0x2324, 0)  # D9
    assert bench.sdo(NODE, "2F 2A 23 00 00 00 00 00") == write_ok(0x232A, 0)  # D10
    assert bench.sdo(NODE, "2F 21 23 00 02 00 00 00") == write_ok(0x2321, 0)  # D11
    assert bench.sdo(NODE, "2F 56 23 00 01 00 00 00") == write_ok(0x2356, 0)  # D12
    assert [sim.parameter(n) for n in ("8-03", "8-04", "8-10", "8-01", "8-54")] == [10, 5, 0, 2, 1]
    assert bench.sdo(NODE, "2B 0C 10 00 64 00 00 00") == write_ok(0x100C, 0)  # D16
    assert bench.sdo(NODE, "2F 0D 10 00 03 00 00 00") == write_ok(0x100D, 0)  # D17
    assert bench.sdo(NODE, "40 FF 2F 00 00 00 00 00") == bytes.fromhex("80 FF 2F 00 00 00 02 06")  # D22
    assert bench.sdo(NODE, "23 05 10 00 80 00 00 40") == bytes.fromhex("80 05 10 00 30 00 09 06")  # D23
    assert bench.sdo(NODE, "40 00 10 00 00 00 00 00") == bytes.fromhex("43 00 10 00 92 01 01 00")  # D24


def test_device_type_fields(bench):
    fc280(bench)
    value = int.from_bytes(bench.sdo_read(NODE, 0x1000, 0)[4:], "little")
    assert (value >> 24, (value >> 16) & 0xFF, value & 0xFFFF) == (0, 1, 402)  # M14 (Tabelle 7.2)


def test_the_fc_profile_over_sdo(bench):
    fc280(bench)
    assert bench.sdo(NODE, "2B 92 26 00 00 20 00 00") == write_ok(0x2692, 0)  # D19: 50 %
    assert bench.sdo(NODE, "2B 90 26 00 7C 04 00 00") == write_ok(0x2690, 0)  # D18: 047C
    bench.run_ms(1500)  # 25 Hz with 3-41 = 3 s for 50 Hz
    assert bench.sdo(NODE, "40 43 26 00 00 00 00 00") == bytes.fromhex("4B 43 26 00 07 0F 00 00")  # D20, D21
    assert bench.sdo_read(NODE, 0x2645, 0) == bytes.fromhex("4B 45 26 00 00 20 00 00")  # HIW 50 %


def test_a_segmented_upload_of_15_40(bench):
    fc280(bench)
    assert bench.sdo(NODE, "40 04 26 00 00 00 00 00") == bytes.fromhex("41 04 26 00 06 00 00 00")
    assert bench.sdo(NODE, "60 00 00 00 00 00 00 00") == b"\x03FC 280\x00"


@pytest.mark.parametrize(
    "index, sub, value, size, code",
    [
        (0x2324, 0, 6, 1, ABORT_VALUE_HIGH),  # 8-04 [0]..[5]
        (0x2323, 0, 0, 2, ABORT_VALUE_LOW),  # 8-03 at least 0.1 s (A27)
        (0x23EA, 0, 0, 1, ABORT_VALUE_LOW),  # 10-02 [1 - 127]
        (0x23EA, 0, 128, 1, ABORT_VALUE_HIGH),
        (0x232A, 0, 5, 1, ABORT_VALUE_RANGE),  # 8-10: [0], [7] (A16)
        (0x23E9, 0, 19, 1, ABORT_VALUE_RANGE),  # 10-01: no [19] (A33)
        (0x2136, 1, 10001, 2, ABORT_VALUE_HIGH),  # 3-10[0] (sub-index 1, A35) at most 100 %
        (0x2136, 9, 0, 2, ABORT_NO_SUBINDEX),  # 3-10 has elements [0]-[7] at sub-indices 1-8
        (0x2643, 0, 0, 2, ABORT_READ_ONLY),  # 16-03
        (0x269A, 0, 0, 4, ABORT_READ_ONLY),  # 16-90
        (0x1014, 0, 0x85, 4, ABORT_READ_ONLY),  # read-only (Tabelle 7.1)
        (0x6040, 0, 6, 2, ABORT_DEVICE_STATE),  # not in the FC profile (§4.4.1)
        (0x1010, 1, 0x12345678, 4, ABORT_NOT_STORED),  # no "save"
        (0x1010, 3, SAVE_SIGNATURE, 4, ABORT_NOT_STORED),  # reserved
        (0x1011, 4, SAVE_SIGNATURE, 4, ABORT_NOT_STORED),  # no "load"
        (0x1005, 0, 0x20000080, 4, ABORT_VALUE_RANGE),  # 29-bit (Tabelle 7.4)
        (0x1800, 5, 32768, 2, ABORT_VALUE_HIGH),  # event timer at most 32767 (§4.1.5)
        (0x2700, 0, 0, 1, ABORT_NO_OBJECT),
    ],
)
def test_refused_writes_abort_with_the_codes_of_tabelle_8_8(bench, index, sub, value, size, code):
    sim = fc280(bench)
    before = sim.parameter("8-04")
    assert bench.sdo_write(NODE, index, sub, value, size) == abort_frame(index, sub, code)
    assert sim.parameter("8-04") == before


def test_the_dsp_402_objects_are_refused_in_the_fc_profile_and_vice_versa(bench):
    fc280(bench)
    assert bench.sdo_write(NODE, 0x6042, 0, 1500, 2) == abort_frame(0x6042, 0, ABORT_DEVICE_STATE)
    assert bench.sdo_read(NODE, 0x6041, 0) == bytes.fromhex("4B 41 60 00 00 00 00 00")  # Startzustand
    assert bench.sdo_write(NODE, 0x232A, 0, 7, 1) == write_ok(0x232A, 0)
    assert bench.sdo_write(NODE, 0x2690, 0, 0x047C, 2) == abort_frame(0x2690, 0, ABORT_DEVICE_STATE)
    assert bench.sdo_read(NODE, 0x6041, 0) == bytes.fromhex("4B 41 60 00 00 02 00 00")  # transition 0


# ---------------------------------------------------------------------------- PDOs (D25-D28)


def test_rpdo_and_tpdo_of_the_fc_profile(bench):
    sim = operational(bench)
    assert bench.frames_with(TPDO1) == [bytes.fromhex("03 06 00 00")]  # on NMT start: 0603, 0 %
    bench.send(RPDO1, "7C 04 00 40")  # CTW 047C, REF 100 %
    bench.run_ms(3000)
    assert sim.model.output_hz == 50.0
    assert bench.frames_with(TPDO1)[-1] == bytes.fromhex("07 0F 00 40")  # D27: STW 0F07, MAV 100 %
    bench.send(RPDO1, "7C 04 00 20")  # D25: REF 50 %
    bench.run_ms(1500)
    assert bench.frames_with(TPDO1)[-1] == bytes.fromhex("07 0F 00 20")


def test_tpdo_inhibit_time_during_a_ramp(bench):
    # M9: 300 x 0.1 ms = 30 ms between two TPDOs (the factory inhibit time, §4.1.4)
    operational(bench)
    bench.clear()
    bench.send(RPDO1, "7C 04 00 40")
    bench.run_ms(1000)
    times = bench.times_of(TPDO1)
    assert [b - a for a, b in zip(times, times[1:])] == [30 * MS] * (len(times) - 1)
    # 0: every change goes out (every 10 ms step of the bench); 32767 (3.2767 s) is the most
    assert bench.sdo_write(NODE, 0x1800, 1, 0x80000185, 4) == write_ok(0x1800, 1)
    assert bench.sdo_write(NODE, 0x1800, 3, 32768, 2) == abort_frame(0x1800, 3, ABORT_VALUE_HIGH)
    assert bench.sdo_write(NODE, 0x1800, 3, 32767, 2) == write_ok(0x1800, 3)
    assert bench.sdo_write(NODE, 0x1800, 3, 0, 2) == write_ok(0x1800, 3)
    assert bench.sdo_write(NODE, 0x1800, 1, 0x185, 4) == write_ok(0x1800, 1)
    bench.clear()
    bench.send(RPDO1, "3C 04 00 40")  # ramp stop
    bench.run_ms(500)
    times = bench.times_of(TPDO1)
    assert [b - a for a, b in zip(times, times[1:])] == [10 * MS] * (len(times) - 1)


def test_tpdo_event_timer(bench):
    # M10: 0 = off; a value is in ms (§4.1.5)
    operational(bench)
    bench.clear()
    bench.run_ms(1000)
    assert bench.frames_with(TPDO1) == []
    assert bench.sdo_write(NODE, 0x1800, 5, 200, 2) == write_ok(0x1800, 5)
    bench.clear()
    bench.run_ms(1000)
    assert len(bench.frames_with(TPDO1)) == 5
    assert bench.sdo_write(NODE, 0x1800, 5, 32767, 2) == write_ok(0x1800, 5)


def test_dsp_402_over_pdos(bench):
    sim = fc280(bench, **{"8-10": 7})
    remap(bench, 0x1400, RPDO1, [0x60400010, 0x60420010])  # D28
    remap(bench, 0x1800, TPDO1, [0x60410010, 0x60440010])
    bench.nmt(NMT_START, NODE)
    assert bench.frames_with(TPDO1)[-1] == bytes.fromhex("00 02 00 00")  # not ready to switch on
    for word, status in ((0x0000, 0x0240), (0x0006, 0x0231), (0x0007, 0x0233)):
        bench.send(RPDO1, word.to_bytes(2, "little") + b"\0\0")
        bench.run_ms(30)
        assert bench.frames_with(TPDO1)[-1][:2] == status.to_bytes(2, "little")
    bench.send(RPDO1, "0F 00 DC 05")  # D26: CW 000F, 1500 RPM
    bench.run_ms(30)
    assert bench.frames_with(TPDO1)[-1] == bytes.fromhex("37 02 00 00")  # A22: enabled, standing
    bench.send(RPDO1, "7F 00 DC 05")
    bench.run_ms(3000)
    assert bench.frames_with(TPDO1)[-1] == bytes.fromhex("37 47 DC 05")  # 1500 RPM, at the reference
    assert sim.read(0x6043) == 1500 and sim.model.output_hz == 50.0


def test_every_transition_of_tabelle_4_3_over_sdo(bench):
    # M11: the control word into 6040h, the status word read back from 6041h
    sim = fc280(bench)
    assert bench.sdo_write(NODE, 0x232A, 0, 7, 1) == write_ok(0x232A, 0)  # 8-10 [7] (A16)
    assert bench.sdo_read(NODE, 0x6041, 0)[4:6] == bytes.fromhex("00 02")  # transition 0
    for transition, word, status in TABELLE_4_3:
        assert bench.sdo_write(NODE, 0x6040, 0, word, 2) == write_ok(0x6040, 0)
        assert (transition, bench.sdo_read(NODE, 0x6041, 0)[4:6]) == (transition, status.to_bytes(2, "little"))
    for word in (0x0006, 0x000F):
        assert bench.sdo_write(NODE, 0x6040, 0, word, 2) == write_ok(0x6040, 0)
    sim.model.over_current()
    assert bench.sdo_read(NODE, 0x6041, 0)[4:6] == bytes.fromhex("3F 02")  # 13, 14 (A20)
    assert bench.sdo_write(NODE, 0x6040, 0, 0x0000, 2) == write_ok(0x6040, 0)
    assert bench.sdo_read(NODE, 0x6041, 0)[4:6] == bytes.fromhex("3F 02")  # 15 needs bit 7's edge (A21)
    assert bench.sdo_write(NODE, 0x6040, 0, 0x0080, 2) == write_ok(0x6040, 0)
    assert bench.sdo_read(NODE, 0x6041, 0)[4:6] == bytes.fromhex("40 02")  # 15


def test_the_vl_dimension_factor(bench):
    sim = fc280(bench, **{"8-10": 7})
    assert bench.sdo_write(NODE, 0x604C, 1, 60, 4) == write_ok(0x604C, 1)  # 1 unit = 60 RPM (rev/s)
    assert bench.sdo_write(NODE, 0x604C, 2, 0, 4) == abort_frame(0x604C, 2, ABORT_VALUE_RANGE)
    for word in (0x0006, 0x000F, 0x007F):
        assert bench.sdo_write(NODE, 0x6040, 0, word, 2) == write_ok(0x6040, 0)
    assert bench.sdo_write(NODE, 0x6042, 0, 25, 2) == write_ok(0x6042, 0)  # 25 rev/s = 1500 RPM
    bench.run_ms(3000)
    assert sim.model.output_hz == 50.0 and sim.read(0x6044) == 25


# ---------------------------------------------------------------------------- the drive on the bus


def test_negative_reference_with_reverse_runs_forward(bench):
    sim = operational(bench)
    bench.send(RPDO1, "7C 84 00 E0")  # M16: CTW 847C (start, reversing), REF -50 %
    bench.run_ms(2000)
    assert sim.model.output_hz == 25.0 and bench.frames_with(TPDO1)[-1] == bytes.fromhex("07 0F 00 20")
    bench.send(RPDO1, "7C 04 00 E0")  # without reversing: backwards
    bench.run_ms(3500)
    assert sim.model.output_hz == -25.0 and bench.frames_with(TPDO1)[-1] == bytes.fromhex("07 0F 00 E0")


def test_fc_profile_sequence_with_its_status_words(bench):
    sim = operational(bench)
    steps = [
        # (the last TPDO of a step may wait for the 30 ms inhibit time)
        ("7C 04 00 20", 1530, "07 0F 00 20", 25.0),  # run at 50 %: 3-41 3 s for 50 Hz
        ("6C 04 00 20", 530, "07 06 00 00", 0.0),  # quick stop: 3-81 1 s for 50 Hz
        ("7C 04 00 20", 1530, "07 0F 00 20", 25.0),
        ("74 04 00 20", 30, "03 06 00 00", 0.0),  # coast: bit 2 = 0 at once
        ("7C 04 00 20", 1530, "07 0F 00 20", 25.0),
        ("3C 04 00 20", 1530, "07 06 00 00", 0.0),  # ramp stop: 3-42
        ("3C 00 00 20", 100, "07 06 00 00", 0.0),  # no data valid: nothing
        ("7C 00 00 20", 1000, "07 06 00 00", 0.0),
        ("7C 06 00 08", 1280, "07 0F 00 08", 6.25),  # ramp 2 to 12.5 %: 3-51 10 s for 50 Hz
        ("78 04 00 20", 30, "07 06 00 00", 0.0),  # DC brake: 0 Hz at once
    ]
    for rpdo, ms, tpdo, hz in steps:
        bench.send(RPDO1, rpdo)
        bench.run_ms(ms)
        assert (rpdo, bench.frames_with(TPDO1)[-1].hex(" ").upper(), sim.model.output_hz) == (rpdo, tpdo, hz)


@pytest.mark.parametrize(
    "reaction, hz, status, alarm",
    [
        (0, 25.0, 0x0F07, 0),  # [0] Aus: the last word stays in force
        (1, 25.0, 0x0E87, 0),  # [1] freeze: held (not following the reference), warning
        (2, 0.0, 0x0687, 0),  # [2] Stopp, warning
        (3, 10.0, 0x0F87, 0),  # [3] Festdrz. (JOG) 3-19
        (4, 65.0, 0x0B87, 0),  # [4] Max. Drehzahl 4-14: at the limit
        (5, 0.0, 0x0608, 0x10),  # [5] Stopp und Alarm: tripped, alarm 16-90 00000010h
    ],
)
def test_control_word_timeout_reactions(bench, reaction, hz, status, alarm):
    sim = operational(bench, **{"8-04": reaction})
    sending(bench, "7C 04 00 20", 2000)  # 8-03 = 1 s: the master's RPDO every 100 ms
    bench.run_ms(4000)  # then silence
    assert sim.model.output_hz == hz
    assert (sim.parameter("16-03"), sim.parameter("16-90")) == (status, alarm)
    assert sim.parameter("16-92") == (0x10 if reaction not in (0, 5) else 0)  # [5]: the alarm instead
    sending(bench, "FC 04 00 20", 200)  # communication back, with a reset edge for [5]
    sending(bench, "7C 04 00 20", 3000)
    assert sim.model.output_hz == 25.0 and sim.parameter("16-92") == 0 and sim.parameter("16-90") == 0


def _guarded_master(bench, word: str, ms: int) -> list[float]:
    """The master for ms: the RPDO1 word and a guarding request every 100 ms;
    the output frequency after each step."""
    seen = []
    for _ in range(ms // 100):
        bench.send(RPDO1, word)
        bench.guard(NODE)
        bench.run_ms(100)
        seen.append(bench.devices[0].model.output_hz)
    return seen


@pytest.mark.parametrize("reaction", [2, 5])
def test_a_short_cut_at_speed_restarts_with_stop_but_not_with_stop_and_alarm(bench, reaction):
    # issue 33: cut 1 s at 25 Hz, the master sending 047C throughout. 8-04 (chapter 6):
    # [2] "Stopp und bei Wiederaufnahme der Kommunikation automatischer Wiederanlauf";
    # [5] "Motor stoppt, setzt den Frequenzumrichter anschließend zurück: über den Feldbus ..."
    sim = operational(bench, **{"8-04": reaction, "8-03": 5, "3-42": 200})  # 8-03 0.5 s, ramp down 2 s
    assert bench.sdo_write(NODE, 0x100C, 0, 100, 2) == write_ok(0x100C, 0)  # guarding 100 ms x 3
    assert bench.sdo_write(NODE, 0x100D, 0, 3, 1) == write_ok(0x100D, 0)
    _guarded_master(bench, "7C 04 00 20", 3000)
    assert sim.model.output_hz == 25.0
    sim.unplug()
    _guarded_master(bench, "7C 04 00 20", 1000)
    sim.plug()
    assert sim.nmt_state == STATE_PRE_OPERATIONAL  # life guarding: CiA 301 without 1029h
    bench.nmt(NMT_START, NODE)  # the master starts the node it hears again
    at_return = sim.model.output_hz
    assert 0 < at_return < 25.0  # still ramping down (3-42: 25 Hz in 1 s)
    after = _guarded_master(bench, "7C 04 00 20", 3000)
    if reaction == 2:
        assert after[-1] == 25.0 and sim.parameter("16-90") == 0  # the automatic restart
        return
    # [5]: down to standstill and stays there on the 047C, tripped (16-03 bit 3, Tabelle 4.10)
    assert all(b <= a for a, b in zip([at_return, *after], after)) and after[-1] == 0.0
    # as the master reads them: 16-03 (2643h) 0608h, tripped, not running (Tabelle 4.10); 16-90
    # (269Ah) bit 4 "Steuerwort-Timeout" (8-03) and bit 22 "Feldbus-Fehl." (guarding, A6), Tabelle 8.1
    assert bench.sdo_read(NODE, 0x2643, 0)[4:6] == bytes.fromhex("08 06")
    assert int.from_bytes(bench.sdo_read(NODE, 0x269A, 0)[4:8], "little") == CONTROL_WORD_TIMEOUT | FIELDBUS_FAULT
    # the fieldbus reset: a rising edge of control word bit 7 (§4.4.2), then it runs again
    _guarded_master(bench, "FC 04 00 20", 100)
    after = _guarded_master(bench, "7C 04 00 20", 2000)
    assert after[-1] == 25.0 and sim.parameter("16-90") == 0 and not sim.parameter("16-03") & 0x0008


def test_life_guarding_a_lost_master_with_emcy(bench):
    # M12: 100Ch x 100Dh = 300 ms; 8-04 [5]: the alarm; 8-07 [1]: an EMCY (D29, D30)
    sim = fc280(bench, **{"8-04": 5, "8-07": 1})
    assert bench.sdo(NODE, "2B 0C 10 00 64 00 00 00") == write_ok(0x100C, 0)  # D16: 100 ms
    assert bench.sdo(NODE, "2F 0D 10 00 03 00 00 00") == write_ok(0x100D, 0)  # D17: x 3
    bench.nmt(NMT_START, NODE)
    for _ in range(5):
        assert bench.guard(NODE) == [bytes([0x05 | (0x80 if _ % 2 else 0)])]
        bench.run_ms(100)
    bench.clear()
    took = bench.run_until(lambda: sim.guarding_lost, 1000, "life guarding")
    assert took == 210  # the first 10 ms step more than 300 ms after the last request
    assert bench.frames_with(EMCY) == [bytes.fromhex("30 81 01 01 00 00 40 00")]  # D29
    assert sim.parameter("16-90") == FIELDBUS_FAULT and sim.parameter("16-92") == 0  # the alarm, not warning 34
    assert sim.nmt_state == STATE_PRE_OPERATIONAL  # CiA 301 without 1029h
    assert bench.sdo_read(NODE, 0x1001, 0)[4] == 0x01 and bench.sdo_read(NODE, 0x603F, 0)[4:6] == b"\x30\x81"
    bench.guard(NODE)  # the master is back
    assert not sim.model.master_lost and sim.parameter("16-90") == FIELDBUS_FAULT
    bench.clear()
    assert bench.sdo_write(NODE, 0x2690, 0, 0x043C, 2) == write_ok(0x2690, 0)
    assert bench.sdo_write(NODE, 0x2690, 0, 0x04BC, 2) == write_ok(0x2690, 0)  # reset edge
    bench.run_ms(10)
    assert bench.frames_with(EMCY) == [bytes(8)]  # D30: "mit dem Inhalt 0"
    assert bench.sdo_read(NODE, 0x1001, 0)[4] == 0


@pytest.mark.parametrize(
    "alarm, emcy, line",
    [
        # Tabelle 8.1 bit 2 "Erdschluss"; Tabelle 8.9 has no earth-fault row, 2240h (CiA 402:
        # earth leakage inside the device) is the one of its two "Kurzschluss" rows that fits (A5)
        (0x00000004, "40 22 01 01 04 00 00 00", "EMCY 2240h Earth fault, error register 01h"),
        # Tabelle 8.1 bit 12 "Kurzschluss": 2130h "Kurzschluss"
        (0x00001000, "30 21 01 01 00 10 00 00", "EMCY 2130h Short circuit, error register 01h"),
    ],
)
def test_earth_fault_and_short_circuit_emcy_say_what_tripped(bench, alarm, emcy, line):
    sim = fc280(bench, **{"8-07": 1})
    bench.nmt(NMT_START, NODE)
    bench.clear()
    sim.model.trip(alarm)
    bench.run_ms(10)
    assert bench.frames_with(EMCY) == [bytes.fromhex(emcy)]
    frame = bench.frames_with(EMCY)[0]
    # the line the CANopen master logs for it (Device.emcy_text)
    logged = FC280.emcy_text(int.from_bytes(frame[:2], "little"), frame[2], frame[3:])
    assert logged.startswith(line + " (generic error); active: alarm word 16-90")


def test_emcy_follows_8_07(bench):
    sim = fc280(bench)
    bench.nmt(NMT_START, NODE)
    sim.model.over_current()
    bench.run_ms(10)
    assert bench.frames_with(EMCY) == []  # [0] Deaktiviert: none (the factory setting)
    sim.model.press_reset()
    assert bench.sdo_write(NODE, 0x2327, 0, 2, 1) == write_ok(0x2327, 0)  # [2] alarms and warnings
    sim.model.warn(0x00000040)  # torque limit
    bench.run_ms(10)
    sim.model.over_current()
    bench.run_ms(10)
    sim.model.clear_warning(0x00000040)
    sim.model.press_reset()
    bench.run_ms(10)
    assert bench.frames_with(EMCY) == [
        bytes.fromhex("02 83 00 08 40 00 00 00"),  # 8302 torque limited, warning word 1
        bytes.fromhex("10 23 01 09 20 00 00 00"),  # 2310 over-current, alarm word 1 (+ the warning)
        bytes(8),
    ]
    assert bench.sdo_write(NODE, 0x2327, 0, 1, 1) == write_ok(0x2327, 0)  # [1] alarms only
    bench.clear()
    sim.model.warn(0x00000040)
    bench.run_ms(10)
    assert bench.frames_with(EMCY) == []


# ---------------------------------------------------------------------------- save and restore


def test_save_and_restore_across_a_power_cycle(bench):
    sim = fc280(bench)
    assert SAVE_SIGNATURE.to_bytes(4, "little") == b"save" and LOAD_SIGNATURE.to_bytes(4, "little") == b"load"
    assert bench.sdo_write(NODE, 0x2323, 0, 50, 2) == write_ok(0x2323, 0)  # 8-03 5 s
    assert bench.sdo_write(NODE, 0x1017, 0, 500, 2) == write_ok(0x1017, 0)
    sim.power_cycle()
    bench.pump.settle()
    assert (sim.parameter("8-03"), sim.read(0x1017)) == (10, 0)  # RAM only (§3.1.5)
    assert bench.sdo_write(NODE, 0x2323, 0, 50, 2) == write_ok(0x2323, 0)
    assert bench.sdo_write(NODE, 0x1017, 0, 500, 2) == write_ok(0x1017, 0)
    assert bench.sdo(NODE, "23 10 10 01 73 61 76 65") == write_ok(0x1010, 1)  # D13, M5
    assert bench.sdo_read(NODE, 0x1010, 1) == bytes.fromhex("43 10 10 01 01 00 00 00")  # saves on command
    sim.power_cycle()
    bench.pump.settle()
    bench.clear()
    bench.run_ms(1000)
    assert sim.parameter("8-03") == 50 and bench.frames_with(HEARTBEAT) == [b"\x7f", b"\x7f"]  # 1017h 500 ms
    assert bench.sdo(NODE, "23 11 10 01 6C 6F 61 64") == write_ok(0x1011, 1)  # D14, M6
    assert sim.parameter("8-03") == 50  # after the next power cycle (§7.1.10)
    bench.nmt(NMT_RESET_NODE, NODE)
    assert sim.parameter("8-03") == 50 and sim.read(0x1017) == 500
    sim.power_cycle()
    bench.pump.settle()
    assert (sim.parameter("8-03"), sim.read(0x1017)) == (10, 0)
    assert sim.parameter("16-90") == DRIVE_INITIALISED and sim.parameter("10-02") == NODE  # Alarm 80
    assert bench.sdo_read(NODE, 0x2643, 0)[4:6] == bytes.fromhex("08 06")  # tripped


def test_save_sub_2_keeps_communication_only_sub_4_drive_only(bench):
    sim = fc280(bench)
    assert bench.sdo_write(NODE, 0x2324, 0, 2, 1) == write_ok(0x2324, 0)
    assert bench.sdo_write(NODE, 0x100C, 0, 100, 2) == write_ok(0x100C, 0)
    assert bench.sdo_write(NODE, 0x6048, 2, 7, 2) == write_ok(0x6048, 2)
    assert bench.sdo_write(NODE, 0x1010, 2, SAVE_SIGNATURE, 4) == write_ok(0x1010, 2)
    sim.power_cycle()
    assert (sim.parameter("8-04"), sim.read(0x100C), sim.read(0x6048, 2)) == (0, 100, 3)
    assert bench.sdo_write(NODE, 0x2324, 0, 2, 1) == write_ok(0x2324, 0)
    assert bench.sdo_write(NODE, 0x6048, 2, 7, 2) == write_ok(0x6048, 2)
    assert bench.sdo_write(NODE, 0x100C, 0, 200, 2) == write_ok(0x100C, 0)
    assert bench.sdo_write(NODE, 0x1010, 4, SAVE_SIGNATURE, 4) == write_ok(0x1010, 4)
    sim.power_cycle()
    assert (sim.parameter("8-04"), sim.read(0x100C), sim.read(0x6048, 2)) == (2, 100, 7)
    assert bench.sdo_write(NODE, 0x1011, 2, LOAD_SIGNATURE, 4) == write_ok(0x1011, 2)
    sim.power_cycle()
    assert (sim.parameter("8-04"), sim.read(0x100C), sim.parameter("16-90")) == (2, 0, 0)


# ---------------------------------------------------------------------------- test hooks


def test_presets_set_parameter_and_the_cable(bench):
    sim = fc280(bench, **{"8-03": 50, "3-10": [100, 200]})
    assert sim.parameter("8-03") == 50 and sim.parameter("3-10", 1) == 200
    assert bench.sdo_read(NODE, 0x2136, 2) == bytes.fromhex("4B 36 21 02 C8 00 00 00")  # 3-10[1] (A35)
    assert bench.sdo_read(NODE, 0x2136, 0) == bytes.fromhex("4F 36 21 00 08 00 00 00")  # 8 elements
    sim.set_parameter("8-04", 3)
    assert bench.sdo_read(NODE, 0x2324, 0) == bytes.fromhex("4F 24 23 00 03 00 00 00")
    assert sim.parameter("10-02") == NODE and sim.parameter("10-01") == 21  # the bench's, 250 kbit/s
    sim.unplug()
    bench.clear()
    bench.send(0x605, "40 00 10 00 00 00 00 00")
    assert bench.frames == []
    sim.plug()
    assert bench.sdo_read(NODE, 0x1000, 0) == bytes.fromhex("43 00 10 00 92 01 01 00")
