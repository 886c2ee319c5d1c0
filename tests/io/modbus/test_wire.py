"""The in-memory wire (runtime/io/modbus/wire.py) remembers the frames it
framed and decoded: a repeated frame must still get the answer of the
moment, a bad frame must be dropped every time, and TCP answers must carry
the transaction id of their own request."""

from __future__ import annotations

from softplc.runtime.io.modbus.wire import MemoryCable
from softplc.runtime.sim.null_modem import RECORD_BYTES

from .plant import plant_config

PROGRAM = "PROGRAM P\nEND_PROGRAM\n"
READ_ID6 = bytes.fromhex("01 03 00 05 00 01 94 0B")  # manual 002 M1: read ID 6 of unit 1
ANSWER_0 = bytes.fromhex("01 03 02 00 00 B8 44")  # ID 6 = 0: STO open
ANSWER_IDLE = bytes.fromhex("01 03 02 00 A1 79 FC")  # ID 6 = 16#00A1: ready, zero speed, STO closed


def test_the_same_request_frame_gets_the_answer_of_the_moment(plants, tmp_path):
    plant = plants(plant_config(tmp_path, PROGRAM, program="P", transport="rtu"))
    server, drive = plant.line.server, plant.drive(1)
    drive.di1 = False
    assert server.exchange(READ_ID6) == ANSWER_0
    drive.di1 = True
    assert server.exchange(READ_ID6) == ANSWER_IDLE
    drive.di1 = False
    assert server.exchange(READ_ID6) == ANSWER_0
    assert plant.line.requests == 3


def test_a_bad_frame_sent_again_is_dropped_again(plants, tmp_path):
    plant = plants(plant_config(tmp_path, PROGRAM, program="P", transport="rtu"))
    server = plant.line.server
    bad = READ_ID6[:-1] + b"\x00"  # last CRC byte wrong
    assert server.exchange(bad) is None
    assert server.exchange(bad) is None
    assert server.malformed == 2
    assert plant.line.requests == 0  # neither reached the drive


def test_tcp_answers_carry_their_own_transaction_id(plants, tmp_path):
    plant = plants(plant_config(tmp_path, PROGRAM, program="P", transport="tcp"))
    server = plant.line.server
    plant.drive(1).di1 = False
    pdu = bytes.fromhex("0000 0006 01 03 0005 0001")  # protocol 0, length 6, unit 1, FC 03, ID 6, one register
    answers = [server.exchange(tid.to_bytes(2, "big") + pdu) for tid in (7, 8, 7, 0x1234)]
    # transaction id, protocol 0, length 5, unit 1, FC 03, 2 bytes, ID 6 = 0
    assert answers == [tid.to_bytes(2, "big") + bytes.fromhex("0000 0005 01 03 02 0000") for tid in (7, 8, 7, 0x1234)]


def test_a_channel_follows_a_drive_while_its_request_repeats(plants, tmp_path):
    """The master sends the same FC 03 frame every 20 ms; what it reads into
    the image changes with the drive (the answers are decoded afresh when
    they differ, and a repeated answer still lands in the image)."""
    channels = [
        {"name": "status", "unit": 1, "function": 3, "offset": 5, "count": 1, "read_to": "%IW0", "period": "20ms"}
    ]
    plant = plants(plant_config(tmp_path, PROGRAM, program="P", transport="rtu", channels=channels))
    drive = plant.drive(1)
    plant.run_ms(50)
    assert plant["%IW0"] == 0x00A1
    drive.di1 = False
    plant.run_ms(40)
    assert plant["%IW0"] == 0
    drive.di1 = True
    plant.run_ms(40)
    assert plant["%IW0"] == 0x00A1
    master_sent = plant.line.cable.sent_by_master()
    assert master_sent == READ_ID6 * (len(master_sent) // len(READ_ID6))


def test_the_cable_keeps_the_newest_frames_and_stays_bounded():
    """Found by the soak benchmark (benchmarks/bench_soak.py): the in-memory
    cable kept every frame of the line, 1.2 MB per 10 minutes of the default
    plant, without bound. It keeps the newest RECORD_BYTES at least, twice
    that at most, each way."""
    cable = MemoryCable()
    frames = [READ_ID6[:-2] + bytes([i % 256, i // 256]) for i in range(3 * RECORD_BYTES // len(READ_ID6))]
    for frame in frames:
        cable.record(False, frame)
        cable.record(True, ANSWER_0)
    master, slave = cable.sent_by_master(), cable.sent_by_slave()
    assert RECORD_BYTES <= len(master) <= 2 * RECORD_BYTES
    assert master.endswith(b"".join(frames[-100:]))
    assert RECORD_BYTES <= len(slave) <= 2 * RECORD_BYTES and slave.endswith(ANSWER_0 * 100)
