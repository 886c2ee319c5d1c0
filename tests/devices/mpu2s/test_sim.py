"""The simulated MPU2-S (runtime/devices/mpu2s/sim.py) on python-can's
virtual bus, in virtual time: a test endpoint on the same channel plays the
PLC, sending the request frames of digest 004 §5.2 byte for byte and
collecting what the device sends; a ProcessImage plays the scan's wires.
Real parts only: the bus, the pump, the clock, the plant."""

from __future__ import annotations

import itertools
import time

import pytest

from softplc.runtime.devices.mpu2s import frames
from softplc.runtime.devices.mpu2s import parameters as P
from softplc.runtime.devices.mpu2s.sim import FAULTS, Mpu2sSimulator
from softplc.runtime.devices.mpu2s.sim_options import Mpu2sScenario, Mpu2sSimOptions
from softplc.runtime.devices.mpu2s.sim_store import ParameterStore, word_problem
from softplc.runtime.devices.mpu2s.sim_sync import State
from softplc.runtime.devices.mpu2s.telegram import ControlRegister2, FaultClass, TelegramAssembler, double_bit
from softplc.runtime.engine.clock import RealClock, VirtualClock
from softplc.runtime.image.memory import ProcessImage
from softplc.runtime.io.can.bus import BusPump, BusSettings, CanEndpoint, open_bus
from softplc.runtime.st import types as T

MS = 1_000_000
S = 1_000_000_000
DEVICE = 1
TELEGRAM_ID = 0x321
WIRING = {
    "raise_f": "%QX20.0",
    "lower_f": "%QX20.1",
    "raise_u": "%QX20.2",
    "lower_u": "%QX20.3",
    "gcb_close": "%QX20.4",
    "gcb_open": "%QX20.5",
    "sync_request": "%QX20.6",
    "gcb_release": "%QX20.7",
    "gcb_closed": "%IX20.0",
    "bus_live": "%IX20.1",
    "phase": "%ID24",
    "f_gen": "%ID28",
    "f_bus": "%ID32",
    "u_gen": "%ID36",
    "u_bus": "%ID40",
}
_channels = itertools.count()


class Bench:
    """The simulator, a PLC endpoint and a process image on one virtual channel."""

    def __init__(self, scenario: Mpu2sScenario | None = None, *, password: int | None = None, tick_ms: int = 10):
        self.settings = BusSettings("virtual", f"test-mpu2s-sim-{next(_channels)}", 125_000)
        self.clock = VirtualClock()
        self.pump = BusPump()
        self.tick = tick_ms * MS
        self.image = ProcessImage()
        self.frames: list[tuple[int, int, bytes]] = []  # (t, can_id, data) as the PLC got them
        self.plc = CanEndpoint(open_bus(self.settings), name="plc", pump=self.pump)
        self.plc.add_handler(lambda m: self.frames.append((self.clock.now_ns(), m.arbitration_id, bytes(m.data))))
        self.plc.start()
        self.sim = Mpu2sSimulator(
            DEVICE,
            settings=self.settings,
            clock=self.clock,
            pump=self.pump,
            name="mpu2s 1",
            scenario=scenario or Mpu2sScenario(wiring=dict(WIRING)),
            password=password,
        )
        self.sim.start()
        self.sim.advance_to(0)  # the engine's first tick

    def stop(self) -> None:
        self.sim.stop()
        self.plc.stop()

    @property
    def now(self) -> int:
        return self.clock.now_ns()

    def run(self, seconds: float, each=None) -> None:
        """Scans of tick_ms as the engine runs them in virtual time: the
        simulator to the tick's time, inputs, each(t) (the program), outputs."""
        end = self.now + round(seconds * S)
        while self.now < end:
            t = min(end, self.now + self.tick)
            self.clock.sleep_until(t)
            self.sim.advance_to(t)
            self.sim.read_inputs(self.image)
            if each is not None:
                each(t)
            self.sim.write_outputs(self.image)

    def set(self, signal: str, on: bool) -> None:
        self.image.write(WIRING[signal], on, T.BOOL)

    def get(self, signal: str, ty=T.REAL):
        return self.image.read(WIRING[signal], ty)

    def telegram(self, since: int = 0) -> list[tuple[int, int, tuple[int, int, int]]]:
        """(t, mux, words) of every telegram frame since `since`."""
        out = []
        for t, can_id, data in self.frames:
            if can_id == TELEGRAM_ID and data[0] == frames.KIND_TELEGRAM and t >= since:
                _device, mux, words = frames.decode_telegram(can_id, data)
                out.append((t, mux, words))
        return out

    def replies(self) -> list[tuple[int, frames.Reply]]:
        return [
            (t, frames.decode_reply(can_id, data))
            for t, can_id, data in self.frames
            if can_id == TELEGRAM_ID and data[0] != frames.KIND_TELEGRAM
        ]

    def request(self, data: bytes | str, seconds: float = 0.05) -> list[frames.Reply]:
        """Send one request frame on 33Fh; the replies that came within `seconds`."""
        before = len(self.replies())
        assert self.plc.send(frames.REQUEST_ID, bytes.fromhex(data) if isinstance(data, str) else data)
        self.run(seconds)
        return [r for _t, r in self.replies()[before:]]

    def read(self, param_id: int) -> list[frames.Reply]:
        return self.request(frames.read_request(DEVICE, param_id))

    def write(self, param_id: int, raw: int) -> list[frames.Reply]:
        return self.request(frames.write_request(DEVICE, param_id, raw))


