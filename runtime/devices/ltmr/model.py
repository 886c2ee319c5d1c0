"""The TeSys T LTMR as a device, without its bus: its register image and
what it does with it over time. Pure: no CAN, no threads, no clock of its
own (advance_to(now_ns) moves it).

    model = LtmrModel({652: 50})
    model.registers[704] = Control1.RUN_FORWARD     # what an RPDO would write
    model.advance_to(2_000_000_000)
    model.lo1, model.motor_running, model.registers[455]

It reads its commands (704), operating mode (540) and settings (541, 601,
602, 606, 608, 609, 631, 632, 643, 644, 652, 653, 682, 683) from the
registers and writes what it shows back: status 455/456, outputs 458/459,
thermal capacity 465, currents 466-469 and 500-507, time to trip 511,
minimum wait 450, trips 451-453, alarms 460/461, a few counters. Registers
it does not own keep whatever was written to them.

Numbers come from manual 001 (DOCA0132EN, shared/manuals/001_*.txt, "L<n>")
and its digest; where the manual gives no value the constant says
"simulator choice, not in the manual".

Thermal image (class N): with θ the thermal capacity as a fraction of the
trip level and I the current in multiples of FLC,

    dθ/dt = ((I / Iu)² − θ) / τ            Iu = ULTIMATE_TRIP_RATIO = 1.125

so from cold (θ = 0) at constant I, θ(t) = (I/Iu)² (1 − e^(−t/τ)) and the
trip (θ = 1) comes at t = −τ ln(1 − (Iu/I)²). An IEC 60947-4-1 class-N relay
trips within N s at 7.2 × FLC from cold; taking exactly N s there gives

    τ = −N / ln(1 − (Iu/7.2)²) = N / 0.024717 = 40.46 · N s   (class 10: 404.6 s)

and then, e.g., 4 × FLC trips after 33.3 s (class 10), 1.2 × FLC after
about 14 min, and 1.05 × FLC never (steady state 87 %), inside IEC's
"no trip at 1.05 Ie, trip at 1.2 Ie within 2 h". Cooling uses the same τ.
Within one step the current is constant and the exponential is exact.
"""

from __future__ import annotations

import math

from .bits import (
    FACTORY_SETTINGS,
    GENERAL_CONFIG2_RESET_MODE_MASK,
    STATUS1_CURRENT_SHIFT,
    AlarmEnable1,
    AlarmRegister1,
    Control1,
    Control2,
    GeneralConfig1,
    Status1,
    Status2,
    TripEnable1,
    TripRegister1,
    current_ratio_field,
)
from .codes import (
    ALARM_NETWORK_COMM,
    ALARM_THERMAL_OVERLOAD,
    TRIP_NETWORK_COMM,
    TRIP_TEST,
    TRIP_THERMAL_OVERLOAD,
    FallbackStrategy,
    OperatingMode,
    ResetMode,
    fallback_allowed,
    is_valid_operating_mode,
)
from .datatypes import encode_commercial_reference, udint_from_registers, udint_to_registers
from .registers import (
    REG_ALARM_CODE,
    REG_ALARM_ENABLE_1,
    REG_ALARM_REGISTER_1,
    REG_AVERAGE_CURRENT,
    REG_AVERAGE_CURRENT_RATIO,
    REG_CONTROL_1,
    REG_CONTROL_2,
    REG_CONTROL_SETTING,
    REG_FLC1,
    REG_FLC2,
    REG_FLC_MAX,
    REG_GENERAL_CONFIG_1,
    REG_GENERAL_CONFIG_2,
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
    REG_MOTOR_STARTS_COUNT,
    REG_NETWORK_FALLBACK,
    REG_OPERATING_MODE,
    REG_STATUS_1,
    REG_STATUS_2,
    REG_THERMAL_ALARM_THRESHOLD,
    REG_THERMAL_CAPACITY,
    REG_THERMAL_RESET_THRESHOLD,
    REG_TIME_TO_TRIP,
    REG_TRIP_CLASS,
    REG_TRIP_CODE,
    REG_TRIP_ENABLE_1,
    REG_TRIP_REGISTER_1,
    REG_TRIP_REGISTER_2,
    REGISTERS,
)

S = 1_000_000_000

# ---------------------------------------------------------------- simulator choices (not in the manual)

