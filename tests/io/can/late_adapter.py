"""A CAN adapter that comes up after the PLC: a real python-can bus class
(python-can's virtual bus) registered as the interface "late" in python-can's
own table of interfaces (can.interfaces.BACKENDS, which its entry points
fill), that cannot be opened while its channel is in ABSENT, as an adapter
that is not plugged in yet cannot.

    late_adapter.register(monkeypatch)   # as python-can registers an entry point's interface
    late_adapter.ABSENT.add(channel)     # not there
    late_adapter.ABSENT.discard(channel) # plugged in: the next open works
"""

from __future__ import annotations

import collections

import can
import can.interfaces
import can.util
from can.interfaces.virtual import VirtualBus

#: python-can's table entry: interface name -> (module, class)
BACKEND = ("late", ("tests.io.can.late_adapter", "LateAdapterBus"))


def register(monkeypatch) -> None:
    """Add "late" to python-can's interfaces for the test, as python-can adds
    an installed plugin's (its entry points fill BACKENDS, and the names it
    accepts, VALID_INTERFACES, when it is imported)."""
    monkeypatch.setitem(can.interfaces.BACKENDS, *BACKEND)
    monkeypatch.setattr(can.util, "VALID_INTERFACES", can.util.VALID_INTERFACES | {BACKEND[0]})


#: channels whose adapter is not there
ABSENT: set[str] = set()
#: opens tried, per channel
ATTEMPTS: collections.Counter = collections.Counter()


class LateAdapterBus(VirtualBus):
    def __init__(self, channel, **kwargs) -> None:
        ATTEMPTS[channel] += 1
        if channel in ABSENT:
            raise can.CanInitializationError(f"no CAN adapter on channel {channel!r}")
        super().__init__(channel=channel, **kwargs)
