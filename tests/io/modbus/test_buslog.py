"""`--bus-log` for Modbus (io/modbus/buslog.py): the default plant's DA1
line recorded beside the CAN log, every request and its answer as they
crossed the line, at engine times that follow the line's model (both
frames at 115200 bit/s 8N1, the DA1's factory rate, manual 002 P5-03,
plus the 1.75 ms gap of Modbus over serial line V1.02, 2.5.1.1)."""

from __future__ import annotations

from pathlib import Path

import pytest
from pymodbus.framer.rtu import FramerRTU

from softplc.runtime.io.modbus.buslog import HEADER, modbus_log_path
from softplc.testing import PLC

RUN_S = 2.0
BAUD, CHAR_BITS, GAP_S = 115_200, 10, 0.00175
#: drive_monitor: FC 3, IDs 6..10 (offset 5, count 5) of unit 1 every 100 ms (io_config/default.toml)
MONITOR = bytes.fromhex("01 03 00 05 00 05")


@pytest.fixture(scope="module")
def lines(tmp_path_factory) -> list[tuple[float, str, str, bytes]]:
    can_log = tmp_path_factory.mktemp("wire") / "plant.asc"
    plc = PLC.from_config(bus_log=can_log)
    try:
        plc.run_for(f"{RUN_S}s")
    finally:
        plc.stop()
    path = modbus_log_path(can_log)
    assert path == can_log.with_name("plant.modbus.log")
    text = path.read_text(encoding="ascii")
    assert text.startswith(HEADER)
    out = []
    for line in text.splitlines()[1:]:
        t, connection, direction, *octets = line.split()
        out.append((float(t), connection, direction, bytes.fromhex("".join(octets))))
    return out


def crc_ok(frame: bytes) -> bool:
    return FramerRTU.compute_CRC(frame[:-2]) == int.from_bytes(frame[-2:], "big")


def test_every_frame_is_a_whole_rtu_frame_of_the_drives_line(lines):
    assert len(lines) > 20
    for t, connection, direction, frame in lines:
        assert connection == "drives" and direction in ("TX", "RX")
        assert frame[0] == 1 and crc_ok(frame), (t, frame.hex(" "))
        assert 0.0 <= t <= RUN_S + 0.1


def test_each_answer_follows_its_request_after_the_time_on_the_line(lines):
    answered = 0
    for (t_tx, _, d_tx, tx), (t_rx, _, d_rx, rx) in zip(lines, lines[1:]):
        if d_tx != "TX" or d_rx != "RX":
            continue
        assert rx[1] & 0x7F == tx[1]  # the same function (an exception sets bit 7)
        assert t_rx - t_tx == pytest.approx(GAP_S + (len(tx) + len(rx)) * CHAR_BITS / BAUD, abs=2e-6)
        answered += 1
    assert answered >= 10


def test_the_monitor_channel_reads_every_100_ms(lines):
    times = [t for t, _, d, frame in lines if d == "TX" and frame[:-2] == MONITOR]
    assert len(times) >= int(RUN_S / 0.1) - 1
    gaps = {round(b - a, 6) for a, b in zip(times, times[1:])}
    assert gaps == {0.1}


def test_no_bus_log_no_file(tmp_path: Path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    plc = PLC.from_config()
    try:
        plc.run_for("0.2s")
    finally:
        plc.stop()
    assert list(tmp_path.iterdir()) == []


def test_an_exception_answer_is_read_in_the_words_the_link_logs(tmp_path: Path):
    """MAP V1.1b3 7: 83h 02h answers FC 3 with "illegal data address" (errors.error_text,
    as the link's log says it); a code Modbus does not define is named so."""
    from ...test_cli import softplc

    def rtu(body: bytes) -> str:
        return (body + FramerRTU.compute_CRC(body).to_bytes(2, "big")).hex(" ").upper()

    log = tmp_path / "run.modbus.log"
    log.write_text(
        HEADER
        + f"0.000000 drives TX {rtu(bytes.fromhex('01 03 00 05 00 05'))}\n"
        + f"0.003000 drives RX {rtu(bytes.fromhex('01 83 02'))}\n"
        + f"0.100000 drives TX {rtu(bytes.fromhex('01 03 00 05 00 05'))}\n"
        + f"0.103000 drives RX {rtu(bytes.fromhex('01 83 21'))}\n",
        encoding="ascii",
    )
    done = softplc("log", log)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[1].endswith("unit 1: exception 2 (illegal data address) to function 3")
    assert lines[3].endswith("unit 1: exception 33 (no exception code of Modbus) to function 3")
