"""The simulated LTMR when things go wrong, on the virtual bus in virtual
time: the master's heartbeat lost (the fallback of register 682), an
overload trip and its reset, a power cycle, faults injected from [[sim]],
and python-canopen's own SDO client against it (manual 001, digest 001)."""

from __future__ import annotations

import threading

import canopen
import pytest

from softplc.runtime.devices.ltmr import bits as ltmr_bits
from softplc.runtime.devices.ltmr import codes as ltmr_codes
from softplc.runtime.devices.ltmr import registers as ltmr
from softplc.runtime.devices.ltmr.bits import Status1, Status2, TripEnable1, TripRegister1
from softplc.runtime.devices.ltmr.codes import FallbackStrategy, OperatingMode, ResetMode
from softplc.runtime.io.canopen.cia301 import (
    NMT_PRE_OPERATIONAL,
    NMT_START,
    NMT_STOP,
    STATE_PRE_OPERATIONAL,
    STATE_STOPPED,
)
from softplc.runtime.io.canopen.eds import shipped_eds

from ...io.canopen.bench import write_ok
from .sim_support import (
    EMCY,
    HEARTBEAT,
    NODE,
    RPDO1,
    TPDO1,
    operational,
    running_forward,
    watched,
)

# ---------------------------------------------------------------------------- communication loss


@pytest.mark.parametrize(
    "strategy, mode, outputs",
    [
        (FallbackStrategy.HOLD, OperatingMode.REVERSER_2W, (True, False)),
        (FallbackStrategy.RUN, OperatingMode.TWO_STEP_2W, (False, True)),
        (FallbackStrategy.OFF, OperatingMode.REVERSER_2W, (False, False)),
        (FallbackStrategy.BOTH_ON, OperatingMode.OVERLOAD_2W, (True, True)),
        (FallbackStrategy.LO1_ON, OperatingMode.REVERSER_2W, (True, False)),
        (FallbackStrategy.LO2_ON, OperatingMode.REVERSER_2W, (False, True)),
    ],
)
def test_heartbeat_loss_applies_the_fallback_of_682(bench, strategy, mode, outputs):
    sim = watched(bench, strategy, {ltmr.REG_OPERATING_MODE: mode, ltmr.REG_CONTROL_SETTING: 1 << 9})
    assert sim.lo1 or sim.lo2
    bench.master_heartbeat_ms = 0  # the PLC is gone
    bench.run_ms(600)
    assert sim.nmt_state == STATE_PRE_OPERATIONAL  # 0x1029:01 = 0
    assert (sim.lo1, sim.lo2) == outputs
    assert sim.register(ltmr.REG_STATUS_2) & Status2.NETWORK_COMM_LOSS  # 456 bit 8
    assert sim.register(ltmr.REG_ALARM_CODE) == ltmr_codes.ALARM_NETWORK_COMM  # 632 bit 15 (default on)
    assert not sim.register(ltmr.REG_NETWORK_PORT_STATUS) & ltmr_bits.NetworkPortStatus.COMMUNICATING


def test_communication_comes_back_then_the_next_rpdo_ends_the_fallback(bench):
    sim = watched(bench, FallbackStrategy.OFF)
    sim.unplug()  # the cable is cut
    bench.run_ms(700)
    assert not sim.lo1
    sim.plug()
    bench.run_ms(200)
    assert sim.register(ltmr.REG_STATUS_2) & Status2.NETWORK_COMM_LOSS  # not Operational yet
    bench.nmt(NMT_START, NODE)
    bench.run_ms(10)
    assert not sim.register(ltmr.REG_STATUS_2) & Status2.NETWORK_COMM_LOSS
    assert sim.register(ltmr.REG_ALARM_CODE) == 0
    assert (
        sim.register(ltmr.REG_NETWORK_PORT_STATUS)
        == ltmr_bits.NetworkPortStatus.CONNECTED | ltmr_bits.NetworkPortStatus.COMMUNICATING
    )
    assert not sim.lo1  # the fallback holds until an RPDO
    status2 = int.from_bytes(bench.frames_with(TPDO1)[-1][2:4], "little")
    assert not status2 & Status2.NETWORK_COMM_LOSS  # TPDO1 on entering Operational
    bench.send(RPDO1, "01 00 00 00 00 00")
    bench.run_ms(10)
    assert sim.lo1


