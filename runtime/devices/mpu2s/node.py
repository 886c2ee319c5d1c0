"""One MPU2-S on plain CAN, as the PLC drives it (io/plaincan): a
[[plaincan]] table of type "mpu2s".

    [[plaincan]]
    type = "mpu2s"
    device = 1                 # its Gerätenummer: telegram and replies on 321h
    telegram = "%IW300"        # the 69 words land here, Nr 1 first (optional)
    password = 1234            # ID 500, sent before the first write (optional)
    timeout = "300ms"          # a request's reply; retries = 2; pace = "100ms"
    stale = "1s"               # no telegram frame for this long: the device is lost

Received (321h + n): the telegram frames (DDh) go to the TelegramAssembler
(telegram.py), the read and write replies (FFh, EEh) to the RequestEngine
(requests.py). At each cycle start the 69 words are copied into the image,
MPU2S_DEVICE[n] (fblocks/vendor/mpu2s.st) gets the device's state, and the
requests that ended hand their results to the program's tables.

Communication: the device is up once a telegram frame came within `stale`
(digest 004 §6.2: about 3 x 100 ms is the shortest the manual allows; 1 s
is the default here, so one late frame does not count as a loss). Lost,
the words keep their last values, MPU2S_DEVICE[n].CommOk is FALSE, and
the password is given again before the next write (A11).
"""

from __future__ import annotations

import struct
from dataclasses import dataclass
from typing import Annotated, Any

from pydantic import Field, PlainValidator

from ...config.errors import key_text
from ...config.values import duration_in, fail, int_range
from ...image.address import parse_address
from ...image.memory import ProcessImage
from ...io.plaincan import MalformedFrame, NodeContext, NodeOptions, PlainCanNodeConfig
from ...plugin.driver import DriverStatus
from ...program import StructWriter
from ...program import global_variable as _global
from ...st import types as T
from . import frames
from .exchange import SERVICE, Mpu2sExchangeService
from .requests import MS, Request, RequestEngine, Result
from .telegram import TelegramAssembler

WORDS = 69  # Nr 1..69 (ch. 3)
#: the 69 words into the image at once, as the words' accessors store them one by one (<H)
_TELEGRAM_WORDS = struct.Struct(f"<{WORDS}H")
#: MPU2S_DEVICE_T's values (fblocks/vendor/mpu2s.st) -> the telegram's keys (telegram.py)
VALUES = {
    "FGen": "f_gen",
    "FBus": "f_bus",
    "FMains": "f_mains",
    "UGen": "u_gen_l12",
    "UGenL23": "u_gen_l23",
    "UGenL31": "u_gen_l31",
    "UBus": "u_bus_l12",
    "UMains": "u_mains_l12",
    "IL1": "i_gen_l1",
    "IL2": "i_gen_l2",
    "IL3": "i_gen_l3",
    "P": "p_gen",
    "Q": "q_gen",
    "PSet": "p_set",
    "CosPhi": "cos_phi",
    "Battery": "battery",
}
STATUS_WORDS = {"FaultClasses": 9, "Control2": 10, "Control1": 12}


def _float(value) -> float:
    return 0.0 if value is None else float(value)


@dataclass
class Mpu2sSettings:
    device: int
    telegram: str | None
    password: int | None
    timeout_ms: int
    retries: int
    pace_ms: int
    stale_ms: int
    variant: int | None


