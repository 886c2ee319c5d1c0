"""The loopback driver: [[loopback]] links wire %Q bytes back to %I bytes,
one scan later. The reference implementation of a driver (plugin/driver.py) and the
smallest bus on the seams (plugin/seams.py).

Public names: BUS, LoopbackDriver, LoopbackLink.
"""

from __future__ import annotations

from ...plugin.seams import BuildContext, Bus, Contribution
from .config import LoopbackLink, LoopbackSection
from .driver import LoopbackDriver


def _build(config, ctx: BuildContext) -> Contribution:
    links = config.loopback
    if not links:
        return Contribution()
    return Contribution(
        drivers=[
            LoopbackDriver("loopback", [(link.source, link.target, link.nbytes) for link in links], ctx.addressing)
        ]
    )


BUS = Bus(name="loopback", order=10, sections=(LoopbackSection(),), build=_build)

__all__ = ["BUS", "LoopbackDriver", "LoopbackLink"]
