"""PDOs between the CAN frame and the process image.

A configured PDO is a list of mapped objects (index, subindex, bit length)
packed one after the other into the frame, little-endian (CiA 301), each
tied to an image address. CANopen data and image words are both
little-endian, so a 16-bit object mapped to %IW0 is a plain byte copy; a
1-bit object goes to a bit address (%IX0.3).

    binding = PdoBinding.from_config(pdo_cfg, "tpdo", od, probe_image)
    binding.unpack(frame_data, image)     # TPDO: frame -> %I   (scan thread)
    data = binding.pack(image)            # RPDO: %Q -> frame   (scan thread)

The transmission side (when a master sends an RPDO: on change, inhibit
time, event timer, SYNC) is TxSchedule.
"""

from __future__ import annotations

from dataclasses import dataclass

from ...image.memory import ProcessImage
from ...plugin.driver import DriverError
from ...st import types as T
from .cia301 import RPDO_COMM, RPDO_MAP, TPDO_COMM, TPDO_MAP, cob_rpdo, cob_tpdo, mapping_entry

_SIZE_BITS = {"B": 8, "W": 16, "D": 32, "L": 64}


def default_cob_id(direction: str, number: int, node_id: int) -> int:
    """The CiA 301 pre-defined connection set: PDO 1..4 only."""
    if not 1 <= number <= 4:
        raise ValueError(f"PDO {number} has no pre-defined COB-ID; the node must be configured with one")
    return (cob_tpdo if direction == "tpdo" else cob_rpdo)(number, node_id)


@dataclass(frozen=True)
class MappedEntry:
    index: int
    subindex: int
    bits: int
    bit_offset: int  # in the frame
    address: object  # LocatedAddress
    area: str
    byte_offset: int | None  # in the image area; None for a bit address
    key: str

    @property
    def mapping_value(self) -> int:
        """The 32-bit mapping entry written to 0x16xx / 0x1Axx (CiA 301)."""
        return mapping_entry(self.index, self.subindex, self.bits)


