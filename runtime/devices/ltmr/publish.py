"""What the LTMR model (model.py) shows in its registers after each step:
status 455/456, outputs 458/459, thermal capacity 465, currents 466-469 and
500-507, time to trip 511 and minimum wait 450 (manual 001, "L<n>").

Plain ints, no IntFlag operations: this runs at every step. The current
registers, which change only with the current and the FLC, are worked out
again only when those change; and nothing is worked out while everything
publish reads (the model's state and the registers it reads or writes) is
as the last publish left it: it would write the same values again.

    publish(model)        # model.registers now shows the model's state
"""

from __future__ import annotations

import math
from operator import itemgetter
from typing import Protocol

from .bits import STATUS1_CURRENT_SHIFT, Status1, Status2, current_ratio_field
from .codes import TRIP_THERMAL_OVERLOAD
from .datatypes import udint_to_registers
from .defaults import LOCAL_DEFAULT_MODE, RUNNING_THRESHOLD_PERCENT
from .registers import (
    REG_AVERAGE_CURRENT,
    REG_AVERAGE_CURRENT_RATIO,
    REG_CONTROL_SETTING,
    REG_FLC1,
    REG_FLC2,
    REG_FLC_MAX,
    REG_IO_STATUS,
    REG_L1_CURRENT,
    REG_L1_CURRENT_RATIO,
    REG_L2_CURRENT,
    REG_L2_CURRENT_RATIO,
    REG_L3_CURRENT,
    REG_L3_CURRENT_RATIO,
    REG_LOGIC_INPUTS,
    REG_LOGIC_OUTPUTS,
    REG_MIN_WAIT_TIME,
    REG_STATUS_1,
    REG_STATUS_2,
    REG_THERMAL_CAPACITY,
    REG_THERMAL_RESET_THRESHOLD,
    REG_TIME_TO_TRIP,
    REG_TRIP_CLASS,
    REG_TRIP_CODE,
)
from .thermal import NO_TRIP_EXPECTED, minimum_wait_s, steady, time_to_trip_s


class LtmrModel(Protocol):
    """What publish() reads and writes of the model (model.py's LtmrModel):
    the registers, the motor's and the thermal image's state, and the
    memos of its last run."""

    registers: dict
    thermal: float  # θ, a fraction of the trip level
    lo1: bool
    lo2: bool
    comm_lost: bool
    t_ns: int | None
    alarms: list[int]
    lockout_until_ns: int
    current_registers: CurrentRegisters
    shown: tuple | None

    @property
    def starting(self) -> bool: ...

    @property
    def current_percent(self) -> float: ...

    @property
    def uses_flc2(self) -> bool: ...


_S1_CONTROLLER_POWER, _S1_READY, _S1_ON = int(Status1.CONTROLLER_POWER), int(Status1.READY), int(Status1.ON)
_S1_TRIPPED, _S1_ALARM = int(Status1.TRIP | Status1.TRIPPED), int(Status1.ALARM)
_S1_RESET_AUTHORIZED, _S1_RUNNING = int(Status1.RESET_AUTHORIZED), int(Status1.RUNNING)
_S1_IN_REMOTE, _S1_STARTING = int(Status1.IN_REMOTE), int(Status1.STARTING)
_S2_SPEED_FLC2, _S2_NETWORK_COMM_LOSS = int(Status2.SPEED_FLC2), int(Status2.NETWORK_COMM_LOSS)
_S2_TRANSITION_LOCKOUT = int(Status2.TRANSITION_LOCKOUT)
# 456 bits the model computes; the others keep what was written
_STATUS2_KEPT = ~(_S2_SPEED_FLC2 | _S2_NETWORK_COMM_LOSS | _S2_TRANSITION_LOCKOUT) & 0xFFFF
# 458: LO1, LO2 (bits 0, 1) and O.4 (bit 3), the trip relay (95-96 / 97-98, 459 bit 15)
_OUTPUTS_KEPT = ~0b1011 & 0xFFFF
_IO_OUTPUT_LO1, _IO_OUTPUT_LO2, _IO_OUTPUT_TRIP = 1 << 12, 1 << 13, 1 << 15
_IO_INPUTS = 0x0FFF  # 459 bits 0-11 = inputs 1..12 (L3579)
_RATIOS = (REG_AVERAGE_CURRENT_RATIO, REG_L1_CURRENT_RATIO, REG_L2_CURRENT_RATIO, REG_L3_CURRENT_RATIO)
_CURRENTS = (REG_AVERAGE_CURRENT, REG_L1_CURRENT, REG_L2_CURRENT, REG_L3_CURRENT)


# every register publish() reads or writes (the written ones too: an
# output changed by someone else must be written again)
_REGISTERS = itemgetter(
    REG_TRIP_CODE,
    REG_THERMAL_RESET_THRESHOLD,
    REG_CONTROL_SETTING,
    REG_LOGIC_INPUTS,
    REG_FLC1,
    REG_FLC2,
    REG_FLC_MAX,
    REG_TRIP_CLASS,
    REG_STATUS_1,
    REG_STATUS_2,
    REG_LOGIC_OUTPUTS,
    REG_IO_STATUS,
    REG_THERMAL_CAPACITY,
    REG_TIME_TO_TRIP,
    REG_MIN_WAIT_TIME,
    *_RATIOS,
    *_CURRENTS,
    *(reg + 1 for reg in _CURRENTS),
)


