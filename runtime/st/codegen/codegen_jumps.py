"""Code generation of JMP and labels: Python has no goto.

A statement list holding a label some JMP names (checker_jumps.py) becomes
a small state machine; a list without one is generated as before, so code
without labels is unchanged and no slower. The labels cut the list into
segments, each run while the state is at most its index::

    _j = 0
    while True:                # counts against the loop budget, as WHILE
        if _j <= 0: <statements before the first label>
        if _j <= 1: <from label 1>          JMP label1  ->  _j = 1; continue
        ...
        break

A JMP from inside loops nested in that list (or an EXIT or CONTINUE from
inside such a list to the loop around it) cannot ``continue`` the right
Python loop directly: it sets ``_go`` to a number naming the transfer and
breaks out; after each loop it leaves, ``if _go == n:`` either finishes
the transfer (the loop it was meant for encloses this point) or breaks on.
FOR variables of the loops left keep their values (as EXIT does), WHILE
and REPEAT hand their loop budget back as when they end.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .. import ast as A
from .codegen_base import CodeGenBase


@dataclass(eq=False)
class JumpFrame:
    """A statement list made a state machine: its state variable, its
    loop-budget local and its jumped-to labels (id(Label) -> index)."""

    state: str
    wd: str
    labels: dict = field(default_factory=dict)


class JumpGen(CodeGenBase):
    """Statement lists with labels, JMP, and transfers out of loops."""

    def _dispatch(self, stmts: list) -> None:
        segments: list = [[]]
        frame = JumpFrame(self.tmp("j"), "")
        for s in stmts:
            if isinstance(s, A.Label) and s.jumped_to:
                frame.labels[id(s)] = len(segments)
                segments.append([])
            else:
                segments[-1].append(s)
        for label_id, k in frame.labels.items():
            self.fn.labels[label_id] = (frame, k)
        # a watchdog fault in the state machine is located at its first label
        self.pos = next(s.pos for s in stmts if isinstance(s, A.Label) and s.jumped_to)
        frame.wd = self._loop_budget_take()
        self.emit("_go = 0")
        self.emit(f"{frame.state} = 0")
        self.emit("while True:")
        self.indent += 1
        self._watchdog_tick(frame.wd)
        self.fn.loop_kinds.append(("jump", frame))
        for k, seg in enumerate(segments):
            if k == 0 and not seg:
                continue
            self.emit(f"if {frame.state} <= {k}:")
            self.indent += 1
            self._body(seg)
            self.indent -= 1
        self.emit("break")
        self.fn.loop_kinds.pop()
        self.indent -= 1
        self._loop_budget_give(frame.wd)

    def _jump(self, s: A.Jump) -> None:
        assert s.target is not None  # the checker resolved it
        frame, k = self.fn.labels[id(s.target)]
        kinds = self.fn.loop_kinds
        at = next(i for i in range(len(kinds) - 1, -1, -1) if kinds[i][0] == "jump" and kinds[i][1] is frame)
        if at == len(kinds) - 1:
            self.emit(f"{frame.state} = {k}")
            self.emit("continue")
            return
        for kind, data in kinds[at + 1 :]:
            if kind == "for" and data[2]:  # the FOR variables of the loops left keep their values
                var, cur, _local = data
                self.emit_store(var, cur, var.ty, None, trusted=True)
        self._transfer(at, ("jmp", frame, k))

    def _leave_through_labels(self, word: str) -> bool:
        """EXIT or CONTINUE inside a labelled list in a loop: True when it
        was generated here (a transfer out of the state machine)."""
        kinds = self.fn.loop_kinds
        if kinds[-1][0] != "jump":
            return False
        at = next(i for i in range(len(kinds) - 1, -1, -1) if kinds[i][0] != "jump")
        kind, data = kinds[at]
        if word == "break" and kind == "for" and data[2]:
            var, cur, _local = data
            self.emit_store(var, cur, var.ty, None, trusted=True)
        self._transfer(at, ("exit",) if word == "break" else ("continue", kind, data))
        return True

    def _transfer(self, target: int, action: tuple) -> None:
        """Leave the Python loops above loop_kinds[target]: name the
        transfer in _go, break; _after_loop goes on after each loop."""
        self.fn.transfers += 1
        token = self.fn.transfers
        self.emit(f"_go = {token}")
        self.emit("break")
        self.fn.crossing.setdefault(len(self.fn.loop_kinds) - 1, []).append((token, target, action))

    def _after_loop(self) -> None:
        """After a statement: the transfers that left the loop it made."""
        depth = len(self.fn.loop_kinds)
        pending = self.fn.crossing.pop(depth, None)
        if not pending:
            return
        for token, target, action in pending:
            self.emit(f"if _go == {token}:")
            self.indent += 1
            if target == depth - 1:
                self.emit("_go = 0")
                if action[0] == "jmp":
                    self.emit(f"{action[1].state} = {action[2]}")
                    self.emit("continue")
                elif action[0] == "exit":
                    self.emit("break")
                else:
                    if action[1] == "repeat":
                        self.pos = action[2][0].pos
                        self.emit(f"if {self.ex(action[2][0])}: break")
                    self.emit("continue")
            else:
                self.emit("break")
                self.fn.crossing.setdefault(depth - 1, []).append((token, target, action))
            self.indent -= 1
