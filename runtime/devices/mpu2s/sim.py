"""The simulated Woodward MPU2-S on plain CAN, with the genset plant behind
it (plant.py): a real, separate peer on the bus, with its own python-can bus
object and CanEndpoint, as any other node.

    sim = Mpu2sSimulator(1, settings=BusSettings("virtual", "plant"), clock=clock, pump=pump,
                         name="mpu2s 1", scenario=Mpu2sSimOptions(...).build(), password=1234)
    sim.start()                 # the telegram on 321h from now on
    sim.advance_to(t)           # virtual time: plant, telegram frames, replies up to t
    sim.plant.f_gen, sim.closes, sim.word(26), sim.inject("bus_dead", None, True)

What the bus sees (manual 004 ch. 2-4, digest 004 §1-§3):
- The send telegram on 320h + device (§1.2): DDh, the mux 0..22, three
  words (§1.4 a), one frame every 100 ms (§1.1), mux 0, 1, ... 22, 0, ...,
  a full telegram every 2.3 s (A32: restarting at mux 0 is assumed). The
  frames' times are start + k·100 ms from the start (or the last power
  cycle), not accumulated: a service step that comes late sends every
  frame due up to its time, each built from the plant at its own time; more
  than one telegram behind (a stalled real-time thread), the older frames
  are skipped, the grid kept.
- Requests on 33Fh (§1.2) whose byte 1 is the device number: FFh read,
  EEh write (§1.4 b, c). A frame with a bad length, kind or checksum is
  counted in `malformed` and dropped (A10: no error reply exists); one for
  another device is none of this device's business (`ignored`).
- Replies on 320h + device (§1.4 d, e), never from the receive handler: a
  request is answered by the first service step REPLY_DELAY_NS (2 ms) or
  more after it came, at most one reply per REPLY_SPACING_NS (10 ms), in
  addition to the telegram's grid (A32: not said); at most REPLY_QUEUE
  requests wait, more are dropped (`overruns`). Parameter rules (the
  password, refused writes, unknown IDs: no reply): sim_store.py.
- The device synchronising its breaker itself while terminals 6 and 3 are
  on (§4.4 mode 1): sim_sync.py; its relays are ORed with the PLC's.

Telegram contents: sim_telegram.py.

The PLC side (the scan, base.py): write_outputs(image) reads the wired
OUTPUT_SIGNALS (BOOL %QX) into the plant's contacts, read_inputs(image)
writes the INPUT_SIGNALS (BOOL %IX, REAL %ID). In virtual time the engine
advances the simulator to its time before read_inputs.

Faults (FAULTS, [[sim]] faults or a test): see their descriptions. The
breaker's close signal (Impuls/Konstant, ID 21 bit 3) and open-relay
polarity (ID 248 bit 2) follow the parameter store.
"""

from __future__ import annotations

import logging
import math
import threading
from collections import deque

import can

from ...image.memory import ProcessImage
from ...io.can.bus import BusPump, BusSettings, CanEndpoint, open_bus
from ...plugin.seams import SimFault
from ...sim.base import SimulatedDevice
from ...st import types as T
from . import frames
from .plant import NS_PER_MS, Breaker, Busbar, Close, Genset, GensetPlant
from .sim_options import INPUT_SIGNALS, OUTPUT_SIGNALS, Mpu2sScenario
from .sim_store import ParameterStore
from .sim_sync import STEP_NS, Conditions, Supervisor
from .sim_telegram import TelegramContents
from .telegram import MUXES

log = logging.getLogger(__name__)

FRAME_PERIOD_NS = 100 * NS_PER_MS  # "ca. 100ms Abstand zwischen zwei Messages" (§1.1)
REPLY_DELAY_NS = 2 * NS_PER_MS
REPLY_SPACING_NS = 10 * NS_PER_MS
REPLY_QUEUE = 32

