"""The loopback driver: a "bus" that is a wire from %Q bytes back to %I bytes.

It is the reference example of the driver interface (plugin/driver.py) for the
CANopen and Modbus drivers: the same life cycle, the same double buffer under
a lock, the same validation before the first cycle. Only the bus is missing:

    scan thread                     the wire (here)       scan thread
    write_outputs: %Q -> _wire  ──────────────────────>   read_inputs: _wire -> %I
         (end of cycle n)                                   (start of cycle n+1)

A real driver has two buffers (outputs the bus thread sends, inputs it
received); the loopback's bus delivers what it was given, so one buffer
serves both. It is still guarded by a lock as if a bus thread used it.

A value the program writes to %Q in cycle n is in %I in cycle n+1: one cycle
of latency, deterministic, no thread and no timing involved. Before the first
write_outputs the inputs read as zeros (a bus that has sent nothing yet).

    drv = LoopbackDriver("loopback[0]", [("%QW0", "%IW10", 2), ("%QB4", "%IB24", 4)])
"""

from __future__ import annotations

import threading
from collections.abc import Iterable
from dataclasses import dataclass

from ...image.address import AddressError, parse_address
from ...image.memory import ProcessImage
from ...plugin.driver import Driver, DriverError, DriverStatus
from ...st.ast import LocatedAddress


@dataclass(frozen=True)
class Link:
    """nbytes bytes from source (in %Q) looped to target (in %I)."""

    source: LocatedAddress
    target: LocatedAddress
    nbytes: int

    def __str__(self) -> str:
        return f"{self.source.text} -> {self.target.text}, {self.nbytes} byte{'s' * (self.nbytes != 1)}"


class LoopbackDriver(Driver):
    def __init__(self, name: str, links: Iterable, addressing: str = "iec", size: int | None = None) -> None:
        """links: (source, target, nbytes) with addresses as strings or
        LocatedAddress; nbytes None copies the source address's own width
        (2 for %QW0, 8 for %QW0:4). addressing and size are those of the
        image the engine will hand in (the profile's model, 64 KiB areas by
        default). A bad link raises DriverError naming it."""
        self.name = name
        # The regions are resolved once, here, so a bad link fails before the
        # first cycle and the copies in the scan thread are plain slices.
        try:
            probe = ProcessImage(addressing) if size is None else ProcessImage(addressing, size)
        except ValueError as exc:
            raise DriverError(f"{name}: {exc}") from None
        self.addressing = probe.addressing
        self.size = probe.size
        self.links: list[Link] = []
        self._copies: list[tuple] = []  # (q offset, wire offset, i offset, nbytes)
        wire_used = 0
        for i, spec in enumerate(links):
            link, q_off, i_off = self._resolve(i, spec, probe)
            # Two links into the same input bytes: which one wins would be an accident.
            for j, (_q, _w, other_off, other_n) in enumerate(self._copies):
                if i_off < other_off + other_n and other_off < i_off + link.nbytes:
                    raise DriverError(
                        f"{self.name}: link {i} ({link}) writes inputs that link {j} ({self.links[j]}) already writes"
                    )
            self.links.append(link)
            self._copies.append((q_off, wire_used, i_off, link.nbytes))
            wire_used += link.nbytes
        self._lock = threading.Lock()
        self._wire = bytearray(wire_used)
        self.exchanges = 0  # write_outputs calls: frames "sent" on the wire

    def _resolve(self, i: int, spec, probe: ProcessImage) -> tuple:
        """(Link, %Q byte offset, %I byte offset) of one link spec."""
        try:
            source, target, *rest = spec
            if len(rest) > 1:
                raise ValueError
        except (TypeError, ValueError):
            raise DriverError(f"{self.name}: link {i} must be (source, target, nbytes), not {spec!r}") from None
        nbytes = rest[0] if rest else None
        where = f"{self.name}: link {i} ({_text(source)} -> {_text(target)})"
        try:
            src = source if isinstance(source, LocatedAddress) else parse_address(source, self.addressing)
            dst = target if isinstance(target, LocatedAddress) else parse_address(target, self.addressing)
            if src.area != "Q" or dst.area != "I":
                raise AddressError(f"a link copies %Q outputs to %I inputs, not %{src.area} to %{dst.area}")
            _, q_off, width = probe.region(src)
            _, i_off, _ = probe.region(dst)
        except AddressError as exc:
            raise DriverError(f"{where}: {exc}") from None
        if nbytes is None:
            nbytes = width
        if isinstance(nbytes, bool) or not isinstance(nbytes, int) or nbytes < 1:
            raise DriverError(f"{where}: nbytes must be a positive integer, not {nbytes!r}")
        for area, off in (("Q", q_off), ("I", i_off)):
            if off + nbytes > self.size:
                raise DriverError(
                    f"{where}: {nbytes} bytes from byte {off} run past the end of the {self.size}-byte %{area} area"
                )
        return Link(src, dst, nbytes), q_off, i_off

    # ------------------------------------------------------------ life cycle

    def start(self) -> None:
        # A (re)started bus has sent nothing yet: the inputs read zeros.
        with self._lock:
            self._wire[:] = bytes(len(self._wire))
        self.exchanges = 0

    def read_inputs(self, image: ProcessImage) -> None:
        self._check_image(image)
        inputs = image.areas["I"]
        with self._lock:  # held only for the copies, as with a bus thread
            wire = self._wire
            for _q, w, i, n in self._copies:
                inputs[i : i + n] = wire[w : w + n]

    def write_outputs(self, image: ProcessImage) -> None:
        self._check_image(image)
        outputs = image.areas["Q"]  # the safe values when the engine holds outputs safe
        with self._lock:
            wire = self._wire
            for q, w, _i, n in self._copies:
                wire[w : w + n] = outputs[q : q + n]
            self.exchanges += 1

    def status(self) -> DriverStatus:
        return DriverStatus(
            True, f"{len(self._wire)} bytes looped in {len(self.links)} links, {self.exchanges} exchanges"
        )

    def _check_image(self, image: ProcessImage) -> None:
        # The offsets were computed for one layout; another would copy the
        # wrong bytes silently. A wiring error, so it raises.
        if image.addressing != self.addressing or image.size != self.size:
            raise DriverError(
                f"{self.name}: configured for a {self.size}-byte {self.addressing} "
                f"image, given a {image.size}-byte {image.addressing} one"
            )


def _text(address) -> str:
    return address.text if isinstance(address, LocatedAddress) else str(address)
