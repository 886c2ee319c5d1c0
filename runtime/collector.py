"""Python's cyclic garbage collector off while a program is checked or
compiled, and while softplc starts.

A check or a compile makes hundreds of thousands of objects that live
until it ends (trees read back from the parse cache, the checker's
annotations, the generated code's tables). With the collector on, every
700 of them set off a collection of the young objects that walks them
again, and the older generations are walked over and over as they grow:
`softplc check` of TcUnit (15,000 lines, 3,400 errors, three rounds)
spent 40 % of its analysis there (1.2 s against 0.7 s with the collector
off; the clean 10,000-line file 0.31 s against 0.22 s). The objects it
leaves as garbage (some 100,000 in rings, for TcUnit) are collected with
the young objects at the first collection after it: one walk instead of
hundreds. mypy does the same with a high threshold.

A start-up is the same: the imports of the engine and the compile side
and the build of an engine allocate mostly what stays alive, and the
collector ran about 100 passes over it for nothing in the pytest fixture's
build (a tenth of its start-up). So the fixture's build and `softplc
test`'s imports and load run with it off too.

Used around the compile side's entry points and those start-ups. When
the collector is off already (an online change in a running PLC turns it
off and decides itself what happens after: engine/change_memory.py), it
is left as it is.
"""

from __future__ import annotations

import contextlib
import gc
from collections.abc import Iterator


@contextlib.contextmanager
def collector_off() -> Iterator[None]:
    """The collector off for the block (or the decorated function), on
    again after it unless it was off before."""
    if not gc.isenabled():
        yield
        return
    gc.disable()
    try:
        yield
    finally:
        gc.enable()


__all__ = ["collector_off"]
