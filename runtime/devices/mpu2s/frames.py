"""MPU2-S CAN frames: identifiers, the byte-0 kinds, the XOR checksum, and
the encoders and decoders of requests, replies and telegram frames. Pure: no
bus, no clock.

    read_request(1, 500)                        # bytes FF 01 01 F4 00 00 FE F5, on REQUEST_ID
    write_request(1, 11, 12800)                 # bytes EE 01 00 0B 32 00 DC 0A (50.00 Hz)
    decode_reply(0x321, data)                   # Reply(kind=0xFF, device=1, param_id=11, raw=12800)
    decode_telegram(0x321, data)                # (1, mux, (w1, w2, w3))

Sources (manual 004 ch. 2, digest 004 §1):
- The bus is raw CAN 2.0A, 11-bit identifiers, every frame 8 bytes, no
  CANopen (§1.1).
- Device -> master: CAN-ID 320h + Gerätenummer, for the cyclic telegram
  (byte 0 DDh) and for the read (FFh) and write (EEh) replies. Master ->
  device: CAN-ID 33Fh for every device, byte 0 FFh read, EEh write, byte 1
  the addressed device's number (§1.2, §1.3).
- Every 16-bit word is big-endian (§1.6). Requests and replies: bytes 2/3
  the parameter ID, 4/5 the data word (0 in a read request), 6/7 the
  checksum Byte6 = B0^B2^B4, Byte7 = B1^B3^B5 (§1.4, §1.5). The telegram
  frame has no checksum: byte 1 is the mux number, bytes 2-7 three data
  words (§1.4 a).

Decided where the manual is unclear (digest 004 §7):
- A9: the range of device numbers is not stated; 1..30. Device 31 would
  send on 33Fh, the request identifier, and 0 (320h) is nowhere used.
- A2: the mux listing is garbled; one mux number per frame, 0..22 on the
  MPU2-S (ch. 3: 69 words, 23 frames). A larger mux is refused.
- A10: the manual defines no error reply; a frame that breaks one of the
  rules above is MalformedFrame, and what to do with it (count, drop) is
  the driver's business.

Signed words go on the bus as their two's complement (§1.6, cos φ table):
to_word(-100) is FF9Ch, from_word(0xFF9C) is -100.
"""

from __future__ import annotations

from dataclasses import dataclass

TELEGRAM_ID_BASE = 0x320  # CAN-ID of device n: 320h + n (§1.2)
REQUEST_ID = 0x33F  # every read and write request (§1.2)
DLC = 8  # "8 Byte Messagelänge" (§1.1)

KIND_TELEGRAM = 0xDD  # "steht im Byte 0 immer der hexadezimale Wert DD" (§1.3)
KIND_READ = 0xFF  # read request and read reply (§1.3)
KIND_WRITE = 0xEE  # write request and write reply (§1.3)
KINDS = (KIND_TELEGRAM, KIND_READ, KIND_WRITE)

DEVICE_MIN = 1  # A9
DEVICE_MAX = 30  # A9: 31 would be 33Fh
MUX_MAX = 22  # 23 frames, mux 0..22 (ch. 3; A2)
WORD_MAX = 0xFFFF


class MalformedFrame(ValueError):
    """A frame that is no valid MPU2-S frame; ``reason`` says why."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


@dataclass(frozen=True)
class Reply:
    """A request or a reply: kind KIND_READ or KIND_WRITE, the device number
    of byte 1, the parameter ID of bytes 2/3 and the data word of bytes 4/5
    (0..FFFFh, as on the bus)."""

    kind: int
    device: int
    param_id: int
    raw: int


def to_word(value: int) -> int:
    """A signed value -32768..32767 (or an unsigned word 0..65535) -> the word
    on the bus, two's complement for a negative value (§1.6)."""
    if not -0x8000 <= value <= WORD_MAX:
        raise ValueError(f"{value} does not fit a 16-bit word (-32768..65535)")
    return value & WORD_MAX


def from_word(word: int) -> int:
    """A word from the bus read as a signed 16-bit value (two's complement)."""
    _check_word(word, "word")
    return word - 0x10000 if word & 0x8000 else word


def device_can_id(device: int) -> int:
    """The CAN-ID a device sends on: 320h + device number (§1.2)."""
    _check_device(device)
    return TELEGRAM_ID_BASE + device


def device_of(can_id: int) -> int:
    """The device number of a device -> master CAN-ID; MalformedFrame for any other ID."""
    device = can_id - TELEGRAM_ID_BASE
    if not DEVICE_MIN <= device <= DEVICE_MAX:
        raise MalformedFrame(f"CAN-ID {can_id:03X}h is no MPU2-S device's (321h..33Eh)")
    return device


def checksum(head: bytes) -> bytes:
    """Bytes 6 and 7 of the first six: B0^B2^B4, B1^B3^B5 (§1.5)."""
    if len(head) != 6:
        raise ValueError(f"the checksum covers 6 bytes, not {len(head)}")
    return bytes((head[0] ^ head[2] ^ head[4], head[1] ^ head[3] ^ head[5]))


