"""An Eaton PowerXL DA1, DB1 or DC1 drive or DE1 speed starter as a Modbus
slave sees it, without its bus: the register image and what the drive does
with it over time. Pure: no pymodbus, no threads, no clock of its own; every
entry point takes the time in nanoseconds and the model integrates up to it.

    drive = EatonDriveModel(Family.DB1)      # comm timeout 3 s (factory code 4)
    drive.telegram(0)
    drive.write(eaton.REG_SPEED_SETPOINT, [500], 0)         # 50.0 Hz
    drive.write(eaton.REG_CONTROL_WORD, [ControlWord.RUN], 0)
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
led there.
"""

from __future__ import annotations

import re
from fractions import Fraction

from ...io.modbus.unit import ModbusRefusal
from . import faults as eaton_faults
from . import parameters as eaton_parameters
from . import registers as eaton
from . import settings as eaton_settings
from . import sim_faults
from .registers import ControlWord, Family, StatusWord

S = 1_000_000_000

# ---------------------------------------------------------------- simulator choices (not in the manual)
# Defaults that let a master drive the model out of the box; a real drive
# leaves the factory with terminal control (P1-12 / P-12 = 0, L397, L413).
DEFAULT_F_MAX_HZ = 50.0  # f-max (P1-01 / P-01)
DEFAULT_F_MIN_HZ = 0.0  # f-min (P1-02 / P-02)
DEFAULT_RAMP_S = 5.0  # t-acc, t-dec (P1-03/P1-04, P-03/P-04)
DEFAULT_QUICK_STOP_S = 1.0  # ramp 2 (DA1 P2-25, DB1/DC1 P-24)
DEFAULT_FIXED_FREQUENCY_1_HZ = 20.0  # DA1 P2-01 / P-20: the DE1 factory FF1 (L622-630)
DEFAULT_FIXED_FREQUENCY_8_HZ = 10.0  # DA1 P2-08, the comm-loss fixed frequency
DEFAULT_MOTOR_VOLTAGE_V = 400
DEFAULT_MOTOR_CURRENT_A = 8.2  # a 4 kW four-pole motor at 400 V
DEFAULT_MOTOR_FREQUENCY_HZ = 50
DEFAULT_MOTOR_SPEED_RPM = 1440
DEFAULT_UNIT_ADDRESS = 1
# Identification IDs 12-16: a 4 kW, 400 V device of each family (RATED_POWER
# lists 4 kW for DA1 FS2 index 6, DB1 FS2 index 1, DC1 FS2 index 7, DE1 FS2
# index 3). How register 12 is laid out is not said (A19): the DA1 gets its
# P0-29 Rating ID nibbles (decode_da1_rating_id), the others the plain
# DRIVE_VARIANTS value 0 (kW, 3-phase in, 3-phase out).
DA1_FRAME_SIZE = 2
DA1_POWER_INDEX = 6
DA1_VOLTAGE_INDEX = 4  # not in the manual
DRIVE_VARIANT = 0
POWER_RATING_KW = 4
VOLTAGE_LEVEL_V = 400
SOFTWARE_VERSION_CONTROL = 310  # 3.10 (two decimals, L1080)
SOFTWARE_VERSION_POWER = 150  # 1.50 (L1084)
SERIAL_NUMBER = (0, 0, 0x1234, 0x5678)
DC_LINK_VOLTAGE_V = 565  # monitor register 23: 400 V x sqrt 2
HEATSINK_TEMPERATURE_C = 30  # monitor register 24
# Current model: magnetising current plus a load current proportional to the
# output frequency, rated current at the motor rated frequency; torque
# proportional to speed (a fan-like load), power = rated power x torque x speed.
MAGNETISING_CURRENT_RATIO = Fraction(3, 10)

# Parameters the model acts on, by parameter number (eaton_parameters.parameter_register
# finds their registers). DE1 has no quick-stop ramp: simulator choice, it
# uses its deceleration ramp P-04. DB1/DC1 P-13 "Letzter Fehler" (L1648)
# shows the last fault; the DA1 has it in P0-13, without a register.
_COMPACT = {
    "f_max": "P-01",
    "f_min": "P-02",
    "accel": "P-03",
    "decel": "P-04",
    "quick": "P-24",
    "ff1": "P-20",
    "voltage": "P-07",
    "current": "P-08",
    "frequency": "P-09",
    "speed": "P-10",
    "last_fault": "P-13",
}
_NAMES = {
    Family.DA1: {
        "f_max": "P1-01",
        "f_min": "P1-02",
        "accel": "P1-03",
        "decel": "P1-04",
        "quick": "P2-25",
        "ff1": "P2-01",
        "ff8": "P2-08",
        "voltage": "P1-07",
        "current": "P1-08",
        "frequency": "P1-09",
        "speed": "P1-10",
    },
    Family.DB1: _COMPACT,
    Family.DC1: _COMPACT,
    Family.DE1: {**_COMPACT, "quick": "P-04"},
}