class Mpu2sOptions(NodeOptions):
    device: Annotated[int, int_range(frames.DEVICE_MIN, frames.DEVICE_MAX)] = Field(
        description=f"the device number (Gerätenummer), {frames.DEVICE_MIN} to {frames.DEVICE_MAX}"
    )
    telegram: Any = Field(None, description='where the 69 telegram words land, such as "%IW300"')
    password: Annotated[int, int_range(0, 9999)] | None = Field(None, description="the code level 2 password, 0..9999")
    timeout: Annotated[int, PlainValidator(duration_in("ms"))] = Field(300, description="a duration such as 300ms")
    retries: Annotated[int, int_range(0, 10)] = Field(2, description="an integer from 0 to 10")
    pace: Annotated[int, PlainValidator(duration_in("ms"))] = Field(100, description="a duration such as 100ms")
    stale: Annotated[int, PlainValidator(duration_in("ms"))] = Field(1000, description="a duration such as 1s")
    variant: Annotated[int, PlainValidator(lambda v: _variant(v))] | None = Field(
        None, description="100 or 400: the device's voltage input (parameters.py)"
    )

    @classmethod
    def check(cls, here: tuple, table: dict, ctx) -> None:
        text = table.get("telegram")
        if text is None:
            return
        addr = ctx.address(here + ("telegram",), text, '"%IW300"')
        if addr is None:
            return
        loc = here + ("telegram",)
        if addr.area != "I" or addr.size != "W" or addr.table is not None or addr.bit is not None:
            ctx.error(loc, f"expected the first input word of the {WORDS}, such as %IW300 (got {text!r})")
            return
        bits = ctx.image_bits(loc, addr)
        if bits is None:
            return
        first, last = bits[0], bits[0] + 16 * WORDS - 1
        if last >= 8 * ctx.probe().size:
            ctx.error(loc, f"the {WORDS} words from {text} do not fit in the %I area")
            return
        other = ctx.claim("I", first, last, loc, f"{text} and the {WORDS - 1} words after it")
        if other is not None:
            ctx.error(loc, f"the {WORDS} words from {text} overlap {other[1]} ({key_text(other[0])})")

    @classmethod
    def ids(cls, table: dict) -> tuple[set[int], set[int]]:
        device = table.get("device")
        if not isinstance(device, int) or isinstance(device, bool):
            return set(), set()
        return {frames.TELEGRAM_ID_BASE + device}, {frames.REQUEST_ID}

    @classmethod
    def default_name(cls, kind: str, table: dict) -> str | None:
        device = table.get("device")
        return f"{kind}_{device}" if isinstance(device, int) and not isinstance(device, bool) else None

    def build(self) -> Mpu2sSettings:
        return Mpu2sSettings(
            self.device,
            self.telegram,
            self.password,
            self.timeout,
            self.retries,
            self.pace,
            self.stale,
            self.variant,
        )


def _variant(value) -> int:
    if value in (100, 400) and not isinstance(value, bool):
        return value
    raise fail("100 or 400", value)


