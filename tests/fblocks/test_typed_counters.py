"""The typed counters (fblocks/iec/typed_counters.py and the
typed_counters.st it writes): IEC 61131-3 ed.3 Table 45 CTU_<T>, CTD_<T>,
CTUD_<T> with PV and CV of type T, run cycle by cycle."""

from __future__ import annotations

import pytest

from softplc.fblocks.iec import typed_counters
from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st import types as T

from .st_bench import Bench


def test_shipped_file_is_what_the_generator_writes(tmp_path):
    # regenerate with: python -m softplc.fblocks.iec.typed_counters
    assert typed_counters.shipped_path().read_text(encoding="utf-8") == typed_counters.render()
    assert typed_counters.main([str(tmp_path)]) == 0
    assert (tmp_path / "typed_counters.st").read_text(encoding="utf-8") == typed_counters.render()


def test_ctu_dint_counts_past_the_int_maximum():
    """32770 rising edges of CU: an INT CTU would stop at 32767."""
    b = Bench(
        "c : CTU_DINT; cu : BOOL; cv : DINT; q : BOOL; old : CTU; oldcv : INT;",
        "cu := NOT cu;\nc(CU := cu, PV := 32768);\ncv := c.CV;\nq := c.Q;\nold(CU := cu);\noldcv := old.CV;",
    )
    b.step(65533)  # CU rises in every odd cycle: 32767 edges
    assert (b["cv"], b["q"], b["oldcv"]) == (32767, False, 32767)
    b.step(6)
    assert (b["cv"], b["q"], b["oldcv"]) == (32770, True, 32767)
    b.step(2, **{"c.R": True})  # R wins over CU: back to 0
    assert (b["cv"], b["q"]) == (0, False)


_TYPES = typed_counters.COUNTER_TYPES


@pytest.mark.parametrize("t", _TYPES, ids=lambda t: t.name)
def test_ctud_counts_up_to_the_maximum_of_its_type_and_stops(t):
    b = Bench(
        f"c : CTUD_{t.name}; cu : BOOL; ld : BOOL := TRUE; cv : {t.name}; qu : BOOL; qd : BOOL;",
        f"c(CU := cu, LD := ld, PV := {t.hi - 1});\ncv := c.CV;\nqu := c.QU;\nqd := c.QD;\nld := FALSE;\ncu := NOT cu;",
    )
    b.step(1)  # LD loads PV
    assert (b["cv"], b["qu"], b["qd"]) == (t.hi - 1, True, False)
    b.step(6)  # three rising edges of CU; the first reaches the maximum
    assert b["cv"] == t.hi


@pytest.mark.parametrize("t", _TYPES, ids=lambda t: t.name)
def test_ctd_counts_down_to_the_minimum_of_its_type_and_stops(t):
    b = Bench(
        f"c : CTD_{t.name}; cd : BOOL; ld : BOOL := TRUE; cv : {t.name}; q : BOOL;",
        f"c(CD := cd, LD := ld, PV := {t.lo + 2});\ncv := c.CV;\nq := c.Q;\nld := FALSE;\ncd := NOT cd;",
    )
    b.step(1)
    assert (b["cv"], b["q"]) == (t.lo + 2, t.lo + 2 <= 0)
    b.step(8)  # four rising edges of CD; two reach the minimum
    assert (b["cv"], b["q"]) == (t.lo, True)


def test_pv_and_cv_have_the_counters_type():
    src = (
        "PROGRAM main\nVAR c : CTU_LINT; d : CTD_UDINT; i : INT; l : LINT; END_VAR\n"
        "c(CU := TRUE, PV := l);\nd(CD := TRUE, PV := 4000000000);\ni := c.CV;\n"
        "l := d.CV;\nd(PV := -1);\nEND_PROGRAM\n"
    )
    diags, _ = check_files([], texts={"t.st": src})
    assert [(d.code, d.pos.line) for d in diags] == [("W121", 5), ("W122", 7)]
    assert "LINT to INT" in diags[0].message
    assert diags[1].message.startswith("-1 does not fit UDINT")


def test_typed_counters_are_compiled_only_into_programs_that_name_one():
    def pous(body: str) -> set:
        src = f"PROGRAM main\nVAR {body} END_VAR\nEND_PROGRAM\n"
        return {p.name for p in compile_files([], texts={"t.st": src}).checked.pous}

    without = pous("c : CTU;")
    assert "CTU" in without and not any(n.startswith(("CTU_", "CTD_", "CTUD_")) for n in without)
    expected = {f"{n}_{t.name}" for n in typed_counters.COUNTERS for t in _TYPES}
    assert expected <= pous("c : CTUD_ULINT;")
    assert T.ULINT in _TYPES and len(expected) == 15
