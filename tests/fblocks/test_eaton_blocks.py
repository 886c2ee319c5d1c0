"""fblocks/vendor/eaton.st and eaton_codes.st: the generated numbers are up
to date and the ST helpers agree with runtime/devices/eaton/registers.py."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.eaton import faults as eaton_faults
from softplc.runtime.devices.eaton import parameters as eaton_parameters
from softplc.runtime.devices.eaton import registers as eaton
from softplc.runtime.devices.eaton import st_codes as eaton_st_codes

from .st_bench import Bench


def test_shipped_codes_are_up_to_date():
    # regenerate with: python -m softplc.runtime.devices
    assert eaton_st_codes.ST_FILE.read_text(encoding="utf-8") == eaton_st_codes.render()


@pytest.fixture(scope="module")
def bench():
    return Bench(
        "id17 : WORD; name : STRING[8]; register : UINT; family : USINT; model : STRING[4];\n"
        "code : UINT; text : STRING[120]; display : STRING[8];",
        "register := EATON_PARAMETER_REGISTER(id17, name);\n"
        "family := EATON_FAMILY(id17); model := EATON_MODEL(id17);\n"
        "text := EATON_FAULT_TEXT(code); display := EATON_FAULT_DISPLAY(code);",
    )


def _every_parameter():
    for id17, (family, model) in eaton.DEVICE_IDENTIFICATION.items():
        de11 = model == "DE11"
        rows = eaton_parameters.PARAMETERS[family] + (eaton_parameters.DE11_PARAMETERS if de11 else ())
        for number in sorted({row.number for row in rows}):
            yield id17, number, eaton_parameters.parameter_register(family, number, de11=de11)


def test_parameter_names_give_the_manuals_registers(bench):
    """Every parameter of every table (digest §3.5: DA1 group x 100 + index,
    the others 128 + n, DE11 P-57/P-58 as printed, A16)."""
    checked = 0
    for id17, number, register in _every_parameter():
        bench.step(id17=id17, name=number)
        assert bench["register"] == register, (id17, number)
        checked += 1
    assert checked > 300


@pytest.mark.parametrize(
    "id17, name", [(5632, "P-03"), (10, "P1-03"), (5632, "X1-03"), (5632, "P1"), (10, "P-123"), (0, "P-03")]
)
def test_names_of_the_wrong_form_give_0(bench, id17, name):
    bench.step(id17=id17, name=name)
    assert bench["register"] == 0


@pytest.mark.parametrize("id17", sorted(eaton.DEVICE_IDENTIFICATION))
def test_family_and_model_from_id17(bench, id17):
    bench.step(id17=id17)
    family, model = eaton.DEVICE_IDENTIFICATION[id17]
    assert (bench["family"], bench["model"]) == (int(family), model)


def test_unknown_id17_is_family_0(bench):
    bench.step(id17=1234)
    assert (bench["family"], bench["model"]) == (0, "")


@pytest.mark.parametrize("code", [4, 50, 25, 74])
def test_fault_texts(bench, code):
    bench.step(code=code)
    assert bench["text"] == eaton_faults.fault_text(code)
    assert bench["display"] == eaton_faults.fault_display(code)


def test_unknown_fault_number(bench):
    bench.step(code=99)
    assert (bench["text"], bench["display"]) == ("unknown fault number", "")
