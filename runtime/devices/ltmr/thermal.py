"""The LTMR's thermal image (class N) as plain functions of floats and ints.

With θ the thermal capacity as a fraction of the trip level and I the current
in multiples of FLC,

    dθ/dt = ((I / Iu)² − θ) / τ            Iu = ULTIMATE_TRIP_RATIO = 1.125

so from cold (θ = 0) at constant I, θ(t) = (I/Iu)² (1 − e^(−t/τ)) and the
trip (θ = 1) comes at t = −τ ln(1 − (Iu/I)²). An IEC 60947-4-1 class-N relay
trips within N s at 7.2 × FLC from cold; taking exactly N s there gives

    τ = −N / ln(1 − (Iu/7.2)²) = N / 0.024717 = 40.46 · N s   (class 10: 404.6 s)

and then, e.g., 4 × FLC trips after 33.3 s (class 10), 1.2 × FLC after
about 14 min, and 1.05 × FLC never (steady state 87 %), inside IEC's
"no trip at 1.05 Ie, trip at 1.2 Ie within 2 h". Cooling uses the same τ.
Within one step the current is constant and the exponential is exact.

    factor = decay(10_000_000, 10)              # e^(−dt/τ) for 10 ms, class 10
    theta = heat(theta, steady(600.0), factor)
"""

from __future__ import annotations

import math

S = 1_000_000_000
ULTIMATE_TRIP_RATIO = 1.125  # Iu: between IEC 60947-4-1's 1.05 (no trip) and 1.2 (trip)
TAU_PER_TRIP_CLASS = -1 / math.log(1 - (ULTIMATE_TRIP_RATIO / 7.2) ** 2)  # τ / N, see above
NO_TRIP_EXPECTED = 0xFFFF  # 511 while the thermal image is not heading for a trip


def tau_s(trip_class: int) -> float:
    """τ in s for the trip class of 606 (s; 0 taken as 1)."""
    return max(1, trip_class) * TAU_PER_TRIP_CLASS


def steady(percent: float) -> float:
    """θ that a constant current (% FLC) tends to."""
    return (percent / 100 / ULTIMATE_TRIP_RATIO) ** 2


def decay(dt_ns: int, trip_class: int) -> float:
    """e^(−dt/τ): how much of θ − steady is left after dt."""
    return math.exp(-dt_ns / S / tau_s(trip_class))


def heat(theta: float, steady_theta: float, factor: float) -> float:
    """θ after a step at constant current, exact for a constant current."""
    return steady_theta + (theta - steady_theta) * factor


def time_to_trip_s(theta: float, percent: float, trip_class: int) -> int:
    """511: seconds until θ reaches the trip level at this current, or NO_TRIP_EXPECTED."""
    target = steady(percent)
    if target <= 1 or theta >= 1:
        return NO_TRIP_EXPECTED
    return min(NO_TRIP_EXPECTED, math.ceil(-tau_s(trip_class) * math.log((target - 1) / (target - theta))))


def minimum_wait_s(theta: float, reset_threshold_percent: int, trip_class: int) -> int:
    """450 for a thermal trip: seconds of cooling (motor off) until θ is below
    the reset threshold (608, % of the trip level)."""
    threshold = reset_threshold_percent / 100
    if threshold <= 0 or theta <= threshold:
        return 0
    return min(0xFFFF, math.ceil(tau_s(trip_class) * math.log(theta / threshold)))
