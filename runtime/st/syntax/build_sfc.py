"""The AST builder's SFC part: the textual form of Sequential Function Chart
(IEC 61131-3 ed.3 6.7, ed.2 2.6) in a PROGRAM or FUNCTION_BLOCK body:
steps with their action associations, transitions and actions. E158: an
ACTION written in SFC, statements before a network."""

from __future__ import annotations

from .. import ast_sfc
from .build_base import BuilderBase
from .lexer import Tok


class SfcBuilder(BuilderBase):
    """Rule callbacks of the sfc_* rules of grammar.lark."""

    def sfc_network(self, c):
        steps = [x for x in c if isinstance(x, ast_sfc.SfcStep)]
        transitions = [x for x in c if isinstance(x, ast_sfc.SfcTransition)]
        actions = [x for x in c if isinstance(x, ast_sfc.SfcAction)]
        return ast_sfc.SfcNetwork(steps, transitions, actions, pos=self._span(c[0], c[-1]))

    def sfc_step(self, c):
        # (INITIAL_STEP | STEP) ident sfc_assoc* END_STEP
        assocs = [x for x in c[2:] if isinstance(x, ast_sfc.SfcAssoc)]
        return ast_sfc.SfcStep(c[1].value, c[0].type == "INITIAL_STEP", assocs, pos=self._span(c[0], c[-1]))

    def sfc_assoc(self, c):
        # ident LPAR [expr ("," expr)*] RPAR
        args = [x for x in c[2:-1] if x is not None]
        return ast_sfc.SfcAssoc(c[0].value, args, pos=self._span(c[0], c[-1]))

    def sfc_priority(self, c):
        # LPAR ident expr RPAR (":=" is dropped)
        if c[1].value.upper() != "PRIORITY":
            self.ctx.report(
                "E001",
                f"'{c[1].value}': a transition takes only PRIORITY in parentheses",
                self._tpos(c[1]),
                "write TRANSITION name (PRIORITY := 1) FROM s1 TO s2 := cond; END_TRANSITION",
            )
        return c[2]

    def sfc_steps(self, c):
        return [(t.value, self._tpos(t)) for t in c if isinstance(t, Tok) and t.type not in ("LPAR", "RPAR")]

    def sfc_transition(self, c):
        # TRANSITION [ident] [sfc_priority] FROM sfc_steps sfc_steps (ASSIGN expr | COLON body) END_TRANSITION
        name = c[1].value if c[1] is not None else None
        sources, targets, kind, cond = c[4], c[5], c[6], c[7]
        pos = self._span(c[0], c[-1])
        if kind.type == "ASSIGN":
            return ast_sfc.SfcTransition(name, c[2], sources, targets, cond=cond, pos=pos)
        if name is None:
            self.ctx.report(
                "E001",
                "a transition whose condition is statements needs a name",
                self._tpos(kind),
                "name it and assign the name: TRANSITION t1 FROM s1 TO s2 : t1 := cond; END_TRANSITION",
            )
        return ast_sfc.SfcTransition(name, c[2], sources, targets, body=cond, pos=pos)

    def sfc_action(self, c):
        # ACTION ident (body | sfc_network) END_ACTION
        body = c[2] if isinstance(c[2], list) else self.sfc_in_action(c[1].value, c[2])
        return ast_sfc.SfcAction(c[1].value, body, pos=self._span(c[0], c[-1]))

    def sfc_in_action(self, name: str, net: ast_sfc.SfcNetwork) -> list:
        """E158 for an ACTION written in SFC (CODESYS allows it; here the
        network of a POU is its body only); the action's statements: none."""
        self.ctx.report(
            "E158",
            f"ACTION {name} is written in SFC: an action's SFC network is not supported",
            net.pos,
            "make the sequence the body of a FUNCTION_BLOCK and call an instance of it in the action",
        )
        return []

    def sfc_after_statements(self, body: list, net: ast_sfc.SfcNetwork) -> None:
        """E158 for statements before the first step of an SFC body."""
        self.ctx.report(
            "E158",
            "statements before an SFC network: a POU's body is either statements or an SFC network",
            self._span(body[0], body[-1]),
            "move the statements into an ACTION and associate it with the steps it belongs to, e.g. a(N)",
        )
