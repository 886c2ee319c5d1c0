"""The FC 280 in its safe state (README, "Safe outputs"): on a task fault and
at the stop the RPDO carries the safe control word, [outputs] safe's or the
device's own (Device.safe_objects: FC profile 0434h, coast; DSP 402 0000h,
disable voltage, coast), and the simulated drive acts on it. Before the
device's values, a plant without [outputs] safe sent 0000h, which the FC
profile ignores (bit 10, data invalid): the pump ran on until the control
word timeout 8-03 tripped it (or forever with the factory 8-04 = off)."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.fc280.control import DspState
from softplc.runtime.devices.fc280.profile import StatusWord

from ..safe_support import fault_the_task, safe_plant

pytestmark = pytest.mark.slow

FC = "fc280_fc.toml"
DSP = "fc280_dsp402.toml"
# (example, its [outputs] safe, the control word the drive gets, how it stops)
CASES = [
    pytest.param(FC, True, 0x043C, "ramp", id="FC profile, [outputs] safe 043C: ramp stop"),
    pytest.param(FC, False, 0x0434, "coast", id="FC profile, the device's 0434: coast"),
    pytest.param(DSP, True, 0x0006, DspState.READY_TO_SWITCH_ON, id="DSP 402, [outputs] safe 0006: shutdown"),
    pytest.param(DSP, False, 0x0000, DspState.SWITCH_ON_DISABLED, id="DSP 402, the device's 0000: disable voltage"),
]


def _running(tmp_path, example: str, configured_safe: bool):
    plc = safe_plant(tmp_path, example, "Main", configured_safe=configured_safe)
    fc = plc.sim("fc28020")
    plc.run_until(lambda: fc.model.output_hz > 20, timeout="10s", what="the drive running above 20 Hz")
    return plc, fc


def _control_word(fc, example: str) -> int:
    """The control word the drive has taken from its RPDO."""
    return fc.parameter("16-80") if example == FC else fc.model._dsp_word


def _safe(fc, example: str, how) -> None:
    model = fc.model
    if how == "coast" or example == DSP:
        assert model.motion().coast and model.output_hz == 0  # the output off at once
    if example == FC:
        status = StatusWord(model.fc_status_word())
        assert not status & StatusWord.TRIP and bool(status & StatusWord.ENABLED) == (how != "coast")
    else:
        assert model.dsp_state == how


@pytest.mark.parametrize(("example", "configured_safe", "word", "how"), CASES)
def test_a_task_fault_stops_the_drive(tmp_path, example, configured_safe, word, how):
    plc, fc = _running(tmp_path, example, configured_safe)
    try:
        fault_the_task(plc)
        plc.run_for("200ms")
        assert _control_word(fc, example) == word
        _safe(fc, example, how)
        plc.run_for("3s")  # the ramp (3-42: 2 s) is over; the word, sent every 100 ms, keeps 8-03 fed
        assert fc.model.output_hz == 0 and not fc.model.tripped
        assert _control_word(fc, example) == word
    finally:
        plc.stop()


@pytest.mark.parametrize(("example", "configured_safe", "word", "how"), CASES)
def test_the_stop_stops_the_drive(tmp_path, example, configured_safe, word, how):
    plc, fc = _running(tmp_path, example, configured_safe)
    plc.stop()
    assert _control_word(fc, example) == word
    if how != "ramp":
        _safe(fc, example, how)
    else:  # the drive, left alone, ramps down on the 3-42 ramp (and 8-03 trips it: no more words)
        assert fc.model.motion().run is False and fc.model.output_hz > 0
        fc.model.advance(fc.model.now_ns + 3_000_000_000)
        assert fc.model.output_hz == 0