DEFAULT_FLC_MAX = 80  # 96, x 0.1 A: 8.0 A, the digest's example (digest 001 §6.4)
DEFAULT_FLC1 = 50  # 652, % FLCmax: 4.0 A
DEFAULT_FLC2 = 100  # 653, % FLCmax: 8.0 A at high speed
DEFAULT_TRIP_CLASS = 10  # 606, s
DEFAULT_THERMAL_RESET_THRESHOLD = 75  # 608, % trip level
DEFAULT_THERMAL_ALARM_THRESHOLD = 85  # 609, % trip level
DEFAULT_RESET_MODE = ResetMode.REMOTE
DEFAULT_OPERATING_MODE = OperatingMode.REVERSER_2W
DEFAULT_NETWORK_FALLBACK = FallbackStrategy.OFF  # 682: a lost PLC stops the motor
DEFAULT_TRANSITION_TIMEOUT_S = 0  # 541, s: no anti-backspin wait unless configured
DEFAULT_STEP_TIMEOUT_S = 5  # 643, unit not printed (manual 001 L4708): taken as s like 541
DEFAULT_STEP_THRESHOLD = 150  # 644, % FLC, unit not printed (L4713)
DEFAULT_LOAD_PERCENT = 80.0  # % FLC while running
DEFAULT_COMMERCIAL_REFERENCE = "LTMR08CBD"  # 64-69: an LTMR with an 8 A current range
DEFAULT_CURRENT_RANGE_MAX = 80  # 81, x 0.1 A
# Enabled protections: thermal overload trip (631 bit 3), self test (bit 9, the
# factory setting, L4519); thermal overload and network port alarms (632 bits 3, 15).
# The network port trip (631 bit 15) is off: a lost PLC raises an alarm and
# applies the fallback, and the motor runs again without a trip reset.
DEFAULT_TRIP_ENABLE_1 = TripEnable1.THERMAL_OVERLOAD | TripEnable1.SELF_TEST
DEFAULT_ALARM_ENABLE_1 = AlarmEnable1.THERMAL_OVERLOAD | AlarmEnable1.NETWORK_PORT
# 601: config via network port (factory, L230), 3 phases (bits 13-14 = 2, DT_PhaseNumber)
DEFAULT_GENERAL_CONFIG_1 = GeneralConfig1.CONFIG_VIA_NETWORK | (2 << 13)

START_DURATION_NS = 1 * S  # inrush of a direct-on-line start
START_CURRENT_PERCENT = 600.0  # % FLC during the inrush (or the load, if higher: a locked rotor)
ULTIMATE_TRIP_RATIO = 1.125  # Iu: between IEC 60947-4-1's 1.05 (no trip) and 1.2 (trip)
TAU_PER_TRIP_CLASS = -1 / math.log(1 - (ULTIMATE_TRIP_RATIO / 7.2) ** 2)  # τ / N, see the docstring
MAX_STEP_NS = 10_000_000  # events (trip, alarm, reset threshold) are seen within 10 ms
NO_TRIP_EXPECTED = 0xFFFF  # 511 while the thermal image is not heading for a trip

# ---------------------------------------------------------------- from the manual

RUNNING_THRESHOLD_PERCENT = 10  # 455 bit 7: "current greater than 10% FLC" (L3533)
DIRECT_TRANSITION = 1 << 9  # 683 bit 9: 1 = stop not required during transition (L4870)
LOCAL_DEFAULT_MODE = 1 << 2  # 683 bit 2: 0 = remote, 1 = local (with LTMCU)
REMOTE_CHANNEL_SHIFT = 5  # 683 bits 5-6: 0 = network, 1 = terminal strip, 2 = HMI
REG_TRANSITION_TIMEOUT = 541  # s
REG_STEP_TIMEOUT = 643
REG_STEP_THRESHOLD = 644
REG_CURRENT_RANGE_MAX = 81
REG_COMMERCIAL_REFERENCE = 64
REG_THERMAL_TRIPS_COUNT = 103
REG_NETWORK_PORT_TRIPS_COUNT = 114
REG_THERMAL_ALARMS_COUNT = 116
REG_TRIPS_COUNT = 122
REG_ALARMS_COUNT = 123
REG_LO1_CLOSINGS = 124  # UDInt 124-125
REG_LO2_CLOSINGS = 126  # UDInt 126-127
STATISTICS = range(100, 450)  # cleared by 705 bit 1

