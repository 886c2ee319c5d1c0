"""An Eaton PowerXL DA1, DB1 or DC1 drive or DE1 speed starter as a Modbus
slave sees it, without its bus: the register image and what the drive does
with it over time. Pure: no pymodbus, no threads, no clock of its own; every
entry point takes the time in nanoseconds and the model integrates up to it.

    drive = EatonDriveModel(Family.DB1)      # comm timeout 3 s (factory code 4)
    drive.telegram(0)
    drive.write(eaton.REG_SPEED_SETPOINT, [500], 0)         # 50.0 Hz
    drive.write(eaton.REG_CONTROL_WORD, [_CW_RUN], 0)
    drive.advance(2_500_000_000)
    drive.read(eaton.REG_STATUS_WORD, 2, 2_500_000_000)      # [status, 250]

The Modbus server wrapper calls telegram(now) for every request addressed to
this unit, then read/write; it raises ModbusRefusal's code as the exception
response (io/modbus/unit.py). Everything about registers, scales and codes
comes from registers.py, faults.py, parameters.py and settings.py; the
behaviour from manual 002 (shared/manuals/002_a23ab2a6587941cb.txt, "L<n>")
and its digest (shared/digests/002_eaton_modbus.md, "§", ambiguities "A<n>").
Where the manual is silent the code says "simulator choice".

Motion: the output frequency moves linearly at the ramp rate, integrated
exactly in rational arithmetic, split at the instants where something
changes (the ramp reaches zero or the setpoint, the comm-loss watchdog
expires), so the state after advance(t) does not depend on how many calls
led there. What the registers mean to the motion is worked out once per
change of the registers (effective.py), and the status and monitor
registers are brought up to date when something reads them (read(),
status(), register()) and what they show changed, so a tick costs next to
nothing at rest or at the setpoint, and only the ramp while ramping.
"""

from __future__ import annotations

from fractions import Fraction

from ...io.modbus.unit import ModbusRefusal
from . import faults as eaton_faults
from . import parameters as eaton_parameters
from . import registers as eaton
from . import settings as eaton_settings
from . import sim_faults
from .checks import ILLEGAL_DATA_ADDRESS, ILLEGAL_DATA_VALUE, check_write
from .defaults import NAMES, set_defaults
from .effective import ZERO, Effective
from .registers import ControlWord, Family, StatusWord

__all__ = ["EatonDriveModel", "ModbusRefusal"]

# the bits as plain ints: IntFlag arithmetic costs microseconds a tick
_CW_FAULT_RESET = int(ControlWord.FAULT_RESET)
_CW_COAST = int(ControlWord.COAST)
_CW_QUICK_STOP = int(ControlWord.QUICK_STOP)
_CW_RUN = int(ControlWord.RUN)
_READY = int(StatusWord.READY)
_RUNNING = int(StatusWord.RUNNING | StatusWord.SPEED_CONTROL_ACTIVE)  # bit 6: simulator choice
_REVERSE = int(StatusWord.REVERSE)
_AT_SETPOINT = int(StatusWord.AT_SETPOINT)
_FAULT = int(StatusWord.FAULT)
_ZERO_SPEED = int(StatusWord.ZERO_SPEED)
_HARDWARE_ENABLE = int(StatusWord.HARDWARE_ENABLE)


