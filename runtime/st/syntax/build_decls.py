"""The AST builder's declarations: source files, POUs, variable blocks and
declarations, types and initial values, configurations; ``AstBuilder`` is
the complete builder the parser uses."""

from __future__ import annotations

import re
from pathlib import Path

from .. import ast, ast_sfc
from .build_base import start_of
from .build_sfc import SfcBuilder
from .build_stmts import StmtBuilder
from .lexer import Tok

_NAME_TYPES = frozenset(("NAME", "SET", "RESET"))
_OOP_MODIFIERS = frozenset(("ABSTRACT", "FINAL", "PUBLIC", "PRIVATE", "PROTECTED", "INTERNAL"))


def identifier_from_path(path: str) -> str:
    """The name a file gives: to the PROGRAM of a file of bare statements, to
    a global variable list (namespaces.py). 'ltmr/write-sdo.st' -> 'write_sdo'."""
    stem = re.sub(r"[^A-Za-z0-9_]+", "_", Path(path).stem)
    stem = re.sub(r"_{2,}", "_", stem).strip("_")
    if not stem:
        return "main"
    return "_" + stem if stem[0].isdigit() else stem


class AstBuilder(StmtBuilder, SfcBuilder):
    """The rule callbacks of grammar.lark: children -> ast nodes (see
    build_base.py); this part: the top level, declarations, configuration."""

    # -- top level
    # Constructs that parse but cannot stand are reported and left out of
    # the tree, so later stages only ever see well-formed declarations.
    def source(self, c):
        decls = []
        for d in c:
            if isinstance(d, list):
                decls.extend(d)
            elif isinstance(d, (ast.Method, ast.Property)):
                self._attach_member(d, decls)
            elif isinstance(d, tuple) and d[0] == "ACTIONS":
                self._contained_actions(d[1], d[2], decls)
            elif isinstance(d, ast.VarBlock) and d.kind != "VAR_GLOBAL":
                self.ctx.report(
                    "E005",
                    f"{d.kind} block outside a POU",
                    d.pos,
                    "only VAR_GLOBAL blocks (a global variable list) stand on their own"
                    + (", VAR_CONFIG goes into a CONFIGURATION" if d.kind == "VAR_CONFIG" else ""),
                )
            else:
                decls.append(d)
        return ast.SourceFile(self.ctx.path, decls, self.qualified_bases, pos=ast.Pos(self.file, 1, 1))

    def _contained_actions(self, actions: list, pos, decls: list) -> None:
        """The actions of an ACTIONS container; those of an unnamed one are
        the PROGRAM's or FUNCTION_BLOCK's above it (RuSTy)."""
        if any(a.pou_name is None for a in actions):
            owner = next((d for d in reversed(decls) if isinstance(d, ast.POU)), None)
            if owner is None or owner.kind not in ("FUNCTION_BLOCK", "PROGRAM"):
                self.ctx.report(
                    "E047",
                    "ACTIONS without a name follows no PROGRAM or FUNCTION_BLOCK",
                    pos,
                    "write ACTIONS Pou, or put the container after the POU its actions belong to",
                )
                return
            for a in actions:
                a.pou_name = a.pou_name or owner.name
        decls.extend(actions)

    def _attach_member(self, m, decls: list) -> None:
        """A METHOD or PROPERTY after END_FUNCTION_BLOCK (as TwinCAT and
        blark export them) belongs to the FUNCTION_BLOCK before it."""
        owner = next((d for d in reversed(decls) if isinstance(d, (ast.POU, ast.Interface))), None)
        if isinstance(owner, ast.POU) and owner.kind in ("FUNCTION_BLOCK", "PROGRAM"):
            (owner.methods if isinstance(m, ast.Method) else owner.properties).append(m)
        elif isinstance(owner, ast.Interface):
            (owner.methods if isinstance(m, ast.Method) else owner.properties).append(m)
        else:
            self.ctx.report(
                "E005",
                f"{'METHOD' if isinstance(m, ast.Method) else 'PROPERTY'} {m.name} belongs to no FUNCTION_BLOCK",
                m.pos,
                "put it inside a FUNCTION_BLOCK, PROGRAM or INTERFACE, or right after one",
            )

    def bare_source(self, c):
        body = [s for s in c if s is not None]
        pou = ast.POU(
            "PROGRAM",
            identifier_from_path(self.ctx.path),
            [],
            body,
            pos=self._span(body[0], body[-1]) if body else ast.Pos(self.file, 1, 1),
        )
        return ast.SourceFile(self.ctx.path, [pou], self.qualified_bases, pos=ast.Pos(self.file, 1, 1))

    def _pou(self, kind: str, c) -> ast.POU:
        var_blocks = [x for x in c if isinstance(x, ast.VarBlock)]
        sfc = next((x for x in c if isinstance(x, ast_sfc.SfcNetwork)), None)
        if sfc is not None and kind == "FUNCTION":
            self.ctx.report(
                "E005",
                "a FUNCTION cannot have an SFC body",
                sfc.pos,
                "SFC is for PROGRAMs and FUNCTION_BLOCKs (IEC 61131-3 ed.3 6.7): they keep the active steps",
            )
            sfc = None
        body = next((x for x in c if isinstance(x, list)), [])
        if sfc is not None:
            if body:
                self.sfc_after_statements(body, sfc)
            body = []
        ret = c[2] if kind == "FUNCTION" else None
        pou = ast.POU(kind, c[1].value, var_blocks, body, return_type=ret, pos=self._span(c[0], c[-1]), sfc=sfc)
        for act in (x for x in c if isinstance(x, ast.Action)):
            if act.pou_name is not None:
                self.ctx.report(
                    "E047",
                    f"ACTION {act.pou_name}.{act.name} inside {pou.name}",
                    act.name_pos,
                    f"inside the POU write ACTION {act.name}: (the POU's name only goes before it outside)",
                )
            else:
                pou.actions.append(act)
        # Where the header ends: a pragma before this point belongs to the POU.
        first = var_blocks[0] if var_blocks else body[0] if body else sfc or c[-1]
        self.ctx.pou_headers.append((pou, start_of(c[0]), start_of(first)))
        self.ctx.items.append(pou)
        return pou

    def program(self, c):
        pou = self._pou("PROGRAM", [x for x in c if not isinstance(x, (ast.Method, ast.Property))])
        pou.methods = [x for x in c if isinstance(x, ast.Method)]  # CODESYS: METHODs of a PROGRAM
        pou.properties = [x for x in c if isinstance(x, ast.Property)]
        return pou

    def function(self, c):
        return self._pou("FUNCTION", c)

    def function_block(self, c):
        mods = tuple(t.type for t in c[1:] if isinstance(t, Tok) and t.type in _OOP_MODIFIERS)
        name = c[1 + len(mods)]
        rest = [c[0], name, *c[2 + len(mods) :]]
        pou = self._pou("FUNCTION_BLOCK", [x for x in rest if not isinstance(x, (tuple, ast.Method, ast.Property))])
        pou.modifiers = mods
        for x in c:
            if isinstance(x, tuple) and x[0] == "EXTENDS":
                if pou.extends is not None:
                    self.ctx.report("E005", "a FUNCTION_BLOCK EXTENDS one base only", x[1][0][1])
                else:
                    pou.extends = x[1][0]
            elif isinstance(x, tuple):
                pou.implements += x[1]
            elif isinstance(x, ast.Method):
                pou.methods.append(x)
            elif isinstance(x, ast.Property):
                pou.properties.append(x)
        return pou

    def action_block(self, c):
        names = [t for t in c if isinstance(t, Tok) and t.type in _NAME_TYPES]
        body = next((x for x in c if isinstance(x, list)), None)
        if body is None:  # written in SFC
            body = self.sfc_in_action(names[-1].value, next(x for x in c if isinstance(x, ast_sfc.SfcNetwork)))
        if len(names) > 2:
            self.ctx.report(
                "E047",
                "an ACTION name is the action's, or Pou.Action",
                self._span(names[0], names[-1]),
                "name the action, and outside its POU the POU before it: ACTION Pou.Name:",
            )
        last = names[-1]
        return ast.Action(
            last.value,
            body,
            pou_name=names[0].value if len(names) > 1 else None,
            name_pos=self._span(names[0], last),
            pos=self._span(c[0], c[-1]),
        )

    def actions_block(self, c):
        """RuSTy's ACTIONS [Pou] ... END_ACTIONS: its actions, each naming
        the POU (source() gives an unnamed container the POU above it)."""
        owner = c[1].value if isinstance(c[1], Tok) and c[1].type in _NAME_TYPES else None
        actions = [a for a in c if isinstance(a, ast.Action)]
        for a in actions:
            if a.pou_name is None:
                a.pou_name = owner
            elif owner is not None and a.pou_name.upper() != owner.upper():
                self.ctx.report(
                    "E047",
                    f"ACTION {a.pou_name}.{a.name} in the ACTIONS of {owner}",
                    a.name_pos,
                    f"name it {a.name} alone, or move it out of ACTIONS {owner}",
                )
                a.pou_name = owner  # checked as the container's, reported once
        return ("ACTIONS", actions, self._span(c[0], c[-1]))

    def fb_inherit(self, c):
        # EXTENDS a.b / IMPLEMENTS I1, I2: (keyword, [(dotted name, Pos)])
        return (c[0].type, list(c[1:]))

    def qualified_name(self, c):
        return ".".join(t.value for t in c), self._span(c[0], c[-1])

    # -- object-oriented ST (checker_oop.py gives them their meaning)
    def _modifiers_and_name(self, c) -> tuple:
        mods = []
        i = 1
        while isinstance(c[i], Tok) and c[i].type in _OOP_MODIFIERS:
            mods.append(c[i].type)
            i += 1
        return tuple(mods), c[i], i + 1

    def method(self, c):
        mods, name, i = self._modifiers_and_name(c)
        ret = c[i]
        var_blocks = [x for x in c if isinstance(x, ast.VarBlock)]
        body = next(x for x in c if isinstance(x, list))
        return ast.Method(name.value, var_blocks, body, ret, mods, pos=self._span(c[0], c[-1]))

    def property(self, c):
        mods, name, i = self._modifiers_and_name(c)
        accessors = dict(x for x in c if isinstance(x, tuple))
        for m in accessors.values():
            m.name = name.value
        return ast.Property(
            name.value, c[i], accessors.get("GET"), accessors.get("SET"), mods, pos=self._span(c[0], c[-1])
        )

    def property_accessor(self, c):
        var_blocks = [x for x in c if isinstance(x, ast.VarBlock)]
        body = next(x for x in c if isinstance(x, list))
        return (c[0].type, ast.Method("", var_blocks, body, None, (), pos=self._span(c[0], c[-1])))

    def interface(self, c):
        bases = next((x for x in c if isinstance(x, tuple)), ())
        return ast.Interface(
            c[1].value,
            list(bases),
            [x for x in c if isinstance(x, ast.Method)],
            [x for x in c if isinstance(x, ast.Property)],
            pos=self._span(c[0], c[-1]),
        )

    def interface_bases(self, c):
        return tuple((t.value, self._tpos(t)) for t in c[1:] if t.type != "COMMA")

    # -- declarations
    def var_block(self, c):
        kind = c[0].type
        quals = {t.type for t in c if isinstance(t, Tok)}
        decls = self._plain_names(
            [d for group in c if isinstance(group, list) for d in group], dotted_ok=kind == "VAR_CONFIG"
        )
        blk = ast.VarBlock(
            kind,
            decls,
            constant="CONSTANT" in quals,
            retain="RETAIN" in quals,
            persistent="PERSISTENT" in quals,
            pos=self._span(c[0], c[-1]),
        )
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
                self.ctx.report(
                    "E005",
                    f"'{d.name}': a qualified name is only allowed in VAR_CONFIG",
                    d.pos,
                    "declare a plain name here",
                )
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
        d = ast.VarDecl(name, spec, init, self._address(loc), pos=self._span(loc, init if init is not None else spec))
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

    def struct_extends_decl(self, c):
        name, base, spec = c[0], c[2], c[3]
        spec.extends = base
        return self.type_decl([name, spec])

    def named_type(self, c):
        return ast.NamedType(c[0].value, pos=self._tpos(c[0]))

    def qualified_type(self, c):
        # Tc2_Standard.TON: the checker resolves the namespace (namespaces.py)
        self.qualified_bases.add(c[0].value.upper())
        return ast.NamedType(".".join(t.value for t in c), pos=self._span(c[0], c[-1]))

    def string_type(self, c):
        return ast.StringTypeSpec(c[0].type == "WSTRING", c[2] if len(c) > 1 else None, pos=self._span(c[0], c[-1]))

    def array_type(self, c):
        ranges = [r for r in c[2:-1] if not isinstance(r, Tok)]
        return ast.ArrayTypeSpec(ranges, c[-1], pos=self._span(c[0], c[-1]))

    def fb_init_array_type(self, c):
        # ARRAY [ ranges ] OF FB_X [ (n := 1), (n := 2) ]: the FB_init inputs of each element
        inits = [x for x in c if isinstance(x, ast.StructInit)]
        elem_at = next(i for i, x in enumerate(c) if isinstance(x, ast.NamedType))
        ranges = [r for r in c[2 : elem_at - 1] if not isinstance(r, Tok)]
        return ast.ArrayTypeSpec(ranges, c[elem_at], fb_inits=inits, pos=self._span(c[0], c[-1]))

    def array_range(self, c):
        return None if len(c) == 1 else (c[0], c[1])

    def ref_type(self, c):
        kind = c[0].type
        return ast.RefTypeSpec(
            c[-1], pointer=kind == "POINTER", reference=kind == "REFERENCE", pos=self._span(c[0], c[-1])
        )

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
        return ast.Resource(
            names[0].value,
            names[1].value if len(names) > 1 else None,
            [x for x in c if isinstance(x, ast.VarBlock)],
            [x for x in c if isinstance(x, ast.TaskDecl)],
            [x for x in c if isinstance(x, ast.ProgramConfig)],
            pos=self._span(c[0], c[-1]),
        )

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
        return ast.ProgramConfig(
            names[0].value,
            names[-1].value,
            names[1].value if len(names) == 3 else None,
            args,
            retain=c[1] is not None and c[1].type == "RETAIN",
            trailing_comma=args.trailing_comma if isinstance(args, ast.ArgList) else None,
            pos=self._span(c[0], last),
        )