class PdoBinding:
    """One PDO of one node: its mapping and its place in the image."""

    def __init__(
        self,
        direction: str,
        number: int,
        entries: list,
        *,
        transmission: int = 255,
        inhibit_us: int = 0,
        event_ms: int = 0,
        configure: bool = True,
        key: str = "",
    ) -> None:
        self.direction = direction  # "tpdo" (node -> image) or "rpdo" (image -> node)
        self.number = number
        self.entries: list[MappedEntry] = entries
        self.transmission = transmission
        self.inhibit_us = inhibit_us
        self.event_ms = event_ms
        self.configure = configure
        self.key = key
        self.nbytes = (sum(e.bits for e in entries) + 7) // 8
        self.cob_id: int | None = None  # read from the node at boot
        # Every entry whole bytes at a byte address: the frame and the image swap
        # plain byte runs, (frame offset, image offset, bytes) per entry; None
        # when an entry needs shifting.
        copies = [
            (e.bit_offset // 8, e.byte_offset, e.bits // 8)
            for e in self.entries
            if e.bits % 8 == 0 and e.bit_offset % 8 == 0 and e.byte_offset is not None
        ]
        self._byte_copies: list[tuple[int, int, int]] | None = copies if len(copies) == len(entries) else None
        # The frame one run of bytes of the image (each entry right after the
        # one before, in the frame as in the image): pack() is one slice.
        self._span: tuple[int, int] | None = None
        if self._byte_copies:
            first = self._byte_copies[0][1]
            if all(start == offset - first for start, offset, _n in self._byte_copies) and all(
                a[0] + a[2] == b[0] for a, b in zip(self._byte_copies, self._byte_copies[1:])
            ):
                self._span = (first, first + sum(n for _s, _o, n in self._byte_copies))

    @property
    def comm_index(self) -> int:
        return (TPDO_COMM if self.direction == "tpdo" else RPDO_COMM) + self.number - 1

    @property
    def map_index(self) -> int:
        return (TPDO_MAP if self.direction == "tpdo" else RPDO_MAP) + self.number - 1

    @classmethod
    def from_config(cls, cfg, direction: str, od, probe: ProcessImage) -> PdoBinding:
        """Resolve a config PdoConfig against the node's object dictionary.
        DriverError names the config key of anything that cannot work."""
        entries = []
        offset = 0
        want_area = "I" if direction == "tpdo" else "Q"
        for e in cfg.entries:
            try:
                var = od.get_variable(e.index, e.subindex)
                if var is None:
                    raise KeyError(e.index)
            except KeyError:
                raise DriverError(f"{e.key}: object {e.index:04X}:{e.subindex:02X} is not in the node's EDS") from None
            if not var.fixed_size:
                raise DriverError(
                    f"{e.key}: object {e.index:04X}:{e.subindex:02X} has no fixed size and cannot be mapped"
                )
            if not getattr(var, "pdo_mappable", True):
                raise DriverError(
                    f"{e.key}: object {e.index:04X}:{e.subindex:02X} ({var.name}) is not PDO-mappable in the EDS"
                )
            bits = len(var)
            addr = e.address
            if addr.area != want_area:
                raise DriverError(f"{e.key}: a {direction.upper()} maps to %{want_area} addresses, not {addr.text}")
            if addr.bit is not None or addr.size in ("", "X"):
                if bits != 1:
                    raise DriverError(
                        f"{e.key}: {addr.text} is a bit but {e.index:04X}:{e.subindex:02X} has {bits} bits"
                    )
                byte_offset = None
            else:
                size = _SIZE_BITS.get(addr.size)
                if size != bits:
                    raise DriverError(
                        f"{e.key}: {e.index:04X}:{e.subindex:02X} ({var.name}) has {bits} "
                        f"bits but {addr.text} holds {size}"
                    )
                _area, byte_offset, _n = probe.region(addr)
            entries.append(MappedEntry(e.index, e.subindex, bits, offset, addr, addr.area, byte_offset, e.key))
            offset += bits
        if offset > 64:
            raise DriverError(f"{cfg.key}: the mapped objects need {offset} bits; a PDO carries 64 (8 bytes)")
        return cls(
            direction,
            cfg.number,
            entries,
            transmission=cfg.transmission,
            inhibit_us=cfg.inhibit_us,
            event_ms=cfg.event_ms,
            configure=cfg.configure,
            key=cfg.key,
        )

    # ------------------------------------------------------------ data

    def unpack(self, data: bytes, image: ProcessImage) -> None:
        """A received TPDO's bytes into the %I area. A frame shorter than the
        mapping leaves the missing objects as they were (CiA 301 says such a
        PDO is not to be processed; the driver counts it as an error)."""
        area = image.areas["I"]
        if self._span is not None and len(data) >= self._span[1] - self._span[0]:
            first, end = self._span
            area[first:end] = data[: end - first]
            return
        if self._byte_copies is not None:
            for start, offset, n in self._byte_copies:
                area[offset : offset + n] = data[start : start + n]
            return
        raw = int.from_bytes(data, "little")
        for e in self.entries:
            value = (raw >> e.bit_offset) & ((1 << e.bits) - 1)
            if e.byte_offset is None:
                image.write(e.address, bool(value), T.BOOL)
            else:
                n = e.bits // 8
                area[e.byte_offset : e.byte_offset + n] = value.to_bytes(n, "little")

    def pack(self, image: ProcessImage) -> bytes:
        """The %Q values of this RPDO as frame bytes."""
        area = image.areas["Q"]
        if self._span is not None:
            return bytes(area[self._span[0] : self._span[1]])
        if self._byte_copies is not None:
            return b"".join(bytes(area[offset : offset + n]) for _start, offset, n in self._byte_copies)
        raw = 0
        for e in self.entries:
            if e.byte_offset is None:
                value = 1 if image.read(e.address, T.BOOL) else 0
            else:
                value = int.from_bytes(area[e.byte_offset : e.byte_offset + e.bits // 8], "little")
            raw |= value << e.bit_offset
        return raw.to_bytes(self.nbytes, "little")


class TxSchedule:
    """When a master sends one RPDO (CiA 301 transmission types as the
    master applies them to what it sends):

      254/255  event-driven: on change, no sooner than the inhibit time after
               the previous frame, and again every event time (0 = never)
               even without change, so a node that missed a frame catches up
      0        after the next SYNC, if changed
      1..240   after every n-th SYNC
    """

    def __init__(self, transmission: int, inhibit_us: int, event_ms: int) -> None:
        self.transmission = transmission
        self.inhibit_ns = inhibit_us * 1000
        self.event_ns = event_ms * 1_000_000
        self.last_sent: bytes | None = None
        self.last_ns: int | None = None
        self._syncs = 0

    def reset(self) -> None:
        """Forget what was sent: the next chance sends (node (re)started)."""
        self.last_sent = None
        self.last_ns = None
        self._syncs = 0

    def due(self, data: bytes, now_ns: int, sync: bool) -> bool:
        t = self.transmission
        if t >= 254:
            if self.last_sent is None or self.last_ns is None:  # nothing sent yet (sent() sets both)
                return True
            if now_ns - self.last_ns < self.inhibit_ns:
                return False
            if data != self.last_sent:
                return True
            return self.event_ns > 0 and now_ns - self.last_ns >= self.event_ns
        if not sync:
            return False
        if t == 0:
            return data != self.last_sent
        self._syncs += 1
        if self._syncs >= t:
            self._syncs = 0
            return True
        return False

    def sent(self, data: bytes, now_ns: int) -> None:
        self.last_sent = data
        self.last_ns = now_ns