class Mpu2sNode:
    def __init__(self, cfg: PlainCanNodeConfig, ctx: NodeContext) -> None:
        s: Mpu2sSettings = cfg.options
        self.name = cfg.name
        self.device = s.device
        self.settings = s
        self.clock = ctx.clock
        self.lock = ctx.lock
        self.lines = ctx.lines  # a device that comes and goes must not flood the log
        self.receives = frozenset({frames.device_can_id(s.device)})
        self.assembler = TelegramAssembler()
        self.engine = RequestEngine(
            s.device,
            ctx.send,
            password=s.password,
            timeout_ns=s.timeout_ms * MS,
            retries=s.retries,
            pace_ns=s.pace_ms * MS,
            variant=s.variant,
        )
        service = ctx.shared.setdefault(SERVICE, Mpu2sExchangeService())
        service.add(s.device, self.submit)
        self.services = {SERVICE: service}
        self.frames = 0  # telegram frames taken
        self._last_frame: int | None = None
        self._shown_version = -1  # the assembler's version _shown was decoded from
        self._shown: dict = {}
        self._up = False
        self._finished: list[tuple[Any, Result]] = []
        self._diag: StructWriter | None = None
        self._setters: list | None = None  # the image's 69 words, once the image is known
        self._block: tuple | None = None  # (area, byte offset) of the 69 words when they are one run of bytes

    # ------------------------------------------------------------ the bus side (under the driver's lock)

    def on_frame(self, can_id: int, data: bytes, now_ns: int) -> None:
        try:
            if data[:1] == bytes([frames.KIND_TELEGRAM]):
                _device, mux, words = frames.decode_telegram(can_id, data)
                self.assembler.feed(mux, words, now_ns)
                self.frames += 1
                self._last_frame = now_ns
                if not self._up:
                    self._up = True
                    self.lines.info(("heard", self.name), "%s: device %d heard", self.name, self.device)
            else:
                self.engine.on_reply(frames.decode_reply(can_id, data), now_ns)
        except frames.MalformedFrame as exc:
            raise MalformedFrame(exc.reason) from None

    def advance(self, now_ns: int) -> None:
        if self._up and (self._last_frame is None or now_ns - self._last_frame > self.settings.stale_ms * MS):
            self._up = False
            self.engine.comm_lost()
            self.lines.warning(
                ("stale", self.name),
                "%s: no telegram from device %d for %d ms",
                self.name,
                self.device,
                self.settings.stale_ms,
            )
        self.engine.advance(now_ns)

    def submit(self, request: Request) -> None:
        """From MPU2S_EXCHANGE (the scan thread): the result is handed back at a cycle start."""
        done = request.done
        request.done = lambda result: self._finished.append((done, result))
        with self.lock:
            self.engine.submit(request)

    # ------------------------------------------------------------ the scan

    def read_inputs(self, image: ProcessImage, now_ns: int) -> None:
        if self.settings.telegram is not None and self.frames:
            if self._setters is None:
                first = parse_address(self.settings.telegram, image.addressing)
                word = first.indices[0]
                addresses = [parse_address(f"%IW{word + i}", image.addressing) for i in range(WORDS)]
                self._setters = [image.accessor(addr, T.WORD)[1] for addr in addresses]
                area, offset, _ = image.region(addresses[0])
                if image.region(addresses[-1])[1] == offset + 2 * (WORDS - 1):  # one run of bytes
                    self._block = (image.areas[area], offset)
            words = self.assembler.words
            if self._block is not None and self.assembler.complete:  # every word came: all 69 at once
                _TELEGRAM_WORDS.pack_into(*self._block, *words[1:])
            else:
                for nr, setter in enumerate(self._setters, start=1):
                    word = words[nr]
                    if word is not None:
                        setter(word)
        finished, self._finished = self._finished, []
        for done, result in finished:
            done(result)
        if self._diag is not None:
            self._show(now_ns)

    def write_outputs(self, image: ProcessImage) -> None:
        # what the scan asked for goes out at its end, when the pace allows
        self.engine.advance(self.clock.now_ns())

    def bind_program(self, globals_obj) -> None:
        table = _global(globals_obj, "MPU2S_DEVICE")
        if table is not None and self.device < len(table):
            self._diag = StructWriter(table[self.device])
            self._diag.set(Configured=True)

    def _show(self, now_ns: int) -> None:
        assert self._diag is not None
        age = None if self._last_frame is None else (now_ns - self._last_frame) // MS
        e, t = self.engine, self.assembler
        if self._shown_version != t.version:  # decoded again only when a frame came
            self._shown_version = t.version
            self._shown = self._telegram_fields()
        self._diag.set(
            CommOk=self._up,
            AgeMs=min(age if age is not None else 0xFFFFFFFF, 0xFFFFFFFF),
            Frames=self.frames,
            Requests=e.sent,
            Timeouts=e.timeouts,
            Failed=e.failed,
            **self._shown,
        )

    def _telegram_fields(self) -> dict:
        """MPU2S_DEVICE_T's fields that come from the telegram's words."""
        t = self.assembler
        return {
            "Complete": t.complete,
            "MainsPresent": t.value("mains_present") is True,
            "GenPresent": t.value("generator_present") is True,
            "BusPresent": t.value("busbar_present") is True,
            "Hours": int(t.value("hours") or 0),
            "EnergyKwh": int(t.value("energy_kwh") or 0),
            "Starts": int(t.value("starts") or 0),
            **{field: _float(t.value(key)) for field, key in VALUES.items()},
            **{field: t.words[nr] or 0 for field, nr in STATUS_WORDS.items()},
        }

    def status(self) -> DriverStatus:
        if self._up:
            return DriverStatus(True, "")
        heard = "lost" if self.frames else "not heard yet"
        return DriverStatus(False, f"{self.name}: {heard}")

    def stop(self) -> None:
        pass
