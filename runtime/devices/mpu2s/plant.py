"""The plant behind an MPU2-S: a genset (engine with governor, generator with
AVR), the busbar it synchronises to and the generator circuit breaker (GCB),
for the synchronisation of digest 004 §4. Pure Python: no threads, no clock;
time comes in as integer nanoseconds through GensetPlant.advance(now_ns) and
everything is deterministic.

    plant = GensetPlant(Genset(f_offset=0.3), Busbar(f=50.0, u=400.0), Breaker(closing_time_ms=80))
    plant.raise_f = True           # contacts, as the PLC's relays drive them
    plant.advance(2 * S)
    plant.phase_deg, plant.f_gen, plant.gcb_closed, plant.closes

The manual describes none of this physics (it is a protocol description,
digest 004 §4.1); every number here is a simulator choice, named where it is
a constructor option:

* Governor and AVR are motor potentiometers (§4.5: the MPU2-S drives them by
  RAISE/LOWER relays): while RAISE is on the set point rises at a constant
  rate (frequency 0.5 Hz/s, voltage 2 % of rated per s), LOWER lowers it,
  both or neither hold it; the set points stay within rated +-10 %. The
  engine frequency and the generator voltage follow their set points with a
  first-order lag (0.5 s and 0.3 s).
* start() ramps both set points from 0 to the initial ones (rated plus the
  offsets) in 5 s; raise and lower act once the ramp is done.
* phi = phase_gen - phase_bus, degrees in [-180, 180], positive when the
  generator leads. Between events every input is constant, the set point
  is linear in time and the frequency is the exact solution of the lag, so
  the slip is integrated in closed form: the result does not depend on how
  the time is cut into advance() calls (to rounding).
* The breaker starts closing on a rising edge of its close contact (a pulse
  or a held contact), whatever the length of the pulse; its contacts touch
  the closing time later, on whatever phase there is then. A close with
  |phi| above the trip limit (20 deg) is a bad close: protection trips the
  breaker open at once (it never reports closed) and counts it. The open
  command's polarity is the MPU2-S's ID 248 bit 2: energise to open
  (Arbeitsstrom) or de-energise to open (Ruhestrom, an undervoltage
  release that also blocks closing). With a held close contact
  (constant_close, ID 21 bit 3 "Konstant") dropping it opens the breaker.
  Opening takes the opening time (50 ms). The feedback contact is the main
  contacts' state.
* Closed on a live bus the generator is locked to it: its frequency is the
  bus's, phi is 0, and the governor's set point moves the active power by
  droop, P = (f_set - f_bus) / (droop * f_rated) * P_rated with a 4 % droop;
  the AVR's set point is held but the voltage is the bus's. Closed on a dead
  bus the generator feeds it: the bus is live at the generator's f and U
  (no load is modelled, P = 0) and goes dead again when the breaker opens.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

NS_PER_S = 1_000_000_000
NS_PER_MS = 1_000_000


def wrap_deg(x: float) -> float:
    """x in [-180, 180] (IEEE remainder: exact)."""
    return math.remainder(x, 360.0)


def _ns(seconds: float) -> int:
    return math.ceil(seconds * NS_PER_S)


class Channel:
    """A motor-potentiometer set point and the value that follows it with a
    first-order lag: frequency (Hz) or voltage (V). Between events the set
    point moves at slope per second and the value is the lag's exact
    solution."""

    def __init__(self, value: float, rate: float, lag_s: float, low: float, high: float) -> None:
        self.setpoint = value
        self.value = value
        self.rate = rate  # set point units per second while RAISE or LOWER is on
        self.lag_s = lag_s
        self.low, self.high = low, high
        self.start_target: float | None = None  # the start ramp's end while starting
        self.start_rate = 0.0

    def motion(self, up: bool, down: bool) -> tuple[float, float]:
        """(slope per s, the bound the set point stops at) for these contacts."""
        if self.start_target is not None:
            return self.start_rate, self.start_target
        if up and not down and self.setpoint < self.high:
            return self.rate, self.high
        if down and not up and self.setpoint > self.low:
            return -self.rate, self.low
        return 0.0, self.setpoint

    def until_bound_ns(self, slope: float, bound: float) -> int | None:
        """Nanoseconds until the set point reaches its bound, None if it does not move."""
        if slope == 0.0:
            return None
        return max(1, _ns((bound - self.setpoint) / slope))  # at least 1 ns: time moves

    def advance(self, dt_s: float, slope: float, bound: float, ref: float) -> float:
        """Move dt_s seconds on; return the integral of (value - ref) over them.
        s(t) = s0 + r t, T x' = s - x:
        x(t) = s0 + r (t - T) + (x0 - s0 + r T) e^(-t/T)."""
        s0, x0, r, lag = self.setpoint, self.value, slope, self.lag_s
        decay = -math.expm1(-dt_s / lag)  # 1 - e^(-t/T), exact for small t
        c = x0 - s0 + r * lag
        integral = (s0 - ref) * dt_s + r * (dt_s * dt_s / 2.0 - lag * dt_s) + c * lag * decay
        self.setpoint = s0 + r * dt_s
        if (r > 0.0 and self.setpoint >= bound) or (r < 0.0 and self.setpoint <= bound):
            self.setpoint = bound  # the split put the bound at this instant: no overshoot
            if self.start_target is not None:
                self.start_target = None
        self.value = s0 + r * (dt_s - lag) + c * (1.0 - decay)
        return integral


class Genset:
    """Engine, governor and AVR (see the module head for the model).
    f_offset / u_offset: the initial set points' distance from rated (Hz, V)."""

    def __init__(
        self,
        *,
        f_rated: float = 50.0,
        u_rated: float = 400.0,
        p_rated_kw: float = 500.0,
        f_offset: float = 0.0,
        u_offset: float = 0.0,
        f_rate: float = 0.5,  # Hz/s while RAISE_F / LOWER_F
        u_rate_pct: float = 2.0,  # % of u_rated per s while RAISE_U / LOWER_U
        f_lag_s: float = 0.5,
        u_lag_s: float = 0.3,
        droop_pct: float = 4.0,
        setpoint_range_pct: float = 10.0,  # the set points stay within rated +- this
        start_time_s: float = 5.0,  # start(): 0 to the initial set points
        running: bool = True,
    ) -> None:
        self.f_rated, self.u_rated, self.p_rated_kw = f_rated, u_rated, p_rated_kw
        self.droop_pct = droop_pct
        self.start_time_s = start_time_s
        self.f_initial = f_rated + f_offset
        self.u_initial = u_rated + u_offset
        band = setpoint_range_pct / 100.0
        self.f = Channel(0.0, f_rate, f_lag_s, f_rated * (1 - band), f_rated * (1 + band))
        self.u = Channel(0.0, u_rate_pct / 100.0 * u_rated, u_lag_s, u_rated * (1 - band), u_rated * (1 + band))
        self.running = False
        if running:
            self.running = True
            self.f.setpoint = self.f.value = self.f_initial
            self.u.setpoint = self.u.value = self.u_initial

    def start(self) -> None:
        """Ramp the set points from where they are to the initial ones."""
        self.running = True
        for ch, target in ((self.f, self.f_initial), (self.u, self.u_initial)):
            if ch.setpoint != target:
                ch.start_target = target
                ch.start_rate = math.copysign(target / self.start_time_s, target - ch.setpoint)

    def stop(self) -> None:
        """Fuel and excitation off: the set points drop to 0, f and U decay with their lags."""
        self.running = False
        for ch in (self.f, self.u):
            ch.setpoint, ch.start_target = 0.0, None

    def power_kw(self, f_bus: float) -> float:
        """Active power by droop while locked to a bus of frequency f_bus."""
        return (self.f.setpoint - f_bus) / (self.droop_pct / 100.0 * self.f_rated) * self.p_rated_kw


