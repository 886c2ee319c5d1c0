"""effective.py: the Eaton model's integer arithmetic rounds as the
registers' scales do (registers.Scale.to_raw, halves away from zero on the
exact value), so the monitor registers read what the Fraction formulas give."""

from __future__ import annotations

from fractions import Fraction

from hypothesis import given
from hypothesis import strategies as st

from softplc.runtime.devices.eaton import registers as eaton
from softplc.runtime.devices.eaton.effective import round_ratio
from softplc.runtime.devices.eaton.model import EatonDriveModel
from softplc.runtime.devices.eaton.registers import ControlWord as CW
from softplc.runtime.devices.eaton.registers import Family

S = 1_000_000_000


def test_halves_round_away_from_zero():
    assert [round_ratio(n, 2) for n in (-5, -3, -1, 1, 3, 5)] == [-3, -2, -1, 1, 2, 3]
    assert round_ratio(1, -2) == -1 and round_ratio(-1, -2) == 1
    assert [round_ratio(n, 10) for n in (4, 5, 6, -4, -5, -6)] == [0, 1, 1, 0, -1, -1]


@given(st.integers(-(10**12), 10**12), st.integers(-(10**6), 10**6).filter(bool))
def test_rounds_as_the_register_scales_do(num, den):
    assert round_ratio(num, den) == eaton.SPEED.to_raw(Fraction(num, den) * eaton.SPEED.step)


@given(st.integers(1, 499), st.integers(1, 7_000))
def test_monitor_registers_follow_the_fraction_formulas(setpoint, ms):
    """A DA1 ramping from 0 to setpoint (0.1 Hz) on its 5 s ramp, read after
    ms (no telegram meanwhile, the watchdog is off): IDs 7-10 as the manual's
    scales give them from the exact output frequency (rated 50 Hz, 8.2 A,
    4 kW; current 30 % + 70 % x load, torque and power from the load)."""
    drive = EatonDriveModel(Family.DA1, registers={505: 0})  # P5-05 = 0: no comm-loss watchdog
    drive.telegram(0)
    drive.write(eaton.REG_CONTROL_WORD, [CW.RUN, setpoint], 0)
    now = ms * 1_000_000
    drive.advance(now)
    out = min(Fraction(50, 5 * S) * now, Fraction(setpoint, 10))
    load = out / 50
    assert drive.read(eaton.REG_ACTUAL_SPEED, 4, now) == [
        eaton.SPEED.to_raw(out),
        eaton.CURRENT.to_raw(Fraction(82, 10) * (Fraction(3, 10) + Fraction(7, 10) * load)),
        eaton.TORQUE.to_raw(100 * load),
        eaton.OUTPUT_POWER.to_raw(4 * load * load),
    ]
