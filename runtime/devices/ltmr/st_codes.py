"""The LTMR numbers for ST programs, generated from registers.py, bits.py, codes.py and pkw.py.

    python -m softplc.runtime.devices    # rewrites fblocks/vendor/ltmr_codes.st (and the others)

The vendor function blocks and user programs read bit masks, register
numbers, PKW function codes and trip/alarm texts from
fblocks/vendor/ltmr_codes.st, so they use the same numbers as the simulator
and the master. A test regenerates the file and compares it with the shipped
one.

    VAR_GLOBAL CONSTANT   LTMR_<FLAGS>_<BIT> : WORD (one per IntFlag member),
                          LTMR_<ENUM>_<VALUE> : UINT, LTMR_REG_* : UINT,
                          LTMR_PKW_* : BYTE, LTMR_TRIP_* / LTMR_ALARM_* : UINT
    FUNCTION LTMR_TRIP_TEXT(Code : UINT) : STRING[80]    DT_FaultCode texts
    FUNCTION LTMR_ALARM_TEXT(Code : UINT) : STRING[80]   DT_WarningCode texts
"""

from __future__ import annotations

import enum

from ..st_text import st_string, vendor_file
from . import bits as ltmr_bits
from . import codes as ltmr_codes
from . import pkw
from . import registers as ltmr

ST_FILE = vendor_file("ltmr_codes.st")
TEXT_LENGTH = 80


def _members_in_order(module, base) -> list:
    """Classes of `module` derived from `base`, in the order the module defines them."""
    return [
        obj
        for obj in vars(module).values()
        if isinstance(obj, type) and issubclass(obj, base) and obj.__module__ == module.__name__
    ]


def _constants(module, prefix: str) -> list:
    return [
        (name, value)
        for name, value in vars(module).items()
        if name.startswith(prefix) and isinstance(value, int) and not isinstance(value, enum.Enum)
    ]


def _title(cls) -> str:
    """The first sentence of a class docstring, for a comment."""
    return " ".join(cls.__doc__.split()).split(". ")[0].rstrip(".")


def _flag_lines() -> list:
    lines = []
    for flags in _members_in_order(ltmr_bits, enum.IntFlag):
        lines.append(f"    (* {_title(flags)} *)")
        for member in flags:
            lines.append(f"    LTMR_{flags.__name__.upper()}_{member.name} : WORD := 16#{int(member):04X};")
        if flags is ltmr_bits.Status1:
            lines.append(f"    LTMR_STATUS1_CURRENT_SHIFT : UINT := {ltmr_bits.STATUS1_CURRENT_SHIFT};")
            lines.append(f"    LTMR_STATUS1_CURRENT_MASK : WORD := 16#{ltmr_bits.STATUS1_CURRENT_MASK:04X};")
    return lines


def _enum_lines() -> list:
    lines = []
    for values in _members_in_order(ltmr_codes, enum.IntEnum):
        lines.append(f"    (* {_title(values)} *)")
        for member in values:
            lines.append(f"    LTMR_{values.__name__.upper()}_{member.name} : UINT := {int(member)};")
    return lines


def _case_branches(function: str, codes: dict) -> list:
    """CASE branches, consecutive codes with the same text joined into a range (100..104)."""
    runs: list[list[int]] = []
    for code in sorted(codes):
        if runs and runs[-1][1] == code - 1 and codes[runs[-1][0]] == codes[code]:
            runs[-1][1] = code
        else:
            runs.append([code, code])
    return [
        f"    {first if first == last else f'{first}..{last}'}: {function} := {st_string(codes[first])};"
        for first, last in runs
    ]


def _text_function(function: str, codes: dict, unknown: str, what: str) -> list:
    return [
        f"(* {what} *)",
        f"FUNCTION {function} : STRING[{TEXT_LENGTH}]",
        "VAR_INPUT",
        "    Code : UINT;",
        "END_VAR",
        "CASE Code OF",
        *_case_branches(function, codes),
        "ELSE",
        f"    {function} := {st_string(unknown)};",
        "END_CASE;",
        "END_FUNCTION",
    ]


def render() -> str:
    lines = [
        "(*",
        "    LTMR_* -- TeSys T LTMR numbers and texts for ST programs.",
        "",
        "    GENERATED from runtime/devices/ltmr/registers.py, bits.py, codes.py and pkw.py by",
        "    runtime/devices/ltmr/st_codes.py. Do not edit: change the Python tables, then run",
        "        python -m softplc.runtime.devices",
        "",
        "    Source of every number: the LTMR CANopen manual (DOCA0132EN), cited in those modules.",
        "        IF (status1 AND LTMR_STATUS1_RUNNING) <> 0 THEN ... END_IF;",
        "        text := LTMR_TRIP_TEXT(tripCode);",
        "*)",
        "VAR_GLOBAL CONSTANT",
        *_flag_lines(),
        *_enum_lines(),
        "    (* PKW function codes (RPDO4/TPDO4 word 2, bits 8-14) *)",
        *(
            f"    LTMR_PKW_{name} : BYTE := 16#{code:02X};"
            for code, name in pkw.FUNCTION_NAMES.items()
            if code != pkw.NONE
        ),
        "    (* register numbers *)",
        *(f"    LTMR_{name} : UINT := {value};" for name, value in _constants(ltmr, "REG_")),
        "    (* trip codes (DT_FaultCode) and alarm codes (DT_WarningCode) *)",
        *(f"    LTMR_{name} : UINT := {value};" for name, value in _constants(ltmr_codes, "TRIP_")),
        *(f"    LTMR_{name} : UINT := {value};" for name, value in _constants(ltmr_codes, "ALARM_")),
        "END_VAR",
        "",
        *_text_function(
            "LTMR_TRIP_TEXT",
            ltmr_codes.TRIP_CODES,
            "unknown trip code",
            "text of a trip code, register 451 and the trip history (DT_FaultCode)",
        ),
        "",
        *_text_function(
            "LTMR_ALARM_TEXT",
            ltmr_codes.ALARM_CODES,
            "unknown alarm code",
            "text of an alarm code, register 460 (DT_WarningCode)",
        ),
    ]
    return "\n".join(lines) + "\n"
