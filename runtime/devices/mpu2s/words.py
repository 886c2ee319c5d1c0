"""The MPU2-S's frames in the manual's words, for `softplc log`
(PlainCanKind.frame_text): a read or write request on 33Fh and its reply
on 320h + device (manual 004 §1.3-1.5) with the parameter's name of
chapter 4 (parameters.py) and the raw data word; a telegram frame (byte 0
DDh) with its mux and its three words by their Nr and name (ch. 3,
telegram.py), raw, as the bus carries them (their scaling needs other
words of the telegram: the program's MPU2S blocks do it)."""

from __future__ import annotations

from . import frames, parameters
from .telegram import FIXED_CODINGS, WORD_TABLE, Word, fixed_value


def _parameter(param_id: int) -> str:
    found = parameters.by_id(param_id)
    return f"ID {param_id} {found[0].name_en}" if found else f"ID {param_id}"


def _scaled(w: Word, raw: int) -> str:
    """A word whose value needs no other word, in a unit of its own (1/100 Hz ...),
    also as that value: 5030 (50.30 Hz)."""
    divisor = FIXED_CODINGS.get(w.coding, 1)
    if divisor == 1:
        return str(raw)
    digits = len(str(divisor)) - 1
    unit = w.unit.removeprefix(f"1/{divisor}").strip()
    return f"{raw} ({fixed_value(w, raw):.{digits}f}{' ' + unit if unit else ''})"


def frame_text(options, can_id: int, data: bytes) -> str | None:
    """The words of a frame of the device options.device, or None when not its."""
    device = options.device
    if can_id == frames.REQUEST_ID:
        try:
            request = frames.decode_request(can_id, data)
        except frames.MalformedFrame as exc:
            return f"malformed request: {exc.reason}" if len(data) > 1 and data[1] == device else None
        if request.device != device:
            return None
        if request.kind == frames.KIND_READ:
            return f"read {_parameter(request.param_id)}"
        return f"write {_parameter(request.param_id)} = {request.raw}"
    if can_id != frames.device_can_id(device):
        return None
    if data[:1] == bytes([frames.KIND_TELEGRAM]):
        try:
            _device, mux, words = frames.decode_telegram(can_id, data)
        except frames.MalformedFrame as exc:
            return f"malformed telegram frame: {exc.reason}"
        named = [
            f"Nr {w.nr} {w.english} = {_scaled(w, raw)}" for w, raw in zip(WORD_TABLE[3 * mux : 3 * mux + 3], words)
        ]
        return f"telegram mux {mux}: " + " | ".join(named)
    try:
        reply = frames.decode_reply(can_id, data)
    except frames.MalformedFrame as exc:
        return f"malformed reply: {exc.reason}"
    verb = "read" if reply.kind == frames.KIND_READ else "written"
    return f"{verb} {_parameter(reply.param_id)} = {reply.raw}"


__all__ = ["frame_text"]