UNPLUG = SimFault(
    "unplug", "the MPU2-S's CAN cable out: no telegram, no replies; the password must be given again", lasting=True
)
BUS_DEAD = SimFault("bus_dead", "the busbar (and the mains it stands for) goes dead; a closed GCB keeps feeding it")
BUS_LIVE = SimFault("bus_live", "the busbar goes live again", value="its frequency in Hz (none: the scenario's)")
REFUSE_CLOSE = SimFault("refuse_close", "the generator breaker does not close", lasting=True)
ALARM = SimFault(
    "alarm", "a fault class present in Nr 9; F2 and F3 stop the device's synchronisation", "0..3 (F0..F3)", True
)
POWER_CYCLE = SimFault("power_cycle", "the MPU2-S off and on: the password is lost, the telegram restarts at mux 0")
FAULTS = (UNPLUG, BUS_DEAD, BUS_LIVE, REFUSE_CLOSE, ALARM, POWER_CYCLE)


def _clamp(x: float, lo: float, hi: float) -> float:
    return min(max(x, lo), hi)


def _fault_class(value: object) -> int:
    if isinstance(value, float) and value.is_integer():
        value = int(value)  # a [[sim]] faults value is a number
    text = str(value).strip().upper().removeprefix("F")
    if text in ("0", "1", "2", "3"):
        return int(text)
    raise ValueError(f"a fault class is 0..3 or F0..F3, not {value!r}")


def _store_overrides(s: Mpu2sScenario) -> dict[str, object]:
    """The parameters that describe the scenario's plant, and its [[sim]]
    parameters over them (sim_store.INITIAL for the rest)."""
    primary = int(_clamp(round(s.rated_voltage), 5, 65000))
    secondary = primary if 50 <= primary <= 480 else 100
    current = s.rated_power * 1000.0 / (math.sqrt(3.0) * s.rated_voltage)
    return {
        "gen_setpoint_frequency": round(_clamp(s.rated_frequency, 40.0, 70.0), 2),
        "gen_rated_frequency": round(_clamp(s.rated_frequency, 50.0, 60.0), 2),
        **{f"{what}_vt_primary": primary for what in ("gen", "bus", "mains")},
        **{f"{what}_vt_secondary": secondary for what in ("gen", "bus", "mains")},
        "gen_setpoint_voltage": secondary,
        "gen_rated_voltage": secondary,
        "gen_rated_power": int(_clamp(round(s.rated_power), 5, 9999)),
        "gen_rated_current": int(_clamp(round(current), 0, 7000)),
        "gcb_closing_time": int(_clamp(s.closing_time_ms, 40, 300)),
        **s.parameters,  # [[sim]] parameters: the user's presets over what the plant implies
    }


def build_plant(s: Mpu2sScenario, store: ParameterStore, t_ns: int) -> GensetPlant:
    """The genset, busbar and breaker of a scenario, at t_ns."""
    genset = Genset(
        f_rated=s.rated_frequency,
        u_rated=s.rated_voltage,
        p_rated_kw=s.rated_power,
        f_offset=s.bus_frequency + s.slip - s.rated_frequency,
        u_offset=s.voltage_offset / 100.0 * s.rated_voltage,
    )
    bus = Busbar(live=s.bus_live, f=s.bus_frequency, u=s.bus_voltage)
    breaker = Breaker(
        closing_time_ms=s.closing_time_ms,
        refuse_close=s.refuse_close,
        trip_limit_deg=s.trip_limit,
        constant_close=store.flag("gcb_close_constant"),
        open_energise=store.flag("gcb_open_relay_energise"),
    )
    return GensetPlant(genset, bus, breaker, t_ns=t_ns)


