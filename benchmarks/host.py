"""How fast this host runs Python, against the reference host the speed
targets are given for: there ``python3 -m timeit 'sum(range(1000))'`` takes
about 8 µs. The factor is this host's time for the same statement (best of
5, as timeit reports it) over 8 µs: 2.0 means this host is twice as slow,
and a figure taken here divided by 2.0 is the reference host's figure.

    from host import timeit_factor
    host = timeit_factor()
    print(host.line())                  # host: timeit factor 1.19 (sum(range(1000)) 9.5 µs; reference 8 µs)
    print(host.scaled(2.4))             # 2.02: seconds here, as on the reference host
"""

from __future__ import annotations

import timeit
from dataclasses import dataclass

REFERENCE_STMT = "sum(range(1000))"
#: what REFERENCE_STMT takes on the reference host (the speed targets' host)
REFERENCE_S = 8e-6
_NUMBER = 20_000


@dataclass(frozen=True)
class HostFactor:
    seconds: float  # one run of REFERENCE_STMT here, best of 5

    @property
    def factor(self) -> float:
        return self.seconds / REFERENCE_S

    def scaled(self, seconds: float) -> float:
        """A time taken here as it would be on the reference host."""
        return seconds / self.factor

    def line(self) -> str:
        return (
            f"host: timeit factor {self.factor:.2f} ({REFERENCE_STMT} {self.seconds * 1e6:.1f} µs here; "
            f"reference host {REFERENCE_S * 1e6:.0f} µs)"
        )


def timeit_factor() -> HostFactor:
    return HostFactor(min(timeit.repeat(REFERENCE_STMT, number=_NUMBER, repeat=5)) / _NUMBER)
