"""Structured Text source -> ``ast.SourceFile``.

    sf = parse_source(text, path, diags)

Never raises: every problem becomes a coded diagnostic in ``diags`` (E001
syntax, E002 invalid character, E003 invalid literal, E004 unterminated
comment/string/pragma, E005 structural, E009 internal; W101 ignored
EXTENDS/IMPLEMENTS) and the result holds whatever could be parsed.

How it works:
  1. lexer.strip_comments blanks out comments and pragmas, keeping every
     line and column; lexer.Lexer cuts the rest into tokens.
  2. The LALR(1) table comes from lark (grammar.lark, built once per
     process; the analysis is cached). The token loop is ours: ``_feed``
     runs the table and calls the ``_Builder`` callbacks, which build the
     ``ast`` nodes directly (no parse tree).
  3. A syntax error does not end the parse: ``_recover`` inserts a missing
     token, handles a known mistake, or skips to a synchronising token
     (';', END_*, THEN, ...) and pops the stack until it fits. Errors right
     after another one are its echoes and are not reported (``calm``).
  4. Pragmas are attached to the item that follows them.
"""
from __future__ import annotations

import difflib
import os
import re
import threading
from bisect import bisect_left
from pathlib import Path
from typing import Optional

from lark import Lark
from lark.lexer import PatternStr
from lark.parse_tree_builder import ExpandSingleChild
from lark.parsers.lalr_analysis import Shift

from . import ast
from .diagnostics import DiagnosticBag
from .lexer import INVALID_RUN, Lexer, Tok, line_col, strip_comments
from .literals import (LiteralError, parse_based, parse_c_hex, parse_hash_literal, parse_int,
                       parse_located, parse_real, parse_string)

__all__ = ["parse_source"]

MAX_ERRORS = 100
# Limits beyond which the input is refused (E005): later stages walk the
# tree recursively, and generated Python has limits of its own (100 levels
# of indentation, 200 nested parentheses). The parser stack grows by 1-4
# entries per nesting level (a parenthesis, a unary operator, IF in IF);
# a chain a + b + c ... makes a tree as deep as it is long.
MAX_STACK = 300
MAX_OPERATORS = 1000

# Keywords reserved everywhere: never names, so a misplaced END_IF is
# reported as such. The others (SET, RESET, AT, ON, WITH, TASK, RETAIN,
# CONSTANT, POINTER, ...) are keywords only where the grammar expects them.
_RESERVED = frozenset("""
    PROGRAM END_PROGRAM FUNCTION END_FUNCTION FUNCTION_BLOCK END_FUNCTION_BLOCK TYPE END_TYPE
    STRUCT END_STRUCT ARRAY STRING WSTRING REF_TO VAR VAR_INPUT VAR_OUTPUT VAR_IN_OUT VAR_GLOBAL
    VAR_EXTERNAL VAR_TEMP VAR_STAT VAR_CONFIG END_VAR END_CONFIGURATION END_RESOURCE
    IF THEN ELSIF ELSE END_IF CASE OF END_CASE FOR TO BY DO END_FOR WHILE END_WHILE REPEAT UNTIL
    END_REPEAT EXIT CONTINUE RETURN AND AND_THEN OR OR_ELSE XOR NOT MOD TRUE FALSE
""".split())

def _identifier_from_path(path: str) -> str:
    """The PROGRAM name for a file of bare statements: 'ltmr/write-sdo.st' -> 'write_sdo'."""
    stem = re.sub(r"[^A-Za-z0-9_]+", "_", Path(path).stem)
    stem = re.sub(r"_{2,}", "_", stem).strip("_")
    if not stem:
        return "main"
    return "_" + stem if stem[0].isdigit() else stem


# ---------------------------------------------------------------- AST builder

_BINARY_OPS = {"OR": "OR", "OR_ELSE": "OR_ELSE", "XOR": "XOR", "AND": "AND", "AMP": "AND",
               "AND_THEN": "AND_THEN", "EQ": "=", "NE": "<>", "LT": "<", "GT": ">", "LE": "<=",
               "GE": ">=", "PLUS": "+", "MINUS": "-", "STAR": "*", "SLASH": "/", "MOD": "MOD",
               "POW": "**"}
_PRECEDENCE = {"OR": 1, "OR_ELSE": 1, "XOR": 2, "AND": 3, "AMP": 3, "AND_THEN": 3, "EQ": 4, "NE": 4,
               "LT": 5, "GT": 5, "LE": 5, "GE": 5, "PLUS": 6, "MINUS": 6, "STAR": 7, "SLASH": 7, "MOD": 7,
               "POW": 8}
_UNARY_OPS = {"MINUS": "-", "PLUS": "+", "NOT": "NOT"}
_ASSIGN_OPS = {"ASSIGN": ":=", "S_ASSIGN": "S=", "R_ASSIGN": "R=", "REF_ASSIGN": "REF="}
_NAME_TYPES = frozenset(("NAME", "SET", "RESET"))


def _start(x) -> tuple:
    if isinstance(x, Tok):
        return x.line, x.column
    return x.pos.line, x.pos.col


def _end(x) -> tuple:
    if isinstance(x, Tok):
        return x.end_line, x.end_column
    return x.pos.end_line, x.pos.end_col


