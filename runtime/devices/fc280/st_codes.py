"""The FC 280 numbers for ST programs, generated from profile.py, parameters.py and diagnostics.py.

    python -m softplc.runtime.devices    # rewrites fblocks/vendor/fc280_codes.st (and the others)

The vendor blocks (fblocks/vendor/fc280.st) and user programs read the
control and status bits, the profile and timeout options, the EMCY codes,
the alarm and warning texts and what FC280_PARAMETER needs per parameter
from fblocks/vendor/fc280_codes.st, so they use the numbers the simulator
and the tests use. A test regenerates the file and compares it with the
shipped one.

    VAR_GLOBAL CONSTANT   FC280_CW_* / FC280_SW_* : WORD     FC profile words (Tabellen 4.7, 4.10)
                          FC280_REFERENCE_100 : INT          4000h = 100 % (§4.4.4)
                          FC280_OBJ_* : WORD                 the FC profile's objects, 1010h, 1011h
                          FC280_SIGNATURE_SAVE / _LOAD : DWORD, FC280_STORE_* : BYTE (§3.1.5)
                          FC280_PROFILE_FC / _DSP402 : USINT   8-10 options
                          FC280_TIMEOUT_* : USINT             8-04 options
                          FC280_FIRST_INDEX : UINT            2000h, parameter 0-00 (§5.1)
                          FC280_EMCY_* : WORD, FC280_EMCY_FLAG_* : BYTE   Tabellen 8.9, 3.4
    FUNCTION FC280_EMCY_TEXT(Code : WORD) : STRING[80]
    FUNCTION FC280_ALARM_TEXT(Bits : DWORD) : STRING[80]   16-90: the lowest set bit's text, '' for 0
             FC280_ALARM2_TEXT (16-91), FC280_WARNING_TEXT (16-92), FC280_WARNING2_TEXT (16-93)
    FUNCTION FC280_PARAMETER_SIZE(Index : UINT) : USINT        bytes; 0 for a parameter not in the table
    FUNCTION FC280_PARAMETER_CONVERSION(Index : UINT) : SINT   Tabelle 6.2 index; 0 for options, counts
    FUNCTION FC280_PARAMETER_SIGNED(Index : UINT) : BOOL
    FUNCTION FC280_CONVERSION_NUMERATOR(Conversion : SINT) : LREAL     the factor of a conversion
    FUNCTION FC280_CONVERSION_DENOMINATOR(Conversion : SINT) : LREAL   index, as a fraction

(The word functions take Bits, not Word: ST names are case-insensitive and
WORD is a type.)
"""

from __future__ import annotations

from ..st_text import TEXT_LENGTH, st_string, vendor_file
from . import diagnostics as diag
from . import parameters as params
from . import profile

ST_FILE = vendor_file("fc280_codes.st")

# Storing and restoring (manual 003 §3.1.5, Tabellen 3.9/3.10, §7.1.9/7.1.10;
# digest 003 D13/D14): the signature is the ASCII word, little endian.
OBJ_STORE = 0x1010  # Parameter speichern
OBJ_RESTORE = 0x1011  # Standardparameter wiederherstellen
SIGNATURE_SAVE = int.from_bytes(b"save", "little")  # 65766173h ("0x65766c173" in §7.1.9, A9)
SIGNATURE_LOAD = int.from_bytes(b"load", "little")  # 64616F6Ch
STORE_ALL = 1  # sub 1: communication and drive parameters (restore: after a power cycle, A11)
STORE_COMMUNICATION = 2  # sub 2: communication parameters
STORE_DRIVE = 4  # sub 4: drive parameters, all set-ups (§7.1.9: the editable ones, A10)

# the parameters FC280_PARAMETER can carry: a number on the bus (not VisStr)
_NUMERIC = [p for p in params.PARAMETERS.values() if p.size > 0]


