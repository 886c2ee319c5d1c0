"""What an Eaton drive's register image means to its motion and its monitor
values, worked out once per change of the image instead of at every tick.

The model (model.py) builds an Effective whenever a register changed and
keeps it until the next change: the control word in effect, the setpoint and
its direction, the ramp rates, the comm-loss timeout, the motor ratings.
Effective.monitor() turns an output frequency into the monitor registers
ID 7-10 in integer arithmetic, rounding exactly as registers.Scale.to_raw
(halves away from zero) on the exact rational values.
"""

from __future__ import annotations

from fractions import Fraction

from . import parameters as eaton_parameters
from . import registers as eaton
from . import settings as eaton_settings
from .defaults import MAGNETISING_CURRENT_RATIO, NAMES, quick_scale, scale
from .registers import ControlWord, Family

S = 1_000_000_000
ZERO = Fraction(0)


def round_ratio(num: int, den: int) -> int:
    """num / den rounded to the nearest integer, halves away from zero (as
    registers._round_half_away on Fraction(num, den))."""
    if den < 0:
        num, den = -num, -den
    if num >= 0:
        return (2 * num + den) // (2 * den)
    return -((-2 * num + den) // (2 * den))


class Effective:
    """The drive's settings as they act now; built from a model's registers
    (drive._regs, found by drive._row and drive._param)."""

    __slots__ = (
        "bus_control",
        "cw",
        "setpoint",
        "setpoint_ff8",
        "target",
        "target_ff8",
        "rates",
        "comm_timeout",
        "rated_hz",
        "_speed",
        "_rated",
        "_current",
        "_torque",
        "_power",
    )

    def __init__(self, drive) -> None:
        family, regs = drive.family, drive._regs
        names = NAMES[family]

        def hz(key: str) -> Fraction:
            row = drive._row(names[key])
            return scale(row).step * row.extract(regs[row.register])

        source = drive._param(eaton_parameters.CONTROL_SOURCE_PARAMETER[family])
        self.bus_control = source in eaton_parameters.MODBUS_CONTROL_SOURCES[family]
        cw = self.cw = regs[eaton.REG_CONTROL_WORD] if self.bus_control else 0

        # the setpoint: ID 2 in 0.1 Hz (L792) limited to f-min..f-max (L784-790); FF1 (bit 6) and
        # "Sollwert mit 0 überschreiben" (bit 7) replace it, 0 wins over f-min (simulator choice);
        # DA1 P5-06 = 3 runs at P2-08 (L388): setpoint_ff8
        f_max, f_min = hz("f_max"), hz("f_min")

        def limited(value: Fraction) -> Fraction:
            return min(max(value, f_min), f_max)

        if cw & ControlWord.ZERO_SETPOINT:
            self.setpoint = ZERO
            self.setpoint_ff8 = ZERO if "ff8" in names else None
        else:
            if cw & ControlWord.FIXED_FREQUENCY_1:
                self.setpoint = limited(hz("ff1"))
            else:
                self.setpoint = limited(eaton.SPEED.step * regs[eaton.REG_SPEED_SETPOINT])
            self.setpoint_ff8 = limited(hz("ff8")) if "ff8" in names else None
        reverse = cw & ControlWord.REVERSE
        self.target = -self.setpoint if reverse else self.setpoint
        ff8 = self.setpoint_ff8
        self.target_ff8 = None if ff8 is None else (-ff8 if reverse else ff8)

        # ramps: Hz per ns; None = no ramp (a ramp time of 0 or an f-max of 0). A ramp time runs
        # from 0 to f-max (simulator choice: the manual does not say what a ramp time refers to)
        if family is Family.DA1:  # ID 4 replaces both ramps: DA1 P5-07 = 1 (L389)
            bus_ramps = drive._param(eaton_parameters.DA1_FIELDBUS_RAMP_CONTROL) == 1
        elif family is Family.DE1:
            bus_ramps = False
        else:  # DB1/DC1 P-12 = 4 (L397, L413)
            bus_ramps = source == eaton_parameters.DB1_DC1_MODBUS_RAMPS_SOURCE
        rates: dict[str, Fraction | None] = {}
        for key in ("accel", "decel", "quick"):
            row = drive._row(names[key])
            if key == "quick":
                seconds = quick_scale(family, regs, row).step * row.extract(regs[row.register])
            elif bus_ramps:
                seconds = eaton.RAMP_TIME.step * regs[eaton.REG_RAMP_TIME]
            else:
                seconds = scale(row).step * row.extract(regs[row.register])
            rates[key] = None if seconds <= 0 or f_max <= 0 else f_max / (seconds * S)
        self.rates = rates
        self.comm_timeout = _comm_timeout(drive)

        rated_hz = self.rated_hz = hz("frequency")
        current = drive._row(names["current"])
        rated_a = scale(current).step * drive._param(current.number)
        self._speed = _ratio(eaton.SPEED.step)
        self._rated = (rated_hz.numerator, rated_hz.denominator)
        self._current = (rated_a.numerator, rated_a.denominator, _ratio(eaton.CURRENT.step))
        torque = family in eaton.PROCESS_DATA[eaton.REG_TORQUE].families
        self._torque = _ratio(eaton.TORQUE.step) if torque else None
        self._power = (regs[eaton.REG_POWER_RATING], _ratio(eaton.OUTPUT_POWER.step))

    def monitor(self, out: Fraction, modulating: bool) -> tuple[int, int, int | None, int | None]:
        """(ID 7 actual speed, ID 8 current, ID 9 torque, ID 10 power) at the
        output frequency out; torque and power None where the family has
        none. ID 7 without sign, the direction is status bit 2 (A24, as
        eaton.speed_setpoint_raw). The current model: magnetising current
        plus a load current proportional to the output frequency, rated
        current at the motor rated frequency; torque proportional to speed
        (a fan-like load), power = rated power x torque x speed."""
        sn, sd = abs(out.numerator), out.denominator  # the speed |out| = sn / sd Hz
        step_n, step_d = self._speed
        speed = min(round_ratio(sn * step_d, sd * step_n), 0xFFFF)
        has_torque = self._torque is not None
        if not modulating:  # no current, no torque, no power
            return speed, 0, 0 if has_torque else None, 0 if has_torque else None
        hn, hd = self._rated
        if hn:  # load = min(speed / rated_hz, 2) = ln / ld
            ln, ld = sn * hd, sd * hn
            if ln > 2 * ld:
                ln, ld = 2, 1
        else:
            ln, ld = 0, 1
        an, ad, (cn, cd) = self._current
        rn, rd = MAGNETISING_CURRENT_RATIO.numerator, MAGNETISING_CURRENT_RATIO.denominator
        # rated_a x (ratio + (1 - ratio) x load), in steps of CURRENT
        current = min(round_ratio(an * (rn * ld + (rd - rn) * ln) * cd, ad * rd * ld * cn), 0xFFFF)
        if self._torque is None:
            return speed, current, None, None
        tn, td = self._torque
        torque = round_ratio(100 * ln * td, ld * tn)  # 100 % x load
        rating, (on, od) = self._power
        power = round_ratio(rating * ln * ln * od, ld * ld * on)  # rating x torque / 100 % x load
        return speed, current, torque, power


def _ratio(step: Fraction) -> tuple[int, int]:
    return step.numerator, step.denominator


def _comm_timeout(drive):
    """(timeout in ns, reaction) of the configured comm-loss monitoring,
    None when off. The watchdog runs only while the drive takes its
    commands from Modbus (simulator choice)."""
    if drive.family is Family.DA1:
        raw = drive._param(eaton_settings.DA1_COMM_TIMEOUT)
        if raw == eaton_settings.DA1_COMM_TIMEOUT_OFF:
            return None
        ns = int(eaton_settings.DA1_COMM_TIMEOUT_SCALE.step * raw * S)
        action = drive._param(eaton_settings.DA1_COMM_LOSS_ACTION)
        try:
            return ns, eaton_settings.Da1CommLossAction(action)
        except ValueError:
            return ns, eaton_settings.Da1CommLossAction.TRIP
    code = drive._param(eaton_settings.COMM_TIMEOUT_PARAMETER[drive.family], "timeout")
    timeout = eaton_settings.COMM_TIMEOUT_CODES.get(code)
    if timeout is None or timeout.timeout_ms is None:
        return None
    return timeout.timeout_ms * 1_000_000, timeout.reaction