class Busbar:
    """Another source on the bar (live: its own f, U, and a frequency drift
    in Hz/s), or dead (0 V, 0 Hz). fed: the genset's breaker energises it."""

    def __init__(self, *, live: bool = True, f: float = 50.0, u: float = 400.0, drift_hz_s: float = 0.0) -> None:
        self.live = live
        self.f = f if live else 0.0
        self.u = u if live else 0.0
        self.drift_hz_s = drift_hz_s if live else 0.0
        self.fed = False

    def go_live(self, f: float, u: float, drift_hz_s: float = 0.0) -> None:
        """Another source energises the bar (now: at the plant's present time)."""
        if self.fed:
            raise ValueError("the genset feeds this busbar: another source cannot go live on it")
        self.live, self.f, self.u, self.drift_hz_s = True, f, u, drift_hz_s

    def go_dead(self) -> None:
        self.live, self.f, self.u, self.drift_hz_s, self.fed = False, 0.0, 0.0, 0.0, False


@dataclass(frozen=True)
class Close:
    """One time the breaker's contacts touched."""

    t_ns: int
    phase_deg: float  # phi at that instant (0 on a dead bus)
    voltage_diff: float  # V, u_gen - u_bus
    slip_hz: float  # f_gen - f_bus
    dead_bus: bool
    tripped: bool  # |phi| above the trip limit: opened again at once


