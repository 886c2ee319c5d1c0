"""The checker's jumps: which label each JMP goes to.

CODESYS and TwinCAT ST have ``label: statement`` and ``JMP label;``
(CODESYS "ST Statement: JMP"; IEC 61131-3 ed.3 has jumps in IL only). The
rules, after CODESYS:

* a label is a name unique in its body (a POU's statements, or one
  action's): the same name twice is E076;
* a JMP reaches the labels of its own statement list and of the lists that
  enclose it, forward and backward: it may leave an IF, a CASE or a loop
  (like EXIT, the FOR variable keeps its value), but never jump into one
  (CODESYS C0117 "No such label within the scope of the 'JMP' statement").
  A label out of reach or unknown is E075.

IEC 61131-3 ed.3's ST has no jumps (7.3.3, Table 72: the statements are
assignment, call, RETURN, IF, CASE, FOR, WHILE, REPEAT, EXIT, CONTINUE):
a JMP is E159 in the profiles that follow it (profile.jumps_in_st).
"""

from __future__ import annotations

from .. import ast as A
from ..profile import names_where
from .checker_base import CheckerBase


def statement_lists(s: A.Stmt) -> list:
    """The statement lists directly inside s (IF branches, CASE branches,
    loop bodies)."""
    if isinstance(s, A.If):
        return [body for _, body in s.branches] + ([s.else_body] if s.else_body else [])
    if isinstance(s, A.Case):
        return [br.body for br in s.branches] + ([s.else_body] if s.else_body else [])
    if isinstance(s, (A.For, A.While, A.Repeat)):
        return [s.body]
    return []


class JumpChecks(CheckerBase):
    """Labels and JMP."""

    def _check_jumps(self, body: list) -> None:
        labels: dict = {}  # UPPER -> Label, the whole body
        jumps: list = []  # (Jump, [the label dicts of the lists it sees])
        self._gather_jumps(body, [], labels, jumps)
        for jmp, _visible in jumps if not self.profile.jumps_in_st else ():
            if self._lowered(jmp.pos):
                continue  # written from IL or a graphical body, where JMP is the language's own
            self.d.error(
                "E159",
                f"JMP {jmp.label}: IEC 61131-3 ST has no jumps (only IL has JMP)",
                jmp.pos,
                "use IF, a loop with EXIT or CONTINUE, or a CASE state machine; the "
                f"{names_where(lambda p: p.jumps_in_st)} profiles accept JMP",
            )
        for jmp, visible in jumps:
            key = jmp.label.upper()
            target = next((lists[key] for lists in reversed(visible) if key in lists), None)
            if target is not None:
                jmp.target = target
                target.jumped_to = True
            elif key in labels:
                self.d.error(
                    "E075",
                    f"JMP {jmp.label}: the label is inside a statement this JMP is not in",
                    jmp.pos,
                    f"the label is at {labels[key].pos}; a JMP may leave an IF, CASE or loop but not jump into one",
                )
            else:
                self.d.error(
                    "E075",
                    f"JMP {jmp.label}: no such label",
                    jmp.pos,
                    self._suggest(key, [lab.name for lab in labels.values()])
                    or f"write '{jmp.label}:' before the statement to jump to",
                )

    def _lowered(self, pos: A.Pos) -> bool:
        """Whether pos lies in ST that an importer wrote from another language."""
        return any(first <= pos.line <= last for first, last in self.lowered_lines.get(pos.file, ()))

    def _gather_jumps(self, stmts: list, outer: list, labels: dict, jumps: list) -> None:
        here: dict = {}  # the labels of this list
        visible = [*outer, here]
        for s in stmts:
            if isinstance(s, A.Label):
                key = s.name.upper()
                first = labels.get(key)
                if first is not None:
                    self.d.error(
                        "E076",
                        f"the label '{s.name}' is defined twice",
                        s.pos,
                        f"the first is at {first.pos}; a label names one place in the body",
                    )
                    continue
                labels[key] = here[key] = s
            elif isinstance(s, A.Jump):
                jumps.append((s, visible))
            else:
                for inner in statement_lists(s):
                    self._gather_jumps(inner, visible, labels, jumps)
