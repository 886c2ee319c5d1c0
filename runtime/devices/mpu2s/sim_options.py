"""The keys of a simulated MPU2-S ([[sim]] type = "mpu2s") besides its bus
and node_id (its device number): the scenario of the genset behind it, and
the wires between that plant and the PLC.

    [[sim]]
    type = "mpu2s"
    node_id = 1                       # the device number (Gerätenummer)
    busbar = "live"                   # or "dead" (a black start)
    bus_frequency = 50.0              # Hz; bus_voltage = 400.0 V
    slip = 0.3                        # the genset's start: f_gen - f_bus, Hz
    voltage_offset = 2.0              # U_gen above rated, %
    closing_time = "80ms"             # the GCB's; refuse_close = true: it never closes
    password = 1234                   # code level 2 (ID 500): writes need it first (optional)
    parameters = { sync_df_max = 0.25, gcb_closing_time = 100 }   # chapter 4's, in their units (optional)
    wiring = { raise_f = "%QX20.0", lower_f = "%QX20.1", gcb_close = "%QX20.4", phase = "%ID20", ... }

`parameters` presets the device's parameter memory (sim_store.py) by the
parameters' keys of parameters.csv, each value in the parameter's unit
(Hz, %, s, V ..., true/false for a switch) and checked against the manual's
range as a write from the bus is: what a scenario starts from, over the
values the plant's keys above imply (gcb_closing_time from closing_time ...).

The wiring is the plant's hard-wired I/O, seen from the PLC: the genset's
raise/lower inputs and the breaker's coils are PLC outputs (%QX); the
breaker's feedback is a PLC input (%IX); a fast synchronoscope (a sync-check
relay's phase angle and frequencies, which the MPU2-S telegram does not
carry) gives %ID REALs. Each signal is optional.

Without a password the simulated device takes every valid write; with one,
writes are refused until ID 500 got it (sim_store.py).
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass, field
from typing import Annotated, Any

from pydantic import Field, PlainValidator

from ...config.errors import key_text
from ...config.relations import Relations
from ...config.section import SimOptions
from ...config.values import choice, duration_in, fail, int_range, real_range
from . import parameters as P
from .sim_store import FACTOR as P_FACTOR
from .sim_store import VARIANT as P_VARIANT

#: PLC outputs the plant reads (contacts): signal -> what it is
OUTPUT_SIGNALS = {
    "raise_f": "governor RAISE (speed up)",
    "lower_f": "governor LOWER",
    "raise_u": "AVR RAISE (voltage up)",
    "lower_u": "AVR LOWER",
    "gcb_close": "GCB close coil",
    "gcb_open": "GCB open coil",
    "sync_request": "MPU2-S terminal 6, Sync. ein",
    "gcb_release": "MPU2-S terminal 3, Freigabe GLS",
}
#: PLC inputs the plant writes: signal -> (what it is, BOOL or REAL)
INPUT_SIGNALS = {
    "gcb_closed": ("the GCB's feedback contact", "BOOL"),
    "bus_live": ("busbar voltage present", "BOOL"),
    "phase": ("phase angle generator - busbar, deg", "REAL"),
    "f_gen": ("generator frequency, Hz", "REAL"),
    "f_bus": ("busbar frequency, Hz", "REAL"),
    "u_gen": ("generator voltage L1-L2, V", "REAL"),
    "u_bus": ("busbar voltage L1-L2, V", "REAL"),
}


def _parameters(value) -> dict:
    if isinstance(value, dict):
        return value
    raise fail("a table of parameter = value, such as { sync_df_max = 0.25 }", value)


def preset_refusal(key: str, value: object) -> str | None:
    """Why [[sim]] parameters cannot preset key to value (None: it can): no
    such parameter, a text or relay word, or a value the manual's range refuses."""
    by_key = {p.key: p for p in P.PARAMETERS}
    p = by_key.get(key)
    if p is None:
        close = difflib.get_close_matches(key, list(by_key), n=1, cutoff=0.6)
        return "no MPU2-S parameter of that key" + (f" (did you mean '{close[0]}'?)" if close else " (parameters.csv)")
    if p.kind in P.WORDS_OF_KIND:
        return f"{p}: a text or relay-manager word, which [[sim]] cannot preset"
    try:
        P.encode(p, value, factor=P_FACTOR if p.factor_id is not None else None, variant=P_VARIANT)
    except ValueError as exc:
        return str(exc)
    return None


def _wiring(value) -> dict:
    if isinstance(value, dict) and all(isinstance(v, str) for v in value.values()):
        return value
    raise fail('a table of signal = "address", such as { gcb_close = "%QX20.4" }', value)


