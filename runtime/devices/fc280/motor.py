"""The FC 280's output as the model moves it: what the control asks of the
output (Motion) and linear ramps in exact rational arithmetic. Pure.

    out = ramp(Fraction(0), Motion(run=True, target=Fraction(25)), Fraction(S), rate)

Simulator choices (manual 003 gives no ramp shape): ramps are linear; a
ramp time is the time for a change of 3-03, the maximum reference (the
model's rate()); a change of direction decelerates through 0 Hz; a ramp
time of 0 changes at once.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction

# The ramp time parameters (§4.4.2 bits 04, 06, 09): ramp 1 up/down, ramp 2 up/down, quick stop
RAMP_1_UP, RAMP_1_DOWN, RAMP_2_UP, RAMP_2_DOWN, QUICK_STOP = "3-41", "3-42", "3-51", "3-52", "3-81"


@dataclass(frozen=True)
class Motion:
    """What the output does now: released (coast), DC brake, held, ramping to
    0 (quick or with the ramp-down), or following target (Hz, signed)."""

    coast: bool = False
    dc_brake: bool = False
    hold: bool = False
    quick: bool = False
    run: bool = False
    target: Fraction = Fraction(0)
    ramp_2: bool = False
    reference: bool = False  # run follows the reference (not jog, not a timeout speed)


_ZERO = Fraction(0)
COAST = Motion(coast=True)
RAMP_STOP = Motion()


def ramp(out: Fraction, m: Motion, dt: Fraction | int, rate: Callable[[str], Fraction | None]) -> Fraction:
    """The output frequency (Hz) dt ns later. rate(parameter): Hz per ns of a
    ramp time parameter, None for no ramp. Accelerating away from 0 uses the
    ramp-up, towards 0 (or a smaller speed, or the other direction) the
    ramp-down, or the quick stop ramp."""
    if m.coast or m.dc_brake:
        return Fraction(0)
    if m.hold:
        return out
    target = m.target if m.run else _ZERO
    while dt > 0 and out != target:
        if out != 0 and (target == 0 or (target > 0) != (out > 0) or abs(target) < abs(out)):
            limit = _ZERO if target == 0 or (target > 0) != (out > 0) else target
            speed = rate(QUICK_STOP if m.quick else RAMP_2_DOWN if m.ramp_2 else RAMP_1_DOWN)
        else:
            limit, speed = target, rate(RAMP_2_UP if m.ramp_2 else RAMP_1_UP)
        if speed is None:
            out = limit
            continue
        # the same exact arithmetic as comparing the time needed to reach limit with dt, with fewer operations
        gap, step = limit - out, speed * dt
        if abs(gap) <= step:
            out, dt = limit, dt - abs(gap) / speed
        else:
            return out + step if gap > 0 else out - step
    return out


def round_half_away(x: Fraction) -> int:
    """As profile.reference_raw rounds: floor(|x| + 1/2), signed, in integers."""
    n, d = x.numerator, x.denominator
    whole = (2 * abs(n) + d) // (2 * d)
    return whole if n >= 0 else -whole


def int16(x: int) -> int:
    return max(-0x8000, min(0x7FFF, x))
