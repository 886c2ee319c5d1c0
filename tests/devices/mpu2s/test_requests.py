"""The request engine (runtime/devices/mpu2s/requests.py) on its own: the
frames it sends for a read or a write, byte for byte (digest 004 §5.2 V4,
V8), in which order (password first, the voltage factor, read-modify-write,
read-back), paced and timed out, and what it makes of the replies. The
device side is a parameter table answering with frames.reply: the codec's
own frames, no bus (the bus and the simulator: test_node.py)."""

from __future__ import annotations

from fractions import Fraction

import pytest

from softplc.runtime.devices.mpu2s import frames
from softplc.runtime.devices.mpu2s.exchange import MGMT_WORDS, finish
from softplc.runtime.devices.mpu2s.parameters import KWUGNSEK_ID, encode, parameter
from softplc.runtime.devices.mpu2s.requests import MS, Outcome, Request, RequestEngine, Result

DEVICE = 1
V4_PASSWORD = "EE 01 01 F4 04 D2 EB 27"  # digest §5.2: the password 1234 to ID 500
V8_DF_MAX = "EE 01 00 1A 00 33 EE 28"  # +df max 0.20 Hz
DF_MAX = parameter("sync_df_max")


class Line:
    """The engine, the frames it sends, a device that answers them."""

    def __init__(self, *, password: int | None = None, answer: bool = True, **engine) -> None:
        self.sent: list[tuple[int, bytes]] = []
        self.words: dict[int, int] = {KWUGNSEK_ID: 400, DF_MAX.id: 0x0026}
        self.answer = answer
        self.hold: set[int] = set()  # IDs whose writes the device does not take
        self.now = 0
        self.results: list[Result] = []
        self.engine = RequestEngine(DEVICE, self._send, password=password, **engine)

    def _send(self, can_id: int, data: bytes) -> bool:
        self.sent.append((can_id, data))
        return True

    def submit(self, param_id: int, *, bit: int = -1, write: bool = False, value=None) -> None:
        self.engine.submit(Request(param_id, bit, write, value, self.results.append))

    def run(self, ms: int, step_ms: int = 10) -> None:
        """Advance the engine; every frame sent is answered 5 ms later."""
        end = self.now + ms * MS
        while self.now < end:
            before = len(self.sent)
            self.engine.advance(self.now)
            self.now += step_ms * MS
            for can_id, data in self.sent[before:]:
                if self.answer:
                    self._reply(can_id, data)

    def _reply(self, can_id: int, data: bytes) -> None:
        request = frames.decode_request(can_id, data)
        if request.kind == frames.KIND_WRITE and request.param_id not in self.hold:
            self.words[request.param_id] = request.raw
        word = self.words.get(request.param_id, 0)
        reply = frames.reply(request.kind, DEVICE, request.param_id, word)
        self.engine.on_reply(frames.decode_reply(frames.device_can_id(DEVICE), reply), self.now)

    def frames_hex(self) -> list[str]:
        return [data.hex(" ").upper() for _id, data in self.sent]


def test_a_write_gives_the_password_first_then_writes_and_reads_back():
    line = Line(password=1234)
    line.submit(DF_MAX.id, write=True, value=0.20)
    line.run(1000)
    assert line.frames_hex() == [V4_PASSWORD, V8_DF_MAX, frames.read_request(1, DF_MAX.id).hex(" ").upper()]
    assert {can_id for can_id, _ in line.sent} == {frames.REQUEST_ID}
    [result] = line.results
    assert result.outcome == Outcome.OK
    assert result.raw == 0x33 and result.value == pytest.approx(0.20, abs=0.005)
    assert result.transactions == 3


def test_the_password_is_given_once_and_again_after_a_communication_loss():
    line = Line(password=1234)
    line.submit(DF_MAX.id, write=True, value=0.20)
    line.submit(DF_MAX.id, write=True, value=0.10)
    line.run(1000)
    assert line.frames_hex().count(V4_PASSWORD) == 1
    line.engine.comm_lost()
    line.submit(DF_MAX.id, write=True, value=0.20)
    line.run(1000)
    assert line.frames_hex().count(V4_PASSWORD) == 2
    assert [r.outcome for r in line.results] == [Outcome.OK] * 3


def test_frames_of_one_device_are_paced():
    line = Line(password=1234, pace_ns=100 * MS)
    line.submit(DF_MAX.id, write=True, value=0.20)
    times = []
    end = 1000 * MS
    while line.now < end:
        before = len(line.sent)
        line.engine.advance(line.now)
        if len(line.sent) > before:
            times.append(line.now)
            line._reply(*line.sent[-1])
        line.now += 1 * MS
    assert [b - a for a, b in zip(times, times[1:])] == [100 * MS, 100 * MS]


def test_no_reply_sends_the_same_frame_again_then_gives_up():
    line = Line(answer=False, timeout_ns=300 * MS, retries=2)
    line.submit(DF_MAX.id)
    line.run(2000)
    assert line.frames_hex() == [frames.read_request(1, DF_MAX.id).hex(" ").upper()] * 3
    [result] = line.results
    assert result.outcome == Outcome.TIMEOUT
    assert "after 3 attempt(s)" in result.message
    assert line.engine.timeouts == 3 and line.engine.failed == 1


