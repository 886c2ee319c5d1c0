"""Pass 2 of a configuration: the checks between values that pydantic
cannot see per value, run on the raw TOML data whatever pass 1 found, so
every error of a file is reported at once.

A Relations object is handed to each section's check (config/section.py):
it collects the errors, parses direct addresses for the profile of the
file (addresses depend on the addressing model), tells where an address
falls in the process image, keeps the %I bits that something already
writes (so two writers of one input are reported), and holds each
section's parsed results for its build (``state``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..image import address as _address
from ..image.memory import ProcessImage
from ..st.ast import LocatedAddress
from ..st.profile import DEFAULT as _DEFAULT_PROFILE
from ..st.profile import PROFILES
from .errors import key_text
from .values import got


class Relations:
    def __init__(self, data: dict, base_dir: Path) -> None:
        self.data = data
        self.base_dir = base_dir
        self.errors: list = []
        #: what may be wrong but need not be (loc, message): the file loads, the launcher logs them
        self.warnings: list = []
        #: a section's parsed results for its build, by section key
        self.state: dict[str, Any] = {}
        #: image bits written from the bus side: (area, first bit, last bit, loc, text)
        self.claimed: list = []
        #: safe values a bus's devices give their %Q addresses: (loc, address,
        #: value); [outputs] safe wins where it sets any bit of the address
        self.safe_defaults: list = []
        self._probe_image: ProcessImage | None = None
        plc = data.get("plc")
        if not isinstance(plc, dict):
            plc = {}
        profile = plc.get("profile", _DEFAULT_PROFILE.name)
        profile = PROFILES.get(profile.lower()) if isinstance(profile, str) else None
        self.addressing = profile.addressing if profile is not None else None

    def error(self, loc: tuple, message: str) -> None:
        self.errors.append((loc, message))

    def required(self, here: tuple, table: dict, model) -> None:
        """The keys a device's own model (its NodeOptions, SimOptions) needs
        and the table lacks: pass 1 takes them as optional, because the
        table's model holds the keys of every device."""
        for name, info in model.model_fields.items():
            key = info.alias or name
            if info.is_required() and key not in table:
                described = f" ({info.description})" if info.description else ""
                self.error(here, f"required key missing: {key}{described}")

    def warning(self, loc: tuple, message: str) -> None:
        self.warnings.append((loc, message))

    # ---------------------------------------------------------------- addresses

    def address(self, loc: tuple, text, examples: str) -> LocatedAddress | None:
        if not isinstance(text, str):
            self.error(loc, f"expected a direct address such as {examples} (got {got(text)})")
            return None
        try:
            return _address.parse_address(text, self.addressing)
        except ValueError as exc:  # AddressError, and LiteralError should one slip through
            message = str(exc)
            if "is not a direct address" in message:
                message = f"expected a direct address such as {examples} (got {got(text)})"
            else:  # drop the address the key already names
                prefix = text.strip().upper() + ": "
                message = message[len(prefix) :] if message.startswith(prefix) else message
            self.error(loc, message)
            return None

    def probe(self) -> ProcessImage:
        """A process image laid out as the profile's, for where addresses fall."""
        if self._probe_image is None:
            self._probe_image = ProcessImage(self.addressing or "iec")
        return self._probe_image

    def image_bits(self, loc: tuple, addr: LocatedAddress) -> tuple | None:
        """(first, last) bit of its area that addr covers, or None (and an
        error) outside the image. The layout is memory.py's: bytes for the
        IEC model, words for Schneider; bit n of byte b is bit 8b + n."""
        image = self.probe()
        if addr.bit is not None or addr.size in ("", "X"):
            if addr.bit is not None:  # %IW3:X2 (Schneider): a bit of a word
                word = image.byte_offset(LocatedAddress(addr.area, "W", addr.indices, None, None, addr.text))
                bit = 8 * word + addr.bit
            elif len(addr.indices) >= 2:
                bit = 8 * addr.indices[-2] + addr.indices[-1]
            else:
                bit = addr.indices[0]
            if bit >= 8 * image.size:
                self.error(loc, f"'{addr.text}' is outside the {image.size}-byte %{addr.area} area")
                return None
            return bit, bit
        try:
            _area, offset, nbytes = image.region(addr)
        except ValueError as exc:
            self.error(loc, str(exc))
            return None
        return 8 * offset, 8 * (offset + nbytes) - 1

    def claim(self, area: str, first: int, last: int, loc: tuple, text: str) -> tuple | None:
        """Bits first..last of an area are written by what loc configures:
        (loc, text) of an earlier claim they overlap (then nothing is
        claimed), or None."""
        for other_area, other_first, other_last, other_loc, other_text in self.claimed:
            if other_area == area and first <= other_last and other_first <= last:
                return other_loc, other_text
        self.claimed.append((area, first, last, loc, text))
        return None

    def writes(self, loc: tuple, area: str, offset: int, nbytes: int, text: str) -> bool:
        """The seam by which a section says "what loc configures writes these
        image bytes" (a bus reads into them: a Modbus channel's read_to, a
        TPDO's entries, a loopback link's target): bytes offset ..
        offset + nbytes - 1 of area. Each byte has one writer, across every
        section and bus (which one wins would be an accident of the scan's
        order): an overlap with an earlier claim is loc's error. True when
        claimed."""
        other = self.claim(area, 8 * offset, 8 * (offset + nbytes) - 1, loc, text)
        if other is None:
            return True
        self.error(loc, f"{text} overlaps {key_text(other[0])} ({other[1]}): each image byte has one writer")
        return False
