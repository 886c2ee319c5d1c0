"""The check of the testing API: the embedded default plant
(io_config/default.toml) tested offline the way a user would, through the
documented API only (softplc.testing, README "Testing a sequence offline"):
the motor behind the simulated LTMR started, tripped by a jam injected into
the simulated device and reset; the Eaton drive started, reversed, stopped
and tripped by an injected drive fault, which the program resets."""

from __future__ import annotations

import threading
from datetime import timedelta

import pytest

from softplc.testing import PLC

# a whole plant over tens of seconds of virtual time
pytestmark = pytest.mark.slow

MOTOR = ("Motor.state", "Motor.ltmr.Running", "Motor.ltmr.Tripped", "Motor.ltmr.ResetAuthorized", "Motor.tripCode")
DRIVE = ("Drive.state", "Drive.drive.RUNNING", "Drive.drive.REVERSED", "Drive.drive.ACTUAL_HZ", "Drive.drive.FAULT")


def fast_trip_class(tables: dict) -> None:
    """The LTMR of the default plant with trip class 5 (register 606) and a
    thermal reset threshold of 95 % (608), so a jam trips in seconds and the
    motor cools below the reset level soon after."""
    for sim in tables["sim"]:
        if sim["type"] == "ltmr":
            sim["registers"] = {"606": 5, "608": 95}


@pytest.fixture
def plant():
    before = set(threading.enumerate())
    plc = PLC.from_config(edit=fast_trip_class)
    # manual operation, set before the first scan
    plc.write("Motor.Auto", False)
    plc.write("Motor.AutoReset", False)
    plc.write("Drive.Auto", False)
    plc.watch(*MOTOR, *DRIVE)
    yield plc
    plc.stop()
    assert {t for t in threading.enumerate() if t.is_alive()} <= before, "a thread outlived plc.stop()"


def test_motor_start_jam_trip_and_reset(plant):
    plc = plant
    assert plc["Motor.state"] == "Stopped" and plc.now == timedelta(0)
    plc.force("Motor.CmdForward", True)
    plc.run_until("Motor.ltmr.Running", timeout="2s")
    assert plc["Motor.state"] == "E_MotorState.Forward"

    jam_at = plc.now
    plc.fault("ltmr40", "load", 800)  # 8 x FLC: the thermal image fills in seconds
    tripped_at = plc.run_until(lambda: plc["Motor.state"] == "Tripped", timeout="20s", what="the jam trip")
    assert timedelta(seconds=1) < tripped_at - jam_at < timedelta(seconds=10)
    assert plc["Motor.tripCode"] != 0 and not plc["Motor.ltmr.Running"]
    assert plc["Motor.trips"] == 1

    # the jam cleared, the command dropped; no reset until the LTMR authorizes it (the motor cools)
    plc.clear_fault("ltmr40", "load")
    plc.unforce("Motor.CmdForward")
    plc.write("Motor.CmdForward", False)
    plc.write("Motor.CmdReset", True)
    plc.run_for("1s")
    assert plc["Motor.state"] == "Tripped"
    plc.run_until("Motor.ltmr.ResetAuthorized", timeout="60s")
    plc.run_until(lambda: plc["Motor.state"] == "Stopped", timeout="1s", what="the reset")
    assert not plc["Motor.ltmr.Tripped"] and plc["Motor.tripCode"] == 0

    states = plc.trace.values("Motor.state")
    assert states == ["Stopped", "Forward", "Tripped", "Resetting", "Stopped"], plc.trace.around()
    running = plc.trace.changes("Motor.ltmr.Running")
    assert [v for _t, v in running] == [False, True, False]


