"""The Eaton PowerXL settings (settings.py: serial line, communication loss,
drive variants and ratings, DE1 terminals) against the manual's own
numbers (manual 002, shared/manuals/002_a23ab2a6587941cb.txt; "L<n>" is a
line of that file; digest shared/digests/002_eaton_modbus.md).

Every expected value below is copied from the manual (or, where a test says
so, from the digest's derived examples); none is computed by the code under
test.
"""

from __future__ import annotations

import pytest

from softplc.runtime.devices.eaton import parameters as eaton_parameters
from softplc.runtime.devices.eaton import settings as eaton_settings
from softplc.runtime.devices.eaton.registers import Family
from softplc.runtime.devices.eaton.settings import COMM_TIMEOUT_CODES, CommLossReaction, Da1CommLossAction

DA1, DB1, DC1, DE1 = Family.DA1, Family.DB1, Family.DC1, Family.DE1


# ---------------------------------------------------------------------------
# Serial settings and communication loss
# ---------------------------------------------------------------------------


def test_data_format_codes():
    assert eaton_settings.DATA_FORMATS[0] == ("N", 1)  # N-1 (L379)
    assert eaton_settings.DATA_FORMATS[1] == ("N", 2)  # N-2
    assert eaton_settings.DATA_FORMATS[2] == ("O", 1)  # O-1
    assert eaton_settings.DATA_FORMATS[3] == ("E", 1)  # E-1


@pytest.mark.parametrize(
    "family, code, baud",
    [
        (DA1, 0, 9600),
        (DA1, 4, 115200),  # P5-03 (L378)
        (DB1, 2, 9600),
        (DB1, 6, 115200),  # P-36 (L399)
        (DC1, 2, 9600),
        (DC1, 4, 38400),  # L422
        (DE1, 0, 9600),
        (DE1, 3, 57600),  # P-35, 0 printed "960 Bit/s" (L437, A6)
    ],
)
def test_baud_rate_codes(family, code, baud):
    assert eaton_settings.SERIAL_SETTINGS[family].baud_codes[code] == baud


def test_db1_dc1_baud_codes_start_at_2():
    assert set(eaton_settings.SERIAL_SETTINGS[DB1].baud_codes) == {2, 3, 4, 5, 6}  # L399 (A4)


@pytest.mark.parametrize(
    "family, address, baud, data_format, baud_factory, format_factory",
    [
        (DA1, "P5-01", "P5-03", "P5-04", 4, 0),  # L377-379: WE 4, "n-1"
        (DB1, "P-36", "P-36", "P-56", 2, None),  # L398-401: WE 2, format blank (A5)
        (DC1, "P-36", "P-36", "P-56", 2, 2),  # L421-424
        (DE1, "P-47", "P-35", "P-48", 4, 1),  # L437, L446-447 (A1, A5)
    ],
)
def test_serial_settings(family, address, baud, data_format, baud_factory, format_factory):
    settings = eaton_settings.SERIAL_SETTINGS[family]
    assert (settings.address, settings.baud_rate, settings.data_format) == (address, baud, data_format)
    assert (settings.baud_factory, settings.data_format_factory) == (baud_factory, format_factory)
    eaton_parameters.parameter_register(family, settings.address)  # every one is in its table


def test_address_registers():
    assert eaton_parameters.parameter_register(DA1, eaton_settings.SERIAL_SETTINGS[DA1].address) == 501  # L377
    assert eaton_parameters.parameter_register(DE1, eaton_settings.SERIAL_SETTINGS[DE1].address) == 175  # L446
    assert eaton_parameters.parameter_register(DE1, eaton_settings.DE1_PDP_ADDRESS) == 162  # L1943


def test_da1_comm_loss_parameters():
    assert eaton_parameters.parameter_register(DA1, eaton_settings.DA1_COMM_TIMEOUT) == 505  # L387
    assert eaton_parameters.parameter_register(DA1, eaton_settings.DA1_COMM_LOSS_ACTION) == 506  # L388
    assert (
        eaton_settings.DA1_COMM_TIMEOUT_SCALE.to_value(eaton_settings.DA1_COMM_TIMEOUT_MAX) == 5.0
    )  # "0.0 - 5.0" (L1395)
    assert eaton_settings.DA1_COMM_TIMEOUT_SCALE.to_value(eaton_settings.DA1_COMM_TIMEOUT_FACTORY) == 2.0  # WE "2" (A7)
    assert eaton_settings.DA1_COMM_LOSS_ACTION_FACTORY == 0  # WE 0 (L388)


@pytest.mark.parametrize(
    "value, name",
    [
        (0, "TRIP"),  # "Abschalten"
        (1, "RAMP_STOP_THEN_TRIP"),  # "Fährt mit Rampe zum Stillstand und schaltet dann ab"
        (2, "RAMP_STOP_NO_FAULT"),  # "... keine Fehlermeldung"
        (3, "FIXED_FREQUENCY_8"),  # "Fährt auf Festfrequenz 8 (P2-08)"
    ],
)
def test_da1_comm_loss_actions(value, name):
    assert Da1CommLossAction(value).name == name  # L388
    assert eaton_parameters.parameter_register(DA1, "P2-08") == 208


