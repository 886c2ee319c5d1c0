"""publish() skips its work while what it reads and writes is as its last
run left it: step by step on random sequences, a model doing so shows the
same registers as one that publishes in full at every step."""

from __future__ import annotations

import random

import pytest

from softplc.runtime.devices.ltmr import registers as ltmr
from softplc.runtime.devices.ltmr.bits import Control1
from softplc.runtime.devices.ltmr.codes import OperatingMode
from softplc.runtime.devices.ltmr.model import LtmrModel
from softplc.runtime.devices.ltmr.publish import _REGISTERS

MS = 1_000_000
MODES = [int(m) for m in OperatingMode]
COMMANDS = (
    0,
    int(Control1.RUN_FORWARD),
    int(Control1.RUN_FORWARD),
    int(Control1.RUN_REVERSE),
    int(Control1.TRIP_RESET),
    int(Control1.RUN_FORWARD | Control1.LOW_SPEED),
)
# what a sequence writes: commands, settings publish reads, and registers it writes (an "HMI")
WRITTEN = (
    ltmr.REG_CONTROL_1,
    ltmr.REG_CONTROL_2,
    ltmr.REG_CONTROL_SETTING,
    ltmr.REG_LOGIC_INPUTS,
    ltmr.REG_TRIP_CLASS,
    ltmr.REG_THERMAL_RESET_THRESHOLD,
    ltmr.REG_FLC1,
    ltmr.REG_FLC2,
    ltmr.REG_STATUS_1,
    ltmr.REG_STATUS_2,
    ltmr.REG_THERMAL_CAPACITY,
    ltmr.REG_TIME_TO_TRIP,
    ltmr.REG_AVERAGE_CURRENT,
)


class _Full(LtmrModel):
    """The model before the skip: publish() never finds its last run's key."""

    shown = property(lambda self: None, lambda self, value: None)


def _pair(rng: random.Random) -> tuple[LtmrModel, LtmrModel]:
    settings = {} if rng.random() < 0.5 else {ltmr.REG_OPERATING_MODE: rng.choice(MODES)}
    load = rng.choice((0, 50, 100, 250, 600))
    return LtmrModel(settings, load_percent=load), _Full(settings, load_percent=load)


def _act(model: LtmrModel, rng_state: tuple, now: int) -> None:
    rng = random.Random()
    rng.setstate(rng_state)
    kind = rng.randrange(12)
    if kind <= 2:
        model.set_register(ltmr.REG_CONTROL_1, rng.choice(COMMANDS))
    elif kind == 3:
        model.set_load(rng.choice((0, 30, 100, 180, 250, 700)))
    elif kind == 4 and rng.random() < 0.3:
        reg = rng.choice(WRITTEN)
        value = rng.choice((0, 1, 2, 3, 4, 5, 0x10, 0x100, 0xFFFF, rng.randrange(0x10000)))
        if reg == ltmr.REG_TRIP_CLASS:
            value = rng.choice((5, 10, 15, 20, 25, 30))
        model.set_register(reg, value)
    elif kind == 5:
        model.press_reset()
    elif kind == 6 and rng.random() < 0.3:
        model.network_lost() if rng.random() < 0.5 else model.network_restored()
    model.advance_to(now)


@pytest.mark.parametrize("seed", range(40))
def test_the_same_registers_as_a_full_publish_at_every_step(seed):
    rng = random.Random(seed)
    memo, full = _pair(rng)
    now = 0
    for _step in range(600):
        now += rng.choice((1, 5, 10, 10, 10, 10, 100, 1000, 5000)) * MS
        state = rng.getstate()
        rng.random()  # the sequence moves on whatever _act drew
        _act(memo, state, now)
        _act(full, state, now)
        assert memo.registers == full.registers, f"seed {seed}, step {_step}"
        assert (memo.thermal, memo.lo1, memo.lo2, memo.alarms) == (full.thermal, full.lo1, full.lo2, full.alarms)


def test_the_key_covers_every_register_publish_writes():
    model = LtmrModel()
    model.advance_to(0)
    before = dict(model.registers)
    for reg in before:
        model.registers[reg] = before[reg] ^ 1
    written = {reg for reg in before if model.registers[reg] != before[reg]}
    model.shown = None
    model.advance_to(0)
    changed = {reg for reg in before if model.registers[reg] == before[reg]}
    watched = set(_REGISTERS.__reduce__()[1])
    assert changed - watched == set(), "a register publish writes is not in its key"
    assert written