@dataclass
class Breaker:
    """The GCB (see the module head). Times in ms; trip_limit_deg: the
    largest |phi| it survives a close on."""

    closing_time_ms: float = 80.0
    opening_time_ms: float = 50.0
    trip_limit_deg: float = 20.0
    refuse_close: bool = False  # it never closes
    constant_close: bool = False  # ID 21.3 "Konstant": dropping the close contact opens it
    open_energise: bool = True  # ID 248.2: TRUE energise to open, FALSE de-energise to open
    closed: bool = field(default=False, init=False)  # the main contacts
    closes: list[Close] = field(default_factory=list, init=False)
    trips: int = field(default=0, init=False)
    refused: int = field(default=0, init=False)  # close edges refuse_close ignored
    closing_due: int | None = field(default=None, init=False)  # ns: the contacts touch
    opening_due: int | None = field(default=None, init=False)  # ns: the contacts part
    _last_close: bool = field(default=False, init=False, repr=False)

    def open_active(self, open_contact: bool) -> bool:
        return open_contact if self.open_energise else not open_contact

    def command(self, t: int, close: bool, open_contact: bool) -> None:
        """The contacts as they are at t: start closing on a rising edge of
        close, opening on an open command (or a dropped held close)."""
        opening = self.open_active(open_contact)
        if close and not self._last_close and not self.closed and self.closing_due is None:
            if opening or self.opening_due is not None:
                pass  # trip-free: an open command wins
            elif self.refuse_close:
                self.refused += 1
            else:
                self.closing_due = t + round(self.closing_time_ms * NS_PER_MS)
        self._last_close = close
        if self.closing_due is not None and (opening or (self.constant_close and not close)):
            self.closing_due = None  # opened while closing
        if self.closed and self.opening_due is None and (opening or (self.constant_close and not close)):
            self.opening_due = t + round(self.opening_time_ms * NS_PER_MS)

    def next_event(self) -> int | None:
        dues = [t for t in (self.closing_due, self.opening_due) if t is not None]
        return min(dues) if dues else None