def flc_in_use_centiamps(registers: dict, flc2: bool) -> float:
    """FLC in 0.01 A: FLC1 (652), or FLC2 (653) at high speed, in % of FLCmax (96, x 0.1 A)."""
    ratio = registers[REG_FLC2] if flc2 else registers[REG_FLC1]
    return ratio * registers[REG_FLC_MAX] / 10


class CurrentRegisters:
    """466-469 and 500-507 for a current (% FLC) and an FLC (0.01 A), kept
    until either changes."""

    def __init__(self) -> None:
        self._key: tuple | None = None
        self._values: dict = {}

    def values(self, percent: float, flc_centiamps: float) -> dict:
        key = (percent, flc_centiamps)
        if key != self._key:
            ratio = min(0xFFFF, round(percent))  # a balanced three-phase load (simulator choice)
            centiamps = min(0xFFFFFFFF, round(percent / 100 * flc_centiamps))
            high, low = udint_to_registers(centiamps)  # lower register = MSW (A5)
            values = dict.fromkeys(_RATIOS, ratio)
            for reg in _CURRENTS:
                values[reg], values[reg + 1] = high, low
            self._key, self._values = key, values
        return self._values


def _shown(model: LtmrModel, percent: float, now: int) -> tuple:
    """Everything publish() reads, and the registers it writes. θ, which
    changes at every step while the motor heats or cools, counts as 465
    shows it (whole percent), but for what reads it finely: a thermal trip
    (455 bit 5 against 608, 450) and an overload current (511)."""
    r = model.registers
    theta = model.thermal
    code = r[REG_TRIP_CODE]
    if code == TRIP_THERMAL_OVERLOAD or (not code and steady(percent) > 1):
        shown_theta = theta
    else:
        shown_theta = math.floor(theta * 100 + 1e-7)
    return (
        _REGISTERS(r),
        percent,
        shown_theta,
        model.lo1,
        model.lo2,
        bool(model.alarms),
        model.starting,
        model.uses_flc2,
        model.comm_lost,
        now < model.lockout_until_ns,
    )


def publish(model: LtmrModel) -> None:
    now = model.t_ns or 0
    percent = model.current_percent
    if _shown(model, percent, now) == model.shown:
        return  # as the last publish left it: it would write the same again
    _publish(model, percent, now)
    model.shown = _shown(model, percent, now)


def _publish(model: LtmrModel, percent: float, now: int) -> None:
    r = model.registers
    code = r[REG_TRIP_CODE]
    tripped = code != 0
    lo1, lo2 = model.lo1, model.lo2
    theta = model.thermal
    thermal_trip = code == TRIP_THERMAL_OVERLOAD
    status1 = _S1_CONTROLLER_POWER
    if tripped:
        status1 |= _S1_TRIPPED
        # 455 bit 5: a thermal trip once θ fell below the reset threshold (608); any other at once
        if not thermal_trip or theta * 100 < r[REG_THERMAL_RESET_THRESHOLD]:
            status1 |= _S1_RESET_AUTHORIZED
    else:
        status1 |= _S1_READY
    if lo1 or lo2:
        status1 |= _S1_ON
    if model.alarms:
        status1 |= _S1_ALARM
    if percent > RUNNING_THRESHOLD_PERCENT:  # 455 bit 7 (L3533)
        status1 |= _S1_RUNNING
    if not r[REG_CONTROL_SETTING] & LOCAL_DEFAULT_MODE:
        status1 |= _S1_IN_REMOTE
    if model.starting:
        status1 |= _S1_STARTING
    r[REG_STATUS_1] = status1 | current_ratio_field(percent) << STATUS1_CURRENT_SHIFT

    flc2 = model.uses_flc2
    status2 = _S2_SPEED_FLC2 if flc2 else 0
    if model.comm_lost:
        status2 |= _S2_NETWORK_COMM_LOSS
    if now < model.lockout_until_ns:
        status2 |= _S2_TRANSITION_LOCKOUT
    r[REG_STATUS_2] = (r[REG_STATUS_2] & _STATUS2_KEPT) | status2

    r[REG_LOGIC_OUTPUTS] = (r[REG_LOGIC_OUTPUTS] & _OUTPUTS_KEPT) | (lo1 | lo2 << 1 | tripped << 3)
    r[REG_IO_STATUS] = (r[REG_LOGIC_INPUTS] & _IO_INPUTS) | (
        (_IO_OUTPUT_LO1 if lo1 else 0) | (_IO_OUTPUT_LO2 if lo2 else 0) | (_IO_OUTPUT_TRIP if tripped else 0)
    )

    # whole percent, rounded down so 465 and the thresholds (608, 609) agree
    r[REG_THERMAL_CAPACITY] = min(0xFFFF, math.floor(theta * 100 + 1e-7))
    r.update(model.current_registers.values(percent, flc_in_use_centiamps(r, flc2)))
    trip_class = r[REG_TRIP_CLASS]
    r[REG_TIME_TO_TRIP] = NO_TRIP_EXPECTED if tripped else time_to_trip_s(theta, percent, trip_class)
    r[REG_MIN_WAIT_TIME] = minimum_wait_s(theta, r[REG_THERMAL_RESET_THRESHOLD], trip_class) if thermal_trip else 0
