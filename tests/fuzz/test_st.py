"""ST into the compiler, through the entry `softplc check` uses
(program.check_files): a coded diagnostic at file:line:col or a clean
result, never a traceback or an internal error, within the harness's time
and memory bounds (support.bounded). What the checker accepts is compiled
and run for a few cycles in virtual time: a runtime fault is an answer, a
Python exception escaping or an internal fault is not.

  * valid programs from the typed grammar (st_decls.valid_programs): the
    checker must accept every one (an error is a finding), then they run;
  * mutants of those and of the corpus of tests/st: token-wise mutations
    (tests/st/fuzz_mutations.py) and byte-level ones, huge numbers, deep
    nesting (st_mutations.py).
"""

from __future__ import annotations

from hypothesis import given

from ..st.fuzz_support import check_and_maybe_run
from .st_decls import valid_programs
from .st_mutations import mutants
from .support import bounded, fuzz, long, short


def _check_valid(src: str) -> str:
    faults: list = []
    with bounded("a valid program"):
        diags = check_and_maybe_run("codesys", src, cycles=3, faults=faults)
    errors = [d.format() for d in diags if d.is_error]
    assert not errors, "the checker refused a valid program:\n" + "\n".join(errors) + "\n" + src
    return "runtime fault" if faults else "ran"


def _check_mutant(case) -> str:
    profile, src = case
    faults: list = []
    with bounded("a mutant"):
        diags = check_and_maybe_run(profile, src, cycles=3, faults=faults)
    if any(d.is_error for d in diags):
        return "diagnostics"
    return "runtime fault" if faults else "ran"


@short(25)
@given(valid_programs())
def test_valid_programs_are_accepted_and_run(src):
    _check_valid(src)


@short(40)
@given(mutants(valid_programs()))
def test_mutants_of_valid_programs_give_diagnostics_or_run(case):
    _check_mutant(case)


@short(20)
@given(mutants(None))
def test_mutants_of_the_corpus_give_diagnostics_or_run(case):
    _check_mutant(case)


@fuzz
def test_long_valid_programs(tally, shard):
    counts = tally("st")

    @long("st", 0.3, shard)
    @given(valid_programs())
    def run(src):
        counts.add(_check_valid(src))

    run()


@fuzz
def test_long_mutants(tally, shard):
    counts = tally("st")

    @long("st", 0.5, shard)
    @given(mutants(valid_programs()))
    def run(case):
        counts.add(_check_mutant(case))

    run()


@fuzz
def test_long_corpus_mutants(tally, shard):
    counts = tally("st")

    @long("st", 0.2, shard)
    @given(mutants(None))
    def run(case):
        counts.add(_check_mutant(case))

    run()