class Mpu2sSimulator(SimulatedDevice):
    """See the module docstring. password: the code level 2 password (ID
    500); None takes the scenario's (and None there: writes need none)."""

    pump: BusPump | None

    def __init__(
        self,
        device: int,
        *,
        settings: BusSettings,
        clock,
        pump: BusPump | None,
        name: str,
        scenario: Mpu2sScenario,
        password: int | None = None,
    ) -> None:
        frames.device_can_id(device)  # ValueError outside 1..30 (A9)
        super().__init__(name, clock=clock, pump=pump)
        self.device = device
        self.settings = settings
        self.scenario = scenario
        self.store = ParameterStore(
            password=password if password is not None else scenario.password, overrides=_store_overrides(scenario)
        )
        self._lock = threading.RLock()
        self._now = clock.now_ns()
        self._plant = build_plant(scenario, self.store, self._now)
        self.supervisor = Supervisor()
        self.endpoint: CanEndpoint | None = None
        self.alarms: set[int] = set()  # fault classes 0..3 present
        self._plc = dict.fromkeys(OUTPUT_SIGNALS, False)  # the PLC's contacts, as last written
        self._outputs: tuple | None = None  # (image, its readers of the wired outputs)
        self._inputs: tuple | None = None  # (image, its writers of the wired inputs)
        self._t0 = self._now  # the telegram's start
        self._k = 0  # the next frame's number since _t0
        self._last_step = -1
        self._pending: deque[tuple[int, frames.Reply]] = deque()
        self._next_reply = 0
        self._breaker_version = self.store.version
        self.contents = TelegramContents(scenario)
        self.frames_sent = self.requests = self.replies = self.malformed = self.ignored = 0
        self.refused_writes = self.unanswered = self.overruns = 0

    # ------------------------------------------------------------------ test and operator API

    @property
    def plant(self) -> GensetPlant:
        return self._plant

    @property
    def closes(self) -> list[Close]:
        return self._plant.closes

    def records(self) -> dict:
        """--final-json: each time the breaker's contacts touched (engine
        time, phase and voltage difference at that instant, slip, dead bus,
        tripped by a phase past trip_limit)."""
        closes = [
            {
                "t_s": c.t_ns / 1e9,
                "phase_deg": c.phase_deg,
                "voltage_diff_v": c.voltage_diff,
                "slip_hz": c.slip_hz,
                "dead_bus": c.dead_bus,
                "tripped": c.tripped,
            }
            for c in self.closes
        ]
        return {"closes": closes} if closes else {}

    def events_since(self, t_ns: int) -> list:
        """The breaker's closes after t_ns, for the traces."""
        closes = self.closes
        if not closes or closes[-1].t_ns <= t_ns:
            return []
        new = []
        for c in reversed(closes):
            if c.t_ns <= t_ns:
                break
            what = "dead bus" if c.dead_bus else f"phase {c.phase_deg:.1f} deg"
            text = f"breaker closed: {what}, dU {c.voltage_diff:.1f} V, slip {c.slip_hz:.3f} Hz"
            new.append((c.t_ns, text + (", tripped (phase past the trip limit)" if c.tripped else "")))
        return new[::-1]

    @property
    def authorised(self) -> bool:
        return self.store.authorised

    def word(self, param_id: int) -> int | None:
        """The word a read of param_id gets (None: an unknown ID)."""
        with self._lock:
            return self.store.read(param_id)

    def set_word(self, param_id: int, word: int) -> None:
        """Set a parameter as the device's front panel would (no password,
        the same range rules: ValueError)."""
        with self._lock:
            self.store.set_word(param_id, word)
            self._breaker_settings()

    def unplug(self) -> None:
        with self._lock:
            self._opened().connected = False
            self.store.lose_authorisation()
            self._pending.clear()

    def plug(self) -> None:
        with self._lock:
            self._opened().connected = True

    def power_cycle(self) -> None:
        """The device off and on: the password is lost, requests in hand are
        forgotten, its own synchronisation stops, the telegram restarts at mux 0."""
        with self._lock:
            self.store.lose_authorisation()
            self._pending.clear()
            self.supervisor.stop()
            self._apply_contacts()
            self._t0, self._k = self._now, 0

    def inject(self, fault: str, value, on: bool) -> None:
        """The faults of FAULTS (from [[sim]] faults or a test)."""
        with self._lock:
            bus = self._plant.bus
            if fault == UNPLUG.name:
                if on:
                    self.unplug()
                else:
                    self.plug()
            elif fault == REFUSE_CLOSE.name:
                self._plant.breaker.refuse_close = on
            elif fault == ALARM.name:
                cls = _fault_class(value)
                if on:
                    self.alarms.add(cls)
                else:
                    self.alarms.discard(cls)
            elif not on:
                return  # the others happen at once; their end does nothing
            elif fault == BUS_DEAD.name:
                bus.go_dead()
                if self._plant.breaker.closed:  # the genset alone feeds the bar now
                    g = self._plant.genset
                    bus.live, bus.fed, bus.f, bus.u = True, True, g.f.value, g.u.value
            elif fault == BUS_LIVE.name:
                if bus.fed:
                    raise ValueError(f"{self.name}: the genset feeds the busbar; another source cannot go live on it")
                f = self.scenario.bus_frequency if value in (None, "") else float(value)
                bus.go_live(f, self.scenario.bus_voltage)
            elif fault == POWER_CYCLE.name:
                self.power_cycle()
            else:
                raise ValueError(f"{self.name}: no fault {fault!r}")

    # ------------------------------------------------------------------ life cycle

    def open(self) -> None:
        with self._lock:
            self.endpoint = CanEndpoint(open_bus(self.settings), name=self.name, pump=self.pump)
            self.endpoint.add_handler(self._on_frame)
            self.endpoint.start()
            self._now = max(self._now, self.clock.now_ns())
            self._t0, self._k = self._now, 0

    def close(self) -> None:
        with self._lock:
            if self.endpoint is not None:
                self.endpoint.stop()

    def service(self, now_ns: int) -> None:
        with self._lock:
            if now_ns < self._now:
                return
            self._breaker_settings()
            self._run_to(now_ns)
            self._now = now_ns
            self._answer(now_ns)
            self._breaker_settings()

    def _opened(self) -> CanEndpoint:
        if self.endpoint is None:
            raise RuntimeError(f"{self.name}: not started (no cable to cut or mend)")
        return self.endpoint

    # ------------------------------------------------------------------ time

    def _conditions(self) -> Conditions:
        return Conditions(self._plc["sync_request"], self._plc["gcb_release"], bool(self.alarms & {2, 3}))

    def _run_to(self, now: int) -> None:
        plant = self._plant
        behind = (now - self._due()) // FRAME_PERIOD_NS
        if behind >= MUXES:
            self._k += behind - MUXES + 1  # more than a telegram late: keep the grid, skip the oldest
        t = plant.t
        self._send_due(t)
        while t < now:
            stepping = self.supervisor.wants(plant, self._conditions())
            t_next = min(now, self._due())
            if stepping:
                t_next = min(t_next, (t // STEP_NS + 1) * STEP_NS)
            plant.advance(t_next)
            t = t_next
            if stepping and t % STEP_NS == 0 and t > self._last_step:
                self._last_step = t
                self.supervisor.step(t, plant, self.store, self._conditions())
                self._apply_contacts()
            self._send_due(t)

    def _due(self) -> int:
        return self._t0 + self._k * FRAME_PERIOD_NS

    def _send_due(self, t: int) -> None:
        while self._due() <= t:
            mux = self._k % MUXES
            words = self.telegram_words()
            frame = frames.telegram_frame(mux, (words[3 * mux + 1], words[3 * mux + 2], words[3 * mux + 3]))
            if self._send(frame):
                self.frames_sent += 1
            self._k += 1

    def _send(self, data: bytes) -> bool:
        return self.endpoint is not None and self.endpoint.send(frames.device_can_id(self.device), data)

    def _apply_contacts(self) -> None:
        p, r, plc = self._plant, self.supervisor.relays, self._plc
        p.raise_f, p.lower_f = plc["raise_f"] or r.raise_f, plc["lower_f"] or r.lower_f
        p.raise_u, p.lower_u = plc["raise_u"] or r.raise_u, plc["lower_u"] or r.lower_u
        p.gcb_close, p.gcb_open = plc["gcb_close"] or r.close, plc["gcb_open"]

    def _breaker_settings(self) -> None:
        """The breaker's close signal and open polarity as the store has them
        (IDs 21, 248: however they were written)."""
        if self.store.version != self._breaker_version:
            self._breaker_version = self.store.version
            self._plant.breaker.constant_close = self.store.flag("gcb_close_constant")
            self._plant.breaker.open_energise = self.store.flag("gcb_open_relay_energise")

    # ------------------------------------------------------------------ requests and replies

    def _on_frame(self, msg: can.Message) -> None:
        if msg.arbitration_id != frames.REQUEST_ID or msg.is_remote_frame:
            return
        with self._lock:
            try:
                request = frames.decode_request(msg.arbitration_id, bytes(msg.data))
            except frames.MalformedFrame as exc:
                self.malformed += 1
                log.debug("%s: request dropped: %s", self.name, exc.reason)
                return
            if request.device != self.device:
                self.ignored += 1
                return
            self.requests += 1
            if len(self._pending) >= REPLY_QUEUE:
                self.overruns += 1
                return
            self._pending.append((self._now + REPLY_DELAY_NS, request))

    def _answer(self, now: int) -> None:
        if not self._pending or self._pending[0][0] > now or now < self._next_reply:
            return
        _ready, request = self._pending.popleft()
        if request.kind == frames.KIND_READ:
            word = self.store.read(request.param_id)
        else:
            result = self.store.write(request.param_id, request.raw)
            word = result.reply
            if not result.stored and word is not None:
                self.refused_writes += 1
                log.debug("%s: write to ID %d refused: %s", self.name, request.param_id, result.reason)
        if word is None:
            self.unanswered += 1  # an unknown ID: the device stays silent
            return
        self._next_reply = now + REPLY_SPACING_NS
        if self._send(frames.reply(request.kind, self.device, request.param_id, word)):
            self.replies += 1

    # ------------------------------------------------------------------ the telegram

    def telegram_words(self) -> list[int]:
        """The 69 words as the device sends them now, index Nr (0 unused)."""
        return self.contents.words(
            self._plant,
            alarms=self.alarms,
            sync_request=self._plc["sync_request"],
            gcb_release=self._plc["gcb_release"],
            p_set_kw=self.store.number("power_setpoint_1"),
        )

    # ------------------------------------------------------------------ the PLC's wires

    def write_outputs(self, image: ProcessImage) -> None:
        """The PLC's outputs onto the plant's contacts (and terminals 3, 6)."""
        if self._outputs is None or self._outputs[0] is not image:
            wiring = self.scenario.wiring
            readers = [(s, image.reader(wiring[s], T.BOOL)) for s in OUTPUT_SIGNALS if s in wiring]
            self._outputs = (image, readers)
        plc = self._plc
        with self._lock:
            for signal, read in self._outputs[1]:
                plc[signal] = bool(read())
            self._apply_contacts()

    def read_inputs(self, image: ProcessImage) -> None:
        """The plant's state onto the PLC's inputs."""
        if self._inputs is None or self._inputs[0] is not image:
            wiring = self.scenario.wiring
            writers = [
                (s, image.writer(wiring[s], T.BOOL if kind == "BOOL" else T.REAL))
                for s, (_what, kind) in INPUT_SIGNALS.items()
                if s in wiring
            ]
            self._inputs = (image, writers)
        with self._lock:
            p = self._plant
            values = {
                "gcb_closed": p.gcb_closed,
                "bus_live": p.bus_live,
                "phase": p.phase_deg,
                "f_gen": p.f_gen,
                "f_bus": p.f_bus,
                "u_gen": p.u_gen,
                "u_bus": p.u_bus,
            }
            for signal, write in self._inputs[1]:
                write(values[signal])