def test_a_late_reply_is_counted_and_changes_nothing():
    line = Line(answer=False)
    line.submit(DF_MAX.id)
    line.run(2000)
    late = frames.decode_reply(frames.device_can_id(1), frames.reply(frames.KIND_READ, 1, DF_MAX.id, 0x33))
    line.engine.on_reply(late, line.now)
    assert line.engine.unmatched == 1
    assert [r.outcome for r in line.results] == [Outcome.TIMEOUT]


def test_a_value_outside_the_range_is_refused_before_the_wire():
    line = Line(password=1234)
    line.submit(DF_MAX.id, write=True, value=5.0)  # 4.2.47: 0.02 .. 0.49 Hz
    line.run(500)
    assert line.sent == []
    [result] = line.results
    assert result.outcome == Outcome.RANGE and result.transactions == 0


def test_an_unknown_parameter_sends_nothing():
    line = Line()
    line.submit(4000)
    line.submit(19, bit=-1, write=True, value=1)  # ID 19 holds several switches: which one?
    line.run(500)
    assert line.sent == []
    assert [r.outcome for r in line.results] == [Outcome.UNKNOWN, Outcome.UNKNOWN]


def test_a_voltage_parameter_reads_its_factor_first_and_keeps_it():
    line = Line(variant=400)  # the 400 V device: 50..480 V (4.2.10 b.)
    p = parameter("gen_setpoint_voltage")  # 4.2.10: scaled with KWUGNSEK (ID 507)
    line.submit(p.id, write=True, value=400)
    line.submit(p.id)
    line.run(2000)
    ids = [frames.decode_request(i, d).param_id for i, d in line.sent]
    assert ids == [KWUGNSEK_ID, p.id, p.id, p.id]
    assert line.words[p.id] == encode(p, 400, factor=400, variant=400) == 400  # raw = U·KWUGNSEK/400 (§3.4)
    assert [r.value for r in line.results] == [pytest.approx(400), pytest.approx(400)]


def test_a_bit_parameter_is_merged_into_the_word_read_first():
    line = Line()
    f_on = parameter("f_controller_on")  # ID 19 bits 15+14 (4.2.18)
    line.words[19] = 0x0F30  # the other switches of the word
    line.submit(19, bit=15, write=True, value=True)
    line.run(1000)
    kinds = [(frames.decode_request(i, d).kind, frames.decode_request(i, d).param_id) for i, d in line.sent]
    assert kinds == [(frames.KIND_READ, 19), (frames.KIND_WRITE, 19), (frames.KIND_READ, 19)]
    assert line.words[19] == 0xCF30
    [result] = line.results
    assert result.outcome == Outcome.OK and result.raw == 0xCF30 and result.value == 1.0
    assert f_on.bits == (15, 14)


@pytest.mark.parametrize(
    "key, value, word, expected",
    [
        ("breaker_logic", 1.0, 0x000A, 0x010A),  # ID 16 bits 11..8, 0001 Parallel (4.2.43)
        ("amz_characteristic", 2.0, 0x0000, 0x0002),  # ID 298 bits 1+0, 10 extremely inverse (4.2.78)
        ("ao1_source", 5.0, 0x0000, 0x0005),  # ID 192, a whole-word code 0..22 (4.2.152, A24)
    ],
)
def test_a_code_comes_from_a_program_as_a_whole_number(key, value, word, expected):
    # MPU2S_PARAM's VALUE is an LREAL: a code is a whole number in it
    p = parameter(key)
    line = Line()
    line.words[p.id] = word
    line.submit(p.id, bit=p.bits[0] if p.bits else -1, write=True, value=value)
    line.submit(p.id, bit=p.bits[0] if p.bits else -1, write=True, value=value + 0.5)
    line.run(2000)
    assert line.words[p.id] == expected
    assert [r.outcome for r in line.results] == [Outcome.OK, Outcome.RANGE]
    assert line.results[0].value == value


def test_a_value_read_is_exact_and_reaches_the_program_as_a_fraction():
    # 4.2.11 gen rated voltage, U·KWUGNSEK/400 (4.2.10): the word 230 with KWUGNSEK 397 is
    # 230·400/397 V; MPU2S_PARAM gets numerator and denominator and divides them in LREAL
    line = Line()
    line.words[KWUGNSEK_ID] = 397
    line.words[296] = 230
    line.submit(296)
    line.run(1000)
    [result] = line.results
    assert result.exact == Fraction(230 * 400, 397) and result.value == 92000 / 397
    mgmt = [1] + [0] * (MGMT_WORDS - 1)
    finish(mgmt, False, result)
    numerator, denominator = mgmt[3] << 16 | mgmt[4], mgmt[6] << 16 | mgmt[7]
    assert (numerator, denominator, mgmt[0], mgmt[2]) == (92000, 397, 0, 230)


def test_a_write_the_device_does_not_take_fails_the_read_back():
    line = Line()
    line.hold.add(DF_MAX.id)
    line.submit(DF_MAX.id, write=True, value=0.20)
    line.run(1000)
    [result] = line.results
    assert result.outcome == Outcome.VERIFY
    assert "0x0033" in result.message and "0x0026" in result.message