def test_entering_pre_operational_by_nmt_applies_the_fallback(bench):
    # manual 001 L75-90: "(4) (7) Enter_Pre-Operational_State and apply fallback"
    sim = running_forward(bench, registers={ltmr.REG_NETWORK_FALLBACK: FallbackStrategy.OFF})
    bench.nmt(NMT_PRE_OPERATIONAL, NODE)
    bench.run_ms(10)
    assert not sim.lo1
    assert sim.register(ltmr.REG_STATUS_2) & Status2.NETWORK_COMM_LOSS
    bench.send(RPDO1, "01 00 00 00 00 00")  # not Operational: ignored
    bench.run_ms(10)
    assert not sim.lo1
    bench.nmt(NMT_START, NODE)
    bench.send(RPDO1, "01 00 00 00 00 00")
    bench.run_ms(10)
    assert sim.lo1


def test_stop_by_nmt_holds_when_682_says_hold(bench):
    sim = running_forward(bench, registers={ltmr.REG_NETWORK_FALLBACK: FallbackStrategy.HOLD})
    bench.nmt(NMT_STOP, NODE)
    bench.run_ms(1000)
    assert sim.nmt_state == STATE_STOPPED
    assert sim.lo1
    assert sim.register(ltmr.REG_STATUS_2) & Status2.NETWORK_COMM_LOSS


def test_network_port_trip_109_stays_until_reset_and_sends_an_emcy(bench):
    sim = watched(
        bench, FallbackStrategy.OFF, {ltmr.REG_TRIP_ENABLE_1: TripEnable1.NETWORK_PORT | TripEnable1.THERMAL_OVERLOAD}
    )
    bench.master_heartbeat_ms = 0
    bench.run_ms(600)
    assert sim.register(ltmr.REG_TRIP_CODE) == ltmr_codes.TRIP_NETWORK_COMM
    assert sim.register(ltmr.REG_TRIP_REGISTER_1) & TripRegister1.NETWORK_PORT
    assert bench.frames_with(EMCY)[-1] == bytes.fromhex("00 10 01 6D 00 00 00 00")  # A22: 0x1000, 109
    bench.master_heartbeat_ms = 100
    bench.nmt(NMT_START, NODE)
    bench.run_ms(200)
    assert sim.register(ltmr.REG_TRIP_CODE) == ltmr_codes.TRIP_NETWORK_COMM
    bench.send(RPDO1, "08 00 00 00 00 00")  # remote reset
    bench.run_ms(10)
    assert sim.register(ltmr.REG_TRIP_CODE) == 0
    assert bench.frames_with(EMCY)[-1] == bytes(8)  # error reset


# ---------------------------------------------------------------------------- overload, reset, self test


