"""Hostile input, the generated module itself: ST cannot reach Python
(no import, no attribute of a builtin, no name outside the module), and
nothing runs but the module (test_hostile_input.py has the identifiers,
strings, comments and file names)."""

from __future__ import annotations

import builtins
import os
import subprocess
import sys

import pytest

from softplc.runtime.program import check_files
from softplc.runtime.st.diagnostics import CompileError

from .hostile_support import SAFE_BUILTINS, assert_inert, compile_st, run

# ---------------------------------------------------------------- ST cannot reach Python


@pytest.mark.parametrize(
    "stmt",
    [
        "x := __import__('os');",
        "x := open('f');",
        "x := eval('1');",
        "x := exec('1');",
        "x := getattr(x, 'y');",
        "print('hello');",
        "x := os.system('ls');",
        "x := sys.modules;",
        "x := s.__class__;",
        "x := s.__dict__;",
        "x := s._assign;",
        "x := s.f_a;",
        "x := x.__class__;",
        "x := self.x;",
        "x := _G;",
        "x := _ctx.now_ns;",
        "x := _K0;",
        "x := v_x;",
        "x := range(3);",
        "x := float(1);",
        "x := object;",
        "x := __builtins__;",
        "x := P_main;",
        "x := FB_ton;",
    ],
)
def test_st_cannot_name_python_objects(stmt):
    """Names that mean something in the generated module (builtins, loader
    bindings, Python names of ST things) are unknown to ST."""
    src = (
        f"TYPE rec : STRUCT a : INT; END_STRUCT END_TYPE\n"
        f"PROGRAM main\nVAR x : DINT; s : rec; END_VAR\n{stmt}\nEND_PROGRAM\n"
    )
    diags, _ = check_files([], texts={"h.st": src})
    errors = [d for d in diags if d.is_error]
    assert errors, f"{stmt!r} was accepted"
    assert all(d.pos.file == "h.st" and d.pos.line == 4 for d in errors), [d.format() for d in errors]
    with pytest.raises(CompileError):
        compile_st(src)


def test_generated_module_gets_only_a_few_builtins():
    src = """
FUNCTION eval : INT
VAR_INPUT open : INT; END_VAR
eval := open + 1;
END_FUNCTION
FUNCTION_BLOCK exec
VAR_OUTPUT q : INT; END_VAR
q := eval(open := q);
END_FUNCTION_BLOCK
PROGRAM main
VAR open : INT := 40; __import__ : exec; print : INT; compile : INT; END_VAR
print := eval(open);
__import__();
compile := __import__.q;
END_PROGRAM
"""
    prog, r = run(src, cycles=2)
    assert r.get("print") == 41 and r.get("compile") == 2 and r.get("open") == 40
    ns = prog.load()
    granted = ns["__builtins__"]
    assert isinstance(granted, dict), "the module must not get the builtins module"
    assert set(granted) <= SAFE_BUILTINS
    for name in ("open", "eval", "exec", "compile", "__import__", "getattr", "globals", "print", "input", "type"):
        assert name not in granted
    for obj in ns.values():  # every function and method of the module sees the same restricted builtins
        fns = (
            [obj]
            if callable(obj) and hasattr(obj, "__globals__")
            else [v for v in vars(obj).values() if hasattr(v, "__globals__")]
            if isinstance(obj, type)
            else []
        )
        for fn in fns:
            if fn.__module__ == "softplc_generated":
                assert fn.__globals__["__builtins__"] is granted
    # ST 'open' etc. are attributes with a prefix, never the builtins
    inst = ns[prog.pou("main").pyname]()
    assert not hasattr(inst, "open") and not hasattr(inst, "print")


# ---------------------------------------------------------------- nothing runs but the module

HOSTILE_PROGRAM = """
(* __import__('os').system('PWNED') *)
{ import os }
TYPE import : STRUCT os : STRING := '$'); import os; os.system("PWNED"); ($''; system : INT; END_STRUCT END_TYPE
FUNCTION __import__ : STRING
VAR_INPUT name : STRING := 'os'; END_VAR
__import__ := CONCAT('__import__(', name);
END_FUNCTION
FUNCTION_BLOCK system
VAR_INPUT cmd : STRING; END_VAR
VAR_OUTPUT ran : INT; last : STRING; END_VAR
ran := ran + 1; last := CONCAT(cmd, '; exec(1)');
END_FUNCTION_BLOCK
PROGRAM main
VAR
    os : import; sys : system; exec : STRING; eval : INT; open : ARRAY[1..3] OF STRING := ['a', '{}', '%s'];
    i : INT;
END_VAR
exec := __import__(name := 'subprocess');
sys(cmd := os.os);
FOR i := 1 TO 3 DO
    open[i] := CONCAT(open[i], '$N$'; import os');
END_FOR
eval := sys.ran + os.system;
END_PROGRAM
"""