class _Builder:
    """lark callbacks (run inside the parser): children -> ast nodes.

    One instance serves every parse (lark binds the callbacks once); ``begin``
    gives it the state of the current parse, which ``_LOCK`` keeps unique."""

    file = "<source>"
    ctx: "_Parse"

    def begin(self, ctx: "_Parse") -> None:
        self.ctx = ctx
        self.file = ctx.path

    # -- positions
    def _tpos(self, t: Tok) -> ast.Pos:
        return ast.Pos(self.file, t.line, t.column, t.end_line, t.end_column)

    def _span(self, first, last) -> ast.Pos:
        return ast.Pos(self.file, *_start(first), *_end(last))

    def _literal_error(self, e: LiteralError, tok: Tok) -> None:
        self.ctx.report("E003", e.message, self._tpos(tok), e.hint, always=True)

    # -- top level
    # Constructs that parse but cannot stand are reported and left out of
    # the tree, so later stages only ever see well-formed declarations.
    def source(self, c):
        decls = []
        for d in c:
            if isinstance(d, list):
                decls.extend(d)
            elif isinstance(d, ast.VarBlock) and d.kind != "VAR_GLOBAL":
                self.ctx.report("E005", f"{d.kind} block outside a POU", d.pos,
                                "only VAR_GLOBAL blocks (a global variable list) stand on their own"
                                + (", VAR_CONFIG goes into a CONFIGURATION" if d.kind == "VAR_CONFIG" else ""))
            else:
                decls.append(d)
        return ast.SourceFile(self.ctx.path, decls, pos=ast.Pos(self.file, 1, 1))

    def bare_source(self, c):
        body = [s for s in c if s is not None]
        pou = ast.POU("PROGRAM", _identifier_from_path(self.ctx.path), [], body,
                      pos=self._span(body[0], body[-1]) if body else ast.Pos(self.file, 1, 1))
        return ast.SourceFile(self.ctx.path, [pou], pos=ast.Pos(self.file, 1, 1))

    def _pou(self, kind: str, c) -> ast.POU:
        var_blocks = [x for x in c if isinstance(x, ast.VarBlock)]
        body = next(x for x in c if isinstance(x, list))
        ret = c[2] if kind == "FUNCTION" else None
        pou = ast.POU(kind, c[1].value, var_blocks, body, return_type=ret, pos=self._span(c[0], c[-1]))
        # Where the header ends: a pragma before this point belongs to the POU.
        first = var_blocks[0] if var_blocks else body[0] if body else c[-1]
        self.ctx.pou_headers.append((pou, _start(c[0]), _start(first)))
        self.ctx.items.append(pou)
        return pou

    def program(self, c):
        return self._pou("PROGRAM", c)

    def function(self, c):
        return self._pou("FUNCTION", c)

    def function_block(self, c):
        return self._pou("FUNCTION_BLOCK", c)

    def fb_inherit(self, c):
        self.ctx.diags.warning("W101", f"{c[0].value.upper()} is ignored: inheritance and interfaces are not supported",
                               self._span(c[0], c[-1]),
                               "declare the inherited variables in this block instead")
        return None

    def body(self, c):
        return [s for s in c if s is not None]

    # -- declarations
    def var_block(self, c):
        kind = c[0].type
        quals = {t.type for t in c if isinstance(t, Tok)}
        decls = self._plain_names([d for group in c if isinstance(group, list) for d in group],
                                  dotted_ok=kind == "VAR_CONFIG")
        blk = ast.VarBlock(kind, decls, constant="CONSTANT" in quals,
                           retain="RETAIN" in quals,
                           persistent="PERSISTENT" in quals, pos=self._span(c[0], c[-1]))
        self.ctx.items.append(blk)
        return blk

    def _plain_names(self, decls: list, dotted_ok: bool = False) -> list:
        """The declarations without those of a dotted name (inst.x), which
        only VAR_CONFIG may have: reported and dropped."""
        if dotted_ok:
            return decls
        kept = []
        for d in decls:
            if "." in d.name:
                self.ctx.report("E005", f"'{d.name}': a qualified name is only allowed in VAR_CONFIG", d.pos,
                                "declare a plain name here")
            else:
                kept.append(d)
        return kept

    def var_name(self, c):
        return ".".join(t.value for t in c), c[0], c[-1]

    def var_decl(self, c):
        # var_name tuples..., LOCATED|None, type, init|None
        *names, loc, spec, init = c
        location = self._address(loc) if loc is not None else None
        end = init if init is not None else spec
        out = []
        for name, first, _ in names:
            d = ast.VarDecl(name, spec, init, location, pos=self._span(first, end))
            self.ctx.items.append(d)
            out.append(d)
        return out

    def unnamed_var_decl(self, c):
        loc, spec, init = c
        # 'AT %QW1 : WORD;' gets a name from the address, '__at_QW1': an
        # identifier for later stages, unlikely to be declared as well (IEC
        # names cannot have '__'; if one is, it is a duplicate declaration).
        name = "__at_" + re.sub(r"\W", "_", loc.value[1:].replace("*", "star"))
        d = ast.VarDecl(name, spec, init, self._address(loc),
                        pos=self._span(loc, init if init is not None else spec))
        self.ctx.items.append(d)
        return [d]

    def type_block(self, c):
        return [d for d in c if isinstance(d, ast.TypeDecl)]

    def type_decl(self, c):
        name, spec = c[0], c[1]
        init = c[2] if len(c) > 2 else None
        d = ast.TypeDecl(name.value, spec, init, pos=self._span(name, init if init is not None else spec))
        self.ctx.items.append(d)
        return d

    def named_type(self, c):
        return ast.NamedType(c[0].value, pos=self._tpos(c[0]))

    def string_type(self, c):
        return ast.StringTypeSpec(c[0].type == "WSTRING", c[2] if len(c) > 1 else None,
                                  pos=self._span(c[0], c[-1]))

    def array_type(self, c):
        ranges = [r for r in c[2:-1] if not isinstance(r, Tok)]
        return ast.ArrayTypeSpec(ranges, c[-1], pos=self._span(c[0], c[-1]))

    def array_range(self, c):
        return None if len(c) == 1 else (c[0], c[1])

    def ref_type(self, c):
        return ast.RefTypeSpec(c[-1], pointer=c[0].type == "POINTER", pos=self._span(c[0], c[-1]))

    def subrange_type(self, c):
        base = ast.NamedType(c[0].value, pos=self._tpos(c[0]))
        return ast.SubrangeTypeSpec(base, c[2], c[3], pos=self._span(c[0], c[-1]))

    def enum_type(self, c):
        return ast.EnumTypeSpec([v for v in c if isinstance(v, tuple)], pos=self._span(c[0], c[-1]))

    def based_enum_type(self, c):
        base = ast.NamedType(c[0].value, pos=self._tpos(c[0]))
        return ast.EnumTypeSpec([v for v in c if isinstance(v, tuple)], base, pos=self._span(c[0], c[-1]))

    def typed_enum_type(self, c):
        return ast.EnumTypeSpec([v for v in c if isinstance(v, tuple)], c[-1], pos=self._span(c[0], c[-1]))

    def enum_value(self, c):
        return c[0].value, c[1], self._span(c[0], c[1] if c[1] is not None else c[0])

    def struct_type(self, c):
        members = self._plain_names([d for group in c[1:-1] for d in group])
        return ast.StructTypeSpec(members, pos=self._span(c[0], c[-1]))

    def array_init(self, c):
        items = [x if isinstance(x, tuple) else (None, x) for x in c[1:-1]]
        return ast.ArrayInit(items, pos=self._span(c[0], c[-1]))

    def repeat_item(self, c):
        count = self.int_lit(c[:1])
        return count, c[2]

    def struct_init(self, c):
        return ast.StructInit(list(c[1:-1]), pos=self._span(c[0], c[-1]))

    def field_init(self, c):
        name, init = c
        return name.value, init, self._span(name, init)

    # -- configuration
    def configuration(self, c):
        blocks = [x for x in c if isinstance(x, ast.VarBlock)]
        resources = [x for x in c if isinstance(x, ast.Resource)]
        tasks = [x for x in c if isinstance(x, ast.TaskDecl)]
        programs = [x for x in c if isinstance(x, ast.ProgramConfig)]
        if tasks or programs:
            # A configuration without RESOURCE has one implicit resource.
            resources.append(ast.Resource(c[1].value, None, [], tasks, programs, pos=self._span(c[0], c[-1])))
        return ast.Configuration(c[1].value, blocks, resources, pos=self._span(c[0], c[-1]))

    def resource(self, c):
        names = [t for t in c[1:3] if isinstance(t, Tok) and t.type in _NAME_TYPES]
        return ast.Resource(names[0].value, names[1].value if len(names) > 1 else None,
                            [x for x in c if isinstance(x, ast.VarBlock)],
                            [x for x in c if isinstance(x, ast.TaskDecl)],
                            [x for x in c if isinstance(x, ast.ProgramConfig)],
                            pos=self._span(c[0], c[-1]))

    def task_decl(self, c):
        params = {}
        for p in c[3:-1]:
            if p is not None:
                params[p[0].upper()] = p[1]
        return ast.TaskDecl(c[1].value, params, pos=self._span(c[0], c[-1]))

    def task_param(self, c):
        return c[0].value, c[1]

    def program_config(self, c):
        # PROGRAM, RETAIN|NON_RETAIN|None, names (instance, [task], type), LPAR|None, args|None, RPAR|None
        names = [t for t in c[2:] if isinstance(t, Tok) and t.type in _NAME_TYPES]
        args = next((x for x in c if isinstance(x, list)), [])
        last = next((x for x in reversed(c) if x is not None), c[0])
        return ast.ProgramConfig(names[0].value, names[-1].value, names[1].value if len(names) == 3 else None,
                                 args, retain=c[1] is not None and c[1].type == "RETAIN",
                                 pos=self._span(c[0], last))

    # -- statements
    def _add_stmt(self, node):
        self.ctx.items.append(node)
        return node

    def assign_stmt(self, c):
        target, op, value = c
        return self._add_stmt(ast.Assign(target, value, _ASSIGN_OPS[op.type], pos=self._span(target, value)))

    def call_stmt(self, c):
        call = c[0]
        if not isinstance(call, ast.Call):
            self.ctx.report("E001", "an expression alone is not a statement", call.pos,
                            "assign it with ':=' or, to call a function block, add the argument list: fb();")
            return None
        return self._add_stmt(ast.CallStmt(call, pos=call.pos))

    def set_stmt(self, c):
        return self._add_stmt(ast.SetReset(c[0].type, c[1], pos=self._span(c[0], c[1])))

    def empty_stmt(self, c):
        return None

    def if_stmt(self, c):
        branches = [(c[1], c[2])] + [b for b in c[3:-2]]
        return self._add_stmt(ast.If(branches, c[-2], pos=self._span(c[0], c[-1])))

    def elsif_part(self, c):
        return c[0], c[1]

    def case_stmt(self, c):
        return self._add_stmt(ast.Case(c[1], list(c[2:-2]), c[-2], pos=self._span(c[0], c[-1])))

    def case_branch(self, c):
        labels, body = c[:-1], c[-1]
        return ast.CaseBranch(labels, body, pos=self._span(labels[0], body[-1] if body else labels[-1]))

    def case_range(self, c):
        return ast.CaseRange(c[0], c[1], pos=self._span(c[0], c[1]))

    def label_name(self, c):
        t = c[0]
        parts = t.value.split(".")
        node = ast.Name(parts[0], pos=ast.Pos(self.file, t.line, t.column, t.line, t.column + len(parts[0])))
        col = t.column + len(parts[0]) + 1
        for p in parts[1:]:
            col += len(p)
            node = ast.Member(node, p, pos=ast.Pos(self.file, t.line, t.column, t.line, col))
            col += 1
        return node

    def for_stmt(self, c):
        var = ast.Name(c[1].value, pos=self._tpos(c[1]))
        return self._add_stmt(ast.For(var, c[2], c[3], c[4], c[5], pos=self._span(c[0], c[-1])))

    def while_stmt(self, c):
        return self._add_stmt(ast.While(c[1], c[2], pos=self._span(c[0], c[-1])))

    def repeat_stmt(self, c):
        return self._add_stmt(ast.Repeat(c[1], c[2], pos=self._span(c[0], c[-1])))

    def exit_stmt(self, c):
        return self._add_stmt(ast.Exit(pos=self._tpos(c[0])))

    def continue_stmt(self, c):
        return self._add_stmt(ast.Continue(pos=self._tpos(c[0])))

    def return_stmt(self, c):
        return self._add_stmt(ast.Return(pos=self._tpos(c[0])))

    # -- expressions
    def expr(self, c):
        """operand, op, operand, ... -> Binary nodes by IEC precedence
        (all operators associate to the left)."""
        file = self.file
        if len(c) > 2 * MAX_OPERATORS:
            self.ctx.report("E005", f"expression too long (more than {MAX_OPERATORS} operators)",
                            self._span(c[0], c[-1]), "split it, using intermediate variables", always=True)
            return c[0]
        operands, ops = [c[0]], []

        def combine():
            op, right = ops.pop(), operands.pop()
            left = operands.pop()
            lp, rp = left.pos, right.pos
            operands.append(ast.Binary(_BINARY_OPS[op.type], left, right,
                                       pos=ast.Pos(file, lp.line, lp.col, rp.end_line, rp.end_col)))

        for i in range(1, len(c), 2):
            op = c[i]
            rank = _PRECEDENCE[op.type]
            while ops and _PRECEDENCE[ops[-1].type] >= rank:
                combine()
            ops.append(op)
            operands.append(c[i + 1])
        while ops:
            combine()
        return operands[0]

    def unary(self, c):
        op, operand = c
        return ast.Unary(_UNARY_OPS[op.type], operand, pos=self._span(op, operand))

    def paren(self, c):
        node = c[1]  # no node of its own; the inner one spans the parentheses
        node.pos = self._span(c[0], c[2])
        return node

    def _number(self, token, parse, kind: str, fallback, **extra) -> ast.Literal:
        """A numeric literal; a malformed one is reported (E003) and read as
        the fallback so that checking goes on."""
        try:
            value = parse(token.value)
        except LiteralError as e:
            self._literal_error(e, token)
            value = fallback
        return ast.Literal(kind, value, pos=self._tpos(token), **extra)

    def int_lit(self, c):
        return self._number(c[0], parse_int, "int", 0)

    def real_lit(self, c):
        return self._number(c[0], parse_real, "real", 0.0)

    def based_lit(self, c):
        return self._number(c[0], parse_based, "int", 0)

    def c_hex_lit(self, c):
        return self._number(c[0], parse_c_hex, "int", 0, c_hex=True)

    def hash_lit(self, c):
        try:
            node = parse_hash_literal(c[0].value)
        except LiteralError as e:
            self._literal_error(e, c[0])
            node = ast.Literal("int", 0)
        node.pos = self._tpos(c[0])
        return node

    def string_lit(self, c):
        t = c[0]
        try:
            value = parse_string(t.value)
        except LiteralError as e:
            self._literal_error(e, t)
            value = ""
        return ast.Literal("wstring" if t.type == "WSTRING_LIT" else "string", value, pos=self._tpos(t))

    def bool_lit(self, c):
        return ast.Literal("bool", c[0].type == "TRUE", pos=self._tpos(c[0]))

    def name(self, c):
        t = c[0]
        return ast.Name(t.value, pos=ast.Pos(self.file, t.line, t.column, t.end_line, t.end_column))

    def _address(self, t: Tok) -> ast.LocatedAddress:
        try:
            return parse_located(t.value)
        except LiteralError as e:
            self._literal_error(e, t)
            return ast.LocatedAddress("M", "", (0,), text=t.value)

    def located(self, c):
        return ast.Located(self._address(c[0]), pos=self._tpos(c[0]))

    def member(self, c):
        base, t = c
        return ast.Member(base, t.value, pos=self._span(base, t))

    def bit_access(self, c):
        base, t = c
        if t.type == "BIT_REF":  # %X3
            t = Tok("INT", t.value[2:], t.start_pos + 2, t.line, t.column + 2)
        return ast.BitAccess(base, self.int_lit([t]), pos=self._span(base, t))

    def index(self, c):
        return ast.Index(c[0], list(c[2:-1]), pos=self._span(c[0], c[-1]))

    def deref(self, c):
        return ast.Deref(c[0], pos=self._span(c[0], c[1]))

    def call(self, c):
        return ast.Call(c[0], c[2], pos=self._span(c[0], c[3]))

    def arg_list(self, c):
        return [a if isinstance(a, ast.Arg) else ast.Arg(None, a, pos=a.pos) for a in c if a is not None]

    def named_arg(self, c):
        return ast.Arg(c[0].value, c[1], pos=self._span(c[0], c[1]))

    def output_arg(self, c):
        name, arrow, target = c
        return ast.Arg(name.value, target, output=True, pos=self._span(name, target if target is not None else arrow))

    def negated_output_arg(self, c):
        _, name, _, target = c
        return ast.Arg(name.value, target, output=True, negated=True, pos=self._span(c[0], target))