def test_an_overload_trips_with_code_4_and_an_emcy_then_a_remote_reset(bench):
    sim = running_forward(bench)
    bench.clear()
    sim.set_load(400)
    bench.run_until(lambda: sim.register(ltmr.REG_TRIP_CODE) != 0, 60_000, "thermal trip")
    assert sim.register(ltmr.REG_TRIP_CODE) == ltmr_codes.TRIP_THERMAL_OVERLOAD
    assert sim.register(ltmr.REG_TRIP_REGISTER_1) & TripRegister1.THERMAL_OVERLOAD
    assert not sim.lo1
    assert bench.frames_with(EMCY) == [bytes.fromhex("00 10 01 04 00 00 00 00")]  # A22 choice
    status = int.from_bytes(bench.frames_with(TPDO1)[-1][:2], "little")
    assert status & Status1.TRIP and status & Status1.TRIPPED and not status & Status1.RUNNING
    assert bench.sdo_read(NODE, 0x1001, 0) == bytes.fromhex("4F 01 10 00 01 00 00 00")
    assert bench.sdo_read(NODE, 0x1003, 1) == bytes.fromhex("43 03 10 01 00 10 00 00")
    sim.set_load(80)
    bench.send(RPDO1, "00 00 00 00 00 00")
    bench.run_until(lambda: sim.register(455) & Status1.RESET_AUTHORIZED, 300_000, "reset authorized")
    assert sim.register(ltmr.REG_THERMAL_CAPACITY) < 75  # 608
    bench.send(RPDO1, "08 00 00 00 00 00")  # 704 bit 3, digest §7.2
    bench.run_ms(10)
    assert sim.register(ltmr.REG_TRIP_CODE) == 0
    assert bench.frames_with(EMCY)[-1] == bytes(8)
    bench.send(RPDO1, "01 00 00 00 00 00")
    bench.run_ms(10)
    assert sim.lo1


def test_manual_reset_mode_needs_the_button(bench):
    sim = running_forward(bench, registers={ltmr.REG_GENERAL_CONFIG_2: ResetMode.MANUAL})
    sim.set_load(720)
    bench.run_until(lambda: sim.register(ltmr.REG_TRIP_CODE) != 0, 20_000, "thermal trip")
    bench.send(RPDO1, "00 00 00 00 00 00")
    bench.run_until(lambda: sim.register(455) & Status1.RESET_AUTHORIZED, 300_000, "reset authorized")
    bench.send(RPDO1, "08 00 00 00 00 00")
    bench.run_ms(10)
    assert sim.register(ltmr.REG_TRIP_CODE) == ltmr_codes.TRIP_THERMAL_OVERLOAD
    sim.press_reset()
    bench.run_ms(10)
    assert sim.register(ltmr.REG_TRIP_CODE) == 0


def test_self_test_by_rpdo(bench):
    sim = operational(bench)
    bench.send(RPDO1, "20 00 00 00 00 00")  # 704 bit 5
    bench.run_ms(10)
    assert sim.register(ltmr.REG_TRIP_CODE) == ltmr_codes.TRIP_TEST  # 10
    assert sim.register(ltmr.REG_TRIP_REGISTER_1) & TripRegister1.TEST  # 452 bit 9
    assert bench.frames_with(EMCY)[-1] == bytes.fromhex("00 10 01 0A 00 00 00 00")


# ---------------------------------------------------------------------------- power


def test_a_power_cycle_forgets_the_commands_and_keeps_the_settings(bench):
    sim = running_forward(bench)
    assert bench.sdo_write(NODE, 0x2007, 0x03, 60, 2) == write_ok(0x2007, 0x03)
    bench.clear()
    sim.power_cycle()
    bench.run_ms(10)
    assert bench.frames_with(HEARTBEAT) == [b"\x00"]
    assert sim.nmt_state == STATE_PRE_OPERATIONAL
    assert not sim.lo1 and sim.register(ltmr.REG_CONTROL_1) == 0
    assert sim.register(ltmr.REG_FLC1) == 60


def test_a_trip_outlives_a_reset_communication_and_is_reported_again(bench):
    sim = operational(bench)
    bench.send(RPDO1, "20 00 00 00 00 00")  # self test: trip 10
    bench.run_ms(10)
    bench.clear()
    bench.send(0x000, "82 28")  # NMT reset communication
    bench.run_ms(10)
    assert bench.frames_with(HEARTBEAT) == [b"\x00"]
    assert sim.register(ltmr.REG_TRIP_CODE) == ltmr_codes.TRIP_TEST
    assert bench.frames_with(EMCY) == [bytes.fromhex("00 10 01 0A 00 00 00 00")]
    assert sim.read(0x1001) == 0x01


# ---------------------------------------------------------------------------- canopen's own master side