# A parameter's printed range, when it is plain integers (checked on writes
# of parameters whose scaling is 1 or empty): "0 - 13", "0-17", "0, 1, 2", "0, 1, ..., 8"
_SPAN = re.compile(r"^\s*(-?\d+)\s*-\s*\+?(-?\d+)\s*$")
_LIST = re.compile(r"^\s*\d+(\s*,\s*\d+)*\s*$")
_LIST_TO = re.compile(r"^\s*(\d+)(?:\s*,\s*\d+)*\s*,\s*\.\.\.\s*,\s*(\d+)\s*$")

# Modbus exception codes. The manual documents no exception responses, only
# requests a drive ignores (A12, digest §2.3); a real slave answers a wrong
# address or value with the standard codes, so the model does.
ILLEGAL_DATA_ADDRESS = 2
ILLEGAL_DATA_VALUE = 3


def _scale(row: eaton_parameters.Parameter) -> eaton.Scale:
    """The linear scale of a parameter the model computes with (every one
    _NAMES names has one); ValueError for a row whose scaling is not one."""
    scale = row.scale
    if scale is None:
        raise ValueError(f"{row.number} {row.name}: {row.scaling!r} is not one linear scale")
    return scale


def _allowed_values(row: eaton_parameters.Parameter):
    """(lowest, highest) or a set of the raw values a parameter row accepts,
    None where its printed range is not a plain integer one."""
    if row.scaling not in ("", eaton_parameters.ONE):
        return None
    text = row.range
    if match := _SPAN.match(text):
        return int(match.group(1)), int(match.group(2))
    if match := _LIST_TO.match(text):
        return int(match.group(1)), int(match.group(2))
    if _LIST.match(text):
        return frozenset(int(v) for v in text.split(","))
    return None


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
        self._defaults()
        for number, value in (registers or {}).items():
            if number not in self._regs:
                raise ValueError(f"{self.family.name} has no register {number}")
            self._regs[number] = int(value) & 0xFFFF

        self._di1 = True
        self.fault = eaton_faults.FAULT_NONE
        self._now: int | None = None
        self._out = Fraction(0)  # output frequency in Hz, negative = reverse
        self._modulating = False  # the output stage is on (status RUNNING)
        self._run_request = False  # a RUN edge was accepted and not withdrawn
        self._quick = False  # ramping down on ramp 2
        self._trip_at_standstill = False  # DA1 P5-06 = 1 after a comm loss
        self._last_telegram: int | None = None
        self._comm_lost = False  # the watchdog fired; waits for a telegram
        self._fixed_frequency_8 = False  # DA1 P5-06 = 3 in effect
        self._cw_prev = self._control_word()
        self._publish()

    # ------------------------------------------------------------------ defaults

    def _name(self, key: str) -> str:
        return _NAMES[self.family][key]

    def _row(self, number: str, keyword: str = "") -> eaton_parameters.Parameter:
        """The table row of a parameter; of a shared register (DB1/DC1 P-36)
        the field whose name contains keyword."""
        rows = eaton_parameters.parameter_rows(self.family, number, de11=self.de11)
        if len(rows) > 1:
            rows = tuple(r for r in rows if keyword.lower() in r.name.lower())
        return rows[0]

    def _param(self, number: str, keyword: str = "") -> int:
        row = self._row(number, keyword)
        return row.extract(self._regs[row.register])

    def _set_param(self, number: str, value: int, keyword: str = "") -> None:
        row = self._row(number, keyword)
        self._regs[row.register] = row.insert(self._regs[row.register], value)

    def _set_scaled(self, key: str, value) -> None:
        row = self._row(self._name(key))
        self._set_param(row.number, _scale(row).to_raw(value))

    def _defaults(self) -> None:
        """Simulator defaults: Modbus control, 0..50 Hz, 5 s ramps, the comm
        timeout at its factory value. Parameters not named here are 0."""
        family = self.family
        self._set_param(
            eaton_parameters.CONTROL_SOURCE_PARAMETER[family], eaton_parameters.MODBUS_CONTROL_SOURCES[family][0]
        )
        for key, value in (
            ("f_max", DEFAULT_F_MAX_HZ),
            ("f_min", DEFAULT_F_MIN_HZ),
            ("accel", DEFAULT_RAMP_S),
            ("decel", DEFAULT_RAMP_S),
            ("ff1", DEFAULT_FIXED_FREQUENCY_1_HZ),
            ("voltage", DEFAULT_MOTOR_VOLTAGE_V),
            ("current", DEFAULT_MOTOR_CURRENT_A),
            ("frequency", DEFAULT_MOTOR_FREQUENCY_HZ),
            ("speed", DEFAULT_MOTOR_SPEED_RPM),
        ):
            self._set_scaled(key, value)
        serial = eaton_settings.SERIAL_SETTINGS[family]
        self._set_param(serial.address, DEFAULT_UNIT_ADDRESS, "adress")
        self._set_param(serial.baud_rate, serial.baud_factory, "baud")
        if serial.data_format_factory is not None:
            self._set_param(serial.data_format, serial.data_format_factory)
        if family is Family.DA1:
            self._regs[eaton.REG_DRIVE_TYPE] = (
                DA1_FRAME_SIZE << 12 | DA1_VOLTAGE_INDEX << 8 | DA1_POWER_INDEX
            )  # P0-29 Rating ID (L1216-1219)
            self._set_param(self._name("quick"), self._quick_scale().to_raw(DEFAULT_QUICK_STOP_S))
            self._set_scaled("ff8", DEFAULT_FIXED_FREQUENCY_8_HZ)
            self._set_param(
                eaton_settings.DA1_COMM_TIMEOUT, eaton_settings.DA1_COMM_TIMEOUT_FACTORY
            )  # 2.0 s (L387, A7)
            self._set_param(
                eaton_settings.DA1_COMM_LOSS_ACTION, eaton_settings.DA1_COMM_LOSS_ACTION_FACTORY
            )  # trip (L388)
        else:
            self._regs[eaton.REG_DRIVE_TYPE] = DRIVE_VARIANT
            if family is not Family.DE1:
                self._set_scaled("quick", DEFAULT_QUICK_STOP_S)
            # DB1/DC1 code 4 "t 3000 ms" (L400, L423, A8), DE1 0 = off (L445)
            self._set_param(
                eaton_settings.COMM_TIMEOUT_PARAMETER[family],
                eaton_settings.COMM_TIMEOUT_FACTORY_CODE[family],
                "timeout",
            )
            if family is Family.DE1:
                self._set_param(eaton_settings.DE1_PDP_ADDRESS, DEFAULT_UNIT_ADDRESS)
        self._regs[eaton.REG_POWER_RATING] = POWER_RATING_KW
        self._regs[eaton.REG_VOLTAGE_LEVEL] = VOLTAGE_LEVEL_V
        self._regs[eaton.REG_SOFTWARE_VERSION_CONTROL] = SOFTWARE_VERSION_CONTROL
        self._regs[eaton.REG_SOFTWARE_VERSION_POWER] = SOFTWARE_VERSION_POWER
        model = "DE11" if self.de11 else family.name
        self._regs[eaton.REG_DEVICE_ID] = next(
            v for v, (_, m) in eaton.DEVICE_IDENTIFICATION.items() if m == model
        )  # L1086-1096
        for register, word in zip(eaton.SERIAL_NUMBER_REGISTERS[family], SERIAL_NUMBER):
            self._regs[register] = word
        monitors = {m.register for m in eaton.MONITOR_VALUES[family]}
        if 23 in monitors:  # P0-20 / P0-08 DC link voltage (L1201, L1575, L1889)
            self._regs[23] = DC_LINK_VOLTAGE_V
        if 24 in monitors:  # P0-21 / P0-09 heatsink temperature (L1202, L1576, L1890)
            self._regs[24] = HEATSINK_TEMPERATURE_C

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
        self._publish()

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
        source = self._param(eaton_parameters.CONTROL_SOURCE_PARAMETER[self.family])
        return source in eaton_parameters.MODBUS_CONTROL_SOURCES[self.family]

    @property
    def comm_lost(self) -> bool:
        """The comm-loss watchdog fired and no telegram has arrived since."""
        return self._comm_lost

    def status(self) -> int:
        """The ID 6 word."""
        return self._regs[eaton.REG_STATUS_WORD]

    def register(self, number: int) -> int:
        """The raw value of any register, for tests."""
        try:
            return self._regs[number]
        except KeyError:
            raise ValueError(f"{self.family.name} has no register {number}") from None

    def trip(self, fault: int) -> None:
        """Inject a fault of eaton_faults.FAULTS at the last advanced time."""
        if fault not in eaton_faults.FAULTS or fault == eaton_faults.FAULT_NONE:
            raise ValueError(f"{fault} is not a fault number of Tabelle 11")
        self._set_fault(fault)
        self._publish()

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
            self._publish()

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
            self._check_write(register + offset, value)
        for offset, value in enumerate(values):
            self._regs[register + offset] = value
        self._apply_control()
        self._publish()

    def _check_write(self, register: int, value: int) -> None:
        name = self.family.name
        if register not in self._regs:
            raise ModbusRefusal(ILLEGAL_DATA_ADDRESS, f"{name} has no register {register}")
        if register not in self._writable:
            raise ModbusRefusal(ILLEGAL_DATA_ADDRESS, f"{name} register {register} is read-only")
        if not 0 <= value <= 0xFFFF:
            raise ModbusRefusal(ILLEGAL_DATA_VALUE, f"{value} is not a 16-bit register value")
        process = eaton.PROCESS_DATA.get(register)
        if process is not None and process.limits is not None:
            low, high = process.limits  # ID 3 0..2000 (L799), ID 4 0..60000 (L805)
            if not low <= value <= high:
                raise ModbusRefusal(ILLEGAL_DATA_VALUE, f"ID {register} takes {low}..{high}, not {value}")
        for row in self._rows.get(register, ()):
            if self._modulating and not row.writable_in_run:
                raise ModbusRefusal(
                    ILLEGAL_DATA_VALUE, f"{name} {row.number} {row.name} can only be written while the drive is stopped"
                )
            field = row.extract(value)
            if row.format == eaton_parameters.S16:
                field = eaton.to_signed16(field)
            allowed = _allowed_values(row)
            if row.number == eaton_settings.DA1_COMM_TIMEOUT and self.family is Family.DA1:
                allowed = (0, eaton_settings.DA1_COMM_TIMEOUT_MAX)  # "0.0 - 5.0" s (L1395)
            if isinstance(allowed, tuple):
                ok = allowed[0] <= field <= allowed[1]
            else:
                ok = allowed is None or field in allowed
            if not ok:
                raise ModbusRefusal(
                    ILLEGAL_DATA_VALUE, f"{name} {row.number} {row.name}: {field} is outside {row.range!r}"
                )

    # ------------------------------------------------------------------ time

    def advance(self, now_ns: int) -> None:
        """Time passes up to now_ns: ramps, the comm-loss watchdog and its
        action. A time before the last one moves nothing (and, as every
        change of state publishes at once, republishes nothing)."""
        if self._now is None:
            self._now = now_ns
        elif self._now >= now_ns:
            return
        while self._now < now_ns:
            deadline = self._comm_deadline()
            end = now_ns
            if deadline is not None and deadline < now_ns:
                end = max(deadline, self._now)
            self._integrate(Fraction(end - self._now))
            self._now = end
            if deadline is not None and deadline < now_ns:
                self._on_comm_loss()
        self._publish()

    def _comm_timeout(self):
        """(timeout in ns, reaction) of the configured comm-loss monitoring,
        None when off. The watchdog runs only while the drive takes its
        commands from Modbus (simulator choice)."""
        if self.family is Family.DA1:
            raw = self._param(eaton_settings.DA1_COMM_TIMEOUT)
            if raw == eaton_settings.DA1_COMM_TIMEOUT_OFF:
                return None
            ns = int(eaton_settings.DA1_COMM_TIMEOUT_SCALE.step * raw * S)
            action = self._param(eaton_settings.DA1_COMM_LOSS_ACTION)
            try:
                return ns, eaton_settings.Da1CommLossAction(action)
            except ValueError:
                return ns, eaton_settings.Da1CommLossAction.TRIP
        code = self._param(eaton_settings.COMM_TIMEOUT_PARAMETER[self.family], "timeout")
        timeout = eaton_settings.COMM_TIMEOUT_CODES.get(code)
        if timeout is None or timeout.timeout_ms is None:
            return None
        return timeout.timeout_ms * 1_000_000, timeout.reaction

    def _comm_deadline(self) -> int | None:
        if self._last_telegram is None or self._comm_lost or not self.bus_control:
            return None
        timeout = self._comm_timeout()
        return None if timeout is None else self._last_telegram + timeout[0]

    def _on_comm_loss(self) -> None:
        """No valid telegram within the timeout (L387-388, L400, L423, L445)."""
        self._comm_lost = True
        _, reaction = self._comm_timeout()
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
        self._publish()

    # ------------------------------------------------------------------ control

    def _control_word(self) -> int:
        """ID 1 as the drive uses it: 0 when the control source is not Modbus
        (the word is stored but ignored)."""
        return self._regs[eaton.REG_CONTROL_WORD] if self.bus_control else 0

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
        if rising & ControlWord.FAULT_RESET and self.fault:
            # every fault's cause is gone once reset is asked for: injected faults are events, and a
            # comm-loss fault is reset by a telegram, which restored the connection
            self.fault = eaton_faults.FAULT_NONE
        if cw & ControlWord.COAST or self.fault or not self._di1:
            self._run_request = False
            self._coast()
        elif cw & ControlWord.QUICK_STOP:
            if self._run_request or self._modulating:
                self._stop(quick=True)  # "Schnellstopp (Rampe 2)" (L771)
        elif not cw & ControlWord.RUN:
            if self._run_request:
                self._stop(quick=False)
        elif rising & ControlWord.RUN:
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
        self._out = Fraction(0)
        self._quick = False
        self._trip_at_standstill = False

    def _set_fault(self, fault: int) -> None:
        """A trip stops the output at once (coast); the first fault stays
        until reset (simulator choice)."""
        if not self.fault:
            self.fault = fault
            if self.family is not Family.DA1:
                self._set_param(self._name("last_fault"), fault)  # P-13 "Letzter Fehler" (L1648)
        self._run_request = False
        self._coast()

    # ------------------------------------------------------------------ motion

    def _hz(self, key: str) -> Fraction:
        row = self._row(self._name(key))
        return _scale(row).step * row.extract(self._regs[row.register])

    def _setpoint(self) -> Fraction:
        """ID 2 in 0.1 Hz (L792) limited to f-min..f-max (L784-790); FF1
        (bit 6) and "Sollwert mit 0 überschreiben" (bit 7) replace it, 0 wins
        over f-min (simulator choice); DA1 P5-06 = 3 runs at P2-08 (L388)."""
        f_max, f_min = self._hz("f_max"), self._hz("f_min")
        cw = self._control_word()
        if cw & ControlWord.ZERO_SETPOINT:
            return Fraction(0)
        if self._fixed_frequency_8:
            value = self._hz("ff8")
        elif cw & ControlWord.FIXED_FREQUENCY_1:
            value = self._hz("ff1")
        else:
            value = eaton.SPEED.step * self._regs[eaton.REG_SPEED_SETPOINT]
        return min(max(value, f_min), f_max)

    def _target(self) -> Fraction:
        """The signed frequency the output heads for."""
        if not self._run_request:
            return Fraction(0)
        reverse = self._control_word() & ControlWord.REVERSE
        return -self._setpoint() if reverse else self._setpoint()

    def _quick_scale(self) -> eaton.Scale:
        if self.family is Family.DA1:  # P2-25 counts by frame size (L1332)
            frame = eaton_settings.decode_da1_rating_id(self._regs[eaton.REG_DRIVE_TYPE]).frame_size
            try:
                return eaton.da1_ramp_scale(frame)
            except ValueError:
                return eaton.da1_ramp_scale(DA1_FRAME_SIZE)
        return _scale(self._row(self._name("quick")))

    def _bus_ramps(self) -> bool:
        """ID 4 replaces both ramps: DA1 P5-07 = 1 (L389), DB1/DC1 P-12 = 4 (L397, L413)."""
        if self.family is Family.DA1:
            return self._param(eaton_parameters.DA1_FIELDBUS_RAMP_CONTROL) == 1
        if self.family is Family.DE1:
            return False
        source = self._param(eaton_parameters.CONTROL_SOURCE_PARAMETER[self.family])
        return source == eaton_parameters.DB1_DC1_MODBUS_RAMPS_SOURCE

    def _ramp_s(self, key: str) -> Fraction:
        if key != "quick" and self._bus_ramps():
            return eaton.RAMP_TIME.step * self._regs[eaton.REG_RAMP_TIME]
        if key == "quick":
            row = self._row(self._name("quick"))
            return self._quick_scale().step * row.extract(self._regs[row.register])
        row = self._row(self._name(key))
        return _scale(row).step * row.extract(self._regs[row.register])

    def _rate(self, key: str) -> Fraction | None:
        """Hz per ns; None = no ramp (a ramp time of 0 or an f-max of 0). A
        ramp time runs from 0 to f-max (simulator choice: the manual does
        not say what a ramp time refers to)."""
        seconds, f_max = self._ramp_s(key), self._hz("f_max")
        if seconds <= 0 or f_max <= 0:
            return None
        return f_max / (seconds * S)

    def _integrate(self, dt: Fraction) -> None:
        """Move the output for dt ns: towards zero on the deceleration ramp
        (ramp 2 in a quick stop), away from it on the acceleration ramp; a
        reversal passes through zero (L468: "gemäß der eingestellten Rampen")."""
        while self._modulating and dt > 0:
            target = self._target()
            out = self._out
            if out == target:
                if not self._run_request:
                    self._standstill()
                break
            if out != 0 and (target == 0 or (target > 0) != (out > 0) or abs(target) < abs(out)):
                limit = Fraction(0) if target == 0 or (target > 0) != (out > 0) else target
                rate = self._rate("quick" if self._quick else "decel")
            else:
                limit, rate = target, self._rate("accel")
            distance = abs(limit - out)
            needed = Fraction(0) if rate is None else distance / rate
            if rate is None or needed <= dt:  # no ramp: there at once
                self._out = limit
                dt -= needed
            else:
                self._out = out + (rate * dt if limit > out else -rate * dt)
                dt = Fraction(0)
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
        """The monitoring registers from the state (digest §3.3)."""
        regs, family = self._regs, self.family
        flags = StatusWord(0)
        bus = self.bus_control
        if self._di1 and not self.fault and bus:
            flags |= StatusWord.READY
        if self._modulating:
            flags |= StatusWord.RUNNING | StatusWord.SPEED_CONTROL_ACTIVE  # bit 6: simulator choice
            target = self._target()
            if self._out < 0 or (self._out == 0 and target < 0):
                flags |= StatusWord.REVERSE
            if self._run_request and self._out == target:
                flags |= StatusWord.AT_SETPOINT
        if self.fault:
            flags |= StatusWord.FAULT
        # "Nullzahl" (A21) while the output frequency is 0, with the enable present: the manual's
        # own example reads ID 6 = 0 from a stopped DA1 (L1125-1140), which is one with STO open
        if self._out == 0 and self._di1:
            flags |= StatusWord.ZERO_SPEED
        if self._di1:
            flags |= StatusWord.HARDWARE_ENABLE  # DA1: STO status, others: DI1 (L845-850)
        regs[eaton.REG_STATUS_WORD] = eaton.status_word(flags, self.fault)
        # ID 7 without sign, the direction is status bit 2 (A24, as eaton.speed_setpoint_raw)
        speed = abs(self._out)
        regs[eaton.REG_ACTUAL_SPEED] = min(eaton.SPEED.to_raw(speed), 0xFFFF)
        rated_hz = self._rated_hz()
        load = min(speed / rated_hz, Fraction(2)) if rated_hz else Fraction(0)
        if self._modulating:
            rated_a = _scale(self._row(self._name("current"))).step * self._param(self._name("current"))
            current = rated_a * (MAGNETISING_CURRENT_RATIO + (1 - MAGNETISING_CURRENT_RATIO) * load)
            torque = 100 * load
        else:
            current = torque = Fraction(0)
        regs[eaton.REG_MOTOR_CURRENT] = min(eaton.CURRENT.to_raw(current), 0xFFFF)
        if family in eaton.PROCESS_DATA[eaton.REG_TORQUE].families:
            regs[eaton.REG_TORQUE] = eaton.TORQUE.to_raw(torque)
            regs[eaton.REG_OUTPUT_POWER] = eaton.OUTPUT_POWER.to_raw(regs[eaton.REG_POWER_RATING] * torque / 100 * load)
        # ID 11 bit 0 = DI1 (L954); on the DA1 the model shows STO there (a DI1 wired with it, A22)
        regs[eaton.REG_DI_STATUS] = 1 if self._di1 else 0

    def _rated_hz(self) -> Fraction:
        row = self._row(self._name("frequency"))
        return _scale(row).step * row.extract(self._regs[row.register])