class _Recorder:
    def __init__(self):
        self.events = None

    def __call__(self, event, args):
        if self.events is not None:
            self.events.append((event, args))


_AUDIT = _Recorder()
_AUDIT_INSTALLED = False


def _audit():
    global _AUDIT_INSTALLED
    if not _AUDIT_INSTALLED:  # audit hooks cannot be removed: install one, idle unless recording
        sys.addaudithook(_AUDIT)
        _AUDIT_INSTALLED = True
    return _AUDIT


SUSPICIOUS_EVENTS = (
    "import",
    "exec",
    "compile",
    "open",
    "os.",
    "subprocess.",
    "socket.",
    "ctypes.",
    "shutil.",
    "builtins.input",
    "code.",
    "pty.",
    "webbrowser.",
    "urllib.",
    "sys._getframe",
    "marshal.",
    "pickle.",
    "object.__setattr__",
    "object.__delattr__",
    "function.__new__",
    "code.__new__",
)


def test_loading_and_running_a_hostile_program_imports_and_executes_nothing():
    prog = compile_st(HOSTILE_PROGRAM)
    assert_inert(
        prog,
        strings=(
            "'); import os; os.system(\"PWNED\"); ('",
            "os",
            "__import__(",
            "; exec(1)",
            "subprocess",
            "a",
            "{}",
            "%s",
            "\n'; import os",
        ),
    )
    audit = _audit()
    audit.events = []
    try:
        r = prog.runner("main")
        load_events, audit.events = audit.events, []
        r.run(5)
        run_events = audit.events
    finally:
        audit.events = None
    # loading executes the generated module once, and nothing else
    assert [e for e, _ in load_events] == ["exec"], load_events
    ((code,),) = [a for _, a in load_events]
    assert code is prog.code and code.co_filename == prog.filename
    # running executes nothing, imports nothing, opens nothing
    assert not [e for e in run_events if e[0].startswith(SUSPICIOUS_EVENTS)], run_events
    assert r.get("eval") == 5 and r.get("exec") == "__import__(subprocess"
    assert r.get("sys.last") == "'); import os; os.system(\"PWNED\"); ('; exec(1)"
    tail = "\n'; import os" * 5
    assert r.get("open") == ["a" + tail, "{}" + tail, "%s" + tail]


def test_hostile_program_calls_no_dangerous_python_function():
    """os.system & co. replaced by recorders while the program loads and
    runs: only the loader's one exec() of the module is seen."""
    calls = []
    recording = False

    def recorder(name, real=None):
        def fn(*args, **kwargs):
            if recording:
                calls.append((name, args))
            return real(*args, **kwargs) if real is not None else None

        return fn

    prog = compile_st(HOSTILE_PROGRAM)
    mp = pytest.MonkeyPatch()
    try:
        for mod, attr in (
            (os, "system"),
            (os, "popen"),
            (os, "execv"),
            (os, "execve"),
            (os, "spawnv"),
            (os, "posix_spawn"),
            (os, "remove"),
            (os, "unlink"),
            (subprocess, "Popen"),
            (subprocess, "run"),
            (subprocess, "check_output"),
        ):
            if hasattr(mod, attr):
                mp.setattr(mod, attr, recorder(f"{mod.__name__}.{attr}"))  # never the real one
        for attr in ("__import__", "exec", "eval", "open", "compile", "input", "getattr"):
            mp.setattr(builtins, attr, recorder(attr, getattr(builtins, attr)))
        recording = True
        r = prog.runner("main")
        r.run(5)
        recording = False
    finally:
        recording = False
        mp.undo()
    assert [c[0] for c in calls] == ["exec"], calls  # the loader executing the module, once
    assert calls[0][1][0] is prog.code
    assert r.get("eval") == 5