# ---------------------------------------------------------------- the grammar, built once

def _cache_file() -> Optional[str]:
    """Where lark caches its grammar analysis (0.03 s to load instead of
    0.5 s to build): the user's own cache directory, never a shared /tmp
    file, since lark loads it with pickle."""
    try:
        import lark
        base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
        directory = os.path.join(base, "softplc")
        os.makedirs(directory, exist_ok=True)
        return os.path.join(directory, f"st-grammar-lark{lark.__version__}.cache")
    except Exception:
        return None


def _build_lark() -> Lark:
    grammar = Path(__file__).with_name("grammar.lark").read_text(encoding="utf-8")
    # lark's lexer is never run (lexer.Lexer is used); 'basic' is the cheapest to set up.
    options = dict(parser="lalr", lexer="basic", maybe_placeholders=True, g_regex_flags=re.ASCII,
                   transformer=_BUILDER)
    cache = _cache_file()
    if cache:
        try:
            return Lark(grammar, cache=cache, **options)
        except Exception:
            pass  # an unwritable or broken cache: build without it
    return Lark(grammar, **options)


class _Reduce:
    """A reduce action, prepared for _Parse._feed: how many values it takes,
    the callback (None: the value passes through, a ?rule with one child),
    the rule's name (for the goto), its symbols (to redo the states when a
    reduction is undone) and ``alias``: the child whose list lark's child
    filter reuses and extends in place (undo cuts it back)."""
    __slots__ = ("size", "callback", "origin", "symbols", "alias")

    def __init__(self, rule, callback) -> None:
        self.size = len(rule.expansion)
        self.symbols = tuple(str(sym.name) for sym in rule.expansion)
        passthrough = isinstance(callback, ExpandSingleChild) and self.size == 1
        self.callback = None if passthrough else callback
        self.origin = str(rule.origin.name)  # lark's names may be Token (slow to compare)
        self.alias = None
        for i, sym in enumerate(rule.expansion):
            if not (sym.is_term and sym.filter_out):
                if not sym.is_term and sym.name.startswith("_"):
                    self.alias = i
                break


