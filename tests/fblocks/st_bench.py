"""A bench for one function block: a PROGRAM around it, stepped a cycle at
a time on the runner's virtual clock; variables read and written by ST path."""

from __future__ import annotations

from softplc.runtime.program import compile_files, locate

CYCLE_MS = 10


class Bench:
    def __init__(self, decls: str, body: str, profile: str = "codesys") -> None:
        text = f"PROGRAM bench\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"
        program = compile_files([], profile=profile, texts={"bench.st": text})
        self.runner = program.runner("bench", cycle_time_ms=CYCLE_MS)

    def __getitem__(self, path: str):
        return self.runner.get(path)

    def __setitem__(self, path: str, value) -> None:
        holder, attr, _type = locate(path, (self.runner.instance,))
        setattr(holder, attr, value)

    def step(self, cycles: int = 1, **inputs) -> Bench:
        for name, value in inputs.items():
            self[name] = value
        self.runner.run(cycles)
        return self