@pytest.fixture
def bench():
    made: list[Bench] = []

    def make(scenario: Mpu2sScenario | None = None, **kw) -> Bench:
        b = Bench(scenario, **kw)
        made.append(b)
        return b

    yield make
    for b in made:
        b.stop()


def scenario(**kw) -> Mpu2sScenario:
    kw.setdefault("wiring", dict(WIRING))
    return Mpu2sScenario(**kw)


# ---------------------------------------------------------------------------- the telegram


def test_telegram_frames_every_100ms_in_mux_order(bench):
    b = bench()
    b.run(4.6)
    got = b.telegram()
    assert len(got) == 47 == b.sim.frames_sent  # t = 0, 0.1, ... 4.6 s
    assert [t for t, _mux, _w in got] == [k * 100 * MS for k in range(47)]
    assert [mux for _t, mux, _w in got] == [k % 23 for k in range(47)]
    assert all(len(data) == 8 for _t, can_id, data in b.frames if can_id == TELEGRAM_ID)


def test_telegram_catches_up_on_its_grid_whatever_the_tick(bench):
    b = bench(tick_ms=250)
    b.run(1.0)
    assert [mux for _t, mux, _w in b.telegram()] == list(range(11))  # 0..1.0 s, none lost, none doubled
    assert b.sim.frames_sent == 11


def test_telegram_decodes_to_the_plant(bench):
    b = bench(scenario(slip=0.3, voltage_offset=2.0))
    b.run(2.3)
    asm = TelegramAssembler()
    for t, mux, words in b.telegram():
        asm.feed(mux, words, t)
    assert asm.complete
    v = asm.values()
    plant = b.sim.plant
    assert v["ident"] == 1301
    assert v["f_gen"] == pytest.approx(plant.f_gen, abs=0.005) and v["f_gen"] == pytest.approx(50.3)
    assert v["f_bus"] == pytest.approx(plant.f_bus, abs=0.005) == 50.0
    assert v["f_mains"] == pytest.approx(50.0)
    assert v["u_gen_l12"] == pytest.approx(plant.u_gen, abs=0.05) and v["u_gen_l12"] == pytest.approx(408.0)
    assert v["u_gen_l1n"] == pytest.approx(408.0 / 3**0.5, abs=0.05)
    assert v["u_bus_l12"] == pytest.approx(plant.u_bus) == 400.0
    assert v["u_mains_l12"] == pytest.approx(400.0)
    assert asm.exponents == {"PGNEXPO": 2, "UGNEXPO": -1, "IGNEXPO": -1, "UNTEXPO": -1, "USSEXPO": -1}
    assert (v["p_gen"], v["q_gen"], v["cos_phi"], v["i_gen_l1"]) == (0.0, 0.0, 1.0, 0.0)
    assert v["mains_present"] is True and v["generator_present"] is True and v["busbar_present"] is True
    assert v["battery"] == 24.0 and v["hours"] == 1234 and v["energy_kwh"] == 123456 and v["starts"] == 42
    reg = asm.words[10]
    assert double_bit(reg, ControlRegister2.T4_BREAKER_OPEN) is True
    assert double_bit(reg, ControlRegister2.T5_GCB_CLOSED) is False
    assert double_bit(reg, ControlRegister2.T3_GCB_RELEASE) is False
    assert asm.words[9] == 0