def _constants() -> list:
    lines = ["    (* FC profile control word, object 2690h = 16-80 (manual 003 §4.4.2, Tabelle 4.7) *)"]
    lines += [f"    FC280_CW_{m.name} : WORD := 16#{int(m):04X};" for m in profile.ControlWord]
    lines += [
        f"    FC280_CW_STANDBY : WORD := 16#{int(profile.STANDBY):04X};"
        "    (* data valid, no stop function, not started *)",
        "    (* FC profile status word, object 2643h = 16-03 (§4.4.3, Tabelle 4.10) *)",
    ]
    lines += [f"    FC280_SW_{m.name} : WORD := 16#{int(m):04X};" for m in profile.StatusWord]
    lines += [
        "    (* reference 16-82 and actual value 16-05: 100 % = 4000h, -100 % = C000h (§4.4.4) *)",
        f"    FC280_REFERENCE_100 : INT := {profile.REFERENCE_100};",
        "    (* objects: the FC profile's (§4.4.1, §4.4.3; 2645h by the index rule, A36), storing (§3.1.5) *)",
        f"    FC280_OBJ_CONTROL_WORD : WORD := 16#{profile.OBJ_CONTROL_WORD:04X};",
        f"    FC280_OBJ_REFERENCE : WORD := 16#{profile.OBJ_REFERENCE:04X};",
        f"    FC280_OBJ_STATUS_WORD : WORD := 16#{profile.OBJ_STATUS_WORD:04X};",
        f"    FC280_OBJ_ACTUAL : WORD := 16#{profile.OBJ_ACTUAL:04X};",
        f"    FC280_OBJ_STORE : WORD := 16#{OBJ_STORE:04X};",
        f"    FC280_OBJ_RESTORE : WORD := 16#{OBJ_RESTORE:04X};",
        f"    FC280_SIGNATURE_SAVE : DWORD := 16#{SIGNATURE_SAVE:08X};    (* 'save' *)",
        f"    FC280_SIGNATURE_LOAD : DWORD := 16#{SIGNATURE_LOAD:08X};    (* 'load' *)",
        f"    FC280_STORE_ALL : BYTE := {STORE_ALL};",
        f"    FC280_STORE_COMMUNICATION : BYTE := {STORE_COMMUNICATION};",
        f"    FC280_STORE_DRIVE : BYTE := {STORE_DRIVE};",
        "    (* 8-10 Steuerwortprofil: [0] FC profile, DSP 402 is [7] in chapter 6 and [5] in §4.3.1 (A16) *)",
        f"    FC280_PROFILE_FC : USINT := {params.PROFILE_FC};",
        f"    FC280_PROFILE_DSP402 : USINT := {params.PROFILE_DSP402};",
        "    (* 8-04 Steuerwort Timeout-Funktion (chapter 6) *)",
    ]
    lines += [
        f"    FC280_{name} : USINT := {value};"
        for name, value in vars(params).items()
        if name.startswith("TIMEOUT_") and isinstance(value, int)
    ]
    lines += [
        "    (* parameter g-nn is object 2000h + g * 100 + nn (§5.1, Tabelle 5.1) *)",
        f"    FC280_FIRST_INDEX : UINT := 16#{params.FIRST_INDEX:04X};",
        "    (* EMCY codes (§8.2.7, Tabelle 8.9); FFxx manufacturer-specific *)",
    ]
    lines += [
        f"    FC280_{name} : WORD := 16#{value:04X};"
        for name, value in vars(diag).items()
        if name.startswith("EMCY_") and isinstance(value, int) and name != "EMCY_LENGTH"
    ]
    lines += [
        "    (* EMCY byte 3 (Tabelle 3.4): which word has an alarm or warning *)",
        *(f"    FC280_EMCY_FLAG_{m.name} : BYTE := 16#{int(m):02X};" for m in diag.EmcyFlags),
        "    (* error register 1001h, EMCY byte 2 (Tabelle 7.3): only bit 0 *)",
        f"    FC280_ERROR_REGISTER_GENERIC : BYTE := 16#{diag.ERROR_REGISTER_GENERIC:02X};",
    ]
    return lines


def _function(name: str, result: str, inputs: list, body: list, what: str) -> list:
    return [
        f"(* {what} *)",
        f"FUNCTION {name} : {result}",
        "VAR_INPUT",
        *(f"    {decl};" for decl in inputs),
        "END_VAR",
        *body,
        "END_FUNCTION",
    ]


def _case(name: str, selector: str, branches: list, default: str) -> list:
    return [
        f"CASE {selector} OF",
        *(f"    {label}: {name} := {value};" for label, value in branches),
        "ELSE",
        f"    {name} := {default};",
        "END_CASE;",
    ]


def _emcy_text() -> list:
    branches = [(f"16#{code:04X}", st_string(text)) for code, text in sorted(diag.EMCY_CODES.items())]
    branches.append(
        (f"16#{diag.EMCY_MANUFACTURER:04X}..16#{diag.EMCY_MANUFACTURER | 0xFF:04X}", st_string(diag.MANUFACTURER_TEXT))
    )
    return _function(
        "FC280_EMCY_TEXT",
        f"STRING[{TEXT_LENGTH}]",
        ["Code : WORD"],
        _case("FC280_EMCY_TEXT", "Code", branches, st_string(diag.UNKNOWN_EMCY_TEXT)),
        "the text of an EMCY code (Tabelle 8.9), CANOPEN_NODE[n].EmcyCode",
    )


