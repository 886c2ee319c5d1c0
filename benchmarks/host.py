"""How fast this host runs Python, against the reference host the speed
targets are given for: there ``python3 -m timeit 'sum(range(1000))'`` takes
about 8 µs. The factor is this host's time for the same statement (best of
5, as timeit reports it) over 8 µs: 2.0 means this host is twice as slow,
and a figure taken here divided by 2.0 is the reference host's figure.

The factor measures the interpreter that runs the benchmark as much as the
machine: the targets' figures were taken on CPython 3.11, and the same
machine's 3.12 and 3.13 run this statement 25-40 % slower while they run
the plant no faster (benchmarks/README.md, the default plant on other
Pythons). line() names the interpreter, and says so when it is not 3.11 (on
the same line: scripts and tests read the next lines as the table).

    from host import timeit_factor
    host = timeit_factor()
    print(host.line())                  # host: timeit factor 1.19 (sum(range(1000)) 9.5 µs here on CPython 3.11.7; ...)
    print(host.scaled(2.4))             # 2.02: seconds here, as on the reference host
"""

from __future__ import annotations

import platform
import sys
import timeit
from dataclasses import dataclass

REFERENCE_STMT = "sum(range(1000))"
#: what REFERENCE_STMT takes on the reference host (the speed targets' host)
REFERENCE_S = 8e-6
_NUMBER = 20_000
#: the interpreter the reference figures were taken on
REFERENCE_PYTHON = (3, 11)


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
        python = f"{platform.python_implementation()} {platform.python_version()}"
        text = (
            f"host: timeit factor {self.factor:.2f} ({REFERENCE_STMT} {self.seconds * 1e6:.1f} µs here on "
            f"{python}; reference host {REFERENCE_S * 1e6:.0f} µs on CPython 3.11)"
        )
        if sys.version_info[:2] != REFERENCE_PYTHON or platform.python_implementation() != "CPython":
            text += "; not 3.11 here: the factor also measures this interpreter at that one loop"
        return text


def timeit_factor() -> HostFactor:
    return HostFactor(min(timeit.repeat(REFERENCE_STMT, number=_NUMBER, repeat=5)) / _NUMBER)
