"""The manual's example telegrams (manual 002 §2.6.6, digest §5.1), byte for
byte: the master's RTU requests and the simulated drive's answers as they
crossed the line, in memory (virtual time) and on the pseudo-terminal cable."""

from __future__ import annotations

import pytest

from softplc.runtime.io.modbus.link import LinkSettings, ModbusError, ModbusLink, Transaction
from softplc.runtime.io.modbus.wire import CODEC_FRAMES

from .plant import WIRES, plant_config

# M1/M2: read ID 6 (status word) of unit 1; the drive answers 0 (a DA1 that is
# stopped with its STO open: no bit set, no fault). M3: write 1 to ID 1
# (control word: run); the drive echoes the request.
READ_ID6 = bytes.fromhex("01 03 00 05 00 01 94 0B")
ANSWER_0 = bytes.fromhex("01 03 02 00 00 B8 44")
WRITE_RUN = bytes.fromhex("01 06 00 00 00 01 48 0A")

PROGRAM = """
PROGRAM P
VAR
    n : INT;
    status AT %IW0 : WORD;
    readNow AT %QX0.0 : BOOL;
    writeNow AT %QX0.1 : BOOL;
    command AT %QW2 : WORD;
END_VAR
n := n + 1;
readNow := n >= 2;
IF n >= 5 THEN
    command := 1;
    writeNow := TRUE;
END_IF
END_PROGRAM
"""

CHANNELS = [
    {
        "name": "status",
        "unit": 1,
        "function": 3,
        "offset": 5,
        "count": 1,
        "read_to": "%IW0",
        "trigger": "edge",
        "edge": "%QX0.0",
    },
    {
        "name": "control",
        "unit": 1,
        "function": 6,
        "offset": 0,
        "write_from": "%QW2",
        "trigger": "edge",
        "edge": "%QX0.1",
    },
]


@pytest.mark.parametrize("wire", WIRES)
def test_manual_telegrams_byte_for_byte(plants, tmp_path, wire):
    plant = plants(plant_config(tmp_path, PROGRAM, program="P", transport="rtu", channels=CHANNELS, wire=wire))
    plant.drive(1).di1 = False  # STO open: status word 0
    cable = plant.line.cable
    plant.run_ms(30)  # the read goes out at the tick after its edge
    assert cable.sent_by_master() == READ_ID6
    assert cable.sent_by_slave() == ANSWER_0
    assert plant["%IW0"] == 0
    plant.run_ms(50)
    assert cable.sent_by_master() == READ_ID6 + WRITE_RUN
    assert cable.sent_by_slave() == ANSWER_0 + WRITE_RUN  # FC 06 answers with the request
    drive = plant.drive(1)
    assert drive.register(1) == 1  # the run command arrived ...
    assert not drive.running  # ... and a drive without its STO does not start
    assert [(c.stats.requests, c.stats.errors) for c in plant.master.channels] == [(1, 0), (1, 0)]


def test_a_frame_with_a_bad_crc_gets_no_answer(plants, tmp_path):
    """The drive stays silent on a CRC error (digest §2.3); the channel says
    RESPONSE_TIMEOUT. Written straight onto the line, as a noisy cable would."""
    import serial

    plant = plants(plant_config(tmp_path, "PROGRAM P\nEND_PROGRAM\n", program="P", transport="rtu", wire="port"))
    plant.run_ms(10)
    cable = plant.line.cable
    with serial.Serial(cable.master_port, 115200, timeout=0.2) as port:
        port.write(READ_ID6[:-1] + b"\x00")  # last CRC byte wrong
        assert port.read(7) == b""
        port.write(READ_ID6)
        answer = port.read(7)
    assert answer[:3] == bytes.fromhex("01 03 02") and len(answer) == 7  # the next good frame is answered


