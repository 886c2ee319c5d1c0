"""The simulated MPU2-S closing its generator breaker itself ("mode 1" of
digest 004 §4.4: the PLC supervises): synchronising onto a live busbar,
or a black start onto a dead one (§4.3 A and B), with the device's own
relays RAISE/LOWER f and U and GCB CLOSE. Pure: sim.py calls step() every
STEP_NS of virtual time with the plant and the parameter store, and ORs
the relays with the PLC's contacts.

The manual describes no algorithm (§4.1); this module's choices:

- It runs while terminal 6 "Sync. ein" and terminal 3 "Freigabe GLS" are
  on, the breaker is open, no F2/F3 alarm is present, the generator is
  live (Nr 30) and the breaker logic is Parallel (ID 16, §4.3 A #4). Either
  terminal going off, or F2/F3, stops it at once (all relays off).
- One step every STEP_NS = 1 ms (a 1..10 ms service; the grid is absolute
  multiples of 1 ms, so the result does not depend on the caller's tick).
- Live bus: the frequency controller aims at f_bus + a slip of 0.1 Hz
  (at most half of +df max, ID 26), the voltage controller at U_bus. Dead
  bus with black start on (ID 19 bits 5+4): both aim at the rated values.
  Dead bus with black start off: nothing, until the bus is live.
- Controllers (§4.5, the three-step rule): each a pulse-pause controller
  with a period of 1 s; at the start of a period, an error beyond the dead
  band (f: ID 44 in Hz; U: ID 37 in % of rated) gives a RAISE or LOWER
  pulse of Kp·|e|/rate (rate: the plant's motor-potentiometer rate, so Kp
  1.0 moves the set point by the error), at least the pulse time (IDs 45,
  38) and at most the period; within the dead band the next step looks
  again. A controller that is off (ID 19) gives no pulses.
- Live-bus close: the slip df = f_gen - f_bus within -df min..+df max
  (IDs 27, 26, A15), dU = 100·(U_gen - U_bus)/U_rated within -dU min..
  +dU max (IDs 309, 28, A16/A17; U_rated the plant's rated voltage), and
  the phase crossing the advance angle -360·df·t_close (t_close ID 32,
  A19): the first step at or past it, so at most one step of slip late
  (0.18 deg at 0.49 Hz). Dead-bus close: |f_gen - f_rated| within ID 29,
  |U_gen - U_rated| in % within ID 30 (A18).
- The close relay: Impuls (ID 21 bit 3 = 0) on for the sync pulse time (ID
  31); Konstant on from the close on, held while terminal 3 stays on and no
  F2/F3 is present (dropping it opens the breaker, plant.py). RAISE/LOWER
  are off from the close command on.
- No feedback "GLS ist ein" once the pulse and the closing time plus
  RETRY_NS are over (a refusing breaker, a trip): it synchronises again.
  Attempts are counted (close_commands); the GCB monitoring alarm after
  five (§4.2 [E]) and the sync and black-start timers are not simulated.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

from .plant import NS_PER_MS, NS_PER_S, GensetPlant, wrap_deg
from .sim_store import ParameterStore

STEP_NS = NS_PER_MS  # one controller step
PERIOD_NS = NS_PER_S  # a controller's pulse period
TARGET_SLIP_HZ = 0.1  # the slip aimed at on a live bus
RETRY_NS = 500 * NS_PER_MS  # after the closing time: no feedback, try again
CROSSING_DEG = 30.0  # a crossing of the advance angle is a small step, not the wrap at 180


class State(enum.Enum):
    IDLE = "idle"
    SYNCHRONISING = "synchronising"
    CLOSING = "closing"  # close command given, waiting for the feedback
    CLOSED = "closed"


@dataclass
class Relays:
    raise_f: bool = False
    lower_f: bool = False
    raise_u: bool = False
    lower_u: bool = False
    close: bool = False


class PulseController:
    """One three-step pulse-pause controller (see the module head)."""

    def __init__(self) -> None:
        self.reset()

    def reset(self) -> None:
        self.direction = 0
        self.pulse_end = 0
        self.period_end = 0

    def step(self, now: int, error: float, deadband: float, kp: float, rate: float, pulse_min_ns: int) -> int:
        """+1 RAISE, -1 LOWER, 0 neither, at now."""
        if now >= self.period_end:
            if abs(error) > deadband and rate > 0.0:
                on = max(pulse_min_ns, math.ceil(kp * abs(error) / rate * NS_PER_S))
                self.direction = 1 if error > 0 else -1
                self.pulse_end = now + min(on, PERIOD_NS)
                self.period_end = now + PERIOD_NS
            else:
                self.direction = 0
                self.period_end = now + STEP_NS
        return self.direction if now < self.pulse_end else 0


@dataclass(frozen=True)
class Conditions:
    """What the device sees on its terminals and alarms at a step."""

    sync_request: bool  # terminal 6
    gcb_release: bool  # terminal 3
    blocked: bool  # an F2 or F3 alarm


class Supervisor:
    """The device's own synchronisation (see the module head)."""

    def __init__(self) -> None:
        self.state = State.IDLE
        self.relays = Relays()
        self.f_ctrl = PulseController()
        self.u_ctrl = PulseController()
        self.close_commands = 0
        self.last_close_ns: int | None = None
        self._close_end = 0  # the close relay drops (Impuls)
        self._wait_end = 0  # no feedback by then: again
        self._last_error: float | None = None  # phase - advance angle at the last step
        self._values: dict[str, float] = {}  # parameter values, as of the store's version
        self._version = -1

    @property
    def active(self) -> bool:
        return self.state is not State.IDLE

    def wants(self, plant: GensetPlant, c: Conditions) -> bool:
        """Whether step() has anything to do (else sim.py need not step it)."""
        return self.active or (c.sync_request and c.gcb_release and not c.blocked and not plant.gcb_closed)

    def _num(self, store: ParameterStore, key: str) -> float:
        if store.version != self._version:
            self._values, self._version = {}, store.version
        value = self._values.get(key)
        if value is None:
            raw = store.value(key)
            value = self._values[key] = float(raw) if isinstance(raw, int | float) else float(raw is True)
        return value

    def _flag(self, store: ParameterStore, key: str) -> bool:
        return self._num(store, key) == 1.0

    def stop(self) -> None:
        self.state = State.IDLE
        self.relays = Relays()
        self._last_error = None

    def step(self, now: int, plant: GensetPlant, store: ParameterStore, c: Conditions) -> None:
        if self.state is State.CLOSED:
            self._hold_closed(plant, store, c)
            return
        if not (c.sync_request and c.gcb_release) or c.blocked:
            self.stop()
            return
        if self.state is State.CLOSING:
            self._closing(now, plant, store)
            return
        if plant.gcb_closed or not plant.gen_live or self._num(store, "breaker_logic") != 1:
            self.stop()
            return
        if self.state is State.IDLE:
            self.state = State.SYNCHRONISING
            self.f_ctrl.reset()
            self.u_ctrl.reset()
            self._last_error = None
        self._synchronise(now, plant, store)

    # ------------------------------------------------------------ states

    def _synchronise(self, now: int, plant: GensetPlant, store: ParameterStore) -> None:
        g = plant.genset
        live = plant.bus_live
        if not live and not self._flag(store, "black_start"):
            self.relays = Relays()
            self._last_error = None
            return
        if live:
            slip = min(TARGET_SLIP_HZ, self._num(store, "sync_df_max") / 2.0)
            f_target, u_target = plant.f_bus + slip, plant.u_bus
        else:
            f_target, u_target = g.f_rated, g.u_rated
        self._control(now, plant, store, f_target - plant.f_gen, u_target - plant.u_gen)
        if self._may_close(plant, store):
            self._close(now, store)

    def _may_close(self, plant: GensetPlant, store: ParameterStore) -> bool:
        g = plant.genset
        if not plant.bus_live:
            self._last_error = None
            df = abs(plant.f_gen - g.f_rated)
            du = abs(100.0 * (plant.u_gen - g.u_rated) / g.u_rated)
            return df <= self._num(store, "black_start_df_max") and du <= self._num(store, "black_start_du_max")
        df = plant.f_gen - plant.f_bus
        du = 100.0 * (plant.u_gen - plant.u_bus) / g.u_rated
        advance = -360.0 * df * self._num(store, "gcb_closing_time") / 1000.0
        error = wrap_deg(plant.phase_deg - advance)
        last, self._last_error = self._last_error, error
        in_window = -self._num(store, "sync_df_min") <= df <= self._num(store, "sync_df_max")
        in_window = in_window and -self._num(store, "sync_du_min") <= du <= self._num(store, "sync_du_max")
        if not in_window or last is None or abs(error) > CROSSING_DEG or abs(last) > CROSSING_DEG:
            return False
        return (df > 0.0 and last < 0.0 <= error) or (df < 0.0 and last > 0.0 >= error)

    def _control(self, now: int, plant: GensetPlant, store: ParameterStore, e_f: float, e_u: float) -> None:
        g = plant.genset
        f_dir = u_dir = 0
        if self._flag(store, "f_controller_on"):
            pulse = round(self._num(store, "f_controller_pulse") * NS_PER_MS)
            kp = self._num(store, "f_controller_kp")
            f_dir = self.f_ctrl.step(now, e_f, self._num(store, "f_controller_deadband"), kp, g.f.rate, pulse)
        if self._flag(store, "u_controller_on"):
            pulse = round(self._num(store, "u_controller_pulse") * NS_PER_MS)
            deadband = self._num(store, "u_controller_deadband") / 100.0 * g.u_rated
            u_dir = self.u_ctrl.step(now, e_u, deadband, self._num(store, "u_controller_kp"), g.u.rate, pulse)
        self.relays = Relays(raise_f=f_dir > 0, lower_f=f_dir < 0, raise_u=u_dir > 0, lower_u=u_dir < 0)

    def _close(self, now: int, store: ParameterStore) -> None:
        self.state = State.CLOSING
        self.close_commands += 1
        self.last_close_ns = now
        pulse_ns = round(self._num(store, "sync_pulse") * NS_PER_S)
        closing_ns = round(self._num(store, "gcb_closing_time") * NS_PER_MS)
        self._close_end = now + pulse_ns
        self._wait_end = now + max(pulse_ns, closing_ns) + RETRY_NS
        self.relays = Relays(close=True)

    def _closing(self, now: int, plant: GensetPlant, store: ParameterStore) -> None:
        constant = self._flag(store, "gcb_close_constant")
        if plant.gcb_closed:
            if constant:
                self.state, self.relays = State.CLOSED, Relays(close=True)  # held (Konstant)
            else:
                self.stop()  # done; closed, nothing more to do
            return
        self.relays = Relays(close=constant or now < self._close_end)
        if now >= self._wait_end:
            self.state = State.SYNCHRONISING  # no feedback: again
            self.relays = Relays()
            self.f_ctrl.reset()
            self.u_ctrl.reset()
            self._last_error = None

    def _hold_closed(self, plant: GensetPlant, store: ParameterStore, c: Conditions) -> None:
        if not plant.gcb_closed:
            self.stop()  # opened (by the PLC, a trip, a dropped constant close)
            return
        constant = self._flag(store, "gcb_close_constant")
        self.relays = Relays(close=constant and c.gcb_release and not c.blocked)