def _prepare_table(lark: Lark) -> dict:
    """lark's LALR table as {state: {symbol: next state (int) | _Reduce}}."""
    callbacks = lark.parse_interactive("").parser_state.parse_conf.callbacks
    reduces: dict = {}
    rows: dict = {}
    for state, actions in lark.parser.parser.parser.parse_table.states.items():
        row = rows[state] = {}
        for symbol, (kind, arg) in actions.items():
            symbol = str(symbol)
            if kind is Shift:
                row[symbol] = arg
            else:
                if id(arg) not in reduces:
                    reduces[id(arg)] = _Reduce(arg, callbacks[arg])
                row[symbol] = reduces[id(arg)]
    return rows


_BUILDER = _Builder()
_LARK = _build_lark()
_LOCK = threading.Lock()  # _BUILDER holds the state of one parse at a time
_ROWS = _prepare_table(_LARK)
_START_STATE = _LARK.parser.parser.parser.parse_table.start_states["start"]
_END_STATE = _LARK.parser.parser.parser.parse_table.end_states["start"]
_TERMINALS = {t.name: t for t in _LARK.terminals}
_LEXER = Lexer(_TERMINALS, _RESERVED)


def _spelling(name: str) -> str:
    """Terminal name -> how it is written ('SEMICOLON' -> ';', '_ELSE' -> 'ELSE')."""
    t = _TERMINALS.get(name)
    if t is not None and isinstance(t.pattern, PatternStr):
        return t.pattern.value.upper()
    return name


_KEYWORD_TERMINALS = frozenset(n for n, t in _TERMINALS.items()
                               if isinstance(t.pattern, PatternStr) and t.pattern.value.isidentifier())
_SEMI = _LEXER.punct[";"]
_COMMA = _LEXER.punct[","]
_COLON = _LEXER.punct[":"]
_FRIENDLY = {"NAME": "a name", "LABEL_NAME": "a name", "INT": "a number", "REAL": "a number",
             "BASED_INT": "a number", "C_HEX": "a number", "HASH_LIT": "a typed literal",
             "STRING_LIT": "a string", "WSTRING_LIT": "a string", "LOCATED": "a direct address",
             "BIT_REF": "a bit number", "S_ASSIGN": "S=", "R_ASSIGN": "R=", "REF_ASSIGN": "REF=",
             "$END": "end of file"}
# Block openers -> their closer, for "END_IF expected to close the IF at line 3".
_CLOSERS = {"IF": "END_IF", "CASE": "END_CASE", "FOR": "END_FOR", "WHILE": "END_WHILE",
            "REPEAT": "END_REPEAT", "PROGRAM": "END_PROGRAM", "FUNCTION": "END_FUNCTION",
            "FUNCTION_BLOCK": "END_FUNCTION_BLOCK", "TYPE": "END_TYPE", "STRUCT": "END_STRUCT",
            "CONFIGURATION": "END_CONFIGURATION", "RESOURCE": "END_RESOURCE",
            **{k: "END_VAR" for k in ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_GLOBAL",
                                      "VAR_EXTERNAL", "VAR_TEMP", "VAR_STAT", "VAR_CONFIG")}}
