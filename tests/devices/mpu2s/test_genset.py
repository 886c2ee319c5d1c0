"""The genset examples end to end, in virtual time: st_programs/genset_sync.st
(MPU2S, MPU2S_PARAM, GENSET_SYNC) through the plain-CAN driver and the
MPU2-S node to the simulated MPU2-S, its genset, busbar and breaker, wired
as io_config/examples/genset.toml and genset_dead_bus.toml wire them. The
sequences of digest 004 §4.3/§4.4: a live-bus close in phase over a sweep
of slips and breaker times, a dead-bus close, the sync-time alarm, a
breaker that never closes, the transducer lost mid-sequence."""

from __future__ import annotations

import pytest

from .plant_support import CLOSED, SYNCHRONISING, Plant, example

# whole plants over tens of seconds of virtual time
pytestmark = pytest.mark.slow


@pytest.fixture
def plants(plc_factory, tmp_path):
    """Genset plants from example tables, stopped after the test (the softplc pytest plugin)."""
    return lambda data: Plant(plc_factory(config=data, base_dir=tmp_path))


def _close(plant: Plant, limit_ms: float = 60_000):
    plant.run_until(lambda: plant.get("Genset.sync.STATE") == CLOSED, limit_ms, "closed")
    [close] = plant.sim.closes
    return close


def test_the_example_reads_the_device_synchronises_closes_and_loads(plants):
    plant = plants(example())
    plant.run_until(lambda: plant.state == "WarmingUp", 5_000, "parameters read")
    # MPU2S_PARAM read IDs 26, 27 and 32 from the device (A31: no defaults, read them)
    store = plant.sim.store
    assert plant.get("Genset.sync.DF_MAX") == pytest.approx(store.number("sync_df_max"), abs=0.001)
    assert plant.get("Genset.sync.DF_MIN") == pytest.approx(store.number("sync_df_min"), abs=0.001)
    assert plant.get("Genset.ParamError") == 0
    close = _close(plant)
    assert not close.tripped and not close.dead_bus
    assert abs(close.phase_deg) < 10.0
    # the testing API's records: what --final-json writes under "[[sim]]"
    ((name, records),) = plant.plc.records.items()
    assert plant.plc.sim(name) is plant.sim
    assert records == {
        "closes": [
            {
                "t_s": close.t_ns / 1e9,
                "phase_deg": close.phase_deg,
                "voltage_diff_v": close.voltage_diff,
                "slip_hz": close.slip_hz,
                "dead_bus": False,
                "tripped": False,
            }
        ]
    }
    plant.run_until(lambda: plant.state == "Running", 60_000, "loaded")
    assert plant.get("Genset.mpu.P_KW") == pytest.approx(250.0, abs=25.0)
    assert plant.sim.plant.p_kw == pytest.approx(250.0, abs=40.0)
    assert plant.get("Genset.mpu.T5_GCB_CLOSED") and plant.get("Genset.mpu.COMM_OK")


SLIPS = (0.1, 0.2, 0.3, -0.15)
CLOSING_MS = (40, 80, 150)


@pytest.mark.parametrize("closing_ms", CLOSING_MS)
@pytest.mark.parametrize("slip", SLIPS)
def test_a_live_bus_close_is_in_phase(plants, slip, closing_ms):
    plant = plants(example(sim={"slip": slip, "closing_time": f"{closing_ms}ms"}))
    # the device's ID 32 is the breaker's closing time: the program reads it from there
    plant.sim.store.set_word(32, closing_ms)
    close = _close(plant)
    assert plant.get("Genset.sync.GCB_CLOSE_TIME") == closing_ms  # TIME in ms, as MPU2S_PARAM read it
    assert not close.tripped
    assert abs(close.phase_deg) < 10.0, f"slip {slip} Hz, {closing_ms} ms: {close.phase_deg:.2f} deg at close"


def test_a_dead_bus_close(plants):
    plant = plants(example("genset_dead_bus.toml"))
    close = _close(plant)
    assert close.dead_bus and not close.tripped
    plant.run_until(lambda: plant.state == "Running", 5_000, "running")
    assert plant.get("Genset.Island")
    assert plant.sim.plant.bus_live and plant.get("Genset.mpu.BUS_PRESENT") is not None


def test_no_phase_measurement_no_close_and_the_sync_time_alarm(plants):
    # the synchronoscope is not wired: PHASE stays 0, never turning through the advance angle
    plant = plants(example(drop_wiring=("phase",)))
    plant.run_until(lambda: plant.get("Genset.sync.STATE") == SYNCHRONISING, 20_000, "synchronising")
    plant.run_until(lambda: plant.get("Genset.sync.SYNC_TIME_ALARM"), 65_000, "sync time alarm (ID 34, 60 s)")
    assert plant.get("Genset.sync.STATE") == SYNCHRONISING  # it keeps synchronising (S6)
    assert plant.sim.closes == []


def test_a_breaker_that_never_closes_is_a_fault_after_five_attempts(plants):
    plant = plants(example(sim={"refuse_close": True}))
    plant.run_until(lambda: plant.get("Genset.sync.CLOSE_FAULT"), 120_000, "GCB close fault (event 89)")
    assert plant.get("Genset.sync.ATTEMPTS") == 5
    plant.run_ms(20)  # the program sees the fault at its next scan
    assert plant.state == "Faulted"
    assert plant.sim.closes == [] and plant.sim.plant.breaker.refused >= 5


def test_the_transducer_lost_mid_sequence_means_no_close(plants):
    # 1 Hz fast: the governor needs seconds to bring the slip into the window
    plant = plants(example(sim={"slip": 1.0}))
    plant.run_until(lambda: plant.get("Genset.sync.STATE") == SYNCHRONISING, 20_000, "synchronising")
    plant.sim.inject("unplug", None, True)  # the MPU2-S's CAN cable out
    plant.plc.watch("Genset.gcbClose")
    plant.run_ms(30_000)
    assert not plant.get("Genset.mpu.COMM_OK") and plant.state == "Faulted"
    assert plant.plc.trace.values("Genset.gcbClose") == [False] and plant.sim.closes == []


def test_supervise_mode_the_device_closes(plants):
    plant = plants(example())
    plant.set("Genset.Supervise", True)
    plant.plc.watch("Genset.gcbClose", "Genset.syncRequest")
    plant.run_until(lambda: plant.get("Genset.sync.STATE") == CLOSED, 60_000, "closed")
    [close] = plant.sim.closes
    assert abs(close.phase_deg) < 10.0 and not close.tripped
    trace = plant.plc.trace
    assert plant.sim.supervisor.close_commands >= 1
    assert trace.values("Genset.gcbClose") == [False]  # the MPU2-S closed, not the PLC
    assert True in trace.values("Genset.syncRequest")  # the program asked: terminal 6 "Sync. ein"
