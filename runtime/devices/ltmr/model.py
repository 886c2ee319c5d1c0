"""The TeSys T LTMR as a device, without its bus: its register image and
what it does with it over time. Pure: no CAN, no threads, no clock of its
own (advance_to(now_ns) moves it).

    model = LtmrModel({652: 50})
    model.registers[704] = Control1.RUN_FORWARD     # what an RPDO would write
    model.advance_to(2_000_000_000)
    model.lo1, model.motor_running, model.registers[455]

It reads its commands (704), operating mode (540) and settings (541, 601,
602, 606, 608, 609, 631, 632, 643, 644, 652, 653, 682, 683) from the
registers and writes what it shows back (publish.py): status 455/456,
outputs 458/459, thermal capacity 465, currents 466-469 and 500-507, time to
trip 511, minimum wait 450, trips 451-453, alarms 460/461, a few counters.
Registers it does not own keep whatever was written to them.

Numbers come from manual 001 (DOCA0132EN, shared/manuals/001_*.txt, "L<n>")
and its digest; the settings at power-up and the simulator's own choices are
in defaults.py, the thermal image (class N) in thermal.py. Time moves in
steps of at most 10 ms; in each the current is constant and the thermal
image exact. The commands are worked out again only when what they depend on
changed: the registers they read, the model's own state, or time where a
timer runs (transition lockout, two-step, automatic reset, fallback RUN).
"""

from __future__ import annotations