@pytest.mark.parametrize(
    "code, timeout_ms, reaction",
    [
        (0, None, CommLossReaction.NONE),  # "keine Reaktion"
        (1, 30, CommLossReaction.TRIP),  # "t 30 ms"
        (2, 100, CommLossReaction.TRIP),
        (3, 1000, CommLossReaction.TRIP),
        (4, 3000, CommLossReaction.TRIP),  # "t 3000 ms"
        (5, 30, CommLossReaction.RAMP_TO_ZERO),  # "r 30 ms"
        (6, 100, CommLossReaction.RAMP_TO_ZERO),
        (7, 1000, CommLossReaction.RAMP_TO_ZERO),
        (8, 3000, CommLossReaction.RAMP_TO_ZERO),  # "r 3000 ms"
    ],
)
def test_comm_timeout_codes(code, timeout_ms, reaction):
    assert COMM_TIMEOUT_CODES[code] == (timeout_ms, reaction)  # L400, L423, L445


def test_comm_timeout_parameters_and_factory_codes():
    assert set(COMM_TIMEOUT_CODES) == set(range(9))
    for family in (DB1, DC1, DE1):
        assert eaton_parameters.parameter_register(family, eaton_settings.COMM_TIMEOUT_PARAMETER[family]) == 164
    assert COMM_TIMEOUT_CODES[eaton_settings.COMM_TIMEOUT_FACTORY_CODE[DC1]].timeout_ms == 3000  # "3000 ms" (A8)
    assert eaton_settings.COMM_TIMEOUT_FACTORY_CODE[DE1] == 0  # WE 0 (L445)


def test_second_loss_action_parameters():
    assert eaton_parameters.parameter_register(DA1, eaton_settings.COMM_LOSS_ACTION_PARAMETERS[DA1]) == 516  # L1406
    assert eaton_parameters.parameter_register(DC1, eaton_settings.COMM_LOSS_ACTION_PARAMETERS[DC1]) == 181  # L1848
    assert eaton_parameters.parameter_register(DE1, eaton_settings.COMM_LOSS_ACTION_PARAMETERS[DE1]) == 168  # L1949
    assert DB1 not in eaton_settings.COMM_LOSS_ACTION_PARAMETERS


# ---------------------------------------------------------------------------
# Drive type and rated power (§2.6.5.7)
# ---------------------------------------------------------------------------


def test_drive_variants():
    assert eaton_settings.DRIVE_VARIANTS[0] == ("kW", 3, 3)  # L970
    assert eaton_settings.DRIVE_VARIANTS[4] == ("kW", 1, 3)  # L974
    assert eaton_settings.DRIVE_VARIANTS[7] == ("HP", 1, 1)  # L977
    assert list(eaton_settings.DRIVE_VARIANT_VALUES[DB1]) == [0, 1, 2, 3, 4, 5]  # Table 14 (L1002-1007)


@pytest.mark.parametrize(
    "family, frame, unit, index, power",
    [
        (DA1, "FS2", "kW", 6, 4),  # L983
        (DA1, "FS7", "kW", 5, 160),  # L993
        (DA1, "FS6", "HP", 7, 15),  # L992, printed 15 (A31)
        (DA1, "FS4", "kW", 5, None),  # L987 "–"
        (DB1, "FS1B", "HP", 1, 2),  # L1016
        (DC1, "FS2", "kW", 8, 3),  # L1043
        (DE1, "FS1", "kW", 0, 0.25),  # L1073
        (DE1, "FS2", "HP", 4, 7.5),  # L1076
    ],
)
def test_rated_power(family, frame, unit, index, power):
    kw, hp = eaton_settings.RATED_POWER[family][frame]
    assert (kw if unit == "kW" else hp)[index] == power


def test_da1_rating_id_fields():
    """P0-29 Rating ID: bits 0-3 power index, 4-7 unit, 8-11 voltage index, 12-15 frame size (L1216-1219)."""
    assert eaton_settings.decode_da1_rating_id(0x7215) == (5, 1, 2, 7)


# ---------------------------------------------------------------------------
# DE1 under Modbus control (§2.5.3, Tabellen 9 and 10)
# ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "di1, di2, control_reverse, reverse",
    [
        (True, False, False, False),  # H = FWD, L, Bit1 = 0 -> FWD (rechts)
        (False, True, False, True),  # L, H = REV, Bit1 = 0 -> REV (links)
        (True, False, True, True),  # H = FWD, L, Bit1 = 1 -> REV
        (False, True, True, False),  # L, H = REV, Bit1 = 1 -> FWD
    ],
)
def test_de1_direction_table(di1, di2, control_reverse, reverse):
    assert eaton_settings.de1_reverse(di1, di2, control_reverse) is reverse  # L606-609


@pytest.mark.parametrize("di1, di2", [(False, False), (True, True)])
def test_de1_direction_outside_the_table(di1, di2):
    with pytest.raises(ValueError, match="Tabelle 9"):
        eaton_settings.de1_reverse(di1, di2, False)


@pytest.mark.parametrize(
    "name, ff0, ff1, number, hz, register",
    [
        ("FF1", False, False, "P-20", 20.0, 148),  # L625
        ("FF2", True, False, "P-21", 30.0, 149),
        ("FF3", False, True, "P-22", 40.0, 150),
        ("FF4", True, True, "P-23", 50.0, 151),  # L628
    ],
)
def test_de1_fixed_frequencies(name, ff0, ff1, number, hz, register):
    assert eaton_settings.DE1_FIXED_FREQUENCIES[name] == (ff0, ff1, number, hz)
    assert eaton_parameters.parameter_register(DE1, number) == register  # L1929-1932
