"""The MPU2-S node (runtime/devices/mpu2s/node.py) in an engine in virtual
time, against the simulated MPU2-S on python-can's virtual bus: the telegram
into %IW and MPU2S, MPU2S_PARAM through the request engine (password,
timeout and retry, password renewal after a loss), a corrupt reply counted
and dropped, and the bus shared with a CANopen master."""

from __future__ import annotations

import itertools
import logging

import pytest

from softplc.runtime.config import config_from_dict
from softplc.runtime.devices.mpu2s import frames
from softplc.runtime.devices.mpu2s.parameters import parameter
from softplc.runtime.engine.build import build_engine
from softplc.runtime.io.can.bus import BusSettings, CanEndpoint, open_bus
from softplc.runtime.io.canopen.master import CanopenDriver
from softplc.runtime.io.plaincan import PlainCanDriver

MS = 1_000_000
_channels = itertools.count()
PROGRAM = """
PROGRAM Main
VAR
    ident AT %IW300 : WORD;         (* telegram Nr 1 *)
    fGenWord AT %IW301 : WORD;      (* Nr 2, 1/100 Hz *)
    mpu : MPU2S;
    par : MPU2S_PARAM;
    go : BOOL;
    write : BOOL;
    id : UINT := 26;
    bit : INT := -1;
    value : LREAL;
END_VAR
mpu(DEVICE := 1);
par(EXECUTE := go, DEVICE := 1, ID := id, BIT := bit, WRITE := write, VALUE := value);
IF par.DONE OR par.ERROR THEN
    go := FALSE;
END_IF
END_PROGRAM
"""
LTMR = {
    "name": "motor",
    "id": 40,
    "eds": "ltmr",
    "heartbeat": "100ms",
    "tpdo": [{"number": 1, "configure": False, "map": [{"object": "2004:06", "address": "%IW100"}]}],
}


@pytest.fixture
def plant(tmp_path):
    made = []

    def make(with_canopen: bool = False, password: int | None = 1234):
        (tmp_path / "main.st").write_text(PROGRAM)
        channel = f"test-mpu2s-node-{next(_channels)}"
        node = {"type": "mpu2s", "device": 1, "telegram": "%IW300"}
        sim: dict = {"type": "mpu2s", "node_id": 1}
        if password is not None:
            node["password"] = sim["password"] = password
        data = {
            "plc": {"programs": ["main.st"]},
            "task": [{"name": "Main", "interval": "10ms", "programs": ["Main"]}],
            "can": [{"name": "can0", "interface": "virtual", "channel": channel, "bitrate": 125000}],
            "plaincan": [node],
            "sim": [sim],
        }
        if with_canopen:
            data["canopen"] = {"node": [LTMR], "sdo_timeout": "1s"}
            data["sim"].append({"type": "ltmr", "node_id": 40})
        engine = build_engine(config_from_dict(data, tmp_path / "plant.toml"), virtual_time=True)
        driver = next(d for d in engine.drivers if isinstance(d, PlainCanDriver))
        engine.start()
        # a listener on the bus: what the PLC sends, as a bus monitor sees it
        monitor = CanEndpoint(open_bus(BusSettings("virtual", channel, 125000)), name="monitor", pump=driver.port.pump)
        seen: list[tuple[int, bytes]] = []
        monitor.add_handler(lambda msg: seen.append((msg.arbitration_id, bytes(msg.data))))
        monitor.start()
        made.append((engine, monitor))
        return engine, driver, engine.simulators["mpu2s1"], monitor, seen

    yield make
    for engine, monitor in made:
        monitor.stop()
        engine.stop()


def _request(engine, *, id: int, bit: int = -1, write: bool = False, value: float = 0.0, limit_ms: int = 3000) -> None:
    engine.set("Main.id", id)
    engine.set("Main.bit", bit)
    engine.set("Main.write", write)
    engine.set("Main.value", value)
    engine.set("Main.go", True)
    start = engine.now_ns()
    while engine.get("Main.go"):
        assert engine.now_ns() - start < limit_ms * MS, "MPU2S_PARAM did not finish"
        engine.run(cycles=1)


def _requests(seen) -> list[str]:
    return [data.hex(" ").upper() for can_id, data in seen if can_id == frames.REQUEST_ID]


def test_the_telegram_lands_in_the_image_and_in_mpu2s(plant):
    engine, driver, sim, _monitor, _seen = plant()
    engine.run(duration_ns=3000 * MS)  # 23 frames 100 ms apart: one whole telegram
    assert engine.get("Main.ident") == 1301  # Nr 1 "Kennung" (A3)
    assert engine.get("Main.mpu.COMM_OK") and engine.get("Main.mpu.COMPLETE")
    p = sim.plant
    assert engine.get("Main.fGenWord") == round(p.f_gen * 100)
    assert engine.get("Main.mpu.F_GEN") == pytest.approx(p.f_gen, abs=0.01)
    assert engine.get("Main.mpu.F_BUS") == pytest.approx(p.f_bus, abs=0.01)
    assert engine.get("Main.mpu.U_BUS") == pytest.approx(p.u_bus, abs=0.1)
    assert engine.get("Main.mpu.GEN_PRESENT") and engine.get("Main.mpu.BUS_PRESENT")
    assert not engine.get("Main.mpu.T5_GCB_CLOSED") and engine.get("Main.mpu.T4_BREAKER_OPEN")
    assert engine.get("Main.mpu.COS_PHI") == pytest.approx(1.0)
    assert driver.status().message == "plaincan can0: 1/1 up"