def test_a_dead_bus_in_the_telegram(bench):
    b = bench(scenario(bus_live=False))
    b.run(2.3)
    asm = TelegramAssembler()
    for t, mux, words in b.telegram():
        asm.feed(mux, words, t)
    v = asm.values()
    assert v["busbar_present"] is False and v["mains_present"] is False and v["generator_present"] is True
    assert v["f_bus"] == 0.0 and v["f_mains"] == 0.0 and v["u_bus_l12"] == 0.0


def test_alarms_and_terminals_in_nr_9_and_nr_10(bench):
    b = bench()
    b.sim.inject("alarm", "F2", True)
    b.sim.inject("alarm", 0.0, True)  # as [[sim]] faults gives a number
    b.set("gcb_release", True)
    b.set("sync_request", True)
    b.run(0.05)
    words = b.sim.telegram_words()
    assert double_bit(words[9], FaultClass.F2) is True and double_bit(words[9], FaultClass.F0) is True
    assert double_bit(words[9], FaultClass.F3) is False and double_bit(words[9], FaultClass.F1) is False
    assert double_bit(words[10], ControlRegister2.T3_GCB_RELEASE) is True
    assert double_bit(words[10], ControlRegister2.T6_SYNC_ON) is True
    b.sim.inject("alarm", "F2", False)
    assert double_bit(b.sim.telegram_words()[9], FaultClass.F2) is False
    with pytest.raises(ValueError, match="fault class"):
        b.sim.inject("alarm", "F7", True)


# ---------------------------------------------------------------------------- parameters


def test_reads_give_the_stored_words_with_their_checksum(bench):
    b = bench()
    [reply] = b.request("FF 01 00 0B 00 00 FF 0A")  # read ID 11
    raw_reply = next(data for _t, can_id, data in b.frames if can_id == TELEGRAM_ID and data[0] == 0xFF)
    assert raw_reply == bytes.fromhex("FF 01 00 0B 32 00 CD 0A")  # V7
    assert reply == frames.Reply(frames.KIND_READ, DEVICE, 11, 12800)
    assert b.request("FF 01 01 FB 00 00 FE FA")[0].raw == 400  # V2: KWUGNSEK
    assert b.request("FF 01 00 13 00 00 FF 12")[0].raw == 0xCC00  # V3: f and U controllers on
    assert b.request("FF 01 01 F4 00 00 FE F5")[0].raw == 0  # V1: the password is not disclosed
    assert [r.raw for r in b.read(26)] == [51]  # +df max 0.20 Hz
    assert [r.raw for r in b.read(32)] == [80]  # the scenario's closing time
    assert b.sim.requests == 6 and b.sim.replies == 6


def test_a_reply_comes_a_service_step_later_and_replies_are_paced(bench):
    b = bench(tick_ms=1)
    sent = b.now
    b.plc.send(frames.REQUEST_ID, frames.read_request(DEVICE, 26))
    b.plc.send(frames.REQUEST_ID, frames.read_request(DEVICE, 27))
    b.run(0.05)
    (t1, r1), (t2, r2) = b.replies()
    assert (r1.param_id, r1.raw, r2.param_id, r2.raw) == (26, 51, 27, 26)
    assert t1 >= sent + 2 * MS and t2 - t1 >= 10 * MS


def test_writes_need_the_password_first(bench):
    b = bench(password=1234)
    assert [r.raw for r in b.request("EE 01 00 1A 00 40 EE 5B")] == [51]  # 0.25 Hz: refused, the old word
    assert b.sim.word(26) == 51 and b.sim.refused_writes == 1 and not b.sim.authorised
    assert [r.raw for r in b.write(500, 4321)] == [4321]  # a wrong password: echoed, nothing unlocked
    assert not b.sim.authorised and b.sim.refused_writes == 2
    assert [r.raw for r in b.request("EE 01 01 F4 04 D2 EB 27")] == [1234]  # V4
    assert b.sim.authorised
    [reply] = b.write(26, 64)
    assert reply == frames.Reply(frames.KIND_WRITE, DEVICE, 26, 64) and b.sim.word(26) == 64
    assert [r.raw for r in b.request("EE 01 00 45 FF 9C 11 D8")] == [0xFF9C]  # V15: -100 kW, signed
    assert [r.raw for r in b.request("EE 01 00 0D FF A1 11 AD")] == [0xFFA1]  # V16: cos φ -0.95
    assert b.sim.store.value("power_setpoint_1") == -100


