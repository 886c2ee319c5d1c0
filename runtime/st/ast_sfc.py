"""The syntax tree of a Sequential Function Chart (IEC 61131-3 ed.3 6.7):
steps, transitions, actions, as written in ST's textual SFC (or made from
a graphical one by an importer). A POU's ``sfc`` (ast.POU) holds its
network; the checker makes it steps and actions (check/checker_sfc.py).
"""

from __future__ import annotations

from dataclasses import dataclass

from .ast import Expr, Node


@dataclass(slots=True, eq=False)
class SfcAssoc(Node):
    """``action(qualifier, time, indicator ...)`` in a step: args as written
    (the checker reads the qualifier, the time and the indicators)."""

    action: str
    args: list  # Expr


@dataclass(slots=True, eq=False)
class SfcStep(Node):
    name: str
    initial: bool
    assocs: list  # SfcAssoc


@dataclass(slots=True, eq=False)
class SfcTransition(Node):
    """TRANSITION [name] [(PRIORITY := n)] FROM sources TO targets, with its
    condition either an expression (``:= expr;``) or ST statements that
    assign the transition's name (``: ... END_TRANSITION``)."""

    name: str | None
    priority: Expr | None
    sources: list  # (step name, Pos)
    targets: list  # (step name, Pos)
    cond: Expr | None = None
    body: list | None = None


@dataclass(slots=True, eq=False)
class SfcAction(Node):
    name: str
    body: list  # statements


@dataclass(slots=True, eq=False)
class SfcNetwork(Node):
    steps: list  # SfcStep, in source order
    transitions: list  # SfcTransition, in source order
    actions: list  # SfcAction
