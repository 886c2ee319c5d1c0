"""Runtime library: the branch a CASE with many labels takes (codegen_stmts
_case): a dictionary of the single labels and a binary search of the
ranges, instead of a chain of comparisons as long as the CASE."""

from __future__ import annotations

from bisect import bisect_right


class CaseTable:
    """labels: (lo, hi, branch) for every label of a CASE, disjoint (the
    checker reports overlaps, E061); calling it with the selector's value
    gives its branch, -1 for none (ELSE)."""

    __slots__ = ("points", "los", "his", "branches")

    def __init__(self, labels: list) -> None:
        self.points = {lo: k for lo, hi, k in labels if lo == hi}
        ranges = sorted((lo, hi, k) for lo, hi, k in labels if lo != hi)
        self.los = [r[0] for r in ranges]
        self.his = [r[1] for r in ranges]
        self.branches = [r[2] for r in ranges]

    def __call__(self, value: int) -> int:
        k = self.points.get(value)
        if k is not None:
            return k
        i = bisect_right(self.los, value) - 1
        if i >= 0 and value <= self.his[i]:
            return self.branches[i]
        return -1
