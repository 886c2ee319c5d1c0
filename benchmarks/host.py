"""How fast this host runs Python, for reading a benchmark's times taken on
another machine: the best of 5 timings of a fixed pure-Python loop, divided
by what it took on the VM the benchmarks' figures were written on. A factor
of 2.0 means this host took twice as long: its times are about 2x theirs.

    from host import timeit_factor
    print(timeit_factor().line())   # host: timeit factor 1.03 (0.119 s for the reference loop; 0.116 s when written)
"""

from __future__ import annotations

import timeit
from dataclasses import dataclass

REFERENCE_STMT = "sum(i * i for i in range(1000))"
REFERENCE_NUMBER = 2000
#: the best of 5 of REFERENCE_STMT x REFERENCE_NUMBER on the 2-core VM where the figures were taken
REFERENCE_S = 0.116


@dataclass(frozen=True)
class HostFactor:
    seconds: float

    @property
    def factor(self) -> float:
        return self.seconds / REFERENCE_S

    def line(self) -> str:
        return (
            f"host: timeit factor {self.factor:.2f} ({self.seconds:.3f} s for the reference loop; "
            f"{REFERENCE_S:.3f} s when written)"
        )


def timeit_factor() -> HostFactor:
    return HostFactor(min(timeit.repeat(REFERENCE_STMT, number=REFERENCE_NUMBER, repeat=5)))