def test_in_memory_a_frame_with_a_bad_crc_is_counted_and_not_answered(plants, tmp_path):
    plant = plants(plant_config(tmp_path, "PROGRAM P\nEND_PROGRAM\n", program="P", transport="rtu"))
    server = plant.line.server
    assert server.exchange(READ_ID6[:-1] + b"\x00") is None  # last CRC byte wrong
    assert server.malformed == 1
    assert server.exchange(READ_ID6[:3]) is None  # cut short
    assert server.malformed == 2
    plant.drive(1).di1 = False
    assert server.exchange(READ_ID6) == ANSWER_0  # the next good frame is answered
    assert server.malformed == 2


def test_in_memory_tcp_frames_carry_the_mbap_header(plants, tmp_path):
    channels = [{**CHANNELS[0], "trigger": "cyclic", "period": "100ms"}]
    del channels[0]["edge"]
    plant = plants(plant_config(tmp_path, PROGRAM, program="P", transport="tcp", channels=channels))
    plant.drive(1).di1 = False
    seen = []
    exchange = plant.line.server.exchange
    plant.line.server.exchange = lambda frame: seen.append(frame) or exchange(frame)
    plant.run_ms(250)  # requests at 0 (the start), 100 and 200 ms
    # transaction id (one more each time), protocol 0, length 6, unit 1, then the PDU: FC 03, ID 6, one register
    assert len(seen) == 3
    assert all(f[2:] == bytes.fromhex("0000 0006 01 03 0005 0001") for f in seen)
    tids = [int.from_bytes(f[:2], "big") for f in seen]
    assert tids == [tids[0], tids[0] + 1, tids[0] + 2]


def test_in_memory_a_silent_unit_times_out_in_virtual_time(plants, tmp_path):
    """The channel's error arrives when the timeout (100 ms) has run out on
    the virtual clock, and the line sends nothing else meanwhile."""
    channels = [
        {"name": "one", "unit": 1, "function": 3, "offset": 5, "count": 1, "read_to": "%IW0", "period": "20ms"},
    ]
    plant = plants(
        plant_config(
            tmp_path, "PROGRAM P\nEND_PROGRAM\n", program="P", transport="rtu", channels=channels, timeout="100ms"
        )
    )
    plant.run_ms(50)
    one = plant.master.channels[0]
    assert one.stats.ok and one.stats.requests == 3  # 0, 20, 40 ms
    plant.engine.simulators["da1_1"].inject("silent", None, True)
    sent = plant.line.cable.sent_by_master()
    plant.run_ms(20)  # the request at 60 ms is waiting for its answer
    assert one.stats.requests == 3 and one.stats.ok
    plant.run_until(lambda: one.stats.requests == 4, 200)
    assert plant.now_ms == pytest.approx(160, abs=10)  # sent at 60 ms + 100 ms of timeout
    assert one.stats.last_error == ModbusError.RESPONSE_TIMEOUT and not one.stats.ok
    assert len(plant.line.cable.sent_by_master()) == len(sent) + len(READ_ID6)  # retries = 0: sent once


def test_in_memory_requests_are_framed_once_and_each_write_carries_its_values(plants, tmp_path):
    """In memory the link keeps the frames pymodbus built for the last
    requests (link.py, _transact_in_memory) and starts afresh when it holds
    CODEC_FRAMES of them: more writes than that, each of a new value, each
    reach the drive with their own value; a repeated read is the same frame
    every time and gets the answer of the moment."""
    plant = plants(plant_config(tmp_path, "PROGRAM P\nEND_PROGRAM\n", program="P", transport="rtu"))
    link = ModbusLink(LinkSettings("drives", "rtu", baud=115200), server=plant.line.server)
    drive = plant.drive(1)
    for value in range(CODEC_FRAMES + 10):  # ID 2, the speed reference in 0.1 Hz
        outcome = link.transact(Transaction(unit=1, function=6, offset=1, values=(value,)), 0)
        assert outcome.error == ModbusError.OK and drive.register(2) == value
    read_id6 = Transaction(unit=1, function=3, offset=5, count=1)
    drive.di1 = False
    assert link.transact(read_id6, 0).values == [0]
    plant.line.cable.clear()
    drive.di1 = True
    assert link.transact(read_id6, 0).values == [0x00A1]
    assert plant.line.cable.sent_by_master() == READ_ID6
