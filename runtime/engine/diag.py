"""PLC_DIAG (fblocks/system/plc_diag.st): the engine's own state as the
program reads it. Written only when something changed, so the scan pays
(almost) nothing for it."""

from __future__ import annotations

from ..program import StructWriter, global_variable


class DiagVariable(StructWriter):
    """PLC_DIAG."""

    def __init__(self, globals_obj) -> None:
        super().__init__(global_variable(globals_obj, "PLC_DIAG"))