class EatonDriveModel:
    #: what the drive answers on the line (manual 002 L664-670: 03, 06, 16 and 23
    #: only; the others are refused with exception 01, A12: simulator choice)
    functions = (3, 6, 16, 23)

    def __init__(self, family: Family, *, de11: bool = False, registers: dict[int, int] | None = None) -> None:
        self.family = Family(family)
        self.de11 = bool(de11) and self.family is Family.DE1
        rows = eaton_parameters.PARAMETERS[self.family] + (eaton_parameters.DE11_PARAMETERS if self.de11 else ())
        self._rows: dict[int, list] = {}
        for row in rows:
            self._rows.setdefault(row.register, []).append(row)
        groups = eaton.REGISTER_GROUPS[self.family]
        self._writable = set(eaton.process_registers(self.family, writes=True))
        self._writable.update(r for r, rs in self._rows.items() if any(p.writable for p in rs))
        readable = set(range(groups.reads[0], groups.reads[1] + 1))
        readable.update(m.register for m in eaton.MONITOR_VALUES[self.family])
        readable.update(eaton.SERIAL_NUMBER_REGISTERS[self.family])
        readable.update(eaton.process_registers(self.family, writes=False))
        if self.family is Family.DA1:
            # the function-block editor's user registers: plain storage here (simulator choice)
            readable.update(eaton.DA1_USER_REGISTERS)
            self._writable.update(eaton.DA1_USER_REGISTERS)
        # the written process data read back as written (simulator choice)
        self._regs = dict.fromkeys(readable | self._writable | set(self._rows), 0)
        self._row_cache: dict[tuple[str, str], eaton_parameters.Parameter] = {}
        self._effective: Effective | None = None  # None: the registers changed since it was built
        self._shown: tuple | None = None  # what the monitor registers show (_publish)
        set_defaults(self)
        for number, value in (registers or {}).items():
            if number not in self._regs:
                raise ValueError(f"{self.family.name} has no register {number}")
            self._regs[number] = int(value) & 0xFFFF
        self._effective = None

        self._di1 = True
        self.fault = eaton_faults.FAULT_NONE
        self._now: int | None = None
        self._out: Fraction = ZERO  # output frequency in Hz, negative = reverse
        self._modulating = False  # the output stage is on (status RUNNING)
        self._run_request = False  # a RUN edge was accepted and not withdrawn
        self._quick = False  # ramping down on ramp 2
        self._trip_at_standstill = False  # DA1 P5-06 = 1 after a comm loss
        self._last_telegram: int | None = None
        self._comm_lost = False  # the watchdog fired; waits for a telegram
        self._fixed_frequency_8 = False  # DA1 P5-06 = 3 in effect
        self._cw_prev = self._control_word()
        self._publish()

    # ------------------------------------------------------------------ registers by parameter

    def _row(self, number: str, keyword: str = "") -> eaton_parameters.Parameter:
        """The table row of a parameter; of a shared register (DB1/DC1 P-36)
        the field whose name contains keyword."""
        key = (number, keyword)
        row = self._row_cache.get(key)
        if row is None:
            rows = eaton_parameters.parameter_rows(self.family, number, de11=self.de11)
            if len(rows) > 1:
                rows = tuple(r for r in rows if keyword.lower() in r.name.lower())
            row = self._row_cache[key] = rows[0]
        return row

    def _param(self, number: str, keyword: str = "") -> int:
        row = self._row(number, keyword)
        return row.extract(self._regs[row.register])

    def _set_param(self, number: str, value: int, keyword: str = "") -> None:
        row = self._row(number, keyword)
        self._regs[row.register] = row.insert(self._regs[row.register], value)
        self._effective = None

    def _now_effective(self) -> Effective:
        """The settings in effect (effective.py), built again after a register changed."""
        effective = self._effective
        if effective is None:
            effective = self._effective = Effective(self)
        return effective

    # ------------------------------------------------------------------ what a user sees

    @property
    def di1(self) -> bool:
        """The hardware enable: DI1 on DB1/DC1/DE1 (L320, L327), STO on the DA1
        (L316, digest §1.3). Takes effect at the last advanced time."""
        return self._di1

    @di1.setter
    def di1(self, value: bool) -> None:
        self._di1 = bool(value)
        if not self._di1:
            self._run_request = False  # the enable lost: coast; a new RUN edge is needed
            self._coast()
        self._apply_control()

    @property
    def actual_hz(self) -> float:
        """The output frequency, negative in reverse."""
        return float(self._out)

    @property
    def running(self) -> bool:
        """The output is active (status RUNNING), ramping down included."""
        return self._modulating

    @property
    def setpoint_hz(self) -> float:
        """The speed setpoint in effect, before the ramp, without its sign."""
        return float(self._setpoint())

    @property
    def bus_control(self) -> bool:
        """The control source (P1-12 / P-12) is Modbus."""
        return self._now_effective().bus_control

    @property
    def comm_lost(self) -> bool:
        """The comm-loss watchdog fired and no telegram has arrived since."""
        return self._comm_lost

    def status(self) -> int:
        """The ID 6 word."""
        self._publish()
        return self._regs[eaton.REG_STATUS_WORD]

    def register(self, number: int) -> int:
        """The raw value of any register, for tests."""
        if number not in self._regs:
            raise ValueError(f"{self.family.name} has no register {number}")
        self._publish()
        return self._regs[number]

    def trip(self, fault: int) -> None:
        """Inject a fault of eaton_faults.FAULTS at the last advanced time."""
        if fault not in eaton_faults.FAULTS or fault == eaton_faults.FAULT_NONE:
            raise ValueError(f"{fault} is not a fault number of Tabelle 11")
        self._set_fault(fault)

    def inject(self, fault: str, value, on: bool) -> None:
        """A fault of sim_faults.FAULTS (but SILENT, the line's)."""
        sim_faults.inject(self, fault, value, on)

    # ------------------------------------------------------------------ Modbus side

    def serve_read(self, address: int, count: int, now_ns: int) -> list[int]:
        """A read on the line at a PDU address (register = address + 1)."""
        return self.read(eaton.register_number(address), count, now_ns)

    def serve_write(self, address: int, values: list[int], now_ns: int) -> None:
        self.write(eaton.register_number(address), values, now_ns)

    def telegram(self, now_ns: int) -> None:
        """A valid telegram addressed to this drive arrived: (re)starts the
        comm-loss watchdog, which runs only after the first one ("bei einer
        aktiven Kommunikationsverbindung", L387)."""
        self.advance(now_ns)
        self._last_telegram = self._now
        if self._comm_lost:
            # the connection is back; a drive stopped by the loss needs a new
            # RUN edge (simulator choice), a tripped one a fault reset
            self._comm_lost = False
            self._fixed_frequency_8 = False

    def read(self, register: int, count: int, now_ns: int) -> list[int]:
        """FC03 (and the read half of FC23). Refused with 3 for a count of 0
        or above 11 (L667; the Modbus standard's code for a quantity out of
        range, simulator choice), with 2 if any register of the block does
        not exist on this family."""
        self.advance(now_ns)
        if not 1 <= count <= eaton.MAX_REGISTERS_PER_READ:
            raise ModbusRefusal(
                ILLEGAL_DATA_VALUE, f"FC03 reads 1..{eaton.MAX_REGISTERS_PER_READ} registers (L667), not {count}"
            )
        missing = [r for r in range(register, register + count) if r not in self._regs]
        if missing:
            raise ModbusRefusal(ILLEGAL_DATA_ADDRESS, f"{self.family.name} has no register {missing[0]}")
        self._publish()
        return [self._regs[r] for r in range(register, register + count)]

    def write(self, register: int, values: list[int], now_ns: int) -> None:
        """FC06 / FC16 (and the write half of FC23). The whole block is
        checked before any register changes (simulator choice). Refused with
        2 for a register that does not exist (also register 3 inside a DB1/DC1
        block 1-4, A11) or cannot be written (read-only, reserved); with 3
        for a value out of its range or a STOP-only parameter while the
        output runs (the access column "STOP", Tabellen 20-23; the drive
        checks the access right, not whether the value changes: simulator
        choice)."""
        self.advance(now_ns)
        if not values:
            raise ModbusRefusal(ILLEGAL_DATA_VALUE, "no register values")
        for offset, value in enumerate(values):
            check_write(self, register + offset, value)
        regs = self._regs
        for offset, value in enumerate(values):
            if regs[register + offset] != value:
                regs[register + offset] = value
                self._effective = None
        self._apply_control()

    # ------------------------------------------------------------------ time

    def advance(self, now_ns: int) -> None:
        """Time passes up to now_ns: ramps, the comm-loss watchdog and its
        action. A time before the last one moves nothing. The monitor
        registers follow when something reads them (_publish)."""
        if self._now is None:
            self._now = now_ns
        elif self._now >= now_ns:
            return
        while self._now < now_ns:
            deadline = self._comm_deadline()
            if not self._modulating and (deadline is None or deadline >= now_ns):
                self._now = now_ns  # at rest and no watchdog fires: nothing moves
                break
            end = now_ns
            if deadline is not None and deadline < now_ns:
                end = max(deadline, self._now)
            self._integrate(end - self._now)
            self._now = end
            if deadline is not None and deadline < now_ns:
                self._on_comm_loss()

    def _comm_deadline(self) -> int | None:
        if self._last_telegram is None or self._comm_lost:
            return None
        effective = self._now_effective()
        if not effective.bus_control or effective.comm_timeout is None:
            return None
        return self._last_telegram + effective.comm_timeout[0]

    def _on_comm_loss(self) -> None:
        """No valid telegram within the timeout (L387-388, L400, L423, L445)."""
        self._comm_lost = True
        _, reaction = self._now_effective().comm_timeout
        action = eaton_settings.Da1CommLossAction
        if reaction in (action.TRIP, eaton_settings.CommLossReaction.TRIP):
            # trips whether running or not (the manual sets no condition; simulator choice)
            self._set_fault(eaton_faults.COMM_LOSS_FAULT)
        elif reaction is action.RAMP_STOP_THEN_TRIP:
            if self._modulating:
                self._trip_at_standstill = True
                self._stop(quick=False)
            else:
                self._set_fault(eaton_faults.COMM_LOSS_FAULT)
        elif reaction in (action.RAMP_STOP_NO_FAULT, eaton_settings.CommLossReaction.RAMP_TO_ZERO):
            # ramps to standstill on the deceleration ramp (simulator choice) and stays there
            self._stop(quick=False)
        elif reaction is action.FIXED_FREQUENCY_8:
            # a running drive changes to P2-08 in its direction; a stopped one stays stopped (simulator choice)
            self._fixed_frequency_8 = True

    # ------------------------------------------------------------------ control

    def _control_word(self) -> int:
        """ID 1 as the drive uses it: 0 when the control source is not Modbus
        (the word is stored but ignored)."""
        return self._now_effective().cw

    def _apply_control(self) -> None:
        """React to the control word, after a write or an input change.

        Simulator choices (the manual gives the bits only, L760-781, A23):
        FAULT_RESET acts on its rising edge; RUN starts on its rising edge
        only, while enabled and without a fault, so after a fault reset, a
        lost enable, COAST, QUICK_STOP or a comm-loss stop a drive with RUN
        still set needs RUN 0 -> 1 again (as the Start Modus factory
        "Edge-r" of real drives; P2-36 / P-30 are not modelled). COAST and
        QUICK_STOP are stop commands that win over RUN."""
        cw = self._control_word()
        rising = cw & ~self._cw_prev
        self._cw_prev = cw
        if rising & _CW_FAULT_RESET and self.fault:
            # every fault's cause is gone once reset is asked for: injected faults are events, and a
            # comm-loss fault is reset by a telegram, which restored the connection
            self.fault = eaton_faults.FAULT_NONE
        if cw & _CW_COAST or self.fault or not self._di1:
            self._run_request = False
            self._coast()
        elif cw & _CW_QUICK_STOP:
            if self._run_request or self._modulating:
                self._stop(quick=True)  # "Schnellstopp (Rampe 2)" (L771)
        elif not cw & _CW_RUN:
            if self._run_request:
                self._stop(quick=False)
        elif rising & _CW_RUN:
            self._run_request = True
            self._modulating = True
            self._quick = False
            self._trip_at_standstill = False

    def _stop(self, *, quick: bool) -> None:
        """Withdraw the run request: the output ramps down (ramp 2 if quick)."""
        self._run_request = False
        if self._modulating:
            self._quick = self._quick or quick
            if self._out == 0:
                self._standstill()

    def _coast(self) -> None:
        self._modulating = False
        self._out = ZERO
        self._quick = False
        self._trip_at_standstill = False

    def _set_fault(self, fault: int) -> None:
        """A trip stops the output at once (coast); the first fault stays
        until reset (simulator choice)."""
        if not self.fault:
            self.fault = fault
            if self.family is not Family.DA1:
                self._set_param(NAMES[self.family]["last_fault"], fault)  # P-13 "Letzter Fehler" (L1648)
        self._run_request = False
        self._coast()

    # ------------------------------------------------------------------ motion

    def _setpoint(self) -> Fraction:
        """ID 2 in 0.1 Hz (L792) limited to f-min..f-max (L784-790); FF1
        (bit 6) and "Sollwert mit 0 überschreiben" (bit 7) replace it, 0 wins
        over f-min (simulator choice); DA1 P5-06 = 3 runs at P2-08 (L388)."""
        effective = self._now_effective()
        if self._fixed_frequency_8:
            assert effective.setpoint_ff8 is not None  # only a DA1 runs at P2-08
            return effective.setpoint_ff8
        return effective.setpoint

    def _target(self) -> Fraction:
        """The signed frequency the output heads for."""
        if not self._run_request:
            return ZERO
        effective = self._now_effective()
        if self._fixed_frequency_8:
            assert effective.target_ff8 is not None  # only a DA1 runs at P2-08
            return effective.target_ff8
        return effective.target

    def _integrate(self, dt: int | Fraction) -> None:
        """Move the output for dt ns: towards zero on the deceleration ramp
        (ramp 2 in a quick stop), away from it on the acceleration ramp; a
        reversal passes through zero (L468: "gemäß der eingestellten Rampen")."""
        # exact rational arithmetic on numerators and denominators (Fraction
        # operators cost microseconds each): a Fraction is made only for the new output
        while self._modulating and dt > 0:
            target = self._target()
            out = self._out
            if out == target:
                if not self._run_request:
                    self._standstill()
                break
            rates = self._now_effective().rates
            on, od, tn, td = out.numerator, out.denominator, target.numerator, target.denominator
            crossing = tn == 0 or (tn > 0) != (on > 0)  # the target is zero or the other way
            if on != 0 and (crossing or abs(tn) * od < abs(on) * td):  # towards zero
                limit = ZERO if crossing else target
                rate = rates["quick" if self._quick else "decel"]
            else:
                limit, rate = target, rates["accel"]
            if rate is None:  # no ramp: there at once
                self._out = limit
                continue
            ln, ld, rn, rd, dn, dd = (
                limit.numerator,
                limit.denominator,
                rate.numerator,
                rate.denominator,
                dt.numerator,
                dt.denominator,
            )
            gap = ln * od - on * ld  # (limit - out) x ld x od
            if abs(gap) * rd * dd <= dn * ld * od * rn:  # the time needed, |gap| / rate, is within dt
                self._out = limit
                dt -= Fraction(abs(gap) * rd, ld * od * rn)
            else:  # out + rate x dt towards the limit
                step = rn * dn * od
                self._out = Fraction(on * rd * dd + (step if gap > 0 else -step), od * rd * dd)
                dt = 0
        if self._modulating and not self._run_request and self._out == 0:
            self._standstill()

    def _standstill(self) -> None:
        """A ramp stop reached zero: the output switches off."""
        trip = self._trip_at_standstill
        self._coast()
        if trip:
            self._set_fault(eaton_faults.COMM_LOSS_FAULT)  # P5-06 = 1: ramps down, then trips (L388)

    # ------------------------------------------------------------------ registers

    def _publish(self) -> None:
        """The monitoring registers from the state (digest §3.3), before
        anything reads them; written only when something they show changed:
        the output, the run state, the fault, the enable or a register (a
        new Effective). They are no input of anything else."""
        effective = self._now_effective()
        out, modulating, fault, di1 = self._out, self._modulating, self.fault, self._di1
        shown = (effective, out, modulating, self._run_request, fault, di1, self._fixed_frequency_8)
        if shown == self._shown:
            return
        self._shown = shown
        regs = self._regs
        flags = 0
        if di1 and not fault and effective.bus_control:
            flags |= _READY
        if modulating:
            flags |= _RUNNING
            target = self._target()
            if out < 0 or (out == 0 and target < 0):
                flags |= _REVERSE
            if self._run_request and out == target:
                flags |= _AT_SETPOINT
        if fault:
            flags |= _FAULT
        # "Nullzahl" (A21) while the output frequency is 0, with the enable present: the manual's
        # own example reads ID 6 = 0 from a stopped DA1 (L1125-1140), which is one with STO open
        if out == 0 and di1:
            flags |= _ZERO_SPEED
        if di1:
            flags |= _HARDWARE_ENABLE  # DA1: STO status, others: DI1 (L845-850)
        regs[eaton.REG_STATUS_WORD] = eaton.status_word(flags, fault)
        speed, current, torque, power = effective.monitor(out, modulating)
        regs[eaton.REG_ACTUAL_SPEED] = speed
        regs[eaton.REG_MOTOR_CURRENT] = current
        if torque is not None and power is not None:  # the DE1 has neither (ID 9, 10)
            regs[eaton.REG_TORQUE] = torque
            regs[eaton.REG_OUTPUT_POWER] = power
        # ID 11 bit 0 = DI1 (L954); on the DA1 the model shows STO there (a DI1 wired with it, A22)
        regs[eaton.REG_DI_STATUS] = 1 if di1 else 0
