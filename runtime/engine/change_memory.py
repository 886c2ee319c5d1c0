"""What an online change leaves in memory, and what the garbage collector
walks meanwhile (online_change.py): the collector paused while a program
is read back, the program frozen out of its sight, and a replaced
program's module taken apart so that reference counting frees it."""

from __future__ import annotations

import contextlib
import gc
from collections.abc import Callable

#: what a class keeps when it is taken apart (the rest: its methods, its slots' descriptors)
_TYPE_OWN = frozenset({"__module__", "__qualname__", "__doc__", "__dict__", "__weakref__"})


def dismantle(ns: dict | None, pace: Callable[[], None] = lambda: None) -> None:
    """A replaced program's module emptied, and its classes (a class is a
    ring: its method resolution order names it, its slots' descriptors
    too): what is left of each, a type and its bases, is some 200 bytes
    that stay, where the whole module (its functions, its globals'
    objects, the slots' descriptors: some 7,000 objects) would stay frozen
    with it. Nothing runs it any more: the swap has rebound the tasks, the
    drivers, the forces and the retain plan to the new one. pace() is
    called before each class (lock_share.pause: while the scan sleeps)."""
    if not ns:
        return
    name = ns.get("__name__")
    for value in list(ns.values()):
        if isinstance(value, type) and value.__module__ == name:
            pace()
            for attr in [a for a in vars(value) if a not in _TYPE_OWN]:
                with contextlib.suppress(AttributeError, TypeError):
                    delattr(value, attr)
    ns.clear()


@contextlib.contextmanager
def collector_paused(frozen: Callable[[], bool]):
    """Python's cyclic garbage collector off while a change compiles or is
    read back: some 100,000 objects that live a while (trees, tables, the
    new classes), which with the collector on set off collections that walk
    them with the interpreter lock held, the scan waiting (up to 80 ms each
    on a 2-core machine). Then, when frozen() (a program read back from the
    compile process, whose rings release() cuts once it is replaced): every
    object alive moved out of the collector's sight (gc.freeze, as
    softplc run does before the first scan), so no collection walks the new
    program, ever; 20 changes of the default plant: 16 overruns instead of
    136. Otherwise (a compile in this process, whose tables the libraries
    share): one collection of the young objects."""
    if not gc.isenabled():  # someone else's choice: kept
        yield
        return
    gc.collect(0)  # what is garbage already is not frozen with the program
    gc.disable()
    try:
        yield
    finally:
        if frozen():  # before the collector is on again: a thread allocating between the two would
            gc.freeze()  # set off a collection of all that came while it was off
            gc.enable()
        else:
            gc.enable()
            gc.collect(1)


def freeze_new_program() -> None:
    """Once a change read back from the compile process is applied and the
    program it replaced taken apart: what the new one made alive since the
    read-back was frozen (its module's classes and functions, its instances
    and their values: about 2,350 objects for the default plant) moved out
    of the collector's sight too, as the read-back itself is. Young, they
    were walked by the next collections, with the interpreter lock held in
    whichever thread allocated (a live soak saw collections of 2-4 ms in the
    servers' call threads after each change). Left alone when the collector
    is off (someone else's choice)."""
    if gc.isenabled():
        gc.freeze()


__all__ = ["collector_paused", "dismantle", "freeze_new_program"]
