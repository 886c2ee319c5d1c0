"""fblocks/vendor/fc280_codes.st: generated from profile.py, parameters.py
and diagnostics.py, up to date, and giving a running ST program the same
numbers and texts as the Python tables."""

from __future__ import annotations

from softplc.runtime.devices.fc280 import diagnostics as diag
from softplc.runtime.devices.fc280 import parameters as params
from softplc.runtime.devices.fc280 import profile, st_codes
from softplc.runtime.program import compile_files


def run(decls: str, body: str):
    text = f"PROGRAM main\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"
    runner = compile_files([], texts={"fc280_use.st": text}).runner("main")
    runner.run(1)
    return runner


def test_shipped_file_is_up_to_date():
    # regenerate with: python -m softplc.runtime.devices
    assert st_codes.ST_FILE.read_text(encoding="utf-8") == st_codes.render()


def test_the_constants_the_blocks_use():
    text = st_codes.render()
    for line in (
        "FC280_CW_DATA_VALID : WORD := 16#0400;",
        "FC280_CW_START : WORD := 16#0040;",
        "FC280_CW_RESET : WORD := 16#0080;",
        "FC280_CW_REVERSE : WORD := 16#8000;",
        "FC280_CW_STANDBY : WORD := 16#043C;",
        "FC280_SW_TRIP : WORD := 16#0008;",
        "FC280_SW_RUNNING : WORD := 16#0800;",
        "FC280_REFERENCE_100 : INT := 16384;",
        "FC280_OBJ_CONTROL_WORD : WORD := 16#2690;",
        "FC280_OBJ_ACTUAL : WORD := 16#2645;",
        "FC280_SIGNATURE_SAVE : DWORD := 16#65766173;",  # §3.1.5, D13
        "FC280_SIGNATURE_LOAD : DWORD := 16#64616F6C;",  # §3.1.5, D14
        "FC280_PROFILE_FC : USINT := 0;",
        "FC280_PROFILE_DSP402 : USINT := 7;",  # A16
        "FC280_TIMEOUT_STOP_AND_ALARM : USINT := 5;",
        "FC280_FIRST_INDEX : UINT := 16#2000;",
        "FC280_EMCY_LIFE_GUARD : WORD := 16#8130;",
        "FC280_EMCY_FLAG_WARNING_WORD : BYTE := 16#08;",
        "16#2323: FC280_PARAMETER_SIZE := 2;    (* 8-03 Steuerwort Timeout-Zeit *)",
        "16#2323: FC280_PARAMETER_CONVERSION := -1;    (* 8-03 Steuerwort Timeout-Zeit *)",
        "16#FF00..16#FFFF: FC280_EMCY_TEXT := 'Manufacturer-specific';",
    ):
        assert line in text, line
    assert "GENERATED" in text and "python -m softplc.runtime.devices\n" in text
    assert st_codes.SIGNATURE_SAVE == 0x65766173 and st_codes.SIGNATURE_LOAD == 0x64616F6C


def test_a_program_reads_the_constants():
    names = {
        **{f"FC280_CW_{m.name}": int(m) for m in profile.ControlWord},
        **{f"FC280_SW_{m.name}": int(m) for m in profile.StatusWord},
        "FC280_CW_STANDBY": int(profile.STANDBY),
        "FC280_REFERENCE_100": profile.REFERENCE_100,
        "FC280_OBJ_STATUS_WORD": profile.OBJ_STATUS_WORD,
        "FC280_OBJ_REFERENCE": profile.OBJ_REFERENCE,
        "FC280_OBJ_STORE": 0x1010,
        "FC280_OBJ_RESTORE": 0x1011,
        "FC280_PROFILE_DSP402": params.PROFILE_DSP402,
        "FC280_TIMEOUT_OFF": params.TIMEOUT_OFF,
        "FC280_EMCY_MANUFACTURER": diag.EMCY_MANUFACTURER,
        **{f"FC280_EMCY_FLAG_{m.name}": int(m) for m in diag.EmcyFlags},
    }
    r = run(
        "".join(f"v{i} : LINT;\n" for i in range(len(names))),
        "".join(f"v{i} := {name};\n" for i, name in enumerate(names)),
    )
    for i, (name, value) in enumerate(names.items()):
        assert r.get(f"v{i}") == value, name


