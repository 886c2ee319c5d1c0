"""The parameter memory of the simulated MPU2-S (sim.py): one word per
parameter ID of parameters.csv, the two voltage factors, the code level 2
password, and the rules a write from the bus meets (manual 004 ch. 4,
digest 004 §1.7, §3).

    store = ParameterStore(password=1234, overrides={"gcb_closing_time": 100})
    store.read(26)                 # 51: +df max 0.20 Hz
    store.write(26, 64)            # WriteResult(reply=51, stored=False, ...): no password yet
    store.write(500, 1234)         # authorised
    store.write(26, 64)            # WriteResult(reply=64, stored=True)
    store.value("sync_df_max")     # 0.25

The manual gives no defaults (digest §3.0, A31) and says nothing of how a
device answers a write it does not take (A10, A11). Simulator choices:

- The device is the 400 V variant (4.2.4 b.): ranges are checked with
  variant=400. KWUGNSEK (ID 507) and KWUNTSEK (ID 508) are 400, so a
  voltage parameter's raw value is its value in V (§3.4); both IDs are
  read-only here (A14: not said), a write to them is refused.
- Initial values (INITIAL below, every other parameter 0 or the end of its
  range nearest 0): controllers f and U on, the others off; breaker logic
  Parallel; +df max 0.20 Hz, -df min 0.10 Hz, dU max and min 5 %, close
  pulse 0.20 s, GCB closing time the scenario's (80 ms); black start off,
  its df max 0.50 Hz and dU max 5 %; close signal Impuls, open relay
  Arbeitsstrom (energise to open). Every initial word passes the write
  check below (a test proves it).
- ID 500 (password, 4.2.1) is no stored value: it reads 0, and a write
  replies with the word written. Without a configured password every
  write is taken. With one, writes are refused until ID 500 got it; the
  authorisation holds until a power cycle or an unplugged cable (the
  device's side of a communication loss, A11).
- A write is refused (not stored, the reply carries the word the device
  still holds) without the password, to a read-only ID, or when any
  parameter in the word fails its documented rule: the field's raw range
  (a bit, double-bit or half-byte field on its own; undocumented bits are
  free), switches 00/11 only, cos φ |raw| >= 70, digit words 0..9 or 0..3
  per digit. A field is checked by decoding it and encoding the value back
  (parameters.decode / encode, which hold the manual's rules). Fault-text
  words take two printable ASCII characters, relay-manager words a valid
  event word (codewords.RelayEvent).
- An ID the table does not know is neither read nor written: the device
  stays silent (A12, "Treat other IDs as unknown"), the master times out.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from . import codewords
from . import parameters as P
from .scaling import KWUGNSEK_ID, KWUNTSEK_ID

VARIANT = 400  # the 400 V device (4.2.4 b.)
FACTOR = 400  # KWUGNSEK and KWUNTSEK: U·400/400, raw = V (§3.4)
PASSWORD_ID = 500  # 4.2.1
READ_ONLY = {KWUGNSEK_ID: FACTOR, KWUNTSEK_ID: FACTOR}

#: the initial values by parameter key, in the parameter's unit
INITIAL: dict[str, object] = {
    "gen_setpoint_frequency": 50.0,
    "gen_rated_frequency": 50.0,
    "gen_vt_secondary": 400,
    "gen_vt_primary": 400,
    "bus_vt_secondary": 400,
    "bus_vt_primary": 400,
    "mains_vt_secondary": 400,
    "mains_vt_primary": 400,
    "gen_setpoint_voltage": 400,
    "gen_rated_voltage": 400,
    "gen_ct_primary": 1000,
    "power_measurement_three_phase": True,
    "gen_rated_power": 500,
    "gen_rated_current": 722,
    "f_controller_on": True,
    "f_controller_start_frequency": 45.0,
    "f_controller_ramp": 5.0,
    "f_controller_deadband": 0.05,
    "f_controller_pulse": 40,
    "f_controller_kp": 1.0,
    "u_controller_on": True,
    "u_controller_deadband": 0.5,
    "u_controller_pulse": 40,
    "u_controller_kp": 1.0,
    "pf_controller_setpoint": 1.0,
    "pf_controller_deadband": 2.0,
    "pf_controller_kp": 1.0,
    "p_controller_ramp": 10,
    "p_controller_max": 100.0,
    "p_controller_deadband": 1.0,
    "p_controller_kp": 1.0,
    "p_controller_sensitivity_reduction": 2.0,
    "warmup_setpoint": 50.0,
    "breaker_logic": 1,  # Parallel
    "gcb_close_constant": False,  # Impuls
    "gcb_open_relay_energise": True,  # Arbeitsstrom
    "sync_df_max": 0.20,
    "sync_df_min": 0.10,
    "sync_du_max": 5.0,
    "sync_du_min": 5.0,
    "sync_pulse": 0.20,
    "gcb_closing_time": 80,
    "sync_time_monitoring_delay": 60,
    "black_start": False,
    "black_start_df_max": 0.50,
    "black_start_du_max": 5.0,
    "black_start_max_time": 30,
    "gcb_monitoring": True,
    "engine_monitoring_delay": 5,
    "monitoring_on_frequency": 40.0,
    "battery_undervoltage_pickup": 20.0,
}


def _field(p: P.Parameter, word: int) -> int:
    return (word & p.mask) >> p.shift if p.bits else word


def field_problem(p: P.Parameter, word: int) -> str | None:
    """Why p's field in word breaks the manual's rules, or None."""
    if p.family == "text":
        if all(0x20 <= b <= 0x7E for b in word.to_bytes(2, "big")):
            return None
        return f"{p}: {word:04X}h is not two printable ASCII characters"
    if p.family == "relay":
        try:
            codewords.RelayEvent.from_word(word)
        except ValueError as exc:
            return f"{p}: {exc}"
        return None
    raw = _field(p, word)
    factor = FACTOR if p.factor_id is not None else None
    try:
        back = P.encode(p, P.decode(p, raw, factor=factor), factor=factor, variant=VARIANT)
    except ValueError as exc:
        return str(exc)
    return None if back == raw else f"{p}: raw {raw} does not survive its conversion ({back})"


def word_problem(param_id: int, word: int) -> str | None:
    """Why word may not be stored at param_id, or None."""
    if param_id in READ_ONLY:
        return f"ID {param_id} is read-only"
    for p in P.by_id(param_id):
        problem = field_problem(p, word)
        if problem is not None:
            return problem
    return None


def _initial_words(overrides: Mapping[str, object]) -> dict[int, int]:
    words = dict.fromkeys(P.all_ids(), 0)
    values = {**INITIAL, **overrides}
    for p in P.PARAMETERS:
        if p.family == "text":
            number = int(p.key.rpartition("_")[2])
            words.update(zip(p.ids, codewords.text_words(f"TERMINAL {number}")))
            continue
        if p.family == "relay":
            words.update(dict.fromkeys(p.ids, codewords.RelayEvent(codewords.Event.GCB_CLOSED, end=True).word))
            continue
        factor = FACTOR if p.factor_id is not None else None
        if p.key in values:
            raw = P.encode(p, values[p.key], factor=factor, variant=VARIANT)
        else:
            lo, hi = P.raw_range(p, factor=factor, variant=VARIANT)
            raw = min(max(0, lo), hi) & 0xFFFF
        if p.bits:
            words[p.id] = (words[p.id] & ~p.mask & 0xFFFF) | raw << p.shift
        else:
            words[p.id] = raw
    words.pop(PASSWORD_ID, None)
    words.update(READ_ONLY)
    return words


@dataclass(frozen=True)
class WriteResult:
    reply: int | None  # the word of the EE reply; None: no reply (an unknown ID)
    stored: bool
    reason: str = ""  # why it was not stored


class ParameterStore:
    """The device's parameter words (see the module head)."""

    def __init__(self, *, password: int | None = None, overrides: Mapping[str, object] | None = None) -> None:
        unknown = set(overrides or {}) - {p.key for p in P.PARAMETERS}
        if unknown:
            raise ValueError(f"no MPU2-S parameter {', '.join(sorted(unknown))}")
        self.password = password
        self.words = _initial_words(overrides or {})
        self.authorised = password is None
        self.version = 0  # counts the changes of words (for caches of values)

    def known(self, param_id: int) -> bool:
        return param_id in self.words or param_id == PASSWORD_ID

    def read(self, param_id: int) -> int | None:
        """The word an FF read gets; None for an unknown ID (no reply)."""
        if param_id == PASSWORD_ID:
            return 0
        return self.words.get(param_id)

    def write(self, param_id: int, word: int) -> WriteResult:
        """An EE write from the bus, with the password and range rules."""
        if param_id == PASSWORD_ID:
            if self.password is None or word == self.password:
                self.authorised = True
                return WriteResult(word, True)
            return WriteResult(word, False, "wrong password")
        old = self.words.get(param_id)
        if old is None:
            return WriteResult(None, False, f"no parameter ID {param_id}")
        if not self.authorised:
            return WriteResult(old, False, "the password (ID 500) was not given")
        problem = word_problem(param_id, word)
        if problem is not None:
            return WriteResult(old, False, problem)
        self.words[param_id] = word
        self.version += 1
        return WriteResult(word, True)

    def set_word(self, param_id: int, word: int) -> None:
        """A local write (the device's front panel): no password, the same
        rules; ValueError for an unknown ID or a word they refuse."""
        if param_id not in self.words:
            raise ValueError(f"no parameter ID {param_id}")
        problem = word_problem(param_id, word)
        if problem is not None:
            raise ValueError(problem)
        self.words[param_id] = word
        self.version += 1

    def lose_authorisation(self) -> None:
        self.authorised = self.password is None

    # ------------------------------------------------------------ values for the device itself

    def value(self, key: str) -> P.Value:
        """A parameter's present value in its unit (a bit field extracted)."""
        p = P.parameter(key)
        word = self.words[p.id]
        if p.bits:
            return P.extract(p, word)
        return P.decode(p, word, factor=FACTOR if p.factor_id is not None else None)

    def number(self, key: str) -> float:
        value = self.value(key)
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise TypeError(f"{key} is no number: {value!r}")
        return float(value)

    def flag(self, key: str) -> bool:
        return self.value(key) is True