_OVERLOAD = {OperatingMode.OVERLOAD_2W, OperatingMode.OVERLOAD_3W}
_INDEPENDENT = {OperatingMode.INDEPENDENT_2W, OperatingMode.INDEPENDENT_3W}
_REVERSER = {OperatingMode.REVERSER_2W, OperatingMode.REVERSER_3W}
_TWO_STEP = {OperatingMode.TWO_STEP_2W, OperatingMode.TWO_STEP_3W}
_TWO_SPEED = {OperatingMode.TWO_SPEED_2W, OperatingMode.TWO_SPEED_3W}
_THREE_WIRE = {
    OperatingMode.OVERLOAD_3W,
    OperatingMode.INDEPENDENT_3W,
    OperatingMode.REVERSER_3W,
    OperatingMode.TWO_STEP_3W,
    OperatingMode.TWO_SPEED_3W,
}
_RUN_BITS = Control1.RUN_FORWARD | Control1.RUN_REVERSE

# 456 bits this model computes; the others keep what was written
_STATUS2_OWNED = Status2.SPEED_FLC2 | Status2.NETWORK_COMM_LOSS | Status2.TRANSITION_LOCKOUT
# 458: LO1, LO2 (bits 0, 1) and O.4 (bit 3), the trip relay (95-96 / 97-98, 459 bit 15)
_OUTPUTS_OWNED = 0b1011
# _publish's bits as plain ints
_S1_CONTROLLER_POWER, _S1_READY, _S1_ON = int(Status1.CONTROLLER_POWER), int(Status1.READY), int(Status1.ON)
_S1_TRIPPED, _S1_ALARM = int(Status1.TRIP | Status1.TRIPPED), int(Status1.ALARM)
_S1_RESET_AUTHORIZED, _S1_RUNNING = int(Status1.RESET_AUTHORIZED), int(Status1.RUNNING)
_S1_IN_REMOTE, _S1_STARTING = int(Status1.IN_REMOTE), int(Status1.STARTING)
_S2_SPEED_FLC2, _S2_NETWORK_COMM_LOSS = int(Status2.SPEED_FLC2), int(Status2.NETWORK_COMM_LOSS)
_S2_TRANSITION_LOCKOUT = int(Status2.TRANSITION_LOCKOUT)
_STATUS2_KEPT = ~int(_STATUS2_OWNED) & 0xFFFF
_IO_OUTPUT_LO1, _IO_OUTPUT_LO2, _IO_OUTPUT_TRIP = 1 << 12, 1 << 13, 1 << 15
_IO_INPUTS = 0x0FFF  # 459 bits 0-11 = inputs 1..12 (L3579)


def default_registers() -> dict:
    """Every register of the map at 0, then the manual's factory settings,
    then the simulator's choices above."""
    registers = dict.fromkeys(REGISTERS, 0)
    registers.update(FACTORY_SETTINGS)
    for i, word in enumerate(encode_commercial_reference(DEFAULT_COMMERCIAL_REFERENCE)):
        registers[REG_COMMERCIAL_REFERENCE + i] = word
    registers.update(
        {
            REG_CURRENT_RANGE_MAX: DEFAULT_CURRENT_RANGE_MAX,
            REG_FLC_MAX: DEFAULT_FLC_MAX,
            REG_OPERATING_MODE: DEFAULT_OPERATING_MODE,
            REG_TRANSITION_TIMEOUT: DEFAULT_TRANSITION_TIMEOUT_S,
            REG_GENERAL_CONFIG_1: DEFAULT_GENERAL_CONFIG_1,
            REG_GENERAL_CONFIG_2: (FACTORY_SETTINGS.get(REG_GENERAL_CONFIG_2, 0) & ~GENERAL_CONFIG2_RESET_MODE_MASK)
            | DEFAULT_RESET_MODE,
            REG_TRIP_CLASS: DEFAULT_TRIP_CLASS,
            REG_THERMAL_RESET_THRESHOLD: DEFAULT_THERMAL_RESET_THRESHOLD,
            REG_THERMAL_ALARM_THRESHOLD: DEFAULT_THERMAL_ALARM_THRESHOLD,
            REG_TRIP_ENABLE_1: DEFAULT_TRIP_ENABLE_1,
            REG_ALARM_ENABLE_1: DEFAULT_ALARM_ENABLE_1,
            REG_STEP_TIMEOUT: DEFAULT_STEP_TIMEOUT_S,
            REG_STEP_THRESHOLD: DEFAULT_STEP_THRESHOLD,
            REG_FLC1: DEFAULT_FLC1,
            REG_FLC2: DEFAULT_FLC2,
            REG_NETWORK_FALLBACK: DEFAULT_NETWORK_FALLBACK,
        }
    )
    return {reg: int(value) & 0xFFFF for reg, value in registers.items()}


