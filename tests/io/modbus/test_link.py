"""The manual's example telegrams (manual 002 §2.6.6, digest §5.1), byte for
byte on a real serial line: the master's RTU requests and the simulated
drive's answers as they crossed the pseudo-terminal cable."""

from __future__ import annotations

from .plant import plant_config

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


def test_manual_telegrams_byte_for_byte(plants, tmp_path):
    plant = plants(plant_config(tmp_path, PROGRAM, program="P", transport="rtu", channels=CHANNELS))
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

    plant = plants(plant_config(tmp_path, "PROGRAM P\nEND_PROGRAM\n", program="P", transport="rtu"))
    plant.run_ms(10)
    cable = plant.line.cable
    with serial.Serial(cable.master_port, 115200, timeout=0.2) as port:
        port.write(READ_ID6[:-1] + b"\x00")  # last CRC byte wrong
        assert port.read(7) == b""
        port.write(READ_ID6)
        answer = port.read(7)
    assert answer[:3] == bytes.fromhex("01 03 02") and len(answer) == 7  # the next good frame is answered
