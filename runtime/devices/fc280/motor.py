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
    ramp-down, or the quick stop ramp.

    Exact rational arithmetic on numerators and denominators (each Fraction
    operator costs about a microsecond, and this runs at every step): a
    Fraction is made only for what is returned."""
    if m.coast or m.dc_brake:
        return Fraction(0)
    if m.hold:
        return out
    target = m.target if m.run else _ZERO
    on, od = out.numerator, out.denominator
    tn, td = target.numerator, target.denominator
    dn, dd = dt.numerator, dt.denominator
    moved = False
    while dn > 0 and (on != tn or od != td):
        away_or_other_way = tn == 0 or (tn > 0) != (on > 0)  # towards 0 (through it to the other direction)
        if on != 0 and (away_or_other_way or abs(tn) * od < abs(on) * td):
            ln, ld = (0, 1) if away_or_other_way else (tn, td)
            speed = rate(QUICK_STOP if m.quick else RAMP_2_DOWN if m.ramp_2 else RAMP_1_DOWN)
        else:
            ln, ld = tn, td
            speed = rate(RAMP_2_UP if m.ramp_2 else RAMP_1_UP)
        moved = True
        if speed is None:
            on, od = ln, ld
            continue
        sn, sd = speed.numerator, speed.denominator
        gn, gd = ln * od - on * ld, ld * od  # gap = limit - out
        if abs(gn) * sd * dd <= sn * dn * gd:  # |gap| <= speed x dt: there within dt
            on, od = ln, ld
            rest = Fraction(dn * gd * sn - abs(gn) * sd * dd, dd * gd * sn)  # dt - |gap| / speed
            dn, dd = rest.numerator, rest.denominator
        else:  # out +/- speed x dt
            step = sn * dn * od
            return Fraction(on * sd * dd + (step if gn > 0 else -step), od * sd * dd)
    return Fraction(on, od) if moved else out


def round_half_away(x: Fraction) -> int:
    """As profile.reference_raw rounds: floor(|x| + 1/2), signed, in integers."""
    n, d = x.numerator, x.denominator
    whole = (2 * abs(n) + d) // (2 * d)
    return whole if n >= 0 else -whole


def int16(x: int) -> int:
    return max(-0x8000, min(0x7FFF, x))
