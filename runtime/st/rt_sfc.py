"""The SFC step type and the action qualifiers (IEC 61131-3 ed.3 6.7):
what the checker (checker_sfc.py) needs of SFC at run time."""

from __future__ import annotations

from . import types as T

# The step flags as a STRUCT type for the checker and the value walkers
# (its class is Step, bound as _SfcStep in the generated module).
STEP_TYPE = T.StructType(
    "SFC_STEP",
    {
        "X": T.StructField("X", T.BOOL, pyname="v_x"),
        "T": T.StructField("T", T.TIME, pyname="v_t"),
    },
    pyclass="_SfcStep",
)

# Qualifiers (ed.3 6.7.4, ed.2 2.6.4) and those that take a duration.
QUALIFIERS = ("N", "R", "S", "P", "P1", "P0", "L", "D", "SD", "DS", "SL")
TIMED = frozenset(("L", "D", "SD", "DS", "SL"))