class _MasterNetwork(canopen.Network):
    """canopen's Network on the bench's master endpoint."""

    def __init__(self, endpoint) -> None:
        super().__init__(bus=None)
        self.endpoint = endpoint
        endpoint.add_handler(lambda msg: self.notify(msg.arbitration_id, bytes(msg.data), msg.timestamp))

    def send_message(self, can_id: int, data: bytes, remote: bool = False) -> None:
        self.endpoint.send(can_id, bytes(data), remote=remote)


def _blocking(bench, work):
    """Run canopen's blocking SDO client in a thread while the pump delivers the frames."""
    outcome = {}

    def run():
        try:
            outcome["value"] = work()
        except BaseException as exc:  # handed to the test thread
            outcome["error"] = exc

    thread = threading.Thread(target=run)
    bench.pump.add_busy(thread.is_alive)
    thread.start()
    bench.pump.settle()
    thread.join()
    bench.pump.remove_busy(thread.is_alive)
    if "error" in outcome:
        raise outcome["error"]
    return outcome.get("value")


def test_canopens_sdo_client_works_against_the_simulator(bench):
    """A real master's client: expedited and segmented SDO, a CiA 301 remap of
    TPDO2 and canopen's own read-back of it. (canopen's Map.save() cannot remap
    here: it sizes an ARRAY from sub-index 0, which the procedure has just set
    to 0, and the manual declares 0x1A0x as ARRAY, manual 001 §4.)"""
    sim = bench.ltmr(NODE)
    network = _MasterNetwork(bench.master)
    with shipped_eds("ltmr.eds") as path:
        remote = canopen.RemoteNode(NODE, str(path))
    network.add_node(remote)

    def configure():
        hardware = remote.sdo.upload(0x1009, 0)  # segmented: "M1.0-ES1.0" (manual 001 §4)
        remote.sdo[0x2007][0x03].raw = 50  # FLC1 := 50 %
        remote.sdo[0x1801][1].raw = 0x800002A8  # 1. invalidate TPDO2
        remote.sdo[0x1A01][0].raw = 0  # 2. no entries
        remote.sdo[0x1A01][1].raw = 0x20040210  # 3. 451 trip code
        remote.sdo[0x1A01][2].raw = 0x20041010  #    465 thermal capacity
        remote.sdo[0x1A01][0].raw = 2  # 4. two entries
        remote.sdo[0x1801][1].raw = 0x2A8  # 5. valid
        remote.tpdo.read()
        return hardware, [(var.index, var.subindex) for var in remote.tpdo[2].map]

    hardware, mapped = _blocking(bench, configure)
    assert hardware == b"M1.0-ES1.0"
    assert mapped == [(0x2004, 0x02), (0x2004, 0x10)]
    assert sim.register(ltmr.REG_FLC1) == 50
    sim.set_register(ltmr.REG_TRIP_CODE, ltmr_codes.TRIP_THERMAL_OVERLOAD)
    bench.clear()
    bench.nmt(NMT_START, NODE)
    assert bench.frames_with(0x2A8) == [bytes.fromhex("04 00 00 00")]


# ---------------------------------------------------------------------------- injected faults


def test_injected_faults_load_and_unplug(bench):
    # what [[sim]] faults = [{ fault = "load", value = 400, for = ... }] and "unplug" do
    sim = running_forward(bench)
    assert sim.register(466) == 80  # 466 average current ratio, % FLC: the model's default load
    sim.inject("load", 400.0, True)
    bench.run_ms(100)
    assert sim.register(466) == 400  # a jam draws 400 % FLC
    sim.inject("load", 400.0, False)
    bench.run_ms(100)
    assert sim.register(466) == 80  # back to the load before
    sim.inject("unplug", None, True)
    bench.clear()
    bench.run_ms(300)
    assert bench.frames == [] and not sim.plugged
    sim.inject("unplug", None, False)
    assert sim.plugged
    with pytest.raises(ValueError, match="no fault 'over_current'"):
        sim.inject("over_current", None, True)
