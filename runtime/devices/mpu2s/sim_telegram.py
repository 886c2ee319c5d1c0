"""The send telegram of the simulated MPU2-S (sim.py): its 69 words built
from the genset plant and the device's state (manual 004 ch. 3, digest 004
§2.1; decoding: telegram.py's TelegramAssembler).

    contents = TelegramContents(scenario)
    words = contents.words(plant, alarms={2}, sync_request=True, gcb_release=True, p_set_kw=0.0)
    words[2]                       # f_gen in 1/100 Hz; index = Nr, words[0] unused

Simulator choices where the manual is silent:
- Nr 1 ident 1301 (A3: the decimal reading). Frequencies Nr 2, 32, 39 in
  1/100 Hz. The mains (Nr 8, 34-39, the high byte of Nr 30) is the busbar
  while another source holds it; absent (0) while the bar is dead or fed by
  this genset alone.
- Voltages L-L and L-N (U/√3). The exponents are chosen once from the
  scenario: the voltages' (UGNEXPO, UNTEXPO, USSEXPO, one value) the
  smallest from -1 up that keeps 130 % of the larger of the rated and the
  bus voltage in an unsigned word (400 V: -1, 0.1 V); the power's (PGNEXPO)
  so that twice the rated power fits a signed word (500 kW: 2, 100 W); the
  current's (IGNEXPO) likewise for twice the rated current, unsigned. The
  exponent bytes are signed int8 (A4). A value beyond its word is clamped.
- Active power P from the plant (droop, plant.py), reactive power 0, cos φ
  1.00 (Nr 26 = 100), currents I = |P| / (√3·U_gen). Nr 5 is power set
  point 1 (ID 69) with PGNWWD (Nr 6) = 2800, factor 1 (A7).
- Nr 9: the injected fault classes F0..F3, 11 for present (A8, A40).
  Nr 10: T3 = the PLC's gcb_release wire, T5 = the breaker closed, T4 =
  the breaker open (A27: read as the GCB, as the GCP-30's terminal 4), T54
  = closed onto a bus another source holds, T6 = the PLC's sync_request
  wire; 11 on, 00 off.
- Nr 29 one participant; Nr 30 low byte generator present (plant.gen_live),
  Nr 33 high byte busbar live (FFh/00h, E10). Battery 24.0 V; hours 1234,
  300 to maintenance, 42 starts, 123456 kWh: constants (no running
  counters). Everything else (internal words, faults, analog inputs) is 0.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

from . import frames
from .plant import GensetPlant
from .sim_options import Mpu2sScenario
from .telegram import WORDS, ControlRegister2, FaultClass, double_bit_mask

IDENT = 1301  # Nr 1 (A3)
PGNWWD = 2800  # Nr 6: Nr 5 = raw·2800/2800·10^PGNEXPO W
COS_PHI_ONE = 100  # Nr 26: 1.00
PARTICIPANTS = 1  # Nr 29
BATTERY_DV = 240  # Nr 52, 1/10 V
HOURS, HOURS_TO_MAINTENANCE, STARTS, ENERGY_KWH = 1234, 300, 42, 123456
PRESENT = 0xFF  # E10
ROOT3 = math.sqrt(3.0)


def exponent_for(largest: float, limit: int) -> int:
    """The smallest exponent from -1 up with largest / 10^e <= limit."""
    e = -1
    while largest / 10.0**e > limit:
        e += 1
    return e


def scaled(value: float, exponent: int, signed: bool = False) -> int:
    """value / 10^exponent as a word, clamped to the word's range."""
    lo, hi = (-0x8000, 0x7FFF) if signed else (0, 0xFFFF)
    return frames.to_word(min(max(round(value / 10.0**exponent), lo), hi))


def frequency(f: float) -> int:
    return min(max(round(f * 100.0), 0), 0xFFFF)


def _byte(exponent: int) -> int:
    return exponent & 0xFF  # int8, two's complement (A4)


class TelegramContents:
    """The words of one simulated device (see the module head)."""

    def __init__(self, scenario: Mpu2sScenario) -> None:
        i_rated = scenario.rated_power * 1000.0 / (ROOT3 * scenario.rated_voltage)
        self.u_expo = exponent_for(1.3 * max(scenario.rated_voltage, scenario.bus_voltage), 0xFFFF)
        self.p_expo = exponent_for(2.0 * scenario.rated_power * 1000.0, 0x7FFF)
        self.i_expo = exponent_for(2.0 * i_rated, 0xFFFF)

    def words(
        self,
        p: GensetPlant,
        *,
        alarms: Iterable[int],
        sync_request: bool,
        gcb_release: bool,
        p_set_kw: float,
    ) -> list[int]:
        """The 69 words now, index Nr (words[0] unused)."""
        w = [0] * (WORDS + 1)
        mains = p.bus_live and not p.bus.fed
        power_w = p.p_kw * 1000.0
        current = abs(power_w) / (ROOT3 * p.u_gen) if p.u_gen > 0.0 else 0.0
        u_mains = p.u_bus if mains else 0.0
        u = self.u_expo
        w[1] = IDENT
        w[2] = frequency(p.f_gen)
        w[3] = scaled(power_w, self.p_expo, signed=True)
        w[4] = _byte(self.p_expo) << 8 | _byte(u)
        w[5] = scaled(p_set_kw * 1000.0, self.p_expo, signed=True)
        w[6] = PGNWWD
        w[7] = scaled(p.u_bus, u)
        w[8] = scaled(u_mains, u)
        w[9] = sum(double_bit_mask(FaultClass[f"F{c}"]) for c in set(alarms))
        w[10] = control_register(p, sync_request=sync_request, gcb_release=gcb_release)
        for nr in (15, 16, 20):  # L2-L3, L3-L1, L1-L2
            w[nr] = scaled(p.u_gen, u)
        for nr in (17, 18, 19):  # L1-N, L2-N, L3-N
            w[nr] = scaled(p.u_gen / ROOT3, u)
        for nr in (22, 23, 24):
            w[nr] = scaled(current, self.i_expo)
        w[26] = COS_PHI_ONE
        w[29] = PARTICIPANTS
        w[30] = (PRESENT if mains else 0) << 8 | (PRESENT if p.gen_live else 0)
        w[31] = _byte(self.i_expo) << 8
        w[32] = frequency(p.f_bus)
        w[33] = (PRESENT if p.bus_live else 0) << 8
        for nr in (34, 35):  # L2-L3, L3-L1
            w[nr] = scaled(u_mains, u)
        for nr in (36, 37, 38):
            w[nr] = scaled(u_mains / ROOT3, u)
        w[39] = frequency(p.f_bus) if mains else 0
        w[43] = w[44] = _byte(u)
        w[45], w[46] = divmod(HOURS, 0x10000)
        w[47], w[48] = HOURS_TO_MAINTENANCE, STARTS
        w[50], w[51] = divmod(ENERGY_KWH, 0x10000)
        w[52] = BATTERY_DV
        return w


def control_register(p: GensetPlant, *, sync_request: bool, gcb_release: bool) -> int:
    """Nr 10, the terminals as double bits (see the module head)."""
    bits = {
        ControlRegister2.T3_GCB_RELEASE: gcb_release,
        ControlRegister2.T5_GCB_CLOSED: p.gcb_closed,
        ControlRegister2.T4_BREAKER_OPEN: not p.gcb_closed,
        ControlRegister2.T54_MAINS_PARALLEL: p.locked,
        ControlRegister2.T6_SYNC_ON: sync_request,
    }
    return sum(double_bit_mask(b) for b, on in bits.items() if on)