def test_a_write_gives_the_password_first_and_is_read_back(plant):
    engine, _driver, sim, _monitor, seen = plant()
    engine.run(duration_ns=500 * MS)
    _request(engine, id=parameter("sync_df_max").id, write=True, value=0.25)
    assert engine.get("Main.par.DONE") and engine.get("Main.par.ERRORID") == 0
    assert engine.get("Main.par.VALUE_READ") == pytest.approx(0.25, abs=0.004)
    assert engine.get("Main.par.FRAMES") == 3
    assert sim.store.number("sync_df_max") == pytest.approx(0.25, abs=0.004)
    assert _requests(seen)[0] == "EE 01 01 F4 04 D2 EB 27"  # V4: password 1234 to ID 500


def test_value_read_is_the_device_value_as_the_scaling_gives_it(plant):
    # issue 33: +df max (ID 26, 4.2.47) is f[Hz]·256: the word 59 is 59/256 = 0.23046875 Hz,
    # not 0.230; a switch reads 1.0/0.0 and a plain word as it is
    engine, _driver, sim, _monitor, _seen = plant()
    sim.store.set_word(26, 59)
    engine.run(duration_ns=500 * MS)
    _request(engine, id=26)
    assert engine.get("Main.par.DONE") and engine.get("Main.par.RAW") == 59
    assert engine.get("Main.par.VALUE_READ") == 59 / 256 == 0.23046875
    engine.run(duration_ns=100 * MS)
    sim.store.set_word(68, 1234)  # the frequency ramp, Hz/s·102.4 (A13): 1234 / 102.4 Hz/s
    _request(engine, id=68)
    assert engine.get("Main.par.VALUE_READ") == 1234 * 5 / 512 == 12.05078125


def test_a_value_outside_the_range_never_reaches_the_wire(plant):
    engine, _driver, sim, _monitor, seen = plant()
    engine.run(duration_ns=500 * MS)
    _request(engine, id=parameter("sync_df_max").id, write=True, value=0.6)  # 4.2.47: at most 0.49 Hz
    assert engine.get("Main.par.ERROR") and engine.get("Main.par.ERRORID") == 2  # MPU2S_ERR_RANGE
    assert _requests(seen) == [] and sim.requests == 0


@pytest.mark.parametrize(
    "key, param_id, bit, mask",
    [
        ("gcb_monitoring", 17, 12, 0x1000),  # 4.2.59, a bit
        ("black_start", 19, 5, 0x0030),  # 4.2.55, a double bit: 00 = aus, 11 = ein (4.2.18)
        ("sync_time_monitoring", 21, 0, 0x0001),  # 4.2.53 (A33)
        ("earth_fault_monitoring", 248, 9, 0x0200),  # 4.2.123
    ],
)
def test_bit_and_double_bit_parameters_are_written_from_st(plant, key, param_id, bit, mask):
    # issue 33: MPU2S_PARAM with BIT and VALUE := 1.0 / 0.0 ("a switch or flag is 1.0 / 0.0"):
    # the whole word read first, the bits merged, written, read back (4.1, 4.2.13 ff.)
    engine, _driver, sim, _monitor, seen = plant()
    engine.run(duration_ns=500 * MS)
    before = sim.store.words[param_id]
    for value, word in ((1.0, before | mask), (0.0, before & ~mask)):
        engine.run(duration_ns=100 * MS)  # EXECUTE low for a scan: the next request's edge
        seen.clear()
        _request(engine, id=param_id, bit=bit, write=True, value=value)
        assert engine.get("Main.par.DONE") and engine.get("Main.par.ERRORID") == 0
        assert (engine.get("Main.par.VALUE_READ"), engine.get("Main.par.RAW")) == (value, word)
        requests = [frames.read_request(1, param_id), frames.write_request(1, param_id, word)]
        requests += [frames.read_request(1, param_id)]
        assert _requests(seen)[-3:] == [r.hex(" ").upper() for r in requests]
        assert sim.store.flag(key) is bool(value) and sim.store.words[param_id] == word  # the rest kept
    assert _requests(seen)[-2][12:17] == f"{word >> 8:02X} {word & 0xFF:02X}"  # bytes 4-5, high first
    engine.run(duration_ns=100 * MS)
    seen.clear()
    _request(engine, id=param_id, bit=bit, write=True, value=0.5)  # neither on nor off
    assert engine.get("Main.par.ERRORID") == 2 and _requests(seen) == []  # MPU2S_ERR_RANGE, nothing sent


