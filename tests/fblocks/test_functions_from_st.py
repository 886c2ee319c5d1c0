"""Every standard function is callable from ST: checked, generated and run."""

from __future__ import annotations

from softplc.fblocks.iec.functions import STANDARD_FUNCTIONS
from softplc.runtime.program import compile_files

# a representative argument type for each generic family
_GENERIC_REP = {
    "ANY": "INT",
    "ANY_ELEMENTARY": "INT",
    "ANY_MAGNITUDE": "INT",
    "ANY_NUM": "INT",
    "ANY_INT": "INT",
    "ANY_SIGNED": "INT",
    "ANY_UNSIGNED": "UINT",
    "ANY_REAL": "REAL",
    "ANY_BIT": "WORD",
    "ANY_STRING": "STRING",
    "ANY_CHARS": "STRING",
    "ANY_DATE": "DATE",
    "ANY_DURATION": "TIME",
}
_INIT = {
    "BOOL": "TRUE",
    "STRING": "'ab1'",
    "WSTRING": '"ab1"',
    "TIME": "T#1s",
    "LTIME": "LT#1s",
    "DATE": "D#2024-02-29",
    "LDATE": "LDATE#2024-02-29",
    "TOD": "TOD#12:00:00",
    "TIME_OF_DAY": "TOD#12:00:00",
    "LTOD": "LTOD#12:00:00",
    "LTIME_OF_DAY": "LTOD#12:00:00",
    "DT": "DT#2024-02-29-12:00:00",
    "DATE_AND_TIME": "DT#2024-02-29-12:00:00",
    "LDT": "LDT#2024-02-29-12:00:00",
    "LDATE_AND_TIME": "LDT#2024-02-29-12:00:00",
    "REAL": "2.0",
    "LREAL": "2.0",
    "INT_YEAR": "2024",
    "CHAR": "CHAR#'A'",
    "WCHAR": 'WCHAR#"A"',
}


def _arg_type(spec: str) -> str:
    generic = spec.split(":", 1)[-1]
    return _GENERIC_REP.get(generic.upper(), generic.upper())


def test_every_standard_function_compiles_and_runs():
    types = set()
    calls = []
    for name, func in sorted(STANDARD_FUNCTIONS.items()):  # AND(...), MOD(...) included
        specs = [p[1] for p in func.params]
        arg_types = [_arg_type(s) for s in specs]
        if func.extensible:
            arg_types.append(arg_types[-1])
        types.update(arg_types)
        args = ", ".join(f"v_{t}" for t in arg_types)
        if name == "NOT":  # NOT(x) alone is the operator, not a statement; formally it is a call
            args = f"IN := {args}"
        if func.params[0][0] in ("YEAR", "HOUR"):  # CONCAT_DATE(1, 1, 1) is no DATE: a range fault
            args = ", ".join("v_INT_YEAR" if p == "YEAR" else "v_INT" for p, _ in func.params)
            types.add("INT_YEAR")
        calls.append(f"{name}({args});")
    decls = "\n".join(f"v_{t} : {t.split('_YEAR')[0]} := {_INIT.get(t, '1')};" for t in sorted(types))
    src = f"PROGRAM main\nVAR\n{decls}\nEND_VAR\n" + "\n".join(calls) + "\nEND_PROGRAM\n"
    prog = compile_files([], texts={"all.st": src})
    assert len(calls) > 900
    prog.runner("main").run(1)
