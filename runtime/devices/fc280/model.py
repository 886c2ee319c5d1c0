"""The Danfoss FC 280 as a drive, without its bus: the parameter memory
(store.py) and the view of it the tick uses (settings.py), the control
words of both profiles (control.py), a motor with linear ramps, the
control word timeout, alarms and warnings. Pure: no CAN,
no threads, no clock of its own; every entry point that acts takes the time
in nanoseconds and the model integrates up to it.

    drive = Fc280Model({"3-41": 500})             # ramp-up 5 s (raw, conversion index -2)
    drive.write("16-82", 0x2000, 0)                # reference 50 %
    drive.write("16-80", 0x047C, 0)                # start
    drive.advance(5 * S)
    drive.output_hz, drive.read("16-03")           # 25.0, 0x0F07

Numbers from manual 003 (shared/manuals/003_*.txt) and digest 003 (§ and
contradictions A<n>); where the manual is silent the code says "simulator
choice". The choices that shape the motor:
- Ramps are linear (motor.py); 3-41/3-42 (3-51/3-52 with ramp 2, 3-81
  quick stop) are the time for a change of 3-03, the maximum reference
  (1-23 if 3-03 is 0). A change of direction decelerates through 0 Hz.
- The output frequency is the motor's (no slip, no load, no current); it is
  limited to 4-14. RPM <-> Hz by 1-25 <-> 1-23.
- A reference is bus reference + the selected preset 3-10 (§4.4.4: "alle
  Sollwerte ... werden addiert"), in % of 3-03 (3-00 [1]) or of 3-02..3-03
  (3-00 [0], clamped there); a negative reference with reverse runs forward
  (§4.4.4 "-x- ergibt +", M16).
- DC brake (bit 2 = 0): the output is 0 Hz at once and the brake current
  flows for 2-02; coast (bit 3 = 0) and trips release the motor at once.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from fractions import Fraction

from .control import (
    DSP_RESET,
    RELAY_CTW_BIT_11,
    RELAY_CTW_BIT_12,
    SETUP_EXTERNAL,
    DspState,
    dsp_next,
    fc_commands,
    vl_commands,
)
from .motor import COAST, RAMP_STOP, Motion, int16, ramp, round_half_away
from .parameters import PROFILE_DSP402, parameter
from .profile import REFERENCE_100, ControlWord
from .settings import Settings
from .status import dsp_status_word, fc_status_word
from .store import SECTIONS_OF_SUB, ParameterStore, Refusal, Refused

S = 1_000_000_000

# 8-04 Steuerwort Timeout-Funktion (§5.4 of the digest, chapter 6)
OFF, FREEZE, STOP, JOG, MAX_SPEED, STOP_AND_ALARM = range(6)

ALARM_WORDS = ("16-90", "16-91", "16-97")  # Tabellen 8.1, 8.2; 16-97 is not tabulated
WARNING_WORDS = ("16-92", "16-93")  # Tabellen 8.3, 8.4
# Bits of Tabelle 8.1 (16-90) and 8.3 (16-92) the drive raises itself
CONTROL_WORD_TIMEOUT = 0x00000010  # both words, "Steuerwort-Timeout"
OVER_CURRENT = 0x00000020  # 16-90
FIELDBUS_FAULT = 0x00400000  # 16-90 "Feldbus-Fehl.", 16-92 warning 34 "Feldbus-Fehler"
DRIVE_INITIALISED = 0x20000000  # 16-90, Alarm 80 (§3.1.5 HINWEIS)


class Fc280Model:
    """See the module docstring. parameters: raw values by number (arrays as
    lists), as if saved before the first power-up; kept: values a restore
    leaves alone (the simulator's node id 10-02 and bit rate 10-01)."""

    def __init__(
        self,
        parameters: Mapping[str, int | Sequence[int]] | None = None,
        *,
        kept: Mapping[str, int] | None = None,
        now_ns: int = 0,
    ) -> None:
        self.store = ParameterStore(parameters, kept)
        self._settings_view = Settings(self.store)
        #: the simulator's object values by section of the non-volatile memory, for save()
        self.snapshot: Callable[[], dict[str, dict]] | None = None
        self._now = now_ns
        self._boot()

    def _boot(self) -> None:
        """The volatile state of a drive just switched on."""
        self.out = Fraction(0)  # output frequency, Hz, signed
        self._fc_word: int | None = None  # the last valid FC control word
        self._dsp_word: int | None = None  # the last 6040h
        self._dsp_rpm = Fraction(0)  # 6042h in RPM
        self._dsp_state = DspState.NOT_READY_TO_SWITCH_ON if self._dsp() else DspState.START  # transition 0
        self._last_word_ns: int | None = None  # the last valid control word (8-03)
        self.word_timed_out = False
        self.master_lost = False
        self._alarm_at_standstill: dict[str, int] = {}  # 8-04 [5] latched: source -> alarm bit of 16-90
        self.alarms = dict.fromkeys(ALARM_WORDS, 0)
        self.injected_warnings = dict.fromkeys(WARNING_WORDS, 0)
        self.trip_lock = False
        self._dc_since: int | None = None
        self._base_key: tuple | None = None  # what _base_motion() was computed from
        self._base = COAST
        self._shown: tuple | None = None  # what _publish() last showed, from what
        self._publish()

    # ------------------------------------------------------------------ parameters

    def read(self, number: str, sub: int = 0) -> int | str:
        """A parameter's raw value (text for VisStr)."""
        return self.store.get(number, sub)

    def _param(self, number: str, sub: int = 0) -> int:
        value = self.store.get(number, sub)
        assert isinstance(value, int)
        return value

    def settings(self) -> Settings:
        """The parameters the drive works with, in their units (settings.py): read
        again from the store after each change of it."""
        view = self._settings_view
        if view.version != self.store.version:
            view = self._settings_view = Settings(self.store)
        return view

    def write(self, number: str, raw: int, now_ns: int, sub: int = 0) -> None:
        """A parameter write from the bus or the drive's LCP; Refused if the
        drive does not take it. 16-80 and 16-82 are the FC profile's control
        word and reference (§4.4.1); 10-31 [2]/[3] saves (chapter 6)."""
        self.advance(now_ns)
        number = parameter(number).number
        if number in ("16-80", "16-82") and self._dsp():
            raise Refused(Refusal.STATE, f"{number} is the FC profile's; 8-10 is [7] DSP 402 (§4.4.1)")
        if number == "8-02" and self.running:
            raise Refused(Refusal.STATE, "8-02 cannot be set while the motor runs (chapter 6)")
        old_profile = self._param("8-10")
        self.store.set(number, raw, sub)
        if number == "16-80":
            self._fc_control_word(raw)
        elif number == "8-10" and raw != old_profile:
            # a profile change starts the new profile from its beginning (simulator choice)
            self._fc_word, self._dsp_word = None, None
            self._dsp_state = DspState.NOT_READY_TO_SWITCH_ON if raw == PROFILE_DSP402 else DspState.START
        elif number == "10-31" and raw:
            self.save(4)  # [2] all set-ups, [3] edit set-up: one set here; then back to [0]
            self.store.set("10-31", 0)
        self._settle()

    def save(self, sub: int) -> None:
        """1010h sub 1, 2 or 4 "save" (Tabelle 3.9; A10: sub 4 = every drive
        parameter, the model has one set-up)."""
        sections = SECTIONS_OF_SUB.get(sub)
        if sections is None:
            raise Refused(Refusal.NOT_STORED, f"1010h sub-index {sub} is reserved")
        self.store.save(sections, self.snapshot() if self.snapshot else None)

    def restore(self, sub: int) -> None:
        """1011h sub 1, 2 or 4 "load": the factory settings after the next power cycle (§7.1.10)."""
        sections = SECTIONS_OF_SUB.get(sub)
        if sections is None:
            raise Refused(Refusal.NOT_STORED, f"1011h sub-index {sub} is reserved")
        self.store.restore(sections)

    def power_cycle(self, now_ns: int) -> None:
        """Off and on: the volatile state is gone, RAM comes from the
        non-volatile memory, a pending restore is applied and shows Alarm 80."""
        self._now = max(self._now, now_ns)
        initialised = self.store.power_up()
        self._boot()
        if initialised:
            self.trip(DRIVE_INITIALISED)

    def reset_node(self, now_ns: int) -> None:
        """NMT reset node: the application restarts with the saved parameters
        (CiA 301); a pending restore waits for a power cycle (§7.1.10)."""
        self._now = max(self._now, now_ns)
        pending, self.store.pending_restore = self.store.pending_restore, set()
        self.store.power_up()
        self.store.pending_restore = pending
        self._boot()

    # ------------------------------------------------------------------ control words

    def _dsp(self) -> bool:
        return self.settings().dsp

    def _fc_control_word(self, word: int) -> None:
        """Bit 10 = 0: the word is ignored, and does not retrigger 8-03 (A28)."""
        if not word & ControlWord.DATA_VALID or not self.settings().bus_control or self._dsp():
            return
        previous = self._fc_word or 0
        self._fc_word = word
        self._valid_control_word()
        if word & ~previous & ControlWord.RESET:  # the rising edge (§4.4.2 bit 07)
            self.reset()

    def dsp_control(self, word: int, now_ns: int) -> None:
        """6040h (8-10 = [7]; Refused in the FC profile, §4.4.1)."""
        self.advance(now_ns)
        if not self._dsp():
            raise Refused(Refusal.STATE, "6040h is the DSP 402 profile's; 8-10 is [0] FC (§4.4.1)")
        previous = self._dsp_word or 0
        self._dsp_word = word
        if self.settings().bus_control:
            self._valid_control_word()
        if word & ~previous & DSP_RESET:  # fault reset on the 0 -> 1 edge of bit 7 (A21)
            self.reset()
        if self._dsp_state != DspState.START and not self.tripped:
            self._dsp_state = dsp_next(self._dsp_state, word)
        self._settle()

    def dsp_target(self, rpm: Fraction | int, now_ns: int) -> None:
        """6042h vl target velocity, in RPM (§4.3.5)."""
        self.advance(now_ns)
        if not self._dsp():
            raise Refused(Refusal.STATE, "6042h is the DSP 402 profile's; 8-10 is [0] FC (§4.4.1)")
        self._dsp_rpm = Fraction(rpm)
        self._settle()

    def _valid_control_word(self) -> None:
        """8-03: "Ein gültiges Steuerwort löst den Timeout-Zähler aus"; it also
        ends a timeout ("bis zur Wiederherstellung der Kommunikation")."""
        self._last_word_ns = self._now
        self.word_timed_out = False

    # ------------------------------------------------------------------ the lost master

    def comm_lost(self, now_ns: int) -> None:
        """Life guarding found the master gone (100Ch x 100Dh): the 8-04
        function (§3.1.4) and warning 34, 16-92 00400000h (§7.1.8): both (A6).
        With 8-04 [5] the alarm is 16-90 00400000h "Feldbus-Fehl." (latched:
        _stop_and_alarm())."""
        self.advance(now_ns)
        self.master_lost = True
        self._stop_and_alarm("master", FIELDBUS_FAULT)
        self._settle()

    def comm_restored(self, now_ns: int) -> None:
        """The master guards again: the 8-04 function ends ([1]..[4]; [2]
        "automatischer Wiederanlauf"), except a latched [5]."""
        self.advance(now_ns)
        self.master_lost = False
        self._settle()

    def _stop_and_alarm(self, source: str, alarm_bit: int) -> None:
        """8-04 [5] "Stopp und Alarm" (chapter 6): "Motor stoppt, setzt den
        Frequenzumrichter anschließend zurück: über den Feldbus, über die
        [Reset]-Taste, über einen Digitaleingang". Latched when the timeout
        comes: the motor ramps down even if communication returns (a restart
        when it returns is [2]'s), the alarm bit shows as a warning meanwhile
        and becomes the alarm at standstill (simulator choice, as Danfoss's
        alarm 17 "ramps down until it stops and then displays an alarm");
        only reset() clears it."""
        if self.settings().timeout_function == STOP_AND_ALARM:
            self._alarm_at_standstill[source] = alarm_bit

    def _reaction(self) -> int | None:
        """The 8-04 function in force, None while communication is fine."""
        if self._alarm_at_standstill:
            return STOP_AND_ALARM  # latched until the alarm and its reset
        if not (self.word_timed_out or self.master_lost):
            return None
        reaction = self.settings().timeout_function
        return None if reaction == OFF else reaction

    # ------------------------------------------------------------------ alarms and warnings

    @property
    def tripped(self) -> bool:
        return any(self.alarms.values())

    def trip(self, alarm_bit: int, *, word: str = "16-90", lock: bool = False) -> None:
        """Fault injection: raise an alarm (Tabellen 8.1, 8.2; 16-97) at the
        model's present time. The drive trips: status bit 3, the motor coasts,
        DSP 402 goes to fault; a reset (control word bit 7, press_reset())
        clears every alarm, unless lock (trip lock, status bit 6: only a power
        cycle clears it)."""
        if word not in ALARM_WORDS:
            raise ValueError(f"the alarm words are {', '.join(ALARM_WORDS)}, not {word!r}")
        self.alarms[word] |= alarm_bit
        self.trip_lock = self.trip_lock or lock
        self.out = Fraction(0)
        self._settle()

    def over_current(self) -> None:
        """Fault injection: Alarm "Überstrom", 16-90 00000020h."""
        self.trip(OVER_CURRENT)

    def warn(self, bit: int, word: str = "16-92") -> None:
        """Fault injection: raise a warning (Tabellen 8.3, 8.4) until clear_warning()."""
        if word not in WARNING_WORDS:
            raise ValueError(f"the warning words are {', '.join(WARNING_WORDS)}, not {word!r}")
        self.injected_warnings[word] |= bit
        self._settle()

    def clear_warning(self, bit: int, word: str = "16-92") -> None:
        """Fault injection: the warning raised by warn() is gone."""
        self.injected_warnings[word] &= ~bit
        self._settle()

    def reset(self) -> None:
        """Acknowledge the alarms (control word bit 7 edge, the LCP [Reset] key):
        an injected alarm's cause is gone by then (simulator choice); a trip
        lock stays. DSP 402: fault -> switch on disabled (transition 15).
        With 8-04 [5] a timeout still in force trips again (a fieldbus reset
        is a valid control word: it has ended the 8-03 timeout already)."""
        if self.trip_lock or not self.tripped:
            return
        self.alarms = dict.fromkeys(ALARM_WORDS, 0)
        if self.word_timed_out:
            self._stop_and_alarm("word", CONTROL_WORD_TIMEOUT)
        if self.master_lost:
            self._stop_and_alarm("master", FIELDBUS_FAULT)
        if self._dsp_state != DspState.START:
            self._dsp_state = DspState.SWITCH_ON_DISABLED
        self._settle()

    def press_reset(self) -> None:
        """The LCP's [Reset] key (8-04 [5] names it): reset()."""
        self.reset()

    def warnings(self) -> dict[str, int]:
        """16-92 and 16-93: the injected warnings and the drive's own. A fault
        is a warning or an alarm, not both: the control word timeout and
        fieldbus fault warnings give way to the alarm of the same bit in 16-90
        (simulator choice; it makes digest 003 D29's byte 3 = 01)."""
        words = dict(self.injected_warnings)
        own = 0
        if self.word_timed_out and self.settings().timeout_function != OFF:
            own |= CONTROL_WORD_TIMEOUT
        if self.master_lost:
            own |= FIELDBUS_FAULT
        for bit in self._alarm_at_standstill.values():  # 8-04 [5] ramping down: the warning first
            own |= bit
        words["16-92"] |= own & ~self.alarms["16-90"]
        return words

    # ------------------------------------------------------------------ time and motion

    def advance(self, now_ns: int) -> None:
        """Time passes up to now_ns: ramps, the DC brake time, the control word
        timeout and its function. A time already reached moves nothing (and
        settles nothing: every change at the present time settles itself)."""
        if now_ns <= self._now:
            return
        while self._now < now_ns:
            deadline = self._deadline()
            end = now_ns if deadline is None or deadline >= now_ns else max(deadline, self._now)
            self._integrate(end - self._now)
            self._now = end
            if deadline is not None and deadline < now_ns:
                self._word_timeout()
            self._standstill_alarm()
        self._settle()

    def _deadline(self) -> int | None:
        if self._last_word_ns is None or self.word_timed_out:
            return None
        return self._last_word_ns + self.settings().timeout_ns

    def _word_timeout(self) -> None:
        """No valid control word within 8-03: the 8-04 function until one comes."""
        self.word_timed_out = True
        self._stop_and_alarm("word", CONTROL_WORD_TIMEOUT)

    def _standstill_alarm(self) -> None:
        """8-04 [5] "Stopp und Alarm": the motor ramps down, then the drive trips
        (_stop_and_alarm())."""
        if self._alarm_at_standstill and self.out == 0:
            bits = 0
            for bit in self._alarm_at_standstill.values():
                bits |= bit
            self._alarm_at_standstill.clear()
            self.trip(bits)

    def _settle(self) -> None:
        """After a change at the present time: the DC brake timer, 8-04 [5], the readouts."""
        self._standstill_alarm()
        motion = self.motion()
        if motion.dc_brake:
            self.out = Fraction(0)
            if self._dc_since is None:
                self._dc_since = self._now
        else:
            self._dc_since = None
        if motion.coast:
            self.out = Fraction(0)
        self._publish()

    def motion(self) -> Motion:
        if self.tripped:
            return COAST
        s = self.settings()
        key = (s.version, self._fc_word, self._dsp_word, self._dsp_state, self._dsp_rpm)
        if key == self._base_key:
            base = self._base
        else:  # the control words or the parameters changed
            base = self._base = self._dsp_motion() if s.dsp else self._fc_motion()
            self._base_key = key
        if not (self.word_timed_out or self.master_lost or self._alarm_at_standstill):
            return base
        reaction = self._reaction()
        if reaction is None or (s.dsp and self._dsp_state != DspState.OPERATION_ENABLED):
            return base  # in DSP 402 the state machine keeps a disabled drive off (simulator choice)
        if reaction == FREEZE:
            return Motion(hold=True)
        if reaction in (STOP, STOP_AND_ALARM):
            return RAMP_STOP
        # [3] jog (3-19) and [4] max speed (4-14), in the direction the motor
        # turns, forward from standstill (simulator choice)
        direction = -1 if self.out < 0 or (self.out == 0 and base.target < 0) else 1
        speed = s.jog_hz if reaction == JOG else s.f_max
        return Motion(run=True, target=direction * min(speed, s.f_max))

    def _fc_motion(self) -> Motion:
        """§4.4.2: coast and DC brake win; hold output frequency can only be
        ended by them; then quick stop, jog (bit 8 is itself a start:
        simulator choice, A23), start, ramp stop."""
        s = self.settings()
        c = fc_commands(self._fc_word if s.bus_control else None, s.selections)
        if c.coast:
            return COAST
        if c.dc_brake:
            return Motion(dc_brake=True)
        if c.hold:
            return Motion(hold=True)
        if c.quick_stop:
            return Motion(quick=True)
        sign = -1 if c.reverse else 1
        if c.jog:
            return Motion(run=True, target=sign * self._limit(s.jog_hz), ramp_2=c.ramp_2)
        if c.start:
            hz = self._reference_hz(self._param("16-82"), c.preset)
            return Motion(run=True, target=self._limit(sign * hz), ramp_2=c.ramp_2, reference=True)
        return Motion(ramp_2=c.ramp_2)

    def _dsp_motion(self) -> Motion:
        """Tabelle 4.3 actions: 5 ramps down (3-42), 11 ramps down with 3-81,
        8, 9, 10, 12 switch the power section off (coast)."""
        state = self._dsp_state
        if state == DspState.SWITCHED_ON:
            return RAMP_STOP
        if state == DspState.QUICK_STOP_ACTIVE:
            return Motion(quick=True)
        if state != DspState.OPERATION_ENABLED:
            return COAST
        s = self.settings()
        v = vl_commands(self._dsp_word, s.selections)
        sign = -1 if v.reverse else 1
        if v.jog:
            return Motion(run=True, target=sign * self._limit(s.dsp_jog_hz))
        if v.quick_stop:
            return Motion(quick=True)
        if v.hold:
            return Motion(hold=True)
        if not v.start:
            return RAMP_STOP
        return Motion(run=True, target=self._limit(sign * self._dsp_rpm * s.hz_per_rpm), reference=True)

    def _reference_hz(self, bus_raw: int, preset: int) -> Fraction:
        """§4.4.4: 4000h = 100 %, plus the preset 3-10[preset] (in %)."""
        s = self.settings()
        percent = Fraction(bus_raw * 100, REFERENCE_100) + s.presets[preset]
        high = s.high
        if s.min_max:
            low = s.low
            return min(max(low + percent * (high - low) / 100, low), high)
        return percent * high / 100

    def _limit(self, hz: Fraction) -> Fraction:
        f_max = self.settings().f_max
        return max(-f_max, min(f_max, hz))

    def _integrate(self, dt: int) -> None:
        """Move the output for dt ns towards what motion() asks."""
        self.out = ramp(self.out, self.motion(), dt, self.settings().rate.__getitem__)

    # ------------------------------------------------------------------ what the drive shows

    @property
    def now_ns(self) -> int:
        return self._now

    @property
    def output_hz(self) -> float:
        return float(self.out)

    @property
    def velocity_rpm(self) -> Fraction:
        """The motor speed in RPM (6043h, 6044h before the dimension factor)."""
        return self.out * self.settings().rpm_per_hz

    @property
    def running(self) -> bool:
        """FC status bit 11: a start signal, or an output frequency > 0 Hz (Tabelle 4.10)."""
        return self.motion().run or self.out != 0

    @property
    def dc_braking(self) -> bool:
        """The DC brake current flows (bit 2 = 0, for 2-02)."""
        return self._dc_since is not None and self._now < self._dc_since + self.settings().dc_brake_ns

    @property
    def dsp_state(self) -> DspState:
        if self._dsp_state != DspState.START and self.tripped:
            return DspState.FAULT  # transitions 13, 14
        return self._dsp_state

    @property
    def active_setup(self) -> int:
        """1-4: 0-10, or with 0-10 = [9] the control word's bits 13/14 (Tabellen 4.5, 4.9)."""
        if self._param("0-10") != SETUP_EXTERNAL:
            return self._param("0-10")
        if self._dsp():
            return vl_commands(self._dsp_word, self.settings().selections).setup
        return fc_commands(self._fc_word, self.settings().selections).setup

    @property
    def relay_01(self) -> bool:
        """Relay 01: FC control word bit 11 with 5-40[0] = [36] "Steuerwort Bit 11"."""
        word = self._fc_word or 0
        return not self._dsp() and bool(word & ControlWord.RELAY_01) and self._param("5-40", 0) == RELAY_CTW_BIT_11

    @property
    def relay_04(self) -> bool:
        """Relay 04: FC control word bit 12 with 5-40[1] = [37] "Steuerwort Bit 12"."""
        word = self._fc_word or 0
        return not self._dsp() and bool(word & ControlWord.RELAY_04) and self._param("5-40", 1) == RELAY_CTW_BIT_12

    def fc_status_word(self) -> int:
        """16-03, object 2643h (Tabelle 4.10)."""
        return self._fc_status_word(self.motion(), self.warnings(), self.settings())

    def _fc_status_word(self, m: Motion, warnings: dict[str, int], s: Settings) -> int:
        return fc_status_word(m, warnings, s, self.out, self.tripped, self.trip_lock)

    def dsp_status_word(self) -> int:
        """6041h: the state's word of Tabelle 4.3 and the bits of Tabelle 4.6;
        0000 in the FC profile (the "Startzustand")."""
        state = self.dsp_state
        if state == DspState.START:
            return 0
        warned = any(self.warnings().values())
        return dsp_status_word(state, self.motion(), self.settings(), self.out, warned)

    def main_actual_value(self) -> int:
        """16-05 HIW, object 2645h: the output frequency scaled as the reference (§4.4.4)."""
        s = self.settings()
        if s.actual_scale is None:
            return 0
        return int16(round_half_away((self.out - s.actual_zero) * s.actual_scale))

    def _publish(self) -> None:
        """The readouts in the parameter memory: 16-03, 16-05, alarm and warning
        words; only when something they are made of changed."""
        m = self.motion()
        s = self.settings()
        alarms = self.alarms
        injected = self.injected_warnings
        key = (
            m,
            self.out,
            s.version,
            self.trip_lock,
            self.word_timed_out,
            self.master_lost,
            tuple(self._alarm_at_standstill.values()),
            *alarms.values(),
            *injected.values(),
        )
        if key == self._shown:
            return
        self._shown = key
        warnings = self.warnings()
        show = self.store.show
        show("16-03", self._fc_status_word(m, warnings, s))
        show("16-05", self.main_actual_value())
        for word, value in (*alarms.items(), *warnings.items()):
            show(word, value)