def test_no_reply_is_retried_then_a_timeout(plant):
    engine, _driver, sim, _monitor, seen = plant()
    engine.run(duration_ns=500 * MS)
    sim.inject("unplug", None, True)
    _request(engine, id=parameter("sync_df_max").id)
    assert engine.get("Main.par.ERROR") and engine.get("Main.par.ERRORID") == 1  # MPU2S_ERR_TIMEOUT
    assert engine.get("Main.par.FRAMES") == 3  # the first and two retries
    assert _requests(seen) == ["FF 01 00 1A 00 00 FF 1B"] * 3  # B7 = B1^B3^B5 = 01h^1Ah^00h
    engine.run(duration_ns=500 * MS)  # no telegram frame for more than `stale` (1 s)
    assert not engine.get("Main.mpu.COMM_OK")


def test_the_password_is_given_again_after_a_communication_loss(plant):
    engine, _driver, sim, _monitor, seen = plant()
    engine.run(duration_ns=500 * MS)
    _request(engine, id=parameter("sync_df_max").id, write=True, value=0.25)
    sim.inject("unplug", None, True)  # the device forgets the password too
    engine.run(duration_ns=2000 * MS)
    assert not engine.get("Main.mpu.COMM_OK") and not sim.authorised
    sim.inject("unplug", None, False)
    engine.run(duration_ns=500 * MS)
    assert engine.get("Main.mpu.COMM_OK")
    _request(engine, id=parameter("sync_df_max").id, write=True, value=0.30)
    assert engine.get("Main.par.DONE"), engine.get("Main.par.ERRORID")
    assert sim.store.number("sync_df_max") == pytest.approx(0.30, abs=0.004)
    assert _requests(seen).count("EE 01 01 F4 04 D2 EB 27") == 2


def test_without_the_password_a_write_is_not_taken(plant):
    engine, _driver, sim, _monitor, _seen = plant(password=None)
    sim.store.password, sim.store.authorised = 1234, False  # the device has one; the configuration does not give it
    engine.run(duration_ns=500 * MS)
    _request(engine, id=parameter("sync_df_max").id, write=True, value=0.25)
    assert engine.get("Main.par.ERRORID") == 4  # MPU2S_ERR_VERIFY: the old value came back
    assert sim.store.number("sync_df_max") == pytest.approx(0.20, abs=0.004)


def test_a_corrupt_reply_is_counted_logged_once_and_dropped(plant, caplog):
    engine, driver, _sim, monitor, _seen = plant()
    engine.run(duration_ns=500 * MS)
    bad = bytearray(frames.reply(frames.KIND_READ, 1, 26, 0x33))
    bad[7] ^= 0xFF  # B7 = B1^B3^B5 no more
    with caplog.at_level(logging.WARNING, logger="softplc.runtime.io.plaincan.driver"):
        for _ in range(3):
            monitor.send(frames.device_can_id(1), bytes(bad))
        engine.run(cycles=2)
    assert driver.malformed == {"mpu2s_1": 3}
    assert driver.status().message == "plaincan can0: 1/1 up, 3 malformed"
    assert len([r for r in caplog.records if "dropped" in r.getMessage()]) == 1


def test_one_connection_to_the_bus_shared_with_a_canopen_master(plant):
    engine, driver, _sim, _monitor, _seen = plant(with_canopen=True)
    master = next(d for d in engine.drivers if isinstance(d, CanopenDriver))
    assert master.endpoint is driver.port.endpoint  # one python-can bus object for both protocols
    engine.run(duration_ns=3000 * MS)
    assert master.status().ok and "1/1 up" in master.status().message  # the LTMR booted through it
    assert engine.get("Main.mpu.COMM_OK") and engine.get("Main.ident") == 1301
    _request(engine, id=parameter("sync_df_max").id)
    assert engine.get("Main.par.DONE")


def test_a_device_that_comes_and_goes_does_not_flood_the_log(plant, caplog):
    # issue 16: every log message from a bus is rate limited. 20 losses and
    # returns in 30 s of plant: one line of each kind per 10 s window, and a
    # "suppressed" line that counts the rest.
    engine, _driver, sim, _monitor, _seen = plant()
    engine.run(duration_ns=500 * MS)
    with caplog.at_level(logging.INFO):
        for _ in range(20):
            sim.inject("unplug", None, True)
            engine.run(duration_ns=1200 * MS)  # more than `stale` (1 s): lost
            sim.inject("unplug", None, False)
            engine.run(duration_ns=300 * MS)  # telegram frames every 100 ms: heard again
        engine.run(duration_ns=10_000 * MS)  # the last windows end: their summaries
    lost = [r.getMessage() for r in caplog.records if "no telegram from device 1" in r.getMessage()]
    assert 3 <= len(lost) <= 8, lost  # 30 s: about one a window, a summary in some
    suppressed = [m for m in lost if m.startswith("suppressed ")]
    assert suppressed and all("similar messages" in m for m in suppressed)
    assert engine.get("Main.mpu.COMM_OK")
