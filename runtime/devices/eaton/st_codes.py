"""The Eaton PowerXL numbers for ST programs, generated from registers.py and faults.py.

    python -m softplc.runtime.devices    # rewrites fblocks/vendor/eaton_codes.st (and the others)

DA1_DRIVE and EATON_PARAMETER (fblocks/vendor/eaton.st) and user programs
read control/status bits, register numbers, ID 17 values and fault texts from
fblocks/vendor/eaton_codes.st, so they use the numbers the simulator uses. A
test regenerates the file and compares it with the shipped one.

    VAR_GLOBAL CONSTANT   EATON_CW_* / EATON_SW_* : WORD   control and status bits
                          EATON_REG_* : UINT                register numbers (IDs)
                          EATON_FAMILY_* : USINT, EATON_ID17_* : WORD
    FUNCTION EATON_FAULT_TEXT(Code : UINT) : STRING[120]   Tabelle 11
    FUNCTION EATON_FAULT_DISPLAY(Code : UINT) : STRING[80]
    FUNCTION EATON_FAMILY(Id17 : WORD) : USINT              0: not an Eaton drive
    FUNCTION EATON_MODEL(Id17 : WORD) : STRING[80]          'DA1' ... 'DE11', ''
"""

from __future__ import annotations

from ..st_text import st_string, vendor_file
from . import faults as eaton_faults
from . import registers as eaton

ST_FILE = vendor_file("eaton_codes.st")
FAULT_TEXT_LENGTH = 120  # the longest cause in Tabelle 11 is 87 characters


def _case_function(name: str, result: str, arg: str, arg_type: str, branches: list, default: str, what: str) -> list:
    return [
        f"(* {what} *)",
        f"FUNCTION {name} : {result}",
        "VAR_INPUT",
        f"    {arg} : {arg_type};",
        "END_VAR",
        f"CASE {arg} OF",
        *(f"    {value}: {name} := {text};" for value, text in branches),
        "ELSE",
        f"    {name} := {default};",
        "END_CASE;",
        "END_FUNCTION",
    ]


def render() -> str:
    ids = sorted(eaton.DEVICE_IDENTIFICATION.items())
    lines = [
        "(*",
        "    EATON_* -- Eaton PowerXL DA1/DB1/DC1/DE1 numbers and texts for ST programs.",
        "",
        "    GENERATED from runtime/devices/eaton/registers.py and faults.py by runtime/devices/eaton/st_codes.py.",
        "    Do not edit: change the Python tables, then run",
        "        python -m softplc.runtime.devices",
        "",
        "    Source of every number: the PowerXL Modbus RTU manual (002), cited in those modules.",
        "    Registers are the manual's IDs, counted from 1; on the wire ID n is offset n-1.",
        "        IF (status AND EATON_SW_FAULT) <> 0 THEN text := EATON_FAULT_TEXT(code); END_IF;",
        "*)",
        "VAR_GLOBAL CONSTANT",
        "    (* ID 1 control word (L760-781) *)",
        *(f"    EATON_CW_{m.name} : WORD := 16#{int(m):04X};" for m in eaton.ControlWord),
        "    (* ID 1 while the PLC holds its outputs safe: stop (DA1_DRIVE declares it, MODBUS_SAFE_WRITE) *)",
        f"    EATON_CW_SAFE : WORD := 16#{int(eaton.SAFE_CONTROL_WORD):04X};",
        "    (* ID 6 status word, bits 0-7 (L831-850); bits 8-15 hold the fault number *)",
        *(f"    EATON_SW_{m.name} : WORD := 16#{int(m):04X};" for m in eaton.StatusWord),
        f"    EATON_FAULT_SHIFT : UINT := {eaton.FAULT_NUMBER_SHIFT};",
        f"    EATON_COMM_LOSS_FAULT : UINT := {eaton_faults.COMM_LOSS_FAULT};",
        f"    EATON_MAX_REGISTERS_PER_READ : UINT := {eaton.MAX_REGISTERS_PER_READ};",
        "    (* register numbers (IDs) *)",
        *(
            f"    EATON_{name} : UINT := {value};"
            for name, value in vars(eaton).items()
            if name.startswith("REG_") and isinstance(value, int)
        ),
        "    (* families, and the ID 17 values that name them (L1086-1096) *)",
        *(f"    EATON_FAMILY_{f.name} : USINT := {int(f)};" for f in eaton.Family),
        *(f"    EATON_ID17_{model} : WORD := {value};" for value, (_f, model) in ids),
        "END_VAR",
        "",
        *_case_function(
            "EATON_FAULT_TEXT",
            f"STRING[{FAULT_TEXT_LENGTH}]",
            "Code",
            "UINT",
            [(f.number, st_string(f.text, FAULT_TEXT_LENGTH)) for f in eaton_faults.FAULTS.values()],
            st_string("unknown fault number"),
            "the cause of a fault number (Tabelle 11)",
        ),
        "",
        *_case_function(
            "EATON_FAULT_DISPLAY",
            "STRING[80]",
            "Code",
            "UINT",
            [(f.number, st_string(f.display)) for f in eaton_faults.FAULTS.values()],
            "''",
            "the drive's display code of a fault number",
        ),
        "",
        *_case_function(
            "EATON_FAMILY",
            "USINT",
            "Id17",
            "WORD",
            [(value, f"EATON_FAMILY_{family.name}") for value, (family, _m) in ids],
            "0",
            "the family of an ID 17 value; 0 for a device the manual does not list",
        ),
        "",
        *_case_function(
            "EATON_MODEL",
            "STRING[80]",
            "Id17",
            "WORD",
            [(value, st_string(model)) for value, (_f, model) in ids],
            "''",
            "the model of an ID 17 value ('DE11' is a DE1 variant)",
        ),
    ]
    return "\n".join(lines) + "\n"
