"""[[loopback]]: links that copy %Q bytes back to %I bytes one scan later."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated, Any

from pydantic import Field

from ...config.errors import key_text
from ...config.relations import Relations
from ...config.section import Section
from ...config.values import Model, area_name, in_range, int_range
from ...image import address as _address
from ...image.memory import AREA_SIZE
from ...st.ast import LocatedAddress


@dataclass
class LoopbackLink:
    source: LocatedAddress  # a %Q byte/word/dword/lword address
    target: LocatedAddress  # a %I byte/word/dword/lword address
    nbytes: int
    key: str  # "loopback[0]"


class _Loopback(Model):
    source: Any = Field(alias="from", description='a %Q byte/word/dword/lword address such as "%QB0"')
    target: Any = Field(alias="to", description='a %I byte/word/dword/lword address such as "%IB0"')
    nbytes: Annotated[int, int_range(1, AREA_SIZE)] = Field(
        alias="bytes", description=f"an integer from 1 to {AREA_SIZE}"
    )


class LoopbackSection(Section):
    key = "loopback"
    many = True
    model = _Loopback
    description = "[[loopback]] tables"

    def check(self, value: Any, ctx: Relations) -> None:
        links: list = ctx.state.setdefault(self.key, [])
        targets: list = []  # (link, to, %I byte offset, bytes) of the good links
        if not isinstance(value, list):
            return
        for i, link in enumerate(value):
            if not isinstance(link, dict):
                continue
            here = ("loopback", i)
            ends = {}
            for key, area in (("from", "Q"), ("to", "I")):
                if key not in link:
                    continue  # pass 1 reports it missing
                addr = ctx.address(here + (key,), link[key], f"%{area}B0, %{area}W2")
                if addr is None:
                    continue
                kind = "%Q output" if area == "Q" else "%I input"
                if addr.area != area:
                    ctx.error(here + (key,), f"expected a {kind} address (got {area_name(addr)})")
                elif addr.bit is not None or addr.table is not None or addr.size not in _address.SIZE_BITS:
                    ctx.error(
                        here + (key,),
                        f"expected a {kind} byte, word, dword or lword address "
                        f"such as %{area}B0 (got '{addr.text}'); the link copies "
                        "whole bytes",
                    )
                else:
                    ends[key] = addr
            nbytes = link.get("bytes")
            if not in_range(nbytes, 1, AREA_SIZE):
                continue  # pass 1 reports it
            spans = {key: self._span(here, addr, nbytes, ctx) for key, addr in ends.items()}
            if len(ends) == 2 and None not in spans.values():
                target = spans["to"]
                assert target is not None
                if self._overlaps(here, ends["to"], target, nbytes, targets, ctx):
                    continue
                targets.append((i, ends["to"], target, nbytes))
                links.append(LoopbackLink(ends["from"], ends["to"], nbytes, key_text(here)))
                self._claim_target(i, ends["to"], nbytes, ctx)

    @staticmethod
    def _span(here: tuple, addr: LocatedAddress, nbytes: int, ctx: Relations) -> int | None:
        """The byte offset of addr when nbytes from it fit the area; else None
        and the error, at bytes: the address itself is in the image."""
        image = ctx.probe()
        try:
            _area, offset, _n = image.region(addr)
        except ValueError as exc:
            ctx.error(here + ("from" if addr.area == "Q" else "to",), str(exc))
            return None
        if offset + nbytes > image.size:
            ctx.error(
                here + ("bytes",),
                f"{nbytes} bytes from '{addr.text}' (byte {offset}) run past the end of the "
                f"{image.size}-byte %{addr.area} area: at most {image.size - offset} from there",
            )
            return None
        return offset

    @staticmethod
    def _overlaps(here: tuple, addr: LocatedAddress, offset: int, nbytes: int, targets: list, ctx: Relations) -> bool:
        """Two links into the same input bytes: which one wins would be an accident."""
        for j, other_addr, other, other_n in targets:
            if offset < other + other_n and other < offset + nbytes:
                ctx.error(
                    here + ("to",),
                    f"'{addr.text}', {nbytes} byte{'s' if nbytes > 1 else ''}, writes input bytes "
                    f"{offset}..{offset + nbytes - 1}; loopback[{j}] (to = '{other_addr.text}', bytes = {other_n}) "
                    f"already writes {max(offset, other)}..{min(offset + nbytes, other + other_n) - 1}",
                )
                return True
        return False

    @staticmethod
    def _claim_target(i: int, target: LocatedAddress, nbytes: int, ctx: Relations) -> None:
        """The %I bytes a link writes, which nothing on a bus may write too
        (the links themselves may overlap: the driver refuses that)."""
        try:
            _area, offset, _n = ctx.probe().region(target)
        except ValueError:
            return
        ctx.claimed.append(
            (
                "I",
                8 * offset,
                8 * (offset + nbytes) - 1,
                ("loopback", i, "to"),
                f"'{target.text}', {nbytes} byte{'s' if nbytes > 1 else ''}",
            )
        )

    def build(self, model: Any, ctx: Relations) -> list[LoopbackLink]:
        return list(ctx.state.get(self.key, []))