def test_without_a_password_every_valid_write_is_taken(bench):
    b = bench()
    assert b.sim.authorised
    assert [r.raw for r in b.request("EE 01 00 1C 00 C8 EE D5")] == [200]  # V10
    assert [r.raw for r in b.request("EE 01 00 13 FF 30 11 22")] == [0xFF30]  # V18: black start on too
    assert b.sim.store.flag("black_start")


@pytest.mark.parametrize(
    ("param_id", "raw", "why"),
    [
        (26, 126, "+df max above 0.49 Hz"),
        (26, 4, "+df max below 0.02 Hz"),
        (11, 17921, "set-point frequency above 70 Hz"),
        (13, 50, "cos φ set point 0.50"),
        (19, 0xCD00, "the U controller switch 01"),
        (16, 0x0900, "breaker logic 1001 (E8)"),
        (130, 3334, "a fault class digit 4"),
        (507, 800, "KWUGNSEK is read-only"),
        (436, 0x4408, "a relay word with bit 3 set"),
    ],
)
def test_a_write_outside_the_rules_is_refused(bench, param_id, raw, why):
    b = bench()
    old = b.sim.word(param_id)
    assert [r.raw for r in b.write(param_id, raw)] == [old], why
    assert b.sim.word(param_id) == old and b.sim.refused_writes == 1


def test_bit_words_keep_their_undocumented_bits(bench):
    b = bench()
    assert [r.raw for r in b.write(19, 0xCC00 | 0x0003)] == [0xCC03]  # bits 1, 0: no parameter, free


def test_an_unknown_id_gets_no_reply(bench):
    b = bench()
    assert b.read(999) == [] and b.write(999, 1) == []
    assert b.sim.requests == 2 and b.sim.unanswered == 2 and b.sim.replies == 0


def test_bad_frames_are_counted_and_get_no_reply_others_are_ignored(bench):
    b = bench()
    assert b.request("FF 01 00 0B 00 00 F4 0B") == []  # checksum off by one
    assert b.request("FF 01 00 0B 00 00") == []  # short
    assert b.request("AA 01 00 0B 00 00 A1 0A") == []  # no kind
    assert b.sim.malformed == 3 and b.sim.requests == 0
    assert b.request("EE 03 00 0B 32 00 DC 08") == []  # V6: device 3's
    assert b.sim.ignored == 1 and b.sim.word(11) == 12800
    assert len(b.read(11)) == 1  # still answering


def test_the_initial_words_pass_the_write_rules():
    store = ParameterStore()
    assert set(P.all_ids()) - {500} <= set(store.words)
    assert {i: word_problem(i, w) for i, w in store.words.items() if i not in (507, 508) and word_problem(i, w)} == {}
    assert store.words[507] == store.words[508] == 400
    assert store.value("sync_df_min") == pytest.approx(0.1, abs=0.004)
    assert store.value("sync_du_max") == 5.0 and store.value("sync_pulse") == 0.2


def test_set_word_is_the_front_panel(bench):
    b = bench(password=1)
    b.sim.set_word(21, b.sim.word(21) | 0x0008)  # Konstant: no password on the panel
    assert b.sim.store.flag("gcb_close_constant") and b.sim.plant.breaker.constant_close
    with pytest.raises(ValueError):
        b.sim.set_word(26, 200)
    with pytest.raises(ValueError):
        b.sim.set_word(999, 0)


# ---------------------------------------------------------------------------- faults


def test_the_faults_are_declared():
    assert [f.name for f in FAULTS] == ["unplug", "bus_dead", "bus_live", "refuse_close", "alarm", "power_cycle"]
    assert {f.name for f in FAULTS if f.lasting} == {"unplug", "refuse_close", "alarm"}


def test_unplugged_it_sends_nothing_and_forgets_the_password(bench):
    b = bench(password=1234)
    b.write(500, 1234)
    assert b.sim.authorised
    b.sim.inject("unplug", None, True)
    b.frames.clear()
    b.run(1.0)
    assert b.read(11) == [] and b.frames == [] and not b.sim.authorised
    b.sim.inject("unplug", None, False)
    b.run(0.3)
    assert len(b.telegram()) == 3 and len(b.read(11)) == 1
    assert [r.raw for r in b.write(26, 64)] == [51]  # the password again first