from .bits import (
    GENERAL_CONFIG2_RESET_MODE_MASK,
    AlarmEnable1,
    AlarmRegister1,
    GeneralConfig1,
    TripEnable1,
    TripRegister1,
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
from .datatypes import udint_from_registers, udint_to_registers
from .defaults import (
    DEFAULT_LOAD_PERCENT,
    DIRECT_TRANSITION,
    LOCAL_DEFAULT_MODE,
    MAX_STEP_NS,
    REG_ALARMS_COUNT,
    REG_LO1_CLOSINGS,
    REG_LO2_CLOSINGS,
    REG_NETWORK_PORT_TRIPS_COUNT,
    REG_STEP_THRESHOLD,
    REG_STEP_TIMEOUT,
    REG_THERMAL_ALARMS_COUNT,
    REG_THERMAL_TRIPS_COUNT,
    REG_TRANSITION_TIMEOUT,
    REG_TRIPS_COUNT,
    REMOTE_CHANNEL_SHIFT,
    RUNNING_THRESHOLD_PERCENT,
    START_CURRENT_PERCENT,
    START_DURATION_NS,
    STATISTICS,
    S,
    default_registers,
)
from .publish import CurrentRegisters, flc_in_use_centiamps, publish
from .registers import (
    REG_ALARM_CODE,
    REG_ALARM_ENABLE_1,
    REG_ALARM_REGISTER_1,
    REG_CONTROL_1,
    REG_CONTROL_2,
    REG_CONTROL_SETTING,
    REG_GENERAL_CONFIG_1,
    REG_GENERAL_CONFIG_2,
    REG_MOTOR_STARTS_COUNT,
    REG_NETWORK_FALLBACK,
    REG_OPERATING_MODE,
    REG_THERMAL_ALARM_THRESHOLD,
    REG_THERMAL_RESET_THRESHOLD,
    REG_TRIP_CLASS,
    REG_TRIP_CODE,
    REG_TRIP_ENABLE_1,
    REG_TRIP_REGISTER_1,
    REG_TRIP_REGISTER_2,
)
from .thermal import decay, heat, steady, tau_s

# How the operating mode (540) drives LO1/LO2; custom logic programs are not simulated
_DIRECT, _SELECT, _TWO_SPEED, _TWO_STEP, _CUSTOM = range(5)
_MODE_KIND = {
    OperatingMode.OVERLOAD_2W: _DIRECT,  # 704 bits 0/1 drive LO1/LO2, in overload mode too (L2576, A12)
    OperatingMode.OVERLOAD_3W: _DIRECT,
    OperatingMode.INDEPENDENT_2W: _DIRECT,
    OperatingMode.INDEPENDENT_3W: _DIRECT,
    OperatingMode.REVERSER_2W: _SELECT,
    OperatingMode.REVERSER_3W: _SELECT,
    OperatingMode.TWO_STEP_2W: _TWO_STEP,
    OperatingMode.TWO_STEP_3W: _TWO_STEP,
    OperatingMode.TWO_SPEED_2W: _TWO_SPEED,
    OperatingMode.TWO_SPEED_3W: _TWO_SPEED,
}
_KIND: dict[int, int] = {int(mode): kind for mode, kind in _MODE_KIND.items()}
_THREE_WIRE = frozenset(
    int(mode)
    for mode in (
        OperatingMode.OVERLOAD_3W,
        OperatingMode.INDEPENDENT_3W,
        OperatingMode.REVERSER_3W,
        OperatingMode.TWO_STEP_3W,
        OperatingMode.TWO_SPEED_3W,
    )
)
# 704 bits as plain ints (Control1)
_FORWARD, _REVERSE, _TRIP_RESET, _SELF_TEST, _LOW_SPEED = 1 << 0, 1 << 1, 1 << 3, 1 << 5, 1 << 6
_RUN_BITS = _FORWARD | _REVERSE
_CLEAR_STATISTICS, _CLEAR_THERMAL_CAPACITY = 1 << 1, 1 << 2  # 705 (Control2)
_TRIP_ENABLE_THERMAL, _TRIP_ENABLE_SELF_TEST = int(TripEnable1.THERMAL_OVERLOAD), int(TripEnable1.SELF_TEST)
_ALARM_ENABLE_THERMAL = int(AlarmEnable1.THERMAL_OVERLOAD)
_ALARM_BITS = {
    ALARM_THERMAL_OVERLOAD: int(AlarmRegister1.THERMAL_OVERLOAD),
    ALARM_NETWORK_COMM: int(AlarmRegister1.NETWORK_PORT),
}
_TEST_BIT, _THERMAL_BIT = 1 << 9, 1 << 3  # 452 (TripRegister1)
_RESET_AUTOMATIC, _RESET_REMOTE = int(ResetMode.AUTOMATIC), int(ResetMode.REMOTE)
_TIMED_FALLBACK = FallbackStrategy.RUN  # two-step: its step timer runs


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
        self.alarms: list[int] = []  # active alarm codes, the newest last
        self.lockout_until_ns = 0  # motor transition timeout 541 after a stop
        self.current_registers = CurrentRegisters()  # publish.py's 466-469, 500-507
        self.shown: tuple | None = None  # publish.py: what its last run read and wrote
        self._start_end_ns: int | None = None  # end of the inrush of the running start
        self._running_since_ns: int | None = None
        self._selected = 0  # reverser / two-speed: 1 = LO1, 2 = LO2, 0 = none
        self._last_selected = 0
        self._wait_release = False  # a start needs the run bits released first
        self._step = 1  # two-step: step 1 (LO1) or 2 (LO2)
        self._held = (False, False)  # outputs at the moment of a HOLD fallback
        self._previous_control = 0
        self._previous_control2 = 0
        self._reset_pressed = False
        self._settled: tuple | None = None  # what the commands depend on, while applying them again changes nothing
        self._decay_key: tuple | None = None  # (dt, trip class) of self._decay
        self._decay = 1.0

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
        end = self._start_end_ns
        return end is not None and self.t_ns is not None and self.t_ns < end

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
    def uses_flc2(self) -> bool:
        """456 bit 6 (L3544-3571): two-speed mode at high speed (LO2)."""
        return self.lo2 and _KIND.get(self.registers[REG_OPERATING_MODE]) == _TWO_SPEED

    @property
    def flc_in_use_centiamps(self) -> float:
        """FLC in 0.01 A: FLC1 (652), or FLC2 (653) at high speed, in % of FLCmax (96, x 0.1 A)."""
        return flc_in_use_centiamps(self.registers, self.uses_flc2)

    @property
    def tau_s(self) -> float:
        return tau_s(self.registers[REG_TRIP_CLASS])

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
        setting = self.registers[REG_CONTROL_SETTING]
        return not setting & LOCAL_DEFAULT_MODE and not (setting >> REMOTE_CHANNEL_SHIFT) & 0x3

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
        r = self.registers
        apply = True
        while True:
            if apply:
                self._apply_commands()
            t = self.t_ns
            if t >= now_ns:
                break
            dt = min(now_ns - t, MAX_STEP_NS)
            end = self._start_end_ns
            if end is not None and t < end:
                dt = min(dt, end - t)  # the inrush ends on time
            code = r[REG_TRIP_CODE]
            self._heat(dt)
            self.t_ns = t + dt
            self._protect()
            # settled commands stay so while what they read is the same: a
            # step changes θ and the time, and what they read only by a trip
            apply = self._settled is None or r[REG_TRIP_CODE] != code
        publish(self)

    def _heat(self, dt_ns: int) -> None:
        """θ over dt at the present current, exact for a constant current."""
        target = steady(self.current_percent)
        if self.thermal == target:
            return  # heat() would give target again
        key = (dt_ns, self.registers[REG_TRIP_CLASS])
        if key != self._decay_key:
            self._decay_key, self._decay = key, decay(*key)
        self.thermal = heat(self.thermal, target, self._decay)

    def _protect(self) -> None:
        r = self.registers
        theta = self.thermal
        alarm = bool(r[REG_ALARM_ENABLE_1] & _ALARM_ENABLE_THERMAL) and theta * 100 >= r[REG_THERMAL_ALARM_THRESHOLD]
        if alarm != (ALARM_THERMAL_OVERLOAD in self.alarms):
            self._set_alarm(ALARM_THERMAL_OVERLOAD, alarm)
        else:
            r[REG_ALARM_CODE] = self.alarms[-1] if self.alarms else 0
        # 1e-9: the trip of the class definition (exactly N s at 7.2 FLC) must not be lost to rounding
        if not r[REG_TRIP_CODE] and r[REG_TRIP_ENABLE_1] & _TRIP_ENABLE_THERMAL and theta >= 1 - 1e-9:
            self._trip(TRIP_THERMAL_OVERLOAD, _THERMAL_BIT)
            self._count(REG_THERMAL_TRIPS_COUNT)

    # ------------------------------------------------------------------ commands -> outputs

    def _inputs(self) -> tuple:
        """Everything _apply_commands reads but time, θ and the current."""
        r = self.registers
        return (
            r[REG_CONTROL_1],
            r[REG_CONTROL_2],
            r[REG_CONTROL_SETTING],
            r[REG_OPERATING_MODE],
            r[REG_TRIP_CODE],
            r[REG_TRIP_ENABLE_1],
            r[REG_GENERAL_CONFIG_2],
            self.fallback,
            self._held,
            self._wait_release,
            self._reset_pressed,
            self._previous_control,
            self._previous_control2,
            self._selected,
            self._step,
            self.lo1,
            self.lo2,
        )

    def _apply_commands(self) -> None:
        """Outputs from the commands, skipped while its inputs are those after
        a run that needs no time: applying them again would change nothing."""
        if self._settled is not None and self._inputs() == self._settled:
            return
        settled = self._commands()
        self._settled = self._inputs() if settled else None

    def _commands(self) -> bool:
        """The outputs from 704/705 and the state; True if a second run with the
        same inputs would do nothing whatever the time, θ and the current."""
        r = self.registers
        now = self.t_ns or 0
        control = r[REG_CONTROL_1]
        rising = control & ~self._previous_control
        self._previous_control = control
        self._apply_control2()
        if rising & _SELF_TEST and not r[REG_TRIP_CODE] and r[REG_TRIP_ENABLE_1] & _TRIP_ENABLE_SELF_TEST:
            self._trip(TRIP_TEST, _TEST_BIT)  # trip code 10, 452 bit 9 (L3448)
        if r[REG_TRIP_CODE]:
            self._try_reset(bool(rising & _TRIP_RESET))
        self._reset_pressed = False
        code = r[REG_TRIP_CODE]
        if code:
            self._select_none()
            self._drive(False, False)
            # an automatic reset waits for θ
            return code != TRIP_THERMAL_OVERLOAD or self.reset_mode != _RESET_AUTOMATIC
        if self.fallback is not None:
            self._drive(*self._fallback_outputs())
            return self.fallback != _TIMED_FALLBACK
        if not self.network_control:
            control = 0
        if self._wait_release:
            if control & _RUN_BITS:
                self._drive(False, False)
                return True
            self._wait_release = False
        kind = _KIND.get(r[REG_OPERATING_MODE], _CUSTOM)
        forward = bool(control & _FORWARD)
        if kind == _DIRECT:
            self._drive(forward, bool(control & _REVERSE))
            return True
        if kind == _SELECT:
            # bit 0 forward (LO1), bit 1 reverse (LO2), both: stop
            reverse = bool(control & _REVERSE)
            target = 1 if forward and not reverse else 2 if reverse and not forward else 0
        elif kind == _TWO_SPEED:
            # run with bit 0: bit 6 low speed -> LO1 on FLC1, without -> LO2 (high speed) on FLC2
            target = (1 if control & _LOW_SPEED else 2) if forward else 0
        elif kind == _TWO_STEP:
            self._drive(*self._two_step(forward, now))
            return not forward or self._step == 2
        else:
            self._drive(False, False)  # custom logic programs are not simulated
            return True
        self._drive(*self._select(target, now))
        return self._selected == target  # else a lockout or a stop first: time counts

    def _try_reset(self, remote_edge: bool) -> None:
        """Reset per 602 bits 0-2 (DT_ResetMode): the device's button always;
        704 bit 3 (rising edge) in remote mode; a thermal trip by itself in
        automatic mode. Only once the reset is authorized."""
        if not self.reset_authorized:
            return
        mode = self.reset_mode
        automatic = mode == _RESET_AUTOMATIC and self.trip_code == TRIP_THERMAL_OVERLOAD
        if self._reset_pressed or (remote_edge and mode == _RESET_REMOTE) or automatic:
            self.registers[REG_TRIP_CODE] = 0
            self.registers[REG_TRIP_REGISTER_1] = 0
            self.registers[REG_TRIP_REGISTER_2] = 0

    def _apply_control2(self) -> None:
        """705 (rising edges): bit 1 clear statistics, bit 2 clear thermal capacity
        level (L4938-4955). Bits 0, 3 and 4 (clear settings) are not simulated."""
        control2 = self.registers[REG_CONTROL_2]
        rising = control2 & ~self._previous_control2
        self._previous_control2 = control2
        if rising & _CLEAR_THERMAL_CAPACITY:
            self.thermal = 0.0
        if rising & _CLEAR_STATISTICS:
            for reg in STATISTICS:
                if reg in self.registers:
                    self.registers[reg] = 0

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
            self.lockout_until_ns = now + self.registers[REG_TRANSITION_TIMEOUT] * S
            self._selected = 0
        if target and target != self._last_selected and now < self.lockout_until_ns:
            target = 0  # transition lockout, 456 bit 9
        if target:
            self._selected = target
        return self._selected == 1, self._selected == 2

    def _select_none(self) -> None:
        if self._selected:
            self._last_selected = self._selected
            self.lockout_until_ns = (self.t_ns or 0) + self.registers[REG_TRANSITION_TIMEOUT] * S
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
        if lo1 == self.lo1 and lo2 == self.lo2:  # the same outputs: what is below would change nothing
            if lo1 or lo2:
                if self._motor_output():
                    return
            elif self._start_end_ns is None and self._running_since_ns is None:
                if _KIND.get(self.registers[REG_OPERATING_MODE]) == _TWO_STEP:
                    self._step = 1
                return
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
            if _KIND.get(self.registers[REG_OPERATING_MODE]) == _TWO_STEP:
                self._step = 1

    def _motor_output(self) -> int:
        """Which output powers the motor: 0 none, 1 LO1, 2 LO2. In overload and
        independent modes LO1 is the contactor; in two-step both steps are one run."""
        kind = _KIND.get(self.registers[REG_OPERATING_MODE])
        if kind == _DIRECT:
            return 1 if self.lo1 else 0
        if kind == _TWO_STEP:
            return 1 if self.lo1 or self.lo2 else 0
        return 1 if self.lo1 else 2 if self.lo2 else 0

    def _motor_energized(self) -> bool:
        return self._motor_output() != 0

    # ------------------------------------------------------------------ trips and alarms

    def _trip(self, code: int, trip_register_1_bit: int) -> None:
        self.registers[REG_TRIP_CODE] = code
        self.registers[REG_TRIP_REGISTER_1] |= int(trip_register_1_bit)
        self._count(REG_TRIPS_COUNT)
        self._select_none()
        self._drive(False, False)
        if self.registers[REG_OPERATING_MODE] in _THREE_WIRE:
            self._wait_release = True  # 3-wire: no restart after the reset without a new start

    def _set_alarm(self, code: int, active: bool) -> None:
        bit = _ALARM_BITS[code]
        if active and code not in self.alarms:
            self.alarms.append(code)
            self.registers[REG_ALARM_REGISTER_1] |= bit
            self._count(REG_ALARMS_COUNT)
            if code == ALARM_THERMAL_OVERLOAD:
                self._count(REG_THERMAL_ALARMS_COUNT)
        elif not active and code in self.alarms:
            self.alarms.remove(code)
            self.registers[REG_ALARM_REGISTER_1] &= ~bit & 0xFFFF
        self.registers[REG_ALARM_CODE] = self.alarms[-1] if self.alarms else 0

    def _count(self, reg: int) -> None:
        self.registers[reg] = min(0xFFFF, self.registers[reg] + 1)

    def _count_udint(self, first: int) -> None:
        value = udint_from_registers(self.registers[first], self.registers[first + 1])
        self.registers[first], self.registers[first + 1] = udint_to_registers(min(0xFFFFFFFF, value + 1))

    def _publish(self) -> None:
        publish(self)