class GensetPlant:
    """The genset, the busbar and the GCB in virtual time. Inputs: the relay
    contacts below, set between advance() calls (they act from the plant's
    present time). Outputs: the properties."""

    def __init__(
        self,
        genset: Genset | None = None,
        bus: Busbar | None = None,
        breaker: Breaker | None = None,
        *,
        phase_deg: float = 0.0,
        t_ns: int = 0,
    ) -> None:
        self.genset = genset or Genset()
        self.bus = bus or Busbar()
        self.breaker = breaker or Breaker()
        self.phi = wrap_deg(phase_deg)  # frozen while the bus is dead
        self.t = t_ns
        self.raise_f = self.lower_f = self.raise_u = self.lower_u = False
        self.gcb_close = self.gcb_open = False

    # ---- outputs
    @property
    def locked(self) -> bool:
        """Closed onto a bus another source holds."""
        return self.breaker.closed and self.bus.live and not self.bus.fed

    @property
    def f_gen(self) -> float:
        return self.bus.f if self.locked else self.genset.f.value

    @property
    def u_gen(self) -> float:
        return self.bus.u if self.locked else self.genset.u.value

    @property
    def f_bus(self) -> float:
        return self.genset.f.value if self.bus.fed else self.bus.f

    @property
    def u_bus(self) -> float:
        return self.genset.u.value if self.bus.fed else self.bus.u

    @property
    def bus_live(self) -> bool:
        return self.bus.live

    @property
    def gen_live(self) -> bool:
        """Voltage and frequency present (simulator choice: above 90 % of
        rated frequency and 80 % of rated voltage; the MPU2-S's own
        thresholds are IDs 25 and the monitoring, digest 004 §4.2)."""
        g = self.genset
        return self.f_gen > 0.9 * g.f_rated and self.u_gen > 0.8 * g.u_rated

    @property
    def phase_deg(self) -> float:
        """phi = phase_gen - phase_bus in [-180, 180], + = generator leading;
        0 when closed, the last value while the bus is dead."""
        return 0.0 if self.breaker.closed else self.phi

    @property
    def gcb_closed(self) -> bool:
        """The feedback contact (T5 "GLS ist ein")."""
        return self.breaker.closed

    @property
    def p_kw(self) -> float:
        return self.genset.power_kw(self.bus.f) if self.locked else 0.0

    @property
    def closes(self) -> list[Close]:
        return self.breaker.closes

    @property
    def trips(self) -> int:
        return self.breaker.trips

    # ---- time
    def advance(self, now_ns: int) -> None:
        """Move to now_ns with the contacts as they are, cutting the time at
        every event (a set point at its bound, the breaker's contacts)."""
        if now_ns < self.t:
            raise ValueError(f"time runs forward: {now_ns} < {self.t}")
        self._command()
        while True:
            t_next = now_ns
            due = self.breaker.next_event()
            if due is not None:
                t_next = min(t_next, due)
            for ch, (slope, bound) in self._motions():
                hit = ch.until_bound_ns(slope, bound)
                if hit is not None:
                    t_next = min(t_next, self.t + hit)
            self._integrate(t_next - self.t)
            self.t = t_next
            self._events()
            self._command()
            if self.t >= now_ns:
                return

    def _motions(self) -> list:
        g = self.genset
        if not g.running:
            return [(g.f, (0.0, g.f.setpoint)), (g.u, (0.0, g.u.setpoint))]
        return [(g.f, g.f.motion(self.raise_f, self.lower_f)), (g.u, g.u.motion(self.raise_u, self.lower_u))]

    def _integrate(self, dt_ns: int) -> None:
        if dt_ns <= 0:
            return
        dt = dt_ns / NS_PER_S
        bus = self.bus
        f_bus0 = bus.f
        locked = self.locked
        (f, (fs, fb)), (u, (us, ub)) = self._motions()
        slip_integral = f.advance(dt, fs, fb, f_bus0)
        u.advance(dt, us, ub, 0.0)
        if bus.live and not bus.fed:
            bus.f += bus.drift_hz_s * dt
        if locked:
            f.value, u.value = bus.f, bus.u  # held by the bus
            self.phi = 0.0
        elif bus.fed:
            bus.f, bus.u = f.value, u.value
            self.phi = 0.0
        elif bus.live:
            # integral of (f_gen - f_bus): the lag's closed form minus the drifting bus
            drift = bus.drift_hz_s * dt * dt / 2.0
            self.phi = wrap_deg(self.phi + 360.0 * (slip_integral - drift))

    def _command(self) -> None:
        self.breaker.command(self.t, self.gcb_close, self.gcb_open)

    def _events(self) -> None:
        br, bus = self.breaker, self.bus
        if br.opening_due is not None and br.opening_due <= self.t:
            br.opening_due = None
            br.closed = False
            if bus.fed:
                bus.go_dead()
        if br.closing_due is not None and br.closing_due <= self.t:
            br.closing_due = None
            dead = not bus.live
            phi = 0.0 if dead else self.phi
            tripped = not dead and abs(phi) > br.trip_limit_deg
            br.closes.append(
                Close(self.t, phi, self.u_gen - self.u_bus, self.f_gen - self.f_bus, dead_bus=dead, tripped=tripped)
            )
            if tripped:
                br.trips += 1
                return
            br.closed = True
            self.phi = 0.0
            if dead:
                bus.live, bus.fed = True, True
                bus.f, bus.u = self.genset.f.value, self.genset.u.value
            else:
                self.genset.f.value, self.genset.u.value = bus.f, bus.u