def _word_text(name: str, table: dict, what: str) -> list:
    body = [f"IF Bits = 0 THEN {name} := '';"]
    for n in range(32):
        bit = 1 << n
        body.append(f"ELSIF (Bits AND 16#{bit:08X}) <> 0 THEN {name} := {st_string(diag.bit_text(table, bit))};")
    body.append("END_IF")
    return _function(name, f"STRING[{TEXT_LENGTH}]", ["Bits : DWORD"], body, what)


def _per_parameter(name: str, result: str, value, default: str, what: str) -> list:
    """A CASE over the numeric parameters' indices; those whose value is the default are left to ELSE."""
    body = ["CASE Index OF"]
    for p in _NUMERIC:
        if value(p) != default:
            body.append(f"    16#{p.index:04X}: {name} := {value(p)};    (* {p.number} {p.name} *)")
    body += ["ELSE", f"    {name} := {default};", "END_CASE;"]
    return _function(name, result, ["Index : UINT"], body, what)


def _conversion(name: str, part: str, what: str) -> list:
    branches = [(str(index), f"{getattr(factor, part)}.0") for index, factor in params.CONVERSION_FACTORS.items()]
    return _function(name, "LREAL", ["Conversion : SINT"], _case(name, "Conversion", branches, "1.0"), what)


def render() -> str:
    lines = [
        "(*",
        "    FC280_* -- Danfoss VLT Midi Drive FC 280 numbers and texts for ST programs.",
        "",
        "    GENERATED from runtime/devices/fc280/profile.py, parameters.py and diagnostics.py by",
        "    runtime/devices/fc280/st_codes.py. Do not edit: change the Python tables, then run",
        "        python -m softplc.runtime.devices",
        "",
        "    Source of every number: the FC 280 CANopen programming guide (manual 003, MG07E1xx),",
        "    cited in those modules.",
        "        IF (status AND FC280_SW_TRIP) <> 0 THEN text := FC280_ALARM_TEXT(alarmWord); END_IF;",
        "        text := FC280_EMCY_TEXT(CANOPEN_NODE[5].EmcyCode);",
        "*)",
        "VAR_GLOBAL CONSTANT",
        *_constants(),
        "END_VAR",
        "",
        *_emcy_text(),
        "",
        *_word_text("FC280_ALARM_TEXT", diag.ALARM_WORD, "alarm word 16-90 (Tabelle 8.1): the lowest set bit's text"),
        "",
        *_word_text("FC280_ALARM2_TEXT", diag.ALARM_WORD_2, "alarm word 2 16-91 (Tabelle 8.2)"),
        "",
        *_word_text("FC280_WARNING_TEXT", diag.WARNING_WORD, "warning word 16-92 (Tabelle 8.3)"),
        "",
        *_word_text("FC280_WARNING2_TEXT", diag.WARNING_WORD_2, "warning word 2 16-93 (Tabelle 8.4)"),
        "",
        *_per_parameter(
            "FC280_PARAMETER_SIZE",
            "USINT",
            lambda p: str(p.size),
            "0",
            "a parameter's size in bytes by its object index (Tabelle 6.1 types); 0: not in the table",
        ),
        "",
        *_per_parameter(
            "FC280_PARAMETER_CONVERSION",
            "SINT",
            lambda p: str(p.conversion if p.conversion is not None else 0),
            "0",
            "a parameter's conversion index (Tabelle 6.1, 6.2); 0 (factor 1) for the others",
        ),
        "",
        *_per_parameter(
            "FC280_PARAMETER_SIGNED",
            "BOOL",
            lambda p: "TRUE" if p.signed else "FALSE",
            "FALSE",
            "a parameter's type is signed (Int16, Int32)",
        ),
        "",
        *_conversion(
            "FC280_CONVERSION_NUMERATOR",
            "numerator",
            "value = raw * factor (Tabelle 6.2): the factor's numerator (-6 is 1/1000000, A34; 67 is 1/60)",
        ),
        "",
        *_conversion("FC280_CONVERSION_DENOMINATOR", "denominator", "the factor's denominator"),
    ]
    return "\n".join(lines) + "\n"
