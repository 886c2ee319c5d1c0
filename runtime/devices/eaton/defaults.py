"""What a simulated Eaton drive holds before anything is written to it: the
simulator's defaults (choices, where the manual names none), the parameters
the model acts on by name, and set_defaults(), which writes them into a
fresh register image (model.py).
"""

from __future__ import annotations

from fractions import Fraction

from . import parameters as eaton_parameters
from . import registers as eaton
from . import settings as eaton_settings
from .registers import Family

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
NAMES = {
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


def scale(row: eaton_parameters.Parameter) -> eaton.Scale:
    """The linear scale of a parameter the model computes with (every one
    NAMES names has one); ValueError for a row whose scaling is not one."""
    found = row.scale
    if found is None:
        raise ValueError(f"{row.number} {row.name}: {row.scaling!r} is not one linear scale")
    return found


def quick_scale(family: Family, regs: dict[int, int], quick_row: eaton_parameters.Parameter) -> eaton.Scale:
    """The scale of the quick-stop ramp (NAMES "quick")."""
    if family is Family.DA1:  # P2-25 counts by frame size (L1332)
        frame = eaton_settings.decode_da1_rating_id(regs[eaton.REG_DRIVE_TYPE]).frame_size
        try:
            return eaton.da1_ramp_scale(frame)
        except ValueError:
            return eaton.da1_ramp_scale(DA1_FRAME_SIZE)
    return scale(quick_row)


def set_defaults(drive) -> None:
    """Simulator defaults into an EatonDriveModel's registers: Modbus
    control, 0..50 Hz, 5 s ramps, the comm timeout at its factory value.
    Parameters not named here are 0."""
    family, regs = drive.family, drive._regs
    names = NAMES[family]

    def set_scaled(key: str, value) -> None:
        row = drive._row(names[key])
        drive._set_param(row.number, scale(row).to_raw(value))

    drive._set_param(
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
        set_scaled(key, value)
    serial = eaton_settings.SERIAL_SETTINGS[family]
    drive._set_param(serial.address, DEFAULT_UNIT_ADDRESS, "adress")
    drive._set_param(serial.baud_rate, serial.baud_factory, "baud")
    if serial.data_format_factory is not None:
        drive._set_param(serial.data_format, serial.data_format_factory)
    if family is Family.DA1:
        regs[eaton.REG_DRIVE_TYPE] = (
            DA1_FRAME_SIZE << 12 | DA1_VOLTAGE_INDEX << 8 | DA1_POWER_INDEX
        )  # P0-29 Rating ID (L1216-1219)
        quick = drive._row(names["quick"])
        drive._set_param(quick.number, quick_scale(family, regs, quick).to_raw(DEFAULT_QUICK_STOP_S))
        set_scaled("ff8", DEFAULT_FIXED_FREQUENCY_8_HZ)
        drive._set_param(eaton_settings.DA1_COMM_TIMEOUT, eaton_settings.DA1_COMM_TIMEOUT_FACTORY)  # 2.0 s (L387, A7)
        drive._set_param(
            eaton_settings.DA1_COMM_LOSS_ACTION, eaton_settings.DA1_COMM_LOSS_ACTION_FACTORY
        )  # trip (L388)
    else:
        regs[eaton.REG_DRIVE_TYPE] = DRIVE_VARIANT
        if family is not Family.DE1:
            set_scaled("quick", DEFAULT_QUICK_STOP_S)
        # DB1/DC1 code 4 "t 3000 ms" (L400, L423, A8), DE1 0 = off (L445)
        drive._set_param(
            eaton_settings.COMM_TIMEOUT_PARAMETER[family],
            eaton_settings.COMM_TIMEOUT_FACTORY_CODE[family],
            "timeout",
        )
        if family is Family.DE1:
            drive._set_param(eaton_settings.DE1_PDP_ADDRESS, DEFAULT_UNIT_ADDRESS)
    regs[eaton.REG_POWER_RATING] = POWER_RATING_KW
    regs[eaton.REG_VOLTAGE_LEVEL] = VOLTAGE_LEVEL_V
    regs[eaton.REG_SOFTWARE_VERSION_CONTROL] = SOFTWARE_VERSION_CONTROL
    regs[eaton.REG_SOFTWARE_VERSION_POWER] = SOFTWARE_VERSION_POWER
    model = "DE11" if drive.de11 else family.name
    regs[eaton.REG_DEVICE_ID] = next(v for v, (_, m) in eaton.DEVICE_IDENTIFICATION.items() if m == model)  # L1086-1096
    for register, word in zip(eaton.SERIAL_NUMBER_REGISTERS[family], SERIAL_NUMBER):
        regs[register] = word
    monitors = {m.register for m in eaton.MONITOR_VALUES[family]}
    if 23 in monitors:  # P0-20 / P0-08 DC link voltage (L1201, L1575, L1889)
        regs[23] = DC_LINK_VOLTAGE_V
    if 24 in monitors:  # P0-21 / P0-09 heatsink temperature (L1202, L1576, L1890)
        regs[24] = HEATSINK_TEMPERATURE_C
