"""The expressions of a sweep's [result]: values to tabulate and
expectations that must hold at the end of a scenario.

They are Python's expression syntax, read by ast and evaluated here, never
by eval(): numbers, strings, True/False, `and or not`, comparisons
(`== != < <= > >=`, chained), `+ - * / // %`, `abs min max round len`, and
names, which are

  an ST path          Genset.State, Line.parts[2].weight, CANOPEN_NODE[40].State
                      (the testing API's plc.read: an enumeration equals its
                      enumerator's name, Genset.State == 'Running')
  records.SIM...      what the simulated device SIM recorded (--final-json's
                      "[[sim]]"): records.mpu2s1.closes[0].phase_deg
  param('KEY')        the scenario's value of a sweep key: param('sim.mpu2s1.slip')
  fault               the first runtime fault's text, '' when none

A value that is not there (no close recorded: closes[0]) is None, and an
expectation that meets one is false, with the reason.
"""

from __future__ import annotations

import ast
import operator
from collections.abc import Callable
from typing import Any

_COMPARE = {
    ast.Eq: operator.eq,
    ast.NotEq: operator.ne,
    ast.Lt: operator.lt,
    ast.LtE: operator.le,
    ast.Gt: operator.gt,
    ast.GtE: operator.ge,
}
_BINARY = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.FloorDiv: operator.floordiv,
    ast.Mod: operator.mod,
}
_FUNCTIONS: dict = {"abs": abs, "min": min, "max": max, "round": round, "len": len}
MAX_LENGTH = 500


class ExpressionError(ValueError):
    """An expression that is not one of the forms above."""


class Missing(Exception):
    """A name or an element that is not there: the value is None."""


def parse_expression(text: str) -> ast.Expression:
    if len(text) > MAX_LENGTH:
        raise ExpressionError(f"longer than {MAX_LENGTH} characters")
    try:
        tree = ast.parse(text, mode="eval")
    except SyntaxError as e:
        raise ExpressionError(f"{text!r}: not an expression ({e.msg})") from None
    for node in ast.walk(tree):
        if not isinstance(node, _ALLOWED):
            raise ExpressionError(f"{text!r}: {type(node).__name__} is not allowed here")
        if isinstance(node, ast.Call):
            name = node.func.id if isinstance(node.func, ast.Name) else None
            if name not in (*_FUNCTIONS, "param") or node.keywords:
                raise ExpressionError(f"{text!r}: only {', '.join(_FUNCTIONS)} and param('KEY') may be called")
    return tree


_ALLOWED = (
    ast.Expression,
    ast.BoolOp,
    ast.And,
    ast.Or,
    ast.UnaryOp,
    ast.Not,
    ast.USub,
    ast.UAdd,
    ast.BinOp,
    ast.Compare,
    ast.Constant,
    ast.Name,
    ast.Load,
    ast.Attribute,
    ast.Subscript,
    ast.Call,
    *_COMPARE,
    *_BINARY,
)


class Scope:
    """What names mean at the end of one scenario: read(path) for ST paths
    (KeyError when there is none), the records, the parameters, the fault."""

    def __init__(self, read: Callable[[str], Any], records: dict, params: dict, fault: str) -> None:
        self.read, self.records, self.params, self.fault = read, records, params, fault


def evaluate(text: str, scope: Scope) -> Any:
    """The expression's value, None where a part of it is not there."""
    try:
        return _eval(parse_expression(text).body, scope)
    except (Missing, TypeError):  # abs(None), 'a' < 1
        return None


def check(text: str, scope: Scope) -> str | None:
    """None when the expectation holds, else why not."""
    try:
        value = _eval(parse_expression(text).body, scope)
    except Missing as e:
        return f"{text}: {e}"
    except TypeError as e:
        return f"{text}: {e}"
    return None if value else f"{text}: false"


def _eval(node: ast.AST, scope: Scope) -> Any:
    if isinstance(node, ast.Constant):
        return node.value
    if isinstance(node, ast.BoolOp):
        is_and = isinstance(node.op, ast.And)
        result: Any = is_and
        for value in node.values:
            result = _eval(value, scope)
            if bool(result) != is_and:
                return result
        return result
    if isinstance(node, ast.UnaryOp):
        operand = _eval(node.operand, scope)
        if isinstance(node.op, ast.Not):
            return not operand
        _need_number(operand)
        return -operand if isinstance(node.op, ast.USub) else +operand
    if isinstance(node, ast.BinOp):
        left, right = _eval(node.left, scope), _eval(node.right, scope)
        _need_number(left, right)
        try:
            return _BINARY[type(node.op)](left, right)
        except ZeroDivisionError:
            raise Missing("division by zero") from None
    if isinstance(node, ast.Compare):
        left = _eval(node.left, scope)
        for op, right_node in zip(node.ops, node.comparators):
            right = _eval(right_node, scope)
            if not _COMPARE[type(op)](left, right):
                return False
            left = right
        return True
    if isinstance(node, ast.Call):
        assert isinstance(node.func, ast.Name)
        args = [_eval(a, scope) for a in node.args]
        if node.func.id == "param":
            if len(args) != 1 or args[0] not in scope.params:
                raise Missing(f"param({', '.join(map(repr, args))}): the keys are {', '.join(scope.params)}")
            return scope.params[args[0]]
        return _FUNCTIONS[node.func.id](*args)
    return _name(node, scope)


def _need_number(*values: Any) -> None:
    for value in values:
        if value is None:
            raise Missing("a value is not there")


def _name(node: ast.AST, scope: Scope) -> Any:
    """A dotted, indexed name: records..., fault, or an ST path."""
    parts = _parts(node, scope)
    head = parts[0]
    if head == "records":
        value: Any = scope.records
        for part in parts[1:]:
            try:
                value = value[part]
            except (KeyError, IndexError, TypeError):
                raise Missing(f"{_text(parts)}: no {part!r} in the records") from None
        return value
    if head == "fault" and len(parts) == 1:
        return scope.fault
    path = _text(parts)
    try:
        return scope.read(path)
    except KeyError as e:
        raise Missing(str(e.args[0]) if e.args else path) from None


def _parts(node: ast.AST, scope: Scope) -> list:
    if isinstance(node, ast.Name):
        return [node.id]
    if isinstance(node, ast.Attribute):
        return [*_parts(node.value, scope), node.attr]
    if isinstance(node, ast.Subscript):
        index = _eval(node.slice, scope)
        if not isinstance(index, int | str) or isinstance(index, bool):
            raise Missing(f"an index must be a whole number, not {index!r}")
        return [*_parts(node.value, scope), index]
    raise Missing(f"{ast.unparse(node)} is not a name")


def _text(parts: list) -> str:
    out = str(parts[0])
    for part in parts[1:]:
        out += f"[{part}]" if isinstance(part, int) else f".{part}"
    return out