class LtmrModel:
    def __init__(self, registers: dict | None = None, *, load_percent: float = DEFAULT_LOAD_PERCENT) -> None:
        self.registers = default_registers()
        for reg, value in (registers or {}).items():
            self.registers[int(reg)] = int(value) & 0xFFFF
        self.load_percent = float(load_percent)
        self.thermal = 0.0  # θ, fraction of the trip level
        self.lo1 = False
        self.lo2 = False
        self.fallback: FallbackStrategy | None = None  # applied after a network communication loss
        self.comm_lost = False
        self.t_ns: int | None = None
        self._start_end_ns: int | None = None  # end of the inrush of the running start
        self._running_since_ns: int | None = None
        self._selected = 0  # reverser / two-speed: 1 = LO1, 2 = LO2, 0 = none
        self._last_selected = 0
        self._lockout_until_ns = 0  # motor transition timeout 541 after a stop
        self._wait_release = False  # a start needs the run bits released first
        self._step = 1  # two-step: step 1 (LO1) or 2 (LO2)
        self._held = (False, False)  # outputs at the moment of a HOLD fallback
        self._previous_control = 0
        self._previous_control2 = 0
        self._reset_pressed = False
        self._alarms: list[int] = []  # active alarm codes, the newest last

    # ------------------------------------------------------------------ what a user sees

    @property
    def operating_mode(self) -> int:
        return self.registers[REG_OPERATING_MODE]

    @property
    def tripped(self) -> bool:
        return self.registers[REG_TRIP_CODE] != 0

    @property
    def trip_code(self) -> int:
        return self.registers[REG_TRIP_CODE]

    @property
    def starting(self) -> bool:
        return self._start_end_ns is not None and self.t_ns is not None and self.t_ns < self._start_end_ns

    @property
    def motor_on(self) -> bool:
        """A contactor output is closed: the motor is switched on (note A: "motor OFF" is the opposite)."""
        return self.lo1 or self.lo2

    @property
    def current_percent(self) -> float:
        """The average current in % of the FLC in use."""
        if not self._motor_energized():
            return 0.0
        if self.starting:
            return max(START_CURRENT_PERCENT, self.load_percent)
        return self.load_percent

    @property
    def motor_running(self) -> bool:
        return self.current_percent > RUNNING_THRESHOLD_PERCENT  # 455 bit 7 (L3533)

    @property
    def flc_in_use_centiamps(self) -> float:
        """FLC in 0.01 A: FLC1 (652), or FLC2 (653) at high speed, in % of FLCmax (96, x 0.1 A)."""
        ratio = self.registers[REG_FLC2] if self._uses_flc2() else self.registers[REG_FLC1]
        return ratio * self.registers[REG_FLC_MAX] / 10

    @property
    def tau_s(self) -> float:
        return max(1, self.registers[REG_TRIP_CLASS]) * TAU_PER_TRIP_CLASS

    @property
    def reset_authorized(self) -> bool:
        """455 bit 5. A thermal trip once the thermal capacity fell below the
        thermal overload trip reset threshold (608); any other trip at once."""
        if not self.tripped:
            return False
        if self.trip_code == TRIP_THERMAL_OVERLOAD:
            return self.thermal * 100 < self.registers[REG_THERMAL_RESET_THRESHOLD]
        return True

    @property
    def reset_mode(self) -> int:
        return self.registers[REG_GENERAL_CONFIG_2] & GENERAL_CONFIG2_RESET_MODE_MASK

    @property
    def in_remote(self) -> bool:
        return not self.registers[REG_CONTROL_SETTING] & LOCAL_DEFAULT_MODE

    @property
    def network_control(self) -> bool:
        """Commands of 704 count: remote mode with the network as remote channel (683 bits 2, 5-6)."""
        channel = (self.registers[REG_CONTROL_SETTING] >> REMOTE_CHANNEL_SHIFT) & 0x3
        return self.in_remote and channel == 0

    @property
    def config_mode(self) -> bool:
        return bool(self.registers[REG_GENERAL_CONFIG_1] & GeneralConfig1.CONFIG_MODE)

    @property
    def config_via_network(self) -> bool:
        return bool(self.registers[REG_GENERAL_CONFIG_1] & GeneralConfig1.CONFIG_VIA_NETWORK)

    # ------------------------------------------------------------------ inputs from outside

    def set_load(self, percent_flc: float) -> None:
        """The mechanical load, as the current it draws while running (% FLC)."""
        self.load_percent = max(0.0, float(percent_flc))

    def press_reset(self) -> None:
        """The Test/Reset button on the device (or the HMI): resets a trip at the
        next step if the reset is authorized, whatever the reset mode."""
        self._reset_pressed = True

    def set_register(self, reg: int, value: int) -> None:
        self.registers[reg] = int(value) & 0xFFFF

    def network_lost(self) -> None:
        """Network communication loss (manual 000 §1.4/§8.4, digest 001 §1.4):
        456 bit 8; alarm 109 if enabled (632 bit 15); trip 109 if enabled
        (631 bit 15); the outputs go to the fallback of 682. A fallback the
        operating mode does not allow (DT_OutputFallbackStrategy's "Motor
        Modes" column) is applied as LO1, LO2 off (simulator choice)."""
        if self.comm_lost:
            return
        self.comm_lost = True
        if self.registers[REG_ALARM_ENABLE_1] & AlarmEnable1.NETWORK_PORT:
            self._set_alarm(ALARM_NETWORK_COMM, True)
        if self.registers[REG_TRIP_ENABLE_1] & TripEnable1.NETWORK_PORT and not self.tripped:
            self._trip(TRIP_NETWORK_COMM, TripRegister1.NETWORK_PORT)
            self._count(REG_NETWORK_PORT_TRIPS_COUNT)
        strategy = self.registers[REG_NETWORK_FALLBACK]
        mode = self.operating_mode
        if (
            strategy not in FallbackStrategy._value2member_map_
            or not is_valid_operating_mode(mode)
            or not fallback_allowed(strategy, mode)
        ):
            strategy = FallbackStrategy.OFF
        self.fallback = FallbackStrategy(strategy)
        self._held = (self.lo1, self.lo2)
        self._publish()

    def network_restored(self) -> None:
        """Communication is back (Operational again): 456 bit 8 and alarm 109
        clear; a trip 109 stays until reset; the fallback stays until
        clear_fallback() (a new RPDO)."""
        if not self.comm_lost:
            return
        self.comm_lost = False
        self._set_alarm(ALARM_NETWORK_COMM, False)
        self._publish()

    def clear_fallback(self) -> None:
        self.fallback = None

    def restart(self) -> None:
        """The controller restarts (power cycle, NMT reset node): commands and
        outputs are gone; settings, trips and the thermal memory are kept
        (non-volatile, simulator choice)."""
        for reg in (REG_CONTROL_1, REG_CONTROL_2, 700):
            self.registers[reg] = 0
        self._previous_control = self._previous_control2 = 0
        self.fallback = None
        self.comm_lost = False
        self._set_alarm(ALARM_NETWORK_COMM, False)
        self._select_none()
        self._drive(False, False)
        self._wait_release = False
        self._publish()

    # ------------------------------------------------------------------ time

    def advance_to(self, now_ns: int) -> None:
        if self.t_ns is None:
            self.t_ns = now_ns
        while True:
            self._apply_commands()
            if self.t_ns >= now_ns:
                break
            dt = min(now_ns - self.t_ns, MAX_STEP_NS)
            if self._start_end_ns is not None and self.starting:
                dt = min(dt, self._start_end_ns - self.t_ns)  # the inrush ends on time
            self._heat(dt)
            self.t_ns += dt
            self._protect()
        self._publish()

    def _heat(self, dt_ns: int) -> None:
        """θ over dt at the present current, exact for a constant current."""
        steady = (self.current_percent / 100 / ULTIMATE_TRIP_RATIO) ** 2
        self.thermal = steady + (self.thermal - steady) * math.exp(-dt_ns / S / self.tau_s)

    def _protect(self) -> None:
        percent = self.thermal * 100
        alarm = (
            bool(self.registers[REG_ALARM_ENABLE_1] & AlarmEnable1.THERMAL_OVERLOAD)
            and percent >= self.registers[REG_THERMAL_ALARM_THRESHOLD]
        )
        self._set_alarm(ALARM_THERMAL_OVERLOAD, alarm)
        # 1e-9: the trip of the class definition (exactly N s at 7.2 FLC) must not be lost to rounding
        if (
            not self.tripped
            and self.registers[REG_TRIP_ENABLE_1] & TripEnable1.THERMAL_OVERLOAD
            and self.thermal >= 1 - 1e-9
        ):
            self._trip(TRIP_THERMAL_OVERLOAD, TripRegister1.THERMAL_OVERLOAD)
            self._count(REG_THERMAL_TRIPS_COUNT)

    # ------------------------------------------------------------------ commands -> outputs

    def _apply_commands(self) -> None:
        now = self.t_ns or 0
        control = self.registers[REG_CONTROL_1]
        rising = control & ~self._previous_control
        self._previous_control = control
        self._apply_control2()
        if (
            rising & Control1.SELF_TEST
            and not self.tripped
            and self.registers[REG_TRIP_ENABLE_1] & TripEnable1.SELF_TEST
        ):
            self._trip(TRIP_TEST, TripRegister1.TEST)  # trip code 10, 452 bit 9 (L3448)
        if self.tripped:
            self._try_reset(bool(rising & Control1.TRIP_RESET))
        self._reset_pressed = False
        if self.tripped:
            self._select_none()
            self._drive(False, False)
            return
        if self.fallback is not None:
            self._drive(*self._fallback_outputs())
            return
        if not self.network_control:
            control = 0
        if self._wait_release:
            if control & _RUN_BITS:
                self._drive(False, False)
                return
            self._wait_release = False
        self._drive(*self._command_outputs(control, now))

    def _try_reset(self, remote_edge: bool) -> None:
        """Reset per 602 bits 0-2 (DT_ResetMode): the device's button always;
        704 bit 3 (rising edge) in remote mode; a thermal trip by itself in
        automatic mode. Only once the reset is authorized."""
        if not self.reset_authorized:
            return
        mode = self.reset_mode
        automatic = mode == ResetMode.AUTOMATIC and self.trip_code == TRIP_THERMAL_OVERLOAD
        if self._reset_pressed or (remote_edge and mode == ResetMode.REMOTE) or automatic:
            self.registers[REG_TRIP_CODE] = 0
            self.registers[REG_TRIP_REGISTER_1] = 0
            self.registers[REG_TRIP_REGISTER_2] = 0

    def _apply_control2(self) -> None:
        """705 (rising edges): bit 1 clear statistics, bit 2 clear thermal capacity
        level (L4938-4955). Bits 0, 3 and 4 (clear settings) are not simulated."""
        control2 = self.registers[REG_CONTROL_2]
        rising = control2 & ~self._previous_control2
        self._previous_control2 = control2
        if rising & Control2.CLEAR_THERMAL_CAPACITY:
            self.thermal = 0.0
        if rising & Control2.CLEAR_STATISTICS:
            for reg in STATISTICS:
                if reg in self.registers:
                    self.registers[reg] = 0

    def _command_outputs(self, control: int, now: int) -> tuple:
        mode = self.operating_mode
        forward = bool(control & Control1.RUN_FORWARD)
        reverse = bool(control & Control1.RUN_REVERSE)
        if mode in _OVERLOAD or mode in _INDEPENDENT:
            # 704 bits 0/1 drive LO1/LO2, in overload mode too (German edition L2576, A12)
            return forward, reverse
        if mode in _REVERSER:
            # bit 0 forward (LO1), bit 1 reverse (LO2), both: stop
            return self._select(1 if forward and not reverse else 2 if reverse and not forward else 0, now)
        if mode in _TWO_SPEED:
            # run with bit 0: bit 6 low speed -> LO1 on FLC1, without -> LO2 (high speed) on FLC2
            low = bool(control & Control1.LOW_SPEED)
            return self._select((1 if low else 2) if forward else 0, now)
        if mode in _TWO_STEP:
            return self._two_step(forward, now)
        return False, False  # custom logic programs are not simulated

    def _select(self, target: int, now: int) -> tuple:
        """Reverser and two-speed: one of LO1/LO2. Changing from one to the
        other needs a stop first unless 683 bit 9 (direct transition); after a
        stop, the other output waits the motor transition timeout 541."""
        current = self._selected
        if current and target and target != current and not self.registers[REG_CONTROL_SETTING] & DIRECT_TRANSITION:
            self._wait_release = True  # "stop required during transition" (L4870)
            target = 0
        if current and target != current:
            self._last_selected = current
            self._lockout_until_ns = now + self.registers[REG_TRANSITION_TIMEOUT] * S
            self._selected = 0
        if target and target != self._last_selected and now < self._lockout_until_ns:
            target = 0  # transition lockout, 456 bit 9
        if target:
            self._selected = target
        return self._selected == 1, self._selected == 2

    def _select_none(self) -> None:
        if self._selected:
            self._last_selected = self._selected
            self._lockout_until_ns = (self.t_ns or 0) + self.registers[REG_TRANSITION_TIMEOUT] * S
        self._selected = 0

    def _two_step(self, run: bool, now: int) -> tuple:
        """Step 1 (LO1), then step 2 (LO2) once the current fell below 644 (% FLC)
        after the start, or after 643 (s), whichever comes first."""
        if not run:
            self._step = 1
            return False, False
        if self._step == 1 and self._running_since_ns is not None:
            timeout = now - self._running_since_ns >= self.registers[REG_STEP_TIMEOUT] * S
            below = not self.starting and self.current_percent < self.registers[REG_STEP_THRESHOLD]
            if timeout or below:
                self._step = 2
        return self._step == 1, self._step == 2

    def _fallback_outputs(self) -> tuple:
        strategy = self.fallback
        if strategy == FallbackStrategy.HOLD:
            return self._held
        if strategy == FallbackStrategy.RUN:  # two-step only: as if the run command stayed
            return self._two_step(True, self.t_ns or 0)
        if strategy == FallbackStrategy.BOTH_ON:
            return True, True
        if strategy == FallbackStrategy.LO1_ON:
            return True, False
        if strategy == FallbackStrategy.LO2_ON:
            return False, True
        return False, False  # OFF

    def _drive(self, lo1: bool, lo2: bool) -> None:
        before = self._motor_output()
        if lo1 and not self.lo1:
            self._count_udint(REG_LO1_CLOSINGS)
        if lo2 and not self.lo2:
            self._count_udint(REG_LO2_CLOSINGS)
        self.lo1, self.lo2 = bool(lo1), bool(lo2)
        after = self._motor_output()
        if after and after != before:  # a (new) start: inrush
            self._start_end_ns = (self.t_ns or 0) + START_DURATION_NS
            self._running_since_ns = self.t_ns
            self._count_udint(REG_MOTOR_STARTS_COUNT)
        elif not after:
            self._start_end_ns = None
            self._running_since_ns = None
            if self.operating_mode in _TWO_STEP:
                self._step = 1

    def _motor_output(self) -> int:
        """Which output powers the motor: 0 none, 1 LO1, 2 LO2. In overload and
        independent modes LO1 is the contactor; in two-step both steps are one run."""
        mode = self.operating_mode
        if mode in _OVERLOAD or mode in _INDEPENDENT:
            return 1 if self.lo1 else 0
        if mode in _TWO_STEP:
            return 1 if self.lo1 or self.lo2 else 0
        return 1 if self.lo1 else 2 if self.lo2 else 0

    def _motor_energized(self) -> bool:
        return self._motor_output() != 0

    def _uses_flc2(self) -> bool:
        return self.operating_mode in _TWO_SPEED and self.lo2  # 456 bit 6 (L3544-3571)

    # ------------------------------------------------------------------ trips and alarms

    def _trip(self, code: int, trip_register_1_bit: int) -> None:
        self.registers[REG_TRIP_CODE] = code
        self.registers[REG_TRIP_REGISTER_1] |= int(trip_register_1_bit)
        self._count(REG_TRIPS_COUNT)
        self._select_none()
        self._drive(False, False)
        if self.operating_mode in _THREE_WIRE:
            self._wait_release = True  # 3-wire: no restart after the reset without a new start

    def _set_alarm(self, code: int, active: bool) -> None:
        bit = {
            ALARM_THERMAL_OVERLOAD: AlarmRegister1.THERMAL_OVERLOAD,
            ALARM_NETWORK_COMM: AlarmRegister1.NETWORK_PORT,
        }[code]
        if active and code not in self._alarms:
            self._alarms.append(code)
            self.registers[REG_ALARM_REGISTER_1] |= int(bit)
            self._count(REG_ALARMS_COUNT)
            if code == ALARM_THERMAL_OVERLOAD:
                self._count(REG_THERMAL_ALARMS_COUNT)
        elif not active and code in self._alarms:
            self._alarms.remove(code)
            self.registers[REG_ALARM_REGISTER_1] &= ~int(bit) & 0xFFFF
        self.registers[REG_ALARM_CODE] = self._alarms[-1] if self._alarms else 0

    def _count(self, reg: int) -> None:
        self.registers[reg] = min(0xFFFF, self.registers[reg] + 1)

    def _count_udint(self, first: int) -> None:
        value = udint_from_registers(self.registers[first], self.registers[first + 1])
        self.registers[first], self.registers[first + 1] = udint_to_registers(min(0xFFFFFFFF, value + 1))

    # ------------------------------------------------------------------ registers out

    def _publish(self) -> None:
        r = self.registers
        now = self.t_ns or 0
        percent = self.current_percent
        tripped = self.tripped
        # plain ints, not IntFlag operations: this runs at every step
        status1 = _S1_CONTROLLER_POWER
        if not tripped:
            status1 |= _S1_READY
        if self.motor_on:
            status1 |= _S1_ON
        if tripped:
            status1 |= _S1_TRIPPED
        if self._alarms:
            status1 |= _S1_ALARM
        if self.reset_authorized:
            status1 |= _S1_RESET_AUTHORIZED
        if self.motor_running:
            status1 |= _S1_RUNNING
        if self.in_remote:
            status1 |= _S1_IN_REMOTE
        if self.starting:
            status1 |= _S1_STARTING
        r[REG_STATUS_1] = status1 | current_ratio_field(percent) << STATUS1_CURRENT_SHIFT

        status2 = 0
        if self._uses_flc2():
            status2 |= _S2_SPEED_FLC2
        if self.comm_lost:
            status2 |= _S2_NETWORK_COMM_LOSS
        if now < self._lockout_until_ns:
            status2 |= _S2_TRANSITION_LOCKOUT
        r[REG_STATUS_2] = (r[REG_STATUS_2] & _STATUS2_KEPT) | status2

        outputs = (1 if self.lo1 else 0) | (2 if self.lo2 else 0) | (8 if tripped else 0)
        r[REG_LOGIC_OUTPUTS] = (r[REG_LOGIC_OUTPUTS] & ~_OUTPUTS_OWNED & 0xFFFF) | outputs
        r[REG_IO_STATUS] = (
            (r[REG_LOGIC_INPUTS] & _IO_INPUTS)
            | (_IO_OUTPUT_LO1 if self.lo1 else 0)
            | (_IO_OUTPUT_LO2 if self.lo2 else 0)
            | (_IO_OUTPUT_TRIP if tripped else 0)
        )

        # whole percent, rounded down so 465 and the thresholds (608, 609) agree
        r[REG_THERMAL_CAPACITY] = min(0xFFFF, math.floor(self.thermal * 100 + 1e-7))
        ratio = min(0xFFFF, round(percent))
        for reg in (REG_AVERAGE_CURRENT_RATIO, REG_L1_CURRENT_RATIO, REG_L2_CURRENT_RATIO, REG_L3_CURRENT_RATIO):
            r[reg] = ratio  # a balanced three-phase load (simulator choice)
        centiamps = min(0xFFFFFFFF, round(percent / 100 * self.flc_in_use_centiamps))
        for reg in (REG_AVERAGE_CURRENT, REG_L1_CURRENT, REG_L2_CURRENT, REG_L3_CURRENT):
            r[reg], r[reg + 1] = udint_to_registers(centiamps)  # lower register = MSW (A5)
        r[REG_TIME_TO_TRIP] = self._time_to_trip_s()
        r[REG_MIN_WAIT_TIME] = self._minimum_wait_s()

    def _time_to_trip_s(self) -> int:
        steady = (self.current_percent / 100 / ULTIMATE_TRIP_RATIO) ** 2
        if self.tripped or steady <= 1 or self.thermal >= 1:
            return NO_TRIP_EXPECTED
        return min(NO_TRIP_EXPECTED, math.ceil(-self.tau_s * math.log((steady - 1) / (steady - self.thermal))))

    def _minimum_wait_s(self) -> int:
        """450: seconds until a thermal trip may be reset (cooling, motor off)."""
        threshold = self.registers[REG_THERMAL_RESET_THRESHOLD] / 100
        if self.trip_code != TRIP_THERMAL_OVERLOAD or threshold <= 0 or self.thermal <= threshold:
            return 0
        return min(0xFFFF, math.ceil(self.tau_s * math.log(self.thermal / threshold)))
