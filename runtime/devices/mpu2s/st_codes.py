"""The MPU2-S numbers for ST programs, generated from frames.py, scaling.py,
parameters.csv, telegram.py and codewords.py.

    python -m softplc.runtime.devices    # rewrites fblocks/vendor/mpu2s_codes.st (and the others)

The genset synchronisation blocks and user programs read parameter IDs,
bit masks, telegram word numbers and event numbers from
fblocks/vendor/mpu2s_codes.st, so they use the numbers the codec and the
tests use. A test regenerates the file and compares it with the shipped
one.

    VAR_GLOBAL CONSTANT   MPU2S_TELEGRAM_ID_BASE, MPU2S_REQUEST_ID : UINT     320h + n, 33Fh (§1.2)
                          MPU2S_KIND_TELEGRAM / _READ / _WRITE : BYTE         DDh, FFh, EEh (§1.3)
                          MPU2S_ID_<KEY> : UINT        the parameters the synchronisation uses (§3.2)
                          MPU2S_MASK_<KEY> : WORD      the bits of a bit, double-bit or half-byte one
                          MPU2S_ID_KWUGNSEK / _KWUNTSEK : UINT   507, 508 (4.2.10, 4.2.110)
                          MPU2S_SCALE_<FAMILY> : LREAL           raw per unit (§3.1)
                          MPU2S_VOLTAGE_DIVISOR : LREAL          raw = U·factor/400
                          MPU2S_NR_<KEY> : UINT        telegram word numbers, Nr = 3·mux + word (§2.1)
                          MPU2S_NR9_* / NR10_* / NR12_* : WORD   double-bit masks (§2.2)
                          MPU2S_STATE_PRESENT : BYTE             FFh (Nr 30, 33; E10)
                          MPU2S_EVENT_* : USINT                  relay-manager events (§3.8)
"""

from __future__ import annotations

from fractions import Fraction

from ..st_text import vendor_file
from . import codewords, frames, scaling, telegram
from . import parameters as params

ST_FILE = vendor_file("mpu2s_codes.st")

#: the parameter IDs of the genset synchronisation (digest §4.1-4.5), in the
#: order of the sync window, breaker handling, black start, rated values,
#: access and the controllers; every parameter in these words is written
SYNC_IDS = (
    *(26, 27, 28, 309, 31, 32, 21, 34),  # window, close pulse, GCB closing time, sync time monitoring
    *(19, 29, 30, 142),  # controller switches and black start
    *(16, 17, 248),  # breaker logic, GCB monitoring, GCB open relay, automatic unlock
    *(12, 296, 11, 10),  # rated and set-point frequency and voltage
    *(500, 507, 508),  # password, voltage factors
    *(122, 25),  # delayed engine monitoring
    *(44, 45, 46, 37, 38, 39),  # frequency and voltage controllers
)

#: the double-bit words whose masks the blocks need
MASK_WORDS = ((9, telegram.FaultClass), (10, telegram.ControlRegister2), (12, telegram.ControlRegister1))


def _lreal(x: Fraction) -> str:
    text = repr(float(x))
    return text if "e" in text or "." in text else text + ".0"


def _parameter_lines() -> list[str]:
    lines = ["    (* parameter IDs (bytes 2/3 of a request) and bit fields (§3.2, §3.3) *)"]
    for param_id in SYNC_IDS:
        if param_id in (scaling.KWUGNSEK_ID, scaling.KWUNTSEK_ID):
            name = "KWUGNSEK" if param_id == scaling.KWUGNSEK_ID else "KWUNTSEK"
            lines.append(f"    MPU2S_ID_{name} : UINT := {param_id};    (* voltage factor, read (§3.4) *)")
            continue
        found = params.by_id(param_id)
        if not found:
            raise ValueError(f"ID {param_id} is in no parameter")
        for p in found:
            lines.append(f"    MPU2S_ID_{p.key.upper()} : UINT := {p.id};    (* {p.section} {p.name_de} *)")
            if p.kind in params.BIT_KINDS:
                lines.append(f"    MPU2S_MASK_{p.key.upper()} : WORD := 16#{p.mask:04X};")
    return lines


def _scale_lines() -> list[str]:
    lines = ["    (* raw = value * scale, rounded half away from zero (§3.1; ramp 102.4: A13) *)"]
    lines += [f"    MPU2S_SCALE_{s.name.upper()} : LREAL := {_lreal(s.per_unit)};" for s in scaling.FAMILIES.values()]
    lines.append(f"    MPU2S_VOLTAGE_DIVISOR : LREAL := {_lreal(Fraction(scaling.FACTOR_DIVISOR))};")
    return lines


def _telegram_lines() -> list[str]:
    lines = ["    (* telegram word numbers: Nr = 3 * mux + word, 1..69 (§2.1) *)"]
    for w in telegram.WORD_TABLE:
        if w.coding is not telegram.Coding.INTERNAL:
            note = f", {w.exponent} applied (A5)" if w.exponent and w.exponent not in w.unit else ""
            lines.append(f"    MPU2S_NR_{w.key.upper()} : UINT := {w.nr};    (* {w.german}, {w.unit}{note} *)")
    for nr, names in MASK_WORDS:
        lines.append(f"    (* Nr {nr}: {telegram.WORD_TABLE[nr - 1].german}, double bits: 11 on, 00 off (A8) *)")
        lines += [f"    MPU2S_NR{nr}_{m.name} : WORD := 16#{telegram.double_bit_mask(m.value):04X};" for m in names]
    lines.append(f"    MPU2S_STATE_PRESENT : BYTE := 16#{telegram.STATE_PRESENT:02X};    (* Nr 30, 33 *)")
    return lines


def render() -> str:
    lines = [
        "(*",
        "    MPU2S_* -- Woodward MPU2-S numbers for ST programs.",
        "",
        "    GENERATED from runtime/devices/mpu2s/parameters.csv, telegram.py, codewords.py, scaling.py",
        "    and frames.py by runtime/devices/mpu2s/st_codes.py. Do not edit: change the tables, then run",
        "        python -m softplc.runtime.devices",
        "",
        "    Source of every number: the MPU2-S protocol description (manual 004), digest 004,",
        "    cited in those modules.",
        "        IF (Nr10 AND MPU2S_NR10_T5_GCB_CLOSED) = MPU2S_NR10_T5_GCB_CLOSED THEN ... END_IF;",
        "        raw := LREAL_TO_UINT(0.2 * MPU2S_SCALE_FREQUENCY);    // MPU2S_ID_SYNC_DF_MAX",
        "*)",
        "VAR_GLOBAL CONSTANT",
        "    (* CAN identifiers and byte 0 (§1.2, §1.3) *)",
        f"    MPU2S_TELEGRAM_ID_BASE : UINT := 16#{frames.TELEGRAM_ID_BASE:03X};    (* device n sends on 320h + n *)",
        f"    MPU2S_REQUEST_ID : UINT := 16#{frames.REQUEST_ID:03X};",
        f"    MPU2S_KIND_TELEGRAM : BYTE := 16#{frames.KIND_TELEGRAM:02X};",
        f"    MPU2S_KIND_READ : BYTE := 16#{frames.KIND_READ:02X};",
        f"    MPU2S_KIND_WRITE : BYTE := 16#{frames.KIND_WRITE:02X};",
        *_parameter_lines(),
        *_scale_lines(),
        *_telegram_lines(),
        "    (* relay-manager events (§3.8) *)",
        *(f"    MPU2S_EVENT_{e.name} : USINT := {e.value};" for e in codewords.Event),
        "END_VAR",
    ]
    return "\n".join(lines) + "\n"
