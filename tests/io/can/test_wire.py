"""`--bus-log` for CAN (io/can/wire.py): the default plant's wire recorded
in python-can's formats and read back with python-can's own readers. The
run is on the virtual clock, so every format holds the same frames at the
same engine times; the PLC's frames are Tx, the devices' Rx, each once."""

from __future__ import annotations

import can
import pytest

from softplc.runtime.plugin.driver import DriverError
from softplc.testing import PLC

from ...test_cli import softplc

FORMATS = (".asc", ".blf", ".log")
RUN_S = 3.0
LTMR, FC280 = 40, 20  # the default plant's node ids (io_config/default.toml)


@pytest.fixture(scope="module")
def recorded(tmp_path_factory) -> dict:
    """suffix -> the frames python-can reads back from the file of that format."""
    out = {}
    for suffix in FORMATS:
        path = tmp_path_factory.mktemp("wire") / f"plant{suffix}"
        plc = PLC.from_config(bus_log=path)
        try:
            plc.run_for(f"{RUN_S}s")
        finally:
            plc.stop()
        out[suffix] = list(can.LogReader(path))
    return out


def channel(m: can.Message) -> int:
    """python-can's channel number (a candump log names it can0, can1 ...)."""
    return int(m.channel.removeprefix("can")) if isinstance(m.channel, str) else m.channel


def frames(messages: list) -> list:
    return [
        (round(m.timestamp, 6), m.arbitration_id, bytes(m.data), m.is_rx, m.is_remote_frame, channel(m))
        for m in messages
    ]


def test_every_format_reads_back_the_same_frames_at_the_same_engine_times(recorded):
    asc = frames(recorded[".asc"])
    assert len(asc) > 100  # boot-ups, SDOs of the boot, PDOs, heartbeats
    assert frames(recorded[".blf"]) == asc
    assert frames(recorded[".log"]) == asc


def test_times_are_engine_seconds_from_the_start(recorded):
    times = [m.timestamp for m in recorded[".asc"]]
    assert times == sorted(times)
    assert 0.0 <= times[0] < 0.1  # the master's first frames at the start of the run
    assert times[-1] <= RUN_S


def test_the_plc_sends_nmt_and_sdo_requests_and_receives_the_nodes_answers(recorded):
    messages = recorded[".asc"]
    nmt = [m for m in messages if m.arbitration_id == 0x000]
    assert nmt and all(not m.is_rx for m in nmt)
    assert any(m.data[0] == 0x01 for m in nmt)  # start remote node (CiA 301)
    for node in (LTMR, FC280):
        requests = [m for m in messages if m.arbitration_id == 0x600 + node]
        answers = [m for m in messages if m.arbitration_id == 0x580 + node]
        assert requests and all(not m.is_rx for m in requests), node
        assert answers and all(m.is_rx for m in answers), node
        assert len(answers) <= len(requests), node  # each answer once, though two devices share the bus
        boot_ups = [m for m in messages if m.arbitration_id == 0x700 + node and bytes(m.data) == b"\x00"]
        assert boot_ups and all(m.is_rx for m in boot_ups), node


def test_an_ending_python_can_does_not_write_is_refused_naming_the_option(tmp_path):
    with pytest.raises(DriverError, match=r"--bus-log .*plant\.xyz: python-can writes no \.xyz file.*\.asc"):
        PLC.from_config(bus_log=tmp_path / "plant.xyz")


def test_softplc_run_bus_log_writes_the_can_and_the_modbus_log(tmp_path):
    done = softplc("run", "--virtual-time", "--duration", "1s", "--bus-log", tmp_path / "wire.log", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    first = (tmp_path / "wire.log").read_text().splitlines()[0]  # candump: (time) can0 ID#DATA T|R
    assert first.startswith("(0.000000) can0 ") and first.endswith(" T")
    assert "drives TX 01 03 00 05 00 05" in (tmp_path / "wire.modbus.log").read_text()


def test_softplc_run_with_an_ending_python_can_does_not_write_exits_2(tmp_path):
    done = softplc("run", "--virtual-time", "--duration", "1s", "--bus-log", tmp_path / "wire.pcap", cwd=tmp_path)
    assert done.returncode == 2
    assert "--bus-log" in done.stderr and "no .pcap file" in done.stderr and "Traceback" not in done.stderr
