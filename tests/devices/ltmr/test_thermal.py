"""The class-N thermal image as functions (runtime/devices/ltmr/thermal.py).
Expected values from the IEC 60947-4-1 class definition (a class-N relay
trips after N s at 7.2 x FLC from cold) and the simulator's Iu = 1.125,
worked out here independently."""

from __future__ import annotations

import math

import pytest

from softplc.runtime.devices.ltmr import thermal

S = 1_000_000_000


@pytest.mark.parametrize("trip_class", [5, 10, 20, 30])
def test_a_class_n_relay_trips_after_n_seconds_at_7_2_flc_from_cold(trip_class):
    # 511 is rounded up; the float logarithm may land a hair above N (then N + 1 is shown)
    assert thermal.time_to_trip_s(0.0, 720.0, trip_class) in (trip_class, trip_class + 1)
    assert thermal.time_to_trip_s(0.0, 720.0 * 1.001, trip_class) == trip_class  # a bit more current: within N s


def test_stepping_10_ms_at_7_2_flc_reaches_the_trip_level_after_the_class_time():
    theta, steps = 0.0, 0
    factor = thermal.decay(10_000_000, 10)
    while theta < 1 - 1e-9:
        theta = thermal.heat(theta, thermal.steady(720.0), factor)
        steps += 1
    assert steps == 1000  # 10 s


def test_no_trip_at_or_below_the_ultimate_trip_current():
    assert thermal.steady(112.5) == pytest.approx(1.0)
    assert thermal.time_to_trip_s(0.5, 112.5, 10) == thermal.NO_TRIP_EXPECTED
    assert thermal.time_to_trip_s(0.5, 105.0, 10) == thermal.NO_TRIP_EXPECTED
    assert thermal.time_to_trip_s(0.5, 0.0, 10) == thermal.NO_TRIP_EXPECTED


def test_time_to_trip_from_a_warm_motor():
    tau = -10 / math.log(1 - (1.125 / 7.2) ** 2)  # class 10
    target = (4.0 / 1.125) ** 2  # 4 x FLC
    expected = -tau * math.log((target - 1) / (target - 0.5))
    assert thermal.time_to_trip_s(0.5, 400.0, 10) == math.ceil(expected)
    assert 0 < expected < 33.3  # faster than from cold (33.3 s)


def test_cooling_to_the_reset_threshold():
    tau = -10 / math.log(1 - (1.125 / 7.2) ** 2)
    assert thermal.minimum_wait_s(1.0, 75, 10) == math.ceil(tau * math.log(1 / 0.75))  # about 117 s
    assert thermal.minimum_wait_s(0.7, 75, 10) == 0  # already below
    assert thermal.minimum_wait_s(1.0, 0, 10) == 0  # no threshold


def test_trip_class_0_counts_as_class_1():
    assert thermal.tau_s(0) == thermal.tau_s(1)
    assert thermal.decay(S, 0) == pytest.approx(math.exp(-1 / thermal.tau_s(1)))