def _check_device(device: int) -> None:
    if not DEVICE_MIN <= device <= DEVICE_MAX:
        raise ValueError(f"device number {device} is outside {DEVICE_MIN}..{DEVICE_MAX} (A9)")


def _check_word(value: int, what: str) -> None:
    if not 0 <= value <= WORD_MAX:
        raise ValueError(f"{what} {value} is outside 0..65535")


def _frame(kind: int, byte1: int, param_id: int, raw: int) -> bytes:
    _check_word(param_id, "parameter ID")
    _check_word(raw, "raw value")
    head = bytes((kind, byte1)) + param_id.to_bytes(2, "big") + raw.to_bytes(2, "big")
    return head + checksum(head)


def read_request(device: int, param_id: int) -> bytes:
    """The 8 data bytes of a read request, sent on REQUEST_ID (§1.4 b)."""
    _check_device(device)
    return _frame(KIND_READ, device, param_id, 0)


def write_request(device: int, param_id: int, raw: int) -> bytes:
    """The 8 data bytes of a write request, sent on REQUEST_ID (§1.4 c); raw
    is the word 0..FFFFh (to_word() for a negative value)."""
    _check_device(device)
    return _frame(KIND_WRITE, device, param_id, raw)


def reply(kind: int, device: int, param_id: int, raw: int) -> bytes:
    """The 8 data bytes of a device's read (KIND_READ) or write (KIND_WRITE)
    reply, sent on device_can_id(device) (§1.4 d, e)."""
    if kind not in (KIND_READ, KIND_WRITE):
        raise ValueError(f"a reply is of kind FFh or EEh, not {kind:02X}h")
    _check_device(device)
    return _frame(kind, device, param_id, raw)


def telegram_frame(mux: int, words: tuple[int, int, int]) -> bytes:
    """The 8 data bytes of telegram frame mux (§1.4 a): DDh, mux, three words."""
    if not 0 <= mux <= MUX_MAX:
        raise ValueError(f"mux {mux} is outside 0..{MUX_MAX}")
    if len(words) != 3:
        raise ValueError(f"a telegram frame carries 3 words, not {len(words)}")
    for word in words:
        _check_word(word, "telegram word")
    return bytes((KIND_TELEGRAM, mux)) + b"".join(w.to_bytes(2, "big") for w in words)


def _check_length(data: bytes) -> None:
    if len(data) != DLC:
        raise MalformedFrame(f"DLC {len(data)}, an MPU2-S frame has 8 bytes")


def _decode_checked(data: bytes) -> Reply:
    """Bytes of a request or a reply: length, kind and checksum checked."""
    _check_length(data)
    if data[0] not in (KIND_READ, KIND_WRITE):
        raise MalformedFrame(f"byte 0 is {data[0]:02X}h, not FFh (read) or EEh (write)")
    if data[6:8] != checksum(data[:6]):
        raise MalformedFrame(f"checksum {data[6]:02X} {data[7]:02X}, expected {checksum(data[:6]).hex(' ').upper()}")
    return Reply(data[0], data[1], int.from_bytes(data[2:4], "big"), int.from_bytes(data[4:6], "big"))


def decode_reply(can_id: int, data: bytes) -> Reply:
    """A device's read or write reply (§1.4 d, e). MalformedFrame: not 8
    bytes, byte 0 not FFh/EEh, a wrong checksum, a CAN-ID that is no
    device's, or byte 1 not the device number of the CAN-ID."""
    device = device_of(can_id)
    got = _decode_checked(data)
    if got.device != device:
        raise MalformedFrame(f"byte 1 names device {got.device}, the CAN-ID {can_id:03X}h device {device}")
    return got


def decode_request(can_id: int, data: bytes) -> Reply:
    """A master's read or write request on 33Fh (§1.4 b, c), as a simulated
    device reads it. MalformedFrame: another CAN-ID, not 8 bytes, byte 0
    not FFh/EEh, a wrong checksum, or a device number outside 1..30."""
    if can_id != REQUEST_ID:
        raise MalformedFrame(f"CAN-ID {can_id:03X}h, requests come on {REQUEST_ID:03X}h")
    got = _decode_checked(data)
    if not DEVICE_MIN <= got.device <= DEVICE_MAX:
        raise MalformedFrame(f"byte 1 names device {got.device}, outside {DEVICE_MIN}..{DEVICE_MAX} (A9)")
    return got


def decode_telegram(can_id: int, data: bytes) -> tuple[int, int, tuple[int, int, int]]:
    """A telegram frame (§1.4 a) -> (device, mux, (w1, w2, w3)), the words
    unsigned. MalformedFrame: not 8 bytes, byte 0 not DDh, a CAN-ID that is
    no device's, or a mux above 22."""
    device = device_of(can_id)
    _check_length(data)
    if data[0] != KIND_TELEGRAM:
        raise MalformedFrame(f"byte 0 is {data[0]:02X}h, a telegram frame has DDh")
    if data[1] > MUX_MAX:
        raise MalformedFrame(f"mux {data[1]} is above {MUX_MAX} (A2)")
    w1, w2, w3 = (int.from_bytes(data[i : i + 2], "big") for i in (2, 4, 6))
    return device, data[1], (w1, w2, w3)
