"""Imported files into the compiler (st/importers: PLCopen XML, TwinCAT
files), through the entry `softplc check` uses (program.check_files) and
the one of `softplc export-st` (importers.st_export): mutants of the
exports the importer tests keep (importer_mutations.py) give coded
diagnostics at file:line:column, or compile and run a few cycles; never a
traceback, an internal error (E009) or a hang.
"""

from __future__ import annotations

from hypothesis import given

from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st.diagnostics import CompileError, DiagnosticBag
from softplc.runtime.st.faults import STFault
from softplc.runtime.st.importers import st_export

from ..st.fuzz_support import assert_well_formed
from .importer_mutations import mutants
from .support import bounded, fuzz, long, short


def check_mutant(case) -> str:
    """The outcome of one mutant: "diagnostics", "ran", "runtime fault"."""
    name, project = case
    with bounded("an imported file"):
        export = DiagnosticBag()
        assert isinstance(st_export(name, project[name], export), str)
        assert_well_formed(export.items, user_files=(name,))
        diags, _ = check_files([], texts=project)
        assert_well_formed(diags, user_files=tuple(project))
        if any(d.is_error for d in diags):
            return "diagnostics"
        try:
            prog = compile_files([], texts=project)
        except CompileError as exc:  # pragma: no cover - a failure, shown in full
            raise AssertionError(f"check_files found no error but compile_files did:\n{exc.format()}") from None
        for pou, kind in prog.pous.items():
            if kind != "PROGRAM":
                continue
            try:
                runner = prog.runner(pou, cycle_time_ms=10)
                runner.ctx.watchdog_s = 0.05
                runner.run(3)
            except STFault as fault:
                assert fault.kind != "internal", f"internal fault (a code generator bug): {fault}"
                return "runtime fault"
    return "ran"


@short(40)
@given(mutants())
def test_mutated_exports_give_diagnostics_or_run(case):
    check_mutant(case)


@fuzz
def test_long_mutated_exports(tally, shard):
    counts = tally("imported files")

    @long("imports", 1.0, shard)
    @given(mutants())
    def run(case):
        counts.add(check_mutant(case))

    run()
