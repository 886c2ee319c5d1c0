"""glibc's malloc as softplc run sets it (engine/libc_heap.py): at most two
arenas however many threads allocate, and a buffer of 1.5 MB mapped on
its own again after the first was freed (glibc otherwise moves its
threshold up and takes the next from an arena, which fragments). Each
case runs in a fresh interpreter: mallopt changes the whole process."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from softplc.runtime.engine.libc_heap import ARENAS

pytestmark = pytest.mark.skipif(
    not sys.platform.startswith("linux") or not os.confstr("CS_GNU_LIBC_VERSION"),
    reason="glibc's malloc only: another C library is left as it is",
)

#: eight threads allocate at once; then malloc_info's heaps are counted,
#: and the bytes glibc maps on their own for a second 1.5 MB buffer
PROBE = r"""
import ctypes, sys, tempfile, threading
from softplc.runtime.engine.libc_heap import steady_malloc
if sys.argv[1] == "steady":
    print(steady_malloc())
else:
    print(None)
libc = ctypes.CDLL(None)
held, barrier = [], threading.Barrier(8)
def allocate():
    barrier.wait()
    held.append(bytearray(4096))  # malloc's, not pymalloc's: over 512 bytes
    barrier.wait()
threads = [threading.Thread(target=allocate) for _ in range(8)]
for t in threads:
    t.start()
for t in threads:
    t.join()
libc.fopen.restype = ctypes.c_void_p
libc.fopen.argtypes = [ctypes.c_char_p, ctypes.c_char_p]
libc.malloc_info.argtypes = [ctypes.c_int, ctypes.c_void_p]
libc.fclose.argtypes = [ctypes.c_void_p]
with tempfile.NamedTemporaryFile("r") as out:
    stream = libc.fopen(out.name.encode(), b"w")
    libc.malloc_info(0, stream)
    libc.fclose(stream)
    print(out.read().count("<heap nr="))
class Mallinfo2(ctypes.Structure):
    _fields_ = [(n, ctypes.c_size_t) for n in (
        "arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks", "fsmblks", "uordblks", "fordblks", "keepcost")]
libc.mallinfo2.restype = Mallinfo2
first = bytearray(1_500_000)
del first
before = libc.mallinfo2().hblkhd
second = bytearray(1_500_000)
print(libc.mallinfo2().hblkhd - before)
"""


def probe(mode: str, **env: str) -> tuple[str, int, int]:
    done = subprocess.run(
        [sys.executable, "-c", PROBE, mode],
        env={k: v for k, v in os.environ.items() if not k.startswith("MALLOC_")} | env,
        capture_output=True,
        text=True,
        check=True,
    )
    took, heaps, mapped = done.stdout.split()
    return took, int(heaps), int(mapped)


def test_steady_malloc_keeps_two_arenas_and_maps_big_buffers_alone() -> None:
    took, heaps, mapped = probe("steady")
    assert took == "True"
    assert heaps <= ARENAS
    assert mapped >= 1_500_000


def test_without_it_glibc_gives_each_thread_an_arena_and_reuses_them() -> None:
    """What softplc run changes: the same probe under glibc's defaults."""
    _, heaps, mapped = probe("plain")
    assert heaps > ARENAS
    assert mapped == 0


def test_a_setting_of_the_environment_is_kept() -> None:
    took, heaps, mapped = probe("steady", MALLOC_ARENA_MAX="4")
    assert took == "True"
    assert heaps == 4  # the user's four, not softplc's two
    assert mapped >= 1_500_000  # the threshold, which the environment left alone, is set
