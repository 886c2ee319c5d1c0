"""Whether an Eaton drive takes a register write (model.py EatonDriveModel.write):
the register exists and is writable, the value is in the range the manual
prints for it, a STOP parameter is written only while the output is off.
A refusal is a ModbusRefusal with the standard exception code.
"""

from __future__ import annotations

import re

from ...io.modbus.unit import ModbusRefusal
from . import parameters as eaton_parameters
from . import registers as eaton
from . import settings as eaton_settings
from .registers import Family

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


def allowed_values(row: eaton_parameters.Parameter):
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


def check_write(drive, register: int, value: int) -> None:
    """ModbusRefusal unless drive (an EatonDriveModel) takes value in register now."""
    name = drive.family.name
    if register not in drive._regs:
        raise ModbusRefusal(ILLEGAL_DATA_ADDRESS, f"{name} has no register {register}")
    if register not in drive._writable:
        raise ModbusRefusal(ILLEGAL_DATA_ADDRESS, f"{name} register {register} is read-only")
    if not 0 <= value <= 0xFFFF:
        raise ModbusRefusal(ILLEGAL_DATA_VALUE, f"{value} is not a 16-bit register value")
    process = eaton.PROCESS_DATA.get(register)
    if process is not None and process.limits is not None:
        low, high = process.limits  # ID 3 0..2000 (L799), ID 4 0..60000 (L805)
        if not low <= value <= high:
            raise ModbusRefusal(ILLEGAL_DATA_VALUE, f"ID {register} takes {low}..{high}, not {value}")
    for row in drive._rows.get(register, ()):
        if drive.running and not row.writable_in_run:
            raise ModbusRefusal(
                ILLEGAL_DATA_VALUE, f"{name} {row.number} {row.name} can only be written while the drive is stopped"
            )
        field = row.extract(value)
        if row.format == eaton_parameters.S16:
            field = eaton.to_signed16(field)
        allowed = allowed_values(row)
        if row.number == eaton_settings.DA1_COMM_TIMEOUT and drive.family is Family.DA1:
            allowed = (0, eaton_settings.DA1_COMM_TIMEOUT_MAX)  # "0.0 - 5.0" s (L1395)
        if isinstance(allowed, tuple):
            ok = allowed[0] <= field <= allowed[1]
        else:
            ok = allowed is None or field in allowed
        if not ok:
            raise ModbusRefusal(ILLEGAL_DATA_VALUE, f"{name} {row.number} {row.name}: {field} is outside {row.range!r}")
