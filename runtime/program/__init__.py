"""A program: ST files compiled with the libraries they use, loaded into a
namespace bound to a process image and run cycle by cycle.

    from softplc.runtime.program import compile_files
    prog = compile_files(["plant.st"], profile="codesys")   # CompileError on errors
    r = prog.runner("Main", cycle_time_ms=10)
    r.run(100)                                              # STFault on a runtime fault
    r.get("counter.CV")

Public names: compile_files, check_files, build_parsed, Program, Runner, ExecContext,
TaskState, locate, global_variable, StructWriter.
"""

from .compile import build_parsed, check_files, compile_files
from .context import ExecContext, TaskState
from .libraries import Library
from .loaded import Program, Runner
from .variables import StructWriter, global_variable, locate

__all__ = [
    "Library",
    "build_parsed",
    "ExecContext",
    "Program",
    "Runner",
    "StructWriter",
    "TaskState",
    "check_files",
    "compile_files",
    "global_variable",
    "locate",
]