def test_emcy_texts_agree_with_diagnostics():
    codes = [*diag.EMCY_CODES, 0xFF00, 0xFF42, 0xFFFF, 0x1001, 0x8300, 0xFE99]
    r = run(
        "".join(f"t{i} : STRING[80];\n" for i in range(len(codes))),
        "".join(f"t{i} := FC280_EMCY_TEXT(16#{code:04X});\n" for i, code in enumerate(codes)),
    )
    for i, code in enumerate(codes):
        assert r.get(f"t{i}") == diag.emcy_code_text(code), hex(code)


def test_word_texts_are_the_lowest_set_bit_and_empty_for_zero():
    functions = {
        "FC280_ALARM_TEXT": diag.alarm_texts,
        "FC280_ALARM2_TEXT": diag.alarm2_texts,
        "FC280_WARNING_TEXT": diag.warning_texts,
        "FC280_WARNING2_TEXT": diag.warning2_texts,
    }
    words = [0, *(1 << n for n in range(32)), 0x00400010, 0xFFFFFFFF, 0x80000000 | 0x00020000]
    calls = [(f, w) for f in functions for w in words]
    r = run(
        "".join(f"t{i} : STRING[80];\n" for i in range(len(calls))),
        "".join(f"t{i} := {f}(16#{w:08X});\n" for i, (f, w) in enumerate(calls)),
    )
    for i, (f, w) in enumerate(calls):
        texts = functions[f](w)
        assert r.get(f"t{i}") == (texts[0] if texts else ""), (f, hex(w))


def test_per_parameter_functions_agree_with_the_table():
    known = list(params.PARAMETERS.values())
    indices = [p.index for p in known] + [0x2000, 0x2FFF, 0x6040]
    r = run(
        "".join(f"s{i} : USINT; c{i} : SINT; g{i} : BOOL;\n" for i in range(len(indices))),
        "".join(
            f"s{i} := FC280_PARAMETER_SIZE(16#{x:04X}); c{i} := FC280_PARAMETER_CONVERSION(16#{x:04X});"
            f" g{i} := FC280_PARAMETER_SIGNED(16#{x:04X});\n"
            for i, x in enumerate(indices)
        ),
    )
    for i, p in enumerate(known):
        assert r.get(f"s{i}") == p.size, p.number  # VisStr: 0, the block carries numbers only
        assert r.get(f"c{i}") == (p.conversion or 0), p.number
        assert r.get(f"g{i}") == p.signed, p.number
    for i in range(len(known), len(indices)):
        assert (r.get(f"s{i}"), r.get(f"c{i}"), r.get(f"g{i}")) == (0, 0, False)
    assert r.get(f"s{known.index(params.parameter('8-03'))}") == 2  # UInt16, D7


def test_conversion_factors_are_tabelle_6_2():
    indices = list(params.CONVERSION_FACTORS) + [7, -7, 99]
    r = run(
        "".join(f"n{i} : LREAL; d{i} : LREAL;\n" for i in range(len(indices))),
        "".join(
            f"n{i} := FC280_CONVERSION_NUMERATOR({x}); d{i} := FC280_CONVERSION_DENOMINATOR({x});\n"
            for i, x in enumerate(indices)
        ),
    )
    for i, x in enumerate(indices):
        factor = params.CONVERSION_FACTORS.get(x, 1)
        assert r.get(f"n{i}") / r.get(f"d{i}") == float(factor), x
    assert (r.get("n1"), r.get("d1")) == (1.0, 60.0)  # 67: 1/60 (A34)
