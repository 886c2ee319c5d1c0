"""The FC 280 parameters the model works with, read once per change of the
parameter memory and kept in plain attributes, in their units (exact
rationals: the conversion index of Tabelle 6.2 applied). The model asks
this view on every tick instead of the store; the store's version tells
when it is stale.

    view = Settings(store)                      # after each store.version change
    view.f_max, view.rate["3-41"], view.hz_per_rpm   # 65 Hz, Hz per ns, 1-23 / 1-25
"""

from __future__ import annotations

from fractions import Fraction

from .control import Selections
from .motor import QUICK_STOP, RAMP_1_DOWN, RAMP_1_UP, RAMP_2_DOWN, RAMP_2_UP
from .parameters import PROFILE_DSP402, parameter
from .profile import REFERENCE_100
from .store import ParameterStore

S = 1_000_000_000
CONTROL_SOURCE_OPTION_A = 3  # 8-02 [3] Option A: the control word comes from the CANopen port (§3.3.1)
MIN_MAX = 0  # 3-00 [0] Min-Max; [1] -Max-+Max
RAMP_TIMES = (RAMP_1_UP, RAMP_1_DOWN, RAMP_2_UP, RAMP_2_DOWN, QUICK_STOP)


class Settings:
    """A snapshot of the parameters the model uses (see the module docstring)."""

    def __init__(self, store: ParameterStore) -> None:
        self.version = store.version

        def raw(number: str, sub: int = 0) -> int:
            value = store.get(number, sub)
            assert isinstance(value, int)
            return value

        def value(number: str, sub: int = 0) -> Fraction:
            return raw(number, sub) * parameter(number).factor

        self.dsp = raw("8-10") == PROFILE_DSP402
        self.bus_control = raw("8-02") == CONTROL_SOURCE_OPTION_A
        self.selections = Selections(raw("8-01"), *(raw(f"8-5{n}") for n in range(7)))
        self.timeout_ns = int(value("8-03") * S)  # 8-03
        self.timeout_function = raw("8-04")
        self.dc_brake_ns = int(value("2-02") * S)
        self.f_max = value("4-14")
        self.hz_per_rpm = value("1-23") / value("1-25")  # RPM <-> Hz by 1-25 <-> 1-23
        self.rpm_per_hz = value("1-25") / value("1-23")
        self.jog_hz = value("3-19") * self.hz_per_rpm  # FC profile jog, and the 8-04 [3] speed
        self.dsp_jog_hz = value("8-90") * self.hz_per_rpm
        self.high = value("3-03")
        self.low = value("3-02")
        self.min_max = raw("3-00") == MIN_MAX
        # 16-05: the output frequency as a reference word, (out - actual_zero) * actual_scale
        # (4000h = 100 % of 3-02..3-03 or of 3-03, §4.4.4); None: 0 (an empty range)
        self.actual_zero = self.low if self.min_max else Fraction(0)
        width = self.high - self.actual_zero
        self.actual_scale = Fraction(REFERENCE_100) / width if width else None
        self.presets = [value("3-10", i) for i in range(parameter("3-10").elements)]
        span = abs(self.high) or value("1-23")
        # Hz per ns of each ramp time: the time for a change of 3-03 (simulator choice); None: at once
        self.rate: dict[str, Fraction | None] = {}
        for number in RAMP_TIMES:
            seconds = value(number)
            self.rate[number] = None if seconds <= 0 else span / (seconds * S)
        self.diagnosis = raw("8-07")  # 8-07: which alarms and warnings send an EMCY