def test_a_power_cycle_restarts_the_telegram_and_loses_the_password(bench):
    b = bench(password=1234)
    b.run(0.5)  # mux 0..5 sent
    b.write(500, 1234)
    b.sim.inject("power_cycle", None, True)
    cycled = b.now
    b.run(0.25)
    assert [mux for _t, mux, _w in b.telegram(since=cycled)] == [0, 1, 2]
    assert not b.sim.authorised
    assert [r.raw for r in b.write(26, 64)] == [51]


def test_the_bus_goes_dead_and_live_again(bench):
    b = bench(scenario(slip=0.0))
    b.sim.inject("bus_dead", None, True)
    b.run(0.02)
    assert not b.get("bus_live", T.BOOL) and b.get("f_bus") == 0.0
    b.sim.inject("bus_live", 50.2, True)
    b.run(0.02)
    assert b.get("bus_live", T.BOOL) and b.get("f_bus") == pytest.approx(50.2)
    b.sim.inject("bus_dead", None, True)
    b.sim.inject("bus_live", None, True)  # the scenario's frequency
    assert b.sim.plant.f_bus == 50.0


# ---------------------------------------------------------------------------- the wires


def test_raise_f_held_for_2_s_raises_the_frequency_by_1_hz(bench):
    b = bench(scenario(slip=0.0))
    b.run(0.1)
    assert b.get("f_gen") == pytest.approx(50.0) and b.get("f_bus") == pytest.approx(50.0)
    assert b.get("u_gen") == pytest.approx(400.0) and b.get("bus_live", T.BOOL)
    b.set("raise_f", True)
    b.run(2.0)
    b.set("raise_f", False)
    b.run(5.0)  # the lag settles (0.5 s)
    assert b.sim.plant.genset.f.setpoint == pytest.approx(51.0, abs=0.01)
    assert b.get("f_gen") == pytest.approx(51.0, abs=0.01)
    assert b.get("phase") == pytest.approx(b.sim.plant.phase_deg, abs=1e-4) and b.get("phase") != 0.0


def test_the_plc_closes_the_breaker_through_its_wire(bench):
    b = bench(scenario(slip=0.0))
    b.set("gcb_close", True)
    b.run(0.2)
    assert b.get("gcb_closed", T.BOOL) and len(b.sim.closes) == 1
    assert double_bit(b.sim.telegram_words()[10], ControlRegister2.T5_GCB_CLOSED) is True


# ---------------------------------------------------------------------------- its own synchronisation


def supervise(b: Bench) -> None:
    b.set("sync_request", True)
    b.set("gcb_release", True)


@pytest.mark.parametrize("slip", [0.1, 0.2, 0.3, -0.2])
def test_it_synchronises_and_closes_onto_a_live_bus(bench, slip):
    b = bench(scenario(slip=slip, voltage_offset=3.0))
    supervise(b)
    b.run(40.0)
    [close] = b.sim.closes
    assert not close.tripped and not close.dead_bus
    assert abs(close.phase_deg) < 10.0
    assert -0.10 <= close.slip_hz <= 0.20
    assert abs(close.voltage_diff) <= 0.05 * 400.0
    assert b.get("gcb_closed", T.BOOL) and b.sim.supervisor.state is State.IDLE
    assert b.sim.supervisor.close_commands == 1
    assert not any((b.sim.plant.raise_f, b.sim.plant.lower_f, b.sim.plant.gcb_close))


def test_the_close_lands_within_a_degree_with_the_default_parameters(bench):
    b = bench(scenario(slip=0.15))
    supervise(b)
    b.run(20.0)
    [close] = b.sim.closes
    assert abs(close.phase_deg) < 1.0


def test_no_synchronisation_without_both_terminals(bench):
    b = bench(scenario(slip=0.1))
    b.set("sync_request", True)
    b.run(15.0)
    assert b.sim.closes == [] and b.sim.plant.f_gen == pytest.approx(50.1)


def test_an_f2_alarm_stops_the_synchronisation(bench):
    b = bench(scenario(slip=0.1))
    b.sim.inject("alarm", 2, True)
    supervise(b)
    b.run(15.0)
    assert b.sim.closes == [] and b.sim.supervisor.state is State.IDLE


