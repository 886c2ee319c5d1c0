"""rtlib.py, the runtime library's one import path: generated code, the
loader, the checker and the standard functions reach every primitive as
rtlib.X. What the primitives do is tested beside the modules that hold
them (test_rt_numeric, test_rt_wrap, test_rt_strings, test_rt_text,
test_rt_convert, test_rt_timedate)."""

from __future__ import annotations

from softplc.runtime.st.rtlib import rt_convert, rt_numeric, rt_strings, rt_text, rt_timedate, rt_wrap, rtlib

# Every name rtlib had before it was split by concern: none may go.
NAMES = """
    int_to_f32
    f32 idiv imod rdiv expt round_half_away trunc wrap wrap_time wrapper convert converts_char make_converter
    real_to_string
    parse_int parse_real parse_bool parse_temporal iec_literal to_ns from_ns shl shr rol ror bcd_to_int int_to_bcd
    sqrt ln log exp sin cos tan asin acos atan atan2 LEN LEFT RIGHT MID CONCAT INSERT DELETE REPLACE FIND
    ADD_TIME SUB_TIME MUL_TIME DIV_TIME ADD_LTIME SUB_LTIME MUL_LTIME DIV_LTIME ADD_TOD_TIME ADD_LTOD_LTIME
    ADD_DT_TIME ADD_LDT_LTIME SUB_DATE_DATE SUB_LDATE_LDATE SUB_TOD_TOD SUB_LTOD_LTOD SUB_DT_DT SUB_LDT_LDT
    SUB_TOD_TIME SUB_LTOD_LTIME SUB_DT_TIME SUB_LDT_LTIME CONCAT_DATE_TOD CONCAT_LDATE_LTOD CONCAT_DATE
    CONCAT_TOD CONCAT_LTOD CONCAT_DT CONCAT_LDT DAY_OF_WEEK CONCAT_LDATE CONCAT_DATE_LTOD
    wcut cut_string string_length
""".split()


def test_every_name_is_still_there():
    assert sorted(rtlib.__all__) == sorted(NAMES)
    assert all(callable(getattr(rtlib, n)) for n in NAMES)


def test_each_name_is_the_function_of_its_module():
    homes = {}
    for module in (rt_numeric, rt_wrap, rt_strings, rt_text, rt_convert, rt_timedate):
        for n in NAMES:
            if getattr(module, n, None) is getattr(rtlib, n):
                homes.setdefault(n, module.__name__)
    assert set(homes) == set(NAMES)
    assert homes["f32"].endswith("rt_numeric") and homes["wrap"].endswith("rt_wrap")
    assert homes["LEFT"].endswith("rt_strings") and homes["iec_literal"].endswith("rt_text")
    assert homes["make_converter"].endswith("rt_convert") and homes["ADD_TIME"].endswith("rt_timedate")