_CLOSER_TYPES = frozenset(_CLOSERS.values())
_VAR_KINDS = frozenset(k for k, v in _CLOSERS.items() if v == "END_VAR")
# Tokens a broken region is skipped to before parsing resumes.
_SYNC = frozenset([_SEMI, "_ELSE", "ELSIF", "UNTIL", "THEN", "DO", "OF", "IF", "CASE", "FOR", "WHILE",
                   "REPEAT", "EXIT", "CONTINUE", "RETURN", *_CLOSERS, *_CLOSERS.values()])
# Tokens tried as "the one that is missing", in this order.
_INSERTABLE = [_SEMI, _COMMA, "THEN", "DO", "OF", "RPAR", "RSQB", "END_IF", "END_CASE", "END_FOR",
               "END_WHILE", "END_VAR", "END_STRUCT", "END_TYPE", "END_FUNCTION_BLOCK", "END_FUNCTION",
               "END_PROGRAM", "END_RESOURCE", "END_CONFIGURATION"]
# At the end of the file: closers first; ';' only when nothing else fits.
_CLOSING = [c for c in _INSERTABLE if c.startswith("END_")] + ["RPAR", "RSQB", _SEMI, "THEN", "DO", "OF"]
_KEYWORDS = sorted(_spelling(n) for n in _KEYWORD_TERMINALS)
_UNSUPPORTED = {"METHOD": "methods", "END_METHOD": "methods", "PROPERTY": "properties",
                "END_PROPERTY": "properties", "INTERFACE": "interfaces", "END_INTERFACE": "interfaces",
                "ACTION": "actions", "END_ACTION": "actions", "NAMESPACE": "namespaces",
                "END_NAMESPACE": "namespaces", "VAR_ACCESS": "VAR_ACCESS blocks"}


class _TooDeep(Exception):
    """The nesting limit (MAX_STACK) is reached; args: the token."""


class _GiveUp(Exception):
    """MAX_ERRORS reported: the rest of the file is not worth reading."""


class _Rejected(Exception):
    """The parser does not accept this token here."""


def _simulate(stack: list, ttype: str, reduced: Optional[list] = None) -> Optional[list]:
    """The state stack after feeding a token of type ttype (reductions and
    the shift), or None if the parser would reject it. Nothing is built;
    the names of the rules reduced on the way go into ``reduced``."""
    stack = list(stack)
    while True:
        action = _ROWS[stack[-1]].get(ttype)
        if action is None:
            return None
        if action.__class__ is int:
            stack.append(action)
            return stack
        if action.size:
            del stack[-action.size:]
        if reduced is not None:
            reduced.append(action.origin)
        stack.append(_ROWS[stack[-1]][action.origin])
        if ttype == "$END" and stack[-1] == _END_STATE:
            return stack


def _is_bare(value) -> bool:
    """A parser stack value that is a name or expression but not a call:
    followed by ';' it would make a bogus call statement."""
    return isinstance(value, Tok) or (isinstance(value, ast.Expr) and not isinstance(value, ast.Call))


def _synthetic(ttype: str, at: Tok, after: bool = True) -> Tok:
    """A token the parser is given by recovery, placed just after (or on) at."""
    t = Tok(ttype, _spelling(ttype), at.end_pos if after else at.start_pos, at.line,
            at.end_column if after else at.column)
    t.end_column = t.column  # it takes no room in the text
    return t


# ---------------------------------------------------------------- one parse