def test_a_dead_bus_closes_only_with_black_start_on(bench):
    b = bench(scenario(bus_live=False, slip=0.3))
    supervise(b)
    b.run(5.0)
    assert b.sim.closes == []
    p = P.parameter("black_start")
    assert [r.raw for r in b.write(19, P.merge(p, b.sim.word(19), True))] == [0xCC30]
    b.run(10.0)
    [close] = b.sim.closes
    assert close.dead_bus and not close.tripped
    assert abs(close.slip_hz - 50.0) <= 0.5  # f_gen against a 0 Hz bus: within 0.50 Hz of rated (ID 29)
    assert abs(close.voltage_diff - 400.0) <= 0.05 * 400.0  # likewise U_gen, 5 % (ID 30)
    assert b.get("gcb_closed", T.BOOL) and b.get("bus_live", T.BOOL)


def test_a_refusing_breaker_does_not_close_and_the_device_tries_again(bench):
    b = bench(scenario(slip=0.2))
    b.sim.inject("refuse_close", None, True)
    supervise(b)
    b.run(30.0)
    assert b.sim.closes == [] and not b.get("gcb_closed", T.BOOL)
    assert b.sim.supervisor.close_commands >= 2 and b.sim.plant.breaker.refused == b.sim.supervisor.close_commands
    b.sim.inject("refuse_close", None, False)
    b.run(15.0)
    assert len(b.sim.closes) == 1 and abs(b.sim.closes[0].phase_deg) < 10.0


def test_constant_close_holds_the_relay_and_dropping_the_release_opens(bench):
    b = bench(scenario(slip=0.1))
    b.sim.set_word(21, b.sim.word(21) | 0x0008)  # ID 21 bit 3: Konstant
    supervise(b)
    b.run(15.0)
    assert b.get("gcb_closed", T.BOOL) and b.sim.plant.gcb_close  # held
    b.set("sync_request", False)
    b.run(1.0)
    assert b.get("gcb_closed", T.BOOL)  # terminal 6 only starts it
    b.set("gcb_release", False)
    b.run(0.2)
    assert not b.get("gcb_closed", T.BOOL) and not b.sim.plant.gcb_close


def test_the_open_relay_polarity_follows_id_248(bench):
    b = bench(scenario(slip=0.0))
    b.sim.set_word(248, b.sim.word(248) & ~0x0004)  # Ruhestrom: de-energise to open
    assert not b.sim.plant.breaker.open_energise
    b.set("gcb_close", True)
    b.run(0.2)
    assert not b.get("gcb_closed", T.BOOL)  # the open coil is not energised: it stays open
    b.set("gcb_close", False)
    b.set("gcb_open", True)
    b.run(0.02)
    b.set("gcb_close", True)
    b.run(0.2)
    assert b.get("gcb_closed", T.BOOL)


# ---------------------------------------------------------------------------- configuration, real time


def test_the_password_comes_from_the_sim_options(bench):
    options = Mpu2sSimOptions.model_validate({"password": 1234, "wiring": dict(WIRING)})
    b = bench(options.build())
    assert b.sim.store.password == 1234 and not b.sim.authorised
    assert [r.raw for r in b.write(26, 64)] == [51]
    with pytest.raises(ValueError, match="0 to 9999"):
        Mpu2sSimOptions.model_validate({"password": 10000})


def test_in_real_time_it_runs_its_own_service_thread():
    settings = BusSettings("virtual", f"test-mpu2s-sim-rt-{next(_channels)}", 125_000)
    got: list[tuple[int, bytes]] = []
    plc = CanEndpoint(open_bus(settings), name="plc")
    plc.add_handler(lambda m: got.append((m.arbitration_id, bytes(m.data))))
    plc.start()
    sim = Mpu2sSimulator(DEVICE, settings=settings, clock=RealClock(), pump=None, name="rt", scenario=scenario())
    sim.start()
    try:
        plc.send(frames.REQUEST_ID, frames.read_request(DEVICE, 11))
        deadline = time.monotonic() + 5.0
        while time.monotonic() < deadline and not (sim.frames_sent >= 3 and sim.replies == 1):
            time.sleep(0.01)
        assert sim.frames_sent >= 3 and sim.replies == 1
        assert (TELEGRAM_ID, bytes.fromhex("FF 01 00 0B 32 00 CD 0A")) in got
    finally:
        sim.stop()
        plc.stop()