def test_drive_start_reverse_stop_and_fault(plant):
    plc = plant
    plc.force("Drive.CmdRun", True)
    plc.run_until(lambda: plc["Drive.drive.AT_SETPOINT"], timeout="10s", what="forward at speed")
    assert plc["Drive.drive.ACTUAL_HZ"] == pytest.approx(40.0)

    plc.script([(plc.now + timedelta(seconds=1), "Drive.CmdReverse", True)])
    plc.run_for("1.5s")
    plc.run_until(
        lambda: plc["Drive.drive.AT_SETPOINT"] and plc["Drive.drive.REVERSED"], timeout="10s", what="reverse at speed"
    )
    assert plc["Drive.drive.ACTUAL_HZ"] == pytest.approx(-40.0)

    plc.force("Drive.CmdRun", False)
    plc.run_until(lambda: not plc["Drive.drive.RUNNING"], timeout="10s", what="stopped")
    hz = [v for _t, v in plc.trace.changes("Drive.drive.ACTUAL_HZ")]
    assert max(hz) == pytest.approx(40.0) and min(hz) == pytest.approx(-40.0) and hz[-1] == 0.0

    # a drive fault (Tabelle 11 code 21) injected into the simulated DA1: the program sees it and resets it
    plc.force("Drive.CmdRun", True)
    plc.run_for("500ms")
    plc.fault("da1_1", "trip", 21)
    plc.run_until("Drive.drive.FAULT", timeout="1s")
    plc.run_until(lambda: plc["Drive.state"] == "Faulted", timeout="1s", what="Faulted")
    plc.write("Drive.CmdReset", True)
    plc.run_until(lambda: not plc["Drive.drive.FAULT"], timeout="5s", what="the fault reset")
    plc.run_until(lambda: plc["Drive.drive.RUNNING"], timeout="5s", what="running again")
    assert plc["Drive.faults"] == 1
    assert "Faulted" in plc.trace.values("Drive.state")


def test_bus_cuts_on_schedule_and_wrong_faults(plant):
    plc = plant
    plc.run_until(lambda: plc["Motor.ltmr.NodeOk"] and plc["Drive.drive.CONNECTED"], timeout="5s", what="both up")
    assert set(plc.sims) == {"ltmr40", "fc28020", "da1_1"}
    assert {"unplug", "load"} <= set(plc.faults_of("ltmr40"))

    plc.watch("Motor.ltmr.NodeOk", "Drive.drive.CONNECTED")
    cut_at = plc.now
    plc.fault("ltmr40", "unplug", duration="2s")  # the LTMR's CAN cable out for 2 s
    plc.run_until(lambda: not plc["Motor.ltmr.NodeOk"], timeout="1s", what="the LTMR lost")
    back_at = plc.run_until("Motor.ltmr.NodeOk", timeout="10s", what="the LTMR back")
    assert back_at - cut_at >= timedelta(seconds=2)  # the cable was out for 2 s; the master booted it again
    assert plc.trace.values("Drive.drive.CONNECTED") == [True]  # the drive's line went on meanwhile

    # (short: the master waits out its timeouts on the real clock while the unit is silent)
    plc.fault("da1_1", "silent")  # the drive stops answering until cleared
    plc.run_until(lambda: not plc["Drive.drive.CONNECTED"], timeout="2s", what="the drive lost")
    plc.clear_fault("da1_1", "silent")
    plc.run_until("Drive.drive.CONNECTED", timeout="5s", what="the drive back")
    assert plc.trace.values("Drive.drive.CONNECTED") == [True, False, True]

    with pytest.raises(ValueError, match="ltmr40 has no fault 'jam'; it has unplug, load"):
        plc.fault("ltmr40", "jam")
    with pytest.raises(ValueError, match="fault load of ltmr40 needs a value"):
        plc.fault("ltmr40", "load")
    with pytest.raises(ValueError, match="fault trip of da1_1 does not last"):
        plc.fault("da1_1", "trip", 21, duration="1s")
    with pytest.raises(KeyError, match="no simulated device 'ltmr' \\(there are: ltmr40, fc28020, da1_1\\)"):
        plc.sim("ltmr")