class _Parse:
    """One run of the parser over one file."""

    def __init__(self, text: str, path: str, diags: DiagnosticBag) -> None:
        self.raw = text
        self.path = path
        self.diags = diags
        self.items: list = []        # nodes a pragma can attach to
        self.pou_headers: list = []  # (POU, start, header end)
        self.errors = 0
        self.calm = 0                # tokens to shift before the next error is reported
        self.comment_trouble = False
        self.skipping = False        # recovery is reading tokens: no parser context
        self.strays: dict = {}       # END_* whose block recovery dropped -> how many
        self.last: Optional[Tok] = None
        self.state_stack = [_START_STATE]
        self.value_stack: list = []

    # -- diagnostics
    def report(self, code: str, message: str, pos: ast.Pos, hint: Optional[str] = None,
               always: bool = False, calm: int = 0) -> None:
        """Add an error, unless it is an echo of the previous one (``always``
        overrides). ``calm``: errors at that many next tokens are echoes."""
        quiet = self.calm and not always
        self.calm = max(self.calm, calm)
        if quiet:
            return
        self.errors += 1
        if self.errors > MAX_ERRORS:
            raise _GiveUp
        self.diags.error(code, message, pos, hint)

    def _pos_at(self, line: int, col: int, end_col: int = 0) -> ast.Pos:
        return ast.Pos(self.path, line, col, line, end_col or col + 1)

    def _tok_pos(self, t: Tok) -> ast.Pos:
        if t.type == "$END":
            return self._eof_pos()
        return ast.Pos(self.path, t.line, t.column, t.line, t.end_column)

    def _eof_pos(self) -> ast.Pos:
        line, col = line_col(self.raw, len(self.raw))
        return ast.Pos(self.path, line, col, line, col)

    # -- driver
    def run(self) -> ast.SourceFile:
        if self.raw.startswith("\ufeff"):
            self.raw = self.raw[1:]  # a BOM: editors do not show it as a column
        text = self.raw

        def comment_error(code, message, start, end, hint):
            self.comment_trouble = self.comment_trouble or code == "E004"
            self.report(code, message, ast.Pos(self.path, *line_col(text, start), *line_col(text, end)),
                        hint, always=True)

        self.text, pragmas = strip_comments(text, comment_error)
        _BUILDER.begin(self)
        self.tokens = _LEXER.tokens(self.text, self._accepts, self._bad_characters)
        try:
            result = self._drive()
        except _GiveUp:
            self.diags.error("E001", f"too many errors; stopped after {MAX_ERRORS}", self._eof_pos())
            result = None
        except _TooDeep as e:
            self.report("E005", "nesting too deep", self._tok_pos(e.args[0]),
                        "split the expression or statement into smaller parts", always=True)
            result = None
        if not isinstance(result, ast.SourceFile):
            result = ast.SourceFile(self.path, [], pos=ast.Pos(self.path, 1, 1))
        if pragmas:
            self._attach(pragmas)
        return result

    def _accepts(self) -> Optional[dict]:
        return None if self.skipping else _ROWS[self.state_stack[-1]]

    def _drive(self):
        feed, stack = self._feed, self.state_stack
        for tok in self.tokens:
            try:
                feed(tok)
            except _Rejected:
                result = self._recover(tok)
                if result is not None:
                    return result
                continue
            self.last = tok
            if self.calm:
                self.calm -= 1
            if len(stack) > MAX_STACK:
                raise _TooDeep(tok)
        return self._feed_or_recover(self._end_token())

    def _feed(self, token: Tok, is_end: bool = False):
        """lark's ParserState.feed_token on the prepared table, plus an undo:
        LALR may reduce before it notices that the token does not fit (a
        statement list into a body, say); on rejection those reductions are
        taken back, so that recovery sees the stack as it was."""
        states, values = self.state_stack, self.value_stack
        ttype = token.type
        undo = None
        while True:
            action = _ROWS[states[-1]].get(ttype)
            if action.__class__ is int:
                states.append(action)
                values.append(token)
                return None
            if action is None:
                if undo:
                    self._undo(undo)
                raise _Rejected
            size = action.size
            if size:
                children = values[-size:]
                del states[-size:]
                del values[-size:]
            else:
                children = []
            if undo is None:
                undo = []
            alias = action.alias
            undo.append((action, children) if alias is None else (action, children, len(children[alias].children)))
            callback = action.callback
            value = children[0] if callback is None else callback(children)
            goto = _ROWS[states[-1]][action.origin]
            states.append(goto)
            values.append(value)
            if is_end and goto == _END_STATE:
                return value

    def _undo(self, undo: list) -> None:
        states, values = self.state_stack, self.value_stack
        for entry in reversed(undo):
            action, children = entry[0], entry[1]
            states.pop()
            values.pop()
            if len(entry) == 3:
                del children[action.alias].children[entry[2]:]
            for symbol in action.symbols:  # the states the children were shifted with
                states.append(_ROWS[states[-1]][symbol])
            values.extend(children)

    def _feed_or_recover(self, tok: Tok):
        """Feed one token outside the main loop; returns the parse result
        if tok ended the file."""
        try:
            result = self._feed(tok, tok.type == "$END")
        except _Rejected:
            return self._recover(tok)
        self.last = tok
        if self.calm:
            self.calm -= 1
        return result

    def _end_token(self) -> Tok:
        line, col = line_col(self.text, len(self.text))
        return Tok("$END", "", len(self.text), line, col)

    def _next_token(self) -> Tok:
        """The next token, read without parser context (while skipping)."""
        self.skipping = True
        try:
            tok = next(self.tokens, None)
        finally:
            self.skipping = False
        if tok is None:
            return self._end_token()
        self.last = tok
        return tok

    def _bad_characters(self, offset: int, line: int, col: int) -> tuple:
        """The lexer is stuck at offset: an unterminated string, or characters
        no token starts with. Returns (offset to go on from, token or None)."""
        text = self.text
        ch = text[offset]
        if ch in "'\"":
            # Take the string to the end of the line (but leave a final ';'
            # alone) and go on as if it were closed.
            nl = text.find("\n", offset)
            rest = text[offset:len(text) if nl < 0 else nl].rstrip()
            if rest.endswith(";") and len(rest) > 1:
                rest = rest[:-1].rstrip()
            self.report("E004", "unterminated string", self._pos_at(line, col, col + len(rest)),
                        f"close it with {ch} on the same line; inside a string write {ch} as ${ch}",
                        always=True, calm=2)  # the rest of the line is guesswork
            kind = "WSTRING_LIT" if ch == '"' else "STRING_LIT"
            tok = Tok(kind, rest + ch, offset, line, col)
            tok.end_column = col + len(rest)
            return offset + len(rest), tok
        m = INVALID_RUN.match(text, offset)
        run = m.group() if m else ch
        if ch == "%":
            message, hint = "invalid direct address", "direct addresses look like %IX0.1, %QW4, %MD3200, %MW3250:X0"
        elif ch == "#":
            message, hint = "unexpected '#'", "typed literals are written without spaces: INT#5, T#1s, Color#Red"
        elif not run[0].isascii():
            message = f"invalid character '{run[0]}'"
            hint = ("identifiers may only use ASCII letters, digits and '_'" if run[0].isalpha()
                    else "only ASCII is allowed outside strings and comments")
        else:
            message, hint = f"invalid character {run[0]!r}", None
        if not self.skipping:
            self.report("E002", message, self._pos_at(line, col, col + len(run)), hint, calm=3)
        return offset + len(run), None

    # -- error recovery
    def _open_blocks(self, with_index: bool = False):
        """Unclosed block keywords on the parser stack, innermost first (with
        their index in the value stack if asked). A block whose END_* is
        already there (END_PROGRAM waiting for an optional ';') is closed."""
        values = self.value_stack
        closed = []
        for i in range(len(values) - 1, -1, -1):
            v = values[i]
            if isinstance(v, Tok):
                if v.type in _CLOSER_TYPES:
                    closed.append(v.type)
                elif v.type in _CLOSERS:
                    if closed and closed[-1] == _CLOSERS[v.type]:
                        closed.pop()
                    else:
                        yield (i, v) if with_index else v

    def _expected(self) -> set:
        """The token types that fit here. Not just the row's keys: LALR
        merges states, so a row may offer tokens a later state refuses."""
        stack = self.state_stack
        return {t for t in _ROWS[stack[-1]] if t.isupper() and _simulate(stack, t) is not None}

    def _describe(self, tok: Tok) -> str:
        if tok.type == "$END":
            return "end of file"
        if tok.type in _KEYWORD_TERMINALS:
            return tok.value.upper()
        return f"'{tok.value}'"

    def _recover(self, tok: Tok):
        """Report the error at tok and get the parser going again: a special
        case, one inserted token, or skipping to a synchronising token.
        Returns the parse result when recovery reached the end of the file."""
        prev = self.last
        if tok.type == "$END":
            self._eof_error()
            return self._finish(tok)
        if self.strays.get(tok.type):
            self.strays[tok.type] -= 1  # the END_* of a block lost in an earlier error
            return None
        special = self._special_case(tok, prev)
        if special is not False:
            return special
        for cand in self._insertable(tok):
            self._missing(cand, tok, prev)
            self._feed(_synthetic(cand, prev) if prev is not None else _synthetic(cand, tok, after=False))
            return self._feed_or_recover(tok)
        self._generic_error(tok, prev)
        return self._resync(tok)

    def _insertable(self, tok: Tok):
        """The token types whose insertion before tok would let it fit."""
        stack = self.state_stack
        for cand in _INSERTABLE:
            after = _simulate(stack, cand)
            reduced: list = []
            if after is None or _simulate(after, tok.type, reduced) is None:
                continue
            # 'x y := 1': not "missing ';'" after a name that cannot be a statement.
            if cand == _SEMI and "call_stmt" in reduced and self.value_stack and _is_bare(self.value_stack[-1]):
                continue
            yield cand
            return

    def _special_case(self, tok: Tok, prev: Optional[Tok]):
        """Errors with a known cause and a tailored recovery. Returns False
        when tok is not one of them, else what _recover returns."""
        value = tok.value.upper()
        if tok.type in ("_ELSE", "ELSIF"):
            for v in reversed(self.value_stack):
                if isinstance(v, Tok) and v.type in ("IF", "CASE", "_ELSE"):
                    if v.type != "_ELSE":
                        break
                    what = "duplicate ELSE" if tok.type == "_ELSE" else "ELSIF after ELSE"
                    self.report("E005", what, self._tok_pos(tok), f"the ELSE at line {v.line} must be the last branch", calm=1)
                    # Drop it (and an ELSIF's condition): what follows joins the ELSE branch.
                    return self._skip_through("THEN") if tok.type == "ELSIF" else None
        if tok.type in _VAR_KINDS:
            opener = next(self._open_blocks(), None)
            if opener is not None and opener.type in ("PROGRAM", "FUNCTION", "FUNCTION_BLOCK"):
                self.report("E005", f"{_spelling(tok.type)} block after the statements", self._tok_pos(tok),
                            "declare variables before the first statement of the POU", calm=1)
                return self._skip_through("END_VAR")
        if tok.type == "EQ" and "ASSIGN" in self._expected():
            self.report("E001", "'=' compares; use ':=' to assign", self._tok_pos(tok), "':=' assigns, '=' compares", calm=1)
            assign = Tok("ASSIGN", ":=", tok.start_pos, tok.line, tok.column)
            assign.end_column = tok.end_column
            return self._feed_or_recover(assign)
        word = value if value in _UNSUPPORTED else None
        if word is None and prev is not None and prev.type == "NAME" and prev.value.upper() in _UNSUPPORTED:
            word = prev.value.upper()
        if word is not None:
            at = tok if word == value else prev
            self.report("E001", f"{word}: {_UNSUPPORTED[word]} are not supported", self._tok_pos(at),
                        "write the logic as a FUNCTION or FUNCTION_BLOCK", calm=1)
            self._unshift(prev if word != value else None)
            end = word if word.startswith("END_") else "END_" + word
            return self._skip_through("NAME", end) if word != end else None
        if tok.type == "LABEL_NAME" and re.compile(r"\s*:").match(self.text, tok.end_pos):
            # In a statement list the lexer offers LABEL_NAME (a case label
            # could follow a statement), so 'lbl:' arrives as one.
            self.report("E001", f"label '{tok.value}:' is not supported", self._tok_pos(tok),
                        "JMP and labels are not supported; use a loop or CASE", calm=1)
            return self._skip_through(_COLON)
        if prev is not None and prev.type == "NAME" and "ASSIGN" in self._expected():
            if prev.value.upper() == "JMP":
                self.report("E001", "JMP is not supported", self._tok_pos(prev),
                            "JMP and labels are not supported; use a loop or CASE", calm=1)
                self._unshift(prev)
                return self._skip_through(_SEMI)
            if tok.type == _COLON:
                self.report("E001", f"label '{prev.value}:' is not supported", self._tok_pos(prev),
                            "JMP and labels are not supported; use a loop or CASE", calm=1)
                self._unshift(prev)
                return None
        return False

    def _unshift(self, tok: Optional[Tok]) -> None:
        """Take tok (just shifted) back off the stack."""
        values = self.value_stack
        if tok is not None and values and values[-1] is tok:
            values.pop()
            self.state_stack.pop()

    def _skip_through(self, ttype: str, value: Optional[str] = None):
        """Drop tokens up to and including the first of type ttype (and
        value, upper-cased), then let parsing go on."""
        while True:
            t = self._next_token()
            if t.type == "$END":
                return self._finish(t)
            if t.type == ttype and (value is None or t.value.upper() == value):
                self.calm = 0  # a clean cut: what follows is new
                return None

    def _missing(self, cand: str, tok: Tok, prev: Optional[Tok]) -> None:
        text = _spelling(cand)
        if cand in _CLOSERS.values():
            opener = next((b for b in self._open_blocks() if _CLOSERS[b.type] == cand), None)
            where = f" to close the {opener.type} at line {opener.line}" if opener else ""
            self.report("E001", f"{text} expected{where}, found {self._describe(tok)}", self._tok_pos(tok),
                        f"add {text} before {self._describe(tok)}", calm=1)
            return
        # Point at where the token is missing: just after the previous one.
        pos = self._pos_at(prev.end_line, prev.end_column) if prev is not None else self._tok_pos(tok)
        opener = next(self._open_blocks(), None)
        item = "declaration" if opener is not None and opener.type in ("TYPE", "STRUCT", *_VAR_KINDS) else "statement"
        hint = {_SEMI: f"missing ';' after the {item}?",
                _COMMA: "separate arguments, names and values with ','"}.get(cand)
        self.report("E001", f"missing '{text}' before {self._describe(tok)}", pos, hint, calm=1)

    def _eof_error(self) -> None:
        if self.comment_trouble:
            return  # the unterminated comment already explains it
        opener = next(self._open_blocks(), None)
        hint = (f"{_CLOSERS[opener.type]} expected to close the {opener.type} at line {opener.line}"
                if opener is not None else "the last statement is incomplete")
        self.report("E001", "unexpected end of file", self._eof_pos(), hint)

    def _generic_error(self, tok: Tok, prev: Optional[Tok]) -> None:
        expected = self._expected()
        hint = None
        if tok.type in _CLOSERS.values() or tok.type in ("_ELSE", "ELSIF"):
            opener = next(self._open_blocks(), None)
            if opener is not None:
                hint = f"{_CLOSERS[opener.type]} expected to close the {opener.type} at line {opener.line}"
        if hint is None:
            hint = self._did_you_mean(tok, prev)
        if hint is None and self._between_pous():
            hint = "outside a POU: PROGRAM, FUNCTION, FUNCTION_BLOCK, TYPE, VAR_GLOBAL or CONFIGURATION"
        if hint is None and {"INT", "NAME", "LPAR", "NOT"} <= expected:
            hint = "an expression (a value or a variable) is missing here"
        if hint is None and {"ARRAY", "STRING", "NAME"} <= expected:
            hint = "a type (INT, STRING[20], ARRAY[1..3] OF REAL, a type name, ...) is missing here"
        if hint is None:
            # Only the closer of the innermost block (the table merges states
            # of VAR and STRUCT, say, and offers both END_VAR and END_STRUCT).
            opener = next(self._open_blocks(), None)
            closer = _CLOSERS[opener.type] if opener is not None else None
            # ('..' is not listed: the hints never offered it.)
            shown = sorted({_FRIENDLY.get(t, _spelling(t)) for t in expected
                            if t != "DOTDOT" and (not t.startswith("END_") or t == closer)})
            if 0 < len(shown) <= 6:
                hint = "expected " + ", ".join(s if s.startswith("a ") else f"'{s}'" for s in shown)
        self.report("E001", f"unexpected {self._describe(tok)}", self._tok_pos(tok), hint, calm=3)

    def _did_you_mean(self, tok: Tok, prev: Optional[Tok]) -> Optional[str]:
        """A misspelt keyword (ELSEIF, ENDIF, VAR_INPUTS) lexes as a name."""
        for t in (tok, prev):
            if t is not None and t.type == "NAME" and len(t.value) > 2:
                close = difflib.get_close_matches(t.value.upper(), _KEYWORDS, n=1, cutoff=0.8)
                if close and close[0] != t.value.upper():
                    # A misspelt FOR leaves its END_FOR without a block.
                    self._lost_opener(Tok(_LEXER.keywords[close[0]], close[0], 0, 0, 0))
                    return f"did you mean {close[0]}?"
        return None

    def _resync(self, tok: Tok):
        """Panic mode: skip to a synchronising token, pop the parser stack
        until that token fits, feed it. tok is the offending token.
        Errors on the next tokens are echoes of this one: ``calm``."""
        while True:
            if tok.type == "$END":
                return self._finish(tok)
            if tok.type == _SEMI and not self._between_pous():
                # The end of the broken statement or declaration: recover
                # within the innermost open block, where the ';' ends what
                # was parsed, or else by dropping the broken item with it.
                if self._pop_for(tok, bounded=True, fits=self._semicolon_ends_item):
                    self.calm = 0  # a clean cut: what follows is new
                    return self._feed_or_recover(tok)
                if self._pop_to_item_boundary():
                    self.calm = 0
                    return None
            elif tok.type in _SYNC and self._pop_for(tok):
                self.calm = 3
                return self._feed_or_recover(tok)
            self._lost_opener(tok)
            tok = self._next_token()

    def _between_pous(self) -> bool:
        """Is the broken part outside any POU, where ';' ends nothing (in a
        file of POUs, not of bare statements)? Then recovery waits for the
        next PROGRAM, FUNCTION, TYPE, VAR_GLOBAL ..."""
        if next(self._open_blocks(), None) is not None:
            return False
        stack = self.state_stack
        for depth in range(len(stack), 0, -1):
            if _simulate(stack[:depth], "$END") is not None:
                return _simulate(stack[:depth], "PROGRAM") is not None
        return False

    def _semicolon_ends_item(self, depth: int) -> bool:
        """Would ';' at this stack depth end a statement or declaration, not
        make an empty statement, nor a lone name into a call statement?"""
        after = _simulate(self.state_stack[:depth], _SEMI)
        if after is None:
            return False
        reduced: list = []
        _simulate(after, "NAME", reduced)  # a statement may follow: what does ';' complete?
        if "empty_stmt" in reduced:
            return False
        return not ("call_stmt" in reduced and depth >= 2 and _is_bare(self.value_stack[depth - 2]))

    def _pop_to_item_boundary(self) -> bool:
        """Pop what was parsed of the current item (declaration, statement)
        of the innermost block: to where the block's closer would fit."""
        opener = next(self._open_blocks(), None)
        if opener is None:  # top level, or a file of bare statements
            closer = "$END"
        else:
            closer = "UNTIL" if opener.type == "REPEAT" else _CLOSERS[opener.type]
        return self._pop_for(Tok(closer, closer, 0, 0, 0), bounded=True)

    def _pop_for(self, tok: Tok, bounded: bool = False, fits=None) -> bool:
        """Pop the fewest states so that tok is accepted (or fits(depth)
        says yes), first without leaving the innermost open block, then
        (unless bounded) anywhere. False if it fits nowhere (the stack is
        then unchanged)."""
        stack, values = self.state_stack, self.value_stack
        if fits is None:
            def fits(depth):
                return _simulate(stack[:depth], tok.type) is not None
        innermost = next(self._open_blocks(with_index=True), None)
        # stack[i + 1] is the state after the opener values[i]: keep it.
        floor = innermost[0] + 2 if innermost is not None else 1
        for lowest in ((floor,) if bounded else (floor, 1)):
            for depth in range(len(stack), lowest - 1, -1):
                if fits(depth):
                    for v in values[depth - 1:]:
                        self._lost_opener(v)
                    del stack[depth:]
                    del values[depth - 1:]
                    return True
        return False

    def _lost_opener(self, tok) -> None:
        """A block keyword dropped by recovery: its END_* will come without
        it and is then not worth another error."""
        if isinstance(tok, Tok) and tok.type in _CLOSERS:
            closer = _CLOSERS[tok.type]
            self.strays[closer] = self.strays.get(closer, 0) + 1

    def _finish(self, end: Tok):
        """At the end of the file: close what is open by inserting the
        missing closers (already reported), or else drop the unfinished
        part; then accept."""
        stack = self.state_stack
        previous = None
        for _ in range(MAX_STACK):
            if _simulate(stack, "$END") is not None:
                break
            # Closers first; ';' (always welcome in a statement list) only
            # when nothing else fits, and never twice in a row.
            cand = next((c for c in _CLOSING if c != previous and _simulate(stack, c) is not None), None)
            if cand is None:
                break
            self._feed(_synthetic(cand, end, after=False))
            previous = cand
        if _simulate(stack, "$END") is None:
            self._pop_for(end)
        return self._feed(end, True)

    # -- pragmas
    def _attach(self, pragmas: list) -> None:
        """Each pragma goes to the item (POU, type, variable block or
        declaration, statement) that follows it; one between a POU's name
        and its first declaration goes to the POU ({external}, attributes)."""
        items = sorted(self.items, key=lambda n: (n.pos.line, n.pos.col))
        starts = [(n.pos.line, n.pos.col) for n in items]
        for p in pragmas:
            end = (p.end_line, p.end_col)
            target = None
            for pou, start, header_end in self.pou_headers:
                if start < end <= header_end:
                    target = pou
                    break
            if target is None:
                i = bisect_left(starts, end)
                if i == len(items):
                    continue  # nothing follows: a trailing pragma has no item
                target = items[i]
            target.pragmas.append(p.text)
            if isinstance(target, ast.POU) and p.text.lower() == "external":
                target.external = True


def parse_source(text: str, path: str, diags: DiagnosticBag) -> ast.SourceFile:
    """Parse one ST file into an ``ast.SourceFile``. Never raises; every
    problem goes into diags."""
    try:
        with _LOCK:
            return _Parse(text, path, diags).run()
    except Exception as e:  # a bug here must not become a traceback for the user
        diags.error("E009", f"internal parser error: {type(e).__name__}: {e}", ast.Pos(str(path), 1, 1),
                    "please report this with the source file")
        return ast.SourceFile(str(path), [], pos=ast.Pos(str(path), 1, 1))