@dataclass
class Mpu2sScenario:
    bus_live: bool = True
    bus_frequency: float = 50.0
    bus_voltage: float = 400.0
    slip: float = 0.3
    voltage_offset: float = 0.0  # % of rated
    rated_frequency: float = 50.0
    rated_voltage: float = 400.0
    rated_power: float = 500.0  # kW
    closing_time_ms: int = 80
    refuse_close: bool = False
    trip_limit: float = 20.0  # deg
    wiring: dict[str, str] = field(default_factory=dict)
    password: int | None = None  # code level 2 (ID 500), 0..9999; None: writes need none
    parameters: dict[str, object] = field(default_factory=dict)  # parameter key -> value in its unit


class Mpu2sSimOptions(SimOptions):
    busbar: Annotated[str, choice(("live", "dead"))] = Field("live", description="'live' or 'dead'")
    bus_frequency: Annotated[float, real_range(40.0, 70.0, "a frequency in Hz")] = Field(50.0, description="Hz")
    bus_voltage: Annotated[float, real_range(0.0, 65000.0, "a voltage in V")] = Field(400.0, description="V")
    slip: Annotated[float, real_range(-5.0, 5.0, "a slip in Hz")] = Field(0.3, description="f_gen - f_bus at start, Hz")
    voltage_offset: Annotated[float, real_range(-20.0, 20.0, "a percentage")] = Field(
        0.0, description="U_gen above rated at start, %"
    )
    rated_frequency: Annotated[float, real_range(40.0, 70.0, "a frequency in Hz")] = Field(50.0, description="Hz")
    rated_voltage: Annotated[float, real_range(1.0, 65000.0, "a voltage in V")] = Field(400.0, description="V")
    rated_power: Annotated[float, real_range(1.0, 9999.0, "a power in kW")] = Field(500.0, description="kW")
    closing_time: Annotated[int, PlainValidator(duration_in("ms"))] = Field(80, description="a duration such as 80ms")
    refuse_close: bool = Field(False, description="true or false")
    trip_limit: Annotated[float, real_range(1.0, 180.0, "an angle in degrees")] = Field(
        20.0, description="the largest |phase| a close survives, deg"
    )
    wiring: Annotated[dict, PlainValidator(_wiring)] = Field(default_factory=dict, description="signal = address")
    password: Annotated[int, int_range(0, 9999)] | None = Field(
        None, description="the code level 2 password (ID 500), 0..9999"
    )
    parameters: Annotated[dict, PlainValidator(_parameters)] = Field(
        default_factory=dict, description="parameter key = value in its unit"
    )

    @classmethod
    def check(cls, here: tuple, sim: dict, ctx: Relations) -> None:
        presets = sim.get("parameters")
        if isinstance(presets, dict):
            for key, value in presets.items():
                why = preset_refusal(key, value)
                if why:
                    ctx.error(here + ("parameters", key), why)
        wiring = sim.get("wiring")
        if not isinstance(wiring, dict):
            return
        for signal, text in wiring.items():
            loc = here + ("wiring", signal)
            if signal not in OUTPUT_SIGNALS and signal not in INPUT_SIGNALS:
                known = ", ".join([*OUTPUT_SIGNALS, *INPUT_SIGNALS])
                ctx.error(loc, f"not a signal of the simulated genset (it has {known})")
                continue
            addr = ctx.address(loc, text, '"%QX20.0"')
            if addr is None:
                continue
            if signal in OUTPUT_SIGNALS:
                if addr.area != "Q" or not _is_bit(addr):
                    ctx.error(
                        loc, f"{OUTPUT_SIGNALS[signal]}: expected a PLC output bit such as %QX20.0 (got {text!r})"
                    )
                continue
            what, kind = INPUT_SIGNALS[signal]
            wanted = _is_bit(addr) if kind == "BOOL" else addr.size == "D" and addr.bit is None
            if addr.area != "I" or not wanted:
                example = "%IX20.0" if kind == "BOOL" else "%ID20"
                ctx.error(loc, f"{what}: expected a PLC input {kind} such as {example} (got {text!r})")
                continue
            bits = ctx.image_bits(loc, addr)
            if bits is not None:
                other = ctx.claim("I", bits[0], bits[1], loc, text)
                if other is not None:
                    ctx.error(loc, f"{text} is also written by {key_text(other[0])} ({other[1]})")

    def build(self) -> Mpu2sScenario:
        return Mpu2sScenario(
            bus_live=self.busbar == "live",
            bus_frequency=self.bus_frequency,
            bus_voltage=self.bus_voltage,
            slip=self.slip,
            voltage_offset=self.voltage_offset,
            rated_frequency=self.rated_frequency,
            rated_voltage=self.rated_voltage,
            rated_power=self.rated_power,
            closing_time_ms=self.closing_time,
            refuse_close=self.refuse_close,
            trip_limit=self.trip_limit,
            wiring=dict(self.wiring),
            password=self.password,
            parameters=dict(self.parameters),
        )


def _is_bit(addr: Any) -> bool:
    return addr.bit is not None or addr.size in ("", "X")
